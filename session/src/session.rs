//! The session: the app's state (the crate's documentation says what it
//! holds and when each stage is recomputed), its commands and its
//! read-only views. Each stage's update is in its own file
//! (`stages.rs`, `allowed.rs`).

use std::collections::BTreeSet;
use std::sync::Arc;

use dmpscope_core::extract::optimum::Refined;
use dmpscope_core::fit::orientation::OrientationRollout;
use dmpscope_core::kernels::similarity::Standardised;
use dmpscope_core::report::summary::Constrained;
use dmpscope_core::{Extraction, Model, Notice, PointEval, Report, Rollout, TableRow};

use crate::commands::Command;
use crate::diagnostics::DiagSnapshot;
use crate::executor::PageTime;
use crate::generalise::{Fitted, GeneraliseSpec, PrimitiveKey, TargetKey, TargetView};
use crate::jobs::Runner;
use crate::landscape::{Shown, Snapshot};
use crate::messages::Messages;
use crate::rl_request::{Progress as RlProgress, RlRequest};
use crate::settings::Settings;
use crate::sources::{Source, SourceSlot};
use crate::stage::Stage;
use crate::state::{
    AllowedKey, AllowedView, Built, ConstrainedKey, DemoEntry, DiagKey, ExtractionKey,
    LandscapeKey, ModelKey, PointKey, PointValue, RlKey, StageRuns,
};
use crate::status::Status;
use crate::workers::WorkerStats;

/// The app's state (see the module's documentation).
pub struct Session {
    pub(crate) runner: Runner,
    pub(crate) slots: Vec<SourceSlot>,
    pub(crate) demos: Vec<DemoEntry>,
    pub(crate) demos_version: u64,
    /// The demos the user excluded, by source and name (kept across
    /// reloads and regroupings).
    pub(crate) excluded: BTreeSet<(usize, String)>,
    pub(crate) messages: Messages,
    /// The model, or why there is none (built at once natively, as a job
    /// of a demo per step in the browser).
    pub(crate) model: Stage<ModelKey, crate::model_work::ModelOutcome>,
    pub(crate) landscape: Stage<LandscapeKey, Snapshot>,
    /// The landscape's latest snapshot as the heat maps show it.
    pub(crate) shown: Option<Shown>,
    pub(crate) extraction: Stage<ExtractionKey, dmpscope_core::Result<Extraction>>,
    pub(crate) diagnostics: Stage<DiagKey, DiagSnapshot>,
    /// `Some(None)`: no gains within the a_peak limit.
    pub(crate) constrained: Stage<ConstrainedKey, Option<Refined>>,
    /// The acceptable region, E's verdict and the pick.
    pub(crate) allowed: Stage<AllowedKey, AllowedView>,
    /// The paper's gains evaluated, per model version.
    pub(crate) presets: Stage<u64, Vec<(String, PointEval)>>,
    /// The k of the last update (Table I's rows are made for it).
    pub(crate) k: f64,
    pub(crate) point: Stage<PointKey, PointValue>,
    /// The user's generalisation, if on.
    pub(crate) generalise: Option<GeneraliseSpec>,
    /// Its primitive (kept while only the target moves) and its run.
    pub(crate) primitive: Stage<PrimitiveKey, Fitted>,
    pub(crate) generalised: Stage<TargetKey, TargetView>,
    pub(crate) rl: Stage<RlKey, RlProgress>,
    pub(crate) rl_request: Option<RlRequest>,
    pub(crate) runs: StageRuns,
    pub(crate) counter: u64,
    /// Whether the landscape waits for a frame that has shown its model
    /// ([`Session::pace_by_frames`]).
    pub(crate) paced: bool,
    /// The model version the last finished frame showed.
    pub(crate) model_shown: Option<u64>,
}

impl Session {
    /// An empty session whose background work runs with `runner`.
    pub fn new(runner: Runner) -> Self {
        Self {
            runner,
            slots: Vec::new(),
            demos: Vec::new(),
            demos_version: 0,
            excluded: BTreeSet::new(),
            messages: Messages::default(),
            model: Stage::default(),
            landscape: Stage::default(),
            shown: None,
            extraction: Stage::default(),
            diagnostics: Stage::default(),
            constrained: Stage::default(),
            allowed: Stage::default(),
            presets: Stage::default(),
            k: dmpscope_core::DEFAULT_K,
            point: Stage::default(),
            generalise: None,
            primitive: Stage::default(),
            generalised: Stage::default(),
            rl: Stage::default(),
            rl_request: None,
            runs: StageRuns::default(),
            counter: 0,
            paced: false,
            model_shown: None,
        }
    }

