//! What happens to each span a walk reaches: the run test, the cell tests, the triangle
//! tests, and keeping the first hit.

use super::cell_log::CellLog;
use super::counters::Counters;
use super::exact_start::PlanePoint;
use super::frame::{run_sample, BlockRun, Follower, Frame, Part, Span};
use super::near_ray::F64Ray;
use super::options::{Query, WalkOptions};
use super::runs;
use super::span_cells::{frame_cells, run_highest, span_cells};
use crate::arith::scalar::{max, min, Scalar};
use crate::arith::{settled, SimdPath};
use crate::geometry::{CellTriangles, Certain, CertainMiss, Face, RaySpace, TriangleHit};
use crate::heightfield::Terrain;
use std::cell::OnceCell;
use std::cmp::Ordering;
use std::ops::ControlFlow;

/// A hit: the ray parameter, the cell `(i, j)` and its triangle (0 or 1).
#[derive(Clone, Debug)]
pub struct Found<S> {
    /// The ray parameter of the hit.
    pub t: S,
    /// The cell `(i, j)` hit.
    pub cell: (usize, usize),
    /// The triangle hit, 0 or 1 (0 on the base).
    pub triangle: u8,
    /// What was hit: a triangle of the cell, or the base (then the cell is the one the hit
    /// point lies over, or beside on a wall).
    pub face: Face,
}

impl<S: Scalar> Found<S> {
    /// The hit point `o + t*d`, in the ray's arithmetic.
    pub fn point(&self, o: &[S; 3], d: &[S; 3]) -> [S; 3] {
        [0, 1, 2].map(|k| o[k].clone() + d[k].clone() * self.t.clone())
    }
}

/// The ray in ray space for the triangle tests, prepared on first use: in exact mode the
/// `f64` filter settles most rays' tests without it, and preparing it divides in intervals.
// (The ray is borrowed, not copied: a copy in the search would be a store that the next load
// cannot be forwarded from.)
pub struct LazyRaySpace<'a, S> {
    origin: &'a [S; 3],
    dir: &'a [S; 3],
    dir_f64: [f64; 3],
    space: OnceCell<RaySpace<S>>,
}

impl<'a, S: Scalar> LazyRaySpace<'a, S> {
    /// The ray `origin + t*dir`; `dir_f64` picks the axes (see [`RaySpace::new`]).
    pub fn new(origin: &'a [S; 3], dir: &'a [S; 3], dir_f64: [f64; 3]) -> Self {
        LazyRaySpace {
            origin,
            dir,
            dir_f64,
            space: OnceCell::new(),
        }
    }

    fn get(&self) -> &RaySpace<S> {
        self.space
            .get_or_init(|| RaySpace::new(self.origin.clone(), self.dir.clone(), self.dir_f64))
    }
}

/// Searches the spans of one walk for the first hit (or any hit, for shadow queries).
pub struct Search<'a, S, C> {
    pub terrain: &'a Terrain,
    pub ray: LazyRaySpace<'a, S>,
    /// For arithmetics without rounding: settles most misses in `f64`.
    pub certain_miss: Option<CertainMiss>,
    /// The origin's height, lowered by a rounding arithmetic's slack ([`Search::widen_by`]).
    pub oz: S,
    /// The origin's height, raised by that slack.
    pub oz_raised: S,
    pub dz: S,
    /// The ray was found under the surface ([`Search::cell_may_hit`]).
    pub under: bool,
    /// The ray moves away from the samples the block test compares it with (see
    /// [`Search::cell_may_hit`]; kept, as the walk asks at every step).
    pub moves_away: bool,
    pub query: Query,
    /// Test each span as a whole before its cells (the run method); a cell walk has none.
    pub run_test: bool,
    pub counters: Counters,
    pub found: Option<Found<S>>,
    /// Two hits on different triangles were found at the same `t`: which one is the answer
    /// then depends on the order the cells were visited in.
    pub tied: bool,
    /// Where the cells the walk reaches are noted.
    pub cells: C,
    /// The triangle the ray starts on and leaves at once: not tested.
    pub start_triangle: Option<((usize, usize), u8)>,
    /// A shadow ray's exact start, for the triangle tests intervals cannot settle.
    pub exact_start: Option<PlanePoint>,
    /// A triangle test intervals could not settle was decided exactly.
    pub decided_exactly: bool,
}

