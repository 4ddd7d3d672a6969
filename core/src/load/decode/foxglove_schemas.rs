//! The Foxglove pose schemas dmpscope reads: their names and what each
//! message holds, and Foxglove's time stamps. The decoders are
//! [`crate::load::decode::foxglove_proto`] and
//! [`crate::load::decode::foxglove_json`]; the writing side is
//! [`crate::export::foxglove`].

/// A Foxglove schema that holds positions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FoxgloveSchema {
    /// `foxglove.PoseInFrame`: one pose per message.
    PoseInFrame,
    /// `foxglove.PosesInFrame`: a pose array, one demo per index.
    PosesInFrame,
    /// `foxglove.FrameTransform`: one transform, one demo per child frame.
    FrameTransform,
    /// `foxglove.FrameTransforms`: transforms, one demo per child frame.
    FrameTransforms,
}

impl FoxgloveSchema {
    /// Every schema.
    pub const ALL: [Self; 4] = [
        Self::PoseInFrame,
        Self::PosesInFrame,
        Self::FrameTransform,
        Self::FrameTransforms,
    ];

    /// The schema of an MCAP schema name, `None` for any other name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The MCAP schema name (the protobuf message's full name).
    pub fn name(self) -> &'static str {
        match self {
            Self::PoseInFrame => "foxglove.PoseInFrame",
            Self::PosesInFrame => "foxglove.PosesInFrame",
            Self::FrameTransform => "foxglove.FrameTransform",
            Self::FrameTransforms => "foxglove.FrameTransforms",
        }
    }
}
/// `seconds` and `nanos` of a stamp in nanoseconds (nanos in `0..1e9`).
pub fn split_stamp(stamp_ns: i64) -> (i64, i64) {
    (
        stamp_ns.div_euclid(1_000_000_000),
        stamp_ns.rem_euclid(1_000_000_000),
    )
}

/// A Foxglove time to nanoseconds: `None` for the zero time ("no stamp"),
/// an `Err` when it does not fit an `i64` of nanoseconds.
pub(crate) fn stamp_ns(seconds: i64, nanos: i64) -> Result<Option<i64>, String> {
    if seconds == 0 && nanos == 0 {
        return Ok(None);
    }
    seconds
        .checked_mul(1_000_000_000)
        .and_then(|s| s.checked_add(nanos))
        .map(Some)
        .ok_or_else(|| format!("timestamp {seconds} s + {nanos} ns is out of range"))
}
