//! Foxglove pose schemas written in JSON (message encoding `json`): their
//! JSON Schemas and message encoders, times as `{"sec": .., "nsec": ..}`.

use serde_json::{Value, json};

use crate::load::decode::foxglove_schemas::FoxgloveSchema;
use crate::load::decode::foxglove_schemas::split_stamp;

/// One `foxglove.FrameTransform` to encode (identity rotation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform<'a> {
    /// The stamp in nanoseconds (0 for none).
    pub stamp_ns: i64,
    /// The parent frame.
    pub parent_frame_id: &'a str,
    /// The child frame: the key of the demo it belongs to.
    pub child_frame_id: &'a str,
    /// The child frame's origin in the parent frame, in metres.
    pub translation: [f64; 3],
}

/// The JSON Schema of a Foxglove schema (the schema data of a JSON channel).
pub fn json_schema(schema: FoxgloveSchema) -> String {
    let string = || json!({ "type": "string" });
    let value = match schema {
        FoxgloveSchema::PoseInFrame => json!({
            "type": "object",
            "title": "foxglove.PoseInFrame",
            "description": "A timestamped pose for an object or reference frame in 3D space",
            "properties": {
                "timestamp": time_schema("Timestamp of pose"),
                "frame_id": string(),
                "pose": pose_schema()
            }
        }),
        FoxgloveSchema::PosesInFrame => json!({
            "type": "object",
            "title": "foxglove.PosesInFrame",
            "description": "An array of timestamped poses for an object or reference frame in 3D space",
            "properties": {
                "timestamp": time_schema("Timestamp of pose"),
                "frame_id": string(),
                "poses": { "type": "array", "items": pose_schema() }
            }
        }),
        FoxgloveSchema::FrameTransform => transform_schema(),
        FoxgloveSchema::FrameTransforms => json!({
            "type": "object",
            "title": "foxglove.FrameTransforms",
            "description": "An array of FrameTransform messages",
            "properties": {
                "transforms": { "type": "array", "items": transform_schema() }
            }
        }),
    };
    value.to_string()
}

/// The schema of a Foxglove time.
fn time_schema(what: &str) -> Value {
    json!({
        "type": "object",
        "title": "time",
        "description": what,
        "properties": {
            "sec": { "type": "integer", "minimum": 0 },
            "nsec": { "type": "integer", "minimum": 0, "maximum": 999_999_999 }
        }
    })
}

/// The schema of `foxglove.Vector3` (`xyz`) or `foxglove.Quaternion`
/// (`xyzw`).
fn components_schema(title: &str, names: &[&str]) -> Value {
    let properties: serde_json::Map<String, Value> = names
        .iter()
        .map(|n| ((*n).to_owned(), json!({ "type": "number" })))
        .collect();
    json!({ "type": "object", "title": title, "properties": properties })
}

/// The schema of `foxglove.Pose`.
fn pose_schema() -> Value {
    json!({
        "type": "object",
        "title": "foxglove.Pose",
        "properties": {
            "position": components_schema("foxglove.Vector3", &["x", "y", "z"]),
            "orientation": components_schema("foxglove.Quaternion", &["x", "y", "z", "w"])
        }
    })
}

/// The schema of `foxglove.FrameTransform`.
fn transform_schema() -> Value {
    json!({
        "type": "object",
        "title": "foxglove.FrameTransform",
        "description": "A transform between two reference frames in 3D space",
        "properties": {
            "timestamp": time_schema("Timestamp of transform"),
            "parent_frame_id": { "type": "string" },
            "child_frame_id": { "type": "string" },
            "translation": components_schema("foxglove.Vector3", &["x", "y", "z"]),
            "rotation": components_schema("foxglove.Quaternion", &["x", "y", "z", "w"])
        }
    })
}

fn time_json(stamp_ns: i64) -> Value {
    let (sec, nsec) = split_stamp(stamp_ns);
    json!({ "sec": sec, "nsec": nsec })
}

fn vector3_json(p: [f64; 3]) -> Value {
    json!({ "x": p[0], "y": p[1], "z": p[2] })
}

fn pose_json(p: [f64; 3]) -> Value {
    json!({
        "position": vector3_json(p),
        "orientation": { "x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0 }
    })
}

fn transform_json(t: &Transform<'_>) -> Value {
    json!({
        "timestamp": time_json(t.stamp_ns),
        "parent_frame_id": t.parent_frame_id,
        "child_frame_id": t.child_frame_id,
        "translation": vector3_json(t.translation),
        "rotation": { "x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0 }
    })
}

/// Encodes `foxglove.PoseInFrame` as JSON (identity orientation). JSON has
/// no NaN or infinity: a non-finite coordinate is written as `null`.
pub fn encode_pose_in_frame_json(stamp_ns: i64, frame_id: &str, position: [f64; 3]) -> Vec<u8> {
    json!({
        "timestamp": time_json(stamp_ns),
        "frame_id": frame_id,
        "pose": pose_json(position)
    })
    .to_string()
    .into_bytes()
}

/// Encodes `foxglove.PosesInFrame` as JSON, one pose per position.
pub fn encode_poses_in_frame_json(
    stamp_ns: i64,
    frame_id: &str,
    positions: &[[f64; 3]],
) -> Vec<u8> {
    let poses: Vec<_> = positions.iter().map(|&p| pose_json(p)).collect();
    json!({
        "timestamp": time_json(stamp_ns),
        "frame_id": frame_id,
        "poses": poses
    })
    .to_string()
    .into_bytes()
}

/// Encodes `foxglove.FrameTransform` as JSON.
pub fn encode_frame_transform_json(transform: &Transform<'_>) -> Vec<u8> {
    transform_json(transform).to_string().into_bytes()
}

/// Encodes `foxglove.FrameTransforms` as JSON.
pub fn encode_frame_transforms_json(transforms: &[Transform<'_>]) -> Vec<u8> {
    let list: Vec<_> = transforms.iter().map(transform_json).collect();
    json!({ "transforms": list }).to_string().into_bytes()
}
