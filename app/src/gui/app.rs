//! [`DmpApp`]: the settings, the session, the views' state and the
//! dialogs. Each frame it hands files that arrived (a drop, a dialog) to the
//! session, brings the session up to date, lays the panels out, and applies
//! what the panels asked for after the layout.

use std::path::PathBuf;

use dmpscope_core::Notice;
use eframe::egui;
use eframe::egui_wgpu;

use super::commands::Command;
use super::file_dialog::{Answer, Dialogs};
use super::frame_log::FrameLog;
use super::panels;
use super::view_state::ViewState;
use crate::session::{self, Runner, Session, Settings, Source};

/// Where eframe keeps the settings.
pub const SETTINGS_KEY: &str = "dmpscope-settings";

/// The app.
pub struct DmpApp {
    /// The user's settings (persisted).
    pub settings: Settings,
    /// The pipeline's state.
    pub(super) session: Session,
    /// What the views remember.
    pub view: ViewState,
    dialogs: Dialogs,
    frame_log: Option<FrameLog>,
    /// Whether the renderer's clear paints the panels' background (the
    /// eframe runs, native and web) instead of each panel filling its rect
    /// (test harnesses, whose renderer clears to transparent).
    clear_paints_background: bool,
    /// Gain sets `--pin` named, pinned once they are known.
    pending_pins: Option<String>,
    #[cfg(feature = "testing")]
    pub(super) frame_watch: super::test_hooks::FrameWatch,
    /// The browser tests' requests and the state they read.
    #[cfg(feature = "testing")]
    pub(super) hooks: Option<super::test_hooks::SharedHooks>,
}

mod exports;
mod pins;

impl DmpApp {
    /// The app on `files` (the bundled planted8 sample when empty: demos that
    /// determine the gains; reach10 is one click away in Samples), with settings
    /// restored from eframe's storage and background work on `runner` (the
    /// platform's executor: threads natively, Web Workers in the browser).
    pub fn new(cc: &eframe::CreationContext<'_>, files: Vec<PathBuf>, runner: Runner) -> Self {
        let settings = cc
            .storage
            .and_then(|s| eframe::get_value::<Settings>(s, SETTINGS_KEY))
            .unwrap_or_default();
        let last = files.last().cloned();
        let sources = files.into_iter().map(Source::Path).collect();
        let mut app = Self::with_runner(settings, sources, runner)
            .with_render_state(cc.wgpu_render_state.as_ref())
            .with_background_from_clear();
        app.dialogs.remember(last);
        app
    }

    /// The app on `sources` (the bundled planted8 sample when empty) with explicit
    /// settings and runner (tests use [`Runner::inline`]).
    pub fn with_runner(settings: Settings, sources: Vec<Source>, runner: Runner) -> Self {
        // In the browser a new model's first layout and the landscape's
        // start (the workers' model) fall in different frames.
        Self::build(settings, sources, runner, cfg!(target_arch = "wasm32"))
    }

    /// As [`DmpApp::with_runner`], a new model's landscape started a frame
    /// after the model is first shown, as in the browser (tests).
    pub fn with_runner_paced(settings: Settings, sources: Vec<Source>, runner: Runner) -> Self {
        Self::build(settings, sources, runner, true)
    }

    fn build(settings: Settings, sources: Vec<Source>, runner: Runner, paced: bool) -> Self {
        let sources = if sources.is_empty() {
            vec![Source::planted_sample()]
        } else {
            sources
        };
        let mut session = Session::new(runner);
        session.pace_by_frames(paced);
        session.apply(session::Command::AddSources(sources));
        session.update(&settings);
        Self {
            settings,
            session,
            view: ViewState::new(None),
            dialogs: Dialogs::default(),
            frame_log: FrameLog::from_env(),
            clear_paints_background: false,
            pending_pins: None,
            #[cfg(feature = "testing")]
            frame_watch: Default::default(),
            #[cfg(feature = "testing")]
            hooks: None,
        }
    }

    /// Draws the 3D view with the wgpu pipeline of `render_state` (none:
    /// the view says it needs one).
    pub fn with_render_state(mut self, render_state: Option<&egui_wgpu::RenderState>) -> Self {
        self.view.view3d = super::view3d::View3d::new(render_state);
        self
    }

    /// Leaves the panels' background to the renderer's clear
    /// ([`eframe::App::clear_color`] is the panels' fill), as [`Self::new`]
    /// does: the panels then draw no fill of their own. Under software
    /// rasterisers (SwiftShader in a browser without a GPU, lavapipe) each
    /// pixel egui fills costs as much as a texture lookup with both of its
    /// shader's branches, so the window-sized fill was about a third of
    /// a frame there (docs/browser.md).
    pub fn with_background_from_clear(mut self) -> Self {
        self.clear_paints_background = true;
        self
    }

