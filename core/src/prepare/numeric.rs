//! The small numeric helpers every stage shares, as NumPy computes them
//! (the golden tests compare with NumPy to the last bits): evenly spaced
//! points, linear interpolation and the trapezoid sum.

/// `n` points from 0 to `stop` as NumPy's `linspace` makes them
/// (`i * step`, the last point exactly `stop`).
pub fn linspace(stop: f64, n: usize) -> Vec<f64> {
    let step = stop / (n - 1) as f64;
    let mut v: Vec<f64> = (0..n).map(|i| i as f64 * step).collect();
    if let Some(last) = v.last_mut() {
        *last = stop;
    }
    v
}

/// Linear interpolation as NumPy's `interp`: `xp` increasing, `x` inside
/// `[xp[0], xp[last]]` (clamped outside).
pub fn interp(x: &[f64], xp: &[f64], fp: &[f64]) -> Vec<f64> {
    let last = xp.len() - 1;
    x.iter()
        .map(|&xv| {
            if xv <= xp[0] {
                return fp[0];
            }
            if xv >= xp[last] {
                return fp[last];
            }
            // xp[j] <= xv < xp[j + 1]
            let j = xp.partition_point(|&p| p <= xv) - 1;
            if xp[j] == xv {
                return fp[j];
            }
            let slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j]);
            slope * (xv - xp[j]) + fp[j]
        })
        .collect()
}

/// The trapezoid sum `sum_k w_k v_k` with `w = 1/2` at both ends, for unit spacing.
pub fn trapezoid(values: impl Iterator<Item = f64>, n: usize) -> f64 {
    let mut total = 0.0;
    for (k, v) in values.enumerate() {
        total += if k == 0 || k + 1 == n { 0.5 * v } else { v };
    }
    total
}
