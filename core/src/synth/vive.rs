//! Synthetic demonstrations of one point-to-point hand reach, as an HTC VIVE
//! tracker would record them: ~90 Hz with timestamp jitter, position noise,
//! rest at both ends, bell-shaped speed with per-demo variation, and in some
//! demos a hesitation and correction near the goal. Deterministic from a seed.

use crate::rng::Rng;

/// One synthetic demonstration: samples `(stamp_ns, position)` in time order.
#[derive(Clone, Debug)]
pub struct SynthDemo {
    /// Samples.
    pub samples: Vec<(i64, [f64; 3])>,
    /// Whether this demo hesitates and corrects near the goal.
    pub corrected: bool,
    /// One orientation `[x, y, z, w]` per sample, when generated with one.
    pub orientations: Option<Vec<[f64; 4]>>,
}

/// Minimum-jerk position profile on [0, 1].
fn min_jerk(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    u * u * u * (10.0 - 15.0 * u + 6.0 * u * u)
}

/// [`reach_demos`] as loaded demos, `synth.mcap:/demo_{i}` with header
/// stamps: what tests build models from.
pub fn reach_raw_demos(seed: u64, count: usize, epoch_ns: i64) -> Vec<crate::RawDemo> {
    reach_demos(seed, count, epoch_ns)
        .into_iter()
        .enumerate()
        .map(|(i, d)| crate::RawDemo {
            name: format!("synth.mcap:/demo_{i}"),
            file: "synth.mcap".into(),
            topic: format!("/demo_{i}"),
            stamps_ns: d.samples.iter().map(|s| s.0).collect(),
            positions: d.samples.iter().map(|s| s.1.into()).collect(),
            orientations: None,
            time_source: crate::load::demo::TimeSource::HeaderStamp,
        })
        .collect()
}

/// `count` demos of one reach from `seed`. Demo `i` starts recording at
/// `epoch_ns + i * 20 s`.
pub fn reach_demos(seed: u64, count: usize, epoch_ns: i64) -> Vec<SynthDemo> {
    let mut rng = Rng::new(seed);
    // The task: from a start near the body to a goal 0.3-0.5 m away.
    let start = [0.35, -0.20, 0.95];
    let direction = [0.62, 0.70, 0.35];
    let norm = direction.iter().map(|v| v * v).sum::<f64>().sqrt();
    let direction = direction.map(|v| v / norm);
    let arc_dir = [0.0, -0.45, 0.89];
    (0..count)
        .map(|i| {
            let reach = rng.range(0.30, 0.50);
            let arc = rng.range(0.015, 0.045);
            let jitter_start = [0, 1, 2].map(|_| 0.01 * rng.normal());
            let total = rng.range(1.0, 1.6);
            let rest_before = rng.range(0.08, 0.15);
            let rest_after = rng.range(0.08, 0.15);
            let moving = total - rest_before - rest_after;
            // Per-demo skew of the bell: warp time as u^gamma.
            let gamma = rng.range(0.85, 1.2);
            let corrected = rng.uniform() < 0.4;
            let undershoot = if corrected {
                rng.range(0.015, 0.03)
            } else {
                0.0
            };
            let correction_time = if corrected {
                rng.range(0.18, 0.28)
            } else {
                0.0
            };
            let pause = if corrected {
                rng.range(0.04, 0.08)
            } else {
                0.0
            };
            let main_time = moving - correction_time - pause;
            let p0: [f64; 3] = std::array::from_fn(|ax| start[ax] + jitter_start[ax]);
            let goal: [f64; 3] = std::array::from_fn(|ax| p0[ax] + reach * direction[ax]);
            let position = |t: f64| -> [f64; 3] {
                let tm = t - rest_before;
                let main = min_jerk((tm / main_time).clamp(0.0, 1.0).powf(gamma));
                let corr = if corrected {
                    min_jerk((tm - main_time - pause) / correction_time)
                } else {
                    0.0
                };
                // Progress along the reach: the main movement stops short by
                // `undershoot`, the correction covers the rest.
                let along = reach * (main * (1.0 - undershoot / reach) + corr * undershoot / reach);
                let bump = arc * (std::f64::consts::PI * (along / reach)).sin();
                std::array::from_fn(|ax| p0[ax] + along * direction[ax] + bump * arc_dir[ax])
            };
            debug_assert!((position(total)[0] - goal[0]).abs() < 1e-9);
            let period = 1.0 / 90.0;
            let first_ns = epoch_ns + i as i64 * 20_000_000_000;
            let mut samples = Vec::new();
            let mut k = 0usize;
            loop {
                let nominal = k as f64 * period;
                if nominal > total {
                    break;
                }
                let jitter = if k == 0 { 0.0 } else { 0.001 * rng.normal() };
                let t = (nominal + jitter).max(0.0);
                let p = position(t.min(total));
                let noisy = p.map(|v| v + 0.0005 * rng.normal());
                samples.push((first_ns + (t * 1e9).round() as i64, noisy));
                k += 1;
            }
            SynthDemo {
                samples,
                corrected,
                orientations: None,
            }
        })
        .collect()
}