/// Whether a ray of height slope `dz` moves away from the samples the block test compares it
/// with (or keeps level): from the highest above the surface when it climbs, from the lowest
/// `under` it when it descends (see [`Follower::moves_away`](super::mipmap)).
pub fn moves_away<S: Scalar>(dz: &S, under: bool) -> bool {
    dz.is_zero() || dz.is_negative() == under
}

/// The rounding a height `oz + dz*t` computed in `S` may carry, for `t` up to `t_max`: eight
/// roundings of the largest magnitude involved (zero when exact).
pub fn slack<S: Scalar>(oz: &S, dz: &S, t_max: &S) -> f64 {
    let size = oz.to_f64().abs() + (dz.to_f64() * t_max.to_f64()).abs();
    8.0 * S::rounding_error(size)
}

impl<S: Scalar, C: CellLog> Search<'_, S, C> {
    /// Visits one span of the walk of `frame`; breaks when the answer is known.
    pub fn span(&mut self, frame: &Frame<S>, span: Span<S>) -> ControlFlow<()> {
        self.stop_before(&span.t_lo)?;
        if self.run_test && !self.run_may_hit(frame, &span) {
            if C::RECORDS {
                span_cells(frame, &span).for_each(|cell| self.cells.reached(cell));
            }
            return ControlFlow::Continue(());
        }
        let several_columns = span.cols.0 != span.cols.1 && !frame.du.is_zero();
        for (cu, cv) in frame_cells(&span) {
            // The part of the span's ray inside this cell's column.
            let (t_lo, t_hi) = if several_columns {
                (
                    max(span.t_lo.clone(), frame.t_at_u(cu)),
                    min(span.t_hi.clone(), frame.t_at_u(cu + 1)),
                )
            } else {
                (span.t_lo.clone(), span.t_hi.clone())
            };
            self.stop_before(&t_lo)?;
            let (i, j) = frame.cell(cu, cv);
            self.reached(i, j);
            if self.cell_may_hit(i, j, &t_lo, &t_hi) {
                self.triangles(i, j)?;
            }
        }
        ControlFlow::Continue(())
    }

    /// Notes cell `(i, j)` as reached.
    #[inline(always)]
    pub fn reached(&mut self, i: usize, j: usize) {
        self.cells.reached((i, j));
    }

    /// The cell test: the ray's lowest height over `[t_lo, t_hi]` against the cell's highest
    /// sample, and its highest height against the cell's lowest sample. Over the closed cell
    /// the surface lies between the two, so a ray above the highest or below the lowest (one
    /// that went under the surface at the grid's edge, where nothing closes it off) touches
    /// neither triangle.
    ///
    /// A ray below a cell it crosses is under the surface, and stays there until it meets it,
    /// which ends the search: no block lies wholly below it from then on, so the block tests
    /// ask for the blocks' lowest samples instead ([`Search::block_may_hit`]).
    #[inline(always)]
    pub fn cell_may_hit(&mut self, i: usize, j: usize, t_lo: &S, t_hi: &S) -> bool {
        let (lowest_sample, highest_sample) = self.terrain.cell_sample_range(i, j);
        let field = self.terrain.field();
        let below = !self.goes_up_to(field.height_of(lowest_sample), t_lo, t_hi);
        if below && !self.under {
            self.under = true;
            self.moves_away = moves_away(&self.dz, true);
        }
        let may_hit = !below && self.comes_down_to(field.height_of(highest_sample), t_lo, t_hi);
        self.counters.cell.record(may_hit)
    }

    /// Breaks when a hit is already known at or before `t` (cells come in order of first
    /// contact, so nothing later can be earlier; equal `t` keeps the earlier cell).
    #[inline(always)]
    pub fn stop_before(&self, t: &S) -> ControlFlow<()> {
        match &self.found {
            Some(found) if found.t <= *t => ControlFlow::Break(()),
            _ => ControlFlow::Continue(()),
        }
    }

    /// Moves every height the search computes along the ray by `slack`, what rounding may
    /// have moved it by (zero in exact arithmetic, see [`slack`]): down where it is compared
    /// with a highest sample, up where with a lowest. A rounding arithmetic then never culls a
    /// run or cell the ray really touches (as a ray ending on flat ground at the lowest height
    /// does). (The origin's height is moved once: the slack of eight roundings covers the
    /// rounding of that sum as well.)
    pub fn widen_by(&mut self, slack: f64) {
        if slack > 0.0 {
            self.oz_raised = self.oz.clone() + S::from_f64(slack);
            self.oz = self.oz.clone() - S::from_f64(slack);
        }
    }

    /// Whether the ray's lowest height over `[t_lo, t_hi]` (lowered, see
    /// [`Search::widen_by`]) comes down to `highest`.
    #[inline(always)]
    fn comes_down_to(&self, highest: f64, t_lo: &S, t_hi: &S) -> bool {
        let t = if self.dz.is_negative() { t_hi } else { t_lo };
        self.oz.clone() + self.dz.clone() * t.clone() <= S::from_f64(highest)
    }

    /// Whether the ray's highest height over `[t_lo, t_hi]` (raised by the slack) goes up to
    /// `lowest`.
    #[inline(always)]
    fn goes_up_to(&self, lowest: f64, t_lo: &S, t_hi: &S) -> bool {
        let t = if self.dz.is_negative() { t_lo } else { t_hi };
        self.oz_raised.clone() + self.dz.clone() * t.clone() >= S::from_f64(lowest)
    }

    /// The block test of the hierarchical walk, for block `(bi, bj)` of level `k >= 1`: the
    /// ray's lowest height over `[t_lo, t_hi]` against the block's highest sample, or, for a
    /// ray found under the surface, its highest height against the block's lowest sample.
    /// (Either is exact for any ray; [`Search::cell_may_hit`] picks the one that can skip
    /// blocks.)
    #[inline(always)]
    pub fn block_may_hit(&mut self, k: u32, (bi, bj): (usize, usize), t_lo: &S, t_hi: &S) -> bool {
        let (mipmap, field) = (self.terrain.mipmap(), self.terrain.field());
        let may_hit = if self.under {
            self.goes_up_to(field.height_of(mipmap.lowest(k, bi, bj)), t_lo, t_hi)
        } else {
            self.comes_down_to(field.height_of(mipmap.highest(k, bi, bj)), t_lo, t_hi)
        };
        self.counters.block.record(may_hit)
    }

    /// The run test of the hierarchical run walk: as the block test, against the highest
    /// sample of all the run's blocks (or the lowest, under the surface).
    pub fn blocks_run_may_hit(&mut self, f: &Frame<S>, run: &BlockRun, t_lo: &S, t_hi: &S) -> bool {
        let sample = run_sample(self.terrain, f, run, self.under);
        let height = self.terrain.field().height_of(sample);
        let may_hit = if self.under {
            self.goes_up_to(height, t_lo, t_hi)
        } else {
            self.comes_down_to(height, t_lo, t_hi)
        };
        self.counters.run.record(may_hit)
    }

    /// The run test: the ray's lowest height over the run against the highest cell under it.
    fn run_may_hit(&mut self, frame: &Frame<S>, span: &Span<S>) -> bool {
        let rows = (span.row, span.row + i64::from(span.rows) - 1);
        let highest = run_highest(self.terrain, frame, span.cols, rows);
        let may_hit = self.comes_down_to(highest, &span.t_lo, &span.t_hi);
        self.counters.run.record(may_hit)
    }

    /// Tests both triangles of cell `(i, j)`.
    pub fn triangles(&mut self, i: usize, j: usize) -> ControlFlow<()> {
        if self.terrain.field().is_hole_cell(i, j) {
            return ControlFlow::Continue(());
        }
        let heights = self.terrain.corner_heights(i, j);
        let start = self.start_triangle;
        let tested = |triangle| start != Some(((i, j), triangle));
        // In `f64`, both triangles at once in SIMD lanes, with the scalar test's answers. (The
        // other arithmetics build the ray space only where the filter below leaves a cell open.)
        let in_f64 = S::as_f64s::<0>(&[]).is_some();
        let lanes = in_f64
            .then(|| {
                self.ray
                    .get()
                    .cell_in_lanes(SimdPath::active(), (i, j), heights)
            })
            .flatten();
        if let Some(hits) = lanes {
            for (triangle, hit) in (0..2).zip(hits) {
                if tested(triangle) {
                    self.keep((i, j), triangle, hit)?;
                }
            }
            return ControlFlow::Continue(());
        }
        // What the `f64` filter settles: a certain miss (`Some(None)`), or a certain hit and
        // an enclosure of its `t` (`Some(Some(t))`).
        let certain: [Option<Option<S>>; 2] = match &self.certain_miss {
            Some(filter) if S::EXACT => {
                let images = filter.cell(i, j, heights);
                let settles = |k: u8| {
                    if !tested(k) {
                        return None;
                    }
                    match images.triangle(k) {
                        Certain::Miss => Some(None),
                        Certain::Crossing => {
                            let (lo, hi) = filter.plane_t((i, j), k, heights)?;
                            S::from_enclosure(lo, hi).map(Some)
                        }
                        Certain::Open => None,
                    }
                };
                // (In straight code: mapped over `[0, 1]`, the answers go through the stack
                // out of line.)
                [settles(0), settles(1)]
            }
            _ => [None, None],
        };
        // (Built only for a triangle the filter leaves open; built before the loop, not on
        // first use in it, where filling an `Option` would copy the cell's values.)
        let open = |k: u8| tested(k) && certain[k as usize].is_none();
        let cell = (open(0) || open(1))
            .then(|| CellTriangles::new(self.ray.get(), i, j, heights.map(S::from_f64)));
        for triangle in 0..2 {
            if !tested(triangle) {
                continue;
            }
            let hit = match (&certain[triangle as usize], &cell) {
                (Some(None), _) => None,
                (Some(Some(t)), _) => Some(TriangleHit {
                    t_first: t.clone(),
                    t_last: Some(t.clone()),
                }),
                (None, None) => unreachable!("the cell is built for every open triangle"),
                (None, Some(cell)) => match self.exact_start.filter(|_| S::EXACT) {
                    Some(start) => self.test_from(start, cell, (i, j), triangle),
                    None => cell.intersect(self.ray.get(), triangle),
                },
            };
            self.keep((i, j), triangle, hit)?;
        }
        ControlFlow::Continue(())
    }

    /// Counts the test of `triangle` of `cell` and keeps its hit if it is the first so far;
    /// breaks a shadow query at a hit that counts.
    #[inline(always)]
    fn keep(
        &mut self,
        cell: (usize, usize),
        triangle: u8,
        hit: Option<TriangleHit<S>>,
    ) -> ControlFlow<()> {
        let counts = hit.as_ref().is_some_and(|hit| self.counts(hit));
        if !self.counters.triangle.record(counts) {
            return ControlFlow::Continue(());
        }
        let Some(hit) = hit else {
            return ControlFlow::Continue(());
        };
        // (A walk may reach a cell twice where its parts meet: the same triangle's hit is
        // the same, and comparing it with itself would be a tie intervals cannot settle.)
        let other = |f: &Found<S>| (f.cell, f.triangle) != (cell, triangle);
        let earlier = self
            .found
            .as_ref()
            .is_none_or(|f| other(f) && hit.t_first < f.t);
        self.tied |= !earlier
            && self.found.as_ref().is_some_and(|f| {
                other(f) && f.t.partial_cmp(&hit.t_first) == Some(Ordering::Equal)
            });
        if earlier {
            self.found = Some(Found {
                t: hit.t_first,
                cell,
                triangle,
                face: Face::Terrain,
            });
        }
        if self.query == Query::Shadow {
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    }
}

