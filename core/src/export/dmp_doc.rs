//! The DMP export a controller can run (`docs/export.md`, schema
//! `docs/dmpscope.dmp.schema.json`): the equations in words, every number
//! they need, and a golden rollout to check an implementation against.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::fit::mapping::Scaling;
use crate::generalise::primitive::{Generalised, Primitive};

/// The schema's name (no URL: it is a name, not a location).
pub const SCHEMA: &str = "dmpscope.dmp";
/// The schema's version; a reader refuses any other.
pub const VERSION: u32 = 2;

/// The equations, in symbols with their words.
#[derive(Clone, Debug, Serialize)]
pub struct Equations {
    /// The transformation system in unit time.
    pub transformation_system: &'static str,
    /// The canonical system.
    pub canonical_system: &'static str,
    /// The forcing term and its basis.
    pub forcing_term: &'static str,
    /// How the forcing term and initial velocity follow the new start and
    /// goal, for this document's mode.
    pub spatial_scaling: &'static str,
    /// The integration scheme.
    pub integration: &'static str,
    /// How unit time maps to real time.
    pub unit_time: &'static str,
}

/// The integration grid.
#[derive(Clone, Debug, Serialize)]
pub struct Integration {
    /// `semi_implicit_euler`.
    pub scheme: &'static str,
    /// Grid points n (the rollout has n samples).
    pub points: usize,
    /// Unit-time step `1 / (n - 1)`.
    pub dt: f64,
}

/// A gain pair.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct GainPair {
    /// Damping over mass.
    pub d: f64,
    /// Stiffness over mass.
    pub k: f64,
}

/// The gains in unit time and their real-time equivalents for `tau`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Gains {
    /// D/M and K/M of the unit-time system (what was extracted).
    pub unit_time: GainPair,
    /// `D/M / tau` and `K/M / tau^2`: the same motion written in seconds.
    pub real_time: GainPair,
    /// Damping ratio `D / (2 sqrt(K))` (the same in both).
    pub zeta: f64,
    /// Natural frequency `sqrt(K/M) / tau`, rad/s.
    pub natural_frequency_rad_s: f64,
    /// The 2 % settling time of the spring-damper at `tau`, seconds
    /// (docs/method.md section 11).
    pub settling_time_s: f64,
}

/// The radial basis.
#[derive(Clone, Debug, Serialize)]
pub struct BasisDoc {
    /// Number of basis functions B.
    pub count: usize,
    /// True: centres and widths live in phase x, not in time.
    pub in_phase: bool,
    /// Centres `c_i`.
    pub centres: Vec<f64>,
    /// Widths `h_i`.
    pub widths: Vec<f64>,
}

/// LWR weights per axis.
#[derive(Clone, Debug, Serialize)]
pub struct Weights {
    /// x axis.
    pub x: Vec<f64>,
    /// y axis.
    pub y: Vec<f64>,
    /// z axis.
    pub z: Vec<f64>,
}

/// The spatial scaling used.
#[derive(Clone, Debug, Serialize)]
pub struct ScalingDoc {
    /// `paper` or `frame`.
    pub mode: &'static str,
    /// The 3 x 3 map it gives for this document's y0, g, y0_new, g_new
    /// (row-major), for checking an implementation's.
    pub matrix: [[f64; 3]; 3],
}

/// Units of the numbers.
#[derive(Clone, Debug, Serialize)]
pub struct Units {
    /// Positions.
    pub position: &'static str,
    /// Real time.
    pub time: &'static str,
    /// Real-time velocity.
    pub velocity: &'static str,
    /// Real-time acceleration.
    pub acceleration: &'static str,
    /// The unit of the recordings the DMP was learned from (`m`, `cm`,
    /// `mm`); every position here is in metres either way.
    pub recorded: &'static str,
}

/// The golden rollout: real time from 0 to tau.
#[derive(Clone, Debug, Serialize)]
pub struct RolloutDoc {
    /// Seconds.
    pub t: Vec<f64>,
    /// Positions, starting exactly at `y0_new`.
    pub y: Vec<[f64; 3]>,
    /// Velocities, m/s.
    pub v: Vec<[f64; 3]>,
    /// Accelerations, m/s^2.
    pub a: Vec<[f64; 3]>,
    /// Orientations `[x, y, z, w]`, one per step, starting exactly at
    /// `orientation.q0_new` (with an orientation DMP).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub q: Option<Vec<[f64; 4]>>,
}

