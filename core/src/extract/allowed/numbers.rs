//! Numbers as the verdict writes them: about four significant digits,
//! shares as percentages, depths with four decimals.

/// A number with about four significant digits.
pub fn num(v: f64) -> String {
    let digits =
        (3 - crate::portable::log10(v.abs().max(1e-300)).floor() as i32).clamp(0, 6) as usize;
    format!("{v:.digits$}")
}

/// A share as a percentage with the digits it needs (`0.02 %`, `12.5 %`).
pub fn percent(share: f64) -> String {
    let p = 100.0 * share;
    let text = if p == 0.0 || p >= 1.0 {
        format!("{p:.1}")
    } else {
        format!("{p:.2}")
    };
    // `2.0 %` reads as `2 %`.
    format!("{} %", text.strip_suffix(".0").unwrap_or(&text))
}

pub(crate) fn depth_text(d: Option<f64>) -> String {
    d.map_or_else(|| "undefined".to_owned(), |v| format!("{v:.4}"))
}
