//! What the demos determine, and gains for the robot where they do not
//! (method.md section 11): the acceptable region of J, E's depth with the
//! identifiability verdict, and a gain pair picked in the region by a
//! named rule.

use serde::{Deserialize, Serialize};

use crate::extract::diagnostics::balance::{FLAT_DEPTH, depth};
use crate::extract::optimum::Extraction;
use crate::extract::robot::RobotGains;
use crate::fit::settings::SkillMode;
use crate::landscape::grid::Landscape;
use crate::landscape::model::{Model, zeta};
use crate::landscape::quantity::Quantity;

pub mod pick;
use pick::Context;

/// The default eps of the acceptable region (the flatness threshold).
pub const DEFAULT_EPS: f64 = 0.02;
/// The damping ratios a `compliant` pick accepts.
pub const COMPLIANT_ZETA: [f64; 2] = [0.7, 1.5];

/// A rule that picks gains in the acceptable region.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PickRule {
    /// J's refined optimum (the paper).
    Optimum,
    /// The least K/M with zeta in [0.7, 1.5].
    Compliant,
    /// zeta nearest 1, then the least K/M.
    Critical,
    /// The least max-over-demos a_peak.
    Smooth,
}

impl PickRule {
    /// Every rule, in the order menus list them.
    pub const ALL: [Self; 4] = [Self::Optimum, Self::Compliant, Self::Critical, Self::Smooth];

    /// Its name on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Self::Optimum => "optimum",
            Self::Compliant => "compliant",
            Self::Critical => "critical",
            Self::Smooth => "smooth",
        }
    }

    /// What it chooses, in words.
    pub fn rule_text(self) -> &'static str {
        match self {
            Self::Optimum => "J's refined optimum",
            Self::Compliant => "the least K/M with zeta in [0.7, 1.5] (soft and well damped)",
            Self::Critical => "zeta nearest 1 (critically damped), then the least K/M",
            Self::Smooth => "the least peak acceleration of any demo",
        }
    }
}

impl std::str::FromStr for PickRule {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or_else(|| format!("unknown pick {s:?}: optimum, compliant, critical or smooth"))
    }
}

/// The grid points whose J is within eps of J*.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Acceptable {
    /// The tolerance: `J <= (1 + eps) J*`.
    pub eps: f64,
    /// The share of the grid's points in the region.
    pub fraction: f64,
    /// The least and greatest D/M in it (`None`: the region is empty).
    pub dm: Option<[f64; 2]>,
    /// The least and greatest K/M in it.
    pub km: Option<[f64; 2]>,
    /// The least and greatest zeta in it.
    pub zeta: Option<[f64; 2]>,
    /// Per grid point (row-major `[i_dm][i_km]`), whether it is in.
    #[serde(skip)]
    pub mask: Vec<bool>,
}

impl Acceptable {
    /// The region of `landscape` (complete) for `k` around `j_star`.
    pub fn new(landscape: &Landscape, k: f64, j_star: f64, eps: f64) -> Self {
        let j = landscape.j(k);
        let mask: Vec<bool> = j.iter().map(|&v| v <= (1.0 + eps) * j_star).collect();
        let n_km = landscape.grid.km.n;
        let mut range = [[f64::INFINITY, f64::NEG_INFINITY]; 3];
        let mut count = 0usize;
        for (idx, _) in mask.iter().enumerate().filter(|&(_, &m)| m) {
            count += 1;
            let (dm, km) = (landscape.dm[idx / n_km], landscape.km[idx % n_km]);
            for (r, v) in range.iter_mut().zip([dm, km, zeta(dm, km)]) {
                r[0] = r[0].min(v);
                r[1] = r[1].max(v);
            }
        }
        let some = |r: [f64; 2]| (count > 0).then_some(r);
        Self {
            eps,
            fraction: count as f64 / mask.len().max(1) as f64,
            dm: some(range[0]),
            km: some(range[1]),
            zeta: some(range[2]),
            mask,
        }
    }

