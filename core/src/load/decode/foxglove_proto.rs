//! Foxglove pose schemas in protobuf, decoded dynamically: the channel's
//! FileDescriptorSet is turned into a descriptor pool once, the fields
//! dmpscope reads are looked up by name once (and their types checked), and
//! every message is decoded as a [`DynamicMessage`]. Field numbers therefore
//! come from the file itself, never from code generated here.

use std::borrow::Cow;

use prost_reflect::{
    DescriptorPool, DynamicMessage, FieldDescriptor, Kind, MessageDescriptor, Value,
};

use crate::load::decode::foxglove_schemas::FoxgloveSchema;
use crate::load::decode::foxglove_schemas::stamp_ns;
use crate::load::decode::{ChannelSchema, MessageDecoder, PoseSample};

/// The decoder of a protobuf channel: `None` unless its schema is one of
/// the Foxglove pose schemas, `Some(Err)` when the FileDescriptorSet is not
/// usable (not a FileDescriptorSet, missing the message or a field, a field
/// of the wrong type).
pub fn decoder(channel: &ChannelSchema<'_>) -> Option<Result<Box<dyn MessageDecoder>, String>> {
    let schema = FoxgloveSchema::from_name(channel.schema_name)?;
    Some(ProtoDecoder::new(schema, channel).map(|d| Box::new(d) as Box<dyn MessageDecoder>))
}

/// The fields of a `google.protobuf.Timestamp` field.
struct Stamp {
    field: FieldDescriptor,
    seconds: FieldDescriptor,
    nanos: FieldDescriptor,
}

/// The path to a Vector3- or Quaternion-like message and its `N` number
/// fields (`x`, `y`, `z`, and `w` for a quaternion).
struct Parts<const N: usize> {
    path: Vec<FieldDescriptor>,
    parts: [FieldDescriptor; N],
}

/// A position: `x`, `y`, `z`.
type Position = Parts<3>;

/// An orientation: `x`, `y`, `z`, `w`.
type Orientation = Parts<4>;

/// The fields of a `foxglove.FrameTransform` (the parent and the rotation
/// only when the schema has them: the TF buffer of `--fixed-frame` needs
/// them, a plain load does not).
struct Transform {
    stamp: Stamp,
    parent: Option<FieldDescriptor>,
    child: FieldDescriptor,
    translation: Position,
    /// The `rotation` and its `x`, `y`, `z`, `w`.
    rotation: Option<Orientation>,
}

/// Where the poses are in a message of each schema.
enum Shape {
    /// `PoseInFrame`: one stamp, one pose.
    Single { stamp: Stamp, pose: Pose },
    /// `PosesInFrame`: one stamp, a list of poses keyed by index.
    Indexed {
        stamp: Stamp,
        poses: FieldDescriptor,
        pose: Pose,
    },
    /// `FrameTransform`: one transform keyed by its child frame.
    Keyed(Transform),
    /// `FrameTransforms`: a list of transforms keyed by their child frames.
    KeyedList {
        transforms: FieldDescriptor,
        each: Transform,
    },
}

struct ProtoDecoder {
    schema: FoxgloveSchema,
    message: MessageDescriptor,
    shape: Shape,
    /// "0", "1", ...: the keys of pose-array indices, made once.
    index_keys: Vec<String>,
}

impl ProtoDecoder {
    fn new(schema: FoxgloveSchema, channel: &ChannelSchema<'_>) -> Result<Self, String> {
        if channel.schema_encoding != "protobuf" {
            return Err(format!(
                "schema encoding {:?}, expected \"protobuf\" (a FileDescriptorSet)",
                channel.schema_encoding
            ));
        }
        let pool = DescriptorPool::decode(channel.schema_data)
            .map_err(|e| format!("not a usable FileDescriptorSet: {e}"))?;
        let name = schema.name();
        let message = pool
            .get_message_by_name(name)
            .ok_or_else(|| format!("the FileDescriptorSet does not define {name}"))?;
        let shape = match schema {
            FoxgloveSchema::PoseInFrame => Shape::Single {
                stamp: Stamp::resolve(&message)?,
                pose: Pose::resolve(&message, &["pose"])?,
            },
            FoxgloveSchema::PosesInFrame => {
                let (poses, pose) = message_field(&message, "poses", true)?;
                Shape::Indexed {
                    stamp: Stamp::resolve(&message)?,
                    poses,
                    pose: Pose::resolve(&pose, &[])?,
                }
            }
            FoxgloveSchema::FrameTransform => Shape::Keyed(Transform::resolve(&message)?),
            FoxgloveSchema::FrameTransforms => {
                let (transforms, each) = message_field(&message, "transforms", true)?;
                Shape::KeyedList {
                    transforms,
                    each: Transform::resolve(&each)?,
                }
            }
        };
        Ok(Self {
            schema,
            message,
            shape,
            index_keys: Vec::new(),
        })
    }
}

