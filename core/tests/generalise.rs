//! Generalisation (method.md section 10): the rollout at a new start, goal
//! and duration, the two scaling modes, and the skill of many demos.

mod golden_data;

use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::geom::Vec3;
use dmpscope_core::{
    Model, PrepSettings, Primitive, RawDemo, Scaling, Skill, Target, TimeSource, Unusable,
    build_model,
};
use golden_data::model;

const DM: f64 = 10.73;
const KM: f64 = 20.71;

#[test]
fn at_its_own_target_the_generalised_rollout_is_todays_to_the_bit() {
    let m = model();
    for i in 0..m.demos().len() {
        let p = Primitive::of_demo(&m, i, DM, KM).expect("demo");
        let old = m.rollout(i, DM, KM);
        for scaling in [Scaling::Paper, Scaling::Frame] {
            let new = p
                .rollout(&Target {
                    scaling,
                    ..Target::default()
                })
                .expect("rollout");
            let p0 = m.demos()[i].p0;
            for k in 0..old.y.len() {
                let y: [f64; 3] = std::array::from_fn(|a| old.y[k][a] + p0[a]);
                assert_eq!(new.unit.y[k], Vec3::from(y), "y at {k}");
                assert_eq!(new.unit.v[k], old.v[k], "v at {k}");
                assert_eq!(new.unit.a[k], old.a[k], "a at {k}");
            }
            assert!(new.warnings.is_empty());
            assert_eq!(new.duration_s, m.demos()[i].duration_s);
        }
    }
}

#[test]
fn a_new_duration_rescales_velocity_and_acceleration_only() {
    let m = model();
    let p = Primitive::of_demo(&m, 0, DM, KM).expect("demo");
    let own = p.rollout(&Target::default()).expect("own");
    let slow = p
        .rollout(&Target {
            duration_s: Some(4.0),
            ..Target::default()
        })
        .expect("slow");
    assert_eq!(own.unit, slow.unit);
    let n = own.t.len();
    assert_eq!(slow.t[0], 0.0);
    assert!((slow.t[n - 1] - 4.0).abs() < 1e-12);
    for k in 0..n {
        for a in 0..3 {
            assert_eq!(slow.v[k][a], own.unit.v[k][a] / 4.0);
            assert_eq!(slow.a[k][a], own.unit.a[k][a] / 16.0);
        }
    }
}

/// Rotation by `angle` about the unit `axis`.
fn rotation(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    let v = 1.0 - c;
    let [x, y, z] = axis;
    [
        [c + x * x * v, x * y * v - z * s, x * z * v + y * s],
        [y * x * v + z * s, c + y * y * v, y * z * v - x * s],
        [z * x * v - y * s, z * y * v + x * s, c + z * z * v],
    ]
}

fn apply(r: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|a| r[a][0] * v[0] + r[a][1] * v[1] + r[a][2] * v[2])
}

#[test]
fn frame_scaling_with_a_rotated_goal_rotates_the_path() {
    let m = model();
    let p = Primitive::of_demo(&m, 1, DM, KM).expect("demo");
    let own = p.rollout(&Target::default()).expect("own");
    let (start, goal) = (p.start_abs(), p.goal_abs());
    let d: [f64; 3] = std::array::from_fn(|a| goal[a] - start[a]);
    // An axis perpendicular to the displacement: the smallest rotation
    // taking d to R d is R itself.
    let e = [0.0, 0.0, 1.0];
    let mut axis = [
        d[1] * e[2] - d[2] * e[1],
        d[2] * e[0] - d[0] * e[2],
        d[0] * e[1] - d[1] * e[0],
    ];
    let len = axis.iter().map(|v| v * v).sum::<f64>().sqrt();
    axis = axis.map(|v| v / len);
    for angle in [0.3, 1.2, -2.5] {
        let r = rotation(axis, angle);
        let new_goal: [f64; 3] = {
            let rd = apply(&r, d);
            std::array::from_fn(|a| start[a] + rd[a])
        };
        let turned = p
            .rollout(&Target {
                goal: Some(new_goal.into()),
                scaling: Scaling::Frame,
                ..Target::default()
            })
            .expect("rotated");
        let extent = d.iter().map(|v| v * v).sum::<f64>().sqrt();
        for k in 0..own.unit.y.len() {
            let rel: [f64; 3] = std::array::from_fn(|a| own.unit.y[k][a] - start[a]);
            let want = apply(&r, rel);
            for a in 0..3 {
                let got = turned.unit.y[k][a] - start[a];
                assert!(
                    (got - want[a]).abs() <= 1e-12 * extent,
                    "angle {angle}, step {k}, axis {a}: {got} vs {}",
                    want[a]
                );
            }
        }
        assert!(turned.final_error < 0.2 * extent);
    }
}

