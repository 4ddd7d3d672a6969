//! From raw demonstrations to a fitted [`Model`], with an explicit policy for
//! the demos that cannot be used (method.md section 13): the CLI and the app
//! both build their model here.
//!
//! May use: landscape, fit, prepare, load.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::fit::settings::DmpSettings;
use crate::landscape::model::Model;
use crate::landscape::model_steps::ModelSteps;
use crate::load::demo::RawDemo;
use crate::notice::Notice;
use crate::prepare::demo::{PrepSettings, PreparedDemo, prepare};

/// What to do with a demonstration that cannot be prepared (too few samples,
/// a non-finite value, stamps that ask for too many points). There is no
/// default: each front end states its own (both skip; the CLI stops when
/// told `--unusable fail`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Unusable {
    /// Leave it out with a warning naming it and why; fail only when no
    /// demonstration is left.
    Skip,
    /// Stop at the first one.
    Fail,
}

/// A model and how it came about.
#[derive(Debug)]
pub struct Built {
    /// The model of the usable demonstrations.
    pub model: Model,
    /// For each of the model's demos, its index in the input.
    pub used: Vec<usize>,
    /// Demos left out, and a note when S cannot be computed (one demo).
    pub notices: Vec<Notice>,
}

/// Prepares every demo and fits the model of the usable ones.
pub fn build_model<'a>(
    demos: impl IntoIterator<Item = &'a RawDemo>,
    prep: &PrepSettings,
    dmp: DmpSettings,
    unusable: Unusable,
) -> Result<Built> {
    let mut steps = BuildSteps::new(demos.into_iter().collect(), *prep, dmp, unusable);
    loop {
        if let Some(built) = steps.step() {
            return built;
        }
    }
}

/// [`build_model`] in steps of one demo each (prepared, then fitted), for
/// a caller that must not hold its thread for the whole build (the
/// browser's page); the same model, bit for bit. `D` is a demo or a
/// reference to one.
#[derive(Debug)]
pub struct BuildSteps<D> {
    demos: Vec<D>,
    prep: PrepSettings,
    dmp: DmpSettings,
    unusable: Unusable,
    stage: BuildStage,
}

/// Where a [`BuildSteps`] is.
#[derive(Debug)]
enum BuildStage {
    /// Preparing demo `next` (those before it are in `prepared`).
    Preparing {
        next: usize,
        prepared: Vec<PreparedDemo>,
        used: Vec<usize>,
        notices: Vec<Notice>,
        reasons: Vec<String>,
        no_rotation: Vec<String>,
    },
    /// Fitting.
    Fitting {
        steps: ModelSteps,
        used: Vec<usize>,
        notices: Vec<Notice>,
    },
    /// Over (its result was handed out).
    Over,
}

impl<D: std::borrow::Borrow<RawDemo>> BuildSteps<D> {
    /// The build of `demos`' model (nothing done yet).
    pub fn new(demos: Vec<D>, prep: PrepSettings, dmp: DmpSettings, unusable: Unusable) -> Self {
        Self {
            demos,
            prep,
            dmp,
            unusable,
            stage: BuildStage::Preparing {
                next: 0,
                prepared: Vec::new(),
                used: Vec::new(),
                notices: Vec::new(),
                reasons: Vec::new(),
                no_rotation: Vec::new(),
            },
        }
    }

    /// Does one step (a demo prepared, or a demo fitted); the result once
    /// the build is over (then `None` again).
    pub fn step(&mut self) -> Option<Result<Built>> {
        match std::mem::replace(&mut self.stage, BuildStage::Over) {
            BuildStage::Preparing {
                next,
                mut prepared,
                mut used,
                mut notices,
                mut reasons,
                mut no_rotation,
            } => {
                let Some(raw) = self.demos.get(next).map(std::borrow::Borrow::borrow) else {
                    return self.start_fit(prepared, used, notices, reasons, &no_rotation);
                };
                match prepare(raw, &self.prep) {
                    Ok(p) => {
                        if raw.orientations.is_some() && p.orientation.is_none() {
                            no_rotation.push(p.name.clone());
                        }
                        prepared.push(p);
                        used.push(next);
                    }
                    Err(e @ Error::InvalidSetting(_)) => return Some(Err(e)),
                    Err(e) if self.unusable == Unusable::Fail => return Some(Err(e)),
                    Err(e) => {
                        notices.push(Notice::warning(format!("left out {e}")));
                        reasons.push(e.to_string());
                    }
                }
                self.stage = BuildStage::Preparing {
                    next: next + 1,
                    prepared,
                    used,
                    notices,
                    reasons,
                    no_rotation,
                };
                None
            }
            BuildStage::Fitting {
                mut steps,
                used,
                notices,
            } => {
                if steps.project_next() {
                    self.stage = BuildStage::Fitting {
                        steps,
                        used,
                        notices,
                    };
                    return None;
                }
                Some(steps.finish().map(|model| Built {
                    model,
                    used,
                    notices,
                }))
            }
            BuildStage::Over => None,
        }
    }

