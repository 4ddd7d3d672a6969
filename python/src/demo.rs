//! `dmpscope.Demo`: one demonstration, loaded from a recording or built
//! from NumPy arrays (t in seconds, positions N x 3 in metres, orientations
//! N x 4 quaternions `[x, y, z, w]`), checked the way the loaders check a
//! recording: bad arrays are a `ValueError` naming the element.

use std::sync::Arc;

use dmpscope_core::geom::{Quat, Vec3, quat_from_xyzw, xyzw};
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::{RawDemo, TimeSource};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A demonstration: time stamps, positions and (optionally) orientations.
///
/// Build one from arrays with `Demo(t, positions, orientations=None,
/// name=None)`: `t` in seconds (N, strictly increasing), `positions` in
/// metres (N x 3, z up), `orientations` unit quaternions `[x, y, z, w]`
/// (N x 4; normalised when not unit). `dmpscope.load` returns them too;
/// their arrays (`t`, `positions`, `orientations`) are the samples in time
/// order, `t` from the first sample, and build a `Demo` that gives the same
/// numbers.
#[pyclass(module = "dmpscope", frozen)]
pub struct Demo {
    /// The samples as loaded.
    pub(crate) raw: RawDemo,
    /// How it was loaded (the report's loading choices, the export's units
    /// and frame).
    pub(crate) options: Arc<LoadOptions>,
}

impl Demo {
    /// A loaded demo.
    pub fn loaded(raw: RawDemo, options: Arc<LoadOptions>) -> Self {
        Self { raw, options }
    }
}

#[pymethods]
impl Demo {
    /// A demo from arrays (see the class's documentation).
    #[new]
    #[pyo3(signature = (t, positions, orientations=None, name=None))]
    fn new(
        py: Python<'_>,
        t: &Bound<'_, PyAny>,
        positions: &Bound<'_, PyAny>,
        orientations: Option<&Bound<'_, PyAny>>,
        name: Option<String>,
    ) -> PyResult<Self> {
        let (t, t_shape) = floats(py, t, "t")?;
        if t_shape.len() != 1 {
            return Err(PyValueError::new_err(format!(
                "t must be one-dimensional (N,), got shape {t_shape:?}"
            )));
        }
        let n = t.len();
        let (p, p_shape) = floats(py, positions, "positions")?;
        if p_shape != [n, 3] {
            return Err(PyValueError::new_err(format!(
                "positions must have shape (N, 3) = ({n}, 3), one row per time stamp, got \
                 {p_shape:?}"
            )));
        }
        let q = match orientations {
            None => None,
            Some(o) if o.is_none() => None,
            Some(o) => {
                let (q, q_shape) = floats(py, o, "orientations")?;
                if q_shape != [n, 4] {
                    return Err(PyValueError::new_err(format!(
                        "orientations must have shape (N, 4) = ({n}, 4), quaternions [x, y, \
                         z, w], got {q_shape:?}"
                    )));
                }
                Some(q)
            }
        };
        let name = name.unwrap_or_else(|| "demo".to_owned());
        let raw = raw_demo(name, &t, &p, q.as_deref()).map_err(PyValueError::new_err)?;
        Ok(Self {
            raw,
            options: Arc::new(LoadOptions::default()),
        })
    }

    /// The demo's name (`file:topic` for a loaded one).
    #[getter]
    fn name(&self) -> &str {
        &self.raw.name
    }

    /// The file it was loaded from ("" for one built from arrays).
    #[getter]
    fn file(&self) -> &str {
        &self.raw.file
    }

    /// The topic (and key) it was read from ("" for one built from arrays).
    #[getter]
    fn topic(&self) -> &str {
        &self.raw.topic
    }

