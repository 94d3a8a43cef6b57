//! The generic inside of [`trace`](super::trace) and [`occluded`](super::occluded): a
//! [`Tracer`] answers both questions in one arithmetic `S`, for code that runs per arithmetic
//! through [`run`](crate::arith::run) (the renderer's pixels).

use super::answer::ScalarTrace;
use super::counters::Counters;
use super::exact_plane::{crosses_plane, plane_t_exact};
use super::exact_start::PlanePoint;
use super::options::{Method, Query, TraceOptions, WalkOptions};
use super::search::Found;
use super::surface::{base_t_exact, trace_scalar};
use super::wedges::Clearance;
use crate::arith::{run, settled, unsettled, Exact, Generic, Scalar};
use crate::geometry::Ray;
use crate::geometry::{gradient, plane_height, triangle_corners, Base, Face, Side};
use crate::heightfield::Terrain;
use glam::DVec3;

/// Traces rays over one terrain with one method, in any arithmetic.
#[derive(Clone, Copy, Debug)]
pub struct Tracer<'a> {
    pub(super) terrain: &'a Terrain,
    method: Method,
    record_cells: bool,
    /// Occlusion rays look no further than this `t` (see [`Tracer::within`]).
    reach: Option<f64>,
    /// Walk the first cells of a path one by one (see [`Tracer::walking_near`]).
    near: bool,
    /// The base under the terrain, part of the surface where given (see [`Tracer::with_base`]).
    pub(super) base: Option<Base>,
}

/// Where an occlusion ray ([`Tracer::occluded`]) starts.
#[derive(Clone, Copy, Debug)]
pub enum Start<'r, S> {
    /// At a point given in the traversal's arithmetic.
    Point(&'r [S; 3]),
    /// On the surface, where `ray` hit it (`hit`): in arithmetics without rounding exactly
    /// there, on the hit triangle's plane; in the others raised by what rounding may have
    /// moved the point below the surface. The ray leaves its own triangle untested where it
    /// leaves the triangle's plane at once.
    Hit {
        /// The ray that hit.
        ray: &'r Ray,
        /// Its hit, in the traversal's arithmetic.
        hit: &'r Found<S>,
    },
    /// At `point` near the hit of `ray` (on a curved surface the hit triangle stands for),
    /// raised like [`Start::Hit`]; the hit triangle is not tested.
    Near {
        /// The ray that hit.
        ray: &'r Ray,
        /// Its hit, in the traversal's arithmetic.
        hit: &'r Found<S>,
        /// Where the occlusion ray starts, before raising.
        point: [f64; 3],
    },
}

/// Whether anything lies in the way of an occlusion ray, and what finding out asked.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Occlusion {
    /// Whether the ray touches the surface after its start; `None` where it was not traced
    /// because it starts above the highest terrain and rises (see [`Tracer::occluded`]).
    pub occluded: Option<bool>,
    /// The ray's queries.
    pub counters: Counters,
    /// Cells covered, in order (when asked for, see [`Tracer::recording_cells`]).
    pub cells: Vec<[usize; 2]>,
    /// Intervals left a decision unsettled and it was made exactly: one triangle test on its
    /// own, or the whole ray again in rationals from the exact hit point.
    pub exactly: bool,
}

impl<'a> Tracer<'a> {
    /// A tracer of `terrain` walking by `method`.
    pub fn new(terrain: &'a Terrain, method: Method) -> Self {
        Tracer {
            terrain,
            method,
            record_cells: false,
            reach: None,
            near: true,
            base: None,
        }
    }

    /// The same tracer, its rays meeting `base` (one made for this terrain, see
    /// [`Base::under`]) as part of the surface, or the terrain alone with `None`.
    pub fn with_base(self, base: Option<Base>) -> Self {
        Tracer { base, ..self }
    }

    /// The base its rays meet, if any.
    pub fn base(&self) -> Option<Base> {
        self.base
    }

    /// The same tracer, its occlusion rays asking only whether the surface lies in the way
    /// up to `t_max` (inclusive; in the arithmetic's own `t`, from the ray's start).
    pub fn within(self, t_max: f64) -> Self {
        Tracer {
            reach: Some(t_max),
            ..self
        }
    }

    /// The same tracer, walking the first cells of a first-hit ray from its clearance one by
    /// one (`true`, the default) or down the hierarchy like the rest: the same answers, at
    /// another cost.
    pub fn walking_near(self, near: bool) -> Self {
        Tracer { near, ..self }
    }

