//! What panels ask for: session commands, and what only the app can do
//! (dialogs, exports, the selection). Panels push them; the app applies
//! them after the frame's layout.

use crate::session;
use dmpscope_core::Quantity;

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
    /// Select a demo (its index in the session's demos that are in the
    /// model, as the plots' demo list counts them).
    Select(usize),
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
    /// The figure of the pinned sets' regenerations, SVG.
    FigureSvg,
    /// The same figure as PNG (natively).
    FigurePng,
    /// The pinned sets' comparison as CSV.
    CompareCsv,
    /// The pinned sets' comparison as Markdown.
    CompareMarkdown,
}

/// A heat map: J, or a quantity of the landscape's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Map {
    /// J = S + k sum d.
    J,
    /// A quantity the landscape keeps per point (`dmpscope_core::quantity`).
    Quantity(Quantity),
}

impl Map {
    /// The map's title.
    pub fn title(self) -> &'static str {
        match self {
            Self::J => "J = S + k sum d",
            Self::Quantity(q) => q.about().title,
        }
    }

    /// The map's short name (menus, buttons).
    pub fn label(self) -> &'static str {
        match self {
            Self::J => "J",
            Self::Quantity(q) => q.about().label,
        }
    }

    /// The file name of its PNG export.
    pub fn file_name(self) -> String {
        let part = match self {
            Self::J => "J",
            Self::Quantity(q) => q.about().file,
        };
        format!("dmpscope-{part}.png")
    }

    /// Every map: J, then the table's quantities.
    pub fn all() -> impl Iterator<Item = Self> {
        std::iter::once(Self::J).chain(dmpscope_core::landscape::quantity::ALL.map(Self::Quantity))
    }

    /// The values of this map in `shown`.
    pub fn values(self, shown: &session::Shown) -> &[f64] {
        match self {
            Self::J => &shown.j,
            Self::Quantity(q) => shown.values(q),
        }
    }
}
