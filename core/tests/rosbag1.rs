//! ROS 1 bags, written by an independent writer (the `rosbags` PyPI
//! package, `tests/bags/make_bags.py`): uncompressed, bz2 and lz4 bags give
//! exactly the demos of the same bags converted to ROS 2 MCAP by
//! `rosbags-convert` (stamps, positions, orientations, skipped topics); a
//! bag from bytes is recognised by its first bytes; a bag whose recording
//! was killed is read as far as it is valid, with warnings; a corrupt one is
//! an error naming the file and the chunk; no cut or flipped byte panics.

use std::path::{Path, PathBuf};

use dmpscope_core::arrange::streams::load_source;
use dmpscope_core::load::options::LoadOptions;
use dmpscope_core::load::source::{SourceData, load_streams};
use dmpscope_core::{Error, RawDemo};

fn bags() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bags")
}

fn streams(path: &Path) -> Vec<RawDemo> {
    let name = path.display().to_string();
    load_streams(&name, SourceData::Path(path), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .demos
}

/// The topic (and key) of a stream, without its file.
fn topic(d: &RawDemo) -> &str {
    d.topic.as_str()
}

#[test]
fn each_compression_gives_the_demos_of_its_ros2_conversion() {
    for k in 1..=3 {
        let bag = streams(&bags().join(format!("reach/reach_{k}.bag")));
        let mcap = streams(&bags().join(format!("converted/reach_{k}")));
        let names = |v: &[RawDemo]| v.iter().map(|d| topic(d).to_owned()).collect::<Vec<_>>();
        assert_eq!(names(&bag), names(&mcap), "reach_{k}");
        assert_eq!(
            names(&bag),
            ["/tf:tracker", "/tf_static:base", "/vive/controller"],
            "reach_{k}"
        );
        for (a, b) in bag.iter().zip(&mcap) {
            assert_eq!(a.stamps_ns, b.stamps_ns, "{}", a.name);
            assert_eq!(a.positions, b.positions, "{}", a.name);
            assert_eq!(a.orientations, b.orientations, "{}", a.name);
            assert_eq!(a.time_source, b.time_source, "{}", a.name);
            assert!(a.orientations.is_some(), "{}", a.name);
        }
        assert!(
            bag[2].name.starts_with(&format!("reach_{k}.bag:")),
            "{}",
            bag[2].name
        );
    }
}

#[test]
fn a_folder_of_bags_loads_like_the_folder_of_conversions_and_names_the_custom_type() {
    let options = LoadOptions::default();
    let folder = bags().join("reach");
    let label = folder.display().to_string();
    let from_bags = load_source(&label, SourceData::Path(&folder), &options).expect("bags");
    let converted = bags().join("converted");
    let label = converted.display().to_string();
    let from_mcap = load_source(&label, SourceData::Path(&converted), &options).expect("mcap");
    assert_eq!(from_bags.demos.len(), 6);
    assert_eq!(from_bags.demos.len(), from_mcap.demos.len());
    for (a, b) in from_bags.demos.iter().zip(&from_mcap.demos) {
        assert_eq!((&a.stamps_ns, &a.positions), (&b.stamps_ns, &b.positions));
    }
    // The custom message type beside the poses is skipped with its name.
    let skipped: Vec<String> = from_bags.skipped.iter().map(|s| s.1.clone()).collect();
    assert!(skipped.iter().all(|s| s == "my_msgs/Button"), "{skipped:?}");
    assert_eq!(skipped.len(), 3);
}

#[test]
fn bytes_are_recognised_as_a_bag_by_their_first_bytes() {
    let bytes = std::fs::read(bags().join("reach/reach_2.bag")).expect("bag");
    let options = LoadOptions::default();
    let loaded = load_streams("upload", SourceData::Bytes(&bytes), &options).expect("bytes");
    let from_file = streams(&bags().join("reach/reach_2.bag"));
    assert_eq!(loaded.demos.len(), from_file.len());
    for (a, b) in loaded.demos.iter().zip(&from_file) {
        assert_eq!((&a.topic, &a.positions), (&b.topic, &b.positions));
    }
}

#[test]
fn a_killed_recording_is_read_as_far_as_it_is_valid_and_says_so() {
    let path = bags().join("odd/unindexed.bag");
    let label = path.display().to_string();
    let loaded = load_streams(&label, SourceData::Path(&path), &LoadOptions::default())
        .expect("an unindexed bag loads");
    let text: Vec<String> = loaded.notices.iter().map(|n| n.text.clone()).collect();
    assert!(text.iter().any(|t| t.contains("has no index")), "{text:?}");
    assert!(text.iter().any(|t| t.contains("truncated")), "{text:?}");
    let full = streams(&bags().join("reach/reach_1.bag"));
    let controller = |v: &[RawDemo]| {
        v.iter()
            .find(|d| d.topic == "/vive/controller")
            .cloned()
            .expect("controller")
    };
    let (cut, whole) = (controller(&loaded.demos), controller(&full));
    assert!(cut.positions.len() > 10 && cut.positions.len() < whole.positions.len());
    assert_eq!(cut.positions[..], whole.positions[..cut.positions.len()]);
}

#[test]
fn a_corrupt_chunk_is_an_error_naming_file_and_chunk() {
    let path = bags().join("odd/corrupt.bag");
    let label = path.display().to_string();
    let err = load_streams(&label, SourceData::Path(&path), &LoadOptions::default())
        .expect_err("corrupt");
    assert!(matches!(err, Error::Bag { .. }), "{err:?}");
    let text = err.to_string();
    assert!(
        text.contains("corrupt.bag") && text.contains("chunk 1") && text.contains("lz4"),
        "{text}"
    );
}

#[test]
fn no_cut_or_flipped_byte_panics() {
    let options = LoadOptions::default();
    for name in [
        "reach/reach_1.bag",
        "reach/reach_2.bag",
        "reach/reach_3.bag",
    ] {
        let bytes = std::fs::read(bags().join(name)).expect("bag");
        for cut in (0..bytes.len()).step_by(211) {
            let _ = load_streams("cut.bag", SourceData::Bytes(&bytes[..cut]), &options);
        }
        for at in (13..bytes.len()).step_by(97) {
            let mut flipped = bytes.clone();
            flipped[at] ^= 0xFF;
            let _ = load_streams("flipped.bag", SourceData::Bytes(&flipped), &options);
        }
    }
    // Only the magic, and a format 1.2 bag: clear errors.
    let err = load_streams("empty.bag", SourceData::Bytes(b"#ROSBAG V2.0\n"), &options)
        .expect_err("no messages");
    assert!(err.to_string().contains("empty.bag"), "{err}");
    let err = load_streams("old.bag", SourceData::Bytes(b"#ROSBAG V1.2\n"), &options)
        .expect_err("format 1.2");
    assert!(err.to_string().contains("format 1"), "{err}");
}

#[test]
fn every_ros1_pose_type_gives_the_same_motion() {
    let reach = streams(&bags().join("reach/reach_1.bag"));
    let controller = reach
        .iter()
        .find(|d| d.topic == "/vive/controller")
        .expect("controller");
    let types = streams(&bags().join("types.bag"));
    let topics: Vec<&str> = types.iter().map(topic).collect();
    assert_eq!(topics, ["/cov", "/odom", "/point", "/transform:tracker"]);
    for d in &types {
        assert_eq!(d.stamps_ns, controller.stamps_ns, "{}", d.name);
        assert_eq!(d.positions, controller.positions, "{}", d.name);
        if d.topic == "/point" {
            assert!(d.orientations.is_none());
        } else {
            assert_eq!(d.orientations, controller.orientations, "{}", d.name);
        }
    }
}

#[test]
fn a_compressed_bag_killed_inside_a_chunk_keeps_its_closed_chunks() {
    // rosbag writes a chunk's header with size 0 and fills it in when the
    // chunk closes: the open chunk's lz4 bytes follow a header saying 0.
    let path = bags().join("odd/killed_lz4.bag");
    let label = path.display().to_string();
    let loaded = load_streams(&label, SourceData::Path(&path), &LoadOptions::default())
        .expect("a killed lz4 bag loads");
    let text: Vec<String> = loaded.notices.iter().map(|n| n.text.clone()).collect();
    assert!(text.iter().any(|t| t.contains("has no index")), "{text:?}");
    assert!(text.iter().any(|t| t.contains("truncated")), "{text:?}");
    let full = streams(&bags().join("reach/reach_3.bag"));
    let controller = |v: &[RawDemo]| {
        v.iter()
            .find(|d| d.topic == "/vive/controller")
            .cloned()
            .expect("controller")
    };
    let (cut, whole) = (controller(&loaded.demos), controller(&full));
    assert!(cut.positions.len() > 10 && cut.positions.len() < whole.positions.len());
    assert_eq!(cut.positions[..], whole.positions[..cut.positions.len()]);
}

#[test]
fn a_recording_without_poses_beside_the_bags_is_skipped_and_said() {
    use dmpscope_core::export::write::{BulkTopic, write_pose_stamped_with_bulk};
    let dir = std::env::temp_dir().join(format!("dmpscope-mixed-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("folder");
    std::fs::copy(bags().join("reach/reach_1.bag"), dir.join("reach_1.bag")).expect("copy");
    // A camera recording: no pose topic at all.
    let camera = BulkTopic {
        topic: "/camera",
        message_bytes: 64,
        messages: 5,
    };
    let file = std::fs::File::create(dir.join("camera.mcap")).expect("create");
    write_pose_stamped_with_bulk(file, &[], false, Some(camera)).expect("write");
    let label = dir.display().to_string();
    let loaded = load_source(&label, SourceData::Path(&dir), &LoadOptions::default())
        .expect("the folder loads");
    assert!(loaded.demos.iter().any(|d| d.topic == "/vive/controller"));
    let text: Vec<String> = loaded.notices.iter().map(|n| n.text.clone()).collect();
    assert!(
        text.iter()
            .any(|t| t.contains("camera.mcap") && t.contains("/camera") && t.contains("skipped")),
        "{text:?}"
    );
    // Alone, it is an error that says why.
    std::fs::remove_file(dir.join("reach_1.bag")).expect("remove");
    let err = load_source(&label, SourceData::Path(&dir), &LoadOptions::default())
        .expect_err("no poses anywhere");
    assert!(err.to_string().contains("camera.mcap"), "{err}");
}