    /// Opens files with the app's own browser only, starting in `start`
    /// (tests: a system dialog would wait for a person).
    pub fn with_app_browser(mut self, start: Option<PathBuf>) -> Self {
        self.dialogs = Dialogs::app_browser_only(start);
        self
    }

    /// What the views remember (tests read it: the selection, where the 3D
    /// view drew its handles).
    pub fn view(&self) -> &ViewState {
        &self.view
    }

    /// The session (read only: change it through [`DmpApp::apply`] or the
    /// settings).
    pub fn session(&self) -> &Session {
        &self.session
    }

    /// Applies a command as a panel would, then brings the session up to
    /// date.
    pub fn apply(&mut self, command: Command, ctx: &egui::Context) {
        self.run(command, ctx);
        self.session.update(&self.settings);
    }

    fn run(&mut self, command: Command, ctx: &egui::Context) {
        let wake = {
            let ctx = ctx.clone();
            move || ctx.request_repaint()
        };
        match command {
            Command::Session(c) => self.session.apply(c),
            Command::Open { folder } => self.dialogs.open(folder, wake),
            Command::Browse => self.dialogs.browse(false),
            Command::Export(e) => match self.export(e) {
                Ok((name, bytes)) => self.dialogs.save(&name, bytes, wake),
                Err(e) => self.session.apply(session::Command::Say(Notice::error(e))),
            },
            Command::Select(i) => self.view.selected = i,
        }
    }

    /// Files dropped on the window (paths natively, bytes in the browser)
    /// and the dialogs' answers, as commands.
    fn take_inputs(&mut self, ctx: &egui::Context) -> Vec<Command> {
        let dropped: Vec<egui::DroppedFileHandle> = ctx.input(|i| i.raw.dropped_files.clone());
        let mut answers = self.dialogs.poll();
        if cfg!(target_arch = "wasm32") {
            // The browser reads dropped files asynchronously: they come back
            // through the dialogs.
            let ctx = ctx.clone();
            let now = self
                .dialogs
                .read_dropped(dropped, move || ctx.request_repaint());
            if !now.is_empty() {
                answers.push(Answer::Open(now));
            }
        } else {
            let paths: Vec<Source> = dropped
                .iter()
                .map(|f| f.path().to_path_buf())
                .filter(|p| !p.as_os_str().is_empty())
                .map(Source::Path)
                .collect();
            if !paths.is_empty() {
                answers.push(Answer::Open(paths));
            }
        }
        answers.extend(self.dialogs.show_browser(ctx));
        let mut out = Vec::new();
        for answer in answers {
            match answer {
                Answer::Open(sources) => {
                    if let Some(Source::Path(p)) = sources.last() {
                        self.dialogs.remember(Some(p.clone()));
                    }
                    out.push(session::Command::AddSources(sources).into());
                }
                Answer::Say(n) => out.push(session::Command::Say(n).into()),
                Answer::NoOpenDialog { folder } => {
                    out.push(session::Command::Say(no_system_dialog()).into());
                    self.dialogs.browse(folder);
                }
                Answer::NoSaveDialog { name, bytes } => {
                    out.push(session::Command::Say(no_system_dialog()).into());
                    self.dialogs.browse_save(&name, bytes);
                }
            }
        }
        out
    }
}

fn no_system_dialog() -> Notice {
    Notice::info(
        "no system file dialog here (it needs an xdg-desktop-portal or zenity): \
         using dmpscope's own file browser",
    )
}

