//! The orientation DMP (method.md section 12) on synthetic demos: a
//! regeneration reproduces the demo's rotation, the quaternion stays unit,
//! and quaternion sign flips between and within demos change nothing.

use dmpscope_core::dmp::DmpSettings;
use dmpscope_core::geom::{Vec3, quat_from_xyzw};
use dmpscope_core::rotation::{self, Q};
use dmpscope_core::{Model, PrepSettings, RawDemo, TimeSource, prepare};

/// A reach whose orientation turns by `angle` about `axis` with a
/// minimum-jerk profile, from `start`, over `secs` at 100 Hz.
fn turning(name: &str, start: Q, axis: [f64; 3], angle: f64, secs: f64) -> RawDemo {
    turning_flipped(name, start, axis, angle, secs, &|_| false)
}

/// [`turning`] with the samples `flip` names stored with the opposite sign
/// (the same rotation, as trackers do).
fn turning_flipped(
    name: &str,
    start: Q,
    axis: [f64; 3],
    angle: f64,
    secs: f64,
    flip: &dyn Fn(usize) -> bool,
) -> RawDemo {
    let n = (secs * 100.0) as usize + 1;
    let len = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let mut stamps = Vec::new();
    let mut positions = Vec::new();
    let mut orientations = Vec::new();
    for k in 0..n {
        let u = k as f64 / (n - 1) as f64;
        let s = u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
        stamps.push(1_700_000_000_000_000_000 + (k as i64) * 10_000_000);
        positions.push(Vec3::new(0.3 * s, 0.1 * s, 0.05 * s));
        let turn = rotation::exp(axis.map(|c| 0.5 * angle * s * c / len));
        orientations.push(rotation::mul(turn, start));
    }
    RawDemo {
        name: name.into(),
        file: "synthetic".into(),
        topic: name.into(),
        stamps_ns: stamps,
        positions,
        orientations: Some(
            orientations
                .iter()
                .enumerate()
                .map(|(k, q)| {
                    let once = dmpscope_core::geom::xyzw(&unit(*q));
                    unit(if flip(k) { once.map(|c| -c) } else { once })
                })
                .collect(),
        ),
        time_source: TimeSource::HeaderStamp,
    }
}

fn unit(q: Q) -> dmpscope_core::geom::Quat {
    quat_from_xyzw(q).expect("a unit quaternion")
}

fn model(demos: &[RawDemo]) -> Model {
    let prepared = demos
        .iter()
        .map(|d| prepare(d, &PrepSettings::default()).expect("prepare"))
        .collect();
    Model::new(prepared, DmpSettings::default()).expect("model")
}

#[test]
fn a_regeneration_reproduces_the_rotation_and_stays_unit() {
    let start = rotation::exp([0.1, -0.2, 0.3]);
    let m = model(&[turning("a", start, [1.0, 1.0, 0.0], 1.4, 2.0)]);
    assert!(m.has_orientation());
    for (dm, km) in [(10.73, 20.71), (25.0, 156.25), (4.0, 4.0)] {
        let (d_rot, alpha) = m.rotation_error(0, dm, km).expect("orientation");
        let path = m.orientation_rollout(0, dm, km).expect("rollout");
        let worst_norm = path
            .q
            .iter()
            .map(|q| (rotation::dot(*q, *q).sqrt() - 1.0).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "{dm} / {km}: d_rot {:.4} deg, alpha_peak {alpha:.2}, |q| - 1 at most {worst_norm:.1e}",
            d_rot.to_degrees()
        );
        assert!(d_rot.to_degrees() < 0.5, "d_rot {} deg", d_rot.to_degrees());
        assert!(worst_norm < 1e-12);
    }
}

#[test]
fn quaternion_sign_flips_change_nothing() {
    let start = rotation::exp([0.4, 0.1, -0.2]);
    let a = turning("a", start, [0.0, 0.0, 1.0], 2.0, 1.5);
    // Every third sample flipped within the demo, the first among them.
    let flipped = turning_flipped("a", start, [0.0, 0.0, 1.0], 2.0, 1.5, &|k| k % 3 == 0);
    // Between demos: the second demo stored with the other sign throughout.
    let b = turning("b", start, [1.0, 0.0, 0.0], -1.0, 2.0);
    let b_flipped = turning_flipped("b", start, [1.0, 0.0, 0.0], -1.0, 2.0, &|_| true);
    let (two, two_flipped) = (model(&[a.clone(), b]), model(&[a.clone(), b_flipped]));
    for (dm, km) in [(10.73, 20.71), (25.0, 156.25)] {
        assert_eq!(
            two.rotation_error(1, dm, km),
            two_flipped.rotation_error(1, dm, km)
        );
    }
    let (m, f) = (model(&[a]), model(&[flipped]));
    for (dm, km) in [(10.73, 20.71), (25.0, 156.25)] {
        let (x, y) = (
            m.rotation_error(0, dm, km).expect("a"),
            f.rotation_error(0, dm, km).expect("flipped"),
        );
        assert_eq!(x, y, "the same d_rot and alpha_peak to the bit");
    }
}
