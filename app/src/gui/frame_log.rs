//! Frame timing for measurements: with `DMPSCOPE_FRAME_LOG=path` the app
//! records the interval between frames and egui's CPU time per frame and
//! rewrites a summary (medians, 95th percentiles, maxima) to `path` every
//! 10 frames, with where the 3D view drew the new target's start and goal
//! (so `tests/frame_time.sh` can drag them). Where Linux tells it
//! (`/proc/thread-self/schedstat`), it also records the app thread's CPU
//! time from one frame to the next (everything the thread ran: `ui`,
//! tessellation, the renderer's submission and the present) and the time
//! the thread waited for a core: egui's CPU time is wall time, which grows
//! when the rasteriser's threads hold the cores.

use std::path::PathBuf;
use web_time::Instant;

/// The log, when asked for.
pub struct FrameLog {
    path: PathBuf,
    last: Option<Instant>,
    intervals_ms: Vec<f64>,
    cpu_ms: Vec<f64>,
    thread_ms: Vec<f64>,
    wait_ms: Vec<f64>,
    last_sched: Option<[u64; 2]>,
    handles: Option<[[f32; 2]; 2]>,
}

impl FrameLog {
    /// The log named by `DMPSCOPE_FRAME_LOG`, if set.
    pub fn from_env() -> Option<Self> {
        let path = std::env::var_os("DMPSCOPE_FRAME_LOG")?;
        Some(Self {
            path: PathBuf::from(path),
            last: None,
            intervals_ms: Vec::new(),
            cpu_ms: Vec::new(),
            thread_ms: Vec::new(),
            wait_ms: Vec::new(),
            last_sched: None,
            handles: None,
        })
    }

    /// Where the new target's start and goal were drawn, screen points.
    pub fn handles(&mut self, at: Option<[[f32; 2]; 2]>) {
        self.handles = at;
    }

    /// Records a frame; `cpu_s` is eframe's CPU time of the previous frame.
    pub fn frame(&mut self, cpu_s: Option<f32>) {
        let now = Instant::now();
        if let Some(last) = self.last {
            self.intervals_ms
                .push(now.duration_since(last).as_secs_f64() * 1e3);
        }
        self.last = Some(now);
        if let Some(cpu) = cpu_s {
            self.cpu_ms.push(f64::from(cpu) * 1e3);
        }
        let sched = thread_sched_ns();
        if let (Some([run0, wait0]), Some([run1, wait1])) = (self.last_sched, sched) {
            self.thread_ms.push(run1.saturating_sub(run0) as f64 * 1e-6);
            self.wait_ms.push(wait1.saturating_sub(wait0) as f64 * 1e-6);
        }
        self.last_sched = sched;
        if self.intervals_ms.len() % 10 == 9 {
            let mut text = format!(
                "frames {}\ninterval_ms {}\ncpu_ms {}\n",
                self.intervals_ms.len(),
                summary(&self.intervals_ms),
                summary(&self.cpu_ms)
            );
            if !self.thread_ms.is_empty() {
                text.push_str(&format!(
                    "thread_cpu_ms {}\nthread_wait_ms {}\n",
                    summary(&self.thread_ms),
                    summary(&self.wait_ms)
                ));
            }
            if let Some([s, g]) = self.handles {
                text.push_str(&format!(
                    "handles start {:.0} {:.0} goal {:.0} {:.0}\n",
                    s[0], s[1], g[0], g[1]
                ));
            }
            let _ = std::fs::write(&self.path, text);
        }
    }

    /// Forgets what was recorded (e.g. once the landscape is complete).
    pub fn reset(&mut self) {
        self.intervals_ms.clear();
        self.cpu_ms.clear();
        self.thread_ms.clear();
        self.wait_ms.clear();
        self.last_sched = None;
        self.last = None;
    }
}

/// This thread's time on a core and waiting for one so far, ns (Linux's
/// scheduler statistics; `None` elsewhere).
fn thread_sched_ns() -> Option<[u64; 2]> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let mut fields = text.split_whitespace().map(str::parse::<u64>);
    Some([fields.next()?.ok()?, fields.next()?.ok()?])
}

fn summary(v: &[f64]) -> String {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let at = |q: f64| {
        s.get(((s.len() as f64 - 1.0) * q).round() as usize)
            .copied()
            .unwrap_or(0.0)
    };
    format!(
        "median {:.2} p95 {:.2} max {:.2}",
        at(0.5),
        at(0.95),
        at(1.0)
    )
}
