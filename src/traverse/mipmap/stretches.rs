//! Clearing the way for an exact walk: an `f64` walk gathers the stretches of the path that
//! may touch the surface, and the exact walk follows only those.

use super::{descend, has_blocks, Part};
use crate::heightfield::Terrain;
use crate::traverse::approximation::{Approximation, Bounds};
use crate::traverse::counters::Counters;
use crate::traverse::frame::{Follower, Frame, Span};
use crate::traverse::options::Query;
use std::ops::ControlFlow;

/// A stretch of the path that may touch the surface, as an `f64` walk found it: `t` from
/// `from` to `to`, and the room to leave around it.
#[derive(Clone, Copy, Debug)]
pub struct Stretch {
    pub from: f64,
    pub to: f64,
    /// Far more than the rounding of any `t` the `f64` walk computed and than the exact
    /// ray's distance from its path (divided by the smaller direction component, as a `t`):
    /// an exact walk from `from - margin` to `to + margin` starts and ends inside blocks the
    /// `f64` walk skipped (or cells it found may be hit), clear of the faces between them.
    pub margin: f64,
}

impl Stretch {
    /// The stretch with room around it, from..to.
    pub fn widened(&self) -> (f64, f64) {
        (self.from - self.margin, self.to + self.margin)
    }
}

/// Walks the `f64` ray near one traced in an arithmetic without rounding, and hands each
/// [`Stretch`] of the path that may touch the surface, in order, to `search`; breaks when
/// `search` does. Between the stretches the exact ray touches nothing (see [`Bounds`]), so an
/// exact walk only follows the stretches: the approach to the first hit, and what lies
/// between the places a shadow ray grazes the surface, are left to the `f64` walk. For a
/// first-hit query the first stretch runs to the segment's end: a camera ray mostly hits
/// where it first may, and its exact walk is faster on from there than an `f64` walk
/// gathering more stretches.
pub fn clear_way(
    ray: &Approximation,
    terrain: &Terrain,
    query: Query,
    counters: &mut Counters,
    search: &mut impl FnMut(Stretch) -> ControlFlow<()>,
) -> ControlFlow<()> {
    let f = &ray.frame;
    // (Without blocks, or bounds that hold, the exact walk follows the whole path.)
    let bounds = has_blocks(f).then(|| Bounds::new(ray, terrain)).flatten();
    let Some(bounds) = bounds else {
        return search(Stretch {
            from: f64::NEG_INFINITY,
            to: f64::INFINITY,
            margin: 0.0,
        });
    };
    let mut clearing = Clearing {
        terrain,
        bounds,
        counters,
        first_only: query == Query::FirstHit,
        stretch: None,
        search,
    };
    let top = terrain.mipmap().top();
    descend(f, top, ray.first_level(query, top), &mut clearing)?;
    clearing.flush()
}

/// The most cells a stretch gathers before it is searched.
const STRETCH_CELLS: u32 = 4;

/// Follows an `f64` walk, gathering the parts of cells that may be hit into stretches.
struct Clearing<'a, F> {
    terrain: &'a Terrain,
    bounds: Bounds,
    counters: &'a mut Counters,
    /// Hand the search only one stretch, from the first cell that may be hit to the end.
    first_only: bool,
    /// The stretch gathered since the last skipped block, and its cells.
    stretch: Option<(Stretch, u32)>,
    search: &'a mut F,
}

impl<F: FnMut(Stretch) -> ControlFlow<()>> Clearing<'_, F> {
    /// Hands the stretch gathered to the search.
    fn flush(&mut self) -> ControlFlow<()> {
        match self.stretch.take() {
            Some((stretch, _)) => (self.search)(stretch),
            None => ControlFlow::Continue(()),
        }
    }
}

impl<F: FnMut(Stretch) -> ControlFlow<()>> Follower<f64> for Clearing<'_, F> {
    fn stop_before(&mut self, t: &f64) -> ControlFlow<()> {
        // The walk moved on past the stretch and its room: a block was skipped since.
        match self.stretch {
            Some((stretch, _)) if *t > stretch.to + 2.0 * stretch.margin => self.flush(),
            _ => ControlFlow::Continue(()),
        }
    }
    // (Inlined by hand, as the search's: the block walk asks at every step.)
    #[inline(always)]
    fn may_hit(&mut self, k: u32, block: (usize, usize), t_lo: &f64, t_hi: &f64) -> bool {
        self.bounds
            .may_hit(self.terrain, k, block, (*t_lo, *t_hi), self.counters)
    }
    fn cell(&mut self, _cell: (usize, usize), part: Part<'_, f64>) -> ControlFlow<()> {
        let to = *part.end_t();
        let (from, cells) = match self.stretch {
            Some((stretch, cells)) => (stretch.from, cells + 1),
            None => (part.at.t, 1),
        };
        let margin = 1e-9 * (from.abs().max(to.abs()) + 1.0) + self.bounds.off_faces;
        if self.first_only {
            let rest = Stretch {
                to: f64::INFINITY,
                ..Stretch { from, to, margin }
            };
            (self.search)(rest)?;
            return ControlFlow::Break(());
        }
        self.stretch = Some((Stretch { from, to, margin }, cells));
        // A long stretch is searched before it ends: past a hit the ray runs inside the
        // terrain, where every block fails its test, to the end of the segment.
        if cells >= STRETCH_CELLS {
            return self.flush();
        }
        ControlFlow::Continue(())
    }
    fn span(&mut self, _f: &Frame<f64>, _span: Span<f64>) -> ControlFlow<()> {
        unreachable!("the block walk that clears the way hands over cells, never spans")
    }
    fn passed(&mut self, _cell: (usize, usize)) {}
    fn moves_away(&self) -> bool {
        self.bounds.moves_away()
    }
}
