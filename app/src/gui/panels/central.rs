//! The middle of the window: the J map with the sum d, S, E and one more
//! quantity's maps beside it (two by two where wide enough, else sum d
//! above a chosen one)
//! (or, while there is no landscape, what the session is doing and what to
//! do), and the 3D view below.

use dmpscope_core::landscape::grid::Grid;
use dmpscope_core::landscape::quantity;
use dmpscope_core::landscape::quantity::Quantity;
use dmpscope_core::report::presets::PAPER_PRESETS;
use eframe::egui::{self, Color32};

use super::super::commands::Map;
use super::super::heatmap::{self, MapInput, Marker};
use super::super::view_state::ViewState;
use super::super::view3d::{Handle, HandleMove, Layers, TargetOverlay};
use super::PanelCtx;
use crate::session::{Command as SessionCommand, Session, Settings, Shown, Status};

/// The least side of the small maps laid out two by two (else stacked).
const MIN_QUAD_SIDE: f32 = 110.0;

/// The central panel.
pub fn central_ui(ui: &mut egui::Ui, cx: &mut PanelCtx<'_>) {
    let session = cx.session;
    let height = (ui.available_height() * 0.5).clamp(200.0, 420.0);
    let status_now = session.status();
    let computing = matches!(status_now, Status::Computing(..));
    match (session.shown(), session.model()) {
        (Some(shown), _) => maps(ui, session, shown, cx.settings, cx.view, height),
        // Before the first snapshot the maps are drawn empty: the layout
        // does not move when it arrives, the operating point can be moved
        // already, and their first layout (text, 5 ms in the browser) is
        // not in the frame that takes the first snapshot.
        (None, Some(model)) if computing => {
            // Out of the view while the maps borrow it.
            let mut blank = std::mem::take(&mut cx.view.blank_maps);
            let version = session.model_version();
            let shown = blank.for_model(model, version, cx.settings.grid);
            maps(ui, session, shown, cx.settings, cx.view, height);
            cx.view.blank_maps = blank;
        }
        (None, _) => status(ui, &status_now, height),
    }
    #[cfg(feature = "testing")]
    crate::gui::test_hooks::mark("maps");
    if let Some(model) = session.model() {
        let view = &mut *cx.view;
        view.view3d
            .toggles(ui, model.demos().len(), model.has_orientation());
        let learned = session
            .rl()
            .and_then(|(r, p)| p.greedy.as_ref().map(|g| (r.demo, g.path.as_slice())));
        // The demo hovered anywhere is the one the 3D view highlights.
        let highlighted = view.hovered.unwrap_or(view.selected);
        let generalised = session.generalised().and_then(Result::ok);
        let overlay = generalised.map(|g| TargetOverlay {
            path: &g.out.unit.y,
            band: &g.out.band,
            start: g.out.start,
            goal: g.out.goal,
            turns: g.out.orientation.as_ref().map(|o| o.q.as_slice()),
            t: view.t_target,
        });
        let pins = view.pins.scene();
        let layers = Layers {
            learned,
            overlay: overlay.as_ref(),
            pins: &pins,
        };
        #[cfg(feature = "testing")]
        crate::gui::test_hooks::mark("3d toggles");
        let moved = view.view3d.show(
            ui,
            model,
            (session.paths(), session.turns()),
            highlighted,
            view.t,
            layers,
        );
        #[cfg(feature = "testing")]
        crate::gui::test_hooks::mark("3d view");
        if let (Some(m), Some(spec)) = (moved, session.generalise_spec()) {
            let mut spec = *spec;
            match m {
                HandleMove::Moved {
                    handle: Handle::Start,
                    to,
                } => spec.target.start = Some(to),
                HandleMove::Moved {
                    handle: Handle::Goal,
                    to,
                } => spec.target.goal = Some(to),
                HandleMove::Turned(v) => {
                    // The goal orientation the run went to, turned in the
                    // scene's frame.
                    if let Some(q) = generalised.and_then(|g| g.out.orientation_goal) {
                        let turn = dmpscope_core::rotation::exp(v.map(|c| 0.5 * c));
                        spec.target.goal_orientation = Some(dmpscope_core::rotation::normalised(
                            dmpscope_core::rotation::mul(turn, q),
                        ));
                    }
                }
            }
            cx.push(SessionCommand::SetGeneralise(Some(spec)));
        }
    }
}

