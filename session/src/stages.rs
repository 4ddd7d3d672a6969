//! The stages of the session and the typed keys they are computed for:
//! each `update_*` compares its stage's key with the settings' and
//! recomputes only when they differ (called in order by
//! [`Session::update`]).

use std::sync::Arc;

use dmpscope_core::arrange::unique_names;
use dmpscope_core::dmp::DmpSettings;
use dmpscope_core::landscape::Grid;
use dmpscope_core::presets::PAPER_PRESETS;
use dmpscope_core::{
    Extraction, Level, Model, PointEval, PrepSettings, RawDemo, Rollout, Unusable, build_model,
    extract,
};

use dmpscope_core::diagnostics::DiagSettings;
use dmpscope_core::extract::{Refined, constrained};
use dmpscope_core::similarity::Standardised;

use super::diagnostics::{DiagSnapshot, DiagnosticsWork};
use super::jobs::{Job, Once, Update};
use super::landscape::{LandscapeWork, Shown, Snapshot};
use super::rl::{Progress as RlProgress, RlRequest, RlWork};
use super::{DemoEntry, PageTime, Session, Settings};

#[derive(Clone, Debug, PartialEq)]
pub(super) struct ModelKey {
    pub(super) demos: u64,
    pub(super) included: Vec<bool>,
    pub(super) prep: PrepSettings,
    pub(super) dmp: DmpSettings,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LandscapeKey {
    pub(super) model: u64,
    pub(super) grid: Grid,
}

/// `f64`s are compared by their bits: a key changes when a value does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ExtractionKey {
    pub(super) landscape: u64,
    pub(super) k: u64,
}

/// The operating point: `f64`s compared by their bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct PointKey {
    pub(super) model: u64,
    pub(super) dm: u64,
    pub(super) km: u64,
}

/// The diagnostics: the extraction they are of and how they are made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct DiagKey {
    pub(super) extraction: ExtractionKey,
    pub(super) settings: DiagSettings,
}

/// The constrained optimum: the extraction's landscape and k, and the
/// a_peak limit's bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ConstrainedKey {
    pub(super) extraction: ExtractionKey,
    pub(super) limit: u64,
}

pub(super) struct ModelState {
    pub(super) key: ModelKey,
    pub(super) version: u64,
    pub(super) built: Result<Arc<Model>, String>,
    /// For each model demo, its index in the demos list.
    pub(super) used: Vec<usize>,
}

pub(super) struct LandscapeState {
    pub(super) key: LandscapeKey,
    pub(super) id: u64,
    pub(super) job: Option<Job<Snapshot>>,
    pub(super) shown: Option<Shown>,
    pub(super) cancelled: bool,
    /// The job stopped without finishing (its thread died).
    pub(super) failed: bool,
    pub(super) page_time: PageTime,
}

pub(super) struct ExtractionState {
    /// What the job (or its result) is for.
    pub(super) key: ExtractionKey,
    pub(super) job: Option<Job<dmpscope_core::Result<Extraction>>>,
    pub(super) result: Option<Extraction>,
    pub(super) error: Option<String>,
}

/// The paper's gains evaluated on a model (their rows follow for any k).
pub(super) struct PresetState {
    pub(super) model: u64,
    pub(super) evals: Vec<(String, PointEval)>,
}

pub(super) struct PointState {
    pub(super) key: PointKey,
    pub(super) eval: PointEval,
    pub(super) paths: Vec<Rollout>,
    /// Every demo's standardised forcing term and sigma_f there.
    pub(super) standardised: Standardised,
    /// Each demo's share of S there (`None` with one demo).
    pub(super) shares: Option<Vec<f64>>,
}

pub(super) struct DiagState {
    pub(super) key: DiagKey,
    pub(super) job: Option<Job<DiagSnapshot>>,
    pub(super) snapshot: Option<DiagSnapshot>,
    pub(super) page_time: PageTime,
}

pub(super) struct ConstrainedState {
    pub(super) key: ConstrainedKey,
    pub(super) job: Option<Job<Option<Refined>>>,
    /// `Some(None)`: no gains within the limit.
    pub(super) result: Option<Option<Refined>>,
}

pub(super) struct RlState {
    pub(super) model: u64,
    pub(super) request: RlRequest,
    pub(super) job: Option<Job<RlProgress>>,
    pub(super) progress: RlProgress,
}

