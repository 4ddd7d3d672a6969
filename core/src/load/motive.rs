//! OptiTrack Motive's CSV export: a first line of metadata pairs
//! (`Format Version,1.22,...,Rotation Type,Quaternion,Length
//! Units,Meters,...`), header rows giving each column's asset type
//! (`Rigid Body`, `Marker`, ...), asset name and group (`Rotation`,
//! `Position`), the row `Frame,Time (Seconds),X,Y,Z,...`, then a row per
//! frame, a cell left empty where the asset was not tracked.
//!
//! Each rigid body with a position is one stream, its name the topic; its
//! quaternion (`X,Y,Z,W`) is read where the export's rotation type is
//! `Quaternion`. Lengths are turned to metres from the unit the export
//! declares. Frames without the body are left out (a dropout, which the
//! gap policy then sees) and said; markers and other assets are skipped
//! and said.

use std::collections::BTreeMap;

use crate::error::{Error, Location, Result};
use crate::geom::{Quat, Vec3, quat_from_xyzw};
use crate::load::demo::{RawDemo, TimeSource};
use crate::notice::Notice;

/// The header rows looked through for the `Frame` row at most (Motive
/// writes four or five).
const MAX_HEADER_ROWS: usize = 16;

/// Skipped assets named in the notice at most.
const LISTED: usize = 10;

/// Asset types of Motive's exports (the row naming them is the types row).
const ASSET_TYPES: [&str; 5] = [
    "Rigid Body",
    "Marker",
    "Rigid Body Marker",
    "Bone",
    "Bone Marker",
];

/// Whether `text` is a Motive export: its first field is `Format Version`.
pub fn is_motive(text: &str) -> bool {
    text.strip_prefix('\u{feff}')
        .unwrap_or(text)
        .starts_with("Format Version,")
}

/// A rigid body's columns: position `X,Y,Z` and, if exported as a
/// quaternion, rotation `X,Y,Z,W`.
#[derive(Default)]
struct Body {
    position: [Option<usize>; 3],
    rotation: [Option<usize>; 4],
}

/// Loads a Motive export as one stream per rigid body, with what was read,
/// converted and skipped said. A cell that is neither empty nor a number
/// is an [`Error::Decode`] naming the file, the body and the frame's data
/// row (0-based) as the sample.
pub fn load_motive(label: &str, text: &str) -> Result<(Vec<RawDemo>, Vec<Notice>)> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = text.lines().enumerate();
    let meta = metadata(lines.next().map_or("", |(_, l)| l));
    let not_motive = |reason: String| Error::Decode {
        at: Location::file(label),
        reason,
    };
    let scale = length_scale(meta.get("Length Units").map(String::as_str))
        .map_err(|unit| not_motive(format!("length unit {unit:?} is not one Motive exports")))?;
    let (header, axes) = header_rows(&mut lines).map_err(not_motive)?;
    let (bodies, skipped) = columns(&header, &axes);
    if bodies.is_empty() {
        return Err(not_motive(
            "no rigid body with a position (export rigid bodies from Motive)".to_owned(),
        ));
    }
    let mut notices = Vec::new();
    let file = file_name(label);
    notices.push(Notice::info(format!(
        "{label}: a Motive export (format {}): rigid bodies {} ({})",
        meta.get("Format Version").map_or("?", String::as_str),
        bodies.keys().cloned().collect::<Vec<_>>().join(", "),
        match scale {
            1.0 => "lengths in metres".to_owned(),
            _ => format!(
                "lengths in {} as it declares, read as metres",
                meta.get("Length Units").map_or("?", String::as_str)
            ),
        }
    )));
    if !skipped.is_empty() {
        let listed = skipped
            .iter()
            .take(LISTED)
            .cloned()
            .collect::<Vec<_>>()
            .join(", ");
        let more = if skipped.len() > LISTED { ", …" } else { "" };
        notices.push(Notice::info(format!(
            "{label}: skipped {} asset(s) that are not rigid bodies: {listed}{more}",
            skipped.len()
        )));
    }
    let rows = lines.filter(|(_, l)| !l.trim().is_empty());
    let (reads, frames) = read_bodies(label, &bodies, rows, scale)?;
    let mut demos = Vec::new();
    for ((name, _), read) in bodies.iter().zip(reads) {
        if read.missing > 0 {
            notices.push(Notice::info(format!(
                "{label}: {name}: {} of {frames} frames without it (not tracked): left out",
                read.missing
            )));
        }
        if read.positions.is_empty() {
            notices.push(Notice::warning(format!(
                "{label}: {name}: never tracked: skipped"
            )));
            continue;
        }
        demos.push(RawDemo {
            name: format!("{file}:{name}"),
            file: label.to_owned(),
            topic: name.clone(),
            stamps_ns: read.stamps_ns,
            positions: read.positions,
            orientations: read.orientations,
            time_source: TimeSource::HeaderStamp,
        });
    }
    Ok((demos, notices))
}