/// Where the maps go while there are none: the session's status in words.
fn status(ui: &mut egui::Ui, status: &Status, height: f32) {
    ui.allocate_ui(egui::vec2(ui.available_width(), height), |ui| {
        ui.horizontal_wrapped(|ui| {
            // While loading the top bar shows the bytes read; a spinner
            // here would ask for a frame each frame.
            if matches!(status, Status::Computing(..)) {
                crate::gui::busy::spinner(ui);
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

/// The J map and the small maps beside it; keeps the operating point moved
/// on them and the small map chosen.
fn maps(
    ui: &mut egui::Ui,
    session: &Session,
    shown: &Shown,
    s: &mut Settings,
    view: &mut ViewState,
    height: f32,
) {
    let grid = shown.grid();
    let mut markers = markers(session);
    markers.extend(view.pins.list().iter().map(|p| Marker {
        label: p.name.clone(),
        dm: p.dm,
        km: p.km,
        colour: Color32::from_rgb(p.colour[0], p.colour[1], p.colour[2]),
    }));
    let cloud: Vec<(f64, f64)> = session
        .diagnostics()
        .map(|d| d.cloud.iter().map(|o| (o.dm, o.km)).collect())
        .unwrap_or_default();
    let region = session
        .allowed()
        .map(|v| v.allowed.acceptable.mask.as_slice())
        .filter(|m| m.len() == grid.len());
    let data = MapsData {
        shown,
        grid,
        markers: &markers,
        cloud: &cloud,
        region,
        log_colour: s.log_colour,
        limit: s.a_peak_limit,
    };
    let mut op = s.op;
    let layout = Layout::of(ui.available_width(), height, session, view.second_map);
    let mut chosen = layout.shown;
    lay_out_maps(ui, &data, &mut view.maps, &layout, &mut chosen, &mut op);
    // Only the user's choice is kept (not what a layout showed instead).
    if chosen != layout.shown {
        view.second_map = chosen;
    }
    // The d_rot map is computed when it is first shown.
    if chosen == Map::Quantity(Quantity::DRotSum) {
        s.dmp.orientation_map = true;
    }
    s.op = op;
}

/// J on the left; on the right the small maps two by two or stacked, as
/// `layout` says, the chosen one with its buttons.
fn lay_out_maps(
    ui: &mut egui::Ui,
    data: &MapsData<'_>,
    caches: &mut [heatmap::Cache; 5],
    layout: &Layout,
    chosen: &mut Map,
    op: &mut (f64, f64),
) {
    let [c_j, c_d, c_s, c_e, c_x] = caches;
    let mut map = |ui: &mut egui::Ui, cache: &mut heatmap::Cache, which: Map, side: f32| {
        data.show(ui, cache, which, side, op);
    };
    ui.horizontal_top(|ui| {
        ui.vertical(|ui| map(ui, c_j, Map::J, layout.big));
        ui.vertical(|ui| match layout.quad {
            Some(side) => {
                ui.horizontal_top(|ui| {
                    ui.vertical(|ui| map(ui, c_d, Map::Quantity(Quantity::DSum), side));
                    ui.vertical(|ui| map(ui, c_s, Map::Quantity(Quantity::S), side));
                });
                ui.horizontal_top(|ui| {
                    ui.vertical(|ui| map(ui, c_e, Map::Quantity(Quantity::ESum), side));
                    ui.vertical(|ui| {
                        choose(ui, &layout.others, chosen);
                        map(ui, c_x, *chosen, side);
                    });
                });
            }
            None => {
                map(ui, c_d, Map::Quantity(Quantity::DSum), layout.small);
                choose(ui, &layout.others, chosen);
                map(ui, c_s, *chosen, layout.small);
            }
        });
    });
}

/// What every map shares: the landscape shown, its overlays, the colour
/// scale and the a_peak limit.
struct MapsData<'a> {
    /// The landscape shown.
    shown: &'a Shown,
    /// Its grid.
    grid: Grid,
    /// The labelled markers.
    markers: &'a [Marker],
    /// The bootstrap optima, drawn on J.
    cloud: &'a [(f64, f64)],
    /// The acceptable region, where it fits the grid.
    region: Option<&'a [bool]>,
    /// Colour on a log scale.
    log_colour: bool,
    /// The a_peak limit, masking J.
    limit: Option<f64>,
}

impl MapsData<'_> {
    /// Shows map `which` (`side` pixels square); a click or drag on it moves `op`.
    fn show(
        &self,
        ui: &mut egui::Ui,
        cache: &mut heatmap::Cache,
        which: Map,
        side: f32,
        op: &mut (f64, f64),
    ) {
        let (shown, limit) = (self.shown, self.limit);
        let n_km = self.grid.km.n;
        let readout = |i: usize, j: usize| {
            let idx = i * n_km + j;
            (shown.j[idx], quantity::ALL.map(|q| shown.values(q)[idx]))
        };
        let on_j = which == Map::J;
        let title = match (which, limit) {
            (Map::J, Some(l)) => format!("{} (grey: a_peak > {l} m/s²)", which.title()),
            _ => which.title().to_owned(),
        };
        let input = MapInput {
            title: &title,
            values: which.values(shown),
            // J's texture follows k; a quantity's is its own (the sign bit
            // keeps the two apart: k is never negative).
            key: (
                shown.version,
                match which {
                    Map::J => shown.k.to_bits(),
                    Map::Quantity(q) => (1 << 63) | q.index() as u64,
                },
            ),
            grid: self.grid,
            log_colour: self.log_colour,
            readout: &readout,
            mask: limit
                .filter(|_| on_j)
                .map(|l| (shown.values(Quantity::APeak), l)),
            iso_zeta: true,
            cloud: if on_j { self.cloud } else { &[] },
            region: self.region,
            note: (shown.snapshot.done == 0).then_some("computing…"),
            labels: on_j,
        };
        heatmap::show(ui, cache, &input, self.markers, op, side);
    }
}

/// Where the maps go: J on the left; on the right, where the window is
/// wide enough, two by two (sum d and S, then E and a chosen quantity,
/// a_peak by default), else sum d above a chosen one (S by default, or E,
/// a_peak), within the height given.
struct Layout {
    /// J's side.
    big: f32,
    /// The small maps' side two by two, where they fit.
    quad: Option<f32>,
    /// The small maps' side stacked.
    small: f32,
    /// What the chosen map may show (d_rot where a demo has orientation).
    others: Vec<Quantity>,
    /// What it shows: the user's choice where offered, else the first.
    shown: Map,
}

impl Layout {
    fn of(width: f32, height: f32, session: &Session, choice: Map) -> Self {
        let quad = heatmap::side_for(egui::vec2(width * 0.25 - 6.0, height * 0.5 - 12.0));
        let quad = (quad >= MIN_QUAD_SIDE).then_some(quad);
        let fixed: &[Quantity] = if quad.is_some() {
            &[Quantity::DSum, Quantity::S, Quantity::ESum]
        } else {
            &[Quantity::DSum]
        };
        let oriented = session.model().is_some_and(|m| m.has_orientation());
        let others: Vec<Quantity> = quantity::ALL
            .into_iter()
            .filter(|q| !fixed.contains(q) && (oriented || *q != Quantity::DRotSum))
            .collect();
        let shown = match choice {
            Map::Quantity(q) if others.contains(&q) => choice,
            _ => others.first().map_or(choice, |&q| Map::Quantity(q)),
        };
        Self {
            big: heatmap::side_for(egui::vec2(width * 0.5, height)),
            quad,
            small: heatmap::side_for(egui::vec2(width * 0.5, height * 0.5 - 12.0)),
            others,
            shown,
        }
    }
}

/// Buttons that choose which of `others` a small map shows.
fn choose(ui: &mut egui::Ui, others: &[Quantity], chosen: &mut Map) {
    ui.horizontal(|ui| {
        for &q in others {
            ui.selectable_value(chosen, Map::Quantity(q), q.about().label);
        }
    });
}

/// The paper's gains, the optimum, the S minimum and the constrained
/// optimum as labelled markers.
fn markers(session: &Session) -> Vec<Marker> {
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
        let picked = session
            .allowed()
            .and_then(|v| v.allowed.pick.as_ref())
            .is_some_and(|p| (p.dm, p.km) == (x.eval.dm, x.eval.km));
        markers.push(Marker {
            label: if picked { "optimum = pick" } else { "optimum" }.into(),
            dm: x.eval.dm,
            km: x.eval.km,
            colour: Color32::from_rgb(255, 90, 60),
        });
    }
    if let Some(m) = session.diagnostics().and_then(|d| d.diagnostics.s_minimum) {
        markers.push(Marker {
            label: "S min".into(),
            dm: m.dm,
            km: m.km,
            colour: Color32::from_rgb(120, 230, 255),
        });
    }
    let optimum = session.extraction().map(|x| (x.eval.dm, x.eval.km));
    if let Some(p) = session.allowed().and_then(|v| v.allowed.pick.as_ref())
        && optimum != Some((p.dm, p.km))
    {
        markers.push(Marker {
            label: format!("pick ({})", p.rule.name()),
            dm: p.dm,
            km: p.km,
            colour: super::allowed::PICK_COLOUR,
        });
    }
    if let Some(Some(c)) = session.constrained() {
        markers.push(Marker {
            label: "constrained".into(),
            dm: c.dm,
            km: c.km,
            colour: Color32::from_rgb(255, 230, 90),
        });
    }
    markers
}
