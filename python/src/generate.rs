//! `dmpscope.regen` and `dmpscope.export`: demos regenerated at one gain
//! pair, or run at a new start, goal and duration (method.md section 10),
//! by the core's [`runs`] as `dmpscope regen` runs them; the DMP document
//! a controller runs (`docs/export.md`) as `regen --out F.json` writes it.

use std::sync::Arc;

use dmpscope_core::Scaling;
use dmpscope_core::export::dmp_doc::run_document;
use dmpscope_core::generalise::primitive::Target;
use dmpscope_core::generalise::run::{Run, Which, runs, unit_quaternion};
use dmpscope_core::geom::Vec3;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyList;

use crate::demo::{frame_id, rows};
use crate::errors::{guarded, invalid, to_py, warn};
use crate::landscape::{Landscape, json_to_py};
use crate::model::{Inputs, ModelKw, build};

/// A primitive run at a target: time, positions, velocities and
/// accelerations in real time, and the orientations where the demo has
/// them.
///
/// Arrays: `t` (N, seconds from 0 to `duration`), `positions` (N x 3,
/// metres, absolute), `velocities` (N x 3, m/s), `accelerations` (N x 3,
/// m/s^2), `orientations` (N x 4 `[x, y, z, w]`, or None),
/// `angular_velocities` (N x 3, rad/s, or None), `band` (N x 3, the skill's
/// per-time SD of its members' positions, metres, or None).
#[pyclass(module = "dmpscope", frozen, get_all)]
pub struct Rollout {
    /// The demo's name, or `skill (N demos)`.
    name: String,
    /// `demo` or `skill`.
    source: &'static str,
    /// D/M it ran at.
    dm: f64,
    /// K/M it ran at.
    km: f64,
    /// Seconds, 0 to `duration`.
    t: Py<PyAny>,
    /// Absolute positions, metres.
    positions: Py<PyAny>,
    /// Real-time velocities, m/s.
    velocities: Py<PyAny>,
    /// Real-time accelerations, m/s^2.
    accelerations: Py<PyAny>,
    /// Unit quaternions `[x, y, z, w]`, or None.
    orientations: Option<Py<PyAny>>,
    /// Real-time angular velocities, rad/s, or None.
    angular_velocities: Option<Py<PyAny>>,
    /// The skill's band, metres, or None.
    band: Option<Py<PyAny>>,
    /// Start, metres.
    start: (f64, f64, f64),
    /// Goal, metres.
    goal: (f64, f64, f64),
    /// Duration T', seconds.
    duration: f64,
    /// Largest real-time speed, m/s.
    peak_speed: f64,
    /// Largest real-time acceleration norm, m/s^2.
    a_peak: f64,
    /// Largest acceleration norm in unit time (as Table I's a_peak).
    a_peak_unit: f64,
    /// Distance of the last point from the goal, metres.
    final_error: f64,
}

#[pymethods]
impl Rollout {
    fn __repr__(&self) -> String {
        format!(
            "Rollout({:?}, D/M {}, K/M {}, {:.3} s, end {:.3} mm from the goal)",
            self.name,
            self.dm,
            self.km,
            self.duration,
            self.final_error * 1e3
        )
    }
}

/// Rows of three as an N x 3 array.
fn rows3<'py>(py: Python<'py>, v: &[Vec3]) -> PyResult<Py<PyAny>> {
    Ok(rows(py, v.iter().flat_map(|p| [p.x, p.y, p.z]).collect(), 3)?.unbind())
}

fn triple(v: Vec3) -> (f64, f64, f64) {
    (v.x, v.y, v.z)
}

