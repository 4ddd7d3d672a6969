//! A landscape filled by tiles computed elsewhere: the browser's workers.
//!
//! [`TiledFill`] cuts the coarse-to-fine visiting order of a grid into
//! tiles, hands them out one at a time and stores the numbers that come
//! back, in whatever order they come. Every fill has a generation; an answer
//! for another generation (a landscape that was replaced or cancelled), for
//! a tile already stored, or of the wrong size is refused, so nothing stale
//! or malformed reaches the view. A tile whose worker died is handed out
//! again. Pure bookkeeping: the pool that moves the messages is
//! [`crate::workers`].

use std::collections::VecDeque;

use dmpscope_core::Result;
use dmpscope_core::landscape::grid::{FillOrder, Grid, Landscape, fill_order};
use dmpscope_core::landscape::quantity;
use dmpscope_core::landscape::quantity::PointValues;

/// What became of an answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    /// Stored.
    Stored,
    /// For another generation: dropped.
    Stale,
    /// Its tile was stored already: dropped.
    Duplicate,
    /// Not a tile of this fill, or values of the wrong length: dropped.
    Malformed,
}

/// A landscape being filled tile by tile from outside.
#[derive(Clone, Debug)]
pub struct TiledFill {
    generation: u64,
    landscape: Landscape,
    tiles: Vec<Vec<(u32, u32)>>,
    next: usize,
    again: VecDeque<usize>,
    stored: Vec<bool>,
}

impl TiledFill {
    /// A fill of `grid` in tiles of at most `tile_points` points, coarse
    /// levels first, for a landscape whose J weighs the orientation error
    /// by `k_rot` (the model's setting).
    pub fn new(grid: Grid, generation: u64, tile_points: usize, k_rot: f64) -> Result<Self> {
        grid.validate()?;
        let order = fill_order(&grid, FillOrder::CoarseToFine);
        let tiles: Vec<Vec<(u32, u32)>> = order
            .chunks(tile_points.max(1))
            .map(<[(u32, u32)]>::to_vec)
            .collect();
        Ok(Self {
            generation,
            landscape: Landscape {
                k_rot,
                ..Landscape::blank(grid)
            },
            stored: vec![false; tiles.len()],
            tiles,
            next: 0,
            again: VecDeque::new(),
        })
    }

    /// The generation answers must carry.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The next tile to compute, `(tile, points)`: tiles handed out again
    /// first, then the next in coarse-to-fine order; `None` when every tile
    /// is out or stored.
    pub fn next_tile(&mut self) -> Option<(usize, &[(u32, u32)])> {
        let tile = match self.again.pop_front() {
            Some(t) => t,
            None if self.next < self.tiles.len() => {
                self.next += 1;
                self.next - 1
            }
            None => return None,
        };
        Some((tile, &self.tiles[tile]))
    }

    /// The points of `tile` while it is not stored (a copy of it for
    /// another worker).
    pub fn tile_points(&self, tile: usize) -> Option<&[(u32, u32)]> {
        (self.stored.get(tile) == Some(&false)).then(|| self.tiles[tile].as_slice())
    }

    /// A tile handed out whose answer will never come (its worker died):
    /// it is handed out again.
    pub fn hand_out_again(&mut self, tile: usize) {
        if self.stored.get(tile) == Some(&false) && !self.again.contains(&tile) {
            self.again.push_back(tile);
        }
    }

    /// Stores the answer for `tile` of `generation`: every quantity of the
    /// table (`dmpscope_core::quantity`) per point, flat.
    pub fn accept(&mut self, generation: u64, tile: usize, values: &[f64]) -> Answer {
        if generation != self.generation {
            return Answer::Stale;
        }
        let Some(points) = self.tiles.get(tile) else {
            return Answer::Malformed;
        };
        if self.stored[tile] {
            return Answer::Duplicate;
        }
        if values.len() != quantity::COUNT * points.len() {
            return Answer::Malformed;
        }
        let points_values: Vec<PointValues> = values
            .chunks_exact(quantity::COUNT)
            .filter_map(|v| v.try_into().ok())
            .collect();
        if self.landscape.store(points, &points_values).is_err() {
            return Answer::Malformed;
        }
        self.stored[tile] = true;
        Answer::Stored
    }

