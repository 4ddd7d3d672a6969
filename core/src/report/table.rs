//! Table I (method.md section 7): one row per gain set, what it gives on
//! every demo, and its columns declared once: their titles for people
//! (the app, Markdown) and for terminals, their CSV keys, units and
//! digits. The CLI's text, the CSV, the Markdown and the app's panel all
//! read [`SUMMARY`] and [`PER_DEMO`].

use serde::{Deserialize, Serialize};

use crate::landscape::model::{Model, PointEval};
use crate::report::presets::PAPER_PRESETS;

/// A column of Table I with one number per gain set.
#[derive(Clone, Copy, Debug)]
pub struct Column {
    /// Its title for people (the app, Markdown): `sum d [m]`.
    pub title: &'static str,
    /// Its title in the terminal's fixed-width table: `sum d[m]`.
    pub short: &'static str,
    /// Its CSV key: `d_sum`.
    pub key: &'static str,
    /// The terminal's column width.
    pub width: usize,
    /// Digits after the point.
    pub digits: usize,
    /// Shown only when a demo has an orientation (method.md section 12).
    pub orientation: bool,
    /// The value of a row.
    pub value: fn(&TableRow) -> f64,
}

impl Column {
    /// The cell of a row.
    pub fn cell(&self, row: &TableRow) -> String {
        format!("{:.*}", self.digits, (self.value)(row))
    }
}

/// A group of Table I's columns with one number per demo.
#[derive(Clone, Copy, Debug)]
pub struct PerDemo {
    /// The group's title in the terminal's sections: `d_mean [mm]`.
    pub section: &'static str,
    /// A column's title for people, before the demo's name: `d_mean`.
    pub prefix: &'static str,
    /// The short prefix of the app's columns: `d`.
    pub short: &'static str,
    /// The unit after the demo's name (`mm`), empty for none.
    pub unit: &'static str,
    /// The CSV key before `:` and the demo's name: `d_mean_mm`.
    pub key: &'static str,
    /// The factor from the row's unit to the shown one (metres to mm).
    pub scale: f64,
    /// Digits after the point.
    pub digits: usize,
    /// Shown only when a demo has an orientation.
    pub orientation: bool,
    /// The app shows one column per demo (a_peak and alpha_peak it
    /// summarises by their largest value instead).
    pub in_app: bool,
    /// The values of a row, one per demo, in the row's unit.
    pub values: fn(&TableRow) -> &[f64],
}

impl PerDemo {
    /// A value's cell.
    pub fn cell(&self, v: f64) -> String {
        format!("{:.*}", self.digits, v * self.scale)
    }

    /// A column's title for people: `d_mean hand [mm]`.
    pub fn title(&self, demo: &str) -> String {
        if self.unit.is_empty() {
            format!("{} {demo}", self.prefix)
        } else {
            format!("{} {demo} [{}]", self.prefix, self.unit)
        }
    }
}

/// The parts of the table shown: the position's, then with `oriented` the
/// orientation's (the `orientation` flag of each column).
pub fn parts(oriented: bool) -> &'static [bool] {
    if oriented { &[false, true] } else { &[false] }
}

/// Table I's columns with one number per gain set, after the gains' name.
pub const SUMMARY: [Column; 8] = [
    Column {
        title: "D/M",
        short: "D/M",
        key: "dm",
        width: 9,
        digits: 3,
        orientation: false,
        value: |r| r.dm,
    },
    Column {
        title: "K/M",
        short: "K/M",
        key: "km",
        width: 9,
        digits: 3,
        orientation: false,
        value: |r| r.km,
    },
    Column {
        title: "zeta",
        short: "zeta",
        key: "zeta",
        width: 7,
        digits: 3,
        orientation: false,
        value: |r| r.zeta,
    },
    Column {
        title: "S",
        short: "S",
        key: "s",
        width: 9,
        digits: 5,
        orientation: false,
        value: |r| r.s,
    },
    Column {
        title: "sum d [m]",
        short: "sum d[m]",
        key: "d_sum",
        width: 9,
        digits: 5,
        orientation: false,
        value: |r| r.d_sum,
    },
    Column {
        title: "J",
        short: "J",
        key: "j",
        width: 9,
        digits: 5,
        orientation: false,
        value: |r| r.j,
    },
    Column {
        title: "E [m]",
        short: "E[m]",
        key: "e_sum",
        width: 9,
        digits: 5,
        orientation: false,
        value: |r| r.e_sum,
    },
    Column {
        title: "sum d_rot [deg]",
        short: "sum d_rot[deg]",
        key: "d_rot_sum_deg",
        width: 14,
        digits: 4,
        orientation: true,
        value: |r| r.d_rot_sum,
    },
];

