//! [`ModelSteps`]: [`Model::new`] one demo at a time, for a caller that
//! must not hold its thread for the whole fit (the browser's page, whose
//! jobs run in slices of about 10 ms between frames). The same arithmetic
//! in the same order: a model built in steps has the bits of one built at
//! once.

use crate::error::{Error, Result};
use crate::fit::basis::Basis;
use crate::fit::lwr::Projections;
use crate::fit::settings::DmpSettings;
use crate::landscape::model::Model;
use crate::prepare::demo::PreparedDemo;

/// A model being fitted: the checks and the basis done, each demo's
/// projections one step each, then the rest.
#[derive(Debug)]
pub struct ModelSteps {
    demos: Vec<PreparedDemo>,
    settings: DmpSettings,
    basis: Basis,
    projections: Vec<Projections>,
    orientation: Vec<Option<Projections>>,
}

impl ModelSteps {
    /// Checks the demos and settings and makes the basis. All demos must
    /// share one grid length.
    pub fn new(demos: Vec<PreparedDemo>, settings: DmpSettings) -> Result<Self> {
        let Some(first) = demos.first() else {
            return Err(Error::InvalidSetting("no demonstrations to fit".into()));
        };
        let n = first.len();
        if let Some(other) = demos.iter().find(|d| d.len() != n) {
            return Err(Error::InvalidSetting(format!(
                "{} has {} grid points, {} has {n}",
                other.name,
                other.len(),
                first.name
            )));
        }
        let floor = settings.axis_sd_floor;
        if !(0.0..=1.0).contains(&floor) {
            return Err(Error::InvalidSetting(format!(
                "the axis SD floor must be a fraction in [0, 1], got {floor}"
            )));
        }
        let basis = Basis::new(&settings, n)?;
        Ok(Self {
            projections: Vec::with_capacity(demos.len()),
            orientation: Vec::with_capacity(demos.len()),
            demos,
            settings,
            basis,
        })
    }

    /// Fits the next demo's projections (its position's and, where it has
    /// one, its orientation's); `false` once every demo is fitted.
    pub fn project_next(&mut self) -> bool {
        let Some(demo) = self.demos.get(self.projections.len()) else {
            return false;
        };
        self.projections.push(Projections::new(&self.basis, demo));
        self.orientation.push(
            demo.orientation
                .as_ref()
                .map(|o| o.projections(&self.basis)),
        );
        true
    }

    /// Demos fitted and in all.
    pub fn progress(&self) -> (usize, usize) {
        (self.projections.len(), self.demos.len())
    }

    /// The model (fitting the demos not yet fitted first).
    pub fn finish(mut self) -> Result<Model> {
        while self.project_next() {}
        Model::assemble(
            self.demos,
            self.settings,
            self.basis,
            self.projections,
            self.orientation,
        )
    }
}
