//! What the session's stages hold and what each is computed for: the
//! demos list, the stages' typed keys (a stage is redone only when its
//! key changes; `f64`s by their bits), their values, and how many times
//! each stage ran.

use std::sync::{Arc, OnceLock};

use dmpscope_core::extract::allowed::Allowed;
use dmpscope_core::extract::diagnostics::DiagSettings;
use dmpscope_core::extract::optimum::Refined;
use dmpscope_core::fit::orientation::OrientationRollout;
use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::kernels::similarity::Standardised;
use dmpscope_core::landscape::grid::Grid;
use dmpscope_core::{DemoInfo, Extraction, Model, PointEval, PrepSettings, RawDemo, Rollout};

/// A demo in the demos list.
#[derive(Clone, Debug, PartialEq)]
pub struct DemoEntry {
    /// The source it came from (an index into `Session::sources`).
    pub source: usize,
    /// The demo as loaded and grouped.
    pub raw: RawDemo,
    /// Its summary, computed once.
    pub info: DemoInfo,
    /// Whether it takes part in the model.
    pub included: bool,
}

/// How many times each stage was computed (the invalidation tests read it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StageRuns {
    /// Source loads started.
    pub loads: usize,
    /// Sources regrouped into demos.
    pub groupings: usize,
    /// Models built.
    pub models: usize,
    /// Landscapes started.
    pub landscapes: usize,
    /// Extractions started.
    pub extractions: usize,
    /// Diagnostics started.
    pub diagnostics: usize,
    /// The paper's gains evaluated (once per model: their rows follow
    /// any k).
    pub tables: usize,
    /// Operating points evaluated, with every demo's path (once per model
    /// and point).
    pub points: usize,
    /// Generalised runs computed (once per model, point and target).
    pub generalised: usize,
}

/// What the model is built from.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ModelKey {
    pub(crate) demos: u64,
    pub(crate) included: Vec<bool>,
    pub(crate) prep: PrepSettings,
    pub(crate) dmp: DmpSettings,
}

/// A model built, for each of its demos the index in the demos list, and
/// what the build had to say (moved to the messages when it arrives).
pub(crate) struct Built {
    pub(crate) model: Arc<Model>,
    pub(crate) used: Vec<usize>,
    pub(crate) notices: Vec<dmpscope_core::Notice>,
}

/// The landscape: the model and the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LandscapeKey {
    pub(crate) model: u64,
    pub(crate) grid: Grid,
}

/// The extraction: the landscape computed and k; `f64`s are compared by
/// their bits: a key changes when a value does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ExtractionKey {
    pub(crate) landscape: u64,
    pub(crate) k: u64,
}

/// The operating point: `f64`s compared by their bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PointKey {
    pub(crate) model: u64,
    pub(crate) dm: u64,
    pub(crate) km: u64,
}

/// The diagnostics: the extraction they are of and how they are made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct DiagKey {
    pub(crate) extraction: ExtractionKey,
    pub(crate) settings: DiagSettings,
}

/// The constrained optimum: the extraction's landscape and k, and the
/// a_peak limit's bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ConstrainedKey {
    pub(crate) extraction: ExtractionKey,
    pub(crate) limit: u64,
}

/// An RL request: the model it trains on and which request (a new one
/// each time the user starts training).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct RlKey {
    pub(crate) model: u64,
    pub(crate) request: u64,
}

/// The operating point evaluated.
pub(crate) struct PointValue {
    pub(crate) eval: PointEval,
    pub(crate) paths: Vec<Rollout>,
    /// Every demo's regenerated orientation (`None` without one).
    pub(crate) turns: Vec<Option<OrientationRollout>>,
    /// Every demo's standardised forcing term and sigma_f there, and each
    /// demo's share of S (`None` with one demo): computed when first asked
    /// for ([`Session::forcing_terms`]), as the views that show them are
    /// mostly closed while the point is dragged.
    pub(crate) standardised: OnceLock<(Standardised, Option<Vec<f64>>)>,
}

/// What the verdict and the pick are computed for (`f64`s by their bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct AllowedKey {
    pub(crate) extraction: ExtractionKey,
    pub(crate) rule: Option<dmpscope_core::extract::allowed::PickRule>,
    pub(crate) eps: u64,
    pub(crate) limit: Option<u64>,
    pub(crate) settle: Option<u64>,
}

/// The verdict with the pick's evaluation (its row of Table I).
pub struct AllowedView {
    /// The region, E's verdict and the pick.
    pub allowed: Allowed,
    /// Every demo's numbers at the pick.
    pub pick_eval: Option<PointEval>,
}

/// The extracted gains of an extraction stage's value.
pub(crate) fn found(value: Option<&dmpscope_core::Result<Extraction>>) -> Option<&Extraction> {
    value.and_then(|r| r.as_ref().ok())
}

/// The constrained optimum of its stage's value.
pub(crate) fn within(value: Option<&Option<Refined>>) -> Option<Option<&Refined>> {
    value.map(Option::as_ref)
}