    /// Seconds from the first sample, in time order (N,).
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, times(&self.raw.sorted()))
    }

    /// Positions, metres, z up (N x 3), in time order.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let flat = self
            .raw
            .sorted()
            .positions
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .collect();
        rows(py, flat, 3)
    }

    /// Orientations, unit quaternions `[x, y, z, w]` (N x 4), or None.
    #[getter]
    fn orientations<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.raw
            .sorted()
            .orientations
            .map(|q| rows(py, q.iter().flat_map(xyzw).collect(), 4))
            .transpose()
    }

    /// The unit its recording was in (`m`, `cm` or `mm`; converted to
    /// metres when loaded).
    #[getter]
    fn units(&self) -> &'static str {
        self.options.units.name()
    }

    /// The frame its positions are in: the fixed frame asked for at
    /// loading, or `world`.
    #[getter]
    fn frame_id(&self) -> String {
        frame_id(&self.options)
    }

    /// Samples in time order (the length of `t`; equal stamps counted
    /// once).
    fn __len__(&self) -> usize {
        self.raw.unique_order().len()
    }

    /// Samples as recorded (equal stamps included), as reports count them.
    #[getter]
    fn n_samples(&self) -> usize {
        self.raw.stamps_ns.len()
    }

    /// Its duration, seconds.
    #[getter]
    fn duration(&self) -> f64 {
        self.raw.duration_s()
    }

    fn __repr__(&self) -> String {
        format!(
            "Demo({:?}, {} samples, {:.3} s{})",
            self.raw.name,
            self.raw.stamps_ns.len(),
            self.raw.duration_s(),
            if self.raw.orientations.is_some() {
                ", with orientations"
            } else {
                ""
            }
        )
    }
}

/// The frame of demos loaded with `options`.
pub fn frame_id(options: &LoadOptions) -> String {
    options
        .fixed_frame
        .clone()
        .unwrap_or_else(|| "world".to_owned())
}

/// `values` (row-major, `columns` per row) as an N x `columns` array.
pub fn rows<'py>(py: Python<'py>, values: Vec<f64>, columns: usize) -> PyResult<Bound<'py, PyAny>> {
    let n = values.len() / columns.max(1);
    Ok(PyArray1::from_vec(py, values)
        .reshape([n, columns])?
        .into_any())
}

/// Any array-like as float64 values in C order, with its shape.
fn floats(
    py: Python<'_>,
    value: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<(Vec<f64>, Vec<usize>)> {
    let numpy = py.import("numpy")?;
    let converted = numpy
        .call_method1("ascontiguousarray", (value, "float64"))
        .map_err(|e| PyValueError::new_err(format!("{what} must be an array of numbers: {e}")))?;
    let array = converted
        .cast::<PyArrayDyn<f64>>()
        .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))?;
    let shape = array.shape().to_vec();
    let values = array.readonly().as_slice()?.to_vec();
    Ok((values, shape))
}

/// Seconds from the first stamp, as the preparation computes them.
pub fn times(raw: &RawDemo) -> Vec<f64> {
    let first = raw.stamps_ns.first().copied().unwrap_or(0);
    raw.stamps_ns
        .iter()
        .map(|s| (s - first) as f64 * 1e-9)
        .collect()
}

/// The largest |t| a stamp in nanoseconds holds, seconds.
const MAX_T_S: f64 = 9.0e9;

/// A demo from checked arrays: `t` (N) seconds, `positions` (3N, row
/// major) metres, `orientations` (4N) `[x, y, z, w]`. The message names
/// the first bad element.
pub fn raw_demo(
    name: String,
    t: &[f64],
    positions: &[f64],
    orientations: Option<&[f64]>,
) -> Result<RawDemo, String> {
    if t.len() < 2 {
        return Err(format!(
            "a demo needs at least 2 samples, got {} (t has shape ({},))",
            t.len(),
            t.len()
        ));
    }
    let stamps_ns = stamps(t)?;
    let positions = points(positions)?;
    let orientations = orientations.map(quaternions).transpose()?;
    Ok(RawDemo {
        file: String::new(),
        topic: String::new(),
        name,
        stamps_ns,
        positions,
        orientations,
        time_source: TimeSource::HeaderStamp,
    })
}

