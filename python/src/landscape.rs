//! `dmpscope.landscape`: sum d, S, J, a_peak, E and d_rot over a grid of
//! gain pairs, and J's optimum, computed by the core as `dmpscope
//! landscape` computes them (all cores, the GIL released, Ctrl+C and a
//! `progress` callback between tiles).

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use dmpscope_core::extract::optimum::map_and_extract;
use dmpscope_core::landscape::grid::{Axis, AxisScale, Grid};
use dmpscope_core::landscape::quantity::Quantity;
use dmpscope_core::report::extraction::landscape_document;
use dmpscope_core::report::summary::Optimum;
use dmpscope_core::{Extraction, Landscape as CoreLandscape};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

use crate::errors::{Watch, guarded, invalid, warn};
use crate::model::{Inputs, ModelKw, build};

/// The grid's keywords (`None`: the CLI's defaults).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GridKw {
    /// Points per axis.
    pub grid: Option<usize>,
    /// D/M range.
    pub dm_range: Option<(f64, f64)>,
    /// K/M range.
    pub km_range: Option<(f64, f64)>,
    /// Even spacing instead of geometric.
    pub linear: bool,
    /// The weight of sum d in J.
    pub k: Option<f64>,
}

impl GridKw {
    /// Whether every keyword is left at its default.
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// The grid, as the CLI's `--grid`, `--dm-range`, `--km-range`,
    /// `--linear` make it.
    pub fn grid(&self) -> Grid {
        let d = Grid::default();
        let scale = if self.linear {
            AxisScale::Linear
        } else {
            AxisScale::Log
        };
        let n = self.grid.unwrap_or(d.dm.n);
        let axis = |range: Option<(f64, f64)>, default: Axis| {
            let (lo, hi) = range.unwrap_or((default.lo, default.hi));
            Axis { lo, hi, n, scale }
        };
        Grid {
            dm: axis(self.dm_range, d.dm),
            km: axis(self.km_range, d.km),
        }
    }

    /// J's weight.
    pub fn k(&self) -> f64 {
        self.k.unwrap_or(dmpscope_core::DEFAULT_K)
    }
}

/// A computed landscape: every quantity over the gain grid as NumPy arrays
/// of shape `(len(dm), len(km))` (the CLI's rows over D/M), and J's
/// optimum.
///
/// Quantities: `d_sum` (metres), `s` (dimensionless), `j` (`s + k d_sum`,
/// plus `k_rot d_rot_sum` when asked), `a_peak` (the largest of any demo,
/// m/s^2 of the unit-time motion), `e_sum` (the skill error, metres; NaN
/// without one), `d_rot_sum` (degrees; NaN without orientations). The
/// arrays are read-only. `to_dict()` is `dmpscope landscape`'s JSON.
#[pyclass(module = "dmpscope", frozen)]
pub struct Landscape {
    pub(crate) inputs: Arc<Inputs>,
    pub(crate) land: Arc<CoreLandscape>,
    pub(crate) optimum: Extraction,
    /// J's weight k of sum d.
    #[pyo3(get)]
    pub(crate) k: f64,
    /// The D/M values (len n_dm).
    #[pyo3(get)]
    dm: Py<PyAny>,
    /// The K/M values (len n_km).
    #[pyo3(get)]
    km: Py<PyAny>,
    /// Summed human-likeness error, metres.
    #[pyo3(get)]
    d_sum: Py<PyAny>,
    /// Cross-demo similarity S.
    #[pyo3(get)]
    s: Py<PyAny>,
    /// J = S + k sum d.
    #[pyo3(get)]
    j: Py<PyAny>,
    /// Largest peak acceleration of any demo, m/s^2 of unit time.
    #[pyo3(get)]
    a_peak: Py<PyAny>,
    /// Skill error E, metres.
    #[pyo3(get)]
    e_sum: Py<PyAny>,
    /// Summed orientation error, degrees.
    #[pyo3(get)]
    d_rot_sum: Py<PyAny>,
}

impl Landscape {
    /// The Python object of a computed landscape.
    pub fn new(
        py: Python<'_>,
        inputs: Arc<Inputs>,
        land: CoreLandscape,
        optimum: Extraction,
        k: f64,
    ) -> PyResult<Self> {
        let shape = [land.grid.dm.n, land.grid.km.n];
        let grid = |values: &[f64]| -> PyResult<Py<PyAny>> {
            let array = PyArray1::from_vec(py, values.to_vec()).reshape(shape)?;
            read_only(array.as_any())?;
            Ok(array.into_any().unbind())
        };
        let axis = |values: &[f64]| -> PyResult<Py<PyAny>> {
            let array = PyArray1::from_vec(py, values.to_vec());
            read_only(array.as_any())?;
            Ok(array.into_any().unbind())
        };
        Ok(Self {
            dm: axis(&land.dm)?,
            km: axis(&land.km)?,
            d_sum: grid(land.values(Quantity::DSum))?,
            s: grid(land.values(Quantity::S))?,
            j: grid(&land.j(k))?,
            a_peak: grid(land.values(Quantity::APeak))?,
            e_sum: grid(land.values(Quantity::ESum))?,
            d_rot_sum: grid(land.values(Quantity::DRotSum))?,
            inputs,
            land: Arc::new(land),
            optimum,
            k,
        })
    }
}