/// The header rows up to the `Frame` row, and that row; or what is
/// missing.
fn header_rows<'a>(
    lines: &mut impl Iterator<Item = (usize, &'a str)>,
) -> std::result::Result<(Vec<Vec<String>>, Vec<String>), String> {
    let mut header: Vec<Vec<String>> = Vec::new();
    for (_, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let row = cells(line);
        if row.first().is_some_and(|c| c == "Frame") {
            return Ok((header, row));
        }
        if header.len() == MAX_HEADER_ROWS {
            return Err(format!(
                "no `Frame` row in its first {MAX_HEADER_ROWS} header rows"
            ));
        }
        header.push(row);
    }
    Err("no `Frame,Time (Seconds),...` row".to_owned())
}

/// A body's samples.
struct Read {
    stamps_ns: Vec<i64>,
    positions: Vec<Vec3>,
    orientations: Option<Vec<Quat>>,
    /// Frames without the body.
    missing: usize,
}

/// The samples of each of `bodies` in the data `rows` (line index,
/// text), each line split once, and the number of frames.
fn read_bodies<'a>(
    label: &str,
    bodies: &BTreeMap<String, Body>,
    rows: impl Iterator<Item = (usize, &'a str)>,
    scale: f64,
) -> Result<(Vec<Read>, usize)> {
    let mut reads: Vec<Read> = bodies
        .values()
        .map(|b| Read {
            stamps_ns: Vec::new(),
            positions: Vec::new(),
            orientations: b.rotation.iter().all(Option::is_some).then(Vec::new),
            missing: 0,
        })
        .collect();
    let mut cells: Vec<&str> = Vec::new();
    let mut frames = 0;
    for (row, (line, text)) in rows.enumerate() {
        frames += 1;
        cells.clear();
        cells.extend(text.split(',').map(|c| c.trim().trim_matches('"')));
        for ((name, body), read) in bodies.iter().zip(&mut reads) {
            let cell = Cell {
                cells: &cells,
                at: Location::file(label).topic(name).sample(row),
                line: line + 1,
            };
            match cell.sample(body)? {
                Some((t_ns, p, q)) => {
                    read.stamps_ns.push(t_ns);
                    read.positions.push(p * scale);
                    if let Some(orientations) = &mut read.orientations {
                        match q {
                            Some(q) => orientations.push(q),
                            // A zero quaternion leaves the body without
                            // orientation.
                            None => read.orientations = None,
                        }
                    }
                }
                None => read.missing += 1,
            }
        }
    }
    Ok((reads, frames))
}

/// A data row's cells, where they are.
struct Cell<'a> {
    cells: &'a [&'a str],
    at: Location,
    line: usize,
}