    /// Demos prepared or fitted, of twice their number.
    pub fn progress(&self) -> (usize, usize) {
        let n = self.demos.len();
        match &self.stage {
            BuildStage::Preparing { next, .. } => (*next, 2 * n),
            BuildStage::Fitting { steps, .. } => (n + steps.progress().0, 2 * n),
            BuildStage::Over => (2 * n, 2 * n),
        }
    }

    /// Every demo prepared: the notices on them, and the fit's start.
    fn start_fit(
        &mut self,
        prepared: Vec<PreparedDemo>,
        used: Vec<usize>,
        mut notices: Vec<Notice>,
        reasons: Vec<String>,
        no_rotation: &[String],
    ) -> Option<Result<Built>> {
        if prepared.is_empty() {
            return Some(Err(Error::NoUsableDemo { reasons }));
        }
        let prep = &self.prep;
        notices.extend(prepared.iter().filter_map(|p| short_window(p, prep)));
        notices.extend(noisy(&prepared));
        if let Some(first) = no_rotation.first() {
            let which = match no_rotation.len() {
                1 => first.clone(),
                n => format!("{n} demos ({first}, ...)"),
            };
            notices.push(Notice::info(format!(
                "{which}: the orientation is the same throughout while the position moves (a \
                 tracker that sends no rotation): no orientation DMP for them, and the \
                 orientation views are off (docs/method.md section 12)"
            )));
        }
        if prepared.len() == 1 {
            notices.push(Notice::info(
                "only one demonstration: S needs two or more and is 0 here",
            ));
        }
        match ModelSteps::new(prepared, self.dmp) {
            Ok(steps) => {
                self.stage = BuildStage::Fitting {
                    steps,
                    used,
                    notices,
                };
                None
            }
            Err(e) => Some(Err(e)),
        }
    }
}

/// The model's settings as the CLI's flags name them (`--sg-window`,
/// `--sg-order`, `--basis`, `--axis-sd-floor`, `--skill-mode`,
/// `--unusable`, `--sg-seconds`, `--k-rot`, `--orientation-gains`), with
/// their defaults: the CLI and the Python package build their model from
/// these.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelFlags {
    /// Savitzky-Golay window (samples, odd).
    pub sg_window: usize,
    /// Savitzky-Golay polynomial order.
    pub sg_order: usize,
    /// Number of DMP basis functions.
    pub basis: usize,
    /// Floor of each axis's SD in S's standardisation (fraction).
    pub axis_sd_floor: f64,
    /// How the one skill follows each demo's start and goal.
    pub skill_mode: crate::fit::settings::SkillMode,
    /// What to do with a demo that cannot be used.
    pub unusable: Unusable,
    /// The Savitzky-Golay window as a duration, seconds.
    pub sg_seconds: Option<f64>,
    /// The weight of the summed orientation error (degrees) in J.
    pub k_rot: f64,
    /// Separate gains `[D/M, K/M]` for the orientation DMP.
    pub orientation_gains: Option<[f64; 2]>,
}

impl Default for ModelFlags {
    fn default() -> Self {
        let (prep, dmp) = (PrepSettings::default(), DmpSettings::default());
        Self {
            sg_window: prep.sg_window,
            sg_order: prep.sg_order,
            basis: dmp.basis_functions,
            axis_sd_floor: dmp.axis_sd_floor,
            skill_mode: dmp.skill_mode,
            unusable: Unusable::Skip,
            sg_seconds: prep.sg_seconds,
            k_rot: dmp.k_rot,
            orientation_gains: dmp.orientation_gains,
        }
    }
}