    /// Points stored and in all.
    pub fn progress(&self) -> (usize, usize) {
        (self.landscape.filled, self.landscape.grid.len())
    }

    /// Whether every tile is stored.
    pub fn is_complete(&self) -> bool {
        self.landscape.is_complete()
    }

    /// The landscape so far (NaN where not stored yet).
    pub fn landscape(&self) -> &Landscape {
        &self.landscape
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use dmpscope_core::fit::settings::DmpSettings;
    use dmpscope_core::landscape::grid::{Axis, AxisScale, LandscapeJob};
    use dmpscope_core::{Model, PrepSettings, PreparedDemo, prepare, synth};

    use super::*;

    fn grid() -> Grid {
        let axis = Axis {
            lo: 1.0,
            hi: 1000.0,
            n: 12,
            scale: AxisScale::Log,
        };
        Grid { dm: axis, km: axis }
    }

    fn model() -> Arc<Model> {
        let demos: Vec<PreparedDemo> = synth::vive::reach_raw_demos(3, 3, 0)
            .iter()
            .map(|raw| prepare(raw, &PrepSettings::default()).expect("prepared"))
            .collect();
        Arc::new(Model::new(demos, DmpSettings::default()).expect("model"))
    }

    fn answer(model: &Model, fill: &TiledFill, points: &[(u32, u32)]) -> Vec<f64> {
        fill.landscape()
            .evaluate(model, points)
            .expect("in the grid")
            .concat()
    }

    #[test]
    fn tiles_answered_in_any_order_give_the_landscape_of_one_pass() {
        let model = model();
        let mut fill = TiledFill::new(grid(), 7, 10, 0.0).expect("fill");
        let mut out = Vec::new();
        while let Some((t, points)) = fill.next_tile() {
            out.push((t, points.to_vec()));
        }
        assert_eq!(out.len(), 15, "144 points in tiles of 10");
        // The coarse level comes first: the first tile holds (0, 0) and
        // points on the largest stride.
        assert_eq!(out[0].1[0], (0, 0));
        out.reverse();
        for (t, points) in &out {
            let values = answer(&model, &fill, points);
            assert_eq!(fill.accept(7, *t, &values), Answer::Stored);
        }
        assert!(fill.is_complete());
        let mut job = LandscapeJob::new(model.clone(), grid(), FillOrder::Raster).expect("job");
        while !job.step(16) {}
        let one_pass = job.landscape();
        let tiled = fill.landscape();
        assert_eq!(tiled.filled, one_pass.filled);
        for (a, b) in tiled.values.iter().zip(&one_pass.values) {
            let same = a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
            assert!(same, "the same bits as one pass");
        }
    }

    #[test]
    fn stale_duplicate_and_malformed_answers_never_reach_the_landscape() {
        let model = model();
        let mut fill = TiledFill::new(grid(), 2, 10, 0.0).expect("fill");
        let (t, points) = fill
            .next_tile()
            .map(|(t, p)| (t, p.to_vec()))
            .expect("a tile");
        let values = answer(&model, &fill, &points);
        assert_eq!(fill.accept(1, t, &values), Answer::Stale);
        assert_eq!(
            fill.accept(2, t, &values[..quantity::COUNT]),
            Answer::Malformed
        );
        assert_eq!(fill.accept(2, 99, &values), Answer::Malformed);
        assert_eq!(fill.landscape().filled, 0, "nothing stored yet");
        assert_eq!(fill.accept(2, t, &values), Answer::Stored);
        assert_eq!(fill.accept(2, t, &values), Answer::Duplicate);
        assert_eq!(fill.progress(), (points.len(), 144));
    }

    #[test]
    fn a_tile_whose_worker_died_is_handed_out_again_once() {
        let mut fill = TiledFill::new(grid(), 0, 100, 0.0).expect("fill");
        let (first, _) = fill.next_tile().expect("tile 0");
        let (second, _) = fill.next_tile().expect("tile 1");
        assert!(
            fill.next_tile().is_none(),
            "two tiles of 100 for 144 points"
        );
        fill.hand_out_again(first);
        fill.hand_out_again(first);
        assert_eq!(fill.next_tile().map(|(t, _)| t), Some(first));
        assert!(fill.next_tile().is_none(), "handed out again once");
        assert_ne!(first, second);
    }
}
