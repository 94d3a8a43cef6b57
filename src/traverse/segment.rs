//! Cutting a ray's segment before its walk: from where a clearance proves it clear, up to
//! where an occlusion ray stops looking, and the level the walk starts at.

use super::frame::Frame;
use super::options::{Query, WalkOptions};
use super::wedges::Clearance;
use crate::arith::Scalar;

/// Where the hierarchical walk starts when the ray is known clear of the surface up to some
/// `t` ([`WalkOptions::clearance`]): `t` moved down by more than the rounding to `S` (the walk
/// may start early, never late), and the level. The other methods walk the whole segment:
/// they are what the hierarchy is measured against.
pub(super) fn clearance_start<S: Scalar>(options: &WalkOptions) -> Option<(f64, u32)> {
    let Clearance { t, level } = options.clearance.filter(|c| c.t > 0.0)?;
    (options.method.is_hierarchical()).then(|| (t - 4.0 * S::rounding_error(t), level))
}

/// The level a hierarchical walk starts at where it knows better than the default: a shadow
/// ray starts on the surface, where every block around it fails its test; a camera ray at
/// the level its clearance names.
pub(super) fn first_level(options: &WalkOptions, start: Option<(f64, u32)>) -> Option<u32> {
    match start {
        _ if options.query == Query::Shadow => Some(0),
        Some((_, level)) => Some(level),
        None => None,
    }
}

/// Cuts the segment at [`WalkOptions::reach`] (keeps all of it without one), ended at exactly
/// that `t` in the walk's arithmetic; `false` if the segment starts beyond it.
pub(super) fn within_reach<S: Scalar>(frame: &mut Frame<S>, options: &WalkOptions) -> bool {
    match options.reach {
        Some(to) => frame.keep(f64::NEG_INFINITY, to),
        None => true,
    }
}

/// Cuts the segment at [`clearance_start`]'s `t` (keeps all of it without a clearance);
/// `false` if the clearance covers it all.
pub(super) fn after_clearance<S: Scalar>(frame: &mut Frame<S>, start: Option<(f64, u32)>) -> bool {
    match start {
        Some((from, _)) => frame.keep(from, f64::INFINITY),
        None => true,
    }
}