impl Cell<'_> {
    /// The number in `column` (`None`: empty), or why it is not one.
    fn number(&self, column: Option<usize>, field: &'static str) -> Result<Option<f64>> {
        let Some(cell) = column
            .and_then(|c| self.cells.get(c))
            .filter(|c| !c.is_empty())
        else {
            return Ok(None);
        };
        let v: f64 = cell.parse().map_err(|_| Error::Decode {
            at: self.at.clone(),
            reason: format!("line {}: {field} is {cell:?}, not a number", self.line),
        })?;
        if !v.is_finite() {
            return Err(Error::NonFinite {
                at: self.at.clone(),
                field,
            });
        }
        Ok(Some(v))
    }

    /// `body`'s stamp, position and quaternion in this row (`None`: it was
    /// not tracked).
    fn sample(&self, body: &Body) -> Result<Option<(i64, Vec3, Option<Quat>)>> {
        let [Some(x), Some(y), Some(z)] = [
            self.number(body.position[0], "position.x")?,
            self.number(body.position[1], "position.y")?,
            self.number(body.position[2], "position.z")?,
        ] else {
            return Ok(None);
        };
        let Some(t) = self.number(Some(1), "t")? else {
            return Ok(None);
        };
        let t_ns = (t * 1e9).round();
        if t_ns.abs() >= 9.2e18 {
            return Err(Error::Decode {
                at: self.at.clone(),
                reason: format!("line {}: t = {t} s does not fit in nanoseconds", self.line),
            });
        }
        let mut q = [0.0; 4];
        for (k, field) in [
            "orientation.x",
            "orientation.y",
            "orientation.z",
            "orientation.w",
        ]
        .into_iter()
        .enumerate()
        {
            q[k] = self.number(body.rotation[k], field)?.unwrap_or(0.0);
        }
        Ok(Some((t_ns as i64, Vec3::new(x, y, z), quat_from_xyzw(q))))
    }
}

/// The rigid bodies' columns by name, and the other assets' names.
fn columns(header: &[Vec<String>], axes: &[String]) -> (BTreeMap<String, Body>, Vec<String>) {
    let empty = Vec::new();
    let types_at = header
        .iter()
        .position(|r| r.iter().any(|c| ASSET_TYPES.contains(&c.as_str())));
    let types = types_at.map_or(&empty, |i| &header[i]);
    let names = types_at.and_then(|i| header.get(i + 1)).unwrap_or(&empty);
    let groups = header
        .iter()
        .find(|r| r.iter().any(|c| c == "Position"))
        .unwrap_or(&empty);
    let mut bodies: BTreeMap<String, Body> = BTreeMap::new();
    let mut skipped: Vec<String> = Vec::new();
    let mut seen: std::collections::BTreeSet<&str> = std::collections::BTreeSet::new();
    for (c, axis) in axes.iter().enumerate().skip(2) {
        let (kind, name) = (at(types, c), at(names, c));
        if name.is_empty() {
            continue;
        }
        if kind != "Rigid Body" {
            if seen.insert(name) {
                skipped.push(name.to_owned());
            }
            continue;
        }
        let body = bodies.entry(name.to_owned()).or_default();
        let index = ["X", "Y", "Z", "W"].iter().position(|a| a == axis);
        match (at(groups, c), index) {
            ("Position", Some(i @ 0..=2)) => body.position[i] = Some(c),
            ("Rotation", Some(i)) => body.rotation[i] = Some(c),
            _ => {}
        }
    }
    bodies.retain(|_, b| b.position.iter().all(Option::is_some));
    (bodies, skipped)
}

/// The cell of `row` at column `c` (empty past its end).
fn at(row: &[String], c: usize) -> &str {
    row.get(c).map_or("", String::as_str)
}

/// The first line's `key,value` pairs.
fn metadata(line: &str) -> BTreeMap<String, String> {
    let cells = cells(line);
    cells
        .chunks(2)
        .filter_map(|kv| match kv {
            [k, v] => Some((k.clone(), v.clone())),
            _ => None,
        })
        .collect()
}

/// Metres per the export's length unit (metres when it says none), or the
/// unit it names that Motive does not export.
fn length_scale(unit: Option<&str>) -> std::result::Result<f64, String> {
    match unit.map(str::to_ascii_lowercase).as_deref() {
        None | Some("meters" | "metres") => Ok(1.0),
        Some("centimeters" | "centimetres") => Ok(0.01),
        Some("millimeters" | "millimetres") => Ok(0.001),
        Some(_) => Err(unit.unwrap_or_default().to_owned()),
    }
}

/// A line's cells, trimmed and unquoted (Motive quotes IDs; names hold no
/// commas).
fn cells(line: &str) -> Vec<String> {
    line.split(',')
        .map(|c| c.trim().trim_matches('"').to_owned())
        .collect()
}

