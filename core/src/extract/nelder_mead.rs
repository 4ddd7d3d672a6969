//! A two-dimensional Nelder-Mead simplex search with the stopping rule of
//! method.md section 6: stop when the simplex spans less than a tolerance.
//!
//! Written here rather than taken from `argmin` because argmin 0.11's
//! `NelderMead` stops only on the spread of the cost values and keeps its
//! simplex private, so the contract's rule cannot be expressed with it.

/// The outcome of a search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Minimum {
    /// The best point.
    pub x: [f64; 2],
    /// The cost there.
    pub cost: f64,
    /// Iterations taken.
    pub iterations: usize,
    /// Whether the span criterion was met (else the iteration cap was hit).
    pub converged: bool,
}

/// Minimises `cost` from the simplex `start` (three points), mapping every
/// point through `project` (e.g. clipping into a box) before it is kept or
/// evaluated. Standard coefficients: reflection 1, expansion 2, contraction
/// 1/2, shrink 1/2. Stops when every vertex lies within `span` of the best
/// in each coordinate, or after `max_iter` iterations.
pub fn minimise(
    mut cost: impl FnMut([f64; 2]) -> f64,
    project: impl Fn([f64; 2]) -> [f64; 2],
    start: [[f64; 2]; 3],
    span: f64,
    max_iter: usize,
) -> Minimum {
    let mut eval = |p: [f64; 2]| {
        let p = project(p);
        let c = cost(p);
        // A NaN cost ranks last, so the search never moves towards it.
        (p, if c.is_nan() { f64::INFINITY } else { c })
    };
    let mut simplex: Vec<([f64; 2], f64)> = start.iter().map(|&p| eval(p)).collect();
    let lerp =
        |a: [f64; 2], b: [f64; 2], t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
    let mut iterations = 0;
    let mut converged = false;
    while iterations < max_iter {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let best = simplex[0].0;
        let spread = simplex[1..]
            .iter()
            .flat_map(|(p, _)| [(p[0] - best[0]).abs(), (p[1] - best[1]).abs()])
            .fold(0.0, f64::max);
        if spread < span {
            converged = true;
            break;
        }
        iterations += 1;
        let centroid = lerp(simplex[0].0, simplex[1].0, 0.5);
        let (worst, worst_cost) = simplex[2];
        let reflected = eval(lerp(centroid, worst, -1.0));
        if reflected.1 < simplex[0].1 {
            let expanded = eval(lerp(centroid, worst, -2.0));
            simplex[2] = if expanded.1 < reflected.1 {
                expanded
            } else {
                reflected
            };
            continue;
        }
        if reflected.1 < simplex[1].1 {
            simplex[2] = reflected;
            continue;
        }
        let contracted = if reflected.1 < worst_cost {
            eval(lerp(centroid, reflected.0, 0.5))
        } else {
            eval(lerp(centroid, worst, 0.5))
        };
        if contracted.1 < reflected.1.min(worst_cost) {
            simplex[2] = contracted;
            continue;
        }
        for v in 1..3 {
            simplex[v] = eval(lerp(best, simplex[v].0, 0.5));
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    Minimum {
        x: simplex[0].0,
        cost: simplex[0].1,
        iterations,
        converged,
    }
}
