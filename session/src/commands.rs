//! What the user (or a test) asks the session to do, beyond changing
//! [`super::Settings`]: the session's only other inputs.

use dmpscope_core::Notice;

use super::rl_request::RlRequest;
use super::sources::Source;

/// A request to the session, applied by [`super::Session::apply`].
#[derive(Clone, Debug)]
pub enum Command {
    /// Open recordings (a drop, a dialog, the command line).
    AddSources(Vec<Source>),
    /// Open a bundled sample: it replaces what is open when that is only
    /// bundled samples, and is added to the user's recordings otherwise
    /// (nothing the user opened is closed).
    OpenSample(Source),
    /// Include or exclude demo `demo` (an index into `Session::demos`).
    SetIncluded {
        /// The demo.
        demo: usize,
        /// Whether it takes part in the model.
        included: bool,
    },
    /// Include or leave out a stream of a recording over the stream filter
    /// (the Recording panel's tick); `None` goes back to the filter's
    /// verdict.
    SetStreamIncluded {
        /// The recording (an index into `Session::recordings`).
        source: usize,
        /// The stream's topic (`/tf:hand`).
        topic: String,
        /// Include, leave out, or as the filter says.
        included: Option<bool>,
    },
    /// Stop reading a recording (an index into `Session::recordings`): it
    /// stays in the list, unread.
    CancelLoading(usize),
    /// Stop the landscape where it is.
    CancelLandscape,
    /// Compute the landscape again from the start.
    RestartLandscape,
    /// Train an RL agent.
    StartRl(RlRequest),
    /// Stop the RL training (the last policy stays).
    CancelRl,
    /// Run the selected demo or the skill at a new start, goal and
    /// duration (`None`: stop).
    SetGeneralise(Option<super::GeneraliseSpec>),
    /// Forget every message.
    ClearMessages,
    /// Tell the user something (a dialog's answer, an export written).
    Say(Notice),
}
