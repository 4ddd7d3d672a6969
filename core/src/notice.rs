//! What the user is told that is not a result: a topic skipped, a demo left
//! out, a truncated file's lost tail. Both front ends show the same notices:
//! the CLI on stderr (`note:`, `warning:`, `error:`), the app in its message
//! list.
//!
//! May use: nothing.

use std::fmt;

use serde::{Deserialize, Serialize};

/// How much a notice matters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Level {
    /// A detail behind an info notice (each of 190 skipped topics): the CLI
    /// prints it with `-v`, the app lists it in the Recording panel.
    Detail,
    /// Worth knowing; nothing was lost (a topic dmpscope does not read).
    Info,
    /// Something was left out or changed (a demo skipped, a file cut short).
    Warning,
    /// Something failed (a file that could not be read).
    Error,
}

impl Level {
    /// The prefix the CLI prints before a notice of this level.
    pub fn prefix(self) -> &'static str {
        match self {
            Self::Detail | Self::Info => "note",
            Self::Warning => "warning",
            Self::Error => "error",
        }
    }
}

/// One thing to tell the user.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Notice {
    /// How much it matters.
    pub level: Level,
    /// The words, naming the file, topic and sample where they apply.
    pub text: String,
}

impl Notice {
    /// A detail, shown when asked for.
    pub fn detail(text: impl Into<String>) -> Self {
        Self {
            level: Level::Detail,
            text: text.into(),
        }
    }

    /// An informational notice.
    pub fn info(text: impl Into<String>) -> Self {
        Self {
            level: Level::Info,
            text: text.into(),
        }
    }

    /// A warning.
    pub fn warning(text: impl Into<String>) -> Self {
        Self {
            level: Level::Warning,
            text: text.into(),
        }
    }

    /// An error.
    pub fn error(text: impl Into<String>) -> Self {
        Self {
            level: Level::Error,
            text: text.into(),
        }
    }
}

impl fmt::Display for Notice {
    /// `note: ...`, `warning: ...` or `error: ...`, as the CLI prints it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.level.prefix(), self.text)
    }
}