    /// `D/M a-b, K/M c-d (zeta e-f)`, or that the region is empty.
    pub fn text(&self) -> String {
        match (self.dm, self.km, self.zeta) {
            (Some(d), Some(k), Some(z)) => format!(
                "D/M {}-{}, K/M {}-{} (zeta {:.2}-{:.2})",
                num(d[0]),
                num(d[1]),
                num(k[0]),
                num(k[1]),
                z[0],
                z[1]
            ),
            _ => "no grid point".to_owned(),
        }
    }
}

/// A number with about four significant digits.
pub fn num(v: f64) -> String {
    let digits =
        (3 - crate::portable::log10(v.abs().max(1e-300)).floor() as i32).clamp(0, 6) as usize;
    format!("{v:.digits$}")
}

/// A picked gain pair and everything a robot needs to know of it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pick {
    /// The rule that chose it.
    pub rule: PickRule,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// Damping ratio.
    pub zeta: f64,
    /// J there.
    pub j: f64,
    /// S there.
    pub s: f64,
    /// sum d there, metres.
    pub d_sum: f64,
    /// E there, metres (`None` without a skill error).
    pub e_sum: Option<f64>,
    /// The largest a_peak of any demo there, m/s^2 of unit time.
    pub a_peak_max: f64,
    /// Why this rule and this point, in words.
    pub why: String,
    /// The gains in real time at the demos' mean duration.
    pub robot: RobotGains,
}

/// What the demos determine and the gains picked for the robot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Allowed {
    /// The skill mode E assumes.
    pub skill_mode: SkillMode,
    /// J's depth (method.md section 9).
    pub j_depth: Option<f64>,
    /// Whether J is flat (the demos do not determine the gains by J).
    pub j_flat: bool,
    /// E's depth (`None` without a skill error).
    pub e_depth: Option<f64>,
    /// Whether E is flat: one skill reproduces the demos about equally
    /// well at all gains.
    pub e_flat: bool,
    /// The least and greatest E over the grid, metres (`None` without a
    /// skill error).
    pub e_range: Option<[f64; 2]>,
    /// The least and greatest `E - sum d` over the grid, metres: how much
    /// worse the one skill reproduces the demos than their own DMPs do
    /// (`None` without a skill error). When it varies much less than E
    /// does, E's variation over the gains is the DMP's own reproduction
    /// error and the demos differ only by the skill's map, even where E's
    /// depth is not small (an alternative to E's depth, docs/method.md
    /// section 11).
    pub e_excess: Option<[f64; 2]>,
    /// What E can and cannot say here (one demo; a refused frame skill).
    pub e_note: Option<String>,
    /// The acceptable region.
    pub acceptable: Acceptable,
    /// The picked gains (`None`: the rule found no point).
    pub pick: Option<Pick>,
    /// Why there is no pick, naming the nearest point.
    pub pick_failure: Option<String>,
    /// The optimum's gains in real time at the demos' mean duration.
    pub optimum_robot: RobotGains,
}

/// How to pick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PickSettings {
    /// The rule; `None`: `optimum` when J is not flat, `compliant` when it
    /// is.
    pub rule: Option<PickRule>,
    /// The region's eps.
    pub eps: f64,
    /// An a_peak limit (m/s^2 of unit time) every pick keeps to.
    pub a_peak_limit: Option<f64>,
}

impl Default for PickSettings {
    fn default() -> Self {
        Self {
            rule: None,
            eps: DEFAULT_EPS,
            a_peak_limit: None,
        }
    }
}

/// The depth of E: section 9's depth with E in place of J and E's grid
/// minimum as the reference.
pub fn e_depth(landscape: &Landscape) -> Option<f64> {
    let e = landscape.values(Quantity::ESum);
    let min = e
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    if !(min.is_finite() && min > 0.0) {
        return None;
    }
    let (n_dm, n_km) = (landscape.grid.dm.n, landscape.grid.km.n);
    let boundary = (0..n_dm)
        .flat_map(|i| (0..n_km).map(move |j| (i, j)))
        .filter(|&(i, j)| i == 0 || j == 0 || i + 1 == n_dm || j + 1 == n_km)
        .map(|(i, j)| e[landscape.index(i, j)])
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    boundary
        .is_finite()
        .then(|| (boundary / min - 1.0).max(0.0))
}