    /// The same tracer, listing the cells each walk covers.
    pub fn recording_cells(self) -> Self {
        Tracer {
            record_cells: true,
            ..self
        }
    }

    /// The first hit of `ray` (the least `t >= 0`), in arithmetic `S`. With `clearance`
    /// (a camera ray's, from its [`Wedges`](super::Wedges)), the ray touches nothing before
    /// its `t`, and a hierarchical walk starts there, at its level.
    #[inline]
    pub fn trace<S: Scalar>(&self, ray: &Ray, clearance: Option<Clearance>) -> ScalarTrace<S> {
        let (o, d) = (ray.origin().map(S::from_f64), ray.dir().map(S::from_f64));
        let walk = WalkOptions {
            clearance,
            ..self.walk(Query::FirstHit)
        };
        trace_scalar(self.terrain, &o, &d, ray.dir(), walk)
    }

    /// Answers `query` for the ray `o + t*d` given in `S` (`dir` is `d` as given), from
    /// `clearance` if given (see [`Tracer::trace`]).
    pub(super) fn ask<S: Scalar>(
        &self,
        o: &[S; 3],
        d: &[S; 3],
        dir: [f64; 3],
        query: Query,
        clearance: Option<Clearance>,
    ) -> ScalarTrace<S> {
        let walk = WalkOptions {
            clearance,
            ..self.walk(query)
        };
        trace_scalar(self.terrain, o, d, dir, walk)
    }

    /// Whether a ray from `from` in direction `dir` touches the surface at some `t > 0`, in
    /// arithmetic `S`. With `skip_above`, a ray that starts above the highest terrain and
    /// rises is not traced. In intervals ([`Scalar::ENCLOSES`]) a decision they cannot settle
    /// is made exactly, from the exact hit point: the ray is cast again in rationals (one
    /// whose primary ray runs in its hit triangle's plane, which only the primary walk tells,
    /// and one from a point leave the intervals unsettled, see
    /// [`settled`](crate::arith::settled)).
    pub fn occluded<S: Scalar>(
        &self,
        from: &Start<'_, S>,
        dir: [f64; 3],
        skip_above: bool,
    ) -> Occlusion {
        if !S::ENCLOSES {
            return self.occluded_in(from, dir, skip_above);
        }
        occluded_settling(self, from, dir, skip_above)
    }

    /// [`Tracer::occluded`] in `S` alone.
    pub(super) fn occluded_in<S: Scalar>(
        &self,
        from: &Start<'_, S>,
        dir: [f64; 3],
        skip_above: bool,
    ) -> Occlusion {
        let (origin, start_triangle, exact_start) = match *from {
            Start::Point(o) => (o.clone(), None, None),
            Start::Hit { ray, hit } if hit.face != Face::Terrain => {
                let [x, y, z] = self.base_point(hit, ray);
                let origin = [x, y, z + S::from_f64(self.lift::<S>(ray, hit))];
                (origin, None, None)
            }
            Start::Hit { ray, hit } => {
                let [x, y, z] = self.plane_point(hit, ray);
                let origin = [x, y, z + S::from_f64(self.lift::<S>(ray, hit))];
                let leaves = self.leaves_at_once(hit, dir);
                let exact = S::EXACT.then_some(PlanePoint {
                    ray: *ray,
                    cell: hit.cell,
                    triangle: hit.triangle,
                });
                (origin, leaves.then_some(hit), exact)
            }
            Start::Near { ray, hit, point } => {
                let [x, y, z] = point;
                let origin = [x, y, z + self.lift::<S>(ray, hit)].map(S::from_f64);
                (origin, Some(hit), None)
            }
        };
        let (_, z_max) = self.terrain.z_range();
        if skip_above && dir[2] > 0.0 && origin[2] > S::from_f64(z_max) {
            return Occlusion::default();
        }
        let start_triangle = start_triangle.map(|hit| (hit.cell, hit.triangle));
        if let Some(short) = self.short_walk(&origin, dir, start_triangle) {
            return short;
        }
        let walk = WalkOptions {
            start_triangle,
            exact_start,
            reach: self.reach,
            ..self.walk(Query::Shadow)
        };
        let answer = trace_scalar(self.terrain, &origin, &dir.map(S::from_f64), dir, walk);
        Occlusion {
            occluded: Some(answer.hit.is_some()),
            counters: answer.counters,
            cells: answer.cells,
            exactly: answer.decided_exactly,
        }
    }

