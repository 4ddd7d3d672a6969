//! The documents `dmpscope landscape` and `dmpscope extract` write, made
//! in one place so the CLI and the Python package give the same JSON to
//! the bit: the landscape's ([`landscape_document`]) and the extraction's
//! [`Report`] with its diagnostics, constrained optimum, verdict and pick
//! ([`extract_report`]), and the extraction in words ([`Report::extract_text`]).

use std::sync::Arc;

use crate::error::{Error, Result};
use crate::extract::allowed::{Allowed, PickSettings};
use crate::extract::diagnostics::{DiagSettings, DiagnosticsJob, FLAT_DEPTH};
use crate::extract::optimum::Extraction;
use crate::landscape::grid::Landscape;
use crate::landscape::model::Model;
use crate::landscape::quantity;
use crate::notice::Notice;
use crate::report::summary::{Constrained, LoadingChoices, Report};
use crate::report::table::TableRow;

/// The landscape document: the report of `model` and `optimum` (keys `k`,
/// `demos`, `optimum`, `table`) plus the grid's axes `dm`, `km`, every
/// quantity of [`quantity::ALL`] by its key (`d_sum`, `s`, `a_peak`,
/// `e_sum`, `d_rot_sum`) and `j`, as rows over D/M (NaN as `null`).
pub fn landscape_document(
    model: &Model,
    landscape: &Landscape,
    optimum: &Extraction,
    k: f64,
) -> serde_json::Result<serde_json::Value> {
    let report = Report::new(model, Some(optimum), k);
    let mut doc = serde_json::to_value(&report)?;
    if let Some(map) = doc.as_object_mut() {
        map.insert("dm".into(), serde_json::to_value(&landscape.dm)?);
        map.insert("km".into(), serde_json::to_value(&landscape.km)?);
        for q in quantity::ALL {
            let rows = landscape.rows(landscape.values(q));
            map.insert(q.about().key.into(), serde_json::to_value(rows)?);
        }
        map.insert(
            "j".into(),
            serde_json::to_value(landscape.rows(&landscape.j(k)))?,
        );
    }
    Ok(doc)
}

/// What an extraction reports besides the optimum (the CLI's `extract`
/// flags).
#[derive(Clone, Debug, PartialEq)]
pub struct ExtractSettings {
    /// The weight of sum d in J.
    pub k: f64,
    /// How the recordings were read and prepared (`None`: not reported).
    pub loading: Option<LoadingChoices>,
    /// The diagnostics' settings (`None`: no diagnostics).
    pub diagnostics: Option<DiagSettings>,
    /// The acceptable region's eps, the pick's rule, an a_peak limit (also
    /// the constrained optimum's) and a settling limit.
    pub pick: PickSettings,
}

impl Default for ExtractSettings {
    fn default() -> Self {
        Self {
            k: crate::landscape::grid::DEFAULT_K,
            loading: None,
            diagnostics: Some(DiagSettings::default()),
            pick: PickSettings::default(),
        }
    }
}

impl ExtractSettings {
    /// Checks every number before anything is computed (the CLI's parsers
    /// check the eps and the settling limit; [`extract_report`] the a_peak
    /// limit, after the diagnostics).
    pub fn check(&self) -> Result<()> {
        crate::extract::optimum::check_k(self.k)?;
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !positive(self.pick.eps) {
            return Err(Error::InvalidSetting(format!(
                "the acceptable region's eps must be a fraction above 0 (0.02 is 2 %), got {}",
                self.pick.eps
            )));
        }
        if let Some(s) = self.pick.settle_within.filter(|&s| !positive(s)) {
            return Err(Error::InvalidSetting(format!(
                "the settling limit must be a number of unit times above 0, got {s}"
            )));
        }
        if let Some(limit) = self.pick.a_peak_limit {
            check_a_peak_limit(limit)?;
        }
        if let Some(d) = &self.diagnostics
            && d.grid_points < 2
        {
            return Err(Error::InvalidSetting(format!(
                "the diagnostics' grid needs 2 or more points per axis, got {}",
                d.grid_points
            )));
        }
        Ok(())
    }
}

