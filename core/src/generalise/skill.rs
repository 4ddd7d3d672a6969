//! One skill from many demos (method.md section 10): at one gain pair, the
//! mean of the demos' forcing terms, each first mapped into a common frame
//! by the chosen [`Scaling`], with their per-time standard deviation.
//!
//! The common frame starts at the mean of the demos' starts and moves by
//! the mean of their displacements `g - y0`; its duration is the mean
//! duration. Each demo's forcing term and initial velocity are mapped from
//! its own displacement to that one ([`Mapping::between`]), so demos with
//! different starts and goals are compared as the same motion. The skill is
//! then a [`Primitive`] like a demo's, and its rollouts carry a band: the
//! per-time SD of the members' own rollouts to the same target.

use crate::error::{Error, Result};
use crate::fit::mapping::{Mapping, Scaling};
use crate::generalise::primitive::{Primitive, check_gains};
use crate::geom::Vec3;
use crate::landscape::model::Model;

/// The skill of a model's demos at one gain pair.
#[derive(Clone, Debug, PartialEq)]
pub struct Skill {
    /// The primitive to roll out (mean forcing term, mean initial
    /// velocity, mean weights).
    pub primitive: Primitive,
    /// Per-time sample SD (N - 1) of the members' mapped forcing terms, per
    /// axis; zeros for one demo.
    pub forcing_sd: Vec<Vec3>,
    /// The members' names, in order.
    pub demos: Vec<String>,
    /// The scaling the members were mapped with.
    pub scaling: Scaling,
}

impl Skill {
    /// The skill of every demo of `model` at `(dm, km)`.
    pub fn new(model: &Model, dm: f64, km: f64, scaling: Scaling) -> Result<Self> {
        check_gains(dm, km)?;
        let parts: Vec<Primitive> = (0..model.demos().len())
            .map(|i| Primitive::of_demo(model, i, dm, km))
            .collect::<Result<_>>()?;
        let count = parts.len();
        if count == 0 {
            return Err(Error::NoUsableDemo {
                reasons: Vec::new(),
            });
        }
        let nf = count as f64;
        let origin = mean3(parts.iter().map(Primitive::start_abs), nf);
        let displacement = mean3(
            parts
                .iter()
                .map(|p| Vec3::from_fn(|a, _| p.goal[a] - p.y0[a])),
            nf,
        );
        let length = displacement.iter().map(|v| v * v).sum::<f64>().sqrt();
        if scaling == Scaling::Frame && length < 1e-9 {
            return Err(Error::InvalidSetting(
                "the demos' mean displacement is zero (they go opposite ways): a \
                 frame-independent skill has no direction; use per-axis scaling"
                    .into(),
            ));
        }
        let mappings = mappings(&parts, displacement, scaling)?;
        let members: Vec<(Vec<Vec3>, Vec3)> = parts
            .iter()
            .zip(&mappings)
            .map(|(p, m)| {
                let f = p.fdt2.iter().map(|f| m.apply(*f)).collect();
                (f, m.apply(p.v0))
            })
            .collect();
        let (mean, forcing_sd) = mean_and_sd(&members, nf);
        let v0 = mean3(members.iter().map(|m| m.1), nf);
        let weights = mean_weights(&parts, &mappings, nf);
        let duration = parts.iter().map(|p| p.duration_s).sum::<f64>() / nf;
        let primitive = Primitive {
            name: format!("skill ({count} demos)"),
            dm,
            km,
            alpha_x: model.settings().alpha_x,
            origin,
            y0: Vec3::zeros(),
            goal: displacement,
            v0,
            duration_s: duration,
            weights,
            fdt2: mean,
            members,
            extent: 0.0,
            orientation: None,
        }
        .with_extent();
        Ok(Self {
            primitive,
            forcing_sd,
            demos: parts.into_iter().map(|p| p.name).collect(),
            scaling,
        })
    }
}

/// Each demo's map from its own displacement to the skill's.
fn mappings(parts: &[Primitive], displacement: Vec3, scaling: Scaling) -> Result<Vec<Mapping>> {
    parts
        .iter()
        .map(|p| {
            let own = Vec3::from_fn(|a, _| p.goal[a] - p.y0[a]);
            Mapping::between(own, displacement, scaling).map_err(|e| match e {
                Error::InvalidSetting(m) => Error::InvalidSetting(format!("{}: {m}", p.name)),
                other => other,
            })
        })
        .collect()
}

/// The members' mean mapped forcing term (scaled by dt^2, as a primitive
/// keeps it) and its per-time sample SD (N - 1; zeros for one member).
fn mean_and_sd(members: &[(Vec<Vec3>, Vec3)], nf: f64) -> (Vec<Vec3>, Vec<Vec3>) {
    let n = members[0].0.len();
    let mut mean = vec![Vec3::zeros(); n];
    for (f, _) in members {
        for (acc, v) in mean.iter_mut().zip(f) {
            for a in 0..3 {
                acc[a] += v[a];
            }
        }
    }
    for v in &mut mean {
        *v = v.map(|c| c / nf);
    }
    let dt = 1.0 / (n - 1) as f64;
    let dt2 = dt * dt;
    let mut forcing_sd = vec![Vec3::zeros(); n];
    if members.len() > 1 {
        for (f, _) in members {
            for ((acc, v), m) in forcing_sd.iter_mut().zip(f).zip(&mean) {
                for a in 0..3 {
                    let e = (v[a] - m[a]) / dt2;
                    acc[a] += e * e;
                }
            }
        }
        for v in &mut forcing_sd {
            *v = v.map(|c| (c / (nf - 1.0)).sqrt());
        }
    }
    (mean, forcing_sd)
}

/// The members' mean LWR weights, each demo's mapped into the skill's frame.
fn mean_weights(parts: &[Primitive], mappings: &[Mapping], nf: f64) -> [Vec<f64>; 3] {
    let b = parts[0].weights[0].len();
    let mut w = [vec![0.0; b], vec![0.0; b], vec![0.0; b]];
    for (p, m) in parts.iter().zip(mappings) {
        for j in 0..b {
            let mapped = m.apply(Vec3::new(p.weights[0][j], p.weights[1][j], p.weights[2][j]));
            for a in 0..3 {
                w[a][j] += mapped[a];
            }
        }
    }
    w.map(|axis| axis.into_iter().map(|v| v / nf).collect())
}

/// The mean of `values` (their sum, in order, over `n`).
fn mean3(values: impl Iterator<Item = Vec3>, n: f64) -> Vec3 {
    let mut s = Vec3::zeros();
    for v in values {
        for a in 0..3 {
            s[a] += v[a];
        }
    }
    s.map(|v| v / n)
}