impl Session {
    pub(super) fn update_sources(&mut self, settings: &Settings) {
        let mut changed = false;
        for slot in &mut self.slots {
            let news = slot.update(&settings.load, &self.runner);
            self.runs.loads += news.loads_started;
            self.runs.groupings += usize::from(news.regrouped);
            changed |= news.demos_changed;
            self.messages.extend(news.notices);
        }
        if changed {
            let excluded = &self.excluded;
            let (sources, mut raws): (Vec<usize>, Vec<RawDemo>) = self
                .slots
                .iter()
                .enumerate()
                .flat_map(|(source, slot)| {
                    slot.demos().iter().map(move |raw| (source, raw.clone()))
                })
                .unzip();
            // Names are unique across recordings, as in the CLI.
            unique_names(&mut raws);
            let demos: Vec<DemoEntry> = sources
                .into_iter()
                .zip(raws)
                .map(|(source, raw)| DemoEntry {
                    source,
                    info: raw.info(),
                    included: !excluded.contains(&(source, raw.name.clone())),
                    raw,
                })
                .collect();
            // A regrouping that gives the same demos (a file that failed to
            // load, a grouping that changes nothing) recomputes nothing.
            if demos != self.demos {
                self.demos = demos;
                self.demos_version = self.next_id();
            }
        }
    }

    pub(super) fn update_model(&mut self, settings: &Settings) {
        if self.demos.is_empty() {
            self.model = None;
            return;
        }
        let key = ModelKey {
            demos: self.demos_version,
            included: self.demos.iter().map(|d| d.included).collect(),
            prep: settings.prep,
            dmp: settings.dmp,
        };
        if self.model.as_ref().is_some_and(|m| m.key == key) {
            return;
        }
        self.runs.models += 1;
        let chosen: Vec<usize> = (0..self.demos.len())
            .filter(|&i| self.demos[i].included)
            .collect();
        let raws = chosen.iter().map(|&i| &self.demos[i].raw);
        let (built, used) = match build_model(raws, &key.prep, key.dmp, Unusable::Skip) {
            Ok(b) => {
                self.messages.extend(b.notices);
                let used = b.used.iter().map(|&i| chosen[i]).collect();
                (Ok(Arc::new(b.model)), used)
            }
            Err(e) => {
                let text = if chosen.is_empty() {
                    "no demonstration is included: tick one in Demos".to_owned()
                } else {
                    e.to_string()
                };
                self.messages.say(Level::Warning, text.clone());
                (Err(text), Vec::new())
            }
        };
        let version = self.next_id();
        self.model = Some(ModelState {
            key,
            version,
            built,
            used,
        });
    }

    pub(super) fn update_landscape(&mut self, settings: &Settings) {
        let Some((model, version)) = self.model_and_version() else {
            self.landscape = None;
            return;
        };
        let key = LandscapeKey {
            model: version,
            grid: settings.grid,
        };
        if self.landscape.as_ref().is_none_or(|l| l.key != key) {
            self.runs.landscapes += 1;
            let job = match LandscapeWork::new(model, settings.grid, &self.runner) {
                Ok(work) => {
                    let mut job = self.runner.start("the landscape", work);
                    if let Some(n) = job.take_notice() {
                        self.messages.say(Level::Warning, n);
                    }
                    Some(job)
                }
                Err(e) => {
                    self.messages.say(Level::Warning, format!("grid: {e}"));
                    None
                }
            };
            let id = self.next_id();
            self.landscape = Some(LandscapeState {
                key,
                id,
                job,
                shown: None,
                cancelled: false,
                failed: false,
                page_time: PageTime::default(),
            });
        }
        let Some(l) = &mut self.landscape else { return };
        let update = l.job.as_mut().and_then(Job::poll);
        if let Some(job) = &l.job {
            l.page_time = job.page_time();
        }
        let snapshot = match update {
            Some(Update::Progress(s)) => Some(s),
            Some(Update::Done(s)) => {
                l.job = None;
                Some(s)
            }
            Some(Update::Failed(e)) => {
                l.job = None;
                l.failed = true;
                self.messages
                    .say(Level::Error, format!("the landscape: {e}"));
                None
            }
            None => None,
        };
        if let Some(s) = snapshot {
            self.counter += 1;
            l.shown = Some(Shown::new(s, settings.k, self.counter));
        }
        if let Some(shown) = &mut l.shown
            && shown.k.to_bits() != settings.k.to_bits()
        {
            shown.set_k(settings.k);
        }
    }

