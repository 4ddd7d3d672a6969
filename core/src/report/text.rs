//! Text for terminals: columns aligned by display width (a CJK character
//! takes two columns, a combining accent none), not by bytes or chars, so
//! tables stay aligned with the names users give their topics.

use unicode_width::UnicodeWidthStr;

/// The columns `s` takes on a terminal.
pub fn width(s: &str) -> usize {
    UnicodeWidthStr::width(s)
}

/// `s` followed by spaces up to `columns` (left-aligned).
pub fn pad_right(s: &str, columns: usize) -> String {
    format!("{s}{}", " ".repeat(columns.saturating_sub(width(s))))
}

/// Spaces up to `columns`, then `s` (right-aligned).
pub fn pad_left(s: &str, columns: usize) -> String {
    format!("{}{s}", " ".repeat(columns.saturating_sub(width(s))))
}

/// The widest of `names` and `least`.
pub fn widest<'a>(names: impl IntoIterator<Item = &'a str>, least: usize) -> usize {
    names.into_iter().map(width).max().unwrap_or(0).max(least)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wide_and_accented_names_pad_to_the_same_column() {
        assert_eq!(width("/左手"), 5);
        assert_eq!(width("/händ"), 5);
        assert_eq!(pad_right("/左手", 7), "/左手  ");
        assert_eq!(pad_right("/händ", 7), "/händ  ");
        assert_eq!(pad_left("ab", 4), "  ab");
        assert_eq!(widest(["a", "/左手"], 4), 5);
    }
}
