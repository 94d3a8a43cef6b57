//! The short walk of a first-hit ray from its clearance (a camera ray's, from its wedge): the
//! cells just past where it may first touch the surface, one by one, without the frame and
//! search record the full walk sets up.
//!
//! Why the answer is the full walk's: the segment is clipped by the same
//! [`clip_to_box`] and starts at the same `t`, so every number compared is the one the full
//! walk compares. The path's cells come in the order the full walk reaches them, and within
//! a cell triangle 0 before triangle 1, and a hit is kept only where it is strictly earlier
//! than the one found, as [`Search`](super::super::search::Search) keeps it. The full walk
//! stops once a hit lies at or before the next cell's entry; the short walk stops at the
//! first cell with a hit and gives the ray back where that hit lies past the cell's exit
//! (rounding), where the next cells would still be looked at.

use super::path::Path;
use super::{Crossing, Segment, Touch, Walked};
use crate::arith::{Scalar, SimdPath};
use crate::geometry::clip_to_box;
use crate::heightfield::Terrain;
use crate::traverse::cell_log::CellLog;
use crate::traverse::counters::{Counters, HitMiss};

/// How many cells a first-hit ray's short walk crosses before the full walk takes over (a
/// ray passing over the terrain skips more down the hierarchy).
const MOST_STEPS: u32 = 48;

/// Where a first-hit ray's short walk ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(in crate::traverse) enum FirstHit {
    /// The first hit: its `t`, cell and triangle.
    Hit {
        t: f64,
        cell: (usize, usize),
        triangle: u8,
    },
    /// The ray touches no triangle.
    Missed,
    /// It touches none before this `t` (after its most cells): the full walk answers from
    /// there.
    From(f64),
}

/// The first hit of `o + t*d` (`d` with both ground components non-zero), walked from
/// `t = from`, before which it touches nothing, its queries added to `counters` and the
/// cells it tests noted in `log`; `None` where the full walk must answer from the start (a
/// start outside the grid, on a grid line, or before the ray enters the terrain's box; a
/// path through a lattice point or found under the surface).
pub(in crate::traverse) fn first_hit(
    terrain: &Terrain,
    o: [f64; 3],
    d: [f64; 3],
    from: f64,
    (counters, log): (&mut Counters, &mut impl CellLog),
) -> Option<FirstHit> {
    let (lo, hi) = terrain.bounds();
    let clipped = clip_to_box(&o, &d, lo, hi)?;
    // The full walk's segment: lengthened by its rounding, from the clearance on where that
    // lies inside (else it starts on the box's face, where this walk does not).
    let t_end = clipped.t1.past_rounding();
    if !(from > clipped.t0 && from < t_end) {
        return None;
    }
    let mut walk = Path::from(terrain, o, d, from)?;
    let segment = Segment::new(o, d, t_end);
    let walked = segment.walk((terrain, &mut walk), &FirstHitting, (counters, log))?;
    // (Where the full walk goes on, it clips the ray itself.)
    let answer = match walked {
        Walked::Touched((t, cell, triangle)) => FirstHit::Hit { t, cell, triangle },
        Walked::Clear => FirstHit::Missed,
        Walked::From(t) => return Some(FirstHit::From(t)),
    };
    counters.bbox.record(true);
    Some(answer)
}

/// A first-hit ray's cell test: the earlier of its triangles' hits.
struct FirstHitting;

impl Touch for FirstHitting {
    type Found = (f64, (usize, usize), u8);
    const MOST_STEPS: u32 = MOST_STEPS;
    const SKIPS: bool = false;
    #[inline(always)]
    fn cell(&self, at: Crossing<'_>, triangles: &mut HitMiss) -> Option<Option<Self::Found>> {
        let (walk, four, span) = (at.walk, at.four, at.span);
        let field = at.terrain.field();
        let cell = walk.cell();
        if field.is_hole_cell(cell.0, cell.1) {
            return Some(None);
        }
        let heights = four.map(|sample| field.height_of(sample));
        let hits = walk
            .ray_space()
            .cell_in_lanes(SimdPath::active(), cell, heights)?;
        let mut first: Option<(f64, u8)> = None;
        for (triangle, hit) in (0u8..2).zip(hits) {
            if !triangles.record(hit.is_some()) {
                continue;
            }
            let Some(hit) = hit else { continue };
            if first.is_none_or(|(t, _)| hit.t_first < t) {
                first = Some((hit.t_first, triangle));
            }
        }
        match first {
            // (Past the cell's exit, or NaN, the full walk would look at the next cell too.)
            Some((t, _)) if t.partial_cmp(&span.1).is_none_or(|order| order.is_gt()) => None,
            Some((t, triangle)) => Some(Some((t, cell, triangle))),
            None => Some(None),
        }
    }
}
