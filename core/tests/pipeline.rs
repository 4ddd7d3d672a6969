//! The pipeline's policy for unusable demos, and `load_source` on what a
//! user can name: bytes, a CSV, a folder, a rosbag2 `metadata.yaml`.

use dmpscope_core::arrange::streams::load_source;
use dmpscope_core::geom::Vec3;
use dmpscope_core::load::options::{LoadOptions, UpAxis};
use dmpscope_core::load::source::SourceData;
use dmpscope_core::{Error, Level, PrepSettings, RawDemo, TimeSource, Unusable, build_model};

fn sample() -> Vec<RawDemo> {
    let bytes = include_bytes!("../../assets/reach10.mcap");
    load_source(
        "reach10.mcap",
        SourceData::Bytes(bytes),
        &LoadOptions::default(),
    )
    .expect("sample")
    .demos
}

fn short(name: &str) -> RawDemo {
    RawDemo {
        name: name.to_owned(),
        file: "short.mcap".into(),
        topic: "/short".into(),
        stamps_ns: (0..5).map(|k| k * 10_000_000).collect(),
        positions: (0..5).map(|k| [0.0, 0.0, k as f64].into()).collect(),
        orientations: None,
        time_source: TimeSource::HeaderStamp,
    }
}

#[test]
fn unusable_demos_are_skipped_with_a_warning_or_stop_the_build() {
    let mut demos = sample();
    demos.insert(2, short("short.mcap:/short"));
    let prep = PrepSettings::default();
    let built = build_model(&demos, &prep, Default::default(), Unusable::Skip).expect("skip");
    assert_eq!(built.model.demos().len(), 10);
    assert_eq!(built.used, [0, 1, 3, 4, 5, 6, 7, 8, 9, 10]);
    // The short demo's warning, and one note for the ten reaches recorded
    // with the identity orientation throughout.
    assert_eq!(built.notices.len(), 2, "{:?}", built.notices);
    assert_eq!(built.notices[0].level, Level::Warning);
    assert!(built.notices[0].text.contains("short.mcap:/short"));
    assert_eq!(built.notices[1].level, Level::Info);
    assert!(
        built.notices[1].text.contains("10 demos")
            && built.notices[1].text.contains("the same throughout")
    );
    let err = build_model(&demos, &prep, Default::default(), Unusable::Fail).expect_err("fail");
    assert!(matches!(err, Error::TooFewSamples { .. }), "{err}");
    // The error says what to change.
    assert!(err.to_string().contains("--sg-window"), "{err}");
    let none = build_model(
        &[short("a"), short("b")],
        &prep,
        Default::default(),
        Unusable::Skip,
    )
    .expect_err("nothing usable");
    match none {
        Error::NoUsableDemo { reasons } => assert_eq!(reasons.len(), 2),
        other => panic!("{other}"),
    }
    let one = build_model(&demos[..1], &prep, Default::default(), Unusable::Skip).expect("one");
    assert!(one.notices.iter().any(|n| n.text.contains("S needs two")));
}

#[test]
fn a_bad_setting_is_an_error_whatever_the_policy() {
    let prep = PrepSettings {
        sg_window: 4,
        ..PrepSettings::default()
    };
    let err = build_model(&sample(), &prep, Default::default(), Unusable::Skip).expect_err("bad");
    assert!(matches!(err, Error::InvalidSetting(_)), "{err}");
}

#[test]
fn load_source_reads_csv_bytes_folders_and_metadata_yaml_alike() {
    let dir = std::env::temp_dir().join(format!("dmpscope-source-{}", std::process::id()));
    let bag = dir.join("bag");
    std::fs::create_dir_all(&bag).expect("folder");
    let bytes = include_bytes!("../../assets/reach10.mcap");
    std::fs::write(bag.join("bag_0.mcap"), bytes).expect("write");
    std::fs::write(
        bag.join("metadata.yaml"),
        "rosbag2_bagfile_information: {}\n",
    )
    .expect("yaml");
    let options = LoadOptions::default();
    let folder = load_source("bag", SourceData::Path(&bag), &options).expect("folder");
    let yaml = bag.join("metadata.yaml");
    let via_yaml = load_source("bag", SourceData::Path(&yaml), &options).expect("metadata.yaml");
    assert_eq!(folder, via_yaml);
    assert_eq!(folder.demos.len(), 10);
    let from_bytes = sample();
    for (a, b) in folder.demos.iter().zip(&from_bytes) {
        assert_eq!((&a.stamps_ns, &a.positions), (&b.stamps_ns, &b.positions));
    }
    // CSV, from bytes and from a path, with the up axis applied.
    let csv = "t,x,y,z\n0,1,2,3\n0.5,1,2,4\n";
    let y_up = LoadOptions {
        up: UpAxis::YUp,
        ..LoadOptions::default()
    };
    std::fs::write(dir.join("take.csv"), csv).expect("csv");
    let a = load_source("take.csv", SourceData::Bytes(csv.as_bytes()), &y_up).expect("bytes");
    let path = dir.join("take.csv");
    let b = load_source("take.csv", SourceData::Path(&path), &y_up).expect("path");
    assert_eq!(a, b);
    assert_eq!(a.demos[0].positions[0], Vec3::new(-3.0, -1.0, 2.0));
    // A folder without recordings is named in the error.
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).expect("empty");
    let err = load_source("empty", SourceData::Path(&empty), &options).expect_err("empty");
    assert!(err.to_string().contains("holds no .mcap file"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}
