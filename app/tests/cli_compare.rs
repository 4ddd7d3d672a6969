//! `dmpscope compare` (issue 45): gain sets side by side carry Table I's
//! numbers for the same gains, and the figure of their regenerations is
//! written as SVG (one path per set and demo) and PNG.

mod support;

use serde_json::Value;
use support::{dmpscope, text, tmp_path};

const SAMPLE: &str = "assets/planted8.mcap";

fn json(args: &[&str]) -> Value {
    let out = dmpscope(args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("json")
}

#[test]
fn each_set_is_the_table_i_row_of_its_gains_with_its_settling_time() {
    let report = json(&["extract", SAMPLE, "--json", "--no-diagnostics"]);
    let compared = json(&["compare", SAMPLE, "--gains", "extracted,Hrstc1", "--json"]);
    let sets = compared["sets"].as_array().expect("sets");
    let names: Vec<&str> = sets.iter().filter_map(|s| s["name"].as_str()).collect();
    assert_eq!(names, ["Extracted", "Hrstc1"]);
    let table = report["table"].as_array().expect("table");
    for set in sets {
        let row = table
            .iter()
            .find(|r| r["name"] == set["name"])
            .unwrap_or_else(|| panic!("no Table I row {}", set["name"]));
        let row = row.as_object().expect("row");
        for key in ["dm", "km", "zeta", "s", "d_sum", "j", "d_mean", "a_peak"] {
            assert!(row.contains_key(key), "Table I has no {key}");
        }
        for (key, value) in row {
            assert_eq!(&set[key], value, "{}: {key}", set["name"]);
        }
        let settling = &set["settling"];
        let unit = settling["unit"].as_f64().expect("settling.unit");
        let seconds = settling["seconds"].as_f64().expect("settling.seconds");
        assert!(unit > 0.0 && seconds > 0.0, "{settling}");
        assert!(set.get("target").is_none(), "no target was asked for");
    }
    // The best of each column names one of the sets.
    let best = compared["best"].as_object().expect("best");
    assert!(best.contains_key("j"), "{best:?}");
    for name in best.values() {
        assert!(names.contains(&name.as_str().expect("name")), "{name}");
    }
}

#[test]
fn a_new_target_gives_each_set_its_end_error_and_peak_acceleration() {
    let compared = json(&[
        "compare",
        SAMPLE,
        "--gains",
        "Hrstc1,25:156.25",
        "--demo",
        "2",
        "--goal",
        "0.5",
        "0.1",
        "0.3",
        "--duration",
        "2",
        "--json",
    ]);
    let sets = compared["sets"].as_array().expect("sets");
    assert_eq!(sets.len(), 2);
    assert_eq!(sets[1]["name"], "25:156.25");
    assert_eq!(sets[1]["dm"].as_f64(), Some(25.0));
    assert_eq!(sets[1]["km"].as_f64(), Some(156.25));
    for set in sets {
        let target = &set["target"];
        let end = target["end_error_m"].as_f64().expect("end error");
        assert!((0.0..0.05).contains(&end), "{target}");
        assert_eq!(target["duration_s"].as_f64(), Some(2.0));
        assert!(target["a_peak"].as_f64().expect("a_peak") > 0.0);
    }
}

/// The `<polyline>` elements of an SVG whose stroke is `rgb` at `width`,
/// paths of more than two points (a legend's sample line has two).
fn polylines(svg: &str, rgb: [u8; 3], width: u32) -> usize {
    let hex = format!("#{:02X}{:02X}{:02X}", rgb[0], rgb[1], rgb[2]);
    svg.split('<')
        .filter(|element| element.starts_with("polyline"))
        .filter(|element| {
            let upper = element.to_ascii_uppercase();
            upper.contains(&format!("STROKE=\"{hex}\""))
                && upper.contains(&format!("STROKE-WIDTH=\"{width}\""))
        })
        .filter(|element| {
            let points = element.split("points=\"").nth(1).unwrap_or("");
            let points = points.split('"').next().unwrap_or("");
            points.split_whitespace().count() > 2
        })
        .count()
}

#[test]
fn the_svg_figure_has_one_path_per_set_and_demo() {
    let path = tmp_path("compare.svg");
    let path_text = path.to_str().expect("utf-8 path");
    let out = dmpscope(&[
        "compare",
        SAMPLE,
        "--gains",
        "extracted,Hrstc1,Hrstc4",
        "--figure",
        path_text,
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let svg = std::fs::read_to_string(&path).expect("the figure");
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(80)]);
    let demos = json(&["info", SAMPLE, "--json"])
        .as_array()
        .expect("demos")
        .len();
    assert_eq!(demos, 8);
    for (i, colour) in dmpscope::figure::SET_COLOURS.iter().take(3).enumerate() {
        // The 3D panel: the set's regeneration of every demo (thin).
        assert_eq!(polylines(&svg, *colour, 1), demos, "set {i} in 3D");
        // The selected demo's x, y, z and its distance from the demo.
        assert_eq!(polylines(&svg, *colour, 2), 4, "set {i} against time");
    }
    assert_eq!(polylines(&svg, dmpscope::figure::SET_COLOURS[3], 1), 0);
    for name in ["Extracted", "Hrstc1", "Hrstc4"] {
        assert!(svg.contains(name), "the legend names {name}");
    }
}

#[test]
fn the_png_figure_is_a_png_of_the_figure_s_size() {
    let path = tmp_path("compare.png");
    let out = dmpscope(&[
        "compare",
        SAMPLE,
        "--gains",
        "extracted,Hrstc1",
        "--demo",
        "3",
        "--figure",
        path.to_str().expect("utf-8 path"),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let png = std::fs::read(&path).expect("the figure");
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let width = u32::from_be_bytes([png[16], png[17], png[18], png[19]]);
    let height = u32::from_be_bytes([png[20], png[21], png[22], png[23]]);
    assert_eq!((width, height), dmpscope::figure::SIZE);
}

#[test]
fn a_figure_of_another_kind_or_an_unknown_gain_is_refused_by_name() {
    let out = dmpscope(&["compare", SAMPLE, "--figure", "out.pdf"]);
    assert!(!out.status.success());
    assert!(
        text(&out.stderr).contains("out.pdf"),
        "{}",
        text(&out.stderr)
    );
    let out = dmpscope(&["compare", SAMPLE, "--gains", "extracted,Hrstc9"]);
    assert!(!out.status.success());
    assert!(
        text(&out.stderr).contains("Hrstc9"),
        "{}",
        text(&out.stderr)
    );
}
