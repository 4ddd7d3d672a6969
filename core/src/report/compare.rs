//! Gain sets compared side by side: up to [`MAX_SETS`] named gain pairs
//! (Table I's rows by name, or typed `DM:KM`), each with its Table I row,
//! its spring-damper's settling time and, for a new target, the run's end
//! error and peak acceleration; the best set of each column.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::extract::allowed::{Settling, mean_duration};
use crate::generalise::primitive::{Primitive, Target};
use crate::generalise::skill::Skill;
use crate::landscape::model::Model;
use crate::report::table::TableRow;

/// The most gain sets compared at once.
pub const MAX_SETS: usize = 6;

/// A named gain pair to compare.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GainSet {
    /// Its name: a Table I row's (`Extracted`, `Hrstc1`, ...) or as typed.
    pub name: String,
    /// D/M.
    pub dm: f64,
    /// K/M.
    pub km: f64,
}

/// Which motion a new target runs: one demo's primitive or the skill of
/// all of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Runs {
    /// Demo `i` (0-based).
    Demo(usize),
    /// The skill of every demo.
    Skill,
}

/// A set's run at a new target (method.md section 10).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TargetRun {
    /// Distance of the run's last point from the goal, metres.
    pub end_error_m: f64,
    /// Largest real-time acceleration norm, m/s^2.
    pub a_peak: f64,
    /// Largest real-time speed, m/s.
    pub peak_speed: f64,
    /// The run's duration, seconds.
    pub duration_s: f64,
}

/// One set's line of the comparison: its Table I row (the same numbers as
/// Table I for the same gains), its settling time and its target run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CompareRow {
    /// The set's Table I row.
    #[serde(flatten)]
    pub row: TableRow,
    /// Its spring-damper's 2 % settling time (method.md section 11).
    pub settling: Settling,
    /// Its run at the new target, when one was asked for.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<TargetRun>,
}

/// A gain pair typed as `DM:KM`, both finite and above zero.
fn typed(item: &str) -> Option<Result<GainSet>> {
    let (dm, km) = item.split_once(':')?;
    let parse = |v: &str| {
        v.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && *x > 0.0)
    };
    Some(match (parse(dm), parse(km)) {
        (Some(dm), Some(km)) => Ok(GainSet {
            name: item.to_owned(),
            dm,
            km,
        }),
        _ => Err(Error::InvalidSetting(format!(
            "gains {item:?}: expected D/M:K/M, two numbers above 0 (e.g. 25:156.25)"
        ))),
    })
}

/// The gain sets a comma-separated list names: Table I's row names (any
/// case; `pick` names the picked row, `optimum` the extracted one) or
/// typed `DM:KM` pairs; at most [`MAX_SETS`], each once.
pub fn resolve(spec: &str, rows: &[TableRow]) -> Result<Vec<GainSet>> {
    let mut sets: Vec<GainSet> = Vec::new();
    for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let set = match typed(item) {
            Some(set) => set?,
            None => named(item, rows)?,
        };
        if !sets.iter().any(|s| s.name == set.name) {
            sets.push(set);
        }
    }
    if sets.is_empty() {
        return Err(Error::InvalidSetting(
            "no gains to compare: name Table I rows or type D/M:K/M pairs".into(),
        ));
    }
    if sets.len() > MAX_SETS {
        return Err(Error::InvalidSetting(format!(
            "{} gain sets: at most {MAX_SETS} are compared at once",
            sets.len()
        )));
    }
    Ok(sets)
}

/// The Table I row `item` names.
fn named(item: &str, rows: &[TableRow]) -> Result<GainSet> {
    let want = item.to_ascii_lowercase();
    let want = match want.as_str() {
        "optimum" => "extracted".to_owned(),
        "pick" | "picked" => "picked".to_owned(),
        _ => want,
    };
    rows.iter()
        .find(|r| {
            let name = r.name.to_ascii_lowercase();
            name == want || (want == "picked" && name.starts_with("picked"))
        })
        .map(|r| GainSet {
            name: r.name.clone(),
            dm: r.dm,
            km: r.km,
        })
        .ok_or_else(|| {
            let known: Vec<&str> = rows.iter().map(|r| r.name.as_str()).collect();
            Error::InvalidSetting(format!(
                "gains {item:?}: not a row of Table I ({}) nor D/M:K/M",
                known.join(", ")
            ))
        })
}

