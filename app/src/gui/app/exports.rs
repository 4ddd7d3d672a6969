//! The app's exports: what the save dialog is given for each (heat maps,
//! the report, Table I, the DMP at a new target, the pinned sets' figure
//! and comparison).

use super::super::commands::Export;
use super::super::export::heatmap_png;
use super::DmpApp;

impl DmpApp {
    /// The file name and bytes of an export (what the save dialog is
    /// given; tests read it).
    pub fn export(&self, what: Export) -> Result<(String, Vec<u8>), String> {
        let report = || {
            self.session
                .report()
                .ok_or_else(|| "nothing to export yet: no model".to_owned())
        };
        Ok(match what {
            Export::Map(map) => {
                let shown = self.session.shown().ok_or("no landscape to export yet")?;
                let bytes =
                    heatmap_png(map.values(shown), &shown.grid(), self.settings.log_colour)?;
                (map.file_name(), bytes)
            }
            Export::ReportJson => {
                let text = serde_json::to_string_pretty(&report()?).map_err(|e| e.to_string())?;
                ("dmpscope-report.json".into(), text.into_bytes())
            }
            Export::TableCsv => ("dmpscope-table.csv".into(), report()?.csv().into_bytes()),
            Export::TableMarkdown => (
                "dmpscope-table.md".into(),
                report()?.markdown().into_bytes(),
            ),
            Export::Dmp => ("dmpscope-dmp.json".into(), self.dmp_json()?.into_bytes()),
            Export::FigureSvg => {
                let svg = crate::figure::svg(&self.figure()?).map_err(|e| e.to_string())?;
                ("dmpscope-compare.svg".into(), svg.into_bytes())
            }
            #[cfg(not(target_arch = "wasm32"))]
            Export::FigurePng => (
                "dmpscope-compare.png".into(),
                crate::figure::png(&self.figure()?).map_err(|e| e.to_string())?,
            ),
            #[cfg(target_arch = "wasm32")]
            Export::FigurePng => return Err("the browser saves the figure as SVG".into()),
            Export::CompareCsv => (
                "dmpscope-compare.csv".into(),
                self.compare_table()?.csv().into_bytes(),
            ),
            Export::CompareMarkdown => (
                "dmpscope-compare.md".into(),
                self.compare_table()?.markdown().into_bytes(),
            ),
        })
    }

    /// The figure of what is on screen: the selected demo against time and
    /// the shown demos in 3D, regenerated at every shown pin (or, with
    /// none, at the operating point).
    pub fn figure(&self) -> Result<crate::figure::Figure, String> {
        use dmpscope_core::report::compare::GainSet;
        let model = self
            .session
            .model()
            .ok_or("nothing to draw yet: no model")?;
        let mut sets: Vec<(GainSet, [u8; 3])> = self
            .view
            .pins
            .list()
            .iter()
            .filter(|p| p.shown)
            .map(|p| {
                let set = GainSet {
                    name: p.name.clone(),
                    dm: p.dm,
                    km: p.km,
                };
                (set, p.colour)
            })
            .collect();
        if sets.is_empty() {
            let (dm, km) = self.settings.op;
            let set = GainSet {
                name: "Operating point".into(),
                dm,
                km,
            };
            sets.push((set, crate::figure::SET_COLOURS[0]));
        }
        let shown: Vec<usize> = (0..model.demos().len())
            .filter(|&i| self.view.view3d.visible.get(i).copied().unwrap_or(true))
            .collect();
        Ok(crate::figure::Figure::of_model(
            model,
            &sets,
            &shown,
            self.view.selected,
        ))
    }

    /// The pinned sets' comparison table.
    fn compare_table(&self) -> Result<dmpscope_core::report::compare_text::CompareTable, String> {
        let model = self
            .session
            .model()
            .ok_or("nothing to export yet: no model")?;
        if self.view.pins.is_empty() {
            return Err("no gain sets pinned (Compare gain sets, in the side panel)".into());
        }
        let names: Vec<String> = model.demos().iter().map(|d| d.name.clone()).collect();
        Ok(dmpscope_core::report::compare_text::CompareTable::new(
            self.view.pins.rows(),
            &names,
        ))
    }

    /// The run at the new target as `docs/export.md`'s document.
    fn dmp_json(&self) -> Result<String, String> {
        use dmpscope_core::export::dmp_doc::{DocContext, dmp_document};
        let model = self
            .session
            .model()
            .ok_or("nothing to export yet: no model")?;
        let g = match self.session.generalised() {
            Some(Ok(g)) => g,
            Some(Err(e)) => return Err(format!("the run at the new target failed: {e}")),
            None => return Err("turn on the run at a new target first (New target tab)".into()),
        };
        let skill = g.forcing_sd.is_some();
        let demos = if skill {
            model.demos().iter().map(|d| d.name.clone()).collect()
        } else {
            vec![g.primitive.name.clone()]
        };
        let scaling = self
            .session
            .generalise_spec()
            .map(|s| s.target.scaling)
            .unwrap_or_default();
        let doc = dmp_document(
            &g.primitive,
            &g.out,
            DocContext {
                demos,
                source: if skill { "skill" } else { "demo" },
                basis: (&model.basis().centres, &model.basis().widths),
                frame_id: self
                    .settings
                    .load
                    .fixed_frame
                    .clone()
                    .unwrap_or_else(|| "world".to_owned()),
                band: skill.then(|| g.out.band.clone()),
                recorded_units: self.settings.load.units,
                scaling,
            },
        )
        .map_err(|e| e.to_string())?;
        serde_json::to_string(&doc).map_err(|e| e.to_string())
    }
}
