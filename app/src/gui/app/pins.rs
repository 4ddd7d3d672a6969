//! Pinning gain sets from text (`--pin`, the browser tests' hook): Table
//! I's row names or `DM:KM`, resolved once they are known.

use super::DmpApp;

impl DmpApp {
    /// Pins the gain sets `text` names (Table I's rows or `DM:KM`) once
    /// they are known (the extraction's, the pick's).
    pub fn with_pins(mut self, text: Option<String>) -> Self {
        self.pending_pins = text;
        self
    }

    /// Pins what `--pin` named as soon as every name resolves; once the
    /// extraction is known a name that still does not is an error shown
    /// in the Compare section.
    pub(super) fn pin_pending(&mut self) {
        let Some(text) = self.pending_pins.as_deref() else {
            return;
        };
        let rows = self.session.table_rows();
        match dmpscope_core::report::compare::resolve(text, &rows) {
            Ok(_) => {
                let text = text.to_owned();
                self.pin_by_text(&text);
                self.pending_pins = None;
            }
            Err(e) if self.session.allowed().is_some() => {
                self.view.pin_error = Some(e.to_string());
                self.pending_pins = None;
            }
            Err(_) => {}
        }
    }

    /// Pins the gain sets `text` names (Table I rows or `DM:KM`), as the
    /// Compare section's field does (tests and the browser tests' hook).
    pub fn pin_by_text(&mut self, text: &str) {
        let rows = self.session.table_rows();
        match dmpscope_core::report::compare::resolve(text, &rows) {
            Ok(sets) => {
                for s in sets {
                    self.view.pin_error = self.view.pins.add(&s.name, s.dm, s.km).err();
                }
            }
            Err(e) => self.view.pin_error = Some(e.to_string()),
        }
    }
}
