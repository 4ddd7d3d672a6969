//! Errors of the core: every one names what the user gave (file, topic,
//! sample index) so it can be shown as is.
//!
//! May use: nothing.

use std::fmt;

/// A result with the core's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Where in the user's input something went wrong.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Location {
    /// The file as the user named it.
    pub file: String,
    /// The topic (or demo name) inside the file, when known.
    pub topic: Option<String>,
    /// The 0-based message index in file order within the topic, when known.
    pub sample: Option<usize>,
}

impl Location {
    /// A location naming only a file.
    pub fn file(file: impl Into<String>) -> Self {
        Self {
            file: file.into(),
            ..Self::default()
        }
    }

    /// This location narrowed to a topic.
    pub fn topic(mut self, topic: impl Into<String>) -> Self {
        self.topic = Some(topic.into());
        self
    }

    /// This location narrowed to a sample.
    pub fn sample(mut self, sample: usize) -> Self {
        self.sample = Some(sample);
        self
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(topic) = &self.topic {
            write!(f, ", topic {topic}")?;
        }
        if let Some(sample) = self.sample {
            write!(f, ", sample {sample}")?;
        }
        Ok(())
    }
}

/// Everything that can go wrong in the core.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The file could not be read from disk.
    #[error("{file}: {reason}")]
    Io {
        /// The file.
        file: String,
        /// The operating system's error (shown in the message, not chained
        /// again as a source, so it is printed once).
        reason: std::io::Error,
    },
    /// The file is not a readable MCAP file (bad magic, truncated, bad CRC, ...).
    #[error("{at}: not a readable MCAP file: {reason}")]
    Mcap {
        /// Where.
        at: Location,
        /// What the reader said, in words.
        reason: String,
    },
    /// The file is not a readable ROS 1 bag (bad magic, a corrupt chunk, a
    /// malformed record).
    #[error("{at}: not a readable ROS 1 bag: {reason}")]
    Bag {
        /// Where.
        at: Location,
        /// What is wrong, in words.
        reason: String,
    },
    /// A message could not be decoded with its schema.
    #[error("{at}: cannot decode message: {reason}")]
    Decode {
        /// Where.
        at: Location,
        /// What was wrong with the bytes.
        reason: String,
    },
    /// A position or stamp is NaN or infinite.
    #[error("{at}: non-finite value in {field}")]
    NonFinite {
        /// Where.
        at: Location,
        /// Which field (`position.x`, ...).
        field: &'static str,
    },
    /// A demonstration is too short for the Savitzky-Golay window.
    #[error(
        "{demo}: too few samples after resampling (n0 = {n0}, need at least {min}, the \
         Savitzky-Golay window): a shorter window (--sg-window, odd and at least the order + 2; \
         the app's Settings: SG window) or a recording at a higher rate"
    )]
    TooFewSamples {
        /// The demo's name.
        demo: String,
        /// The resampled length.
        n0: usize,
        /// The least that works.
        min: usize,
    },
    /// A demonstration's time stamps do not advance.
    #[error("{demo}: {reason}")]
    BadTiming {
        /// The demo's name.
        demo: String,
        /// What is wrong.
        reason: String,
    },
    /// A file holds no demonstration the loaders understand.
    #[error("{file}: no pose topic found{}", skipped_list(.skipped))]
    NoDemos {
        /// The file.
        file: String,
        /// Topics that were seen and skipped, with their schema names.
        skipped: Vec<(String, String)>,
    },
    /// A source cannot be read as a recording (a folder without MCAP files,
    /// bytes that are not text where text was expected).
    #[error("{path}: {reason}")]
    Source {
        /// The file or folder.
        path: String,
        /// Why not.
        reason: String,
    },
    /// No demonstration is usable: each reason names a demo and what is
    /// wrong with it (empty when there was none at all).
    #[error("no usable demonstration{}", reasons_list(.reasons))]
    NoUsableDemo {
        /// One line per demo that was left out.
        reasons: Vec<String>,
    },
    /// Every source was read but none gave a demonstration.
    #[error(
        "no demonstration found: every stream was skipped (see the notes above), or \
         segmentation found no movement between rests"
    )]
    NoDemonstration,
    /// A target a primitive cannot run at (a start, goal, duration or
    /// orientation out of range), in words naming the argument.
    #[error("{0}")]
    Target(String),
    /// A setting is out of its range.
    #[error("invalid setting: {0}")]
    InvalidSetting(String),
    /// Training stopped because something became non-finite.
    #[error("training stopped: {0}")]
    Training(String),
    /// The work was cancelled by the caller.
    #[error("cancelled")]
    Cancelled,
}

fn reasons_list(reasons: &[String]) -> String {
    if reasons.is_empty() {
        return " (no demonstration was found in the inputs)".to_owned();
    }
    format!(": {}", reasons.join("; "))
}

fn skipped_list(skipped: &[(String, String)]) -> String {
    if skipped.is_empty() {
        return String::new();
    }
    let items: Vec<String> = skipped
        .iter()
        .map(|(topic, schema)| format!("{topic} ({schema})"))
        .collect();
    format!("; skipped: {}", items.join(", "))
}