impl Allowed {
    /// The region, E's verdict and the pick of `model` on `landscape`
    /// (complete) around `extraction`.
    pub fn new(
        model: &Model,
        landscape: &Landscape,
        extraction: &Extraction,
        settings: PickSettings,
    ) -> Self {
        let k = extraction.k;
        let j_depth = depth(landscape, k, extraction.j);
        let j_flat = j_depth.is_none_or(|d| d < FLAT_DEPTH);
        let n = model.demos().len();
        let refusal = model.skill_refusal();
        let e_depth = if refusal.is_some() {
            None
        } else {
            e_depth(landscape)
        };
        let e_note = match refusal {
            Some(why) => Some(format!("no skill error E: {why}")),
            None if n < 2 => Some(
                "with one demo E equals sum d: E needs two demos to say anything about \
                 generalisation"
                    .to_owned(),
            ),
            None => None,
        };
        let e_flat = n >= 2 && e_depth.is_some_and(|d| d < FLAT_DEPTH);
        let e_range = refusal.is_none().then(|| {
            landscape
                .values(Quantity::ESum)
                .iter()
                .filter(|v| v.is_finite())
                .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], &v| {
                    [lo.min(v), hi.max(v)]
                })
        });
        let e_excess = refusal.is_none().then(|| excess(landscape)).flatten();
        let acceptable = Acceptable::new(landscape, k, extraction.j, settings.eps);
        let duration = mean_duration(model);
        let ctx = Context {
            model,
            landscape,
            extraction,
            acceptable: &acceptable,
            limit: settings.a_peak_limit,
            duration,
        };
        let (pick, pick_failure) = match settings.rule {
            Some(rule) => match ctx.pick(rule) {
                Ok(p) => (
                    Some(p.with_why(format!("asked for: {}", rule.rule_text()))),
                    None,
                ),
                Err(e) => (None, Some(e)),
            },
            None if !j_flat => {
                let why = format!(
                    "J is not flat (depth {} >= {FLAT_DEPTH}): the demos determine the gains; \
                     {}{}",
                    depth_text(j_depth),
                    PickRule::Optimum.rule_text(),
                    ctx.limited()
                );
                split(ctx.pick(PickRule::Optimum).map(|p| p.with_why(why)))
            }
            None => {
                let why = format!(
                    "J is flat (depth {} < {FLAT_DEPTH}): the demos allow a region of gains; \
                     within it, {}{}",
                    depth_text(j_depth),
                    PickRule::Compliant.rule_text(),
                    ctx.limited()
                );
                match ctx.pick(PickRule::Compliant) {
                    Ok(p) => (Some(p.with_why(why)), None),
                    Err(e) => {
                        let why = format!(
                            "J is flat (depth {}); {e}, so {}",
                            depth_text(j_depth),
                            PickRule::Critical.rule_text()
                        );
                        split(ctx.pick(PickRule::Critical).map(|p| p.with_why(why)))
                    }
                }
            }
        };
        Self {
            skill_mode: model.settings().skill_mode,
            j_depth,
            j_flat,
            e_depth,
            e_flat,
            e_range,
            e_excess,
            e_note,
            acceptable,
            pick,
            pick_failure,
            optimum_robot: RobotGains::new(extraction.eval.dm, extraction.eval.km, duration),
        }
    }

    /// The verdict in words: never a dead end.
    pub fn text(&self) -> String {
        let mut s = String::new();
        let region = self.acceptable.text();
        let picked = match &self.pick {
            Some(p) => format!(
                "picked by {}: D/M {}, K/M {} (zeta {:.3})",
                p.rule.name(),
                num(p.dm),
                num(p.km),
                p.zeta
            ),
            None => "no pick".to_owned(),
        };
        if self.j_flat {
            s.push_str(&format!("the data allow {region}; {picked}\n"));
        } else {
            s.push_str(&format!(
                "acceptable (J within {} of J*): {region}; {picked}\n",
                percent(self.acceptable.eps)
            ));
        }
        s.push_str(&format!(
            "  region: {} of the grid\n",
            percent(self.acceptable.fraction)
        ));
        if let Some(p) = &self.pick {
            s.push_str(&format!("  why: {}\n", p.why));
            s.push_str(&format!("  for the robot: {}\n", p.robot.text()));
        }
        if let Some(f) = &self.pick_failure {
            s.push_str(&format!("  {f}\n"));
        }
        s.push_str(&self.identifiability_text());
        s
    }

    /// E's verdict in words (skill mode, depth, what it means).
    pub fn identifiability_text(&self) -> String {
        if let Some(note) = &self.e_note {
            return format!("  skill error ({}): {note}\n", self.skill_mode.name());
        }
        let depth = match self.e_range {
            Some([lo, hi]) => format!(
                "{} (E {} - {} m over the grid)",
                depth_text(self.e_depth),
                num(lo),
                num(hi)
            ),
            None => depth_text(self.e_depth),
        };
        if self.e_flat {
            format!(
                "  identifiability ({} skill: {}): E's depth {depth} < {FLAT_DEPTH}: one skill \
                 reproduces the demos equally well at all gains, so under this generalisation \
                 the demos carry no information about the gains. Demos that would: ones that \
                 differ in a way the map does not explain, such as recovering from a push, or \
                 starting off the path or at a different speed towards the same goal.\n",
                self.skill_mode.name(),
                self.skill_mode.assumes()
            )
        } else if let (Some([lo, hi]), Some([e_lo, e_hi])) = (self.e_excess, self.e_range)
            && hi - lo < EXCESS_SMALL * (e_hi - e_lo)
        {
            format!(
                "  identifiability ({} skill: {}): E's depth {depth}, but E - sum d stays within \
                 {} to {} m while E spans {} m: one skill reproduces each demo about as well as \
                 its own DMP does at every gain, so the demos differ only by the skill's map and \
                 E's variation is the DMP's own reproduction error, not information about the \
                 gains\n",
                self.skill_mode.name(),
                self.skill_mode.assumes(),
                num(lo),
                num(hi),
                num(e_hi - e_lo)
            )
        } else {
            format!(
                "  identifiability ({} skill: {}): E's depth {depth}: the demos' differences are \
                 not all the skill's own map, and E prefers some gains\n",
                self.skill_mode.name(),
                self.skill_mode.assumes()
            )
        }
    }
}

