//! RL with DMP: the environment's dynamics and rewards against hand
//! computation, both action modes and the decision options, bad input, the
//! hand-written gradients against finite differences, the normalisers and
//! the orthogonal initialisation, reproducibility of training, and the
//! learner's sanity task (a point mass with a known optimum) that a broken
//! PPO fails.

use dmpscope_core::fit::settings::DmpSettings;
use dmpscope_core::geom::Vec3;
use dmpscope_core::load::mcap::load_bytes;
use dmpscope_core::rl::env::{ACT, ActionMode, DmpEnv, EnvOptions, ExploreScale};
use dmpscope_core::rl::loss::{Batch, actor_loss_grad, critic_loss_grad, log_prob};
use dmpscope_core::rl::mlp::{Adam, Mlp, clip_grad_norm};
use dmpscope_core::rl::norm::{ReturnScale, RunningStat};
use dmpscope_core::rl::outcome::diverged;
use dmpscope_core::rl::point_mass::PointMass;
use dmpscope_core::rl::ppo::{PpoConfig, Trainer};
use dmpscope_core::rl::task::Task;
use dmpscope_core::rng::Rng;
use dmpscope_core::{Model, PrepSettings, prepare};

fn model() -> Model {
    let bytes = include_bytes!("../../assets/reach10.mcap");
    let loaded = load_bytes("reach10.mcap", bytes).expect("sample");
    let d = prepare(&loaded.demos[0], &PrepSettings::default()).expect("prepare");
    Model::new(vec![d], DmpSettings::default()).expect("model")
}

fn env(m: &Model, dm: f64, km: f64) -> DmpEnv {
    DmpEnv::new(m, 0, dm, km, EnvOptions::default()).expect("env")
}

