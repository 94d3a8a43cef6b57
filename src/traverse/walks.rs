//! The four walks behind one trait ([`Walk`]), and the one place a [`Method`] picks its walk
//! ([`choose`]): the trace, the certifying `f64` walk and the listing of covered cells all
//! take the walk from there.

use super::approximation::Approximation;
use super::cell_log::CellLog;
use super::certified::Certifying;
use super::frame::{Follower, Frame, Levels, Part, Span};
use super::mipmap;
use super::span_cells::span_cells;
use super::{dda, runs, Method};
use crate::arith::scalar::Scalar;
use std::ops::ControlFlow;

/// One way to walk the grid along a ray's path.
pub(super) trait Walk {
    /// Whether an `f64` walk clears the way for this walk in the arithmetics without rounding
    /// (see [`clear_way`](mipmap::stretches::clear_way)).
    const CLEARS_WAY: bool = false;
    /// Whether the search tests each span the walk hands over as a whole before its cells
    /// (the run test, [`Search::span`](super::search::Search::span)).
    const TESTS_RUNS: bool = false;
    /// Walks the path of `f`, handing what it reaches to `follower`, until it breaks;
    /// `levels`: how high a hierarchical walk may climb and where it starts (see
    /// [`mipmap::walk`]).
    fn walk<S: Scalar>(
        f: &Frame<S>,
        levels: Levels,
        follower: &mut impl Follower<S>,
    ) -> ControlFlow<()>;
    /// The same walk in `f64` along an `f64` ray near an exact one, for the exact ray's
    /// answer (see [`certify`](super::certified::certify)).
    fn certify<S: Scalar, C: CellLog>(
        ray: &Approximation,
        certifying: &mut Certifying<'_, '_, S, C>,
    ) -> ControlFlow<()>;
    /// Walks every cell the path covers, culling nothing: the hierarchies then have nothing
    /// to skip, and their cells are the run walk's.
    fn cover<S: Scalar>(f: &Frame<S>, follower: &mut impl Follower<S>) -> ControlFlow<()> {
        runs::walk(f, follower)
    }
}

/// The min-max mipmap's block walk ([`Method::Mipmap`]).
pub(super) struct Blocks;
/// The hierarchical run walk ([`Method::HierarchicalRuns`]).
pub(super) struct BlockRuns;
/// The run walk ([`Method::Runs`]).
pub(super) struct Runs;
/// The cell DDA ([`Method::Dda`]).
pub(super) struct Cells;

impl Walk for Blocks {
    const CLEARS_WAY: bool = true;
    fn walk<S: Scalar>(
        f: &Frame<S>,
        levels: Levels,
        follower: &mut impl Follower<S>,
    ) -> ControlFlow<()> {
        mipmap::walk(f, follower, levels)
    }
    fn certify<S: Scalar, C: CellLog>(
        ray: &Approximation,
        certifying: &mut Certifying<'_, '_, S, C>,
    ) -> ControlFlow<()> {
        certifying.blocks(ray, false)
    }
}

impl Walk for BlockRuns {
    fn walk<S: Scalar>(
        f: &Frame<S>,
        levels: Levels,
        follower: &mut impl Follower<S>,
    ) -> ControlFlow<()> {
        mipmap::walk_runs(f, follower, levels)
    }
    fn certify<S: Scalar, C: CellLog>(
        ray: &Approximation,
        certifying: &mut Certifying<'_, '_, S, C>,
    ) -> ControlFlow<()> {
        certifying.blocks(ray, true)
    }
}

impl Walk for Runs {
    const TESTS_RUNS: bool = true;
    fn walk<S: Scalar>(
        f: &Frame<S>,
        _levels: Levels,
        follower: &mut impl Follower<S>,
    ) -> ControlFlow<()> {
        runs::walk(f, follower)
    }
    fn certify<S: Scalar, C: CellLog>(
        ray: &Approximation,
        certifying: &mut Certifying<'_, '_, S, C>,
    ) -> ControlFlow<()> {
        certifying.runs(ray)
    }
}

impl Walk for Cells {
    fn walk<S: Scalar>(
        f: &Frame<S>,
        _levels: Levels,
        follower: &mut impl Follower<S>,
    ) -> ControlFlow<()> {
        dda::walk(f, follower)
    }
    fn certify<S: Scalar, C: CellLog>(
        ray: &Approximation,
        certifying: &mut Certifying<'_, '_, S, C>,
    ) -> ControlFlow<()> {
        certifying.cells(ray)
    }
    fn cover<S: Scalar>(f: &Frame<S>, follower: &mut impl Follower<S>) -> ControlFlow<()> {
        dda::walk(f, follower)
    }
}

/// Code generic over the walk, run by [`choose`].
pub(super) trait WithWalk {
    type Output;
    fn with<W: Walk>(self) -> Self::Output;
}

/// Runs `user` with the walk of `method`: the one place a method picks its walk.
#[inline(always)]
pub(super) fn choose<U: WithWalk>(method: Method, user: U) -> U::Output {
    match method {
        Method::Mipmap => user.with::<Blocks>(),
        Method::HierarchicalRuns => user.with::<BlockRuns>(),
        Method::Runs => user.with::<Runs>(),
        Method::Dda => user.with::<Cells>(),
    }
}

/// Lists the cells a walk covers, in order, testing none.
#[derive(Default)]
pub(super) struct Covering {
    pub cells: Vec<[usize; 2]>,
}

impl<S: Scalar> Follower<S> for Covering {
    fn stop_before(&mut self, _t: &S) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    fn may_hit(&mut self, _k: u32, _block: (usize, usize), _t_lo: &S, _t_hi: &S) -> bool {
        true
    }
    fn cell(&mut self, _cell: (usize, usize), part: Part<'_, S>) -> ControlFlow<()> {
        runs::walk(&part.path(), self)
    }
    fn span(&mut self, f: &Frame<S>, span: Span<S>) -> ControlFlow<()> {
        self.cells.extend(span_cells(f, &span).map(|(i, j)| [i, j]));
        ControlFlow::Continue(())
    }
    // (Every block may be hit: none is passed by.)
    fn passed(&mut self, _cell: (usize, usize)) {}
    fn moves_away(&self) -> bool {
        false
    }
}
