//! How much of a demo's smoothed acceleration is noise (method.md section
//! 2, "Noise"). The position noise `sigma` of each axis is estimated from
//! the fourth differences of the uniformly resampled positions (which a
//! smooth motion sampled densely leaves near zero, and white noise of
//! variance `sigma^2` gives variance `70 sigma^2`), robustly:
//! `sigma = MAD(diff4) / 0.6745 / sqrt(70)`. White noise through the
//! Savitzky-Golay second-derivative kernel `h` leaves an acceleration noise
//! of RMS `sigma * |h| / spacing^2`; the share is that noise's RMS over the
//! smoothed acceleration's RMS, over the three axes. Above
//! [`NOISE_DOMINATES`] the demo is named with the `--sg-seconds` value
//! whose window brings it below.

use crate::error::Result;
use crate::prepare::savgol::{MAX_SG_WINDOW, SavGol};

/// The share above which noise dominates a demo's acceleration: its noise
/// is more than half its RMS.
pub const NOISE_DOMINATES: f64 = 0.5;

/// A suggested window aims this far below [`NOISE_DOMINATES`], so that the
/// window a duration rounds to at each demo's rate still clears it.
const MARGIN: f64 = 0.8;

/// The white-noise standard deviation of one uniformly sampled signal,
/// from the median absolute fourth difference (0 for fewer than 5 samples).
pub fn white_noise_sigma(signal: &[f64]) -> f64 {
    let mut d4: Vec<f64> = signal
        .windows(5)
        .map(|w| (w[0] - 4.0 * w[1] + 6.0 * w[2] - 4.0 * w[3] + w[4]).abs())
        .collect();
    if d4.is_empty() {
        return 0.0;
    }
    let mid = d4.len() / 2;
    let (_, median, _) = d4.select_nth_unstable_by(mid, f64::total_cmp);
    *median / 0.6745 / 70f64.sqrt()
}

/// The noise share at `window` samples: the predicted acceleration noise's
/// RMS over the smoothed acceleration's, `None` where the window does not
/// fit the samples.
fn share_at(
    columns: &[Vec<f64>; 3],
    sigma2: f64,
    window: usize,
    order: usize,
    spacing: f64,
) -> Result<Option<f64>> {
    if window > columns[0].len() {
        return Ok(None);
    }
    let sg = SavGol::new(window, order)?;
    let gain2: f64 = sg.centre_kernel(2).iter().map(|c| c * c).sum();
    let noise2 = sigma2 * gain2 / spacing.powi(4);
    // Both as the 3-vector's mean square: summed over the axes.
    let mut total = 0.0;
    for col in columns {
        let a = sg.apply(col, spacing)?.d2;
        total += a.iter().map(|v| v * v).sum::<f64>();
    }
    let rms2 = total / columns[0].len().max(1) as f64;
    Ok(Some(if rms2 > 0.0 {
        (noise2 / rms2).sqrt()
    } else {
        0.0
    }))
}

/// The noise share of the acceleration at `window` samples (`None` where
/// the window does not fit), and where it is above [`NOISE_DOMINATES`] the
/// narrowest wider window (samples, growing by a quarter) whose share is
/// below it with a margin (`None`: none up to [`MAX_SG_WINDOW`] fits).
pub fn acc_noise(
    columns: &[Vec<f64>; 3],
    window: usize,
    order: usize,
    spacing: f64,
) -> Result<(Option<f64>, Option<usize>)> {
    let sigma2: f64 = columns.iter().map(|c| white_noise_sigma(c).powi(2)).sum();
    let Some(now) = share_at(columns, sigma2, window, order, spacing)? else {
        return Ok((None, None));
    };
    if now <= NOISE_DOMINATES {
        return Ok((Some(now), None));
    }
    let mut w = window;
    loop {
        w = (w + w / 4 + 1) | 1;
        if w > MAX_SG_WINDOW {
            return Ok((Some(now), None));
        }
        match share_at(columns, sigma2, w, order, spacing)? {
            None => return Ok((Some(now), None)),
            Some(s) if s < NOISE_DOMINATES * MARGIN => return Ok((Some(now), Some(w))),
            Some(_) => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn the_noise_of_white_noise_on_a_smooth_signal_is_found() {
        let mut rng = Rng::new(3);
        let signal: Vec<f64> = (0..5000)
            .map(|k| (k as f64 / 500.0).sin() + 0.001 * rng.normal())
            .collect();
        let sigma = white_noise_sigma(&signal);
        assert!((sigma - 0.001).abs() < 0.0001, "{sigma}");
        let clean: Vec<f64> = (0..5000).map(|k| (k as f64 / 500.0).sin()).collect();
        assert!(white_noise_sigma(&clean) < 1e-9);
    }
}
