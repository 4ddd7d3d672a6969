//! Length units of a recording (method.md section 1): positions are read
//! in metres unless the user says the file holds centimetres or millimetres
//! (motion-capture exports often do). The factor is applied at loading, so
//! every later number (d, a_peak, gains' effects, exports) is in metres; a
//! demo whose size says the guess is wrong gets a warning naming it.

use serde::{Deserialize, Serialize};

use crate::load::demo::RawDemo;
use crate::notice::Notice;

/// A demo whose bounding box has a larger diagonal than this, in metres
/// after the units are applied, is suspiciously large for a hand motion.
pub const SUSPECT_EXTENT_M: f64 = 5.0;

/// A demo with a position farther than this from the origin, in metres, is
/// suspicious too (a tracker's workspace is a few metres).
pub const SUSPECT_DISTANCE_M: f64 = 100.0;

/// The length unit of a recording's positions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// Metres (ROS, Foxglove): used as read.
    #[default]
    M,
    /// Centimetres.
    Cm,
    /// Millimetres (many motion-capture exports).
    Mm,
}

impl Units {
    /// Every unit, in the order a selector offers them.
    pub const ALL: [Self; 3] = [Self::M, Self::Cm, Self::Mm];

    /// Metres per unit.
    pub fn metres(self) -> f64 {
        match self {
            Self::M => 1.0,
            Self::Cm => 0.01,
            Self::Mm => 0.001,
        }
    }

    /// The unit's symbol (`m`, `cm`, `mm`), as on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::M => "m",
            Self::Cm => "cm",
            Self::Mm => "mm",
        }
    }

    /// Converts a demo's positions to metres (metres themselves are left
    /// untouched, bit for bit).
    pub fn apply(self, demo: &mut RawDemo) {
        if self == Self::M {
            return;
        }
        let f = self.metres();
        for p in &mut demo.positions {
            *p *= f;
        }
    }
}

/// A warning for a demo (in metres) whose size suggests another unit, else
/// `None`.
pub fn suspect(demo: &RawDemo, units: Units) -> Option<Notice> {
    let extent = demo.extent_m();
    let far = demo.positions.iter().map(|p| p.norm()).fold(0.0, f64::max);
    if extent <= SUSPECT_EXTENT_M && far <= SUSPECT_DISTANCE_M {
        return None;
    }
    let what = if extent > SUSPECT_EXTENT_M {
        format!("its positions span {extent:.1} m")
    } else {
        format!("its positions lie {far:.0} m from the origin")
    };
    let hint = match units {
        Units::M => {
            "millimetres read as metres? --units mm (the app's Loading: units) reads them as millimetres"
        }
        Units::Cm => "millimetres read as centimetres? --units mm",
        Units::Mm => "far for a hand motion even in millimetres: check the file's units",
    };
    Some(Notice::warning(format!(
        "{}: {}: {what} (read in {}): {hint}",
        demo.file,
        demo.topic,
        units.name()
    )))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::demo::TimeSource;

    fn demo(scale: f64) -> RawDemo {
        RawDemo {
            name: "m.csv".into(),
            file: "m.csv".into(),
            topic: "csv".into(),
            stamps_ns: vec![0, 10_000_000, 20_000_000],
            positions: vec![
                [193.184 * scale, -402.32 * scale, -168.017 * scale].into(),
                [293.0 * scale, -302.0 * scale, -100.0 * scale].into(),
                [593.0 * scale, -102.0 * scale, 0.0].into(),
            ],
            orientations: None,
            time_source: TimeSource::HeaderStamp,
        }
    }

    #[test]
    fn millimetres_read_as_metres_are_flagged_and_converted_are_not() {
        let mut d = demo(1.0);
        let warning = suspect(&d, Units::M).expect("a 400 m reach is suspect");
        assert!(warning.text.contains("--units mm") && warning.text.contains("m.csv: csv"));
        Units::Mm.apply(&mut d);
        assert!(suspect(&d, Units::Mm).is_none());
        assert!((d.positions[0][0] - 0.193184).abs() < 1e-15);
        // Metres stay bit for bit.
        let mut m = demo(0.001);
        let before = m.positions.clone();
        Units::M.apply(&mut m);
        assert_eq!(m.positions, before);
    }
}
