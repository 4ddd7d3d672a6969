//! Table I and the extraction as one serde type, [`Report`], with its text,
//! CSV and Markdown renderings (method.md sections 6 and 7). Every output
//! of them comes from here: the CLI's `extract` (text or `--json`), its
//! `landscape --out` (this shape plus the grids) and the app's exports.
//!
//! The JSON shape (`serde_json::to_value(&report)`):
//!
//! ```text
//! {
//!   "k": 20.0,                                   weight of sum d in J
//!   "demos": [{"name", "n_samples", "duration_s"}],
//!   "optimum": null | {"dm", "km", "zeta", "j", "s", "d_sum",
//!                      "on_edge", "edge", "grid_min_j", "iterations", "converged"},
//!   "table": [{"name", "dm", "km", "zeta", "d_mean": [m per demo],
//!              "a_peak": [m/s^2 per demo], "d_sum", "s", "j",
//!              "e": [m per demo], "e_sum"}],
//!   "diagnostics": {"depth", "flat", "k_ratio", "balanced_k",      (when computed)
//!                   "s_minimum": {"dm", "km", "s"},
//!                   "demos": [{"name", "s_share", "loo": {"dm", "km", "j", "on_edge"}}],
//!                   "bootstrap": {"n", "seed", "dm": [p5, p50, p95], "km": [..],
//!                                 "on_edge_fraction"}},
//!   "diagnostics_about": {"grid", "resamples", "notes"},            (with diagnostics)
//!   "constrained": {"a_peak_limit", "optimum": null | {"dm", "km",   (with an a_peak limit)
//!                   "j", "a_peak", "on_edge"}},
//!   "loading": {"units", "up", "demos", "segments", "trim_rest",    (extract)
//!               "sg_window", "sg_order", "sg_seconds"},
//!   "skill_mode": "frame" | "per-axis" | "none",   (the verdict of method.md
//!   "j_depth", "j_flat",                           section 11, `allowed`
//!   "e_depth", "e_flat",                           flattened: extract, and
//!   "e_range": null | [lo, hi],                    the app's export once
//!   "e_note": null | "...",                        computed)
//!   "acceptable": {"eps", "fraction", "dm": null | [lo, hi],
//!                  "km": null | [lo, hi], "zeta": null | [lo, hi]},
//!   "pick": null | {"rule", "dm", "km", "zeta", "j", "s", "d_sum", "e_sum",
//!                   "a_peak_max", "why", "robot": {..as optimum_robot}},
//!   "pick_failure": null | "...",
//!   "optimum_robot": {"duration_s", "stiffness_per_mass", "damping_per_mass",
//!                     "natural_frequency_rad_s", "natural_frequency_hz",
//!                     "zeta", "settling_time_s"}
//! }
//! ```
//!
//! A diagnostic that cannot be computed (one demo: S-based ones) is `null`;
//! so are `e` and `e_sum` without a skill error (a refused frame skill).
//!
//! `edge` names the box sides the optimum lies on ("" when interior);
//! `d_mean`, `a_peak` and `e` follow `demos`' order.

use crate::report::text::{pad_right, widest};
use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use crate::extract::diagnostics::{DiagAbout, Diagnostics};
use crate::extract::optimum::Extraction;
use crate::extract::point::GainPoint;
use crate::landscape::model::Model;
use crate::report::table::{TableRow, preset_rows};

/// A demonstration as a report lists it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DemoSummary {
    /// The demo's name, `file:topic`.
    pub name: String,
    /// Samples as recorded.
    pub n_samples: usize,
    /// Duration, seconds.
    pub duration_s: f64,
}

/// The extracted gains as a report shows them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Optimum {
    /// The gains and J, S and sum d there (read through `Deref`:
    /// `optimum.dm`).
    #[serde(flatten)]
    pub at: GainPoint,
    /// Whether the optimum lies on the box's edge.
    pub on_edge: bool,
    /// The sides it lies on, in words ("" when interior).
    pub edge: String,
    /// `J` at the grid minimum the refinement started from.
    pub grid_min_j: f64,
    /// Nelder-Mead iterations.
    pub iterations: usize,
    /// Whether the simplex shrank below its tolerance.
    pub converged: bool,
}

impl From<&Extraction> for Optimum {
    fn from(x: &Extraction) -> Self {
        Self {
            at: GainPoint {
                dm: x.eval.dm,
                km: x.eval.km,
                zeta: x.eval.zeta,
                j: x.j,
                s: x.eval.s,
                d_sum: x.eval.d_sum,
            },
            on_edge: x.on_edge(),
            edge: x.edges.describe(),
            grid_min_j: x.grid_min_j,
            iterations: x.iterations,
            converged: x.converged,
        }
    }
}