/// Checks an a_peak limit (a positive number of m/s^2).
fn check_a_peak_limit(limit: f64) -> Result<()> {
    if limit.is_finite() && limit > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidSetting(format!(
            "--a-peak-limit must be a positive number of m/s^2, got {limit}"
        )))
    }
}

/// The report of an extraction as `extract --json` prints it: Table I and
/// the optimum, the loading choices, the diagnostics (run by `diagnose`,
/// which may show progress or stop them), the constrained optimum, what the
/// data allow and the pick (a row of Table I after `Extracted`). `notify`
/// gets what the user should know as it arises: a flat J, a missing skill
/// error, a failed pick. A bad a_peak limit is an
/// [`Error::InvalidSetting`] after the diagnostics.
pub fn extract_report(
    model: &Arc<Model>,
    landscape: &Landscape,
    optimum: &Extraction,
    settings: &ExtractSettings,
    diagnose: &mut dyn FnMut(&mut DiagnosticsJob) -> Result<()>,
    notify: &mut dyn FnMut(Notice),
) -> Result<Report> {
    let k = settings.k;
    let mut report = Report::new(model, Some(optimum), k);
    report.loading = settings.loading.clone();
    if let Some(diag) = settings.diagnostics {
        let mut job = DiagnosticsJob::new(Arc::clone(model), landscape, optimum, diag);
        diagnose(&mut job)?;
        if job.diagnostics().flat {
            notify(Notice::info(format!(
                "J is flat (depth below {FLAT_DEPTH}): J alone does not determine the gains; the \
                 output says what the data allow and which gains are picked in it"
            )));
        }
        report = report.with_diagnostics(job.diagnostics().clone(), job.about().clone());
    }
    if let Some(limit) = settings.pick.a_peak_limit {
        check_a_peak_limit(limit)?;
        report.constrained = Some(Constrained::compute(model, landscape, k, limit));
    }
    let allowed = Allowed::new(model, landscape, optimum, settings.pick);
    if let Some(why) = model.skill_refusal() {
        notify(Notice::warning(format!("no skill error E: {why}")));
    }
    if let Some(failure) = &allowed.pick_failure {
        notify(Notice::warning(failure.clone()));
    }
    if let Some(p) = &allowed.pick {
        let eval = model.evaluate(p.dm, p.km);
        let name = format!("Picked ({})", p.rule.name());
        report.table.insert(1, TableRow::from_eval(name, &eval, k));
    }
    report.allowed = Some(allowed);
    Ok(report)
}

impl Report {
    /// The extraction in words, as `dmpscope extract` prints it: the
    /// optimum (after what the data allow when J is flat), the constrained
    /// optimum, the gains for the robot, the diagnostics and Table I.
    pub fn extract_text(&self) -> String {
        let mut s = String::new();
        // A flat J leads with what the data allow and the pick (never a dead
        // end); a determined one with its optimum.
        let flat = self.allowed.as_ref().is_some_and(|a| a.j_flat);
        if flat && let Some(a) = &self.allowed {
            s.push_str(&a.text());
            s.push('\n');
        }
        s.push_str(&self.optimum_text());
        if let Some(c) = &self.constrained {
            s.push_str(&c.text(self.optimum.as_ref().map(|o| o.j)));
        }
        if let Some(a) = &self.allowed {
            s.push_str(&format!("for the robot: {}\n", a.optimum_robot.text()));
            if !flat {
                s.push('\n');
                s.push_str(&a.text());
            }
        }
        s.push('\n');
        let diag = self.diagnostics_text();
        if !diag.is_empty() {
            s.push_str(&diag);
            s.push('\n');
        }
        s.push_str(&self.table_text());
        s
    }
}
