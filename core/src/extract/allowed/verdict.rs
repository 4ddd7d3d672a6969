//! What the demos determine, and the gains picked for the robot
//! (method.md section 11): J's depth and region, E's depth and excess, the
//! identifiability verdict in words, and the pick.

use serde::{Deserialize, Serialize};

use crate::extract::allowed::numbers::{depth_text, num, percent};
use crate::extract::allowed::pick::Context;
use crate::extract::allowed::region::{Acceptable, EXCESS_SMALL, e_depth, excess};
use crate::extract::allowed::rule::{Pick, PickRule, PickSettings};
use crate::extract::diagnostics::balance::{FLAT_DEPTH, depth};
use crate::extract::optimum::Extraction;
use crate::extract::robot::RobotGains;
use crate::fit::settings::SkillMode;
use crate::landscape::grid::Landscape;
use crate::landscape::model::Model;
use crate::landscape::quantity::Quantity;

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
        let e = EVerdict::of(model, landscape);
        let acceptable = Acceptable::new(landscape, k, extraction.j, settings.eps);
        let duration = mean_duration(model);
        let ctx = Context {
            model,
            landscape,
            extraction,
            acceptable: &acceptable,
            limit: settings.a_peak_limit,
            settle_within: settings.settle_within,
            duration,
        };
        let (pick, pick_failure) = choose(&ctx, settings.rule, j_depth, j_flat);
        Self {
            skill_mode: model.settings().skill_mode,
            j_depth,
            j_flat,
            e_depth: e.depth,
            e_flat: e.flat,
            e_range: e.range,
            e_excess: e.excess,
            e_note: e.note,
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
            Some(p) => p.headline(),
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
            s.push_str(&format!(
                "  settling (2 %, ln 50 / sigma): {:.3} unit times, {:.3} s at T = {:.3} s\n",
                p.settling.unit, p.settling.seconds, p.robot.duration_s
            ));
            if p.on_edge {
                s.push_str(&format!(
                    "  ON THE EDGE: the {} pick lies on {} of the box, where its rule would go \
                     further; widen the box (--dm-range / --km-range) or keep the picks to gains \
                     that settle in time (--settle-within)\n",
                    p.rule.name(),
                    p.edge
                ));
            }
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

/// What E says over the grid (method.md section 11).
struct EVerdict {
    depth: Option<f64>,
    flat: bool,
    range: Option<[f64; 2]>,
    excess: Option<[f64; 2]>,
    note: Option<String>,
}

impl EVerdict {
    /// E's depth, flatness, range and excess over `landscape`, and what E
    /// cannot say (one demo; a refused frame skill).
    fn of(model: &Model, landscape: &Landscape) -> Self {
        let n = model.demos().len();
        let refusal = model.skill_refusal();
        let depth = if refusal.is_some() {
            None
        } else {
            e_depth(landscape)
        };
        let note = match refusal {
            Some(why) => Some(format!("no skill error E: {why}")),
            None if n < 2 => Some(
                "with one demo E equals sum d: E needs two demos to say anything about \
                 generalisation"
                    .to_owned(),
            ),
            None => None,
        };
        let range = refusal.is_none().then(|| {
            landscape
                .values(Quantity::ESum)
                .iter()
                .filter(|v| v.is_finite())
                .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], &v| {
                    [lo.min(v), hi.max(v)]
                })
        });
        Self {
            depth,
            flat: n >= 2 && depth.is_some_and(|d| d < FLAT_DEPTH),
            range,
            excess: refusal.is_none().then(|| excess(landscape)).flatten(),
            note,
        }
    }
}

/// The pick: the rule asked for, else the optimum where J is not flat and
/// `compliant` (failing that, `critical`) where it is; each with why.
fn choose(
    ctx: &Context<'_>,
    rule: Option<PickRule>,
    j_depth: Option<f64>,
    j_flat: bool,
) -> (Option<Pick>, Option<String>) {
    match rule {
        Some(rule) => match ctx.pick(rule) {
            Ok(p) => (
                Some(p.with_why(format!("asked for: {}{}", rule.rule_text(), ctx.limited()))),
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
    }
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