impl ModelFlags {
    /// The preprocessing settings.
    pub fn prep(&self) -> PrepSettings {
        PrepSettings {
            sg_window: self.sg_window,
            sg_order: self.sg_order,
            sg_seconds: self.sg_seconds,
            ..PrepSettings::default()
        }
    }

    /// The DMP settings.
    pub fn dmp(&self) -> DmpSettings {
        DmpSettings {
            basis_functions: self.basis,
            axis_sd_floor: self.axis_sd_floor,
            skill_mode: self.skill_mode,
            k_rot: self.k_rot,
            orientation_gains: self.orientation_gains,
            ..DmpSettings::default()
        }
    }

    /// Checks what the CLI's parsers check (a window duration above 0).
    pub fn check(&self) -> Result<()> {
        match self.sg_seconds {
            Some(v) if !(v.is_finite() && v > 0.0) => Err(Error::InvalidSetting(format!(
                "expected a duration in seconds above 0, got {v}"
            ))),
            _ => Ok(()),
        }
    }

    /// The model of `demos` (see [`build_model`]).
    pub fn build<'a>(&self, demos: impl IntoIterator<Item = &'a RawDemo>) -> Result<Built> {
        self.check()?;
        build_model(demos, &self.prep(), self.dmp(), self.unusable)
    }
}

/// The span under which a Savitzky-Golay window of samples smooths too
/// little (with 21 samples: a recording at about 670 Hz and more, a robot
/// arm's log), seconds.
pub const SHORT_WINDOW_S: f64 = 0.03;

/// A warning when the window in samples spans less than
/// [`SHORT_WINDOW_S`] of a demo's resampled time.
fn short_window(p: &PreparedDemo, prep: &PrepSettings) -> Option<Notice> {
    if prep.sg_seconds.is_some() || p.n0 < 2 {
        return None;
    }
    let spacing = p.duration_s / (p.n0 - 1) as f64;
    let span = (prep.sg_window - 1) as f64 * spacing;
    (span < SHORT_WINDOW_S).then(|| {
        Notice::warning(format!(
            "{}: the {}-sample Savitzky-Golay window spans {:.0} ms at its {:.0} Hz: its \
             velocities and accelerations (and S) are mostly noise; --sg-seconds 0.2 (the \
             app's Settings: SG window in seconds) sets the window as a duration",
            p.name,
            prep.sg_window,
            span * 1e3,
            1.0 / spacing
        ))
    })
}

/// A warning naming the demos whose smoothed acceleration is mostly noise
/// (method.md section 2, "Noise"), with the `--sg-seconds` that smooths
/// them all (the widest any of them needs).
fn noisy(prepared: &[PreparedDemo]) -> Option<Notice> {
    let threshold = crate::prepare::noise::NOISE_DOMINATES;
    let loud: Vec<&PreparedDemo> = prepared
        .iter()
        .filter(|p| p.acc_noise.is_some_and(|n| n > threshold))
        .collect();
    let first = loud.first()?;
    let which = match loud.len() {
        1 => first.name.clone(),
        n => format!("{n} demos ({}, ...)", first.name),
    };
    let worst = loud
        .iter()
        .filter_map(|p| p.acc_noise)
        .fold(0.0f64, f64::max);
    let fix = loud
        .iter()
        .filter_map(|p| p.suggested_sg_seconds)
        .fold(None::<f64>, |m, s| Some(m.map_or(s, |m| m.max(s))));
    let advice = match fix {
        Some(s) => format!(
            "--sg-seconds {s} (the app's Settings: SG window in seconds) smooths it below {:.0} %",
            threshold * 100.0
        ),
        None => "a wider Savitzky-Golay window (--sg-seconds) smooths it".to_owned(),
    };
    Some(Notice::warning(format!(
        "{which}: the smoothed acceleration is mostly noise (the position noise through the \
         Savitzky-Golay window is up to {:.0} % of its RMS; method.md section 2, \"Noise\"), and S \
         is computed from it; {advice}",
        worst * 100.0
    )))
}
