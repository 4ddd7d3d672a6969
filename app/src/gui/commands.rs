//! What panels ask for: session commands, and what only the app can do
//! (dialogs, exports). Panels return them; the app applies them after the
//! frame's layout.

use crate::session;

/// A panel's request.
#[derive(Clone, Debug)]
pub enum Command {
    /// A request to the session.
    Session(session::Command),
    /// Open recordings with the system's dialog (a folder when `folder`);
    /// falls back to the in-app browser where there is no system dialog.
    Open {
        /// Pick a folder (rosbag2) instead of files.
        folder: bool,
    },
    /// Open recordings with the in-app file browser.
    Browse,
    /// Save an export through the save dialog.
    Export(Export),
}

impl From<session::Command> for Command {
    fn from(c: session::Command) -> Self {
        Self::Session(c)
    }
}

/// What to export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Export {
    /// A heat map as PNG.
    Map(Map),
    /// The report (gains, extraction, Table I) as JSON.
    ReportJson,
    /// Table I as CSV.
    TableCsv,
    /// Table I as Markdown.
    TableMarkdown,
    /// The DMP run at the new target, as `docs/export.md`'s JSON.
    Dmp,
}

/// One of the three heat maps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Map {
    /// J = S + k sum d.
    J,
    /// sum d.
    DSum,
    /// S.
    S,
    /// The largest peak acceleration of any demo.
    APeak,
}

impl Map {
    /// The map's title.
    pub fn title(self) -> &'static str {
        match self {
            Self::J => "J = S + k sum d",
            Self::DSum => "sum d [m]",
            Self::S => "S",
            Self::APeak => "max a_peak [m/s²]",
        }
    }

    /// The values of this map in `shown`.
    pub fn values(self, shown: &session::Shown) -> &[f64] {
        match self {
            Self::J => &shown.j,
            Self::DSum => &shown.d_sum,
            Self::S => &shown.s,
            Self::APeak => &shown.a_peak,
        }
    }
}
