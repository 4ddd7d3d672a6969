//! How much of a demo's smoothed acceleration is noise (method.md section
//! 2, "Noise"): the share of the Savitzky-Golay second derivative that a
//! twice-wider window (2w + 1 samples, same order) changes, as the ratio of
//! root-mean-squares over the three axes on the uniform grid,
//! `RMS(a_w - a_2w+1) / RMS(a_w)`. A motion the window already resolves
//! changes little (a few percent); where the window spans less than the
//! noise's correlation the acceleration is mostly noise and the wider
//! window changes most of it. Above [`NOISE_DOMINATES`] the demo is named
//! with the `--sg-seconds` value that brings it below.

use crate::error::Result;
use crate::prepare::savgol::SavGol;

/// The share above which noise dominates a demo's acceleration.
pub const NOISE_DOMINATES: f64 = 0.5;

/// The second derivatives of `columns` (one per axis, uniform spacing)
/// under a window of `window` samples and the given order; `None` where
/// the window does not fit the samples.
fn second(
    columns: &[Vec<f64>; 3],
    window: usize,
    order: usize,
    spacing: f64,
) -> Result<Option<[Vec<f64>; 3]>> {
    if window > columns[0].len() {
        return Ok(None);
    }
    let sg = SavGol::new(window, order)?;
    let mut out: [Vec<f64>; 3] = Default::default();
    for (axis, col) in columns.iter().enumerate() {
        out[axis] = sg.apply(col, spacing)?.d2;
    }
    Ok(Some(out))
}

/// `RMS(a - b) / RMS(a)` over the axes (0 for a zero acceleration).
fn share(a: &[Vec<f64>; 3], b: &[Vec<f64>; 3]) -> f64 {
    let (mut diff, mut total) = (0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        for (u, v) in x.iter().zip(y) {
            diff += (u - v) * (u - v);
            total += u * u;
        }
    }
    if total > 0.0 {
        (diff / total).sqrt()
    } else {
        0.0
    }
}

/// The noise share of the acceleration at `window` samples, and the
/// smallest window (samples, doubling: 2w + 1, 4w + 3, ...) whose share is
/// below [`NOISE_DOMINATES`] where it is above (`None`: it is below, or no
/// wider window fits). `None` for the share where a twice-wider window
/// does not fit the demo.
pub fn acc_noise(
    columns: &[Vec<f64>; 3],
    window: usize,
    order: usize,
    spacing: f64,
) -> Result<(Option<f64>, Option<usize>)> {
    let Some(mut now) = second(columns, window, order, spacing)? else {
        return Ok((None, None));
    };
    let mut w = window;
    let mut first = None;
    for _ in 0..6 {
        let wider = 2 * w + 1;
        if wider > crate::prepare::savgol::MAX_SG_WINDOW {
            return Ok((first, None));
        }
        let Some(next) = second(columns, wider, order, spacing)? else {
            return Ok((first, None));
        };
        let s = share(&now, &next);
        if first.is_none() {
            first = Some(s);
        }
        if s < NOISE_DOMINATES {
            return Ok((first, (w != window).then_some(w)));
        }
        (now, w) = (next, wider);
    }
    Ok((first, None))
}
