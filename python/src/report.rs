//! `dmpscope.extract`: the gains minimising J, whether the demos determine
//! them (the diagnostics), what the data allow, the pick for the robot and
//! Table I, made by the core's [`extract_report`] as `dmpscope extract`
//! makes them: `Report.to_dict()` is its `--json` output and
//! `Report.text()` its text.

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use dmpscope_core::Report as CoreReport;
use dmpscope_core::extract::allowed::{Pick as CorePick, PickRule, PickSettings};
use dmpscope_core::extract::diagnostics::DiagSettings;
use dmpscope_core::report::extraction::{ExtractSettings, extract_report};
use pyo3::prelude::*;

use crate::errors::{Watch, guarded, invalid, to_py, warn};
use crate::landscape::{GridKw, Landscape, check_k, compute, to_py_value};
use crate::model::{ModelKw, build};

/// The gains picked for the robot in the acceptable region by a named rule
/// (`optimum`, `compliant`, `critical`, `smooth`), with what a robot needs
/// of them. `str(pick)` is the line `dmpscope extract` prints.
#[pyclass(module = "dmpscope", frozen)]
pub struct Pick {
    pick: CorePick,
}

#[pymethods]
impl Pick {
    /// The rule that chose it.
    #[getter]
    fn rule(&self) -> &'static str {
        self.pick.rule.name()
    }

    /// D/M, per unit time.
    #[getter]
    fn dm(&self) -> f64 {
        self.pick.dm
    }

    /// K/M, per unit time squared.
    #[getter]
    fn km(&self) -> f64 {
        self.pick.km
    }

    /// Damping ratio.
    #[getter]
    fn zeta(&self) -> f64 {
        self.pick.zeta
    }

    /// J there.
    #[getter]
    fn j(&self) -> f64 {
        self.pick.j
    }

    /// Why this rule and this point, in words.
    #[getter]
    fn why(&self) -> &str {
        &self.pick.why
    }

    /// Whether it lies on the box's edge in its rule's direction.
    #[getter]
    fn on_edge(&self) -> bool {
        self.pick.on_edge
    }

    /// Every field, as in `to_dict()["pick"]` of the report.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py_value(py, &self.pick)
    }

    fn __str__(&self) -> String {
        self.pick.headline()
    }

    fn __repr__(&self) -> String {
        format!(
            "Pick(rule={:?}, dm={}, km={}, zeta={})",
            self.pick.rule.name(),
            self.pick.dm,
            self.pick.km,
            self.pick.zeta
        )
    }
}

/// An extraction's report (`dmpscope extract`): attributes `k`, `demos`,
/// `optimum`, `table` (Table I), `diagnostics`, `diagnostics_about`,
/// `constrained`, `loading`, `verdict`, `acceptable`, `pick`,
/// `pick_failure`, `optimum_robot`; `to_dict()` is `extract --json` and
/// `text()` (or `str(report)`) its text. The dictionaries hold JSON's
/// values (NaN as None).
#[pyclass(module = "dmpscope", frozen)]
pub struct Report {
    report: CoreReport,
    /// The landscape the extraction was made on.
    #[pyo3(get)]
    landscape: Py<Landscape>,
}

impl Report {
    /// One key of the JSON document.
    fn key<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        self.to_dict(py)?.get_item(key)
    }
}

