//! From the demos a Python caller hands over to the core's model, as the
//! CLI builds it from its FILES: the model's keywords
//! ([`ModelKw`] -> [`ModelFlags`]), the demos' names made unique, the
//! unusable ones left out with a warning, and what the reports need of
//! loading (units, frame, the loading choices).

use std::sync::Arc;

use dmpscope_core::arrange::streams::unique_names;
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::pipeline::{ModelFlags, Unusable};
use dmpscope_core::report::summary::LoadingChoices;
use dmpscope_core::{Model, RawDemo, SkillMode};
use pyo3::prelude::*;
use pyo3::types::PyList;

use crate::demo::Demo;
use crate::errors::{guarded, invalid, to_py, warn};

/// The model's keywords (`None`: the core's default, as the CLI's).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModelKw {
    /// Savitzky-Golay window, samples (odd).
    pub sg_window: Option<usize>,
    /// Savitzky-Golay polynomial order.
    pub sg_order: Option<usize>,
    /// The window as a duration, seconds.
    pub sg_seconds: Option<f64>,
    /// DMP basis functions.
    pub basis: Option<usize>,
    /// `frame`, `per-axis` or `none`.
    pub skill_mode: Option<String>,
    /// `skip` or `fail`.
    pub unusable: Option<String>,
    /// Floor of each axis's SD in S's standardisation.
    pub axis_sd_floor: Option<f64>,
    /// The weight of the orientation error in J.
    pub k_rot: Option<f64>,
    /// Separate orientation gains `(D/M, K/M)`.
    pub orientation_gains: Option<(f64, f64)>,
}

impl ModelKw {
    /// Whether every keyword is left at its default.
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// The core's flags; an unknown name is an error in the CLI's words.
    pub fn flags(&self) -> Result<ModelFlags, String> {
        let d = ModelFlags::default();
        let unusable = match self.unusable.as_deref() {
            None => d.unusable,
            Some("skip") => Unusable::Skip,
            Some("fail") => Unusable::Fail,
            Some(other) => return Err(format!("unknown unusable {other:?}: skip or fail")),
        };
        let skill_mode = match self.skill_mode.as_deref() {
            None => d.skill_mode,
            Some(name) => name.parse::<SkillMode>()?,
        };
        Ok(ModelFlags {
            sg_window: self.sg_window.unwrap_or(d.sg_window),
            sg_order: self.sg_order.unwrap_or(d.sg_order),
            basis: self.basis.unwrap_or(d.basis),
            axis_sd_floor: self.axis_sd_floor.unwrap_or(d.axis_sd_floor),
            skill_mode,
            unusable,
            sg_seconds: self.sg_seconds.or(d.sg_seconds),
            k_rot: self.k_rot.unwrap_or(d.k_rot),
            orientation_gains: self
                .orientation_gains
                .map(|(a, b)| [a, b])
                .or(d.orientation_gains),
        })
    }
}

/// A model and what the reports and exports need of its demos.
pub struct Inputs {
    /// The model of the usable demos.
    pub model: Arc<Model>,
    /// For each of the model's demos, its index in the list handed over.
    pub used: Vec<usize>,
    /// The flags it was built with.
    pub flags: ModelFlags,
    /// How the first demo was loaded (units, frame, grouping).
    pub options: Arc<LoadOptions>,
}

impl Inputs {
    /// The loading choices a report states.
    pub fn loading(&self) -> LoadingChoices {
        LoadingChoices::of(&self.options, &self.flags.prep())
    }

    /// The model's index of demo `i` of the list handed over.
    pub fn model_index(&self, i: usize) -> Option<usize> {
        self.used.iter().position(|&u| u == i)
    }
}

/// The demos of `value`: a sequence of `Demo` (or one).
pub fn demos_of(value: &Bound<'_, PyAny>) -> PyResult<Vec<(RawDemo, Arc<LoadOptions>)>> {
    if let Ok(one) = value.cast::<Demo>() {
        let d = one.get();
        return Ok(vec![(d.raw.clone(), Arc::clone(&d.options))]);
    }
    let items: Vec<Bound<'_, PyAny>> = match value.cast::<PyList>() {
        Ok(list) => list.iter().collect(),
        Err(_) => value
            .try_iter()
            .map_err(|_| type_error(value))?
            .collect::<PyResult<_>>()?,
    };
    items
        .iter()
        .map(|item| {
            let d = item.cast::<Demo>().map_err(|_| type_error(item))?.get();
            Ok((d.raw.clone(), Arc::clone(&d.options)))
        })
        .collect()
}

fn type_error(value: &Bound<'_, PyAny>) -> PyErr {
    let name = value
        .get_type()
        .name()
        .map_or_else(|_| "?".to_owned(), |n| n.to_string());
    pyo3::exceptions::PyTypeError::new_err(format!(
        "expected a list of dmpscope.Demo (from dmpscope.load or dmpscope.Demo(t, positions)), \
         got {name}"
    ))
}

/// The model of `demos` built as the CLI builds it (GIL released), its
/// notices issued as warnings.
pub fn build(py: Python<'_>, demos: &Bound<'_, PyAny>, kw: &ModelKw) -> PyResult<Inputs> {
    let flags = kw.flags().map_err(invalid)?;
    let given = demos_of(demos)?;
    let options = given
        .first()
        .map_or_else(|| Arc::new(LoadOptions::default()), |(_, o)| Arc::clone(o));
    let mut raw: Vec<RawDemo> = given.into_iter().map(|(r, _)| r).collect();
    unique_names(&mut raw);
    let built = py.detach(|| guarded(|| flags.build(&raw).map_err(to_py)))?;
    warn(py, &built.notices)?;
    Ok(Inputs {
        model: Arc::new(built.model),
        used: built.used,
        flags,
        options,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_keywords_are_the_cli_defaults() {
        assert_eq!(ModelKw::default().flags(), Ok(ModelFlags::default()));
        assert!(ModelKw::default().is_default());
    }

    #[test]
    fn names_are_checked() {
        let kw = ModelKw {
            skill_mode: Some("per-axis".into()),
            unusable: Some("fail".into()),
            ..ModelKw::default()
        };
        let flags = kw.flags().expect("valid names");
        assert_eq!(flags.skill_mode, SkillMode::PerAxis);
        assert_eq!(flags.unusable, Unusable::Fail);
        let bad = ModelKw {
            skill_mode: Some("paper".into()),
            ..ModelKw::default()
        };
        assert!(
            bad.flags()
                .is_err_and(|e| e.contains("frame, per-axis or none"))
        );
    }
}