impl MessageDecoder for ProtoDecoder {
    fn decode(&mut self, data: &[u8], out: &mut dyn FnMut(PoseSample<'_>)) -> Result<(), String> {
        let Self {
            schema,
            message,
            shape,
            index_keys,
        } = self;
        let msg = DynamicMessage::decode(message.clone(), data)
            .map_err(|e| format!("not a valid protobuf {}: {e}", schema.name()))?;
        match shape {
            Shape::Single { stamp, pose } => {
                let (position, orientation) = pose.read(&msg)?;
                out(PoseSample {
                    key: None,
                    stamp_ns: stamp.read(&msg)?,
                    position,
                    orientation,
                    ..PoseSample::default()
                })
            }
            Shape::Indexed { stamp, poses, pose } => {
                let stamp_ns = stamp.read(&msg)?;
                let list = msg.get_field(poses);
                let read = messages(&list, poses)?
                    .map(|m| pose.read(m))
                    .collect::<Result<Vec<_>, String>>()?;
                while index_keys.len() < read.len() {
                    index_keys.push(index_keys.len().to_string());
                }
                for (key, (position, orientation)) in index_keys.iter().zip(read) {
                    out(PoseSample {
                        key: Some(Cow::Borrowed(key)),
                        stamp_ns,
                        position,
                        orientation,
                        ..PoseSample::default()
                    });
                }
            }
            Shape::Keyed(transform) => out(transform.read(&msg)?),
            Shape::KeyedList { transforms, each } => {
                let list = msg.get_field(transforms);
                let samples = messages(&list, transforms)?
                    .map(|t| each.read(t))
                    .collect::<Result<Vec<_>, String>>()?;
                samples.into_iter().for_each(out);
            }
        }
        Ok(())
    }
}

impl Stamp {
    fn resolve(message: &MessageDescriptor) -> Result<Self, String> {
        let (field, time) = message_field(message, "timestamp", false)?;
        Ok(Self {
            field,
            seconds: scalar_field(&time, "seconds", Scalar::Integer)?,
            nanos: scalar_field(&time, "nanos", Scalar::Integer)?,
        })
    }

    /// The stamp in nanoseconds, `None` when unset or zero.
    fn read(&self, msg: &DynamicMessage) -> Result<Option<i64>, String> {
        if !msg.has_field(&self.field) {
            return Ok(None);
        }
        let value = msg.get_field(&self.field);
        let time = value
            .as_message()
            .ok_or_else(|| not_a("message", &self.field))?;
        let seconds = integer(&time.get_field(&self.seconds), &self.seconds)?;
        let nanos = integer(&time.get_field(&self.nanos), &self.nanos)?;
        stamp_ns(seconds, nanos)
    }
}

/// A `foxglove.Pose` at a path: its position, and its orientation when the
/// schema has one.
struct Pose {
    position: Position,
    orientation: Option<Orientation>,
}

impl Pose {
    fn resolve(message: &MessageDescriptor, path: &[&str]) -> Result<Self, String> {
        let with = |last: &'static str| path.iter().copied().chain([last]).collect::<Vec<_>>();
        Ok(Self {
            position: Parts::resolve(message, &with("position"), ["x", "y", "z"])?,
            orientation: Parts::resolve(message, &with("orientation"), ["x", "y", "z", "w"]).ok(),
        })
    }

