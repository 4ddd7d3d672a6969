//! The paper's reference gains (method.md section 7) and the Table I rows of
//! any gain points ([`crate::report::summary::TableRow`]).

use serde::Serialize;

use crate::landscape::model::Model;
use crate::report::summary::TableRow;

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

/// Table I for named gain points.
pub fn table(model: &Model, points: &[(String, f64, f64)], k: f64) -> Vec<TableRow> {
    points
        .iter()
        .map(|(name, dm, km)| TableRow::from_eval(name.clone(), &model.evaluate(*dm, *km), k))
        .collect()
}

/// Table I rows of the five paper presets.
pub fn preset_rows(model: &Model, k: f64) -> Vec<TableRow> {
    let points: Vec<(String, f64, f64)> = PAPER_PRESETS
        .iter()
        .map(|p| (p.name.to_owned(), p.dm, p.km))
        .collect();
    table(model, &points, k)
}
