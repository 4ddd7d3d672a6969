//! A training run's stability figure (issue 14): the learning curve (mean
//! return per iteration) cut into ten consecutive parts; a run **diverged**
//! when its last tenth's mean return is more than 10 % below its best
//! tenth's (relative to the best's magnitude).

/// Parts the learning curve is cut into.
pub const PARTS: usize = 10;
/// How far below the best part the last may fall, as a fraction.
pub const DIVERGED_DROP: f64 = 0.10;

/// The best and the last of the curve's tenths' mean returns (`None` for
/// an empty curve; with fewer than ten iterations, each is a part).
pub fn tenths(returns: &[f64]) -> Option<(f64, f64)> {
    if returns.is_empty() {
        return None;
    }
    let size = returns.len().div_ceil(PARTS);
    let means: Vec<f64> = returns
        .chunks(size)
        .map(|c| c.iter().sum::<f64>() / c.len() as f64)
        .collect();
    let best = means.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Some((best, *means.last()?))
}

/// Whether the run diverged (see the module's note); an empty curve has not.
pub fn diverged(returns: &[f64]) -> bool {
    tenths(returns).is_some_and(|(best, last)| best - last > DIVERGED_DROP * best.abs())
}