#[pymethods]
impl Report {
    /// `dmpscope extract --json` as Python objects.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py_value(py, &self.report)
    }

    /// `dmpscope extract`'s text.
    fn text(&self) -> String {
        self.report.extract_text()
    }

    fn __str__(&self) -> String {
        self.report.extract_text()
    }

    fn __repr__(&self) -> String {
        let pick = self.report.allowed.as_ref().and_then(|a| a.pick.as_ref());
        format!(
            "Report({} demos, {})",
            self.report.demos.len(),
            pick.map_or_else(|| "no pick".to_owned(), CorePick::headline)
        )
    }

    /// J's weight k.
    #[getter]
    fn k(&self) -> f64 {
        self.report.k
    }

    /// The demos: `name`, `n_samples`, `duration_s`.
    #[getter]
    fn demos<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "demos")
    }

    /// J's refined optimum (`dm`, `km`, `zeta`, `j`, `s`, `d_sum`,
    /// `on_edge`, `edge`, ...).
    #[getter]
    fn optimum<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "optimum")
    }

    /// Table I: one dict per row (`Extracted`, the pick, the paper's gains).
    #[getter]
    fn table<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "table")
    }

    /// The diagnostics (depth, flat, balance, shares, leave-one-out,
    /// bootstrap), or None when skipped.
    #[getter]
    fn diagnostics<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.report
            .diagnostics
            .as_ref()
            .map(|d| to_py_value(py, d))
            .transpose()
    }

    /// How the diagnostics were made (their grid, resamples, notes).
    #[getter]
    fn diagnostics_about<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.report
            .diagnostics_about
            .as_ref()
            .map(|d| to_py_value(py, d))
            .transpose()
    }

    /// The optimum under the a_peak limit, when one was given.
    #[getter]
    fn constrained<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.report
            .constrained
            .as_ref()
            .map(|c| to_py_value(py, c))
            .transpose()
    }

    /// How the recordings were read and prepared.
    #[getter]
    fn loading<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.report
            .loading
            .as_ref()
            .map(|l| to_py_value(py, l))
            .transpose()
    }

    /// What the demos determine: `skill_mode`, `j_depth`, `j_flat`,
    /// `e_depth`, `e_flat`, `e_range`, `e_excess`, `e_note`.
    #[getter]
    fn verdict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let all = self.to_dict(py)?;
        let out = pyo3::types::PyDict::new(py);
        for key in [
            "skill_mode",
            "j_depth",
            "j_flat",
            "e_depth",
            "e_flat",
            "e_range",
            "e_excess",
            "e_note",
        ] {
            if let Ok(v) = all.get_item(key) {
                out.set_item(key, v)?;
            }
        }
        Ok(out.into_any())
    }

    /// The acceptable region: `eps`, `fraction`, `dm`, `km`, `zeta` ranges.
    #[getter]
    fn acceptable<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "acceptable")
    }

    /// The picked gains (a `Pick`), or None when the rule found none.
    #[getter]
    fn pick(&self) -> Option<Pick> {
        let allowed = self.report.allowed.as_ref()?;
        allowed.pick.clone().map(|pick| Pick { pick })
    }

    /// Why there is no pick, or None.
    #[getter]
    fn pick_failure(&self) -> Option<String> {
        self.report.allowed.as_ref()?.pick_failure.clone()
    }

    /// The optimum's gains in real time at the demos' mean duration.
    #[getter]
    fn optimum_robot<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "optimum_robot")
    }
}

/// What `extract` asks besides the grid and the model.
pub struct ExtractKw {
    /// The pick's rule by name.
    pub pick: Option<String>,
    /// The acceptable region's eps.
    pub accept_eps: f64,
    /// Whether to run the diagnostics.
    pub diagnostics: bool,
    /// Bootstrap resamples.
    pub bootstrap: usize,
    /// The bootstrap's seed.
    pub bootstrap_seed: u64,
    /// Points per axis of the resampled extractions' grid.
    pub diag_grid: usize,
    /// An a_peak limit, m/s^2.
    pub a_peak_limit: Option<f64>,
    /// A settling limit, unit times.
    pub settle_within: Option<f64>,
}

impl ExtractKw {
    /// The core's settings for `k`.
    pub fn settings(&self, k: f64) -> Result<ExtractSettings, String> {
        let rule = self
            .pick
            .as_deref()
            .map(str::parse::<PickRule>)
            .transpose()?;
        Ok(ExtractSettings {
            k,
            loading: None,
            diagnostics: self.diagnostics.then_some(DiagSettings {
                grid_points: self.diag_grid,
                bootstrap: self.bootstrap,
                seed: self.bootstrap_seed,
            }),
            pick: PickSettings {
                rule,
                eps: self.accept_eps,
                a_peak_limit: self.a_peak_limit,
                settle_within: self.settle_within,
            },
        })
    }
}

