//! Pinned gain sets (issue 45): up to six named gain pairs, each with a
//! colour of [`SET_COLOURS`], compared with one another and with the live
//! operating point. What they show is computed here once per set and
//! model (and target), never per frame: each pin's regeneration of every
//! demo, its run at the New target tab's target, and the comparison rows.

use std::sync::Arc;

use dmpscope_core::fit::orientation::OrientationRollout;
use dmpscope_core::generalise::primitive::Generalised;
use dmpscope_core::report::compare::{CompareRow, GainSet, MAX_SETS, Runs, compare, target_run};
use dmpscope_core::{Model, Rollout};

use super::view3d::ScenePin;
use crate::figure::SET_COLOURS;
use crate::session::generalise::{GeneraliseSpec, TargetSource};

/// One pinned gain set.
#[derive(Clone, Debug, PartialEq)]
pub struct Pin {
    /// Its name (a Table I row's, a typed pair, or as renamed).
    pub name: String,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
    /// Its colour (sRGB).
    pub colour: [u8; 3],
    /// Whether its overlays are drawn.
    pub shown: bool,
    /// Its regeneration of every model demo, in model order.
    regen: Vec<Rollout>,
    /// Its regenerated orientation of every model demo (`None` for a demo
    /// without orientation).
    turns: Vec<Option<OrientationRollout>>,
    /// Its run at the target, or why there is none.
    target: Option<Result<Generalised, String>>,
    /// Every demo's standardised forcing term `f[demo][k]` (the Forcing
    /// terms tab).
    forcing: Vec<Vec<[f64; 3]>>,
}

/// What the pins' computed parts were computed for: the model version, the
/// table's k, and the target (its bits).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Key {
    model: Option<u64>,
    k: u64,
    target: Option<(Option<usize>, [u64; 7], bool)>,
}

/// The pinned sets and what they show.
#[derive(Default)]
pub struct Pins {
    list: Vec<Pin>,
    key: Key,
    rows: Vec<CompareRow>,
    /// Per pin, whether its computed parts are current.
    fresh: Vec<bool>,
}

fn target_key(spec: &GeneraliseSpec) -> (Option<usize>, [u64; 7], bool) {
    let t = &spec.target;
    let v = |p: Option<dmpscope_core::geom::Vec3>, a: usize| p.map_or(u64::MAX, |p| p[a].to_bits());
    (
        match spec.source {
            TargetSource::Demo(i) => Some(i),
            TargetSource::Skill => None,
        },
        [
            v(t.start, 0),
            v(t.start, 1),
            v(t.start, 2),
            v(t.goal, 0),
            v(t.goal, 1),
            v(t.goal, 2),
            t.duration_s.map_or(u64::MAX, f64::to_bits),
        ],
        t.scaling == dmpscope_core::Scaling::Frame,
    )
}