    pub(super) fn update_extraction(&mut self, settings: &Settings) {
        let complete = self.landscape.as_ref().and_then(|l| {
            let shown = l.shown.as_ref()?;
            shown.snapshot.complete().then_some((l.id, shown))
        });
        let (Some((id, shown)), Some((model, _))) = (complete, self.model_and_version()) else {
            self.extraction = None;
            return;
        };
        let key = ExtractionKey {
            landscape: id,
            k: settings.k.to_bits(),
        };
        if let Some(x) = &mut self.extraction
            && x.key != key
        {
            // A one-step work cannot be stopped: while the extraction for
            // another k runs, wait for it (its answer is dropped) rather than
            // pile up threads as k is dragged.
            x.result = None;
            x.error = None;
            if let Some(job) = &mut x.job {
                match job.poll() {
                    None | Some(Update::Progress(_)) => return,
                    Some(_) => x.job = None,
                }
            }
        }
        if self.extraction.as_ref().is_none_or(|x| x.key != key) {
            self.runs.extractions += 1;
            let (landscape, k) = (shown.snapshot.landscape.clone(), settings.k);
            let work = Once::new(move || extract(&model, &landscape, k));
            self.extraction = Some(ExtractionState {
                key,
                job: Some(self.runner.start("the extraction", work)),
                result: None,
                error: None,
            });
        }
        let Some(x) = &mut self.extraction else {
            return;
        };
        let failed = match x.job.as_mut().and_then(Job::poll) {
            Some(Update::Done(Ok(found))) => {
                x.result = Some(found);
                None
            }
            Some(Update::Done(Err(e))) => Some(e.to_string()),
            Some(Update::Failed(e)) => Some(e),
            Some(Update::Progress(_)) | None => return,
        };
        x.job = None;
        if let Some(e) = failed {
            self.messages
                .say(Level::Warning, format!("extraction: {e}"));
            x.error = Some(e);
        }
    }

    /// The diagnostics of the current extraction, recomputed when it or the
    /// diagnostics' settings change (gone while k is dragged).
    pub(super) fn update_diagnostics(&mut self, settings: &Settings) {
        let Some((model, _)) = self.model_and_version() else {
            self.diagnostics = None;
            return;
        };
        let ready = self.extraction.as_ref().and_then(|x| {
            let found = x.result.as_ref()?;
            let landscape = &self.landscape.as_ref()?.shown.as_ref()?.snapshot.landscape;
            Some((x.key, found, landscape))
        });
        let Some((extraction, found, landscape)) = ready else {
            self.diagnostics = None;
            return;
        };
        let key = DiagKey {
            extraction,
            settings: settings.diagnostics,
        };
        if self.diagnostics.as_ref().is_none_or(|d| d.key != key) {
            let work = DiagnosticsWork::new(
                model,
                landscape.clone(),
                found.clone(),
                settings.diagnostics,
                &self.runner,
            );
            self.runs.diagnostics += 1;
            let mut job = self.runner.start("the diagnostics", work);
            if let Some(n) = job.take_notice() {
                self.messages.say(Level::Warning, n);
            }
            self.diagnostics = Some(DiagState {
                key,
                job: Some(job),
                snapshot: None,
                page_time: PageTime::default(),
            });
        }
        let Some(d) = &mut self.diagnostics else {
            return;
        };
        if let Some(job) = &d.job {
            d.page_time = job.page_time();
        }
        match d.job.as_mut().and_then(Job::poll) {
            Some(Update::Progress(s)) => d.snapshot = Some(s),
            Some(Update::Done(s)) => {
                d.snapshot = Some(s);
                d.job = None;
            }
            Some(Update::Failed(e)) => {
                d.job = None;
                self.messages
                    .say(Level::Error, format!("the diagnostics: {e}"));
            }
            None => {}
        }
    }