    /// Starts the landscape of a new model only once a frame has shown
    /// that model ([`Session::frame_shown`]), not in the frame that first
    /// draws it. For the browser: the first layout of a new model (its
    /// plots, 3D paths and table: 15-25 ms of the page's thread) and the
    /// start of the workers then fall in different frames, and that layout
    /// is not slowed by workers computing beside it on a 2-core machine.
    /// The landscape starts one frame later. Off by default (natively the
    /// landscape runs on threads of its own).
    pub fn pace_by_frames(&mut self, on: bool) {
        self.paced = on;
    }

    /// Tells the session that a frame has been drawn, showing the model of
    /// version `model` ([`Session::model_version`] when its panels were
    /// laid out; see [`Session::pace_by_frames`]); `true` when the
    /// landscape waits for the next frame, so the caller should ask for it.
    #[must_use]
    pub fn frame_shown(&mut self, model: Option<u64>) -> bool {
        self.model_shown = model;
        // The next update starts it.
        self.landscape_awaits_frame()
    }

    /// Whether the current model has not been shown yet, so that its
    /// landscape must wait (see [`Session::pace_by_frames`]).
    pub(crate) fn model_unshown(&self) -> bool {
        self.paced && self.model_version().is_some() && self.model_version() != self.model_shown
    }

    /// Whether the landscape waits for a frame that shows its model: paced,
    /// with a model, and the landscape's stage left empty for it (see
    /// `update_landscape`).
    fn landscape_awaits_frame(&self) -> bool {
        self.paced && self.model_version().is_some() && self.landscape.key().is_none()
    }

    pub(crate) fn next_id(&mut self) -> u64 {
        self.counter += 1;
        self.counter
    }

    /// Applies a command; its effects are computed by the next
    /// [`Session::update`].
    pub fn apply(&mut self, command: Command) {
        match command {
            Command::AddSources(sources) => {
                self.slots.extend(sources.into_iter().map(SourceSlot::new));
            }
            Command::OpenSample(sample) => {
                if self.slots.iter().all(|s| s.source.is_sample()) {
                    self.slots.clear();
                    self.demos.clear();
                    self.excluded.clear();
                    self.demos_version = self.next_id();
                }
                self.slots.push(SourceSlot::new(sample));
            }
            Command::SetIncluded { demo, included } => {
                if let Some(d) = self.demos.get_mut(demo) {
                    d.included = included;
                    let key = (d.source, d.raw.name.clone());
                    if included {
                        self.excluded.remove(&key);
                    } else {
                        self.excluded.insert(key);
                    }
                }
            }
            Command::SetStreamIncluded {
                source,
                topic,
                included,
            } => {
                if let Some(slot) = self.slots.get_mut(source) {
                    match included {
                        Some(on) => slot.overrides.insert(topic, on),
                        None => slot.overrides.remove(&topic),
                    };
                }
            }
            Command::CancelLoading(source) => {
                if let Some(slot) = self.slots.get(source) {
                    slot.cancel();
                }
            }
            Command::CancelLandscape => {
                self.landscape.cancel();
            }
            Command::RestartLandscape => {
                self.landscape.clear();
                self.shown = None;
            }
            Command::StartRl(request) => self.start_rl(request),
            Command::CancelRl => {
                if self.rl.cancel()
                    && let Some(progress) = self.rl.value_mut()
                {
                    progress.done = true;
                    progress.cancelled = true;
                }
            }
            Command::SetGeneralise(spec) => self.generalise = spec,
            Command::ClearMessages => self.messages.clear(),
            Command::Say(notice) => self.messages.push(notice),
        }
    }

    /// Brings every stage up to date with `settings`: the one place that
    /// compares keys and decides what to recompute. Cheap when nothing
    /// changed.
    pub fn update(&mut self, settings: &Settings) {
        self.k = settings.k;
        self.update_sources(settings);
        self.update_model(settings);
        self.update_landscape(settings);
        self.update_extraction(settings);
        self.update_diagnostics(settings);
        self.update_constrained(settings);
        self.update_allowed(settings);
        self.update_presets();
        self.update_point(settings);
        self.update_generalised(settings);
        self.update_rl();
        // The executor's workers: one that failed, or none that started.
        for text in self.runner.take_notices() {
            self.messages
                .say(dmpscope_core::notice::Level::Warning, text);
        }
    }

    /// The generalisation: recomputed when the model, the operating point
    /// or the target changes; its primitive only when the model, the point
    /// or the source changes (a goal drag rolls the same primitive out).
    fn update_generalised(&mut self, settings: &Settings) {
        let (Some(spec), Some((model, version))) = (self.generalise, self.model_and_version())
        else {
            self.generalised.clear();
            self.primitive.clear();
            return;
        };
        let key = TargetKey::new(version, settings.op, &spec);
        self.primitive.ensure_now(key.primitive(), |_| {
            crate::generalise::fit(&model, settings.op, &spec)
        });
        let primitive = &self.primitive;
        let computed = self
            .generalised
            .ensure_now(key, |_| crate::generalise::run(primitive, &spec));
        self.runs.generalised += usize::from(computed);
    }