/// Marks a NumPy array read-only.
fn read_only(array: &Bound<'_, PyAny>) -> PyResult<()> {
    array.getattr("flags")?.setattr("writeable", false)
}

/// JSON text as Python objects (`json.loads`): NaN is `None`, as in the
/// CLI's JSON.
pub fn json_to_py<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// A serde value as Python objects, through the same JSON the CLI prints.
pub fn to_py_value<'py, T: serde::Serialize>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| invalid(e.to_string()))?;
    json_to_py(py, &text)
}

#[pymethods]
impl Landscape {
    /// J's optimum refined by Nelder-Mead: `dm`, `km`, `zeta`, `j`, `s`,
    /// `d_sum`, `on_edge`, `edge`, `grid_min_j`, `iterations`, `converged`.
    #[getter]
    fn optimum<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py_value(py, &Optimum::from(&self.optimum))
    }

    /// The demos of the model, by name, in its order.
    #[getter]
    fn demos(&self) -> Vec<String> {
        self.inputs
            .model
            .demos()
            .iter()
            .map(|d| d.name.clone())
            .collect()
    }

    /// The grid: `{"dm": {"lo", "hi", "n", "scale"}, "km": {...}}`.
    #[getter]
    fn grid<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py_value(py, &self.land.grid)
    }

    /// `dmpscope landscape`'s JSON document as Python objects (NaN as None).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let doc = landscape_document(&self.inputs.model, &self.land, &self.optimum, self.k)
            .map_err(|e| invalid(e.to_string()))?;
        to_py_value(py, &doc)
    }

    fn __repr__(&self) -> String {
        let x = &self.optimum.eval;
        format!(
            "Landscape({} x {} grid, {} demos, optimum D/M {:.4}, K/M {:.4}, J {:.6})",
            self.land.grid.dm.n,
            self.land.grid.km.n,
            self.inputs.model.demos().len(),
            x.dm,
            x.km,
            self.optimum.j
        )
    }
}

/// Computes the landscape of `inputs` over `grid` and its optimum (GIL
/// released; signals and `progress` between tiles), the edge warning
/// issued.
pub fn compute(
    py: Python<'_>,
    inputs: Arc<Inputs>,
    grid: &GridKw,
    progress: Option<&Py<PyAny>>,
) -> PyResult<Landscape> {
    let (g, k) = (grid.grid(), grid.k());
    let cancel = AtomicBool::new(false);
    let mut watch = Watch::new(&cancel, progress);
    let model = &inputs.model;
    let (land, optimum, notices) = py.detach(|| {
        guarded(|| {
            g.validate().map_err(|e| watch.error(e))?;
            map_and_extract(model, g, k, &cancel, &mut |done, total| {
                watch.tick(done, total);
            })
            .map_err(|e| watch.error(e))
        })
    })?;
    warn(py, &notices)?;
    Landscape::new(py, inputs, land, optimum, k)
}

/// The landscape of `demos` (see the stub for the keywords).
#[pyfunction]
#[pyo3(signature = (
    demos, *, grid=None, dm_range=None, km_range=None, linear=false, k=None,
    sg_window=None, sg_order=None, sg_seconds=None, basis=None, skill_mode=None,
    unusable=None, axis_sd_floor=None, k_rot=None, orientation_gains=None, progress=None
))]
pub fn landscape(
    py: Python<'_>,
    demos: &Bound<'_, PyAny>,
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
) -> PyResult<Landscape> {
    let grid = GridKw {
        grid,
        dm_range,
        km_range,
        linear,
        k,
    };
    check_k(grid.k())?;
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
    let inputs = Arc::new(build(py, demos, &kw)?);
    compute(py, inputs, &grid, progress.as_ref())
}

/// Checks k before anything is computed.
pub fn check_k(k: f64) -> PyResult<()> {
    dmpscope_core::extract::optimum::check_k(k).map_err(crate::errors::to_py)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_keywords_are_the_cli_grid() {
        assert_eq!(GridKw::default().grid(), Grid::default());
        assert_eq!(GridKw::default().k(), dmpscope_core::DEFAULT_K);
        let linear = GridKw {
            grid: Some(16),
            dm_range: Some((1.0, 50.0)),
            linear: true,
            ..GridKw::default()
        }
        .grid();
        assert_eq!((linear.dm.n, linear.dm.lo, linear.dm.hi), (16, 1.0, 50.0));
        assert_eq!(linear.km.scale, AxisScale::Linear);
        assert_eq!((linear.km.lo, linear.km.hi), (0.1, 1000.0));
    }
}