    fn read(&self, msg: &DynamicMessage) -> Result<([f64; 3], Option<[f64; 4]>), String> {
        let orientation = match &self.orientation {
            Some(o) => o.read_set(msg)?,
            None => None,
        };
        Ok((self.position.read(msg)?, orientation))
    }
}

impl<const N: usize> Parts<N> {
    fn resolve(
        message: &MessageDescriptor,
        path: &[&str],
        names: [&str; N],
    ) -> Result<Self, String> {
        let mut desc = message.clone();
        let mut fields = Vec::with_capacity(path.len());
        for name in path {
            let (field, inner) = message_field(&desc, name, false)?;
            fields.push(field);
            desc = inner;
        }
        let mut parts = Vec::with_capacity(N);
        for name in names {
            parts.push(scalar_field(&desc, name, Scalar::Float)?);
        }
        let parts = parts
            .try_into()
            .map_err(|_| "a vector's field count".to_owned())?;
        Ok(Self {
            path: fields,
            parts,
        })
    }

    /// The numbers; unset messages on the way give zeros, as in protobuf.
    fn read(&self, msg: &DynamicMessage) -> Result<[f64; N], String> {
        read_parts(msg, &self.path, &self.parts)
    }

    /// The numbers, `None` where a message on the way is unset (an
    /// orientation the message does not carry).
    fn read_set(&self, msg: &DynamicMessage) -> Result<Option<[f64; N]>, String> {
        read_set_parts(msg, &self.path, &self.parts)
    }
}

fn read_set_parts<const N: usize>(
    msg: &DynamicMessage,
    path: &[FieldDescriptor],
    parts: &[FieldDescriptor; N],
) -> Result<Option<[f64; N]>, String> {
    match path.split_first() {
        None => read_parts(msg, &[], parts).map(Some),
        Some((first, rest)) => {
            if !msg.has_field(first) {
                return Ok(None);
            }
            let value = msg.get_field(first);
            let inner = value.as_message().ok_or_else(|| not_a("message", first))?;
            read_set_parts(inner, rest, parts)
        }
    }
}

fn read_parts<const N: usize>(
    msg: &DynamicMessage,
    path: &[FieldDescriptor],
    parts: &[FieldDescriptor; N],
) -> Result<[f64; N], String> {
    match path.split_first() {
        None => {
            let mut p = [0.0; N];
            for (v, field) in p.iter_mut().zip(parts) {
                *v = float(&msg.get_field(field), field)?;
            }
            Ok(p)
        }
        Some((first, rest)) => {
            if !msg.has_field(first) {
                return Ok([0.0; N]);
            }
            let value = msg.get_field(first);
            let inner = value.as_message().ok_or_else(|| not_a("message", first))?;
            read_parts(inner, rest, parts)
        }
    }
}

impl Transform {
    fn resolve(message: &MessageDescriptor) -> Result<Self, String> {
        Ok(Self {
            stamp: Stamp::resolve(message)?,
            parent: scalar_field(message, "parent_frame_id", Scalar::String).ok(),
            child: scalar_field(message, "child_frame_id", Scalar::String)?,
            translation: Parts::resolve(message, &["translation"], ["x", "y", "z"])?,
            rotation: Parts::resolve(message, &["rotation"], ["x", "y", "z", "w"]).ok(),
        })
    }

    /// The pose of one transform: keyed by its child frame, at its
    /// translation.
    fn read<'m>(&self, msg: &'m DynamicMessage) -> Result<PoseSample<'m>, String> {
        let key = match msg.get_field(&self.child) {
            Cow::Borrowed(Value::String(s)) => Cow::Borrowed(s.as_str()),
            Cow::Owned(Value::String(s)) => Cow::Owned(s),
            _ => return Err(not_a("string", &self.child)),
        };
        let parent = match &self.parent {
            None => None,
            Some(field) => match msg.get_field(field) {
                Cow::Borrowed(Value::String(s)) => Some(Cow::Borrowed(s.as_str())),
                Cow::Owned(Value::String(s)) => Some(Cow::Owned(s)),
                _ => return Err(not_a("string", field)),
            },
        };
        // An unset rotation is the identity, as TF takes it.
        let orientation = match &self.rotation {
            Some(r) => Some(r.read_set(msg)?.unwrap_or([0.0, 0.0, 0.0, 1.0])),
            None => None,
        };
        Ok(PoseSample {
            key: Some(key),
            stamp_ns: self.stamp.read(msg)?,
            position: self.translation.read(msg)?,
            parent,
            orientation,
        })
    }
}

