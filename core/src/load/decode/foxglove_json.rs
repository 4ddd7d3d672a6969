//! Foxglove pose schemas in JSON (message encoding `json`). The channel's
//! JSON Schema is not needed and not checked: fields are read by name as
//! Foxglove writes them (times as `{"sec": .., "nsec": ..}`), a missing or
//! `null` field counts as its zero value as in protobuf, and a field of the
//! wrong JSON type is an error naming its path. The writing side (JSON
//! Schemas and message encoders) is [`crate::export::foxglove_json`].

use std::borrow::Cow;

use serde_json::{Map, Value};

use crate::load::decode::foxglove_schemas::FoxgloveSchema;
use crate::load::decode::foxglove_schemas::stamp_ns;
use crate::load::decode::{ChannelSchema, MessageDecoder, PoseSample};

/// A JSON object.
type Object = Map<String, Value>;

/// The decoder of a JSON channel: `None` unless its schema is one of the
/// Foxglove pose schemas (the schema's encoding and data are not used).
pub fn decoder(channel: &ChannelSchema<'_>) -> Option<Result<Box<dyn MessageDecoder>, String>> {
    let schema = FoxgloveSchema::from_name(channel.schema_name)?;
    Some(Ok(Box::new(JsonDecoder {
        schema,
        index_keys: Vec::new(),
    })))
}

struct JsonDecoder {
    schema: FoxgloveSchema,
    /// "0", "1", ...: the keys of pose-array indices, made once.
    index_keys: Vec<String>,
}

impl MessageDecoder for JsonDecoder {
    fn decode(&mut self, data: &[u8], out: &mut dyn FnMut(PoseSample<'_>)) -> Result<(), String> {
        let name = self.schema.name();
        let value: Value =
            serde_json::from_slice(data).map_err(|e| format!("not valid JSON for {name}: {e}"))?;
        let root = value
            .as_object()
            .ok_or_else(|| format!("a {name} message must be a JSON object"))?;
        match self.schema {
            FoxgloveSchema::PoseInFrame => {
                let stamp_ns = stamp(root, "")?;
                let pose = object(Some(root), "pose", "")?;
                out(PoseSample {
                    key: None,
                    stamp_ns,
                    position: vector(pose, "position", "pose.")?,
                    orientation: quaternion(pose, "orientation", "pose.")?,
                    ..PoseSample::default()
                });
            }
            FoxgloveSchema::PosesInFrame => {
                let stamp_ns = stamp(root, "")?;
                let poses = objects(root, "poses")?
                    .enumerate()
                    .map(|(i, pose)| {
                        let (pose, path) = (Some(pose?), format!("poses[{i}]."));
                        Ok((
                            vector(pose, "position", &path)?,
                            quaternion(pose, "orientation", &path)?,
                        ))
                    })
                    .collect::<Result<Vec<_>, String>>()?;
                while self.index_keys.len() < poses.len() {
                    self.index_keys.push(self.index_keys.len().to_string());
                }
                for (key, (position, orientation)) in self.index_keys.iter().zip(poses) {
                    out(PoseSample {
                        key: Some(Cow::Borrowed(key)),
                        stamp_ns,
                        position,
                        orientation,
                        ..PoseSample::default()
                    });
                }
            }
            FoxgloveSchema::FrameTransform => out(transform(root, "")?),
            FoxgloveSchema::FrameTransforms => {
                let samples = objects(root, "transforms")?
                    .enumerate()
                    .map(|(i, t)| transform(t?, &format!("transforms[{i}].")))
                    .collect::<Result<Vec<_>, String>>()?;
                samples.into_iter().for_each(out);
            }
        }
        Ok(())
    }
}

/// The pose of a `foxglove.FrameTransform`: keyed by its child frame, at
/// its translation; `path` prefixes its fields in errors (`transforms[2].`).
fn transform<'v>(t: &'v Object, path: &str) -> Result<PoseSample<'v>, String> {
    let child = match field(t, "child_frame_id") {
        None => "",
        Some(Value::String(s)) => s.as_str(),
        Some(_) => return Err(format!("{path}child_frame_id is not a string")),
    };
    let parent = match field(t, "parent_frame_id") {
        None => "",
        Some(Value::String(s)) => s.as_str(),
        Some(_) => return Err(format!("{path}parent_frame_id is not a string")),
    };
    Ok(PoseSample {
        key: Some(Cow::Borrowed(child)),
        stamp_ns: stamp(t, path)?,
        position: vector(Some(t), "translation", path)?,
        parent: Some(Cow::Borrowed(parent)),
        // An unset rotation is the identity, as TF takes it.
        orientation: Some(quaternion(Some(t), "rotation", path)?.unwrap_or([0.0, 0.0, 0.0, 1.0])),
    })
}

