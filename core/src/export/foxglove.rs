//! Foxglove recordings written: the pose schemas' protobuf
//! FileDescriptorSets (built here, field numbers as in Foxglove's published
//! `.proto` files), protobuf message encoders and an MCAP writer of
//! encoded topics; the JSON side is [`crate::export::foxglove_json`].

use std::collections::BTreeMap;
use std::io::{Seek, Write};
use std::sync::OnceLock;

use mcap::records::MessageHeader;
use prost_reflect::prost::Message as _;
use prost_reflect::prost_types::field_descriptor_proto::{Label, Type};
use prost_reflect::prost_types::{
    DescriptorProto, FieldDescriptorProto, FileDescriptorProto, FileDescriptorSet,
};
use prost_reflect::{DescriptorPool, DynamicMessage, Value};

use crate::export::write::TopicSamples;

use crate::export::foxglove_json::{Transform, encode_pose_in_frame_json, json_schema};
use crate::load::decode::foxglove_schemas::FoxgloveSchema;
use crate::load::decode::foxglove_schemas::split_stamp;

/// How the messages of a channel are encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FoxgloveEncoding {
    /// Protobuf, described by a FileDescriptorSet.
    Protobuf,
    /// JSON, described by a JSON Schema.
    Json,
}

impl FoxgloveEncoding {
    /// The MCAP channel's message encoding.
    pub fn message_encoding(self) -> &'static str {
        match self {
            Self::Protobuf => "protobuf",
            Self::Json => "json",
        }
    }

    /// The MCAP schema's encoding.
    pub fn schema_encoding(self) -> &'static str {
        match self {
            Self::Protobuf => "protobuf",
            Self::Json => "jsonschema",
        }
    }

    /// The MCAP schema's data for `schema`.
    pub fn schema_data(self, schema: FoxgloveSchema) -> Vec<u8> {
        match self {
            Self::Protobuf => descriptor_set_bytes(schema),
            Self::Json => json_schema(schema).into_bytes(),
        }
    }
}

// ------------------------------------------------------------ descriptors

const TIMESTAMP_PROTO: &str = "google/protobuf/timestamp.proto";
const VECTOR3_PROTO: &str = "foxglove/Vector3.proto";
const QUATERNION_PROTO: &str = "foxglove/Quaternion.proto";
const POSE_PROTO: &str = "foxglove/Pose.proto";
const POSE_IN_FRAME_PROTO: &str = "foxglove/PoseInFrame.proto";
const POSES_IN_FRAME_PROTO: &str = "foxglove/PosesInFrame.proto";
const FRAME_TRANSFORM_PROTO: &str = "foxglove/FrameTransform.proto";
const FRAME_TRANSFORMS_PROTO: &str = "foxglove/FrameTransforms.proto";

/// One field of a descriptor; `type_name` is set for message fields.
fn field(name: &str, number: i32, ty: Type, type_name: Option<&str>) -> FieldDescriptorProto {
    FieldDescriptorProto {
        name: Some(name.to_owned()),
        number: Some(number),
        label: Some(Label::Optional as i32),
        r#type: Some(ty as i32),
        type_name: type_name.map(str::to_owned),
        ..FieldDescriptorProto::default()
    }
}

/// A repeated message field.
fn repeated(name: &str, number: i32, type_name: &str) -> FieldDescriptorProto {
    FieldDescriptorProto {
        label: Some(Label::Repeated as i32),
        ..field(name, number, Type::Message, Some(type_name))
    }
}

/// A proto3 file holding one message.
fn file(
    name: &str,
    package: &str,
    deps: &[&str],
    message: &str,
    fields: Vec<FieldDescriptorProto>,
) -> FileDescriptorProto {
    FileDescriptorProto {
        name: Some(name.to_owned()),
        package: Some(package.to_owned()),
        dependency: deps.iter().map(|d| (*d).to_owned()).collect(),
        message_type: vec![DescriptorProto {
            name: Some(message.to_owned()),
            field: fields,
            ..DescriptorProto::default()
        }],
        syntax: Some("proto3".to_owned()),
        ..FileDescriptorProto::default()
    }
}