/// The orientation DMP (method.md section 12): the same phase, basis and
/// grid as the position, at the position's gains or its own.
#[derive(Clone, Debug, Serialize)]
pub struct OrientationDoc {
    /// The transformation system.
    pub equation: &'static str,
    /// The integration.
    pub integration: &'static str,
    /// LWR weights of the orientation forcing term per axis.
    pub weights: Weights,
    /// The fitted start orientation `[x, y, z, w]`.
    pub q0: [f64; 4],
    /// The fitted goal orientation.
    pub q_goal: [f64; 4],
    /// The start orientation of this run.
    pub q0_new: [f64; 4],
    /// The goal orientation of this run.
    pub q_goal_new: [f64; 4],
    /// `w(0)` in unit time (rad per unit time), used unchanged.
    pub initial_angular_velocity: [f64; 3],
    /// The orientation's gains `[D_M, K_M]` in unit time: the position's,
    /// or separate ones (`--orientation-gains`).
    pub gains_unit_time: [f64; 2],
}

/// One exported DMP.
#[derive(Clone, Debug, Serialize)]
pub struct DmpDocument {
    /// [`SCHEMA`].
    pub schema: &'static str,
    /// [`VERSION`].
    pub version: u32,
    /// The demo's name, or `skill (N demos)`.
    pub name: String,
    /// `demo` or `skill`.
    pub source: &'static str,
    /// The demos it was made from.
    pub demos: Vec<String>,
    /// The equations.
    pub equations: Equations,
    /// The integration grid.
    pub integration: Integration,
    /// Duration of the motion, seconds (T').
    pub tau: f64,
    /// The fitted motion's own duration, seconds.
    pub fitted_duration_s: f64,
    /// The gains.
    pub gains: Gains,
    /// Decay of the canonical system.
    pub alpha_x: f64,
    /// The basis.
    pub basis: BasisDoc,
    /// LWR weights of the forcing term per axis.
    pub weights: Weights,
    /// `y'(0)` in unit time of the fitted motion (scaled like the forcing
    /// term before use).
    pub initial_velocity: [f64; 3],
    /// Fitted start, metres.
    pub y0: [f64; 3],
    /// Fitted goal, metres.
    pub g: [f64; 3],
    /// New start, metres.
    pub y0_new: [f64; 3],
    /// New goal, metres.
    pub g_new: [f64; 3],
    /// The scaling.
    pub scaling: ScalingDoc,
    /// The frame the positions are in.
    pub frame_id: String,
    /// The up axis of that frame (`z`: ROS REP 103).
    pub up_axis: &'static str,
    /// Units.
    pub units: Units,
    /// The golden rollout.
    pub rollout: RolloutDoc,
    /// Skills: per-time SD of the members' positions at the new target
    /// (metres), beside `rollout.y`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rollout_sd: Option<Vec<[f64; 3]>>,
    /// The orientation DMP, for a demo recorded with orientation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orientation: Option<OrientationDoc>,
}

const ORIENTATION_EQUATION: &str = "w'(u) = -D_M w(u) + K_M 2 log(q_goal_new * conj(q(u))) + \
     f_o(x(u)), q' = 1/2 w * q (Hamilton product, quaternions [x, y, z, w], w the angular \
     velocity in the space frame, rad per unit time); log(v, s) = atan2(|v|, s) v / |v|; \
     f_o as the position's forcing term with orientation.weights";
const ORIENTATION_INTEGRATION: &str = "q_0 = q0_new, w_0 = initial_angular_velocity; a_k = \
     -D_M w_k + K_M 2 log(q_goal_new * conj(q_k)) + f_o(x(u_k)); w_{k+1} = w_k + a_k dt; \
     q_{k+1} = exp(w_{k+1} dt / 2) * q_k, exp(v) = (sin|v| v / |v|, cos|v|), renormalised";

const TRANSFORMATION: &str = "y''(u) = -D_M y'(u) - K_M (y(u) - g_new) + Q f(x(u)), per axis, \
     u in [0, 1] unit time, y' = dy/du; D_M, K_M = gains.unit_time.d, .k";