#[test]
fn the_skill_of_identical_demos_is_the_demo() {
    let m = model();
    let same = m.subset(&[2, 2, 2]).expect("subset");
    for scaling in [Scaling::Paper, Scaling::Frame] {
        let skill = Skill::new(&same, DM, KM, scaling).expect("skill");
        let demo = Primitive::of_demo(&same, 0, DM, KM).expect("demo");
        let target = Target {
            goal: Some(Vec3::from([0.1, 0.5, 0.4])),
            start: Some(Vec3::from([0.2, -0.1, 0.0])),
            duration_s: Some(2.0),
            scaling,
            ..Target::default()
        };
        let a = skill.primitive.rollout(&target).expect("skill rollout");
        let b = demo.rollout(&target).expect("demo rollout");
        let scale = b
            .unit
            .y
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        for k in 0..a.unit.y.len() {
            for c in 0..3 {
                assert!((a.unit.y[k][c] - b.unit.y[k][c]).abs() <= 1e-12 * scale);
                assert!(a.band[k][c] <= 1e-12 * scale, "band {}", a.band[k][c]);
            }
        }
        assert!(skill.forcing_sd.iter().flatten().all(|v| *v <= 1e-9));
        assert_eq!(skill.demos.len(), 3);
    }
}

#[test]
fn the_skill_of_different_demos_has_a_band_and_reaches_its_goal() {
    let m = model();
    let skill = Skill::new(&m, DM, KM, Scaling::Frame).expect("skill");
    let out = skill
        .primitive
        .rollout(&Target {
            scaling: Scaling::Frame,
            ..Target::default()
        })
        .expect("rollout");
    let widest = out.band.iter().flatten().fold(0.0f64, |m, v| m.max(*v));
    assert!(widest > 1e-4, "the demos differ: {widest}");
    assert_eq!(out.band[0], Vec3::zeros());
    assert!(out.final_error < 0.02, "{}", out.final_error);
}

#[test]
fn bad_targets_name_the_argument() {
    let m = model();
    let p = Primitive::of_demo(&m, 0, DM, KM).expect("demo");
    let err = |t: Target| p.rollout(&t).expect_err("bad").to_string();
    let s = p.start_abs();
    let e = err(Target {
        goal: Some(s),
        ..Target::default()
    });
    assert!(
        e.contains("the goal (--goal) equals the start (--start)"),
        "{e}"
    );
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-6, 1e10] {
        let e = err(Target {
            duration_s: Some(bad),
            ..Target::default()
        });
        assert!(e.contains("--duration"), "{e}");
    }
    let e = err(Target {
        goal: Some(Vec3::from([f64::NAN, 0.0, 0.0])),
        ..Target::default()
    });
    assert!(e.contains("--goal"), "{e}");
    let e = Primitive::of_demo(&m, 7, DM, KM)
        .expect_err("range")
        .to_string();
    assert!(
        e.contains("--demo 8 is out of range: there are 3 demos"),
        "{e}"
    );
    assert!(Primitive::of_demo(&m, 0, f64::NAN, KM).is_err());
}