/// The file descriptor of one of the `.proto` files, by its file name.
fn proto_file(name: &str) -> Option<FileDescriptorProto> {
    const TS: Option<&str> = Some(".google.protobuf.Timestamp");
    const V3: Option<&str> = Some(".foxglove.Vector3");
    const Q: Option<&str> = Some(".foxglove.Quaternion");
    const POSE: Option<&str> = Some(".foxglove.Pose");
    let fox = "foxglove";
    let xyz = |w: bool| {
        let mut f = vec![
            field("x", 1, Type::Double, None),
            field("y", 2, Type::Double, None),
            field("z", 3, Type::Double, None),
        ];
        if w {
            f.push(field("w", 4, Type::Double, None));
        }
        f
    };
    let stamp_and_frame = || {
        vec![
            field("timestamp", 1, Type::Message, TS),
            field("frame_id", 2, Type::String, None),
        ]
    };
    Some(match name {
        TIMESTAMP_PROTO => file(
            name,
            "google.protobuf",
            &[],
            "Timestamp",
            vec![
                field("seconds", 1, Type::Int64, None),
                field("nanos", 2, Type::Int32, None),
            ],
        ),
        VECTOR3_PROTO => file(name, fox, &[], "Vector3", xyz(false)),
        QUATERNION_PROTO => file(name, fox, &[], "Quaternion", xyz(true)),
        POSE_PROTO => file(
            name,
            fox,
            &[QUATERNION_PROTO, VECTOR3_PROTO],
            "Pose",
            vec![
                field("position", 1, Type::Message, V3),
                field("orientation", 2, Type::Message, Q),
            ],
        ),
        POSE_IN_FRAME_PROTO => {
            let mut f = stamp_and_frame();
            f.push(field("pose", 3, Type::Message, POSE));
            file(name, fox, &[POSE_PROTO, TIMESTAMP_PROTO], "PoseInFrame", f)
        }
        POSES_IN_FRAME_PROTO => {
            let mut f = stamp_and_frame();
            f.push(repeated("poses", 3, ".foxglove.Pose"));
            file(name, fox, &[POSE_PROTO, TIMESTAMP_PROTO], "PosesInFrame", f)
        }
        FRAME_TRANSFORM_PROTO => file(
            name,
            fox,
            &[QUATERNION_PROTO, VECTOR3_PROTO, TIMESTAMP_PROTO],
            "FrameTransform",
            vec![
                field("timestamp", 1, Type::Message, TS),
                field("parent_frame_id", 2, Type::String, None),
                field("child_frame_id", 3, Type::String, None),
                field("translation", 4, Type::Message, V3),
                field("rotation", 5, Type::Message, Q),
            ],
        ),
        FRAME_TRANSFORMS_PROTO => file(
            name,
            fox,
            &[FRAME_TRANSFORM_PROTO],
            "FrameTransforms",
            vec![repeated("transforms", 1, ".foxglove.FrameTransform")],
        ),
        _ => return None,
    })
}

/// The `.proto` files a schema needs, dependencies first.
fn files_of(schema: FoxgloveSchema) -> &'static [&'static str] {
    const COMMON: [&str; 3] = [TIMESTAMP_PROTO, VECTOR3_PROTO, QUATERNION_PROTO];
    match schema {
        FoxgloveSchema::PoseInFrame => &[
            COMMON[0],
            COMMON[1],
            COMMON[2],
            POSE_PROTO,
            POSE_IN_FRAME_PROTO,
        ],
        FoxgloveSchema::PosesInFrame => &[
            COMMON[0],
            COMMON[1],
            COMMON[2],
            POSE_PROTO,
            POSES_IN_FRAME_PROTO,
        ],
        FoxgloveSchema::FrameTransform => &[COMMON[0], COMMON[1], COMMON[2], FRAME_TRANSFORM_PROTO],
        FoxgloveSchema::FrameTransforms => &[
            COMMON[0],
            COMMON[1],
            COMMON[2],
            FRAME_TRANSFORM_PROTO,
            FRAME_TRANSFORMS_PROTO,
        ],
    }
}

