//! Demos as people record them (method.md section 13): a demo whose end is
//! near its start after going far (a loop, or a reach and return with no
//! rest at the far end) is said, because a DMP's forcing term scales with
//! `goal - start`, nearly zero then; `--cut farthest` keeps each demo from
//! its start to its farthest point from the start, the reach.

use crate::load::demo::RawDemo;
use crate::notice::Notice;

/// A demo ends within this share of its farthest distance from its start
/// (method.md section 13): a loop.
pub const LOOP_SHARE: f64 = 0.2;

/// A demo whose end is this close to its farthest distance (as a share of
/// it) already ends at its farthest point: `--cut farthest` leaves it, so
/// that tracker noise near a goal the hand rested at cuts nothing.
pub const ENDS_FARTHEST: f64 = 0.98;

/// Its start-to-end distance and its farthest distance from its start, in
/// time order, metres.
fn reach(demo: &RawDemo) -> Option<(f64, f64, usize)> {
    let sorted = demo.sorted();
    let start = *sorted.positions.first()?;
    let end = *sorted.positions.last()?;
    let (far_at, far) = sorted
        .positions
        .iter()
        .map(|p| (p - start).norm())
        .enumerate()
        .fold(
            (0, 0.0f64),
            |best, (i, d)| if d > best.1 { (i, d) } else { best },
        );
    Some(((end - start).norm(), far, far_at))
}

/// The notice for a demo that ends near where it started after going far:
/// what that does to a DMP and what to do.
pub fn loop_notice(demo: &RawDemo, min_extent_m: f64) -> Option<Notice> {
    let (ends, far, _) = reach(demo)?;
    if far < min_extent_m || ends >= LOOP_SHARE * far {
        return None;
    }
    Some(Notice::warning(format!(
        "{}: {}: ends {:.1} cm from its start after going {:.1} cm away (a loop, or a reach and \
         return without a rest at its far end): a DMP scales its forcing term with goal - start, \
         {:.0} % of the motion here, so it regenerates it poorly and generalises it worse; \
         --cut farthest (the app's Loading: cut each demo at its farthest point) keeps the reach, \
         or --demos segment --segments out the reaches of a take that rests at both ends",
        demo.file,
        demo.name,
        ends * 100.0,
        far * 100.0,
        100.0 * ends / far
    )))
}

/// The demo from its start to its farthest point from its start, and what
/// was cut; `None` when it already ends at its farthest point (within
/// [`ENDS_FARTHEST`]: nothing to cut).
pub fn cut_farthest(demo: &RawDemo) -> Option<(RawDemo, Notice)> {
    let sorted = demo.sorted();
    let (ends, far, far_at) = reach(&sorted)?;
    if far_at + 1 >= sorted.positions.len() || far_at < 1 || ends >= ENDS_FARTHEST * far {
        return None;
    }
    let kept = sorted.part(0..far_at + 1, demo.name.clone(), demo.topic.clone());
    let notice = Notice::info(format!(
        "{}: {}: cut at its farthest point from its start ({:.1} cm away): kept {:.2} s of {:.2} s \
         (--cut farthest)",
        demo.file,
        demo.name,
        far * 100.0,
        kept.duration_s(),
        sorted.duration_s()
    ));
    Some((kept, notice))
}