/// One run as a `Rollout`.
fn rollout(py: Python<'_>, r: &Run) -> PyResult<Rollout> {
    let out = &r.out;
    let duration = out.duration_s;
    let orientation = out.orientation.as_ref();
    let unit_peak = out
        .unit
        .a
        .iter()
        .map(|a| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt())
        .fold(0.0, f64::max);
    Ok(Rollout {
        name: r.primitive.name.clone(),
        source: if r.skill.is_some() { "skill" } else { "demo" },
        dm: r.primitive.dm,
        km: r.primitive.km,
        t: PyArray1::from_vec(py, out.t.clone()).into_any().unbind(),
        positions: rows3(py, &out.unit.y)?,
        velocities: rows3(py, &out.v)?,
        accelerations: rows3(py, &out.a)?,
        orientations: orientation
            .map(|o| rows(py, o.q.iter().flatten().copied().collect(), 4).map(Bound::unbind))
            .transpose()?,
        angular_velocities: orientation
            .map(|o| {
                let w = o.w.iter().flatten().map(|c| c / duration).collect();
                rows(py, w, 3).map(Bound::unbind)
            })
            .transpose()?,
        band: r.skill.as_ref().map(|_| rows3(py, &out.band)).transpose()?,
        start: triple(out.start),
        goal: triple(out.goal),
        duration,
        peak_speed: out.peak_speed,
        a_peak: out.a_peak,
        a_peak_unit: unit_peak,
        final_error: out.final_error,
    })
}

/// Where and how long to run, and which primitives.
pub struct TargetKw {
    /// A demo: its index in the list given (0-based) or its name.
    pub demo: Option<Py<PyAny>>,
    /// The skill of all demos.
    pub skill: bool,
    /// New start, metres.
    pub start: Option<(f64, f64, f64)>,
    /// New goal, metres.
    pub goal: Option<(f64, f64, f64)>,
    /// New duration, seconds.
    pub duration: Option<f64>,
    /// `paper` or `frame`.
    pub scaling: String,
    /// New start orientation `[x, y, z, w]`.
    pub start_orientation: Option<[f64; 4]>,
    /// New goal orientation.
    pub goal_orientation: Option<[f64; 4]>,
}

/// The model of `demos`, or of a `Landscape`'s demos.
fn inputs_of(py: Python<'_>, demos: &Bound<'_, PyAny>, kw: &ModelKw) -> PyResult<Arc<Inputs>> {
    if let Ok(land) = demos.cast::<Landscape>() {
        if !kw.is_default() {
            return Err(invalid(
                "a Landscape was given: it already has its model settings; pass the demos \
                 instead to change them",
            ));
        }
        return Ok(Arc::clone(&land.get().inputs));
    }
    Ok(Arc::new(build(py, demos, kw)?))
}

/// The model's index of the demo `which` names (an index into the list
/// given, or a name).
fn demo_index(py: Python<'_>, inputs: &Inputs, which: &Py<PyAny>) -> PyResult<usize> {
    let which = which.bind(py);
    let names: Vec<&str> = inputs
        .model
        .demos()
        .iter()
        .map(|d| d.name.as_str())
        .collect();
    if let Ok(name) = which.extract::<String>() {
        return names.iter().position(|n| *n == name).ok_or_else(|| {
            invalid(format!(
                "no demo is named {name:?}; the demos are {}",
                names.join(", ")
            ))
        });
    }
    let i: i64 = which.extract().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err("demo must be an index (int) or a demo's name")
    })?;
    let given = inputs.used.iter().max().map_or(0, |m| m + 1);
    let index = usize::try_from(i)
        .ok()
        .filter(|&i| i < given)
        .ok_or_else(|| {
            invalid(format!(
                "demo must be between 0 and {} (0-based: the CLI's --demo N is demo=N-1), got {i}",
                given.saturating_sub(1)
            ))
        })?;
    inputs.model_index(index).ok_or_else(|| {
        invalid(format!(
            "demo {index} was left out as unusable (see the warning); it has no DMP"
        ))
    })
}

/// The target, checked; its notes issued.
fn target_of(py: Python<'_>, kw: &TargetKw) -> PyResult<Target> {
    let scaling = match kw.scaling.as_str() {
        "paper" => Scaling::Paper,
        "frame" => Scaling::Frame,
        other => {
            return Err(invalid(format!(
                "unknown scaling {other:?}: paper or frame"
            )));
        }
    };
    if let Some(d) = kw.duration
        && !(d.is_finite() && d > 0.0)
    {
        return Err(invalid(format!(
            "duration must be a positive number of seconds, got {d}"
        )));
    }
    let mut notices = Vec::new();
    let mut unit = |what: &str, q: Option<[f64; 4]>| -> PyResult<Option<[f64; 4]>> {
        let Some(q) = q else { return Ok(None) };
        let (q, note) = unit_quaternion(what, q).map_err(to_py)?;
        notices.extend(note);
        Ok(Some(q))
    };
    let start_orientation = unit("start_orientation", kw.start_orientation)?;
    let goal_orientation = unit("goal_orientation", kw.goal_orientation)?;
    warn(py, &notices)?;
    let point = |p: Option<(f64, f64, f64)>| p.map(|(x, y, z)| Vec3::new(x, y, z));
    Ok(Target {
        start: point(kw.start),
        goal: point(kw.goal),
        duration_s: kw.duration,
        scaling,
        start_orientation,
        goal_orientation,
    })
}