const CANONICAL: &str = "x(u) = exp(-alpha_x u), x(0) = 1 (closed form, not integrated)";
const FORCING: &str = "f_a(x) = x sum_i psi_i(x) w_a,i / sum_i psi_i(x), \
     psi_i(x) = exp(-h_i (x - c_i)^2); c = basis.centres, h = basis.widths, w_a = weights.<axis>";
const SCALING_PAPER: &str = "paper: Q = diag(m_a), m_a = (g_new_a - y0_new_a) / (g_a - y0_a), \
     m_a = 1 where |g_a - y0_a| < 1e-9; Q is the identity when g_new - y0_new = g - y0";
const SCALING_FRAME: &str = "frame: Q = s R, s = |g_new - y0_new| / |g - y0|, R the smallest \
     rotation taking (g - y0) / |g - y0| to (g_new - y0_new) / |g_new - y0_new| (Rodrigues; \
     identity when parallel); Q is the identity when g_new - y0_new = g - y0";
const INTEGRATION: &str = "semi-implicit Euler on u_k = k dt, k = 0..n-1, dt = 1/(n-1): \
     y_0 = y0_new, v_0 = Q initial_velocity; a_k = -D_M v_k - K_M (y_k - g_new) + Q f(x(u_k)); \
     v_{k+1} = v_k + a_k dt; y_{k+1} = y_k + v_{k+1} dt";
const UNIT_TIME: &str = "t = tau u: position y(t) = y(u), velocity = y'(u) / tau, acceleration \
     = y''(u) / tau^2; in real time the gains are D_M / tau and K_M / tau^2 and the forcing term \
     Q f / tau^2";

/// Everything needed besides the primitive and its rollout.
pub struct DocContext<'a> {
    /// The demos the primitive came from.
    pub demos: Vec<String>,
    /// `demo` or `skill`.
    pub source: &'static str,
    /// Basis centres and widths.
    pub basis: (&'a [f64], &'a [f64]),
    /// The frame of the positions.
    pub frame_id: String,
    /// The skill's per-time position SD, when a skill.
    pub band: Option<Vec<crate::geom::Vec3>>,
    /// The scaling mode used.
    pub scaling: Scaling,
    /// The unit the recordings were in (converted to metres at loading).
    pub recorded_units: crate::load::units::Units,
}

/// The export of `primitive` run at `out`. Fails, naming the field,
/// when any number is not finite: an export never holds NaN.
pub fn dmp_document(
    primitive: &Primitive,
    out: &Generalised,
    ctx: DocContext<'_>,
) -> Result<DmpDocument> {
    let n = out.t.len();
    let tau = out.duration_s;
    let [wx, wy, wz] = primitive.weights.clone();
    let doc = DmpDocument {
        schema: SCHEMA,
        version: VERSION,
        name: primitive.name.clone(),
        source: ctx.source,
        demos: ctx.demos,
        equations: equations(ctx.scaling),
        integration: Integration {
            scheme: "semi_implicit_euler",
            points: n,
            dt: 1.0 / (n.max(2) - 1) as f64,
        },
        tau,
        fitted_duration_s: primitive.duration_s,
        gains: gains(primitive, tau),
        alpha_x: primitive.alpha_x,
        basis: BasisDoc {
            count: ctx.basis.0.len(),
            in_phase: true,
            centres: ctx.basis.0.to_vec(),
            widths: ctx.basis.1.to_vec(),
        },
        weights: Weights {
            x: wx,
            y: wy,
            z: wz,
        },
        initial_velocity: primitive.v0.into(),
        y0: primitive.start_abs().into(),
        g: primitive.goal_abs().into(),
        y0_new: out.start.into(),
        g_new: out.goal.into(),
        scaling: ScalingDoc {
            mode: ctx.scaling.name(),
            matrix: out.mapping.matrix(),
        },
        frame_id: ctx.frame_id,
        up_axis: "z",
        units: units(ctx.recorded_units),
        rollout: RolloutDoc {
            t: out.t.clone(),
            y: crate::geom::arrays(&out.unit.y),
            v: crate::geom::arrays(&out.v),
            a: crate::geom::arrays(&out.a),
            q: out.orientation.as_ref().map(|o| o.q.clone()),
        },
        rollout_sd: ctx.band.as_deref().map(crate::geom::arrays),
        orientation: orientation_doc(primitive, out),
    };
    validate(&doc)?;
    Ok(doc)
}