    /// An `f64` occlusion ray with a short reach, answered by the
    /// [`short_walk`](super::short_walk) where it can be (with the near walk's switch, as it
    /// is the same idea: the first cells one by one), for the hierarchical methods whose
    /// answers it reproduces, over the terrain alone (a base is tested beside the full walk).
    #[inline(always)]
    fn short_walk<S: Scalar>(
        &self,
        origin: &[S; 3],
        dir: [f64; 3],
        start_triangle: Option<((usize, usize), u8)>,
    ) -> Option<Occlusion> {
        let reach = self.reach?;
        let o = S::as_f64s(origin)?;
        if !(self.near && self.method.is_hierarchical()) || self.record_cells || self.base.is_some()
        {
            return None;
        }
        let (occluded, counters) =
            super::short_walk::short_walk(self.terrain, *o, dir, reach, start_triangle)?;
        Some(Occlusion {
            occluded: Some(occluded),
            counters,
            cells: Vec::new(),
            exactly: false,
        })
    }

    /// The walk options of a query of this tracer.
    fn walk(&self, query: Query) -> WalkOptions {
        WalkOptions {
            record_cells: self.record_cells,
            near: self.near,
            base: self.base,
            ..WalkOptions::new(self.method, query)
        }
    }

    /// How far to raise a start on the surface above what rounding may have moved it below
    /// (zero in exact arithmetic): the surface is a height field, so up is always outside. The
    /// point is `o + t*d`, each component within a few roundings of `|o| + |t*d|`; off by that
    /// across an edge, the surface may be higher by the steepest slope times it.
    fn lift<S: Scalar>(&self, ray: &Ray, hit: &Found<S>) -> f64 {
        let t = hit.t.to_f64().abs();
        let (ray_o, ray_d) = (ray.origin(), ray.dir());
        let largest = (0..3).fold(0.0f64, |m, k| m.max(ray_o[k].abs() + t * ray_d[k].abs()));
        64.0 * S::rounding_error(largest) * (1.0 + self.terrain.max_slope())
    }

    /// The hit point as a ray from the flat triangle starts at, in arithmetic `S`.
    fn plane_point<S: Scalar>(&self, found: &Found<S>, ray: &Ray) -> [S; 3] {
        let (ray_o, ray_d) = (ray.origin(), ray.dir());
        let [x, y] = [0, 1].map(|k| S::along(ray_o[k], ray_d[k], &found.t));
        // Rounding arithmetics take the height on the hit triangle's plane: exact on flat
        // ground. Without rounding the ray's own point is on the plane, and enclosing it takes
        // a fifth of the work of enclosing the plane's height over the enclosures of x and y;
        // on a flat triangle the point's height is the triangle's, exactly: intervals must
        // know it then, or the run and cell tests of a ray from a terrace's top, the highest
        // sample of the runs and cells around it, cannot be settled where intervals walk (a
        // path along a grid row, which the `f64` walk leaves to them), and each such ray is
        // cast again in rationals, at a millisecond a ray.
        let z = if S::EXACT {
            match self.flat_height(found) {
                Some(height) => S::from_f64(height),
                None => S::along(ray_o[2], ray_d[2], &found.t),
            }
        } else {
            let (i, j) = found.cell;
            let heights = self.terrain.corner_heights(i, j).map(S::from_f64);
            plane_height(found.triangle, found.cell, heights, x.clone(), y.clone())
        };
        [x, y, z]
    }

    /// The point where a ray hit the base, in arithmetic `S`, on the face's plane exactly.
    fn base_point<S: Scalar>(&self, found: &Found<S>, ray: &Ray) -> [S; 3] {
        let (ray_o, ray_d) = (ray.origin(), ray.dir());
        let mut point = [0, 1, 2].map(|k| S::along(ray_o[k], ray_d[k], &found.t));
        let field = self.terrain.field();
        let (w, h) = (field.width() as i64 - 1, field.height() as i64 - 1);
        match (found.face, self.base) {
            (Face::Floor, Some(base)) => point[2] = S::from_f64(base.floor()),
            (Face::Wall(Side::West), _) => point[0] = S::zero(),
            (Face::Wall(Side::East), _) => point[0] = S::from_i64(w),
            (Face::Wall(Side::South), _) => point[1] = S::zero(),
            (Face::Wall(Side::North), _) => point[1] = S::from_i64(h),
            _ => {}
        }
        point
    }