impl<S: Scalar, C: CellLog> Search<'_, S, C> {
    /// Tests triangle `k` of `cell` for a shadow ray whose start is known exactly: a hit that
    /// counts, or none. A test the intervals cannot settle is decided exactly on its own.
    // (Out of line, so that the interval walk's triangle loop stays small.)
    #[inline(never)]
    fn test_from(
        &mut self,
        start: PlanePoint,
        cell: &CellTriangles<S>,
        at: (usize, usize),
        k: u8,
    ) -> Option<TriangleHit<S>> {
        let test = || {
            let hit = cell.intersect(self.ray.get(), k);
            hit.filter(|hit| self.counts(hit))
        };
        if let (hit, true) = settled(test) {
            return hit;
        }
        let decided = start.touches_after_start(self.terrain, self.ray.dir_f64, at, k);
        let Some(first) = decided else {
            // (Tested again to leave the decision unsettled: the ray is then cast again.)
            return test();
        };
        self.decided_exactly = true;
        // (Rounded to nearest: its neighbours enclose it.)
        let t = first.and_then(|t| S::from_enclosure(t.next_down(), t.next_up()))?;
        Some(TriangleHit {
            t_first: t,
            t_last: None,
        })
    }

    /// Whether a hit counts: a shadow ray must touch the surface after its start.
    fn counts(&self, hit: &TriangleHit<S>) -> bool {
        match self.query {
            Query::FirstHit => true,
            Query::Shadow => hit
                .t_last
                .as_ref()
                .is_none_or(|t| !t.is_negative() && !t.is_zero()),
        }
    }
}

