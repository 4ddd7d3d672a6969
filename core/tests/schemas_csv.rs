//! The plain CSV loader (`t,x,y,z`): with and without a header row, blank
//! lines, rounding of stamps, and errors that name the 0-based data row.

use dmpscope_core::error::Location;
use dmpscope_core::load::csv::load_csv;
use dmpscope_core::{Error, TimeSource};

#[test]
fn csv_with_and_without_header() {
    let plain = "0,0.1,0.2,0.3\n0.01,0.4,0.5,0.6\n\n0.025,0.7,0.8,0.9\n";
    let headed = "t,x,y,z\r\n\r\n0, 0.1, 0.2, 0.3\r\n0.01,0.4,0.5,0.6\r\n0.025,0.7,0.8,0.9";
    let a = load_csv("data/reach.csv", plain).expect("plain");
    let b = load_csv("data/reach.csv", headed).expect("with header");
    assert_eq!(a, b);
    let bom = format!("\u{feff}{plain}");
    assert_eq!(load_csv("data/reach.csv", &bom).expect("with BOM"), a);
    assert_eq!(a.name, "reach.csv");
    assert_eq!(a.file, "data/reach.csv");
    assert_eq!(a.topic, "csv");
    assert_eq!(a.time_source, TimeSource::HeaderStamp);
    assert_eq!(a.stamps_ns, [0, 10_000_000, 25_000_000]);
    assert_eq!(
        xyz(&a.positions),
        [[0.1, 0.2, 0.3], [0.4, 0.5, 0.6], [0.7, 0.8, 0.9]]
    );
    // Stamps are rounded, not truncated, and may be absolute.
    let c = load_csv("c.csv", "1700000000.123456,0,0,0\n0.0000000029,1,1,1\n").expect("load");
    assert_eq!(c.stamps_ns[1], 3);
    assert!(
        (c.stamps_ns[0] - 1_700_000_000_123_456_000).abs() < 512,
        "{}",
        c.stamps_ns[0]
    );
}

#[test]
fn csv_errors_name_the_row() {
    let cases: [(&str, usize, &str); 5] = [
        ("0,1,2,3\n0.01,1,2\n", 1, "line 2"),
        ("t,x,y,z\n\n0,1,2,3\n0.01,1,abc,3\n", 1, "line 4"),
        ("0,1,abc,3\n", 0, "line 1"),
        ("0,1,2,3\n1,2,3,4\n2,3,4,5,6\n", 2, "5 fields"),
        ("0,1,2,3\n1e300,0,0,0\n", 1, "does not fit"),
    ];
    for (text, row, part) in cases {
        let err = load_csv("bad.csv", text).expect_err(text);
        let Error::Decode { at, reason } = &err else {
            panic!("{text:?}: expected a decode error, got {err:?}");
        };
        assert_eq!(
            at,
            &Location::file("bad.csv").topic("csv").sample(row),
            "{text:?}: {reason}"
        );
        assert!(err.to_string().contains(part), "{err}");
    }
    for (text, row, field) in [
        ("0,1,2,3\n0.01,NaN,2,3\n", 1, "position.x"),
        ("0,1,2,3\n0.01,1,2,-inf\n", 1, "position.z"),
        ("inf,1,2,3\n", 0, "t"),
    ] {
        let err = load_csv("nan.csv", text).expect_err(text);
        let Error::NonFinite { at, field: f } = &err else {
            panic!("{text:?}: expected a non-finite error, got {err:?}");
        };
        assert_eq!(
            (at, *f),
            (&Location::file("nan.csv").topic("csv").sample(row), field)
        );
    }
    for text in ["", "t,x,y,z\n", "\n\n"] {
        let err = load_csv("empty.csv", text).expect_err(text);
        assert!(matches!(err, Error::Decode { .. }), "{err:?}");
    }
}

/// Positions as plain arrays, to compare with literals.
fn xyz(v: &[dmpscope_core::geom::Vec3]) -> Vec<[f64; 3]> {
    v.iter().map(|p| (*p).into()).collect()
}