    /// The generalisation asked for (`None`: off).
    pub fn generalise_spec(&self) -> Option<&GeneraliseSpec> {
        self.generalise.as_ref()
    }

    /// The generalised run at the operating point, or why there is none.
    pub fn generalised(&self) -> Option<Result<&TargetView, &str>> {
        let g = &self.generalised;
        g.key()
            .map(|_| g.value().ok_or_else(|| g.error().unwrap_or_default()))
    }

    /// The recordings opened, in order.
    pub fn sources(&self) -> impl Iterator<Item = &Source> {
        self.slots.iter().map(|s| &s.source)
    }

    /// The recordings opened, in order, with their streams and what became
    /// of each (the Recording panel).
    pub fn recordings(&self) -> &[SourceSlot] {
        &self.slots
    }

    /// Whether a recording is being read.
    pub fn loading(&self) -> bool {
        self.slots.iter().any(SourceSlot::loading)
    }

    /// The demos of every recording, in order.
    pub fn demos(&self) -> &[DemoEntry] {
        &self.demos
    }

    /// The messages, oldest first.
    pub fn messages(&self) -> &[Notice] {
        self.messages.list()
    }

    /// The model, when one could be built.
    pub fn model(&self) -> Option<&Arc<Model>> {
        self.built().map(|b| &b.model)
    }

    /// Identifies the current model: changes whenever a new one is built.
    pub fn model_version(&self) -> Option<u64> {
        self.model_and_version().map(|(_, v)| v)
    }

    /// For each model demo, its index in [`Session::demos`].
    pub fn model_demos(&self) -> &[usize] {
        self.built().map_or(&[], |b| b.used.as_slice())
    }

    /// The landscape as the heat maps show it.
    pub fn shown(&self) -> Option<&Shown> {
        self.shown.as_ref()
    }

    /// Whether the landscape is being computed.
    pub fn landscape_running(&self) -> bool {
        self.landscape.running()
    }

    /// Whether the landscape is complete.
    pub fn landscape_complete(&self) -> bool {
        self.shown().is_some_and(|s| s.snapshot.complete())
    }

    /// The extracted gains for the current k, once known.
    pub fn extraction(&self) -> Option<&Extraction> {
        crate::state::found(self.extraction.value())
    }

    /// Whether the optimum is being extracted.
    pub fn extracting(&self) -> bool {
        self.extraction.running()
    }

    /// The diagnostics of the extraction so far (`None` until it is known).
    pub fn diagnostics(&self) -> Option<&DiagSnapshot> {
        self.diagnostics.value()
    }

    /// Whether the diagnostics are being computed.
    pub fn diagnosing(&self) -> bool {
        self.diagnostics.running()
    }

    /// The optimum under the a_peak limit: `None` without a limit or until
    /// computed, `Some(None)` when no gains are within it.
    pub fn constrained(&self) -> Option<Option<&Refined>> {
        crate::state::within(self.constrained.value())
    }

    /// The operating point's evaluation (its gains, d, a_peak, S).
    pub fn point(&self) -> Option<&PointEval> {
        self.point.value().map(|p| &p.eval)
    }

    /// Every demo's standardised forcing term and sigma_f at the operating
    /// point.
    pub fn forcing_terms(&self) -> Option<&Standardised> {
        self.point_standardised().map(|(s, _)| s)
    }

    /// Each model demo's share of S at the operating point (`None` with
    /// one demo).
    pub fn point_shares(&self) -> Option<&[f64]> {
        self.point_standardised()
            .and_then(|(_, shares)| shares.as_deref())
    }

    /// The operating point's standardised forcing terms and shares of S,
    /// computed on first use.
    fn point_standardised(&self) -> Option<&(Standardised, Option<Vec<f64>>)> {
        let model = self.model()?;
        let p = self.point.value()?;
        Some(p.standardised.get_or_init(|| {
            let standardised = model.similarity().standardised(p.eval.dm, p.eval.km);
            let shares = standardised.shares();
            (standardised, shares)
        }))
    }

    /// Table I for the k of the last update: extracted (when known), the
    /// paper's gains, the operating point.
    pub fn table_rows(&self) -> Vec<TableRow> {
        let k = self.k;
        let mut rows: Vec<TableRow> = self
            .extraction()
            .map(|x| TableRow::from_eval("Extracted", &x.eval, x.k))
            .into_iter()
            .collect();
        if let Some(view) = self.allowed()
            && let (Some(p), Some(eval)) = (&view.allowed.pick, &view.pick_eval)
        {
            rows.push(TableRow::from_eval(
                format!("Picked ({})", p.rule.name()),
                eval,
                k,
            ));
        }
        if let Some(evals) = self.presets.value() {
            rows.extend(
                evals
                    .iter()
                    .map(|(n, e)| TableRow::from_eval(n.clone(), e, k)),
            );
        }
        rows.extend(
            self.point
                .value()
                .map(|p| TableRow::from_eval("Operating point", &p.eval, k)),
        );
        rows
    }