/// The elements of a repeated message field.
fn messages<'v>(
    list: &'v Value,
    field: &FieldDescriptor,
) -> Result<impl Iterator<Item = &'v DynamicMessage>, String> {
    let items = list.as_list().ok_or_else(|| not_a("list", field))?;
    if items.iter().any(|v| v.as_message().is_none()) {
        return Err(not_a("list of messages", field));
    }
    Ok(items.iter().filter_map(Value::as_message))
}

/// The kinds of scalar fields dmpscope reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    /// `double` or `float`.
    Float,
    /// Any integer type.
    Integer,
    /// `string`.
    String,
}

/// A message field (repeated or not, as asked) and its message type.
fn message_field(
    message: &MessageDescriptor,
    name: &str,
    list: bool,
) -> Result<(FieldDescriptor, MessageDescriptor), String> {
    let field = find_field(message, name)?;
    match field.kind() {
        Kind::Message(inner) if field.is_list() == list && !field.is_map() => Ok((field, inner)),
        _ => Err(format!(
            "field {} is {}, expected {}a message",
            field.full_name(),
            describe_kind(&field),
            if list { "a repeated field of " } else { "" }
        )),
    }
}

/// A singular scalar field of the given kind.
fn scalar_field(
    message: &MessageDescriptor,
    name: &str,
    scalar: Scalar,
) -> Result<FieldDescriptor, String> {
    let field = find_field(message, name)?;
    let fits = match field.kind() {
        Kind::Double | Kind::Float => scalar == Scalar::Float,
        Kind::Int32
        | Kind::Int64
        | Kind::Uint32
        | Kind::Uint64
        | Kind::Sint32
        | Kind::Sint64
        | Kind::Fixed32
        | Kind::Fixed64
        | Kind::Sfixed32
        | Kind::Sfixed64 => scalar == Scalar::Integer,
        Kind::String => scalar == Scalar::String,
        _ => false,
    };
    if fits && !field.is_list() && !field.is_map() {
        Ok(field)
    } else {
        let expected = match scalar {
            Scalar::Float => "a double",
            Scalar::Integer => "an integer",
            Scalar::String => "a string",
        };
        Err(format!(
            "field {} is {}, expected {expected}",
            field.full_name(),
            describe_kind(&field)
        ))
    }
}

fn find_field(message: &MessageDescriptor, name: &str) -> Result<FieldDescriptor, String> {
    message
        .get_field_by_name(name)
        .ok_or_else(|| format!("message {} has no field {name}", message.full_name()))
}

/// A field's type in words, for errors.
fn describe_kind(field: &FieldDescriptor) -> String {
    let kind = match field.kind() {
        Kind::Message(m) => m.full_name().to_owned(),
        Kind::Enum(e) => e.full_name().to_owned(),
        other => format!("{other:?}").to_lowercase(),
    };
    if field.is_map() {
        format!("a map ({kind})")
    } else if field.is_list() {
        format!("repeated {kind}")
    } else {
        kind
    }
}

fn not_a(what: &str, field: &FieldDescriptor) -> String {
    format!("field {} is not a {what}", field.full_name())
}

fn float(value: &Value, field: &FieldDescriptor) -> Result<f64, String> {
    match value {
        Value::F64(v) => Ok(*v),
        Value::F32(v) => Ok(f64::from(*v)),
        _ => Err(not_a("number", field)),
    }
}

fn integer(value: &Value, field: &FieldDescriptor) -> Result<i64, String> {
    match value {
        Value::I64(v) => Ok(*v),
        Value::I32(v) => Ok(i64::from(*v)),
        Value::U32(v) => Ok(i64::from(*v)),
        Value::U64(v) => i64::try_from(*v)
            .map_err(|_| format!("field {} is out of range: {v}", field.full_name())),
        _ => Err(not_a("integer", field)),
    }
}
