//! The stages of the session and the typed keys they are computed for:
//! each `update_*` makes its stage's key from the settings and the stages
//! before it and hands it to its [`Stage`], which recomputes only when the
//! key differs (called in order by [`Session::update`]).

use std::sync::{Arc, OnceLock};

use dmpscope_core::arrange::streams::unique_names;
use dmpscope_core::extract::optimum::constrained;
use dmpscope_core::report::presets::PAPER_PRESETS;
use dmpscope_core::{Level, Model, RawDemo, extract};

use crate::diagnostics::DiagnosticsWork;
use crate::jobs::Once;
use crate::landscape::{LandscapeWork, Shown};
use crate::model_work::{ModelWork, build_now};
use crate::rl::RlWork;
use crate::rl_request::RlRequest;
use crate::session::Session;
use crate::settings::Settings;
use crate::stage::Polled;
use crate::state::{
    ConstrainedKey, DemoEntry, DiagKey, ExtractionKey, LandscapeKey, ModelKey, PointKey,
    PointValue, RlKey,
};

impl Session {
    pub(crate) fn update_sources(&mut self, settings: &Settings) {
        let mut changed = false;
        for slot in &mut self.slots {
            let news = slot.update(&settings.load, &self.runner);
            self.runs.loads += news.loads_started;
            self.runs.groupings += usize::from(news.regrouped);
            changed |= news.demos_changed;
            self.messages.extend(news.notices);
        }
        if !changed {
            return;
        }
        let excluded = &self.excluded;
        let (sources, mut raws): (Vec<usize>, Vec<RawDemo>) = self
            .slots
            .iter()
            .enumerate()
            .flat_map(|(source, slot)| slot.demos().iter().map(move |raw| (source, raw.clone())))
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

    pub(crate) fn update_model(&mut self, settings: &Settings) {
        if self.demos.is_empty() {
            self.model.clear();
            return;
        }
        let key = ModelKey {
            demos: self.demos_version,
            included: self.demos.iter().map(|d| d.included).collect(),
            prep: settings.prep,
            dmp: settings.dmp,
        };
        let (prep, dmp, demos) = (key.prep, key.dmp, &self.demos);
        let arrived = if self.runner.threaded() {
            // Natively at once (milliseconds): no frame goes without a model.
            self.model
                .ensure_now(key, |_| Ok(build_now(demos, prep, dmp)))
        } else {
            // Elsewhere a job of a demo per step: in the browser, slices
            // between frames (tests: at once, at the first poll).
            let runner = &self.runner;
            self.model.ensure_job(key, || {
                Ok(runner.start("the model", ModelWork::new(demos, prep, dmp)))
            });
            match self.model.poll() {
                Polled::Value => true,
                Polled::Failed(e) => {
                    let text = format!("the model: {e}");
                    self.messages.say(Level::Warning, text.clone());
                    self.model.set_error(text);
                    false
                }
                Polled::Nothing => false,
            }
        };
        if arrived {
            self.runs.models += 1;
            match self.model.value_mut() {
                Some(Ok(built)) => self.messages.extend(std::mem::take(&mut built.notices)),
                Some(Err(text)) => self.messages.say(Level::Warning, text.clone()),
                None => {}
            }
        }
    }

    pub(crate) fn update_landscape(&mut self, settings: &Settings) {
        let Some((model, version)) = self.model_and_version() else {
            self.landscape.clear();
            self.shown = None;
            return;
        };
        let key = LandscapeKey {
            model: version,
            grid: settings.grid,
        };
        if self.model_unshown() && !self.landscape.is_for(&key) {
            // Starts at the next frame (see `Session::pace_by_frames`);
            // the landscape of an older model is gone meanwhile.
            self.landscape.clear();
            self.shown = None;
            return;
        }
        let (runner, messages) = (&self.runner, &mut self.messages);
        if self.landscape.ensure_job(key, || {
            LandscapeWork::new(model, settings.grid, runner)
                .map(|work| runner.start("the landscape", work))
                .map_err(|e| {
                    messages.say(Level::Warning, format!("grid: {e}"));
                    format!("grid: {e}")
                })
        }) {
            self.runs.landscapes += 1;
            self.shown = None;
            if let Some(n) = self.landscape.take_notice() {
                self.messages.say(Level::Warning, n);
            }
        }
        match self.landscape.poll() {
            Polled::Value => {
                // The snapshot moves to the view (the stage keeps its key).
                if let Some(s) = self.landscape.take_value() {
                    self.counter += 1;
                    self.shown = Some(Shown::new(s, settings.k, self.counter));
                }
            }
            Polled::Failed(e) => self
                .messages
                .say(Level::Error, format!("the landscape: {e}")),
            Polled::Nothing => {}
        }
        if let Some(shown) = &mut self.shown
            && shown.k.to_bits() != settings.k.to_bits()
        {
            shown.set_k(settings.k);
        }
    }

    /// The key of the extraction for `k`, once the landscape is complete.
    fn extraction_key(&self, k: f64) -> Option<ExtractionKey> {
        self.landscape_complete().then(|| ExtractionKey {
            landscape: self.landscape.version(),
            k: k.to_bits(),
        })
    }

    pub(crate) fn update_extraction(&mut self, settings: &Settings) {
        let (Some(key), Some((model, _)), Some(shown)) = (
            self.extraction_key(settings.k),
            self.model_and_version(),
            &self.shown,
        ) else {
            self.extraction.clear();
            return;
        };
        let k = settings.k;
        let runner = &self.runner;
        if self.extraction.ensure_serial(key, || {
            // Cloned only when a job starts (never per frame).
            let landscape = shown.snapshot.landscape.clone();
            let work = Once::new(move || extract(&model, &landscape, k));
            Ok(runner.start("the extraction", work))
        }) {
            self.runs.extractions += 1;
        }
        let failed = match self.extraction.poll() {
            Polled::Value => match self.extraction.value() {
                Some(Err(e)) => Some(e.to_string()),
                _ => None,
            },
            Polled::Failed(e) => Some(e),
            Polled::Nothing => None,
        };
        if let Some(e) = failed {
            self.messages
                .say(Level::Warning, format!("extraction: {e}"));
            self.extraction.set_error(e);
        }
    }

    /// The diagnostics of the current extraction, recomputed when it or the
    /// diagnostics' settings change (gone while k is dragged).
    pub(crate) fn update_diagnostics(&mut self, settings: &Settings) {
        let ready =
            crate::state::found(self.extraction.value()).zip(self.extraction.key().copied());
        let (Some((found, extraction)), Some((model, _)), Some(shown)) =
            (ready, self.model_and_version(), &self.shown)
        else {
            self.diagnostics.clear();
            return;
        };
        let key = DiagKey {
            extraction,
            settings: settings.diagnostics,
        };
        let runner = &self.runner;
        if self.diagnostics.ensure_job(key, || {
            // Cloned only when a job starts (never per frame).
            let (landscape, found) = (shown.snapshot.landscape.clone(), found.clone());
            let work = DiagnosticsWork::new(model, landscape, found, settings.diagnostics, runner);
            Ok(runner.start("the diagnostics", work))
        }) {
            self.runs.diagnostics += 1;
            if let Some(n) = self.diagnostics.take_notice() {
                self.messages.say(Level::Warning, n);
            }
        }
        if let Polled::Failed(e) = self.diagnostics.poll() {
            self.messages
                .say(Level::Error, format!("the diagnostics: {e}"));
        }
    }

    /// The optimum under the a_peak limit, when one is set.
    pub(crate) fn update_constrained(&mut self, settings: &Settings) {
        let limit = settings.a_peak_limit.filter(|l| l.is_finite() && *l > 0.0);
        if limit.is_some() && self.extraction.waiting() {
            // The extraction waits for its last job: so does this stage
            // (one job at a time, whatever the user drags).
            if let Polled::Failed(e) = self.constrained.poll() {
                self.messages
                    .say(Level::Error, format!("the constrained optimum: {e}"));
            }
            return;
        }
        let extraction = self.extraction.key().copied();
        let (Some(limit), Some(extraction), Some((model, _)), Some(shown)) =
            (limit, extraction, self.model_and_version(), &self.shown)
        else {
            self.constrained.clear();
            return;
        };
        if !self.landscape_complete() {
            self.constrained.clear();
            return;
        }
        let key = ConstrainedKey {
            extraction,
            limit: limit.to_bits(),
        };
        let k = settings.k;
        let runner = &self.runner;
        self.constrained.ensure_serial(key, || {
            let landscape = shown.snapshot.landscape.clone();
            let work = Once::new(move || constrained(&model, &landscape, k, limit));
            Ok(runner.start("the constrained optimum", work))
        });
        if let Polled::Failed(e) = self.constrained.poll() {
            self.messages
                .say(Level::Error, format!("the constrained optimum: {e}"));
        }
    }

    /// The paper's gains on the model: evaluated once per model, their
    /// rows made for the current k when asked ([`Session::table_rows`]).
    pub(crate) fn update_presets(&mut self) {
        let Some((model, version)) = self.model_and_version() else {
            self.presets.clear();
            return;
        };
        let evaluated = self.presets.ensure_now(version, |_| {
            Ok(PAPER_PRESETS
                .iter()
                .map(|p| (p.name.to_owned(), model.evaluate(p.dm, p.km)))
                .collect())
        });
        self.runs.tables += usize::from(evaluated);
    }

    /// The operating point: its evaluation and every demo's path, once per
    /// model and point (its row follows for any k).
    pub(crate) fn update_point(&mut self, settings: &Settings) {
        let Some((model, version)) = self.model_and_version() else {
            self.point.clear();
            return;
        };
        let (dm, km) = settings.op;
        let key = PointKey {
            model: version,
            dm: dm.to_bits(),
            km: km.to_bits(),
        };
        let evaluated = self.point.ensure_now(key, |_| {
            let (eval, turns) = model.evaluate_with_turns(dm, km);
            Ok(PointValue {
                eval,
                paths: (0..model.demos().len())
                    .map(|i| model.rollout(i, dm, km))
                    .collect(),
                turns,
                standardised: OnceLock::new(),
            })
        });
        self.runs.points += usize::from(evaluated);
    }

    pub(crate) fn update_rl(&mut self) {
        let version = self.model_and_version().map(|(_, v)| v);
        if self.rl.key().is_some_and(|k| Some(k.model) != version) {
            self.rl.clear();
            self.rl_request = None;
        }
        match self.rl.poll() {
            Polled::Value => {
                if let Some(why) = self
                    .rl
                    .value()
                    .filter(|p| p.done)
                    .and_then(|p| p.stopped.clone())
                {
                    self.messages.say(Level::Error, format!("RL: {why}"));
                }
            }
            Polled::Failed(e) => {
                if let Some(p) = self.rl.value_mut() {
                    p.done = true;
                }
                self.messages.say(Level::Error, format!("RL: {e}"));
            }
            Polled::Nothing => {}
        }
    }

    pub(crate) fn start_rl(&mut self, request: RlRequest) {
        let Some((model, version)) = self.model_and_version() else {
            self.messages
                .say(Level::Warning, "RL needs a model: open demos first");
            return;
        };
        let key = RlKey {
            model: version,
            request: self.next_id(),
        };
        let work = match RlWork::new(model, request.clone(), &self.runner) {
            Ok(work) => work,
            Err(e) => {
                self.messages.say(Level::Warning, format!("RL: {e}"));
                return;
            }
        };
        let progress = work.progress().clone();
        let runner = &self.runner;
        self.rl
            .ensure_job(key, || Ok(runner.start("RL training", work)));
        self.rl.set_value(progress);
        if let Some(n) = self.rl.take_notice() {
            self.messages.say(Level::Warning, n);
        }
        self.rl_request = Some(request);
    }

    pub(crate) fn model_and_version(&self) -> Option<(Arc<Model>, u64)> {
        self.built()
            .map(|b| (b.model.clone(), self.model.version()))
    }
}