/// The export of one run of [`crate::generalise::run::runs`]: a demo's
/// DMP (`source` `demo`) or the skill's (`skill`, with its band), in
/// `frame_id`, the recordings having been in `recorded_units`; as
/// `dmpscope regen --out F.json` writes it.
pub fn run_document(
    model: &crate::landscape::model::Model,
    run: &crate::generalise::run::Run,
    frame_id: String,
    scaling: Scaling,
    recorded_units: crate::load::units::Units,
) -> Result<DmpDocument> {
    dmp_document(
        &run.primitive,
        &run.out,
        DocContext {
            demos: match &run.skill {
                Some(s) => s.demos.clone(),
                None => vec![run.primitive.name.clone()],
            },
            source: if run.skill.is_some() { "skill" } else { "demo" },
            basis: (&model.basis().centres, &model.basis().widths),
            frame_id,
            band: run.skill.as_ref().map(|_| run.out.band.clone()),
            scaling,
            recorded_units,
        },
    )
}

/// The equations in words, with the scaling's.
fn equations(scaling: Scaling) -> Equations {
    Equations {
        transformation_system: TRANSFORMATION,
        canonical_system: CANONICAL,
        forcing_term: FORCING,
        spatial_scaling: match scaling {
            Scaling::Paper => SCALING_PAPER,
            Scaling::Frame => SCALING_FRAME,
        },
        integration: INTEGRATION,
        unit_time: UNIT_TIME,
    }
}

/// The gains in unit and real time at the duration `tau`.
fn gains(primitive: &Primitive, tau: f64) -> Gains {
    Gains {
        unit_time: GainPair {
            d: primitive.dm,
            k: primitive.km,
        },
        real_time: GainPair {
            d: primitive.dm / tau,
            k: primitive.km / (tau * tau),
        },
        zeta: crate::landscape::model::zeta(primitive.dm, primitive.km),
        natural_frequency_rad_s: primitive.km.sqrt() / tau,
        settling_time_s: crate::extract::robot::settling_time(primitive.dm, primitive.km) * tau,
    }
}

/// The units of every number, and the recordings' own.
fn units(recorded: crate::load::units::Units) -> Units {
    Units {
        position: "m",
        time: "s",
        velocity: "m/s",
        acceleration: "m/s^2",
        recorded: recorded.name(),
    }
}

/// The orientation part of the document, for a primitive with one.
fn orientation_doc(primitive: &Primitive, out: &Generalised) -> Option<OrientationDoc> {
    let o = primitive.orientation.as_ref()?;
    let path = out.orientation.as_ref()?;
    let [x, y, z] = o.weights.clone();
    Some(OrientationDoc {
        equation: ORIENTATION_EQUATION,
        integration: ORIENTATION_INTEGRATION,
        weights: Weights { x, y, z },
        q0: o.start,
        q_goal: o.goal,
        q0_new: *path.q.first()?,
        q_goal_new: out.orientation_goal.unwrap_or(o.goal),
        initial_angular_velocity: o.w0,
        gains_unit_time: [o.gains.0, o.gains.1],
    })
}

/// Fails on the first non-finite number, naming its field.
fn validate(doc: &DmpDocument) -> Result<()> {
    let value = serde_json::to_value(doc)
        .map_err(|e| Error::InvalidSetting(format!("the export does not serialise: {e}")))?;
    // serde_json turns non-finite floats into null: any null is one.
    fn find_null(v: &serde_json::Value, path: &mut String) -> bool {
        match v {
            serde_json::Value::Null => true,
            serde_json::Value::Array(items) => items.iter().enumerate().any(|(i, item)| {
                let len = path.len();
                path.push_str(&format!("[{i}]"));
                let found = find_null(item, path);
                if !found {
                    path.truncate(len);
                }
                found
            }),
            serde_json::Value::Object(map) => map.iter().any(|(k, item)| {
                let len = path.len();
                path.push('.');
                path.push_str(k);
                let found = find_null(item, path);
                if !found {
                    path.truncate(len);
                }
                found
            }),
            _ => false,
        }
    }
    let mut path = String::new();
    if find_null(&value, &mut path) {
        return Err(Error::InvalidSetting(format!(
            "the export would hold a non-finite number at {}: nothing written (the motion \
             diverges at these gains and target)",
            path.trim_start_matches('.')
        )));
    }
    Ok(())
}
