//! RL with DMP: the environment's dynamics and rewards against hand
//! computation, the hand-written gradients against finite differences, and
//! reproducibility of training.

use dmpscope_core::io::load_bytes;
use dmpscope_core::rl::env::{ACT, DmpEnv};
use dmpscope_core::rl::mlp::{Adam, Mlp};
use dmpscope_core::rl::ppo::{Batch, actor_loss_grad, critic_loss_grad, log_prob};
use dmpscope_core::rl::{PpoConfig, Trainer};
use dmpscope_core::synth::Rng;
use dmpscope_core::{PrepSettings, PreparedDemo, prepare};

fn demo() -> PreparedDemo {
    let bytes = include_bytes!("../../assets/reach10.mcap");
    let loaded = load_bytes("reach10.mcap", bytes).expect("sample");
    prepare(&loaded.demos[0], &PrepSettings::default()).expect("prepare")
}

#[test]
fn one_decision_integrates_and_rewards_as_method_md_says() {
    let d = demo();
    let (dm, km) = (10.0, 100.0);
    let mut env = DmpEnv::new(&d, dm, km).expect("env");
    let u = [0.3, -0.2, 0.1];
    let f = env.forcing(&u);
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
        let norm = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
        reward += -1e-3 * norm(a) - 1e-7 * norm(f);
    }
    let step = env.step(&u, None, None);
    assert!(!step.done);
    assert_eq!(env.position(), y);
    assert!(
        (step.reward - reward).abs() < 1e-15,
        "{} vs {reward}",
        step.reward
    );
}

#[test]
fn the_last_decision_adds_the_terminal_reward_and_stiff_gains_reach_the_goal() {
    let d = demo();
    let mut env = DmpEnv::new(&d, 63.0, 1000.0).expect("env");
    let mut last = None;
    for _ in 0..100 {
        last = Some(env.step(&[0.0; ACT], None, None));
    }
    let last = last.expect("steps");
    assert!(last.done);
    assert!(env.goal_error() < 1e-3, "error {}", env.goal_error());
    // A soft spring does not get there in one unit of time.
    let mut soft = DmpEnv::new(&d, 4.0, 4.0).expect("env");
    for _ in 0..100 {
        soft.step(&[0.0; ACT], None, None);
    }
    assert!(soft.goal_error() > 0.05, "error {}", soft.goal_error());
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

fn batch(actor: &Mlp, log_std: &[f64; 3], rng: &mut Rng) -> Batch {
    let mut b = Batch::default();
    for k in 0..12 {
        let obs: [f64; 7] = std::array::from_fn(|_| rng.normal());
        let (mu, _) = actor.forward(&obs);
        let act: [f64; 3] = std::array::from_fn(|j| mu[j] + 0.3 * rng.normal());
        // Old log-probs a little off so ratios differ from 1, some clipped.
        let logp = log_prob(&act, &mu, log_std) + 0.3 * rng.normal();
        b.obs.push(obs);
        b.act.push(act);
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
    let (_, g) = actor_loss_grad(&actor, &log_std, &b, &idx, clip);
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
            actor_loss_grad(&a, &s, &b, &idx, clip).0
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
        let num = (actor_loss_grad(&actor, &plus, &b, &idx, clip).0
            - actor_loss_grad(&actor, &minus, &b, &idx, clip).0)
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
    let d = demo();
    let run = |seed| {
        let env = DmpEnv::new(&d, 10.73, 20.71).expect("env");
        let mut t = Trainer::new(env, PpoConfig::default(), seed);
        for _ in 0..15 {
            t.iterate();
        }
        (t.returns.clone(), t.greedy())
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
    assert_eq!(ga.path.len(), d.len());
}

#[test]
fn small_steps_give_the_numbers_of_whole_iterations() {
    let d = demo();
    let env = DmpEnv::new(&d, 25.0, 156.25).expect("env");
    let mut whole = Trainer::new(env.clone(), PpoConfig::default(), 4);
    let mut sliced = Trainer::new(env, PpoConfig::default(), 4);
    let mut steps = 0;
    for _ in 0..3 {
        let a = whole.iterate();
        let b = loop {
            steps += 1;
            if let Some(s) = sliced.step() {
                break s;
            }
        };
        assert_eq!(a, b);
    }
    assert!(steps > 3 * 4, "an iteration is many steps ({steps})");
    assert_eq!(whole.greedy(), sliced.greedy());
}
