//! The orientation DMP (method.md section 12) on synthetic demos: a
//! regeneration reproduces the demo's rotation, the quaternion stays unit,
//! and quaternion sign flips between and within demos change nothing.

mod common;

use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::geom::{Vec3, quat_from_xyzw};
use dmpscope_core::rotation;
use dmpscope_core::rotation::QuatXyzw;
use dmpscope_core::{Model, PrepSettings, RawDemo, TimeSource, prepare};

/// A reach whose orientation turns by `angle` about `axis` with a
/// minimum-jerk profile, from `start`, over `secs` at 100 Hz.
fn turning(name: &str, start: QuatXyzw, axis: [f64; 3], angle: f64, secs: f64) -> RawDemo {
    turning_flipped(name, start, axis, angle, secs, &|_| false)
}

/// [`turning`] with the samples `flip` names stored with the opposite sign
/// (the same rotation, as trackers do).
fn turning_flipped(
    name: &str,
    start: QuatXyzw,
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

fn unit(q: QuatXyzw) -> dmpscope_core::geom::Quat {
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

fn planted_raw() -> Vec<RawDemo> {
    let spec = dmpscope_core::synth::planted_forcing::PlantedSpec {
        dm: 10.73,
        km: 20.71,
        noise_m: 1e-4,
        demos: 8,
        seed: 42,
        scale_forcing: None,
    };
    common::planted_raw(&spec)
}

#[test]
fn planted_orientations_come_back_at_the_planted_gains() {
    let m = model(&planted_raw());
    let mut worst = 0.0f64;
    for i in 0..m.demos().len() {
        let (d_rot, _) = m.rotation_error(i, 10.73, 20.71).expect("orientation");
        worst = worst.max(d_rot.to_degrees());
        let path = m.orientation_rollout(i, 10.73, 20.71).expect("rollout");
        for q in &path.q {
            assert!((rotation::dot(*q, *q).sqrt() - 1.0).abs() < 1e-12);
        }
    }
    eprintln!("planted orientation: d_rot at most {worst:.4} deg at the planted gains");
    assert!(worst < 0.1, "{worst} deg");
}

/// The operating point's one-pass evaluation (each demo's orientation
/// integrated once for its d_rot and its path) gives what the two apart
/// give, to the bit; so do its other branches (separate orientation gains,
/// no orientation error).
#[test]
fn the_one_pass_point_equals_the_evaluation_and_the_rollouts() {
    let raw = planted_raw();
    let prepared: Vec<_> = raw
        .iter()
        .map(|d| prepare(d, &PrepSettings::default()).expect("prepare"))
        .collect();
    let separate = DmpSettings {
        orientation_gains: Some([20.0, 100.0]),
        ..DmpSettings::default()
    };
    let m = model(&raw);
    // The demos four at a time, one per lane: groups of four and fewer,
    // and demos without orientation between them.
    let mut mixed = raw[..6].to_vec();
    mixed[1].orientations = None;
    mixed[4].orientations = None;
    // A demo that turns 206 degrees beside three that turn little: its
    // lane takes the exact log (a rotation to go past 180 degrees) while
    // the others take the polynomial.
    let mut branches = raw[..3].to_vec();
    branches.insert(
        1,
        turning(
            "far",
            rotation::exp([0.1, 0.0, 0.0]),
            [0.2, 1.0, 0.3],
            3.6,
            2.0,
        ),
    );
    let models = [
        ("one pass", m.clone()),
        ("five demos", model(&raw[..5])),
        ("mixed", model(&mixed)),
        ("mixed branches", model(&branches)),
        (
            "separate gains",
            Model::new(prepared, separate).expect("model"),
        ),
        ("no orientation error", m.without_orientation_error()),
    ];
    for (what, m) in &models {
        for (dm, km) in [(10.73, 20.71), (0.5, 900.0), (60.0, 0.2)] {
            let (eval, turns) = m.evaluate_with_turns(dm, km);
            assert_eq!(
                format!("{eval:?}"),
                format!("{:?}", m.evaluate(dm, km)),
                "{what} at ({dm}, {km})"
            );
            assert_eq!(turns.len(), m.demos().len());
            for (i, path) in turns.iter().enumerate() {
                let apart = m.orientation_rollout(i, dm, km);
                let has = m.demos()[i].orientation.is_some();
                assert_eq!(apart.is_some(), has, "{what}: demo {i}");
                assert_eq!(
                    format!("{path:?}"),
                    format!("{apart:?}"),
                    "{what}: demo {i}"
                );
            }
        }
    }
    let (eval, _) = models[0].1.evaluate_with_turns(10.73, 20.71);
    assert!(eval.d_rot.iter().all(|d| d.is_finite()));
}

#[test]
fn a_new_goal_and_start_orientation_are_reached() {
    use dmpscope_core::{Primitive, Target};
    let m = model(&planted_raw());
    // The gains of CartesianDMP's defaults (alpha 25, beta 6.25): the
    // spring settles well inside unit time. At the planted 10.73 / 20.71 it
    // settles in about 1.6 unit times, so a goal far from the demo's own is
    // still degrees away at the end (what the robot's settling time says).
    let p = Primitive::of_demo(&m, 0, 25.0, 156.25).expect("primitive");
    let own = p.orientation.as_ref().expect("orientation").goal;
    let goal = rotation::mul(rotation::exp([0.3, -0.2, 0.25]), own);
    let start = rotation::exp([0.05, 0.1, 0.2]);
    let out = p
        .rollout(&Target {
            goal_orientation: Some(goal),
            start_orientation: Some(start),
            ..Target::default()
        })
        .expect("rollout");
    let path = out.orientation.expect("orientation path");
    assert!(
        (0..4).all(|c| (path.q[0][c] - start[c]).abs() < 1e-15),
        "starts at the new start (to rounding: the state is the rotation to go)"
    );
    for q in &path.q {
        assert!((rotation::dot(*q, *q) - 1.0).abs() < 1e-12, "unit: {q:?}");
    }
    // The same goal with the other sign is the same orientation: the
    // shorter way round, the same path.
    let flipped = p
        .rollout(&Target {
            goal_orientation: Some(goal.map(|c| -c)),
            start_orientation: Some(start),
            ..Target::default()
        })
        .expect("rollout")
        .orientation
        .expect("path");
    assert_eq!(flipped.q, path.q, "a flipped goal turns the same way");
    let end = rotation::angle(*path.q.last().expect("end"), goal).to_degrees();
    eprintln!(
        "new goal {:.1} deg from the own: reached within {end:.4} deg",
        rotation::angle(goal, own).to_degrees()
    );
    assert!(end < 0.05, "{end} deg");
    // A goal equal to the start is fine: the forcing term still turns it.
    let still = p
        .rollout(&Target {
            goal_orientation: Some(start),
            start_orientation: Some(start),
            ..Target::default()
        })
        .expect("rollout")
        .orientation
        .expect("path");
    let turned = still
        .q
        .iter()
        .map(|q| rotation::angle(*q, start))
        .fold(0.0, f64::max);
    assert!(turned > 0.01 && rotation::angle(*still.q.last().expect("end"), start) < 1e-3);
}