/// A field, `None` when missing or `null`.
fn field<'v>(obj: &'v Object, name: &str) -> Option<&'v Value> {
    obj.get(name).filter(|v| !v.is_null())
}

/// An object field, `None` when missing (or the parent is).
fn object<'v>(
    obj: Option<&'v Object>,
    name: &str,
    path: &str,
) -> Result<Option<&'v Object>, String> {
    match obj.and_then(|o| field(o, name)) {
        None => Ok(None),
        Some(Value::Object(inner)) => Ok(Some(inner)),
        Some(_) => Err(format!("{path}{name} is not an object")),
    }
}

/// The objects of an array field (empty when missing); an element that is
/// not an object is an `Err` item naming its index.
fn objects<'v>(
    obj: &'v Object,
    name: &'v str,
) -> Result<impl Iterator<Item = Result<&'v Object, String>>, String> {
    let items: &[Value] = match field(obj, name) {
        None => &[],
        Some(Value::Array(items)) => items,
        Some(_) => return Err(format!("{name} is not an array")),
    };
    Ok(items.iter().enumerate().map(move |(i, item)| {
        item.as_object()
            .ok_or_else(|| format!("{name}[{i}] is not an object"))
    }))
}

/// The `x`, `y`, `z` of a Vector3 field; missing parts are zero.
fn vector(obj: Option<&Object>, name: &str, path: &str) -> Result<[f64; 3], String> {
    parts(object(obj, name, path)?, ["x", "y", "z"], name, path)
}

/// The `x`, `y`, `z`, `w` of a Quaternion field, as stored (missing parts
/// are zero); `None` when the field itself is missing: no orientation.
fn quaternion(obj: Option<&Object>, name: &str, path: &str) -> Result<Option<[f64; 4]>, String> {
    match object(obj, name, path)? {
        None => Ok(None),
        Some(q) => parts(Some(q), ["x", "y", "z", "w"], name, path).map(Some),
    }
}

/// Named number fields of an object; missing ones are zero.
fn parts<const N: usize>(
    v: Option<&Object>,
    names: [&str; N],
    name: &str,
    path: &str,
) -> Result<[f64; N], String> {
    let mut p = [0.0; N];
    for (value, part) in p.iter_mut().zip(names) {
        *value = match v.and_then(|v| field(v, part)) {
            None => 0.0,
            Some(Value::Number(n)) => n
                .as_f64()
                .ok_or_else(|| format!("{path}{name}.{part} is not a finite number"))?,
            Some(_) => return Err(format!("{path}{name}.{part} is not a number")),
        };
    }
    Ok(p)
}

/// The `timestamp` field in nanoseconds, `None` when missing or zero.
fn stamp(obj: &Object, path: &str) -> Result<Option<i64>, String> {
    let Some(time) = object(Some(obj), "timestamp", path)? else {
        return Ok(None);
    };
    let sec = integer(time, "sec", path)?;
    let nsec = integer(time, "nsec", path)?;
    stamp_ns(sec, nsec)
}

/// An integer part of the timestamp (0 when missing); a number with a
/// fraction or beyond `i64` is an error.
fn integer(time: &Object, name: &str, path: &str) -> Result<i64, String> {
    let Some(value) = field(time, name) else {
        return Ok(0);
    };
    let bad = || format!("{path}timestamp.{name} is not an integer in range: {value}");
    let Value::Number(n) = value else {
        return Err(bad());
    };
    if let Some(v) = n.as_i64() {
        return Ok(v);
    }
    match n.as_f64() {
        // 2^63 is exact in f64; everything strictly inside fits an i64.
        Some(v) if v.fract() == 0.0 && v.abs() < 9_223_372_036_854_775_808.0 => Ok(v as i64),
        _ => Err(bad()),
    }
}
