//! Picking gains in the acceptable region by a named rule (method.md
//! section 11): the refined optimum (under an a_peak limit, the
//! constrained one), or the grid point a rule prefers; a rule with no
//! point says why and names the nearest.

use crate::extract::allowed::numbers::{num, percent};
use crate::extract::allowed::region::Acceptable;
use crate::extract::allowed::rule::{COMPLIANT_ZETA, Pick, PickRule, Settling, settling_unit};
use crate::extract::optimum::Extraction;
use crate::extract::point::GainPoint;
use crate::extract::robot::RobotGains;
use crate::landscape::grid::Landscape;
use crate::landscape::model::{Model, zeta};

/// What a pick looks at.
#[derive(Clone, Copy)]
pub(crate) struct Context<'a> {
    /// The model the points are evaluated with.
    pub(crate) model: &'a Model,
    /// The complete landscape.
    pub(crate) landscape: &'a Landscape,
    /// J's refined optimum and its k.
    pub(crate) extraction: &'a Extraction,
    /// The acceptable region.
    pub(crate) acceptable: &'a Acceptable,
    /// An a_peak limit every pick keeps to.
    pub(crate) limit: Option<f64>,
    /// A settling limit (unit time) the grid rules' picks keep to.
    pub(crate) settle_within: Option<f64>,
    /// The demos' mean duration, seconds (the robot's gains).
    pub(crate) duration: f64,
}