fn norm(x: [f64; 3]) -> f64 {
    (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
}

#[test]
fn one_decision_integrates_and_rewards_as_method_md_says() {
    let m = model();
    let d = &m.demos()[0];
    let (dm, km) = (10.0, 100.0);
    let mut env = env(&m, dm, km);
    let u = [0.3, -0.2, 0.1];
    let f = env.forcing(&u, 0);
    // By hand: 10 semi-implicit Euler steps of dt = 1/1000.
    let (mut y, mut v) = (d.y_raw[0], d.yd[0]);
    let dt = 1.0 / (d.len() - 1) as f64;
    let mut reward = 0.0;
    for _ in 0..10 {
        let a: [f64; 3] = std::array::from_fn(|i| -dm * v[i] - km * (y[i] - d.goal[i]) + f[i]);
        for i in 0..3 {
            v[i] += a[i] * dt;
            y[i] += v[i] * dt;
        }
        reward += -1e-3 * norm(a) - 1e-7 * norm(f);
    }
    let step = env.step(&u);
    assert!(!step.done);
    assert_eq!(Vec3::from(env.position()), y);
    assert!(
        (step.reward - reward).abs() < 1e-15,
        "{} vs {reward}",
        step.reward
    );
}

#[test]
fn the_last_decision_adds_the_terminal_reward_and_stiff_gains_reach_the_goal() {
    let m = model();
    let mut env = env(&m, 63.0, 1000.0);
    let mut last = None;
    for _ in 0..100 {
        last = Some(env.step(&[0.0; ACT]));
    }
    let last = last.expect("steps");
    assert!(last.done);
    assert!(env.goal_error() < 1e-3, "error {}", env.goal_error());
    // A soft spring does not get there in one unit of time.
    let mut soft = self::env(&m, 4.0, 4.0);
    for _ in 0..100 {
        soft.step(&[0.0; ACT]);
    }
    assert!(soft.goal_error() > 0.05, "error {}", soft.goal_error());
}

#[test]
fn a_thousand_decisions_give_the_same_return_as_a_hundred_held_ten_steps() {
    let m = model();
    let opts = EnvOptions {
        decisions: 1000,
        mode: ActionMode::Forcing,
        ..EnvOptions::default()
    };
    let mut fine = DmpEnv::new(&m, 0, 10.0, 100.0, opts).expect("env");
    let mut coarse = env(&m, 10.0, 100.0);
    assert_eq!((fine.decisions(), coarse.decisions()), (1000, 100));
    let u = |k: usize| [0.1 * (k as f64 * 0.3).sin(), -0.05, 0.02];
    let (mut rf, mut rc) = (0.0, 0.0);
    for k in 0..100 {
        rc += coarse.act(&u(k)).reward;
        for _ in 0..10 {
            rf += fine.act(&u(k)).reward;
        }
    }
    assert_eq!(fine.position(), coarse.position());
    assert!((rf - rc).abs() < 1e-12 * rc.abs(), "{rf} vs {rc}");
}

#[test]
fn residual_mode_with_no_action_is_the_lfd_regeneration() {
    let m = model();
    let (dm, km) = (25.0, 156.25);
    let opts = EnvOptions {
        decisions: 100,
        mode: ActionMode::Residual,
        ..EnvOptions::default()
    };
    let env = DmpEnv::new(&m, 0, dm, km, opts).expect("env");
    // A policy whose mean is 0 everywhere: zero last layer.
    let trainer = Trainer::new(env, PpoConfig::default(), 1);
    let mut policy = trainer.policy().clone();
    policy.actor.params.iter_mut().for_each(|p| *p = 0.0);
    let run = trainer.task().greedy(&policy).expect("run");
    let lfd = m.rollout(0, dm, km);
    let worst = run
        .path
        .iter()
        .zip(&lfd.y)
        .map(|(a, b)| norm(std::array::from_fn(|i| a[i] - b[i])))
        .fold(0.0, f64::max);
    assert_eq!(run.path.len(), lfd.y.len());
    assert!(worst < 1e-9, "residual with u = 0 departs by {worst} m");
    // In forcing mode the same policy is the spring alone, elsewhere.
    let spring = self::env(&m, dm, km).greedy(&policy).expect("run");
    assert!(spring.final_error > 0.0 && spring.path != run.path);
}

#[test]
fn exploration_is_scaled_to_the_demos_acceleration_or_its_forcing_term() {
    let m = model();
    let d = &m.demos()[0];
    let (dm, km) = (32.6, 1000.0);
    let rms = |xs: &[Vec3], a: usize| {
        (xs.iter().map(|x| x[a] * x[a]).sum::<f64>() / xs.len() as f64).sqrt()
    };
    let accel = env(&m, dm, km);
    let opts = EnvOptions {
        explore: ExploreScale::Forcing,
        ..EnvOptions::default()
    };
    let forcing = DmpEnv::new(&m, 0, dm, km, opts).expect("env");
    let fitted = m.forcing(0, dm, km);
    let scale = accel.action_scale();
    for a in 0..ACT {
        let want = rms(&d.ydd, a) / scale[a];
        assert!((accel.action_size()[a] - want).abs() < 1e-12 * want);
        let want = rms(&fitted, a) / scale[a];
        assert!((forcing.action_size()[a] - want).abs() < 1e-12 * want);
        // At K/M = 1000 the fitted term is mostly the spring's K (y - g).
        assert!(forcing.action_size()[a] > 10.0 * accel.action_size()[a]);
    }
    // The policy starts at init_sd of it.
    let t = Trainer::new(accel.clone(), PpoConfig::default(), 1);
    for (ls, s) in t.policy().log_std.iter().zip(accel.action_size()) {
        let want = (PpoConfig::default().init_sd * s).ln();
        assert!((ls - want).abs() < 1e-12, "{ls} vs {want}");
    }
}

#[test]
fn bad_input_gets_clear_errors() {
    let m = model();
    for (dm, km) in [(f64::NAN, 10.0), (10.0, f64::INFINITY), (-1.0, 10.0)] {
        let e = DmpEnv::new(&m, 0, dm, km, EnvOptions::default())
            .expect_err("bad gains")
            .to_string();
        assert!(e.contains("finite, non-negative gains"), "{e}");
    }
    for decisions in [0, 1001] {
        let opts = EnvOptions {
            decisions,
            mode: ActionMode::Forcing,
            ..EnvOptions::default()
        };
        let e = DmpEnv::new(&m, 0, 10.0, 10.0, opts)
            .expect_err("decisions")
            .to_string();
        assert!(e.contains("decisions per episode must be 1 to 1000"), "{e}");
    }
    let e = DmpEnv::new(&m, 3, 10.0, 10.0, EnvOptions::default()).expect_err("no demo");
    assert!(e.to_string().contains("no demo 4"), "{e}");
    // A demo that ends where it starts: a closed loop.
    let loaded =
        load_bytes("reach10.mcap", include_bytes!("../../assets/reach10.mcap")).expect("sample");
    let mut raw = loaded.demos[0].clone();
    let n = raw.positions.len();
    for (k, p) in raw.positions.iter_mut().enumerate() {
        let t = k as f64 / (n - 1) as f64 * std::f64::consts::TAU;
        *p = Vec3::new(0.1 * t.sin(), 0.1 * (1.0 - t.cos()), 0.0);
    }
    let d = prepare(&raw, &PrepSettings::default()).expect("prepare");
    let loop_model = Model::new(vec![d], DmpSettings::default()).expect("model");
    let e = DmpEnv::new(&loop_model, 0, 10.0, 10.0, EnvOptions::default())
        .expect_err("no motion")
        .to_string();
    assert!(
        e.contains("from its start") && e.contains("no motion to learn"),
        "{e}"
    );
}

#[test]
fn a_policy_that_goes_non_finite_stops_training_with_a_message() {
    let m = model();
    let mut t = Trainer::new(env(&m, 10.0, 100.0), PpoConfig::default(), 1);
    t.iterate().expect("a sound iteration");
    // Poison the actor as a diverged update would.
    let mut bad = t.policy().clone();
    bad.actor.params[0] = f64::NAN;
    let e = t.task().greedy(&bad).expect_err("non-finite").to_string();
    assert!(e.contains("not finite"), "{e}");
}

fn fd_check(analytic: &[f64], f: &mut dyn FnMut(usize, f64) -> f64, n: usize) {
    let h = 1e-6;
    for i in (0..n).step_by((n / 40).max(1)) {
        let num = (f(i, h) - f(i, -h)) / (2.0 * h);
        let tol = 1e-6 * (1.0 + num.abs());
        assert!(
            (num - analytic[i]).abs() < tol,
            "parameter {i}: finite difference {num}, analytic {}",
            analytic[i]
        );
    }
}

#[test]
fn mlp_gradients_match_finite_differences() {
    let mut rng = Rng::new(3);
    let net = Mlp::new(&[7, 64, 64, 3], &mut rng, 1.0);
    let x = [0.1, -0.5, 0.3, 0.9, -0.2, 0.05, 0.7];
    let w = [0.7, -1.3, 0.4];
    let loss = |net: &Mlp| -> f64 { net.forward(&x).0.iter().zip(w).map(|(o, w)| o * w).sum() };
    let (_, trace) = net.forward(&x);
    let mut grad = vec![0.0; net.params.len()];
    net.backward(&trace, &w, &mut grad);
    let n = net.params.len();
    fd_check(
        &grad,
        &mut |i, h| {
            let mut p = net.clone();
            p.params[i] += h;
            loss(&p)
        },
        n,
    );
}

/// An entropy weight, so its gradient is checked too.
const ENT: f64 = 0.01;

fn batch(actor: &Mlp, log_std: &[f64; 3], rng: &mut Rng) -> Batch {
    let mut b = Batch::default();
    for k in 0..12 {
        let obs: [f64; 7] = std::array::from_fn(|_| rng.normal());
        let (mu, _) = actor.forward(&obs);
        let act: [f64; 3] = std::array::from_fn(|j| mu[j] + 0.3 * rng.normal());
        // Old log-probs a little off so ratios differ from 1, some clipped.
        let logp = log_prob(&act, &mu, log_std) + 0.3 * rng.normal();
        b.obs.push(obs.to_vec());
        b.act.push(act.to_vec());
        b.logp.push(logp);
        b.adv
            .push(if k % 3 == 0 { -1.0 } else { 0.5 } * (1.0 + rng.uniform()));
        b.ret.push(rng.normal());
    }
    b
}

#[test]
fn ppo_actor_and_critic_gradients_match_finite_differences() {
    let mut rng = Rng::new(11);
    let actor = Mlp::new(&[7, 64, 64, 3], &mut rng, 0.5);
    let critic = Mlp::new(&[7, 64, 64, 1], &mut rng, 1.0);
    let log_std = [-0.4, -0.9, 0.1];
    let b = batch(&actor, &log_std, &mut rng);
    let idx: Vec<usize> = (0..b.adv.len()).collect();
    let clip = 0.2;
    let (_, g) = actor_loss_grad(&actor, &log_std, &b, &idx, clip, ENT);
    let n = g.len();
    assert!(g.iter().any(|v| *v != 0.0));
    fd_check(
        &g,
        &mut |i, h| {
            let (mut a, mut s) = (actor.clone(), log_std);
            if i < a.params.len() {
                a.params[i] += h;
            } else {
                s[i - a.params.len()] += h;
            }
            actor_loss_grad(&a, &s, &b, &idx, clip, ENT).0
        },
        n,
    );
    // The log-sd entries (the last three) are checked too.
    for j in 0..3 {
        let i = n - 3 + j;
        let mut plus = log_std;
        plus[j] += 1e-6;
        let mut minus = log_std;
        minus[j] -= 1e-6;
        let num = (actor_loss_grad(&actor, &plus, &b, &idx, clip, ENT).0
            - actor_loss_grad(&actor, &minus, &b, &idx, clip, ENT).0)
            / 2e-6;
        assert!((num - g[i]).abs() < 1e-6 * (1.0 + num.abs()), "log-sd {j}");
    }
    let (_, g) = critic_loss_grad(&critic, &b, &idx);
    fd_check(
        &g,
        &mut |i, h| {
            let mut c = critic.clone();
            c.params[i] += h;
            critic_loss_grad(&c, &b, &idx).0
        },
        critic.params.len(),
    );
}

#[test]
fn adam_descends_a_quadratic() {
    let mut p = vec![3.0, -2.0];
    let mut adam = Adam::new(2, 0.1);
    for _ in 0..500 {
        let g = vec![2.0 * p[0], 2.0 * p[1]];
        adam.step(&mut p, &g);
    }
    assert!(p[0].abs() < 1e-2 && p[1].abs() < 1e-2, "{p:?}");
}

#[test]
fn training_is_reproducible_and_learns() {
    let m = model();
    let run = |seed| {
        let mut t = Trainer::new(env(&m, 10.73, 20.71), PpoConfig::default(), seed);
        for _ in 0..15 {
            t.iterate().expect("iteration");
        }
        let g = t.task().greedy(t.policy()).expect("run");
        (t.returns.clone(), g)
    };
    let (a, ga) = run(7);
    let (b, gb) = run(7);
    assert_eq!(a, b, "same seed, same learning curve");
    assert_eq!(ga, gb);
    let (c, _) = run(8);
    assert_ne!(a, c, "another seed, another curve");
    let first = a[..3].iter().sum::<f64>() / 3.0;
    let last = a[a.len() - 3..].iter().sum::<f64>() / 3.0;
    assert!(last > first, "the return improves: {first} -> {last}");
    assert_eq!(ga.path.len(), m.demos()[0].len());
}

#[test]
fn small_steps_give_the_numbers_of_whole_iterations() {
    let m = model();
    let e = env(&m, 25.0, 156.25);
    let mut whole = Trainer::new(e.clone(), PpoConfig::default(), 4);
    let mut sliced = Trainer::new(e, PpoConfig::default(), 4);
    let mut steps = 0;
    for _ in 0..3 {
        let a = whole.iterate().expect("iteration");
        let b = loop {
            steps += 1;
            if let Some(s) = sliced.step().expect("step") {
                break s;
            }
        };
        assert_eq!(a, b);
    }
    assert!(steps > 3 * 4, "an iteration is many steps ({steps})");
    assert_eq!(whole.policy(), sliced.policy());
}

#[test]
fn orthogonal_layers_are_orthonormal_times_their_gain() {
    let mut rng = Rng::new(5);
    let net = Mlp::orthogonal(&[7, 64, 3], &mut rng, 2.0, 0.5);
    // Layer 1: 64 x 7, orthonormal columns times 2.
    let w = &net.params[..64 * 7];
    for i in 0..7 {
        for j in 0..7 {
            let dot: f64 = (0..64).map(|r| w[r * 7 + i] * w[r * 7 + j]).sum();
            let want = if i == j { 4.0 } else { 0.0 };
            assert!((dot - want).abs() < 1e-10, "columns {i},{j}: {dot}");
        }
    }
    // Layer 2: 3 x 64, orthonormal rows times 0.5, after 64 zero biases.
    let off = 64 * 7 + 64;
    let w2 = &net.params[off..off + 3 * 64];
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..64).map(|c| w2[i * 64 + c] * w2[j * 64 + c]).sum();
            let want = if i == j { 0.25 } else { 0.0 };
            assert!((dot - want).abs() < 1e-10, "rows {i},{j}: {dot}");
        }
    }
}

