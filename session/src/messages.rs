//! What the app tells the user: each message with its level, shown once
//! (a message already in the list is not added again) until cleared.

use dmpscope_core::{Level, Notice};

/// The messages to show, oldest first.
#[derive(Clone, Debug, Default)]
pub struct Messages {
    list: Vec<Notice>,
}

impl Messages {
    /// Adds a message unless the same one is already listed (details are
    /// not messages: the Recording panel lists them).
    pub fn push(&mut self, notice: Notice) {
        if notice.level != Level::Detail && !self.list.contains(&notice) {
            self.list.push(notice);
        }
    }

    /// Adds a message of `level`.
    pub fn say(&mut self, level: Level, text: impl Into<String>) {
        self.push(Notice {
            level,
            text: text.into(),
        });
    }

    /// Adds several.
    pub fn extend(&mut self, notices: impl IntoIterator<Item = Notice>) {
        for n in notices {
            self.push(n);
        }
    }

    /// The messages.
    pub fn list(&self) -> &[Notice] {
        &self.list
    }

    /// Forgets every message.
    pub fn clear(&mut self) {
        self.list.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_message_is_listed_once() {
        let mut m = Messages::default();
        m.say(Level::Warning, "a");
        m.say(Level::Warning, "a");
        m.say(Level::Error, "a");
        assert_eq!(m.list().len(), 2);
        m.clear();
        m.say(Level::Warning, "a");
        assert_eq!(m.list().len(), 1);
    }
}
