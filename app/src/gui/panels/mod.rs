//! The panels: functions `fn(&mut egui::Ui, &mut PanelCtx)`, each given the
//! session (read only), the settings and the views' state in a
//! [`PanelCtx`], pushing what they ask for as [`Command`]s that the app
//! applies after the frame's layout.
//!
//! [`Command`]: super::Command

mod allowed;
mod central;
mod compare;
mod compare_table;
mod context;
mod demos;
mod diagnostics;
mod gains;
mod generalise;
mod loading;
mod orientation_target;
mod plots_panel;
mod recording;
mod rl;
mod rl_table;
mod settings;
mod side;
mod table;
mod top_bar;

pub use central::central_ui;
pub use context::PanelCtx;
pub use plots_panel::plots_ui;
pub use side::side_ui;
pub use table::table_ui;
pub use top_bar::top_bar_ui;