impl Context<'_> {
    /// `, among the gains with a_peak within L` when a limit is set.
    pub(crate) fn limited(&self) -> String {
        let mut text = self.limit.map_or(String::new(), |l| {
            format!(", among the gains whose a_peak stays within {l} m/s^2")
        });
        if let Some(s) = self.settle_within {
            text.push_str(&format!(
                ", among the gains that settle within {s} unit times"
            ));
        }
        text
    }

    /// The gains `rule` picks, evaluated, or why there are none.
    pub(crate) fn pick(&self, rule: PickRule) -> Result<Pick, String> {
        let (dm, km) = match rule {
            PickRule::Optimum => self.optimum()?,
            _ => self.grid_pick(rule)?,
        };
        let e = self.model.evaluate(dm, km);
        let edge = self.edge(rule, dm, km);
        Ok(Pick {
            rule,
            at: GainPoint::of(&e, self.extraction.k),
            e_sum: e.e_sum.is_finite().then_some(e.e_sum),
            a_peak_max: e.a_peak.iter().copied().fold(0.0, f64::max),
            why: String::new(),
            settling: Settling::of(dm, km, self.duration),
            on_edge: !edge.is_empty(),
            edge,
            robot: RobotGains::new(dm, km, self.duration),
        })
    }

    /// The sides of the grid's box the pick of `rule` at `(dm, km)` lies on
    /// in the direction the rule pushes ("" when none): `compliant` and
    /// `critical` go to the least K/M (then D/M), `smooth` wherever a_peak
    /// falls, `optimum` wherever J does (the extraction's own edges).
    fn edge(&self, rule: PickRule, dm: f64, km: f64) -> String {
        if rule == PickRule::Optimum {
            return if self.extraction.on_edge() {
                self.extraction.edges.describe()
            } else {
                String::new()
            };
        }
        let (d, k) = (&self.landscape.dm, &self.landscape.km);
        let at = |v: f64, axis: &[f64], first: bool| {
            let end = if first { axis.first() } else { axis.last() };
            end.is_some_and(|&e| e == v)
        };
        let mut sides = Vec::new();
        if at(km, k, true) {
            sides.push("the least K/M");
        }
        if rule == PickRule::Smooth {
            if at(dm, d, true) {
                sides.push("the least D/M");
            }
            if at(km, k, false) {
                sides.push("the greatest K/M");
            }
            if at(dm, d, false) {
                sides.push("the greatest D/M");
            }
        }
        sides.join(" and ")
    }

    /// The refined optimum, or under a limit the constrained one.
    fn optimum(&self) -> Result<(f64, f64), String> {
        let x = &self.extraction.eval;
        let peak = x.a_peak.iter().copied().fold(0.0, f64::max);
        match self.limit {
            Some(limit) if peak > limit => {
                let r = crate::extract::optimum::constrained(
                    self.model,
                    self.landscape,
                    self.extraction.k,
                    limit,
                )
                .ok_or_else(|| {
                    format!("no gains on the grid keep every demo's a_peak within {limit}")
                })?;
                // The limit removes points first; what is left must still
                // be acceptable.
                let bound = (1.0 + self.acceptable.eps) * self.extraction.j;
                if r.value > bound {
                    return Err(format!(
                        "the optimum under the a_peak limit {limit}, D/M {}, K/M {} (J {:.6}), is \
                         more than {} above J* {:.6}: no gains in the acceptable region keep \
                         a_peak within the limit",
                        num(r.dm),
                        num(r.km),
                        r.value,
                        percent(self.acceptable.eps),
                        self.extraction.j
                    ));
                }
                Ok((r.dm, r.km))
            }
            _ => Ok((x.dm, x.km)),
        }
    }

    /// The region's points (within the limit) as `(dm, km, zeta, a_peak)`.
    fn candidates(&self) -> Vec<[f64; 4]> {
        let n_km = self.landscape.grid.km.n;
        let peak = self.landscape.a_peak();
        self.acceptable
            .mask
            .iter()
            .enumerate()
            .filter(|&(i, &m)| m && self.limit.is_none_or(|l| peak[i] <= l))
            .map(|(i, _)| {
                let (dm, km) = (self.landscape.dm[i / n_km], self.landscape.km[i % n_km]);
                [dm, km, zeta(dm, km), peak[i]]
            })
            .filter(|p| {
                self.settle_within
                    .is_none_or(|s| settling_unit(p[0], p[1]) <= s)
            })
            .collect()
    }

    /// The region's points within the a_peak limit, whatever their settling.
    fn candidates_without_settling(&self) -> Vec<[f64; 4]> {
        Context {
            settle_within: None,
            ..*self
        }
        .candidates()
    }

    /// Why `rule` has no point when no grid point is left (the region
    /// empty, or the a_peak limit removing all of it), naming the nearest.
    fn nearest_when_empty(&self, rule: PickRule) -> String {
        let n_km = self.landscape.grid.km.n;
        let at = |i: usize| (self.landscape.dm[i / n_km], self.landscape.km[i % n_km]);
        let peak = self.landscape.a_peak();
        let least = |values: &mut dyn Iterator<Item = (usize, f64)>| {
            values
                .filter(|(_, v)| v.is_finite())
                .min_by(|a, b| a.1.total_cmp(&b.1))
        };
        let in_region = &mut self
            .acceptable
            .mask
            .iter()
            .enumerate()
            .filter(|&(_, &m)| m)
            .map(|(i, _)| (i, peak[i]));
        if let (Some(limit), Some((i, a))) = (self.limit, least(in_region)) {
            let (dm, km) = at(i);
            return format!(
                "no gains in the acceptable region keep a_peak within {limit}: no {} pick; the \
                 nearest is D/M {}, K/M {} (zeta {:.3}, a_peak {})",
                rule.name(),
                num(dm),
                num(km),
                zeta(dm, km),
                num(a)
            );
        }
        let j = self.landscape.j(self.extraction.k);
        let every = &mut j.iter().copied().enumerate();
        match least(every) {
            Some((i, v)) => {
                let (dm, km) = at(i);
                let limit = self
                    .limit
                    .map_or(String::new(), |l| format!(" with a_peak within {l}"));
                format!(
                    "no grid point is within {} of J*{limit}: no {} pick (a finer grid or a \
                     larger --accept-eps finds one); the nearest is D/M {}, K/M {} (zeta {:.3}, J \
                     {:.6}, {} above J*)",
                    percent(self.acceptable.eps),
                    rule.name(),
                    num(dm),
                    num(km),
                    zeta(dm, km),
                    v,
                    percent(v / self.extraction.j - 1.0)
                )
            }
            None => format!("no grid point has a finite J: no {} pick", rule.name()),
        }
    }

    fn grid_pick(&self, rule: PickRule) -> Result<(f64, f64), String> {
        let points = self.candidates();
        if points.is_empty()
            && let Some(s) = self.settle_within
            && !self.candidates_without_settling().is_empty()
        {
            return Err(format!(
                "no gains in the acceptable region settle within {s} unit times (2 %): no {} \
                 pick; a larger --settle-within, or a wider box, finds one",
                rule.name()
            ));
        }
        let limit = self
            .limit
            .map_or(String::new(), |l| format!(" with a_peak within {l}"));
        if points.is_empty() {
            return Err(self.nearest_when_empty(rule));
        }
        // Ties: the smaller K/M, then the smaller D/M.
        let tie = |a: &[f64; 4], b: &[f64; 4]| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0]));
        let band_distance = |z: f64| (COMPLIANT_ZETA[0] - z).max(z - COMPLIANT_ZETA[1]).max(0.0);
        let best = match rule {
            PickRule::Compliant => {
                let inside = points.iter().filter(|p| band_distance(p[2]) == 0.0);
                match inside.min_by(|a, b| tie(a, b)) {
                    Some(p) => *p,
                    None => {
                        let near = points
                            .iter()
                            .min_by(|a, b| {
                                band_distance(a[2])
                                    .total_cmp(&band_distance(b[2]))
                                    .then(tie(a, b))
                            })
                            .copied()
                            .unwrap_or(points[0]);
                        return Err(format!(
                            "no gains in the acceptable region{limit} have zeta in [{}, {}]; the \
                             nearest is D/M {}, K/M {} (zeta {:.3})",
                            COMPLIANT_ZETA[0],
                            COMPLIANT_ZETA[1],
                            num(near[0]),
                            num(near[1]),
                            near[2]
                        ));
                    }
                }
            }
            PickRule::Critical => *points
                .iter()
                .min_by(|a, b| {
                    (a[2] - 1.0)
                        .abs()
                        .total_cmp(&(b[2] - 1.0).abs())
                        .then(tie(a, b))
                })
                .unwrap_or(&points[0]),
            PickRule::Smooth | PickRule::Optimum => *points
                .iter()
                .min_by(|a, b| a[3].total_cmp(&b[3]).then(tie(a, b)))
                .unwrap_or(&points[0]),
        };
        Ok((best[0], best[1]))
    }
}