impl DmpApp {
    /// The five panels; returns the commands they pushed. `left_out`:
    /// the [`part`]s not drawn (the browser probe's; none otherwise).
    fn panels_ui(&mut self, ui: &mut egui::Ui, left_out: u32) -> Vec<Command> {
        let shown = |bit: u32| left_out & (1 << bit) == 0;
        let (side_frame, central_frame) = self.panel_frames(ui.style());
        // One context for every panel: they change the settings and the
        // views' state in place and push what else they ask for.
        let mut cx = panels::PanelCtx {
            session: &self.session,
            settings: &mut self.settings,
            view: &mut self.view,
            out: Vec::new(),
        };
        egui::Panel::top("top").frame(side_frame).show(ui, |ui| {
            if shown(part::TOP_BAR) {
                panels::top_bar_ui(ui, &mut cx);
            }
        });
        #[cfg(feature = "testing")]
        super::test_hooks::mark("top");
        // The docked panels claim their whole size, so the layout does not
        // depend on what the first frames had to show (files load off the
        // frame).
        let docked = |panel: egui::Panel, default: f32, min: f32| {
            panel.frame(side_frame).default_size(default).min_size(min)
        };
        docked(egui::Panel::left("side"), 330.0, 280.0).show(ui, |ui| {
            claim(ui, shown(part::SIDE), |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| panels::side_ui(ui, &mut cx));
            });
        });
        #[cfg(feature = "testing")]
        super::test_hooks::mark("side");
        docked(egui::Panel::right("plots"), 380.0, 340.0).show(ui, |ui| {
            claim(ui, shown(part::PLOTS), |ui| panels::plots_ui(ui, &mut cx));
        });
        #[cfg(feature = "testing")]
        super::test_hooks::mark("plots");
        docked(egui::Panel::bottom("table"), 200.0, 150.0).show(ui, |ui| {
            claim(ui, shown(part::TABLE), |ui| panels::table_ui(ui, &mut cx));
        });
        #[cfg(feature = "testing")]
        super::test_hooks::mark("table");
        egui::CentralPanel::default()
            .frame(central_frame)
            .show(ui, |ui| {
                if shown(part::CENTRAL) {
                    panels::central_ui(ui, &mut cx);
                }
            });
        cx.out
    }

    /// The parts of the frame the browser probe asked to leave out
    /// (`window.dmpscope_hide`), after applying its other requests: frames
    /// back to back, the 3D view's drawing off.
    #[cfg(feature = "testing")]
    fn left_out(&mut self, ctx: &egui::Context) -> u32 {
        let mask = self.hooks.as_ref().map_or(0, |h| h.borrow().hide);
        if mask & (1 << part::CONTINUOUS) != 0 {
            ctx.request_repaint();
        }
        if mask & (1 << part::VIEW3D_SET) != 0 {
            self.view
                .view3d
                .set_drawing(mask & (1 << part::VIEW3D) == 0);
        }
        mask
    }

    /// Nothing is left out outside the browser tests' build.
    #[cfg(not(feature = "testing"))]
    fn left_out(&mut self, _ctx: &egui::Context) -> u32 {
        0
    }

    /// The side and central panels' frames: egui's, without their fill
    /// when the clear paints the background.
    fn panel_frames(&self, style: &egui::Style) -> (egui::Frame, egui::Frame) {
        let side = egui::Frame::side_top_panel(style);
        let central = egui::Frame::central_panel(style);
        if self.clear_paints_background {
            (
                side.fill(egui::Color32::TRANSPARENT),
                central.fill(egui::Color32::TRANSPARENT),
            )
        } else {
            (side, central)
        }
    }
}

/// Claims `ui`'s whole size and, when `shown`, adds the panel's content.
fn claim(ui: &mut egui::Ui, shown: bool, add: impl FnOnce(&mut egui::Ui)) {
    ui.set_min_size(ui.available_size());
    if shown {
        add(ui);
    }
}

/// The bits of the browser probe's mask (`web/tests/frame_probe.mjs`): the
/// parts of the frame it leaves out to measure what each costs.
pub(super) mod part {
    /// The top bar.
    pub const TOP_BAR: u32 = 0;
    /// The side panel.
    pub const SIDE: u32 = 1;
    /// The plots panel.
    pub const PLOTS: u32 = 2;
    /// The table panel.
    pub const TABLE: u32 = 3;
    /// The central panel.
    pub const CENTRAL: u32 = 4;
    /// Every panel (a label only).
    pub const EVERYTHING: u32 = 5;
    /// The 3D view's drawing (with [`VIEW3D_SET`]).
    #[cfg_attr(not(feature = "testing"), allow(dead_code))]
    pub const VIEW3D: u32 = 6;
    /// Not a part: frames back to back.
    #[cfg_attr(not(feature = "testing"), allow(dead_code))]
    pub const CONTINUOUS: u32 = 7;
    /// Not a part: set the 3D view's drawing from [`VIEW3D`].
    #[cfg_attr(not(feature = "testing"), allow(dead_code))]
    pub const VIEW3D_SET: u32 = 8;
}

