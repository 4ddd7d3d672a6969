//! Which primitives `dmpscope regen` and the Python package's `regen` run,
//! and their runs at a target (method.md section 10): every demo's, one
//! demo's or the skill of all ([`Which`], [`runs`]), and a quaternion
//! argument made unit ([`unit_quaternion`]).

use crate::error::{Error, Result};
use crate::generalise::primitive::{Generalised, Primitive, Target};
use crate::generalise::skill::Skill;
use crate::landscape::model::Model;
use crate::notice::Notice;
use crate::rotation::QuatXyzw;

/// Which primitives to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Which {
    /// Every demo's, in the model's order.
    All,
    /// Demo `i` of the model (0-based).
    Demo(usize),
    /// The skill of all demos.
    Skill,
}

/// One primitive run at a target.
#[derive(Clone, Debug)]
pub struct Run {
    /// The primitive.
    pub primitive: Primitive,
    /// Its run.
    pub out: Generalised,
    /// The model's demo index, for a demo's own comparison and stamps.
    pub demo: Option<usize>,
    /// Skills: the forcing SD and members.
    pub skill: Option<Skill>,
}

/// The primitives `which` names at gains `(dm, km)`, each run at `target`.
/// A target the primitive cannot run at is an [`Error::Target`] naming the
/// argument; a demo out of range an [`Error::InvalidSetting`].
pub fn runs(model: &Model, dm: f64, km: f64, which: Which, target: &Target) -> Result<Vec<Run>> {
    let run_of = |primitive: Primitive, demo, skill| -> Result<Run> {
        let out = primitive.rollout(target).map_err(|e| match e {
            Error::InvalidSetting(m) => Error::Target(m),
            other => other,
        })?;
        Ok(Run {
            primitive,
            out,
            demo,
            skill,
        })
    };
    let indices: Vec<usize> = match which {
        Which::Skill => {
            let skill = Skill::new(model, dm, km, target.scaling)?;
            return Ok(vec![run_of(skill.primitive.clone(), None, Some(skill))?]);
        }
        Which::Demo(i) => vec![i],
        Which::All => (0..model.demos().len()).collect(),
    };
    indices
        .into_iter()
        .map(|i| run_of(Primitive::of_demo(model, i, dm, km)?, Some(i), None))
        .collect()
}

/// A quaternion argument `[x, y, z, w]` made unit, with a note when it
/// was not (`what` names the argument in both); an
/// [`Error::InvalidSetting`] for a zero or non-finite one.
pub fn unit_quaternion(what: &str, q: QuatXyzw) -> Result<(QuatXyzw, Option<Notice>)> {
    let norm = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    if !(norm.is_finite() && norm > 1e-6) {
        return Err(Error::InvalidSetting(format!(
            "{what} must be a rotation: a quaternion of finite, non-zero norm, got {q:?}"
        )));
    }
    let note = ((norm - 1.0).abs() > 1e-9).then(|| {
        Notice::info(format!(
            "{what} {q:?} has norm {norm:.6}; normalised to unit"
        ))
    });
    Ok((q.map(|c| c / norm), note))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quaternions_are_made_unit_with_a_note() {
        let (q, note) = unit_quaternion("--goal-orientation", [0.0, 0.0, 0.0, 2.0]).expect("unit");
        assert_eq!(q, [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(
            note.map(|n| n.to_string()).as_deref(),
            Some(
                "note: --goal-orientation [0.0, 0.0, 0.0, 2.0] has norm 2.000000; normalised to unit"
            )
        );
        let (q, note) = unit_quaternion("q", [0.0, 1.0, 0.0, 0.0]).expect("unit");
        assert_eq!((q, note), ([0.0, 1.0, 0.0, 0.0], None));
        assert!(unit_quaternion("q", [0.0; 4]).is_err());
        assert!(unit_quaternion("q", [f64::NAN, 0.0, 0.0, 1.0]).is_err());
    }
}