    /// Whether a ray in direction `dir` leaves the hit triangle's plane at once, so that it
    /// touches the triangle it starts on only at its start (in floats decided with room to
    /// spare for rounding: when in doubt the triangle is tested like any other).
    fn leaves_at_once<S: Scalar>(&self, found: &Found<S>, dir: [f64; 3]) -> bool {
        let heights = self.terrain.corner_heights(found.cell.0, found.cell.1);
        let (gx, gy) = gradient(found.triangle, heights);
        let (n, s) = (DVec3::new(-gx, -gy, 1.0), DVec3::from(dir));
        let terms = [n.x * s.x, n.y * s.y, n.z * s.z];
        let sum: f64 = terms.iter().sum();
        if sum.abs() > 1e-9 * terms.iter().map(|t| t.abs()).sum::<f64>() {
            return true;
        }
        // Without rounding the ray starts on the plane itself, and leaves it at once unless it
        // runs in it: asked exactly (intervals cannot tell the two apart in the tests).
        S::EXACT && crosses_plane(self.terrain, found.cell, found.triangle, dir)
    }

    /// The height of the hit triangle if it is flat (its three corners at one height).
    fn flat_height<S: Scalar>(&self, found: &Found<S>) -> Option<f64> {
        let heights = self.terrain.corner_heights(found.cell.0, found.cell.1);
        let [a, b, c] = triangle_corners(found.triangle).map(|k| heights[k]);
        (a == b && b == c).then_some(a)
    }
}

/// Whether anything lies in the way from where `ray` first hits the surface towards `dir`, in
/// the options' method and arithmetic: the shadow ray a renderer casts from a hit (see
/// [`Start::Hit`]), starting on the surface, exactly there in exact arithmetic. `None` where
/// `ray` misses. The answer's counters are the occlusion ray's.
pub fn occluded_from_hit(
    terrain: &Terrain,
    ray: &Ray,
    dir: [f64; 3],
    options: &TraceOptions,
) -> Option<Occlusion> {
    let mut tracer = Tracer::new(terrain, options.method).with_base(options.base);
    if options.record_cells {
        tracer = tracer.recording_cells();
    }
    let (ran, rational) = run(options.arith, &FromHit { tracer, ray, dir });
    let mut occlusion = ran.output?;
    occlusion.counters.rational_rounded = rational.rounded;
    occlusion.counters.rational_saturated = rational.saturated;
    occlusion.exactly |= ran.redone;
    Some(occlusion)
}

/// [`occluded_from_hit`] in whichever arithmetic [`run`] picks.
struct FromHit<'a> {
    tracer: Tracer<'a>,
    ray: &'a Ray,
    dir: [f64; 3],
}

impl Generic for FromHit<'_> {
    type Output = Option<Occlusion>;
    fn run<S: Scalar>(&self) -> Self::Output {
        let hit = self.tracer.trace::<S>(self.ray, None).hit?;
        let from = Start::Hit {
            ray: self.ray,
            hit: &hit,
        };
        Some(self.tracer.occluded(&from, self.dir, false))
    }
}

/// [`Tracer::occluded`] in intervals: a ray with a decision they cannot settle is cast again
/// in rationals from the exact hit point (where the start is a hit), and its answer marked
/// as made exactly; otherwise the intervals are left unsettled for the caller to run again.
fn occluded_settling<S: Scalar>(
    tracer: &Tracer<'_>,
    from: &Start<'_, S>,
    dir: [f64; 3],
    skip_above: bool,
) -> Occlusion {
    let (answer, is_settled) = settled(|| tracer.occluded_in(from, dir, skip_above));
    if is_settled {
        return answer;
    }
    let exact = |ray: &Ray, hit: &Found<S>| {
        let t = match tracer.base.filter(|_| hit.face != Face::Terrain) {
            Some(base) => base_t_exact(tracer.terrain, &base, ray, hit.face, false)?.0,
            None => plane_t_exact(tracer.terrain, ray, hit.cell, hit.triangle)?,
        };
        Some(Found {
            t: Exact(t),
            cell: hit.cell,
            triangle: hit.triangle,
            face: hit.face,
        })
    };
    let again = match *from {
        // (The caller runs the whole ray again in rationals, see `run`.)
        Start::Point(_) => None,
        Start::Hit { ray, hit } => exact(ray, hit)
            .map(|hit| tracer.occluded_in(&Start::Hit { ray, hit: &hit }, dir, skip_above)),
        Start::Near { ray, hit, point } => exact(ray, hit).map(|hit| {
            let from = Start::Near {
                ray,
                hit: &hit,
                point,
            };
            tracer.occluded_in(&from, dir, skip_above)
        }),
    };
    match again {
        Some(answer) => Occlusion {
            exactly: true,
            ..answer
        },
        None => {
            unsettled();
            answer
        }
    }
}
