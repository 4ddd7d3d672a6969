//! What the window says where the landscape goes, when there is no
//! landscape to show (or it is still coming): a user is never left with a
//! spinner that waits for nothing.

/// Where the session is, in the words the window shows.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    /// No recording is open.
    NoSources,
    /// Recordings are being read.
    Loading,
    /// The recordings gave no demonstration (each failure is in the
    /// messages).
    NoDemos,
    /// Demos were found but none could be used, and why.
    NoUsableDemo(String),
    /// The grid is not valid, or the landscape could not start.
    NoLandscape,
    /// The landscape is being computed: points done and in all.
    Computing(usize, usize),
    /// The landscape was cancelled at this many points of all.
    Cancelled(usize, usize),
    /// The landscape's work stopped before the end (the messages say why).
    Stopped(usize, usize),
    /// The landscape is complete.
    Ready,
}

impl Status {
    /// The sentence the window shows, with what to do.
    pub fn describe(&self) -> String {
        match self {
            Self::NoSources => {
                "No recording is open: use Open… or drop .mcap / .csv files or a rosbag2 folder \
                 on the window."
                    .into()
            }
            Self::Loading => "Reading the recordings…".into(),
            Self::NoDemos => "No demonstration was found in the recordings opened (the messages \
                              say why). Open a recording with a pose topic, or change the \
                              Loading options (frame filter, what a demo is)."
                .into(),
            Self::NoUsableDemo(why) => format!(
                "No demonstration can be used: {why}. Open other recordings, include other \
                 demos, or change the Loading or preprocessing settings."
            ),
            Self::NoLandscape => {
                "The landscape cannot be computed with these grid settings (see the messages)."
                    .into()
            }
            Self::Computing(_, 0) => "Computing the landscape…".into(),
            Self::Computing(done, total) => format!("Computing the landscape… {done}/{total}"),
            Self::Cancelled(done, total) => {
                format!("The landscape was cancelled at {done}/{total} points.")
            }
            Self::Stopped(done, total) => format!(
                "The landscape stopped at {done}/{total} points (see the messages); Restart \
                 computes it again."
            ),
            Self::Ready => "The landscape is complete.".into(),
        }
    }
}
