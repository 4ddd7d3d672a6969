//! The table of the landscape's per-point quantities: each is declared
//! once here (its name, unit, default colour scale and the names it is
//! exported under), and the kernel's point values, the landscape's grids,
//! the tiles, the heat maps, the exports and the CLI's JSON read this
//! table. Adding a quantity touches the kernel (`Model::evaluate_lanes`)
//! and this file.
//!
//! J is not here: it is recombined from S and sum d for any k
//! ([`crate::landscape::grid::Landscape::j`]), never stored.

use serde::Serialize;

/// A quantity the landscape keeps at every grid point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum Quantity {
    /// sum over demos of d (method.md section 4), metres.
    DSum,
    /// The cross-demo similarity S (method.md section 5).
    S,
    /// The largest a_peak of any demo, m/s^2 of the unit-time motion.
    APeak,
    /// The skill error E (method.md section 11), metres.
    ESum,
    /// sum over demos of d_rot (method.md section 12), degrees; NaN when no
    /// demo has an orientation.
    DRotSum,
}

/// How many quantities there are (the length of a point's values).
pub const COUNT: usize = 5;

/// Every quantity, in the order of a point's values.
pub const ALL: [Quantity; COUNT] = [
    Quantity::DSum,
    Quantity::S,
    Quantity::APeak,
    Quantity::ESum,
    Quantity::DRotSum,
];

/// A point's values, one per quantity in [`ALL`]'s order.
pub type PointValues = [f64; COUNT];

/// What the views and exports need to know of a quantity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct About {
    /// Its short name in read-outs and menus (`sum d`).
    pub label: &'static str,
    /// Its map's title, with the unit (`sum d [m]`).
    pub title: &'static str,
    /// Its part of an exported file's name (`sum-d`).
    pub file: &'static str,
    /// Its name in JSON and file names (`d_sum`).
    pub key: &'static str,
    /// Its unit, as printed (`m`; empty: none).
    pub unit: &'static str,
    /// Whether its map is coloured on a log scale by default.
    pub log_colour: bool,
    /// One line on what it is.
    pub about: &'static str,
}

impl Quantity {
    /// Its position in a point's values.
    pub fn index(self) -> usize {
        self as usize
    }

    /// Its name, unit, colour scale and export names.
    pub fn about(self) -> About {
        match self {
            Self::DSum => About {
                label: "sum d",
                title: "sum d [m]",
                file: "sum-d",
                key: "d_sum",
                unit: "m",
                log_colour: true,
                about: "the demos' regeneration error, summed",
            },
            Self::S => About {
                label: "S",
                title: "S",
                file: "S",
                key: "s",
                unit: "",
                log_colour: true,
                about: "the cross-demo similarity of the standardised forcing terms",
            },
            Self::APeak => About {
                label: "a_peak",
                title: "max a_peak [m/s²]",
                file: "a-peak",
                key: "a_peak",
                unit: "m/s^2",
                log_colour: true,
                about: "the largest peak acceleration of any demo (unit time)",
            },
            Self::ESum => About {
                label: "E",
                title: "E [m]",
                file: "E",
                key: "e_sum",
                unit: "m",
                log_colour: true,
                about: "the one skill's error regenerating every demo at its own start and goal",
            },
            Self::DRotSum => About {
                label: "d_rot",
                title: "sum d_rot [deg]",
                file: "sum-d-rot",
                key: "d_rot_sum",
                unit: "deg",
                log_colour: true,
                about: "the demos' orientation error (angle to the demo), summed, in degrees",
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_in_the_order_of_a_points_values_and_keys_are_unique() {
        for (i, q) in ALL.iter().enumerate() {
            assert_eq!(q.index(), i);
            let same_key = ALL
                .iter()
                .filter(|o| o.about().key == q.about().key)
                .count();
            assert_eq!(same_key, 1, "{q:?}");
        }
    }
}