/// Checks the gains are positive numbers.
fn check_gains(dm: f64, km: f64) -> PyResult<()> {
    for (name, v) in [("dm", dm), ("km", km)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(invalid(format!(
                "{name} must be a positive number, got {v}"
            )));
        }
    }
    Ok(())
}

/// The runs `kw` asks for, with the model they ran on; their warnings
/// issued.
pub fn run_all(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
    dm: f64,
    km: f64,
    kw: &TargetKw,
    model: &ModelKw,
) -> PyResult<(Arc<Inputs>, Vec<Run>, Scaling)> {
    check_gains(dm, km)?;
    if kw.skill && kw.demo.is_some() {
        return Err(invalid("pass demo= or skill=True, not both"));
    }
    let target = target_of(py, kw)?;
    let inputs = inputs_of(py, demos, model)?;
    let which = match (&kw.demo, kw.skill) {
        (_, true) => Which::Skill,
        (Some(d), false) => Which::Demo(demo_index(py, &inputs, d)?),
        (None, false) => Which::All,
    };
    let found =
        py.detach(|| guarded(|| runs(&inputs.model, dm, km, which, &target).map_err(to_py)))?;
    for r in &found {
        let notices: Vec<_> = r
            .out
            .warnings
            .iter()
            .map(|w| dmpscope_core::Notice::warning(w.clone()))
            .collect();
        warn(py, &notices)?;
    }
    Ok((inputs, found, target.scaling))
}

/// Every run as a `Rollout`: one when a demo or the skill was asked for,
/// else a list.
pub fn rollouts(py: Python<'_>, runs: &[Run], one: bool) -> PyResult<Py<PyAny>> {
    let mut all = runs.iter().map(|r| rollout(py, r));
    if one {
        let first = all
            .next()
            .ok_or_else(|| invalid("no run was made: no demo to run"))??;
        return Ok(Py::new(py, first)?.into_any());
    }
    let list = PyList::empty(py);
    for r in all {
        list.append(Py::new(py, r?)?)?;
    }
    Ok(list.into_any().unbind())
}

/// The DMP document of the one run `kw` names, written to `path` when
/// given (the bytes `regen --out F.json` writes), as Python objects.
pub fn export_doc(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
    dm: f64,
    km: f64,
    path: Option<std::path::PathBuf>,
    kw: &TargetKw,
    model: &ModelKw,
    frame: Option<String>,
) -> PyResult<Py<PyAny>> {
    if kw.demo.is_none() && !kw.skill {
        return Err(invalid(
            "an export holds one DMP: pass demo= (an index from 0, or a name) or skill=True to \
             choose it",
        ));
    }
    let (inputs, found, scaling) = run_all(py, demos, dm, km, kw, model)?;
    let run = found
        .first()
        .ok_or_else(|| invalid("no run was made: no demo to export"))?;
    let frame = frame.unwrap_or_else(|| frame_id(&inputs.options));
    let doc = run_document(&inputs.model, run, frame, scaling, inputs.options.units)
        .map_err(|e| invalid(format!("not written: {e}")))?;
    let mut text = serde_json::to_string(&doc).map_err(|e| invalid(e.to_string()))?;
    text.push('\n');
    if let Some(path) = path {
        std::fs::write(&path, &text).map_err(|e| {
            pyo3::exceptions::PyOSError::new_err(format!("{}: cannot write: {e}", path.display()))
        })?;
    }
    Ok(json_to_py(py, &text)?.unbind())
}
