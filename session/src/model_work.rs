//! The model as a [`Work`] of one demo per step (the core's
//! [`BuildSteps`]): where jobs run on the caller's thread in slices (the
//! browser's page), a new model is built between frames, not inside one
//! (issue 43: about 25 ms of the page's thread for the bundled sample).

use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::pipeline::BuildSteps;
use dmpscope_core::prepare::demo::PrepSettings;
use dmpscope_core::{RawDemo, Unusable};

use crate::jobs::{Step, Work};

/// A model built, its demos' indices in the session's demos list, and what
/// the build had to say; or why there is none.
pub(crate) type ModelOutcome = Result<(dmpscope_core::Built, Vec<usize>), String>;

/// Builds the model of the chosen demos, a demo per step.
pub(crate) struct ModelWork {
    steps: BuildSteps<RawDemo>,
    /// For each demo given, its index in the session's demos list.
    chosen: Vec<usize>,
}

impl ModelWork {
    /// The build of `raws` (the session's demos at `chosen`).
    pub(crate) fn new(
        raws: Vec<RawDemo>,
        chosen: Vec<usize>,
        prep: PrepSettings,
        dmp: DmpSettings,
    ) -> Self {
        Self {
            steps: BuildSteps::new(raws, prep, dmp, Unusable::Skip),
            chosen,
        }
    }
}

impl Work for ModelWork {
    type Output = ModelOutcome;

    fn step(&mut self) -> Step<ModelOutcome> {
        let Some(built) = self.steps.step() else {
            return Step::Working;
        };
        Step::Done(match built {
            Ok(b) => {
                let used = b.used.iter().map(|&i| self.chosen[i]).collect();
                Ok((b, used))
            }
            Err(e) => Err(if self.chosen.is_empty() {
                no_demo_included()
            } else {
                e.to_string()
            }),
        })
    }
}

/// What the window says when every demo is unticked.
pub(crate) fn no_demo_included() -> String {
    "no demonstration is included: tick one in Demos".to_owned()
}