/// The landscape `demos` names: itself when it is one (no other grid or
/// model keyword may be given then), else computed.
pub fn landscape_of(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
    grid: &GridKw,
    kw: &ModelKw,
    progress: Option<&Py<PyAny>>,
) -> PyResult<Py<Landscape>> {
    if let Ok(land) = demos.cast::<Landscape>() {
        if !grid.is_default() || !kw.is_default() {
            return Err(invalid(
                "a Landscape was given: it already has its grid, k and model settings; pass the \
                 demos instead to change them",
            ));
        }
        return Ok(land.clone().unbind());
    }
    check_k(grid.k())?;
    let inputs = Arc::new(build(py, demos, kw)?);
    Py::new(py, compute(py, inputs, grid, progress)?)
}

/// The report of `demos` or of a computed `Landscape` (see the stub).
pub fn extract_with(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
    grid: &GridKw,
    kw: &ModelKw,
    extract: &ExtractKw,
    progress: Option<&Py<PyAny>>,
) -> PyResult<Report> {
    let probe = extract.settings(grid.k()).map_err(invalid)?;
    probe.check().map_err(to_py)?;
    let landscape = landscape_of(py, demos, grid, kw, progress)?;
    let land = landscape.get();
    let mut settings = extract.settings(land.k).map_err(invalid)?;
    settings.loading = Some(land.inputs.loading());
    let cancel = AtomicBool::new(false);
    let mut watch = Watch::new(&cancel, progress);
    let mut notices = Vec::new();
    let report = py.detach(|| {
        guarded(|| {
            extract_report(
                &land.inputs.model,
                &land.land,
                &land.optimum,
                &settings,
                &mut |job| job.run_cancellable(&cancel, &mut |d, t| watch.tick(d, t)),
                &mut |notice| notices.push(notice),
            )
            .map_err(|e| watch.error(e))
        })
    })?;
    warn(py, &notices)?;
    Ok(Report { report, landscape })
}

/// The extraction of `demos` (see the stub for the keywords).
#[pyfunction]
#[pyo3(signature = (
    demos, *, pick=None, accept_eps=dmpscope_core::extract::allowed::DEFAULT_EPS,
    diagnostics=true, bootstrap=DiagSettings::default().bootstrap,
    bootstrap_seed=DiagSettings::default().seed, diag_grid=DiagSettings::default().grid_points,
    a_peak_limit=None, settle_within=None, grid=None, dm_range=None, km_range=None,
    linear=false, k=None, sg_window=None, sg_order=None, sg_seconds=None, basis=None,
    skill_mode=None, unusable=None, axis_sd_floor=None, k_rot=None, orientation_gains=None,
    progress=None
))]
pub fn extract(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
    pick: Option<String>,
    accept_eps: f64,
    diagnostics: bool,
    bootstrap: usize,
    bootstrap_seed: u64,
    diag_grid: usize,
    a_peak_limit: Option<f64>,
    settle_within: Option<f64>,
    grid: Option<usize>,
    dm_range: Option<(f64, f64)>,
    km_range: Option<(f64, f64)>,
    linear: bool,
    k: Option<f64>,
    sg_window: Option<usize>,
    sg_order: Option<usize>,
    sg_seconds: Option<f64>,
    basis: Option<usize>,
    skill_mode: Option<String>,
    unusable: Option<String>,
    axis_sd_floor: Option<f64>,
    k_rot: Option<f64>,
    orientation_gains: Option<(f64, f64)>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Report> {
    let grid = GridKw {
        grid,
        dm_range,
        km_range,
        linear,
        k,
    };
    let kw = ModelKw {
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
    let extract = ExtractKw {
        pick,
        accept_eps,
        diagnostics,
        bootstrap,
        bootstrap_seed,
        diag_grid,
        a_peak_limit,
        settle_within,
    };
    extract_with(py, demos, &grid, &kw, &extract, progress.as_ref())
}