impl std::ops::Deref for Optimum {
    type Target = GainPoint;

    fn deref(&self) -> &GainPoint {
        &self.at
    }
}

/// Table I with the extraction it compares against.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// The weight `k` of sum d in J.
    pub k: f64,
    /// The model's demos, in order.
    pub demos: Vec<DemoSummary>,
    /// The extracted optimum, when known.
    pub optimum: Option<Optimum>,
    /// Table I: `Extracted` (when known), the paper's gains, then any others.
    pub table: Vec<TableRow>,
    /// The diagnostics of the extraction, when computed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diagnostics: Option<Diagnostics>,
    /// How the diagnostics were made.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diagnostics_about: Option<DiagAbout>,
    /// The optimum under an a_peak limit, when one was asked for.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub constrained: Option<Constrained>,
    /// How the recordings were read and prepared, when the caller says.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loading: Option<LoadingChoices>,
    /// What the demos determine and the picked gains (method.md section
    /// 11), when computed: its fields sit at the top level
    /// (`skill_mode`, `e_depth`, `acceptable`, `pick`, ...).
    #[serde(default, flatten, skip_serializing_if = "Option::is_none")]
    pub allowed: Option<crate::extract::allowed::Allowed>,
}

/// The loading and preparation choices behind a report (so a reader knows
/// the units, what was trimmed and how demos were cut).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LoadingChoices {
    /// The positions' unit in the files (converted to metres).
    pub units: crate::load::units::Units,
    /// The recordings' up axis.
    pub up: crate::load::options::UpAxis,
    /// What a demonstration is: `topic`, `file` or `segment`.
    pub demos: String,
    /// With segments: which were kept (`all`, `first`, `last`, `N`).
    pub segments: String,
    /// Whether rests at the ends were cut.
    pub trim_rest: bool,
    /// The Savitzky-Golay window in samples (when not a duration).
    pub sg_window: usize,
    /// Its polynomial order.
    pub sg_order: usize,
    /// The window as a duration, seconds, when asked for.
    pub sg_seconds: Option<f64>,
}

impl LoadingChoices {
    /// The choices of loading options and preparation settings.
    pub fn of(load: &crate::load::options::LoadOptions, prep: &crate::PrepSettings) -> Self {
        use crate::load::options::Grouping;
        let (demos, segments) = match load.demos {
            Grouping::PerTopic => ("topic", "all".to_owned()),
            Grouping::PerFile => ("file", "all".to_owned()),
            Grouping::Segmented(s) => ("segment", s.keep.name()),
        };
        Self {
            units: load.units,
            up: load.up,
            demos: demos.to_owned(),
            segments,
            trim_rest: load.trim_rest,
            sg_window: prep.sg_window,
            sg_order: prep.sg_order,
            sg_seconds: prep.sg_seconds,
        }
    }
}

/// The least J among the gains whose largest a_peak (any demo) stays within
/// a limit (method.md section 9).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Constrained {
    /// The limit, m/s^2.
    pub a_peak_limit: f64,
    /// The constrained optimum (`None`: no grid point is within the limit).
    pub optimum: Option<ConstrainedOptimum>,
}

/// Where the constrained optimum is.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ConstrainedOptimum {
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// J there.
    pub j: f64,
    /// The largest a_peak of any demo there, m/s^2.
    pub a_peak: f64,
    /// Whether it lies on the box's edge.
    pub on_edge: bool,
}

impl Constrained {
    /// The constrained optimum of `model` on `landscape` (complete) for `k`.
    pub fn compute(
        model: &Model,
        landscape: &crate::landscape::grid::Landscape,
        k: f64,
        limit: f64,
    ) -> Self {
        let found = crate::extract::optimum::constrained(model, landscape, k, limit);
        Self::from_refined(model, limit, found.as_ref())
    }

    /// The report of a constrained optimum already found (`None`: none
    /// within `limit`).
    pub fn from_refined(
        model: &Model,
        limit: f64,
        found: Option<&crate::extract::optimum::Refined>,
    ) -> Self {
        let optimum = found.map(|r| {
            let e = model.evaluate(r.dm, r.km);
            ConstrainedOptimum {
                dm: r.dm,
                km: r.km,
                j: r.value,
                a_peak: e.a_peak.iter().copied().fold(0.0, f64::max),
                on_edge: r.edges.any(),
            }
        });
        Self {
            a_peak_limit: limit,
            optimum,
        }
    }