/// The least and greatest `E - sum d` over the grid's points where both
/// are finite.
fn excess(landscape: &Landscape) -> Option<[f64; 2]> {
    let e = landscape.values(Quantity::ESum);
    let d = landscape.values(Quantity::DSum);
    let range = e
        .iter()
        .zip(d)
        .map(|(e, d)| e - d)
        .filter(|v| v.is_finite())
        .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], v| {
            [lo.min(v), hi.max(v)]
        });
    range[0].is_finite().then_some(range)
}

/// When `E - sum d` varies by less than this share of E's own variation
/// over the grid, E's variation is the DMP's own reproduction error.
pub const EXCESS_SMALL: f64 = 0.1;

/// A share as a percentage with the digits it needs (`0.02 %`, `12.5 %`).
pub fn percent(share: f64) -> String {
    let p = 100.0 * share;
    let text = if p == 0.0 || p >= 1.0 {
        format!("{p:.1}")
    } else {
        format!("{p:.2}")
    };
    // `2.0 %` reads as `2 %`.
    format!("{} %", text.strip_suffix(".0").unwrap_or(&text))
}

fn depth_text(d: Option<f64>) -> String {
    d.map_or_else(|| "undefined".to_owned(), |v| format!("{v:.4}"))
}

fn split(r: Result<Pick, String>) -> (Option<Pick>, Option<String>) {
    match r {
        Ok(p) => (Some(p), None),
        Err(e) => (None, Some(e)),
    }
}

/// The demos' mean duration, seconds.
pub fn mean_duration(model: &Model) -> f64 {
    let demos = model.demos();
    demos.iter().map(|d| d.duration_s).sum::<f64>() / demos.len().max(1) as f64
}