    /// The report of the current model, extraction, diagnostics (once
    /// complete), the constrained optimum (with an a_peak limit) and Table I (the app's JSON, CSV and Markdown exports),
    /// for the k of the last update.
    pub fn report(&self) -> Option<Report> {
        let model = self.model()?;
        let report = Report::with_rows(model, self.extraction(), self.k, self.table_rows());
        // The diagnostics once complete (a partial bootstrap is no summary).
        let mut report = match self.diagnostics().filter(|d| d.complete()) {
            Some(d) => report.with_diagnostics(d.diagnostics.clone(), d.about.clone()),
            None => report,
        };
        if let (Some(key), Some(found)) = (self.constrained.key(), self.constrained.value()) {
            let limit = f64::from_bits(key.limit);
            report.constrained = Some(Constrained::from_refined(model, limit, found.as_ref()));
        }
        report.allowed = self.allowed().map(|v| v.allowed.clone());
        Some(report)
    }

    /// Why the extraction failed, if it did.
    pub fn extraction_error(&self) -> Option<&str> {
        self.extraction.error()
    }

    /// Every model demo regenerated at the operating point.
    pub fn paths(&self) -> &[Rollout] {
        self.point.value().map_or(&[], |p| p.paths.as_slice())
    }

    /// Every demo's orientation regenerated at the operating point, in the
    /// model's order (`None` for a demo without orientation; empty before
    /// the first evaluation).
    pub fn turns(&self) -> &[Option<OrientationRollout>] {
        self.point.value().map_or(&[], |p| p.turns.as_slice())
    }

    /// The RL run, if one was started: what it trains and how far it is.
    pub fn rl(&self) -> Option<(&RlRequest, &RlProgress)> {
        self.rl_request.as_ref().zip(self.rl.value())
    }

    /// How many times each stage was computed.
    pub fn runs(&self) -> StageRuns {
        self.runs
    }

    /// Whether any background work is under way.
    pub fn busy(&self) -> bool {
        self.loading()
            || self.landscape_running()
            || self.model.running()
            || self.landscape_awaits_frame()
            || self.extracting()
            || self.diagnosing()
            || self.rl.running()
    }

    /// What the executor's pool of workers has done (zeros without one).
    pub fn worker_stats(&self) -> WorkerStats {
        self.runner.worker_stats()
    }

    /// Work done on the caller's thread by the landscape (the browser's
    /// page thread).
    pub fn landscape_page_time(&self) -> PageTime {
        self.landscape.page_time()
    }

    /// Work done on the caller's thread by the diagnostics (the browser's
    /// page thread).
    pub fn diagnostics_page_time(&self) -> PageTime {
        self.diagnostics.page_time()
    }

    /// What the window should say where the landscape goes.
    pub fn status(&self) -> Status {
        status_of(self)
    }

    fn landscape_cancelled(&self) -> bool {
        self.landscape.cancelled()
    }

    fn landscape_failed(&self) -> bool {
        self.landscape.died()
    }

    fn model_error(&self) -> Option<&str> {
        match self.model.value() {
            Some(Err(why)) => Some(why),
            _ => self.model.error(),
        }
    }

    /// The model built, if any.
    pub(crate) fn built(&self) -> Option<&Built> {
        self.model.value().and_then(|b| b.as_ref().ok())
    }
}

/// The status of `session`.
fn status_of(session: &Session) -> Status {
    if session.slots.is_empty() {
        return Status::NoSources;
    }
    if session.demos.is_empty() {
        return if session.loading() {
            Status::Loading
        } else {
            Status::NoDemos
        };
    }
    if let Some(why) = session.model_error() {
        return Status::NoUsableDemo(why.to_owned());
    }
    let (done, total) = session
        .shown()
        .map_or((0, 0), |s| (s.snapshot.done, s.snapshot.total));
    if session.landscape_running() {
        Status::Computing(done, total)
    } else if total > 0 && done == total {
        Status::Ready
    } else if session.landscape_cancelled() {
        Status::Cancelled(done, total)
    } else if session.landscape_failed() {
        Status::Stopped(done, total)
    } else if session.model().is_none() || session.landscape_awaits_frame() {
        // Not built yet (the first update has not run), or the landscape
        // starts at the next update (`Session::pace_by_frames`).
        Status::Computing(0, 0)
    } else {
        Status::NoLandscape
    }
}