/// A search for the ray's answer, before any walk.
// (Inlined by hand: called once per ray, but `Search` is large, and out of line its
// construction costs every ray.)
#[inline(always)]
pub(super) fn new_search<'a, S: Scalar, C: CellLog>(
    terrain: &'a Terrain,
    (o, d, dir_f64): (&'a [S; 3], &'a [S; 3], [f64; 3]),
    near: Option<F64Ray>,
    options: &WalkOptions,
    counters: Counters,
    run_test: bool,
) -> Search<'a, S, C> {
    Search {
        terrain,
        ray: LazyRaySpace::new(o, d, dir_f64),
        certain_miss: near
            .map(|(origin, [rx, ry, rz], dir)| CertainMiss::new(origin, rx.max(ry).max(rz), dir)),
        oz: o[2].clone(),
        oz_raised: o[2].clone(),
        dz: d[2].clone(),
        under: false,
        moves_away: moves_away(&d[2], false),
        query: options.query,
        run_test,
        counters,
        found: None,
        tied: false,
        cells: C::default(),
        start_triangle: options.start_triangle,
        // (`S::EXACT` is asked here as well as where the start is used, which compiles it out
        // of the rounding arithmetics, `f64` included.)
        exact_start: options
            .exact_start
            .filter(|_| S::EXACT && options.query == Query::Shadow),
        decided_exactly: false,
    }
}