#[test]
fn normalisers_track_mean_variance_and_return_scale() {
    let mut s = RunningStat::new(2);
    let xs: Vec<[f64; 2]> = (0..1000)
        .map(|k| [k as f64, 3.0 - 0.5 * k as f64])
        .collect();
    for x in &xs {
        s.update(x);
    }
    let mean = 499.5;
    let var = (0..1000).map(|k| (k as f64 - mean).powi(2)).sum::<f64>() / 1000.0;
    assert!((s.mean[0] - mean).abs() < 1e-3 && (s.var[0] - var).abs() < 1e-3 * var);
    assert!((s.mean[1] - (3.0 - 0.5 * mean)).abs() < 1e-3);
    let z = s.normalise(&[mean, 1e9]);
    assert!(z[0].abs() < 1e-3 && z[1] == 10.0, "{z:?}");
    // Rewards -1, -3, -1, ... with gamma 0: the return is the reward, its
    // deviation 1, so the scaled rewards tend to the rewards themselves.
    let mut r = ReturnScale::new(0.0);
    let mut last = 0.0;
    for k in 0..4000 {
        last = r.scale(if k % 2 == 0 { -1.0 } else { -3.0 }, false);
    }
    assert!((last + 3.0).abs() < 1e-2, "{last}");
    let mut g = vec![3.0, 4.0];
    assert_eq!(clip_grad_norm(&mut g, 1.0), 5.0);
    assert!((g[0] - 0.6).abs() < 1e-15 && (g[1] - 0.8).abs() < 1e-15);
}