impl Pins {
    /// The pins, in the order they were pinned.
    pub fn list(&self) -> &[Pin] {
        &self.list
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Pins `(dm, km)` as `name` (made unique), with the first colour no
    /// pin has; an error when six are pinned or the gains are not positive.
    pub fn add(&mut self, name: &str, dm: f64, km: f64) -> Result<(), String> {
        if self.list.len() >= MAX_SETS {
            return Err(format!(
                "at most {MAX_SETS} sets are pinned: remove one first"
            ));
        }
        if !(dm.is_finite() && dm > 0.0 && km.is_finite() && km > 0.0) {
            return Err(format!("D/M {dm} and K/M {km} must be numbers above 0"));
        }
        let mut unique = name.trim().to_owned();
        if unique.is_empty() {
            unique = format!("{dm:.3}:{km:.3}");
        }
        let base = unique.clone();
        let mut n = 2;
        while self.list.iter().any(|p| p.name == unique) {
            unique = format!("{base} ({n})");
            n += 1;
        }
        let colour = SET_COLOURS
            .iter()
            .copied()
            .find(|c| self.list.iter().all(|p| p.colour != *c))
            .unwrap_or(SET_COLOURS[0]);
        self.list.push(Pin {
            name: unique,
            dm,
            km,
            colour,
            shown: true,
            regen: Vec::new(),
            turns: Vec::new(),
            target: None,
            forcing: Vec::new(),
        });
        self.fresh.push(false);
        self.rows.clear();
        Ok(())
    }

    /// Removes pin `i`.
    pub fn remove(&mut self, i: usize) {
        if i < self.list.len() {
            self.list.remove(i);
            self.fresh.remove(i);
            self.rows.clear();
        }
    }

    /// Renames pin `i` (to a unique, non-empty name).
    pub fn rename(&mut self, i: usize, name: &str) {
        let name = name.trim();
        let taken = self
            .list
            .iter()
            .enumerate()
            .any(|(j, p)| j != i && p.name == name);
        if let Some(p) = self.list.get_mut(i)
            && !name.is_empty()
            && !taken
        {
            p.name = name.to_owned();
            self.rows.clear();
        }
    }

    /// Shows or hides pin `i`'s overlays.
    pub fn set_shown(&mut self, i: usize, shown: bool) {
        if let Some(p) = self.list.get_mut(i) {
            p.shown = shown;
        }
    }

    /// Brings what the pins show up to `model` (its version), `k` and the
    /// New target tab's `spec`: only what changed is computed.
    pub fn refresh(
        &mut self,
        model: Option<(&Arc<Model>, u64)>,
        k: f64,
        spec: Option<&GeneraliseSpec>,
    ) {
        let key = Key {
            model: model.map(|m| m.1),
            k: k.to_bits(),
            target: spec.map(target_key),
        };
        if key != self.key {
            self.key = key;
            self.fresh.iter_mut().for_each(|f| *f = false);
            self.rows.clear();
        }
        let Some((model, _)) = model else {
            return;
        };
        for (pin, fresh) in self.list.iter_mut().zip(&mut self.fresh) {
            if *fresh {
                continue;
            }
            pin.regen = (0..model.demos().len())
                .map(|i| model.rollout(i, pin.dm, pin.km))
                .collect();
            pin.turns = (0..model.demos().len())
                .map(|i| model.orientation_rollout(i, pin.dm, pin.km))
                .collect();
            pin.forcing = model.similarity().standardised(pin.dm, pin.km).f;
            pin.target = spec.map(|s| {
                let runs = match s.source {
                    TargetSource::Demo(i) => Runs::Demo(i),
                    TargetSource::Skill => Runs::Skill,
                };
                target_run(model, &set_of(pin), runs, &s.target).map_err(|e| e.to_string())
            });
            *fresh = true;
        }
        if self.rows.is_empty() && !self.list.is_empty() {
            let sets: Vec<GainSet> = self.list.iter().map(set_of).collect();
            let target = spec.map(|s| {
                let runs = match s.source {
                    TargetSource::Demo(i) => Runs::Demo(i),
                    TargetSource::Skill => Runs::Skill,
                };
                (runs, s.target)
            });
            self.rows = compare(model, &sets, k, target.as_ref().map(|(r, t)| (*r, t)))
                .or_else(|_| compare(model, &sets, k, None))
                .unwrap_or_default();
        }
    }

    /// The comparison's rows (pin order), once computed.
    pub fn rows(&self) -> &[CompareRow] {
        &self.rows
    }

    /// The shown pins with their regenerations (every model demo).
    pub fn shown_regen(&self) -> impl Iterator<Item = (&Pin, &[Rollout])> {
        self.list
            .iter()
            .filter(|p| p.shown && !p.regen.is_empty())
            .map(|p| (p, p.regen.as_slice()))
    }

    /// The shown pins with their regenerated orientation of demo `i` (those
    /// whose demo `i` has one).
    pub fn shown_turns(&self, i: usize) -> impl Iterator<Item = (&Pin, &OrientationRollout)> {
        self.list
            .iter()
            .filter(|p| p.shown)
            .filter_map(move |p| p.turns.get(i)?.as_ref().map(|t| (p, t)))
    }

    /// The shown pins with demo `i`'s standardised forcing term.
    pub fn shown_forcing(&self, i: usize) -> impl Iterator<Item = (&Pin, &[[f64; 3]])> {
        self.list
            .iter()
            .filter(|p| p.shown)
            .filter_map(move |p| p.forcing.get(i).map(|f| (p, f.as_slice())))
    }

    /// The shown pins with their runs at the target.
    pub fn shown_targets(&self) -> impl Iterator<Item = (&Pin, &Generalised)> {
        self.list
            .iter()
            .filter(|p| p.shown)
            .filter_map(|p| match &p.target {
                Some(Ok(g)) => Some((p, g)),
                _ => None,
            })
    }

    /// Why pin `i` has no run at the target, if it has none.
    pub fn target_failure(&self, i: usize) -> Option<&str> {
        match self.list.get(i).and_then(|p| p.target.as_ref()) {
            Some(Err(e)) => Some(e),
            _ => None,
        }
    }

    /// The shown pins as the 3D view draws them: name, colour, every
    /// demo's regeneration and the run at the target.
    pub fn scene(&self) -> Vec<(String, ScenePin<'_>)> {
        self.list
            .iter()
            .filter(|p| p.shown && !p.regen.is_empty())
            .map(|p| {
                let target = match &p.target {
                    Some(Ok(g)) => Some(g.unit.y.as_slice()),
                    _ => None,
                };
                (
                    p.name.clone(),
                    ScenePin {
                        colour: p.colour,
                        regen: &p.regen,
                        target,
                    },
                )
            })
            .collect()
    }

    /// The pins as the core's gain sets.
    pub fn sets(&self) -> Vec<GainSet> {
        self.list.iter().map(set_of).collect()
    }
}

fn set_of(p: &Pin) -> GainSet {
    GainSet {
        name: p.name.clone(),
        dm: p.dm,
        km: p.km,
    }
}
