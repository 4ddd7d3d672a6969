//! The middle of the window: the J map with the sum d and S maps beside it
//! (or, while there is no landscape, what the session is doing and what to
//! do), and the 3D view below.

use dmpscope_core::presets::PAPER_PRESETS;
use eframe::egui::{self, Color32};

use super::super::commands::{Command, Map};
use super::super::heatmap::{self, MapInput, Marker};
use super::super::view_state::ViewState;
use crate::session::{Session, Settings, Shown, Status};

/// The central panel.
pub fn central_ui(
    ui: &mut egui::Ui,
    session: &Session,
    s: &mut Settings,
    view: &mut ViewState,
) -> Vec<Command> {
    let height = (ui.available_height() * 0.5).clamp(200.0, 420.0);
    match session.shown() {
        Some(shown) => maps(ui, session, shown, s, view, height),
        None => status(ui, &session.status(), height),
    }
    if let Some(model) = session.model() {
        view.view3d.toggles(ui, model.demos().len());
        let learned = session
            .rl()
            .and_then(|(r, p)| p.greedy.as_ref().map(|g| (r.demo, g.path.as_slice())));
        view.view3d
            .show(ui, model, session.paths(), view.selected, view.t, learned);
    }
    Vec::new()
}

/// Where the maps go while there are none: the session's status in words.
fn status(ui: &mut egui::Ui, status: &Status, height: f32) {
    ui.allocate_ui(egui::vec2(ui.available_width(), height), |ui| {
        ui.horizontal_wrapped(|ui| {
            if matches!(status, Status::Loading | Status::Computing(..)) {
                ui.spinner();
            }
            let colour = match status {
                Status::NoDemos
                | Status::NoUsableDemo(_)
                | Status::NoLandscape
                | Status::Stopped(..) => Color32::from_rgb(240, 180, 80),
                _ => ui.visuals().text_color(),
            };
            ui.colored_label(colour, status.describe());
        });
    });
}

fn maps(
    ui: &mut egui::Ui,
    session: &Session,
    shown: &Shown,
    s: &mut Settings,
    view: &mut ViewState,
    height: f32,
) {
    let grid = shown.grid();
    let mut markers: Vec<Marker> = PAPER_PRESETS
        .iter()
        .map(|p| Marker {
            label: p.name.to_owned(),
            dm: p.dm,
            km: p.km,
            colour: Color32::from_rgb(255, 160, 200),
        })
        .collect();
    if let Some(x) = session.extraction() {
        markers.push(Marker {
            label: "optimum".into(),
            dm: x.eval.dm,
            km: x.eval.km,
            colour: Color32::from_rgb(255, 90, 60),
        });
    }
    let n_km = grid.km.n;
    let readout = |i: usize, j: usize| {
        let idx = i * n_km + j;
        (shown.d_sum[idx], shown.s[idx], shown.j[idx])
    };
    let log_colour = s.log_colour;
    let mut op = s.op;
    let [c_j, c_d, c_s] = &mut view.maps;
    let mut map = |ui: &mut egui::Ui, cache, which: Map, side: f32| {
        let input = MapInput {
            title: which.title(),
            values: which.values(shown),
            key: (
                shown.version,
                if which == Map::J {
                    shown.k.to_bits()
                } else {
                    0
                },
            ),
            grid,
            log_colour,
            readout: &readout,
        };
        heatmap::show(ui, cache, &input, &markers, &mut op, side);
    };
    // J on the left, sum d and S stacked on the right, within `height`.
    let width = ui.available_width();
    let big = heatmap::side_for(egui::vec2(width * 0.5, height));
    let small = heatmap::side_for(egui::vec2(width * 0.5, height * 0.5));
    ui.horizontal_top(|ui| {
        ui.vertical(|ui| map(ui, c_j, Map::J, big));
        ui.vertical(|ui| {
            map(ui, c_d, Map::DSum, small);
            map(ui, c_s, Map::S, small);
        });
    });
    s.op = op;
}
