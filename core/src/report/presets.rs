//! The paper's reference gains (method.md section 7): its extracted gains
//! and its four heuristics, by the names Table I gives them.

use serde::Serialize;

/// A named gain pair.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Preset {
    /// The name as the paper's Table I gives it.
    pub name: &'static str,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
}

/// The paper's extracted gains and its four heuristics.
pub const PAPER_PRESETS: [Preset; 5] = [
    Preset {
        name: "Ours",
        dm: 10.73,
        km: 20.71,
    },
    Preset {
        name: "Hrstc1",
        dm: 25.0,
        km: 156.25,
    },
    Preset {
        name: "Hrstc2",
        dm: 10.0,
        km: 200.0,
    },
    Preset {
        name: "Hrstc3",
        dm: 100.0,
        km: 20.0,
    },
    Preset {
        name: "Hrstc4",
        dm: 4.0,
        km: 4.0,
    },
];

/// Looks a preset up by name, ignoring case.
pub fn preset(name: &str) -> Option<Preset> {
    PAPER_PRESETS
        .iter()
        .find(|p| p.name.eq_ignore_ascii_case(name))
        .copied()
}