/// A minimum-jerk reach by `delta` over 1.5 s at 100 Hz.
fn reach(delta: [f64; 3]) -> Model {
    let n = 151;
    let samples: Vec<(i64, [f64; 3])> = (0..n)
        .map(|k| {
            let s = k as f64 / (n - 1) as f64;
            let m = 10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5);
            (k as i64 * 10_000_000, delta.map(|d| 0.1 + d * m))
        })
        .collect();
    let raw = RawDemo {
        name: "reach".into(),
        file: "reach.mcap".into(),
        topic: "/hand".into(),
        stamps_ns: samples.iter().map(|s| s.0).collect(),
        positions: samples.iter().map(|s| s.1.into()).collect(),
        orientations: None,
        time_source: TimeSource::HeaderStamp,
    };
    build_model(
        [&raw],
        &PrepSettings::default(),
        DmpSettings::default(),
        Unusable::Fail,
    )
    .expect("model")
    .model
}

/// Demo 0 of `m` with its goal raised by 0.1 m, under `scaling`.
fn raised_goal(m: &Model, scaling: Scaling) -> dmpscope_core::Generalised {
    let p = Primitive::of_demo(m, 0, DM, KM).expect("demo");
    let mut goal = p.goal_abs();
    goal[2] += 0.1;
    p.rollout(&Target {
        goal: Some(goal),
        scaling,
        ..Target::default()
    })
    .expect("moved")
}

#[test]
fn per_axis_scaling_warns_about_an_axis_that_barely_moves() {
    // z moves 4 mm in a 0.5 m reach: under 5 %.
    let m = reach([0.3, 0.4, 0.004]);
    let out = raised_goal(&m, Scaling::Paper);
    assert_eq!(out.warnings.len(), 1, "{:?}", out.warnings);
    assert!(
        out.warnings[0].contains("4.0 mm on z") && out.warnings[0].contains("--scaling frame"),
        "{:?}",
        out.warnings
    );
    // The frame-independent mode has no per-axis factor to warn of.
    assert!(raised_goal(&m, Scaling::Frame).warnings.is_empty());
    // Every axis well away from zero: no warning.
    let m = reach([0.3, 0.4, 0.2]);
    let out = raised_goal(&m, Scaling::Paper);
    assert!(out.warnings.is_empty(), "{:?}", out.warnings);
}

#[test]
fn an_export_never_holds_nan() {
    use dmpscope_core::export::dmp_doc::{DocContext, dmp_document};
    let m = model();
    // Gains so large that the integration overflows: refused, so no export
    // (JSON, CSV or MCAP) and no view ever gets its numbers.
    let p = Primitive::of_demo(&m, 0, 1e300, 1e300).expect("demo");
    let err = p
        .rollout(&Target::default())
        .expect_err("diverges")
        .to_string();
    assert!(err.contains("the motion diverges"), "{err}");
    let p = Primitive::of_demo(&m, 0, DM, KM).expect("demo");
    let mut out = p.rollout(&Target::default()).expect("rollout");
    // A document holding a non-finite number is refused too.
    out.a[500][1] = f64::NAN;
    let ctx = || DocContext {
        demos: vec![p.name.clone()],
        source: "demo",
        basis: (&m.basis().centres, &m.basis().widths),
        frame_id: "world".into(),
        band: None,
        scaling: Scaling::Paper,
        recorded_units: dmpscope_core::load::units::Units::M,
    };
    let err = dmp_document(&p, &out, ctx())
        .expect_err("refused")
        .to_string();
    assert!(err.contains("non-finite number at rollout."), "{err}");
    // At sane gains the same document is written.
    let p = Primitive::of_demo(&m, 0, DM, KM).expect("demo");
    let out = p.rollout(&Target::default()).expect("rollout");
    let doc = dmp_document(&p, &out, ctx()).expect("written");
    assert_eq!(Vec3::from(doc.rollout.y[0]), p.start_abs());
}