/// The file name of a label (a path or a name).
fn file_name(label: &str) -> String {
    std::path::Path::new(label)
        .file_name()
        .map_or_else(|| label.to_owned(), |n| n.to_string_lossy().into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Motive 1.22 export in millimetres: two rigid bodies (`left`
    /// with a frame it lost), and a marker.
    const EXPORT: &str = "\
Format Version,1.22,Take Name,t,Capture Frame Rate,120.000000,Rotation Type,Quaternion,Length Units,Millimeters,Coordinate Space,Global

,,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Rigid Body,Marker,Marker,Marker
,,left,left,left,left,left,left,left,right,right,right,right,right,right,right,m1,m1,m1
,,\"A\",\"A\",\"A\",\"A\",\"A\",\"A\",\"A\",\"B\",\"B\",\"B\",\"B\",\"B\",\"B\",\"B\",\"C\",\"C\",\"C\"
,,Rotation,Rotation,Rotation,Rotation,Position,Position,Position,Rotation,Rotation,Rotation,Rotation,Position,Position,Position,Position,Position,Position
Frame,Time (Seconds),X,Y,Z,W,X,Y,Z,X,Y,Z,W,X,Y,Z,X,Y,Z
0,0.000000,0,0,0,1,100,200,300,0,0,0,1,1,2,3,5,5,5
1,0.008333,,,,,,,,0,0,0,1,2,3,4,5,5,5
2,0.016667,0,0,0.7071068,0.7071068,110,210,310,0,0,0,1,3,4,5,,,
";

    #[test]
    fn reads_each_rigid_body_in_metres_and_says_what_it_left_out() {
        assert!(is_motive(EXPORT));
        let (demos, notices) = load_motive("take.csv", EXPORT).expect("loads");
        let names: Vec<&str> = demos.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(names, ["take.csv:left", "take.csv:right"]);
        let left = &demos[0];
        assert_eq!(left.topic, "left");
        assert_eq!(left.stamps_ns, [0, 16_667_000]);
        assert!((left.positions[1].x - 0.110).abs() < 1e-12);
        assert!((left.positions[0].z - 0.300).abs() < 1e-12);
        let q = left.orientations.as_ref().expect("quaternions")[1];
        assert!(
            (q.k - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-6,
            "{q:?}"
        );
        assert_eq!(demos[1].positions.len(), 3);
        let said: Vec<&str> = notices.iter().map(|n| n.text.as_str()).collect();
        let has = |s: &str| said.iter().any(|t| t.contains(s));
        assert!(
            has("lengths in Millimeters as it declares, read as metres"),
            "{said:?}"
        );
        assert!(
            has("left: 1 of 3 frames without it (not tracked): left out"),
            "{said:?}"
        );
        assert!(
            has("skipped 1 asset(s) that are not rigid bodies: m1"),
            "{said:?}"
        );
    }

    #[test]
    fn a_bad_cell_names_the_file_body_and_frame() {
        let bad = EXPORT.replace("3,4,5,,,", "3,x,5,,,");
        let err = load_motive("take.csv", &bad)
            .expect_err("refused")
            .to_string();
        assert!(err.contains("take.csv") && err.contains("right"), "{err}");
        assert!(
            err.contains("sample 2") && err.contains("\"x\", not a number"),
            "{err}"
        );
    }

    #[test]
    fn a_file_without_rigid_bodies_or_frame_row_is_refused() {
        let markers = EXPORT.replace("Rigid Body", "Marker");
        let err = load_motive("m.csv", &markers)
            .expect_err("refused")
            .to_string();
        assert!(err.contains("no rigid body"), "{err}");
        let cut: String = EXPORT.lines().take(4).collect::<Vec<_>>().join("\n");
        let err = load_motive("m.csv", &cut).expect_err("refused").to_string();
        assert!(err.contains("no `Frame,Time (Seconds),...` row"), "{err}");
        let inches = EXPORT.replace("Millimeters", "Inches");
        assert!(load_motive("m.csv", &inches).is_err());
        assert!(!is_motive("t,x,y,z\n0,0,0,0\n"));
    }
}
