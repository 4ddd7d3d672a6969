//! The model as a [`Work`] of one demo per step (the core's
//! [`BuildSteps`]): where jobs run on the caller's thread in slices (the
//! browser's page), a new model is built between frames, not inside one
//! (issue 43: about 25 ms of the page's thread for the bundled sample).
//! Where jobs run elsewhere (natively), [`build_now`] builds it at once
//! from the session's demos in place.

use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::pipeline::{BuildSteps, build_model};
use dmpscope_core::prepare::demo::PrepSettings;
use dmpscope_core::{RawDemo, Unusable};

use crate::jobs::{Step, Work};
use crate::state::{Built, DemoEntry};

/// A model built (its demos' indices in the session's demos list, what the
/// build had to say), or why there is none.
pub(crate) type ModelOutcome = Result<Built, String>;

/// Builds the model of the chosen demos, a demo per step.
pub(crate) struct ModelWork {
    steps: BuildSteps<RawDemo>,
    /// For each demo given, its index in the session's demos list.
    chosen: Vec<usize>,
}

impl ModelWork {
    /// The build of the included demos of `demos` (copied: the work runs
    /// as a job, apart from the session's list).
    pub(crate) fn new(demos: &[DemoEntry], prep: PrepSettings, dmp: DmpSettings) -> Self {
        let chosen = included(demos);
        let raws = chosen.iter().map(|&i| demos[i].raw.clone()).collect();
        Self {
            steps: BuildSteps::new(raws, prep, dmp, Unusable::Skip),
            chosen,
        }
    }
}

impl Work for ModelWork {
    type Output = ModelOutcome;

    fn step(&mut self) -> Step<ModelOutcome> {
        match self.steps.step() {
            Some(built) => Step::Done(outcome(built, &self.chosen)),
            None => Step::Working,
        }
    }
}

/// The model of the included demos of `demos` built at once, reading them
/// in place (natively: milliseconds, no copy of the demos).
pub(crate) fn build_now(demos: &[DemoEntry], prep: PrepSettings, dmp: DmpSettings) -> ModelOutcome {
    let chosen = included(demos);
    let built = build_model(
        chosen.iter().map(|&i| &demos[i].raw),
        &prep,
        dmp,
        Unusable::Skip,
    );
    outcome(built, &chosen)
}

/// The indices of the included demos.
fn included(demos: &[DemoEntry]) -> Vec<usize> {
    (0..demos.len()).filter(|&i| demos[i].included).collect()
}

/// The model built from the demos at `chosen`, its demos' indices mapped
/// back to the session's list; or why there is none.
fn outcome(built: dmpscope_core::Result<dmpscope_core::Built>, chosen: &[usize]) -> ModelOutcome {
    match built {
        Ok(b) => Ok(Built {
            model: std::sync::Arc::new(b.model),
            used: b.used.iter().map(|&i| chosen[i]).collect(),
            notices: b.notices,
        }),
        Err(_) if chosen.is_empty() => Err(no_demo_included()),
        Err(e) => Err(e.to_string()),
    }
}

/// What the window says when every demo is unticked.
pub(crate) fn no_demo_included() -> String {
    "no demonstration is included: tick one in Demos".to_owned()
}