impl eframe::App for DmpApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        if let Some(log) = &mut self.frame_log {
            // Only frames after the landscape is complete: the drag.
            if self.session.landscape_complete() {
                log.handles(
                    self.view
                        .view3d
                        .handles_on_screen()
                        .map(|h| h.map(|p| [p.x, p.y])),
                );
                log.frame(frame.info().cpu_usage);
            } else {
                log.reset();
            }
        }
        #[cfg(feature = "testing")]
        self.frame_watch.frame(
            self.session.landscape_running(),
            self.session.status().describe(),
            frame.info().cpu_usage,
            ctx.current_pass_index(),
        );
        let arrived = self.take_inputs(&ctx);
        for c in arrived {
            self.run(c, &ctx);
        }
        self.session.update(&self.settings);
        self.view.follow(&self.session);
        // A run at a new target of a demo follows the selected demo,
        // whichever tab is open (a new demo starts at its own target).
        if let Some(spec) = self.session.generalise_spec()
            && let session::TargetSource::Demo(i) = spec.source
            && i != self.view.selected
        {
            let mut next = session::GeneraliseSpec::demo(self.view.selected);
            next.target.scaling = spec.target.scaling;
            self.session
                .apply(session::Command::SetGeneralise(Some(next)));
            self.session.update(&self.settings);
        }
        #[cfg(feature = "testing")]
        self.serve_test_hooks(&ctx);
        #[cfg(feature = "testing")]
        super::test_hooks::mark("update");

        let left_out = self.left_out(&ctx);
        if left_out & (1 << part::EVERYTHING) != 0 {
            ui.label(format!("frame {}", ctx.cumulative_frame_nr()));
            if !ctx.will_discard() && self.session.frame_shown(self.session.model_version()) {
                ctx.request_repaint();
            }
            #[cfg(feature = "testing")]
            self.publish_test_state(&ctx);
            return;
        }
        let played = self.play(&ctx);
        self.pin_pending();
        // The pinned sets follow the model, k and the target (computed only
        // when one of them changed).
        self.view.pins.refresh(
            self.session.model().zip(self.session.model_version()),
            self.settings.k,
            self.session.generalise_spec(),
        );
        let before = self.settings.clone();
        let drawn = self.session.model_version();
        let commands = self.panels_ui(ui, left_out);
        #[cfg(feature = "testing")]
        self.frame_watch.model_drawn(drawn);
        self.after_play(played);
        let hover_moved = self.view.end_hover();
        let changed = !commands.is_empty() || self.settings != before;
        if hover_moved {
            ctx.request_repaint();
        }
        for c in commands {
            self.run(c, &ctx);
        }
        if changed {
            self.session.update(&self.settings);
            ctx.request_repaint();
        }
        // A pass egui discards (it runs `ui` again at once, in the same
        // frame: a first layout of sizes it did not know) shows nothing.
        if !ctx.will_discard() && self.session.frame_shown(drawn) {
            ctx.request_repaint();
        }
        #[cfg(feature = "testing")]
        {
            self.frame_watch.ui_done(ctx.will_discard());
            if !ctx.will_discard() {
                self.publish_test_state(&ctx);
            }
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, SETTINGS_KEY, &self.settings);
    }

    /// The panels' fill: with [`DmpApp::with_background_from_clear`] the
    /// clear is the panels' background.
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        visuals.panel_fill.to_normalized_gamma_f32()
    }
}

impl DmpApp {
    /// The durations the playback's cursors follow: the selected demo's and
    /// a new target's run's.
    fn durations(&self) -> Option<crate::gui::playback::Durations> {
        let model = self.session.model()?;
        let demo = model.demos().get(self.view.selected)?.duration_s;
        let target = self
            .session
            .generalised()
            .and_then(Result::ok)
            .map(|g| g.out.duration_s);
        Some(crate::gui::playback::Durations { demo, target })
    }

    /// Advances the playback by this frame's time (the space bar plays or
    /// pauses) and puts the cursors where it is; the cursors as set, to
    /// tell a move by hand afterwards.
    fn play(&mut self, ctx: &egui::Context) -> Option<(f64, f64)> {
        let d = self.durations()?;
        let p = &mut self.view.playback;
        if ctx.input(|i| i.key_pressed(egui::Key::Space)) && !ctx.egui_wants_keyboard_input() {
            p.toggle(d);
        }
        if p.playing {
            let dt = ctx.input(|i| f64::from(i.stable_dt)).min(0.25);
            p.advance(dt, d);
            self.view.t = p.demo_t(d);
            self.view.t_target = p.target_t(d);
            ctx.request_repaint();
        }
        Some((self.view.t, self.view.t_target))
    }

    /// Follows a cursor moved by hand (a slider, a pointer on a plot): the
    /// clock goes there, and the other cursor with it.
    fn after_play(&mut self, set: Option<(f64, f64)>) {
        let (Some(d), Some((t, t_target))) = (self.durations(), set) else {
            return;
        };
        let p = &mut self.view.playback;
        if self.view.t != t {
            p.seek(self.view.t, d);
        } else if self.view.t_target != t_target {
            let clock = if p.real_time {
                self.view.t_target * d.target.unwrap_or(d.demo)
            } else {
                self.view.t_target
            };
            p.clock = clock;
        } else {
            return;
        }
        self.view.t = p.demo_t(d);
        self.view.t_target = p.target_t(d);
    }
}
