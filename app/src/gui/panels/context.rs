//! [`PanelCtx`]: what every panel is given, and where it puts what it asks
//! for.

use super::super::commands::Command;
use super::super::view_state::ViewState;
use crate::session::{Session, Settings};

/// What every panel is given: the session (read only), the settings and the
/// views' state to change, and the commands it asks for.
pub struct PanelCtx<'a> {
    /// The session, read only: panels change it through commands.
    pub session: &'a Session,
    /// The user's settings, changed in place.
    pub settings: &'a mut Settings,
    /// The views' state, changed in place.
    pub view: &'a mut ViewState,
    /// The commands asked for so far this frame, applied after the layout.
    pub out: Vec<Command>,
}

impl PanelCtx<'_> {
    /// Asks for `c` (a GUI command or a session command), applied after the
    /// frame's layout.
    pub fn push(&mut self, c: impl Into<Command>) {
        self.out.push(c.into());
    }
}
