//! The trade-off between fidelity and similarity: the Pareto front of
//! `(sum d, S)` over the grid (method.md section 9). J's optimum for any k
//! lies on it, where the line of slope `-k` touches it (J as the paper has
//! it: with `--k-rot` J also weighs the orientation, which this front does
//! not show).

/// The grid points (indices into `d_sum` and `s`) no other point beats in
/// both sum d and S, by increasing sum d (and so decreasing S). Points with
/// a value not finite are ignored; of points equal in both, the first.
pub fn pareto_front(d_sum: &[f64], s: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..d_sum.len().min(s.len()))
        .filter(|&i| d_sum[i].is_finite() && s[i].is_finite())
        .collect();
    order.sort_by(|&a, &b| {
        d_sum[a]
            .total_cmp(&d_sum[b])
            .then(s[a].total_cmp(&s[b]))
            .then(a.cmp(&b))
    });
    let mut front = Vec::new();
    let mut best_s = f64::INFINITY;
    for i in order {
        if s[i] < best_s {
            best_s = s[i];
            front.push(i);
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::pareto_front;

    #[test]
    fn the_front_keeps_only_points_nothing_beats_in_both() {
        //            0    1    2    3    4    5
        let d = [3.0, 1.0, 2.0, 2.0, 4.0, f64::NAN];
        let s = [1.0, 5.0, 2.0, 3.0, 1.0, 0.0];
        // 1 (d 1, S 5), 2 (d 2, S 2), 0 (d 3, S 1); 3 is beaten by 2, 4 by
        // 0, 5 is not finite.
        assert_eq!(pareto_front(&d, &s), vec![1, 2, 0]);
        assert!(pareto_front(&[], &[]).is_empty());
    }

    #[test]
    fn every_minimum_of_a_weighted_sum_is_on_the_front() {
        let n = 50;
        let d: Vec<f64> = (0..n).map(|i| ((i * 37) % 50) as f64 / 7.0).collect();
        let s: Vec<f64> = (0..n).map(|i| ((i * 11) % 50) as f64 / 3.0).collect();
        let front = pareto_front(&d, &s);
        for k in [0.1, 1.0, 10.0] {
            let best = (0..n)
                .min_by(|&a, &b| (s[a] + k * d[a]).total_cmp(&(s[b] + k * d[b])))
                .expect("points");
            let j = s[best] + k * d[best];
            assert!(front.iter().any(|&i| (s[i] + k * d[i]) == j), "k {k}");
        }
    }
}
