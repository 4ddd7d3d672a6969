#![doc = include_str!("../README.md")]

pub mod demo;
pub mod errors;
pub mod generate;
pub mod landscape;
pub mod model;
pub mod report;

use std::path::PathBuf;
use std::sync::Arc;

use dmpscope_core::arrange::pool::{load_demos, read_path};
use dmpscope_core::extract::allowed::DEFAULT_EPS;
use dmpscope_core::extract::diagnostics::DiagSettings;
use dmpscope_core::landscape::grid::Grid;
use dmpscope_core::load::flags::LoadFlags;
use dmpscope_core::pipeline::ModelFlags;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

use crate::demo::Demo;
use crate::errors::{DmpscopeError, DmpscopeNote, DmpscopeWarning, guarded, invalid, to_py, warn};
use crate::generate::{Rollout, TargetKw, export_doc, rollouts, run_all};
use crate::landscape::Landscape;
use crate::model::ModelKw;
use crate::report::{Pick, Report};

/// `paths` as paths: one str or path-like, or a sequence of them.
fn paths_of(paths: &Bound<'_, PyAny>) -> PyResult<Vec<PathBuf>> {
    if paths.is_instance_of::<PyString>() || paths.hasattr("__fspath__")? {
        return Ok(vec![paths.extract()?]);
    }
    paths.try_iter()?.map(|p| p?.extract()).collect()
}

/// One str or a sequence of str, as a list.
fn strings(value: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Vec<String>> {
    match value {
        None => Ok(Vec::new()),
        Some(v) if v.is_instance_of::<PyString>() => Ok(vec![errors::text_of(v, what)?]),
        Some(v) => v.try_iter()?.map(|s| errors::text_of(&s?, what)).collect(),
    }
}

/// The demonstrations in recordings (see the stub for the keywords).
#[pyfunction]
#[pyo3(signature = (
    paths, *, topic=None, demos="topic", units="m", segments="all", trim_rest=false,
    exclude=None, frame=None, fixed_frame=None, min_extent=LoadFlags::default().min_extent,
    y_up=false, rest_speed=LoadFlags::default().rest_speed,
    min_rest=LoadFlags::default().min_rest, min_demo=LoadFlags::default().min_demo,
    gaps="split", cut="none", drop_bad_orientation=false
))]
fn load(
    py: Python<'_>,
    paths: &Bound<'_, PyAny>,
    topic: Option<&Bound<'_, PyAny>>,
    demos: &str,
    units: &str,
    segments: &str,
    trim_rest: bool,
    exclude: Option<&Bound<'_, PyAny>>,
    frame: Option<&Bound<'_, PyAny>>,
    fixed_frame: Option<String>,
    min_extent: f64,
    y_up: bool,
    rest_speed: f64,
    min_rest: f64,
    min_demo: f64,
    gaps: &str,
    cut: &str,
    drop_bad_orientation: bool,
) -> PyResult<Vec<Demo>> {
    let flags = LoadFlags {
        frames: strings(frame, "frame")?,
        fixed_frame,
        topics: strings(topic, "topic")?,
        exclude: strings(exclude, "exclude")?,
        min_extent,
        y_up,
        demos: demos.parse().map_err(invalid)?,
        rest_speed,
        min_rest,
        min_demo,
        gaps: gaps.parse().map_err(invalid)?,
        units: units.parse().map_err(invalid)?,
        trim_rest,
        segments: segments.parse().map_err(invalid)?,
        drop_bad_orientation,
        cut: cut.parse().map_err(invalid)?,
    };
    let paths = paths_of(paths)?;
    let options = Arc::new(flags.options());
    let mut notices: Vec<_> = flags.segments_notice().into_iter().collect();
    let loaded = py.detach(|| {
        guarded(|| {
            load_demos(&paths, &options, &mut read_path, &mut |n| {
                notices.extend_from_slice(n);
            })
            .map_err(to_py)
        })
    });
    // What was said before an error is said too, as the CLI prints it.
    warn(py, &notices)?;
    Ok(loaded?
        .into_iter()
        .map(|raw| Demo::loaded(raw, Arc::clone(&options)))
        .collect())
}

/// Demos regenerated at one gain pair, or run at a new target (see the
/// stub).
#[pyfunction]
#[pyo3(signature = (
    demos, dm, km, *, demo=None, skill=false, start=None, goal=None, duration=None,
    scaling="paper", goal_orientation=None, start_orientation=None, sg_window=None,
    sg_order=None, sg_seconds=None, basis=None, skill_mode=None, unusable=None,
    axis_sd_floor=None, k_rot=None, orientation_gains=None
))]
fn regen(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
    dm: f64,
    km: f64,
    demo: Option<Py<PyAny>>,
    skill: bool,
    start: Option<(f64, f64, f64)>,
    goal: Option<(f64, f64, f64)>,
    duration: Option<f64>,
    scaling: &str,
    goal_orientation: Option<[f64; 4]>,
    start_orientation: Option<[f64; 4]>,
    sg_window: Option<usize>,
    sg_order: Option<usize>,
    sg_seconds: Option<f64>,
    basis: Option<usize>,
    skill_mode: Option<String>,
    unusable: Option<String>,
    axis_sd_floor: Option<f64>,
    k_rot: Option<f64>,
    orientation_gains: Option<(f64, f64)>,
) -> PyResult<Py<PyAny>> {
    let one = demo.is_some() || skill;
    let kw = TargetKw {
        demo,
        skill,
        start,
        goal,
        duration,
        scaling: scaling.to_owned(),
        start_orientation,
        goal_orientation,
    };
    let model = ModelKw {
        sg_window,
        sg_order,
        sg_seconds,
        basis,
        skill_mode,
        unusable,
        axis_sd_floor,
        k_rot,
        orientation_gains,
    };
    let (_, runs, _) = run_all(py, demos, dm, km, &kw, &model)?;
    rollouts(py, &runs, one)
}