/// The sanity task: PPO, with the settings the DMP agent trains with, must
/// come within 10 % of the point mass's known least cost in 60 000 decisions;
/// a learner that does not learn (step size 0) or one that climbs the wrong
/// way (the advantage's sign flipped through a negative step size) cannot.
#[test]
fn ppo_solves_the_point_mass_and_a_broken_ppo_does_not() {
    let task = PointMass::new(10);
    let (best, forces) = task.optimal_cost();
    assert!((best - 2.3121387283236996).abs() < 1e-12, "{best}");
    // The closed form is the optimum: the forces give it, a nudge costs.
    let cost = |u: &[f64]| {
        let mut t = PointMass::new(10);
        t.reset();
        -u.iter().map(|f| t.act(&[*f]).reward).sum::<f64>()
    };
    assert!((cost(&forces) - best).abs() < 1e-12);
    let mut nudged = forces.clone();
    nudged[3] += 0.1;
    assert!(cost(&nudged) > best);
    let train = |lr: f64| {
        let budget = 60_000;
        let mut config = PpoConfig::for_episode(10, budget);
        config.lr = lr;
        let mut t = Trainer::new(PointMass::new(10), config, 3);
        while t.decisions() < budget {
            t.iterate().expect("iteration");
        }
        let mut task = t.task().clone();
        -t.policy().run(&mut task).expect("run").ret
    };
    let learned = train(PpoConfig::default().lr);
    assert!(
        learned <= 1.10 * best,
        "cost {learned} against the optimum {best}"
    );
    for broken in [0.0, -PpoConfig::default().lr] {
        let c = train(broken);
        assert!(c > 2.0 * best, "a broken PPO (lr {broken}) got {c}");
    }
}

#[test]
fn a_curve_that_falls_from_its_best_diverged() {
    let rising: Vec<f64> = (0..100).map(|k| -5.0 + 0.04 * k as f64).collect();
    assert!(!diverged(&rising));
    let mut collapsed = rising.clone();
    collapsed[90..].iter_mut().for_each(|r| *r = -4.0);
    assert!(diverged(&collapsed));
    assert!(!diverged(&[]));
}