impl<S: Scalar, C: CellLog> Follower<S> for Search<'_, S, C> {
    fn stop_before(&mut self, t: &S) -> ControlFlow<()> {
        Search::stop_before(self, t)
    }
    // Inlined by hand: a call costs a fifth of the walk's time, and whether the compiler
    // inlines it by itself depends on unrelated code elsewhere in the crate.
    #[inline(always)]
    fn may_hit(&mut self, k: u32, (bi, bj): (usize, usize), t_lo: &S, t_hi: &S) -> bool {
        if k == 0 {
            self.cell_may_hit(bi, bj, t_lo, t_hi)
        } else {
            let may_hit = self.block_may_hit(k, (bi, bj), t_lo, t_hi);
            if may_hit {
                self.terrain.fetch_below(k, bi, bj);
            }
            may_hit
        }
    }
    fn run_may_hit(&mut self, f: &Frame<S>, run: &BlockRun, t_lo: &S, t_hi: &S) -> bool {
        self.blocks_run_may_hit(f, run, t_lo, t_hi)
    }
    // (Inlined by hand too: the run walk calls it as well, and out of line it would slow the
    // block walk.)
    #[inline(always)]
    fn cell(&mut self, (i, j): (usize, usize), part: Part<'_, S>) -> ControlFlow<()> {
        if part.alone {
            self.reached(i, j);
            return self.triangles(i, j);
        }
        runs::walk(&part.path(), self)
    }
    #[inline(always)]
    fn span(&mut self, f: &Frame<S>, span: Span<S>) -> ControlFlow<()> {
        Search::span(self, f, span)
    }
    fn passed(&mut self, (i, j): (usize, usize)) {
        self.reached(i, j);
    }
    fn moves_away(&self) -> bool {
        self.moves_away
    }
}