/// The DMP document a controller runs (see the stub).
#[pyfunction]
#[pyo3(signature = (
    demos, dm, km, path=None, *, demo=None, skill=false, start=None, goal=None,
    duration=None, scaling="paper", goal_orientation=None, start_orientation=None,
    frame_id=None, sg_window=None, sg_order=None, sg_seconds=None, basis=None,
    skill_mode=None, unusable=None, axis_sd_floor=None, k_rot=None, orientation_gains=None
))]
fn export(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
    dm: f64,
    km: f64,
    path: Option<PathBuf>,
    demo: Option<Py<PyAny>>,
    skill: bool,
    start: Option<(f64, f64, f64)>,
    goal: Option<(f64, f64, f64)>,
    duration: Option<f64>,
    scaling: &str,
    goal_orientation: Option<[f64; 4]>,
    start_orientation: Option<[f64; 4]>,
    frame_id: Option<String>,
    sg_window: Option<usize>,
    sg_order: Option<usize>,
    sg_seconds: Option<f64>,
    basis: Option<usize>,
    skill_mode: Option<String>,
    unusable: Option<String>,
    axis_sd_floor: Option<f64>,
    k_rot: Option<f64>,
    orientation_gains: Option<(f64, f64)>,
) -> PyResult<Py<PyAny>> {
    let kw = TargetKw {
        demo,
        skill,
        start,
        goal,
        duration,
        scaling: scaling.to_owned(),
        start_orientation,
        goal_orientation,
    };
    let model = ModelKw {
        sg_window,
        sg_order,
        sg_seconds,
        basis,
        skill_mode,
        unusable,
        axis_sd_floor,
        k_rot,
        orientation_gains,
    };
    export_doc(py, demos, dm, km, path, &kw, &model, frame_id)
}

/// The defaults every keyword left out takes: the core's, the CLI's.
#[pyfunction]
fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let (grid, diag, load, model) = (
        Grid::default(),
        DiagSettings::default(),
        LoadFlags::default(),
        ModelFlags::default(),
    );
    let d = PyDict::new(py);
    d.set_item("grid", grid.dm.n)?;
    d.set_item("dm_range", (grid.dm.lo, grid.dm.hi))?;
    d.set_item("km_range", (grid.km.lo, grid.km.hi))?;
    d.set_item("k", dmpscope_core::DEFAULT_K)?;
    d.set_item("accept_eps", DEFAULT_EPS)?;
    d.set_item("bootstrap", diag.bootstrap)?;
    d.set_item("bootstrap_seed", diag.seed)?;
    d.set_item("diag_grid", diag.grid_points)?;
    d.set_item("min_extent", load.min_extent)?;
    d.set_item("rest_speed", load.rest_speed)?;
    d.set_item("min_rest", load.min_rest)?;
    d.set_item("min_demo", load.min_demo)?;
    d.set_item("sg_window", model.sg_window)?;
    d.set_item("sg_order", model.sg_order)?;
    d.set_item("basis", model.basis)?;
    d.set_item("skill_mode", model.skill_mode.name())?;
    d.set_item("axis_sd_floor", model.axis_sd_floor)?;
    d.set_item("k_rot", model.k_rot)?;
    Ok(d)
}

/// Panics inside the guard: the test that a Rust panic reaches Python as
/// a `DmpscopeError`, never as a crash.
#[pyfunction]
fn _panic_for_test(message: &str) -> PyResult<()> {
    guarded(|| -> PyResult<()> { panic!("{message}") })
}

/// The extension module `dmpscope._core`; the package `dmpscope`
/// re-exports it.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<Demo>()?;
    m.add_class::<Landscape>()?;
    m.add_class::<Report>()?;
    m.add_class::<Pick>()?;
    m.add_class::<Rollout>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(landscape::landscape, m)?)?;
    m.add_function(wrap_pyfunction!(report::extract, m)?)?;
    m.add_function(wrap_pyfunction!(regen, m)?)?;
    m.add_function(wrap_pyfunction!(export, m)?)?;
    m.add_function(wrap_pyfunction!(defaults, m)?)?;
    m.add_function(wrap_pyfunction!(_panic_for_test, m)?)?;
    m.add("DmpscopeError", py.get_type::<DmpscopeError>())?;
    m.add("DmpscopeWarning", py.get_type::<DmpscopeWarning>())?;
    m.add("DmpscopeNote", py.get_type::<DmpscopeNote>())?;
    Ok(())
}