/// The FileDescriptorSet of a schema: its message's file and every file it
/// depends on, as Foxglove writes it into an MCAP schema record.
pub fn descriptor_set(schema: FoxgloveSchema) -> FileDescriptorSet {
    FileDescriptorSet {
        file: files_of(schema)
            .iter()
            .filter_map(|name| proto_file(name))
            .collect(),
    }
}

/// [`descriptor_set`] serialized: the schema data of a protobuf channel.
pub fn descriptor_set_bytes(schema: FoxgloveSchema) -> Vec<u8> {
    descriptor_set(schema).encode_to_vec()
}

// --------------------------------------------------------------- messages

/// The pool of every built-in descriptor, built once.
fn pool() -> Result<&'static DescriptorPool, String> {
    static POOL: OnceLock<Result<DescriptorPool, String>> = OnceLock::new();
    POOL.get_or_init(|| {
        let mut set = descriptor_set(FoxgloveSchema::PoseInFrame);
        for name in [
            POSES_IN_FRAME_PROTO,
            FRAME_TRANSFORM_PROTO,
            FRAME_TRANSFORMS_PROTO,
        ] {
            set.file.extend(proto_file(name));
        }
        DescriptorPool::from_file_descriptor_set(set).map_err(|e| e.to_string())
    })
    .as_ref()
    .map_err(Clone::clone)
}

/// A message of a built-in type with the given fields set.
fn message(name: &str, fields: Vec<(&str, Value)>) -> Result<DynamicMessage, String> {
    let desc = pool()?
        .get_message_by_name(name)
        .ok_or_else(|| format!("no built-in descriptor of {name}"))?;
    let mut msg = DynamicMessage::new(desc);
    for (field, value) in fields {
        msg.try_set_field_by_name(field, value)
            .map_err(|e| format!("{name}.{field}: {e}"))?;
    }
    Ok(msg)
}

fn time_proto(stamp_ns: i64) -> Result<Value, String> {
    let (seconds, nanos) = split_stamp(stamp_ns);
    let nanos = i32::try_from(nanos).map_err(|e| e.to_string())?;
    let fields = vec![
        ("seconds", Value::I64(seconds)),
        ("nanos", Value::I32(nanos)),
    ];
    message("google.protobuf.Timestamp", fields).map(Value::Message)
}

fn vector3_proto(p: [f64; 3]) -> Result<Value, String> {
    let fields = vec![
        ("x", Value::F64(p[0])),
        ("y", Value::F64(p[1])),
        ("z", Value::F64(p[2])),
    ];
    message("foxglove.Vector3", fields).map(Value::Message)
}

fn identity_proto() -> Result<Value, String> {
    message("foxglove.Quaternion", vec![("w", Value::F64(1.0))]).map(Value::Message)
}

fn pose_proto(p: [f64; 3]) -> Result<Value, String> {
    let fields = vec![
        ("position", vector3_proto(p)?),
        ("orientation", identity_proto()?),
    ];
    message("foxglove.Pose", fields).map(Value::Message)
}

fn transform_proto(t: &Transform<'_>) -> Result<DynamicMessage, String> {
    let fields = vec![
        ("timestamp", time_proto(t.stamp_ns)?),
        (
            "parent_frame_id",
            Value::String(t.parent_frame_id.to_owned()),
        ),
        ("child_frame_id", Value::String(t.child_frame_id.to_owned())),
        ("translation", vector3_proto(t.translation)?),
        ("rotation", identity_proto()?),
    ];
    message("foxglove.FrameTransform", fields)
}

/// Encodes `foxglove.PoseInFrame` as protobuf (identity orientation); an
/// `Err` only if the built-in descriptors were broken.
pub fn encode_pose_in_frame_proto(
    stamp_ns: i64,
    frame_id: &str,
    position: [f64; 3],
) -> Result<Vec<u8>, String> {
    let fields = vec![
        ("timestamp", time_proto(stamp_ns)?),
        ("frame_id", Value::String(frame_id.to_owned())),
        ("pose", pose_proto(position)?),
    ];
    Ok(message("foxglove.PoseInFrame", fields)?.encode_to_vec())
}

