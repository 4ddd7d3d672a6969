//! What a stream's orientations say about themselves (method.md section
//! 12): each sample's quaternion counted as it is read (carried, missing,
//! unusable: zero or not finite), and at the end of the file what that
//! means: nothing to say; a stream of zero quaternions (or none at all
//! beside them), a source that sends no rotation; samples without one
//! beside samples with one; else the error naming file, topic and the
//! first unusable sample, or with `drop_bad_orientation` a warning.

use crate::error::{Error, Location, Result};

/// The orientations of one stream, counted as its samples are read.
#[derive(Clone, Debug, Default)]
pub(crate) struct OrientationCounts {
    /// Samples read.
    samples: usize,
    /// Samples whose message carries no orientation.
    missing: usize,
    /// Unusable orientations (zero or not finite), and how many of them
    /// are exactly zero.
    bad: (usize, usize),
    /// The first unusable one: its message's index in the file and value.
    first_bad: Option<(usize, [f64; 4])>,
}

impl OrientationCounts {
    /// Counts a sample (message `index`) whose message carries `given`
    /// (`None`: none), `usable` when it is a unit quaternion's.
    pub(crate) fn record(&mut self, index: usize, given: Option<[f64; 4]>, usable: bool) {
        self.samples += 1;
        match given {
            None => self.missing += 1,
            Some(q) if !usable => {
                self.first_bad.get_or_insert((index, q));
                self.bad.0 += 1;
                self.bad.1 += usize::from(q == [0.0; 4]);
            }
            Some(_) => {}
        }
    }

    /// What the counts mean for the stream `source` of file `label`: a
    /// warning to give, or the error of an unusable quaternion (unless
    /// `drop_bad` keeps the positions without orientation).
    pub(crate) fn verdict(
        &self,
        label: &str,
        source: &str,
        drop_bad: bool,
    ) -> Result<Option<String>> {
        let (n, missing) = (self.samples, self.missing);
        let Some((index, q)) = self.first_bad else {
            return Ok((missing > 0 && missing < n).then(|| {
                format!(
                    "{label}: {source}: {missing} of {n} samples carry no orientation: the \
                     demo has none"
                )
            }));
        };
        let (bad, zero) = self.bad;
        if zero + missing == n {
            return Ok(Some(format!(
                "{label}: {source}: every orientation is the zero quaternion (a source that \
                 sends no rotation): the demo has no orientation"
            )));
        }
        if drop_bad {
            return Ok(Some(format!(
                "{label}: {source}: {bad} of {n} samples have no usable orientation (zero or \
                 not finite, the first at sample {index}: {q:?}): the demo has none \
                 (--drop-bad-orientation)"
            )));
        }
        Err(Error::NonFinite {
            at: Location::file(label).topic(source).sample(index),
            field: if q.iter().all(|c| c.is_finite()) {
                "orientation (a zero quaternion; --drop-bad-orientation loads the positions \
                 without orientation)"
            } else {
                "orientation (--drop-bad-orientation loads the positions without orientation)"
            },
        })
    }
}
