//! Takes as people record them, written as MCAP: reach-and-return trials
//! with or without a pause at the far end, and one take of reaches to
//! several goals and returns home.

use dmpscope_core::export::write::{TopicSamples, write_pose_stamped};
use dmpscope_core::rng::Rng;

use super::tmp_path;

/// The tracker's rate.
pub const RATE_HZ: f64 = 120.0;
/// Where every take rests between its motions.
pub const HOME: [f64; 3] = [0.2, -0.1, 0.9];

/// A take being written: stamps and positions at [`RATE_HZ`], with 0.3 mm
/// of tracker noise.
pub struct Take {
    t: f64,
    pub samples: Vec<(i64, [f64; 3])>,
    rng: Rng,
}

impl Take {
    pub fn new(seed: u64) -> Self {
        Self {
            t: 1000.0,
            samples: Vec::new(),
            rng: Rng::new(seed),
        }
    }

    pub fn push(&mut self, p: [f64; 3]) {
        let noisy = p.map(|v| v + 0.0003 * self.rng.normal());
        self.samples.push(((self.t * 1e9).round() as i64, noisy));
        self.t += 1.0 / RATE_HZ;
    }

    pub fn here(&self) -> [f64; 3] {
        self.samples.last().map_or(HOME, |s| s.1)
    }

    pub fn rest(&mut self, seconds: f64, at: [f64; 3]) {
        for _ in 0..(seconds * RATE_HZ) as usize {
            self.push(at);
        }
    }

    /// A minimum-jerk move from `from` to `to` over `seconds`, bowed
    /// sideways by 3 cm at its middle.
    pub fn mv(&mut self, from: [f64; 3], to: [f64; 3], seconds: f64) {
        let n = (seconds * RATE_HZ) as usize;
        for k in 1..=n {
            let s = k as f64 / n as f64;
            let shape = 10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5);
            let bow = 0.03 * (std::f64::consts::PI * s).sin();
            self.push(std::array::from_fn(|ax| {
                from[ax] + (to[ax] - from[ax]) * shape + if ax == 2 { bow } else { 0.0 }
            }));
        }
    }
}

pub fn goal(i: usize) -> [f64; 3] {
    let a = 0.4 * i as f64;
    [
        HOME[0] + 0.35 * a.cos(),
        HOME[1] + 0.35 * a.sin(),
        HOME[2] + 0.05,
    ]
}

/// A topic's name and its stamped positions.
pub type Topic = (String, Vec<(i64, [f64; 3])>);

/// Writes `topics` (name, samples) as PoseStamped into a temp MCAP file.
pub fn write(name: &str, topics: &[Topic]) -> String {
    let path = tmp_path(name);
    let samples: Vec<TopicSamples<'_>> = topics
        .iter()
        .map(|(topic, samples)| TopicSamples {
            orientations: None,
            topic,
            frame_id: "world",
            samples,
        })
        .collect();
    let file = std::fs::File::create(&path).expect("file");
    write_pose_stamped(std::io::BufWriter::new(file), &samples, true).expect("write");
    path.to_str().expect("path").to_owned()
}

/// Six reach-to-grasp trials (topics `/trial_1` ..), 0.35 m each; in
/// trials 3 and 6 the hand did not pause at the object.
pub fn trials(name: &str) -> String {
    let trials: Vec<Topic> = (0..6)
        .map(|i| {
            let mut take = Take::new(i as u64);
            take.rest(0.6, HOME);
            take.mv(HOME, goal(i), 1.1);
            let pause = if i == 2 || i == 5 { 0.0 } else { 0.6 };
            take.rest(pause, take.here());
            take.mv(take.here(), HOME, 1.1);
            take.rest(0.6, HOME);
            (format!("/trial_{}", i + 1), take.samples)
        })
        .collect();
    write(name, &trials)
}
