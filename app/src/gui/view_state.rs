//! What the views remember between frames that is not a setting and not
//! the session's: the selected demo, the time cursor, the 3D camera, the
//! heat maps' textures, the RL panel's choices, text being typed.

use dmpscope_core::Model;
use dmpscope_core::landscape::grid::Grid;
use dmpscope_core::load::options::SegmentSettings;
use eframe::{egui, egui_wgpu};

use super::commands::Map;
use super::heatmap::Cache;
use super::view3d::View3d;
use crate::session::Session;

/// The RL panel's choices.
#[derive(Clone, Debug)]
pub struct RlChoices {
    /// 0: the operating point, 1: the extracted gains, 2 + i: preset i.
    pub gains: usize,
    /// Decisions to train.
    pub steps: usize,
    /// The seed.
    pub seed: u64,
    /// Decisions per episode and the action mode.
    pub options: dmpscope_core::rl::env::EnvOptions,
}

impl Default for RlChoices {
    fn default() -> Self {
        Self {
            gains: 1,
            steps: dmpscope_core::rl::ppo::DEFAULT_DECISIONS,
            seed: 1,
            options: dmpscope_core::rl::env::EnvOptions::default(),
        }
    }
}

/// What the right panel shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RightTab {
    /// The selected demo's position, velocity and acceleration.
    #[default]
    Demo,
    /// Every demo's standardised forcing term and sigma_f.
    Forcing,
    /// The Pareto front of (sum d, S).
    TradeOff,
    /// The demo or skill run at a new start, goal and duration.
    Generalised,
}

/// The views' state.
pub struct ViewState {
    /// The demo shown in the plots (a model demo index).
    pub selected: usize,
    /// The time cursor shared by the 3D view and the plots, unit time.
    pub t: f64,
    /// The new target's run's cursor, unit time (with playback in real
    /// time it follows the run's own duration).
    pub t_target: f64,
    /// Playback.
    pub playback: super::playback::Playback,
    /// The 3D view's camera and toggles.
    pub view3d: View3d,
    /// The heat maps' textures: J, sum d, S, E, the chosen small map.
    pub maps: [Cache; 5],
    /// The chosen small map (S by default; two by two, a quantity other
    /// than sum d, S and E).
    pub second_map: Map,
    /// What the right panel shows.
    pub right: RightTab,
    /// The Demo tab plots the orientation (demos with one) instead of the
    /// position.
    pub orientation_plots: bool,
    /// The demo under the pointer last frame (a model demo index),
    /// highlighted in the forcing terms, the 3D view and the demos list.
    pub hovered: Option<usize>,
    /// The demo under the pointer this frame, as the views find it.
    pub hovering: Option<usize>,
    /// The Pareto front of the landscape shown, computed once per snapshot.
    pub pareto: super::tradeoff::FrontCache,
    /// The RL panel's choices.
    pub rl: RlChoices,
    /// The frame filter as typed (applied on Enter or leaving the field).
    pub frames_text: String,
    /// The Recording section's timelines of continuous takes.
    pub timelines: super::timeline::TimelineCache,
    /// The fixed frame as typed.
    pub fixed_frame_text: String,
    /// The topic patterns as typed.
    pub topics_text: String,
    /// The exclude patterns as typed.
    pub exclude_text: String,
    /// The segmentation thresholds, kept while demos are not segmented.
    pub segment: SegmentSettings,
    /// Where the gain presets' buttons, the "New target" tab and its
    /// switch were drawn last frame, by name (what the browser tests click).
    pub click_targets: std::collections::BTreeMap<&'static str, egui::Rect>,
    /// The pinned gain sets and what they show (issue 45).
    pub pins: super::pins::Pins,
    /// The Compare section's typed gains (`DM:KM`) and its last error.
    pub pin_text: String,
    /// Why the last pin was refused.
    pub pin_error: Option<String>,
    /// Table I's panel shows the pinned sets' comparison.
    pub compare_table: bool,
    /// The pinned sets the Demo tab's plots drew last frame (tests).
    pub plot_pin_lines: usize,
    /// The empty landscape the maps draw before the first snapshot.
    pub blank_maps: BlankMaps,
    /// The model the views were set up for.
    model_seen: Option<u64>,
}

/// An empty landscape for the maps to draw before the first snapshot of a
/// model's, made once per model and grid.
#[derive(Default)]
pub struct BlankMaps {
    made: Option<(Option<u64>, Grid, crate::session::Shown)>,
}

impl BlankMaps {
    /// The empty landscape of `grid` for `model` (version `version`).
    pub fn for_model(
        &mut self,
        model: &Model,
        version: Option<u64>,
        grid: Grid,
    ) -> &crate::session::Shown {
        let fresh = matches!(&self.made, Some((v, g, _)) if *v == version && *g == grid);
        if !fresh {
            self.made = None;
        }
        let (_, _, shown) = self
            .made
            .get_or_insert_with(|| (version, grid, crate::session::Shown::blank(model, grid)));
        shown
    }
}

impl ViewState {
    /// The views' state, drawing the 3D view with `render_state` if any.
    pub fn new(render_state: Option<&egui_wgpu::RenderState>) -> Self {
        Self {
            selected: 0,
            t: 0.5,
            t_target: 0.5,
            playback: super::playback::Playback::default(),
            view3d: View3d::new(render_state),
            maps: Default::default(),
            second_map: Map::Quantity(dmpscope_core::landscape::quantity::Quantity::S),
            right: RightTab::default(),
            orientation_plots: false,
            hovered: None,
            hovering: None,
            pareto: Default::default(),
            rl: RlChoices::default(),
            frames_text: String::new(),
            topics_text: String::new(),
            fixed_frame_text: String::new(),
            timelines: Default::default(),
            exclude_text: String::new(),
            segment: SegmentSettings::default(),
            click_targets: std::collections::BTreeMap::new(),
            pins: super::pins::Pins::default(),
            pin_text: String::new(),
            pin_error: None,
            compare_table: false,
            plot_pin_lines: 0,
            blank_maps: BlankMaps::default(),
            model_seen: None,
        }
    }

    /// Ends a frame's hovering: what was found becomes what is
    /// highlighted; returns whether that changed (a repaint shows it).
    pub fn end_hover(&mut self) -> bool {
        let changed = self.hovered != self.hovering;
        self.hovered = self.hovering.take();
        changed
    }

    /// Follows a new model: the camera fits it again and the selection
    /// stays inside it.
    pub fn follow(&mut self, session: &Session) {
        let id = session.model_version();
        if id != self.model_seen {
            self.model_seen = id;
            self.view3d.reset();
        }
        let n = session.model().map_or(0, |m| m.demos().len());
        self.selected = self.selected.min(n.saturating_sub(1));
    }
}