/// Encodes `foxglove.PosesInFrame` as protobuf, one pose per position.
pub fn encode_poses_in_frame_proto(
    stamp_ns: i64,
    frame_id: &str,
    positions: &[[f64; 3]],
) -> Result<Vec<u8>, String> {
    let poses = positions
        .iter()
        .map(|&p| pose_proto(p))
        .collect::<Result<_, _>>()?;
    let fields = vec![
        ("timestamp", time_proto(stamp_ns)?),
        ("frame_id", Value::String(frame_id.to_owned())),
        ("poses", Value::List(poses)),
    ];
    Ok(message("foxglove.PosesInFrame", fields)?.encode_to_vec())
}

/// Encodes `foxglove.FrameTransform` as protobuf.
pub fn encode_frame_transform_proto(transform: &Transform<'_>) -> Result<Vec<u8>, String> {
    Ok(transform_proto(transform)?.encode_to_vec())
}

/// Encodes `foxglove.FrameTransforms` as protobuf.
pub fn encode_frame_transforms_proto(transforms: &[Transform<'_>]) -> Result<Vec<u8>, String> {
    let list = transforms
        .iter()
        .map(|t| transform_proto(t).map(Value::Message))
        .collect::<Result<_, _>>()?;
    let fields = vec![("transforms", Value::List(list))];
    Ok(message("foxglove.FrameTransforms", fields)?.encode_to_vec())
}

// ------------------------------------------------------------------- MCAP

/// One topic of already encoded messages, each `(log_time_ns, bytes)`.
pub struct EncodedTopic<'a> {
    /// The topic name.
    pub topic: &'a str,
    /// The messages in the order they should be written.
    pub messages: &'a [(i64, Vec<u8>)],
}

/// Writes already encoded messages of one Foxglove schema into an MCAP file
/// (zstd-compressed chunks when `compress`), one channel per topic, with the
/// schema record Foxglove would write (FileDescriptorSet or JSON Schema).
pub fn write_encoded<W: Write + Seek>(
    out: W,
    schema: FoxgloveSchema,
    encoding: FoxgloveEncoding,
    topics: &[EncodedTopic<'_>],
    compress: bool,
) -> mcap::McapResult<W> {
    let compression = compress.then_some(mcap::Compression::Zstd);
    let mut writer = mcap::WriteOptions::new()
        .compression(compression)
        .library(concat!("dmpscope/", env!("CARGO_PKG_VERSION")))
        .create(out)?;
    let schema_id = writer.add_schema(
        schema.name(),
        encoding.schema_encoding(),
        &encoding.schema_data(schema),
    )?;
    for topic in topics {
        let channel_id = writer.add_channel(
            schema_id,
            topic.topic,
            encoding.message_encoding(),
            &BTreeMap::new(),
        )?;
        for (sequence, (log_time, data)) in topic.messages.iter().enumerate() {
            let time = u64::try_from(*log_time).unwrap_or(0);
            writer.write_to_known_channel(
                &MessageHeader {
                    channel_id,
                    sequence: sequence as u32,
                    log_time: time,
                    publish_time: time,
                },
                data,
            )?;
        }
    }
    writer.finish()?;
    Ok(writer.into_inner())
}

/// Writes the topics as `foxglove.PoseInFrame` in JSON (the stamp is both
/// message timestamp and log time), each topic's samples in the order given.
pub fn write_pose_in_frame_json<W: Write + Seek>(
    out: W,
    topics: &[TopicSamples<'_>],
    compress: bool,
) -> mcap::McapResult<W> {
    let encoded: Vec<Vec<(i64, Vec<u8>)>> = topics
        .iter()
        .map(|t| {
            t.samples
                .iter()
                .map(|&(stamp, p)| (stamp, encode_pose_in_frame_json(stamp, t.frame_id, p)))
                .collect()
        })
        .collect();
    let list: Vec<EncodedTopic<'_>> = topics
        .iter()
        .zip(&encoded)
        .map(|(t, messages)| EncodedTopic {
            topic: t.topic,
            messages,
        })
        .collect();
    write_encoded(
        out,
        FoxgloveSchema::PoseInFrame,
        FoxgloveEncoding::Json,
        &list,
        compress,
    )
}