/// The set's run at `target` (of demo `i` or the skill).
pub fn target_run(
    model: &Model,
    set: &GainSet,
    runs: Runs,
    target: &Target,
) -> Result<crate::generalise::primitive::Generalised> {
    let primitive = match runs {
        Runs::Demo(i) => Primitive::of_demo(model, i, set.dm, set.km)?,
        Runs::Skill => Skill::new(model, set.dm, set.km, target.scaling)?.primitive,
    };
    primitive.rollout(target)
}

/// Each set's line: its Table I row at `k`, its settling at the demos'
/// mean duration and, with a target, its run there.
pub fn compare(
    model: &Model,
    sets: &[GainSet],
    k: f64,
    target: Option<(Runs, &Target)>,
) -> Result<Vec<CompareRow>> {
    let duration = mean_duration(model);
    sets.iter()
        .map(|set| {
            let row = TableRow::from_eval(set.name.clone(), &model.evaluate(set.dm, set.km), k);
            let target = match target {
                Some((runs, at)) => {
                    let run = target_run(model, set, runs, at)?;
                    Some(TargetRun {
                        end_error_m: run.final_error,
                        a_peak: run.a_peak,
                        peak_speed: run.peak_speed,
                        duration_s: run.duration_s,
                    })
                }
                None => None,
            };
            Ok(CompareRow {
                settling: Settling::of(set.dm, set.km, duration),
                row,
                target,
            })
        })
        .collect()
}

/// A column of the comparison where less is better, with its value.
pub struct Better {
    /// Its key (as in the JSON).
    pub key: &'static str,
    /// Its value for a row (NaN where it has none).
    pub value: fn(&CompareRow) -> f64,
}

/// The largest of a row's per-demo values (NaN for none).
fn worst(values: &[f64]) -> f64 {
    values.iter().copied().fold(f64::NAN, f64::max)
}

/// The columns whose best set is marked: less is better in each.
pub const BETTER: [Better; 8] = [
    Better {
        key: "s",
        value: |r| r.row.s,
    },
    Better {
        key: "d_sum",
        value: |r| r.row.d_sum,
    },
    Better {
        key: "j",
        value: |r| r.row.j,
    },
    Better {
        key: "e_sum",
        value: |r| r.row.e_sum,
    },
    Better {
        key: "a_peak",
        value: |r| worst(&r.row.a_peak),
    },
    Better {
        key: "settling",
        value: |r| r.settling.unit,
    },
    Better {
        key: "target_end_error_m",
        value: |r| r.target.map_or(f64::NAN, |t| t.end_error_m),
    },
    Better {
        key: "target_a_peak",
        value: |r| r.target.map_or(f64::NAN, |t| t.a_peak),
    },
];

/// For each of [`BETTER`]'s columns that some row has, the index of the
/// row with the least value (the first of equals).
pub fn best(rows: &[CompareRow]) -> Vec<(&'static str, usize)> {
    BETTER
        .iter()
        .filter_map(|b| {
            rows.iter()
                .enumerate()
                .map(|(i, r)| (i, (b.value)(r)))
                .filter(|(_, v)| v.is_finite())
                .min_by(|x, y| x.1.total_cmp(&y.1))
                .map(|(i, _)| (b.key, i))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(name: &str, dm: f64, km: f64) -> TableRow {
        TableRow {
            name: name.into(),
            dm,
            km,
            zeta: 0.0,
            d_mean: vec![],
            a_peak: vec![],
            d_sum: 0.0,
            s: 0.0,
            j: 0.0,
            e: vec![],
            e_sum: f64::NAN,
            d_rot: vec![],
            alpha_peak: vec![],
            d_rot_sum: f64::NAN,
        }
    }

    #[test]
    fn names_and_typed_pairs_resolve_and_bad_ones_say_why() {
        let rows = [
            row("Extracted", 12.0, 25.0),
            row("Picked (compliant)", 40.0, 500.0),
            row("Hrstc1", 25.0, 156.25),
        ];
        let sets = resolve("extracted, PICK,hrstc1,3.5:7", &rows).expect("sets");
        let names: Vec<&str> = sets.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            ["Extracted", "Picked (compliant)", "Hrstc1", "3.5:7"]
        );
        assert_eq!((sets[3].dm, sets[3].km), (3.5, 7.0));
        let unknown = resolve("Hrstc9", &rows).expect_err("unknown");
        assert!(
            unknown
                .to_string()
                .contains("Extracted, Picked (compliant), Hrstc1")
        );
        assert!(resolve("1:-2", &rows).is_err());
        assert!(resolve("1:1,2:2,3:3,4:4,5:5,6:6,7:7", &rows).is_err());
        assert!(resolve(" , ", &rows).is_err());
    }
}
