//! The generalisation stage (method.md section 10): the selected demo or
//! the skill of all demos, at the operating point's gains, run at a new
//! start, goal and duration. Recomputed when the model, the operating point
//! or the target changes (a drag of the goal changes the target every
//! frame: one primitive and its rollout, well under a millisecond).

use std::sync::Arc;

use dmpscope_core::geom::Vec3;
use dmpscope_core::{Generalised, Model, Primitive, Scaling, Skill, Target};

use crate::stage::Stage;

/// What is generalised.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TargetSource {
    /// A model demo (its index).
    Demo(usize),
    /// The skill of all the model's demos.
    Skill,
}

/// The user's generalisation: what, where to and how.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneraliseSpec {
    /// The demo or the skill.
    pub source: TargetSource,
    /// New start, goal (absolute metres) and duration; `None` keeps the
    /// source's own; the scaling mode.
    pub target: Target,
}

impl GeneraliseSpec {
    /// Demo `i` at its own target, per-axis scaling.
    pub fn demo(i: usize) -> Self {
        Self {
            source: TargetSource::Demo(i),
            target: Target::default(),
        }
    }

    /// The same source and scaling at the source's own target (Reset).
    pub fn reset(&self) -> Self {
        Self {
            source: self.source,
            target: Target {
                scaling: self.target.scaling,
                ..Target::default()
            },
        }
    }
}

/// A generalised run, as the views show it.
#[derive(Clone, Debug)]
pub struct TargetView {
    /// The primitive run (its own start, goal and duration are the
    /// defaults of the target); shared with the stage, not copied per run.
    pub primitive: Arc<Primitive>,
    /// The run at the target.
    pub out: Generalised,
    /// Skills: the forcing terms' per-time SD.
    pub forcing_sd: Option<Arc<Vec<Vec3>>>,
}

/// The key the stage was computed for (f64s by their bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct TargetKey {
    model: u64,
    dm: u64,
    km: u64,
    source: TargetSource,
    start: Option<[u64; 3]>,
    goal: Option<[u64; 3]>,
    start_orientation: Option<[u64; 4]>,
    goal_orientation: Option<[u64; 4]>,
    duration: Option<u64>,
    scaling: Scaling,
}

impl TargetKey {
    pub(crate) fn new(model: u64, (dm, km): (f64, f64), spec: &GeneraliseSpec) -> Self {
        let bits = |v: Vec3| [v.x, v.y, v.z].map(f64::to_bits);
        Self {
            model,
            dm: dm.to_bits(),
            km: km.to_bits(),
            source: spec.source,
            start: spec.target.start.map(bits),
            goal: spec.target.goal.map(bits),
            start_orientation: spec.target.start_orientation.map(|q| q.map(f64::to_bits)),
            goal_orientation: spec.target.goal_orientation.map(|q| q.map(f64::to_bits)),
            duration: spec.target.duration_s.map(f64::to_bits),
            scaling: spec.target.scaling,
        }
    }
}

/// What the primitive depends on: a drag of the goal keeps it and only
/// rolls it out again.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PrimitiveKey {
    model: u64,
    dm: u64,
    km: u64,
    source: TargetSource,
    /// A skill's members are mapped by the scaling mode; a demo's are not.
    scaling: Option<Scaling>,
}

impl TargetKey {
    /// What the run's primitive depends on.
    pub(crate) fn primitive(&self) -> PrimitiveKey {
        PrimitiveKey {
            model: self.model,
            dm: self.dm,
            km: self.km,
            source: self.source,
            scaling: (self.source == TargetSource::Skill).then_some(self.scaling),
        }
    }
}

/// A primitive and, for a skill, its forcing terms' per-time SD.
pub(crate) type Fitted = (Arc<Primitive>, Option<Arc<Vec<Vec3>>>);

/// The run of the stage's primitive at the spec's target.
pub(crate) fn run(
    primitive: &Stage<PrimitiveKey, Fitted>,
    spec: &GeneraliseSpec,
) -> Result<TargetView, String> {
    let Some((primitive, forcing_sd)) = primitive.value() else {
        return Err(primitive.error().unwrap_or_default().to_owned());
    };
    primitive
        .rollout(&spec.target)
        .map(|out| TargetView {
            primitive: primitive.clone(),
            out,
            forcing_sd: forcing_sd.clone(),
        })
        .map_err(|e| match e {
            dmpscope_core::error::Error::InvalidSetting(m) => m,
            other => other.to_string(),
        })
}

/// The demo's primitive, or the skill's with its forcing SD.
pub(crate) fn fit(
    model: &Model,
    (dm, km): (f64, f64),
    spec: &GeneraliseSpec,
) -> Result<Fitted, String> {
    match spec.source {
        TargetSource::Demo(i) => Ok((
            Arc::new(Primitive::of_demo(model, i, dm, km).map_err(|e| e.to_string())?),
            None,
        )),
        TargetSource::Skill => {
            let skill =
                Skill::new(model, dm, km, spec.target.scaling).map_err(|e| e.to_string())?;
            Ok((Arc::new(skill.primitive), Some(Arc::new(skill.forcing_sd))))
        }
    }
}