/// Time stamps in nanoseconds, strictly increasing.
fn stamps(t: &[f64]) -> Result<Vec<i64>, String> {
    let mut out: Vec<i64> = Vec::with_capacity(t.len());
    for (i, &v) in t.iter().enumerate() {
        if !v.is_finite() {
            return Err(format!("t[{i}] is {v}: time stamps must be finite"));
        }
        if v.abs() > MAX_T_S {
            return Err(format!(
                "t[{i}] = {v} s is out of range (|t| up to {MAX_T_S:e} s)"
            ));
        }
        let ns = (v * 1e9).round() as i64;
        if let Some(&last) = out.last()
            && ns <= last
        {
            return Err(format!(
                "t must increase strictly (by 1 ns or more): t[{i}] = {v} s is not after t[{}] \
                 = {} s",
                i - 1,
                t[i - 1]
            ));
        }
        out.push(ns);
    }
    Ok(out)
}

/// Rows of three finite numbers.
fn points(values: &[f64]) -> Result<Vec<Vec3>, String> {
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(format!(
            "positions[{}, {}] is {}: positions must be finite",
            i / 3,
            i % 3,
            values[i]
        ));
    }
    Ok(values
        .chunks_exact(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect())
}

/// Rows of four numbers as unit quaternions. A row that is unit to the
/// last bit is kept as it is (the arrays a loaded demo gave build the same
/// demo); any other is normalised; a zero or non-finite one is refused.
fn quaternions(values: &[f64]) -> Result<Vec<Quat>, String> {
    values
        .chunks_exact(4)
        .enumerate()
        .map(|(i, c)| {
            let q = [c[0], c[1], c[2], c[3]];
            let squared: f64 = q.iter().map(|v| v * v).sum();
            if q.iter().all(|v| v.is_finite()) && (squared - 1.0).abs() <= 4.0 * f64::EPSILON {
                let [x, y, z, w] = q;
                return Ok(Quat::new_unchecked(nalgebra::Quaternion::new(w, x, y, z)));
            }
            quat_from_xyzw(q).ok_or_else(|| {
                format!(
                    "orientations[{i}] = {q:?} is not a rotation: a quaternion [x, y, z, w] of \
                     finite, non-zero norm"
                )
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_make_a_demo() {
        let t = [0.0, 0.01, 0.02];
        let p = [0.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.2, 0.0, 0.0];
        let q = [0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let demo = raw_demo("a".into(), &t, &p, Some(&q)).expect("a demo");
        assert_eq!(demo.stamps_ns, vec![0, 10_000_000, 20_000_000]);
        assert_eq!(times(&demo), vec![0.0, 0.01, 0.02]);
        let first = demo.orientations.as_ref().map(|o| xyzw(&o[0]));
        assert_eq!(first, Some([0.0, 0.0, 0.0, 1.0]));
    }

    #[test]
    fn bad_arrays_are_named() {
        let p = [0.0; 9];
        let err = |t: &[f64], p: &[f64]| raw_demo("a".into(), t, p, None).err();
        assert!(err(&[0.0, f64::NAN, 1.0], &p).is_some_and(|e| e.contains("t[1]")));
        assert!(err(&[0.0, 0.5, 0.5], &p).is_some_and(|e| e.contains("increase strictly")));
        assert!(err(&[0.0], &p[..3]).is_some_and(|e| e.contains("at least 2")));
        let mut bad = p;
        bad[4] = f64::INFINITY;
        assert!(err(&[0.0, 1.0, 2.0], &bad).is_some_and(|e| e.contains("positions[1, 1]")));
        let q = [0.0; 12];
        let got = raw_demo("a".into(), &[0.0, 1.0, 2.0], &p, Some(&q)).err();
        assert!(got.is_some_and(|e| e.contains("orientations[0]")));
    }

    #[test]
    fn loaded_times_round_trip_to_the_same_stamps() {
        let stamps: Vec<i64> = (0..500)
            .map(|i| 1_700_000_000_000_000_000 + i * 4_166_667)
            .collect();
        let raw = RawDemo {
            name: "a".into(),
            file: String::new(),
            topic: String::new(),
            stamps_ns: stamps.clone(),
            positions: vec![Vec3::zeros(); stamps.len()],
            orientations: None,
            time_source: TimeSource::LogTime,
        };
        let again = stamps_of(&times(&raw));
        let first = stamps[0];
        let relative: Vec<i64> = stamps.iter().map(|s| s - first).collect();
        assert_eq!(again, relative);
    }

    fn stamps_of(t: &[f64]) -> Vec<i64> {
        stamps(t).unwrap_or_default()
    }
}
