//! Generalised rollouts and skills (method.md section 10) against the
//! independent NumPy reference `tests/golden/generalise.py`
//! (`expected_generalise.json`, conventions in `tests/golden/README.md`).

mod golden_data;

use dmpscope_core::geom::Vec3;
use dmpscope_core::{Generalised, Model, Primitive, Scaling, Skill, Target};
use golden_data::{f, golden, model};
use serde_json::Value;

const TOL: f64 = 1e-9;

fn vec3(v: &Value) -> Option<[f64; 3]> {
    let a = v.as_array()?;
    Some([f(&a[0]), f(&a[1]), f(&a[2])])
}

fn rows(v: &Value) -> Vec<[f64; 3]> {
    v.as_array()
        .expect("rows")
        .iter()
        .map(|r| vec3(r).expect("row"))
        .collect()
}

/// `|ours - golden| <= TOL * max(1, max |golden|)` over every sample and
/// axis (docs/export.md's rule); returns the worst error over that scale.
#[track_caller]
fn compare(case: &str, what: &str, ours: &[Vec3], golden: &[[f64; 3]], idx: &[usize]) -> f64 {
    let scale = golden.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()));
    let mut worst = 0.0f64;
    for (row, &k) in golden.iter().zip(idx) {
        for a in 0..3 {
            let e = (ours[k][a] - row[a]).abs() / scale;
            worst = worst.max(e);
            assert!(
                e <= TOL,
                "{case}: {what}[{k}][{a}] = {} vs golden {} ({e:.2e} of {scale})",
                ours[k][a],
                row[a]
            );
        }
    }
    worst
}

/// The case's target: its start, goal, duration and scaling.
fn case_target(case: &Value) -> Target {
    let scaling = match case["scaling"].as_str() {
        Some("frame") => Scaling::Frame,
        _ => Scaling::Paper,
    };
    Target {
        start: vec3(&case["start"]).map(Vec3::from),
        goal: vec3(&case["goal"]).map(Vec3::from),
        duration_s: case["duration"].as_f64(),
        scaling,
        ..Target::default()
    }
}

/// The indices of the samples the reference gives.
fn case_indices(case: &Value) -> Vec<usize> {
    case["idx"]
        .as_array()
        .expect("idx")
        .iter()
        .map(|v| v.as_u64().expect("index") as usize)
        .collect()
}

/// The case's run at its target: the skill's (with the skill) or a demo's.
fn run_case(
    m: &Model,
    case: &Value,
    target: &Target,
    dm: f64,
    km: f64,
) -> (Generalised, Option<Skill>) {
    match case["source"].as_str() {
        Some("skill") => {
            let skill = Skill::new(m, dm, km, target.scaling).expect("skill");
            (
                skill.primitive.rollout(target).expect("rollout"),
                Some(skill),
            )
        }
        _ => {
            let i = case["demo"].as_u64().expect("demo") as usize;
            let p = Primitive::of_demo(m, i, dm, km).expect("demo");
            (p.rollout(target).expect("rollout"), None)
        }
    }
}

/// The run's mapping Q, its exact start and its sample times.
fn check_mapping_start_and_times(name: &str, case: &Value, out: &Generalised, idx: &[usize]) {
    let q = out.mapping.matrix();
    for (r, row) in case["Q"].as_array().expect("Q").iter().enumerate() {
        let row = vec3(row).expect("Q row");
        for c in 0..3 {
            assert!((q[r][c] - row[c]).abs() <= 1e-12, "{name}: Q[{r}][{c}]");
        }
    }
    let start = vec3(&case["start_used"]).expect("start_used");
    assert_eq!(
        out.unit.y[0],
        Vec3::from(start),
        "{name}: starts exactly at the start"
    );
    for (k, t) in idx.iter().zip(case["t"].as_array().expect("t")) {
        assert!(
            (out.t[*k] - f(t)).abs() <= 1e-12 * f(t).max(1.0),
            "{name}: t"
        );
    }
}

/// The run's positions, velocities and accelerations; the worst error over scale.
fn compare_the_paths(name: &str, case: &Value, out: &Generalised, idx: &[usize]) -> f64 {
    let mut worst = 0.0f64;
    worst = worst.max(compare(name, "y", &out.unit.y, &rows(&case["y"]), idx));
    worst = worst.max(compare(name, "v", &out.v, &rows(&case["v"]), idx));
    worst = worst.max(compare(name, "a", &out.a, &rows(&case["a"]), idx));
    worst
}

/// A skill's own start and duration, its band and forcing SD; the worst
/// error over scale.
fn check_the_skill(
    name: &str,
    case: &Value,
    out: &Generalised,
    skill: &Skill,
    idx: &[usize],
) -> f64 {
    let mut worst = 0.0f64;
    let own = skill.primitive.start_abs();
    let golden_start = vec3(&case["skill_start"]).expect("skill_start");
    for a in 0..3 {
        assert!(
            (own[a] - golden_start[a]).abs() <= 1e-15,
            "{name}: skill start"
        );
    }
    let d = f(&case["skill_duration"]);
    assert!((skill.primitive.duration_s - d).abs() <= 1e-14 * d);
    worst = worst.max(compare(name, "band", &out.band, &rows(&case["band"]), idx));
    worst = worst.max(compare(
        name,
        "forcing_sd",
        &skill.forcing_sd,
        &rows(&case["forcing_sd"]),
        idx,
    ));
    worst
}

/// One case of the reference against ours; the worst error over scale.
fn check_case(m: &Model, case: &Value) -> f64 {
    let name = case["name"].as_str().expect("name");
    let (dm, km) = (f(&case["dm"]), f(&case["km"]));
    let target = case_target(case);
    let idx = case_indices(case);
    let (out, skill) = run_case(m, case, &target, dm, km);
    check_mapping_start_and_times(name, case, &out, &idx);
    let mut worst = compare_the_paths(name, case, &out, &idx);
    if let Some(skill) = skill {
        worst = worst.max(check_the_skill(name, case, &out, &skill, &idx));
    }
    worst
}

#[test]
fn generalised_rollouts_match_the_reference() {
    let expected = golden("expected_generalise.json");
    let m = model();
    let mut worst = 0.0f64;
    for case in expected["cases"].as_array().expect("cases") {
        worst = worst.max(check_case(&m, case));
    }
    eprintln!("worst error over scale: {worst:.2e}");
}