/// Table I's columns with one number per demo, group by group.
pub const PER_DEMO: [PerDemo; 5] = [
    PerDemo {
        section: "d_mean [mm]",
        prefix: "d_mean",
        short: "d",
        unit: "mm",
        key: "d_mean_mm",
        scale: 1e3,
        digits: 3,
        orientation: false,
        in_app: true,
        values: |r| &r.d_mean,
    },
    PerDemo {
        section: "a_peak [m/s^2]",
        prefix: "a_peak",
        short: "a_peak",
        unit: "",
        key: "a_peak",
        scale: 1.0,
        digits: 2,
        orientation: false,
        in_app: false,
        values: |r| &r.a_peak,
    },
    PerDemo {
        section: "e, the skill's error [mm]",
        prefix: "e",
        short: "e",
        unit: "mm",
        key: "e_mm",
        scale: 1e3,
        digits: 3,
        orientation: false,
        in_app: true,
        values: |r| &r.e,
    },
    PerDemo {
        section: "d_rot, the orientation's error [deg]",
        prefix: "d_rot",
        short: "d_rot",
        unit: "deg",
        key: "d_rot_deg",
        scale: 1.0,
        digits: 4,
        orientation: true,
        in_app: true,
        values: |r| &r.d_rot,
    },
    PerDemo {
        section: "alpha_peak [rad/s^2]",
        prefix: "alpha_peak",
        short: "alpha_peak",
        unit: "",
        key: "alpha_peak",
        scale: 1.0,
        digits: 2,
        orientation: true,
        in_app: false,
        values: |r| &r.alpha_peak,
    },
];

/// One row of Table I: a gain set and what it gives on every demo.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TableRow {
    /// What the gains are (a preset's name, `Extracted`, `Operating point`).
    pub name: String,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// Damping ratio.
    pub zeta: f64,
    /// Human-likeness error per demo, metres over 1 s.
    pub d_mean: Vec<f64>,
    /// Peak acceleration per demo.
    pub a_peak: Vec<f64>,
    /// `sum d`.
    pub d_sum: f64,
    /// `S`.
    pub s: f64,
    /// `J` for the table's `k`.
    pub j: f64,
    /// Skill error per demo (method.md section 11), metres; NaN without
    /// a skill error (`null` in JSON, read back as NaN).
    #[serde(default, deserialize_with = "nans_for_nulls")]
    pub e: Vec<f64>,
    /// `E = sum e` (NaN without a skill error; absent in old reports).
    #[serde(default = "nan", deserialize_with = "nan_for_null")]
    pub e_sum: f64,
    /// Orientation error per demo (method.md section 12), degrees; NaN for
    /// a demo without orientation.
    #[serde(default, deserialize_with = "nans_for_nulls")]
    pub d_rot: Vec<f64>,
    /// Peak angular acceleration per demo, rad/s^2 of unit time; NaN
    /// without orientation.
    #[serde(default, deserialize_with = "nans_for_nulls")]
    pub alpha_peak: Vec<f64>,
    /// `sum d_rot`, degrees (NaN when no demo has an orientation).
    #[serde(default = "nan", deserialize_with = "nan_for_null")]
    pub d_rot_sum: f64,
}

fn nan() -> f64 {
    f64::NAN
}

/// A number that JSON holds as `null` when it was NaN.
fn nan_for_null<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Option::<f64>::deserialize(d).map(|v| v.unwrap_or(f64::NAN))
}

/// Numbers that JSON holds as `null` where they were NaN.
fn nans_for_nulls<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
    Vec::<Option<f64>>::deserialize(d)
        .map(|v| v.into_iter().map(|x| x.unwrap_or(f64::NAN)).collect())
}

impl TableRow {
    /// A row from an evaluation.
    pub fn from_eval(name: impl Into<String>, eval: &PointEval, k: f64) -> Self {
        Self {
            name: name.into(),
            dm: eval.dm,
            km: eval.km,
            zeta: eval.zeta,
            d_mean: eval.d.clone(),
            a_peak: eval.a_peak.clone(),
            d_sum: eval.d_sum,
            s: eval.s,
            j: eval.j(k),
            e: eval.e.clone(),
            e_sum: eval.e_sum,
            d_rot: eval.d_rot.iter().map(|r| r.to_degrees()).collect(),
            alpha_peak: eval.alpha_peak.clone(),
            d_rot_sum: eval.d_rot_sum,
        }
    }

    /// Whether any demo of the row has an orientation.
    pub fn oriented(&self) -> bool {
        self.d_rot_sum.is_finite()
    }

    /// The row's cells as the CSV and Markdown tables print them: the
    /// name, the position's [`SUMMARY`] columns and [`PER_DEMO`] groups
    /// (each group's cells demo by demo), then with `oriented` the
    /// orientation's columns and groups likewise.
    pub fn cells(&self, oriented: bool) -> Vec<String> {
        let mut c = vec![self.name.clone()];
        for &part in parts(oriented) {
            c.extend(
                SUMMARY
                    .iter()
                    .filter(|col| col.orientation == part)
                    .map(|col| col.cell(self)),
            );
            for group in PER_DEMO.iter().filter(|g| g.orientation == part) {
                c.extend((group.values)(self).iter().map(|&v| group.cell(v)));
            }
        }
        c
    }
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
