//! Plain CSV demonstrations: one `t,x,y,z` row per sample, `t` in seconds,
//! positions in metres, comma separated, optionally followed by the
//! orientation `qx,qy,qz,qw` (every row the same width). A first row whose fields are all
//! non-numeric is a header and is skipped; blank lines and a UTF-8 byte
//! order mark are skipped. Quoting is not supported.

use crate::error::{Error, Location, Result};
use crate::geom::{Vec3, quat_from_xyzw};
use crate::load::demo::{RawDemo, TimeSource};

/// The topic CSV demos carry (there is one demo per file).
pub const CSV_TOPIC: &str = "csv";

/// The field names of the columns, as errors name them.
const FIELDS: [&str; 8] = [
    "t",
    "position.x",
    "position.y",
    "position.z",
    "orientation.x",
    "orientation.y",
    "orientation.z",
    "orientation.w",
];

/// Loads a CSV file's text as one demo named by the label's file name
/// (`file` is the label itself, `topic` is `csv`). Stamps are
/// `round(t * 1e9)` ns. A bad data row is an [`Error::Decode`] naming its
/// 0-based data row (header and blank lines not counted) as the sample; a
/// NaN or infinite value is an [`Error::NonFinite`].
pub fn load_csv(label: &str, text: &str) -> Result<RawDemo> {
    let at = || Location::file(label).topic(CSV_TOPIC);
    let mut stamps_ns = Vec::new();
    let mut positions = Vec::new();
    let mut orientations = Vec::new();
    let mut first_zero: Option<usize> = None;
    let mut width = None;
    let mut first = true;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    for (line_index, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let is_first = std::mem::replace(&mut first, false);
        if is_first && line.split(',').all(|f| f.trim().parse::<f64>().is_err()) {
            continue;
        }
        let row = stamps_ns.len();
        let w = *width.get_or_insert_with(|| row_width(line));
        let (values, t_ns) = data_row(line, w).map_err(|e| match e {
            RowError::Decode(reason) => Error::Decode {
                at: at().sample(row),
                reason: format!("line {}: {reason}", line_index + 1),
            },
            RowError::NonFinite(field) => Error::NonFinite {
                at: at().sample(row),
                field,
            },
        })?;
        stamps_ns.push(t_ns);
        positions.push(Vec3::new(values[1], values[2], values[3]));
        if let (Some(8), [.., qx, qy, qz, qw]) = (width, &values[..]) {
            let q = quat_from_xyzw([*qx, *qy, *qz, *qw]);
            if q.is_none() && first_zero.is_none() {
                first_zero = Some(row);
            }
            orientations.push(q);
        }
    }
    // A zero quaternion (method.md section 12) is an error, unless every
    // row's is zero: columns that hold no rotation.
    let all_zero = orientations.iter().all(Option::is_none);
    if let Some(row) = first_zero
        && !all_zero
    {
        return Err(Error::NonFinite {
            at: at().sample(row),
            field: "orientation (a zero quaternion)",
        });
    }
    if positions.is_empty() {
        return Err(Error::Decode {
            at: at(),
            reason: "no data rows (expected t,x,y,z per line)".to_owned(),
        });
    }
    let name = std::path::Path::new(label)
        .file_name()
        .map_or_else(|| label.to_owned(), |n| n.to_string_lossy().into_owned());
    Ok(RawDemo {
        name,
        file: label.to_owned(),
        topic: CSV_TOPIC.to_owned(),
        stamps_ns,
        positions,
        // With orientation columns every row's quaternion must be usable.
        orientations: if width == Some(8) {
            orientations.into_iter().collect()
        } else {
            None
        },
        time_source: TimeSource::HeaderStamp,
    })
}

/// Why a data row is not one.
enum RowError {
    /// Not a row of numbers of the file's width, or a time out of range.
    Decode(String),
    /// A NaN or infinite value in this field.
    NonFinite(&'static str),
}

/// A data row's values and its stamp, `round(t * 1e9)` ns.
fn data_row(line: &str, width: usize) -> std::result::Result<(Vec<f64>, i64), RowError> {
    let values = parse_row(line, width).map_err(RowError::Decode)?;
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(RowError::NonFinite(FIELDS[i]));
    }
    let t_ns = (values[0] * 1e9).round();
    // i64 spans about +-292 years of nanoseconds.
    if t_ns.abs() >= 9.2e18 {
        return Err(RowError::Decode(format!(
            "t = {} s does not fit in nanoseconds",
            values[0]
        )));
    }
    Ok((values, t_ns as i64))
}

/// The width of the rows: 8 when the first data row has more than 4
/// fields (`t,x,y,z,qx,qy,qz,qw`), else 4.
fn row_width(line: &str) -> usize {
    if line.split(',').count() > 4 { 8 } else { 4 }
}

/// The `width` numbers of one row, or what is wrong with it.
fn parse_row(line: &str, width: usize) -> std::result::Result<Vec<f64>, String> {
    let expected = if width == 8 {
        "8 (t,x,y,z,qx,qy,qz,qw)"
    } else {
        "4 (t,x,y,z)"
    };
    let mut values = Vec::with_capacity(width);
    let mut fields = line.split(',');
    for name in &FIELDS[..width] {
        let field = fields
            .next()
            .ok_or_else(|| format!("{} fields, expected {expected}", values.len()))?
            .trim();
        values.push(
            field
                .parse()
                .map_err(|_| format!("{name} is {field:?}, not a number"))?,
        );
    }
    let extra = fields.count();
    if extra > 0 {
        return Err(format!("{} fields, expected {expected}", width + extra));
    }
    Ok(values)
}