    /// The constrained optimum in words, against the free one's J.
    pub fn text(&self, free_j: Option<f64>) -> String {
        let limit = self.a_peak_limit;
        match &self.optimum {
            None => format!(
                "constrained: no gains on the grid keep every demo's a_peak within {limit} m/s^2\n"
            ),
            Some(c) => {
                let above = free_j.map_or(String::new(), |f| {
                    format!(
                        ", {:+.1} % on the free optimum's J",
                        100.0 * (c.j / f - 1.0)
                    )
                });
                let edge = if c.on_edge { ", on the box edge" } else { "" };
                format!(
                    "constrained (a_peak <= {limit} m/s^2): D/M {:.4}, K/M {:.4}, J {:.6}, a_peak {:.3}{above}{edge}\n",
                    c.dm, c.km, c.j, c.a_peak
                )
            }
        }
    }
}

/// Table I's rows: `Extracted` (when known), the five paper presets, then
/// `extra`.
pub fn table_rows(
    model: &Model,
    extraction: Option<&Extraction>,
    k: f64,
    extra: impl IntoIterator<Item = TableRow>,
) -> Vec<TableRow> {
    let mut rows: Vec<TableRow> = extraction
        .map(|x| TableRow::from_eval("Extracted", &x.eval, k))
        .into_iter()
        .collect();
    rows.extend(preset_rows(model, k));
    rows.extend(extra);
    rows
}

impl Report {
    /// The report of `model` with the rows of [`table_rows`].
    pub fn new(model: &Model, extraction: Option<&Extraction>, k: f64) -> Self {
        Self::with_rows(model, extraction, k, table_rows(model, extraction, k, []))
    }

    /// The report of `model` with rows computed by the caller (the app's
    /// cached ones).
    pub fn with_rows(
        model: &Model,
        extraction: Option<&Extraction>,
        k: f64,
        table: Vec<TableRow>,
    ) -> Self {
        let demos = model
            .demos()
            .iter()
            .map(|d| DemoSummary {
                name: d.name.clone(),
                n_samples: d.n_samples,
                duration_s: d.duration_s,
            })
            .collect();
        Self {
            k,
            demos,
            optimum: extraction.map(Optimum::from),
            table,
            diagnostics: None,
            diagnostics_about: None,
            constrained: None,
            loading: None,
            allowed: None,
        }
    }

    /// The report with the extraction's diagnostics.
    pub fn with_diagnostics(mut self, diagnostics: Diagnostics, about: DiagAbout) -> Self {
        self.diagnostics = Some(diagnostics);
        self.diagnostics_about = Some(about);
        self
    }

    /// The demos' names.
    pub fn demo_names(&self) -> Vec<String> {
        self.demos.iter().map(|d| d.name.clone()).collect()
    }

    /// The optimum in words: `(M:D:K)`, zeta, J with S and sum d, the edge.
    pub fn optimum_text(&self) -> String {
        let Some(o) = &self.optimum else {
            return "no optimum extracted\n".to_owned();
        };
        let mut s = String::new();
        if let Some(d) = self.diagnostics.as_ref().filter(|d| d.flat) {
            let depth = d
                .depth
                .map_or_else(|| "undefined".to_owned(), |v| format!("{v:.4}"));
            let _ = writeln!(
                s,
                "J is flat (depth {depth} < {}): J alone does not determine the gains; its \
                 least value is at",
                crate::extract::diagnostics::balance::FLAT_DEPTH
            );
        }
        let _ = writeln!(s, "(M:D:K) = 1 : {:.4} : {:.4}", o.dm, o.km);
        let _ = writeln!(s, "zeta    = {:.4}", o.zeta);
        let _ = writeln!(
            s,
            "J       = {:.6}  (S = {:.6}, sum d = {:.6} m, k = {})",
            o.j, o.s, o.d_sum, self.k
        );
        if o.on_edge {
            let _ = writeln!(s, "on edge = yes: {} (widen the range)", o.edge);
        } else {
            let _ = writeln!(s, "on edge = no");
        }
        s
    }

    /// The diagnostics in words (empty without them): the inconsistent
    /// demos first, then depth and balance, the S minimum, leave-one-out and
    /// the bootstrap.
    pub fn diagnostics_text(&self) -> String {
        let (Some(d), Some(about)) = (&self.diagnostics, &self.diagnostics_about) else {
            return String::new();
        };
        let mut s = consistency_text(d);
        s.push_str(&figures_text(d));
        s.push_str(&per_demo_text(d, about));
        s.push_str(&bootstrap_text(d));
        for note in &about.notes {
            let _ = writeln!(s, "note: {note}");
        }
        s
    }
}

