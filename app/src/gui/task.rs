//! Work that may take longer than a frame, off the frame: on a thread
//! natively; in the browser (no threads) it runs at the first poll, where
//! it is short (a file's demos, one extraction).

use std::sync::mpsc::{Receiver, TryRecvError};

/// A computation of a `T` under way.
pub struct Task<T> {
    /// Native: the thread's answer.
    rx: Option<Receiver<T>>,
    /// Web: the work, run when first polled.
    later: Option<Box<dyn FnOnce() -> T>>,
    /// The answer when the thread could not start or died.
    failed: Option<String>,
}

impl<T: Send + 'static> Task<T> {
    /// Starts `work`; `wake` is called when it is done.
    pub fn start(
        name: &str,
        work: impl FnOnce() -> T + Send + 'static,
        wake: impl Fn() + Send + 'static,
    ) -> Self {
        if cfg!(target_arch = "wasm32") {
            return Self {
                rx: None,
                later: Some(Box::new(work)),
                failed: None,
            };
        }
        let (tx, rx) = std::sync::mpsc::channel();
        let spawned = std::thread::Builder::new()
            .name(format!("dmpscope {name}"))
            .spawn(move || {
                let _ = tx.send(work());
                wake();
            });
        match spawned {
            Ok(_) => Self {
                rx: Some(rx),
                later: None,
                failed: None,
            },
            Err(e) => Self {
                rx: None,
                later: None,
                failed: Some(format!("cannot start {name}: {e}")),
            },
        }
    }

    /// The answer once the work is done, or the reason there is none.
    pub fn poll(&mut self) -> Option<Result<T, String>> {
        if let Some(work) = self.later.take() {
            return Some(Ok(work()));
        }
        if let Some(e) = self.failed.take() {
            return Some(Err(e));
        }
        let rx = self.rx.as_ref()?;
        match rx.try_recv() {
            Ok(v) => {
                self.rx = None;
                Some(Ok(v))
            }
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => {
                self.rx = None;
                Some(Err("the work stopped unexpectedly".into()))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_task_answers_once() {
        let mut t = Task::start("test", || 6 * 7, || {});
        let mut answer = None;
        for _ in 0..1000 {
            if let Some(a) = t.poll() {
                answer = Some(a);
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        assert_eq!(answer, Some(Ok(42)));
        assert_eq!(t.poll(), None);
    }
}