    /// The optimum under the a_peak limit, when one is set.
    pub(super) fn update_constrained(&mut self, settings: &Settings) {
        let limit = settings.a_peak_limit.filter(|l| l.is_finite() && *l > 0.0);
        let (Some(limit), Some(x), Some((model, _))) =
            (limit, &self.extraction, self.model_and_version())
        else {
            self.constrained = None;
            return;
        };
        if !self.landscape_complete() {
            self.constrained = None;
            return;
        }
        let key = ConstrainedKey {
            extraction: x.key,
            limit: limit.to_bits(),
        };
        if let Some(c) = &mut self.constrained
            && c.key != key
        {
            // One at a time while the limit is dragged (as the extraction).
            c.result = None;
            if let Some(job) = &mut c.job {
                match job.poll() {
                    None | Some(Update::Progress(_)) => return,
                    Some(_) => c.job = None,
                }
            }
        }
        if self.constrained.as_ref().is_none_or(|c| c.key != key) {
            let Some(shown) = self.shown() else { return };
            let (landscape, k) = (shown.snapshot.landscape.clone(), settings.k);
            let work = Once::new(move || constrained(&model, &landscape, k, limit));
            self.constrained = Some(ConstrainedState {
                key,
                job: Some(self.runner.start("the constrained optimum", work)),
                result: None,
            });
        }
        let Some(c) = &mut self.constrained else {
            return;
        };
        match c.job.as_mut().and_then(Job::poll) {
            Some(Update::Done(found)) => {
                c.result = Some(found);
                c.job = None;
            }
            Some(Update::Failed(e)) => {
                c.job = None;
                self.messages
                    .say(Level::Error, format!("the constrained optimum: {e}"));
            }
            Some(Update::Progress(_)) | None => {}
        }
    }

    /// The paper's gains on the model: evaluated once per model, their
    /// rows made for the current k when asked ([`Session::table_rows`]).
    pub(super) fn update_presets(&mut self) {
        let Some((model, version)) = self.model_and_version() else {
            self.presets = None;
            return;
        };
        if self.presets.as_ref().is_none_or(|p| p.model != version) {
            self.runs.tables += 1;
            let evals = PAPER_PRESETS
                .iter()
                .map(|p| (p.name.to_owned(), model.evaluate(p.dm, p.km)))
                .collect();
            self.presets = Some(PresetState {
                model: version,
                evals,
            });
        }
    }

    /// The operating point: its evaluation and every demo's path, once per
    /// model and point (its row follows for any k).
    pub(super) fn update_point(&mut self, settings: &Settings) {
        let Some((model, version)) = self.model_and_version() else {
            self.point = None;
            return;
        };
        let (dm, km) = settings.op;
        let key = PointKey {
            model: version,
            dm: dm.to_bits(),
            km: km.to_bits(),
        };
        if self.point.as_ref().is_none_or(|p| p.key != key) {
            self.runs.points += 1;
            let eval = model.evaluate(dm, km);
            let paths = (0..model.demos().len())
                .map(|i| model.rollout(i, dm, km))
                .collect();
            let similarity = model.similarity();
            let standardised = similarity.standardised(dm, km);
            let shares = standardised.shares();
            self.point = Some(PointState {
                key,
                eval,
                paths,
                standardised,
                shares,
            });
        }
    }

    pub(super) fn update_rl(&mut self) {
        let version = self.model_and_version().map(|(_, v)| v);
        if self.rl.as_ref().is_some_and(|r| Some(r.model) != version) {
            self.rl = None;
        }
        let Some(rl) = &mut self.rl else { return };
        match rl.job.as_mut().and_then(Job::poll) {
            Some(Update::Progress(p)) => rl.progress = p,
            Some(Update::Done(p)) => {
                if let Some(why) = &p.stopped {
                    self.messages.say(Level::Error, format!("RL: {why}"));
                }
                rl.progress = p;
                rl.job = None;
            }
            Some(Update::Failed(e)) => {
                rl.job = None;
                rl.progress.done = true;
                self.messages.say(Level::Error, format!("RL: {e}"));
            }
            None => {}
        }
    }

    pub(super) fn start_rl(&mut self, request: RlRequest) {
        let Some((model, version)) = self.model_and_version() else {
            self.messages
                .say(Level::Warning, "RL needs a model: open demos first");
            return;
        };
        match RlWork::new(model, request.clone(), &self.runner) {
            Ok(work) => {
                let progress = work.progress().clone();
                let mut job = self.runner.start("RL training", work);
                if let Some(n) = job.take_notice() {
                    self.messages.say(Level::Warning, n);
                }
                self.rl = Some(RlState {
                    model: version,
                    request,
                    job: Some(job),
                    progress,
                });
            }
            Err(e) => self.messages.say(Level::Warning, format!("RL: {e}")),
        }
    }

    pub(super) fn model_and_version(&self) -> Option<(Arc<Model>, u64)> {
        let m = self.model.as_ref()?;
        m.built
            .as_ref()
            .ok()
            .map(|model| (model.clone(), m.version))
    }
}
