//! Which points of a long series a view draws: every `k`-th and the last,
//! at most about `max` of them (a software rasteriser pays for every
//! segment; a few hundred points are smooth at any size a view has). The
//! 3D paths, the time plots and a new target's plots share it, so a
//! series keeps its ends in every view.

/// The indices kept of a series of `len` points: every `k`-th from the
/// first (`k` the least that keeps at most `max`), and the last.
pub fn kept(len: usize, max: usize) -> impl Iterator<Item = usize> {
    let stride = len.div_ceil(max.max(1)).max(1);
    let last = len.checked_sub(1);
    // The last is added where the stride does not land on it.
    let extra = last.filter(|&l| l % stride != 0);
    (0..len).step_by(stride).chain(extra)
}

/// The points kept of `points` (see [`kept`]).
pub fn thinned<T: Copy>(points: &[T], max: usize) -> Vec<T> {
    kept(points.len(), max).map(|k| points[k]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_every_kth_and_the_last_once() {
        assert_eq!(kept(10, 4).collect::<Vec<_>>(), vec![0, 3, 6, 9]);
        assert_eq!(kept(11, 4).collect::<Vec<_>>(), vec![0, 3, 6, 9, 10]);
        assert_eq!(kept(3, 300).collect::<Vec<_>>(), vec![0, 1, 2]);
        assert_eq!(kept(1, 5).collect::<Vec<_>>(), vec![0]);
        assert_eq!(kept(0, 5).count(), 0);
        // At least the ends.
        assert_eq!(kept(5, 0).collect::<Vec<_>>(), vec![0, 4]);
        // At most `max` and the last, more than half of `max`.
        for len in [1001, 1250, 5000] {
            let n = kept(len, 250).count();
            assert!(n > 125 && n <= 251, "{len}: {n}");
        }
        assert_eq!(thinned(&[1.0, 2.0, 3.0], 2), vec![1.0, 3.0]);
    }
}
