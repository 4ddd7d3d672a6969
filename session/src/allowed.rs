//! The stage of what the demos determine (method.md section 11): the
//! acceptable region, E's verdict and the picked gains, computed as a job
//! from the complete landscape and the extraction whenever either, the
//! pick rule, the region's eps or the a_peak limit changes.

use dmpscope_core::Level;
use dmpscope_core::extract::allowed::{Allowed, PickSettings};

use crate::jobs::Once;
use crate::session::Session;
use crate::settings::Settings;
use crate::stage::Polled;
use crate::state::{AllowedKey, AllowedView};

impl Session {
    /// Brings the verdict up to date (after the extraction's stage).
    pub(crate) fn update_allowed(&mut self, settings: &Settings) {
        if self.extraction.waiting() {
            self.poll_allowed();
            return;
        }
        let (Some(extraction), Some(Ok(x)), Some((model, _)), Some(shown)) = (
            self.extraction.key().copied(),
            self.extraction.value(),
            self.model_and_version(),
            &self.shown,
        ) else {
            self.allowed.clear();
            return;
        };
        if !self.landscape_complete() {
            self.allowed.clear();
            return;
        }
        let limit = settings.a_peak_limit.filter(|l| l.is_finite() && *l > 0.0);
        let settle = settings.settle_within.filter(|s| s.is_finite() && *s > 0.0);
        let eps = if settings.accept_eps.is_finite() && settings.accept_eps > 0.0 {
            settings.accept_eps
        } else {
            dmpscope_core::extract::allowed::DEFAULT_EPS
        };
        let key = AllowedKey {
            extraction,
            rule: settings.pick,
            eps: eps.to_bits(),
            limit: limit.map(f64::to_bits),
            settle: settle.map(f64::to_bits),
        };
        let pick = PickSettings {
            rule: settings.pick,
            eps,
            a_peak_limit: limit,
            settle_within: settle,
        };
        let runner = &self.runner;
        self.allowed.ensure_serial(key, || {
            // Cloned only when the key changed, not every frame.
            let x = x.clone();
            let landscape = shown.snapshot.landscape.clone();
            let work = Once::new(move || {
                let allowed = Allowed::new(&model, &landscape, &x, pick);
                let pick_eval = allowed.pick.as_ref().map(|p| model.evaluate(p.dm, p.km));
                AllowedView { allowed, pick_eval }
            });
            Ok(runner.start("the acceptable region and the pick", work))
        });
        self.poll_allowed();
    }

    fn poll_allowed(&mut self) {
        if let Polled::Failed(e) = self.allowed.poll() {
            self.messages
                .say(Level::Error, format!("the acceptable region: {e}"));
        }
    }

    /// What the demos determine and the picked gains (`None` until the
    /// landscape and the extraction are complete).
    pub fn allowed(&self) -> Option<&AllowedView> {
        self.allowed.value()
    }
}