/// A number with `prec` digits, or `n/a`.
fn opt(v: Option<f64>, prec: usize) -> String {
    v.map_or_else(|| "n/a".to_owned(), |v| format!("{v:.prec$}"))
}

/// The demos whose share of S is above the threshold, or that none is.
fn consistency_text(d: &Diagnostics) -> String {
    let mut s = String::new();
    let n = d.demos.len();
    let bad = d.inconsistent();
    if bad.is_empty() {
        let _ = writeln!(
            s,
            "consistent: no demo's share of S is above {:.0}/N",
            crate::extract::diagnostics::INCONSISTENT_SHARE
        );
    } else {
        let _ = writeln!(
            s,
            "inconsistent demos (share of S above {:.0}/N = {:.3}):",
            crate::extract::diagnostics::INCONSISTENT_SHARE,
            crate::extract::diagnostics::INCONSISTENT_SHARE / n as f64
        );
        for &i in &bad {
            let dd = &d.demos[i];
            let _ = writeln!(s, "  {}  share {}", dd.name, opt(dd.s_share, 3));
        }
    }
    s
}

/// The depth and its verdict, k_ratio, the balanced k and S's minimum.
fn figures_text(d: &Diagnostics) -> String {
    let mut s = String::new();
    let verdict = if d.flat {
        "FLAT: the data do not determine the gains"
    } else {
        "determined"
    };
    let _ = writeln!(
        s,
        "depth   = {}  ({verdict}; flat below {})",
        opt(d.depth, 4),
        crate::extract::diagnostics::balance::FLAT_DEPTH
    );
    let _ = writeln!(
        s,
        "k_ratio = {}  (k sum d / S at the optimum)",
        opt(d.k_ratio, 4)
    );
    let _ = writeln!(
        s,
        "balanced k = {}  (median S / median sum d)",
        opt(d.balanced_k, 4)
    );
    match &d.s_minimum {
        Some(m) => {
            let _ = writeln!(
                s,
                "S minimum: D/M {:.4}, K/M {:.4}, S {:.6}",
                m.dm, m.km, m.s
            );
        }
        None => {
            let _ = writeln!(s, "S minimum: n/a");
        }
    }
    s
}

/// Each demo's share of S and its leave-one-out optimum.
fn per_demo_text(d: &Diagnostics, about: &DiagAbout) -> String {
    let mut s = String::new();
    let g = about.grid;
    let _ = writeln!(
        s,
        "\nper demo (leave-one-out and bootstrap on a {}x{} grid, same box):",
        g.dm.n, g.km.n
    );
    let name_w = widest(d.demos.iter().map(|x| x.name.as_str()), 4);
    let _ = writeln!(
        s,
        "{:<name_w$}  {:>7}  {:>10}  {:>10}  {:>9}  {:>7}",
        "demo", "share", "LOO D/M", "LOO K/M", "LOO J", "on edge"
    );
    for dd in &d.demos {
        let (dm, km, j, edge) = dd
            .loo
            .map_or(("-".into(), "-".into(), "-".into(), "-"), |l| {
                (
                    format!("{:.3}", l.dm),
                    format!("{:.3}", l.km),
                    format!("{:.5}", l.j),
                    if l.on_edge { "yes" } else { "no" },
                )
            });
        let _ = writeln!(
            s,
            "{}  {:>7}  {dm:>10}  {km:>10}  {j:>9}  {edge:>7}",
            pad_right(&dd.name, name_w),
            opt(dd.s_share, 3)
        );
    }
    s
}

/// The bootstrap's percentiles of the optimum, or that there is none.
fn bootstrap_text(d: &Diagnostics) -> String {
    match &d.bootstrap {
        Some(b) => format!(
            "\nbootstrap ({} resamples, seed {}): D/M {:.3} / {:.3} / {:.3}, K/M {:.3} / {:.3} / {:.3} (5/50/95 %), on an edge {:.0} %\n",
            b.n,
            b.seed,
            b.dm[0],
            b.dm[1],
            b.dm[2],
            b.km[0],
            b.km[1],
            b.km[2],
            b.on_edge_fraction * 100.0
        ),
        None => "\nbootstrap: n/a\n".to_owned(),
    }
}
