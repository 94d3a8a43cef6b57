//! The generic inside of [`trace`](super::trace) and [`occluded`](super::occluded): a
//! [`Tracer`] answers both questions in one arithmetic `S`, for code that runs per arithmetic
//! through [`run`](crate::arith::run) (the renderer's pixels).

use super::answer::ScalarTrace;
use super::counters::Counters;
use super::departure::{Departure, Start};
use super::exact_plane::plane_t_exact;
use super::options::{Method, Query, TraceOptions, WalkOptions};
use super::search::Found;
use super::surface::{base_t_exact, trace_scalar};
use super::wedges::Clearance;
use crate::arith::{run, settled, unsettled, Exact, Generic, Scalar};
use crate::geometry::{Base, Face, Ray};
use crate::heightfield::Terrain;

/// Traces rays over one terrain with one method, in any arithmetic.
#[derive(Clone, Copy, Debug)]
pub struct Tracer<'a> {
    pub(super) terrain: &'a Terrain,
    method: Method,
    record_cells: bool,
    /// Occlusion rays look no further than this `t` (see [`Tracer::within`]).
    reach: Option<f64>,
    /// Occlusion rays touch no triangle but their own before this `t` (see
    /// [`Tracer::clear_before`]).
    clear: f64,
    /// Walk the first cells of a path one by one (see [`Tracer::walking_near`]).
    near: bool,
    /// The base under the terrain, part of the surface where given (see [`Tracer::with_base`]).
    pub(super) base: Option<Base>,
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
            clear: 0.0,
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

    /// The same tracer, its occlusion rays known (by the caller's bounds) to touch no
    /// triangle but their own before `t` (in the arithmetic's own `t`): a short walk starts
    /// there, the full walk as before (the answer is the same).
    pub fn clear_before(self, t: f64) -> Self {
        Tracer { clear: t, ..self }
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
        self.occluded_from(&self.departure(from), dir, skip_above)
    }

    /// What every occlusion ray from `from` shares, whatever its direction: worked out once
    /// for the rays [`Tracer::occluded_from`] casts from it.
    #[inline(always)]
    pub fn departure<'r, S: Scalar>(&self, from: &Start<'r, S>) -> Departure<'r, S> {
        Departure::new(self.terrain, self.base, from)
    }

    /// [`Tracer::occluded`] from the start `departure` was worked out from (by this tracer's
    /// terrain and base, see [`Tracer::departure`]): the same answer, the start's share of
    /// the work done once for all its rays.
    pub fn occluded_from<S: Scalar>(
        &self,
        departure: &Departure<'_, S>,
        dir: [f64; 3],
        skip_above: bool,
    ) -> Occlusion {
        if !S::ENCLOSES {
            return self.occluded_in(departure, dir, skip_above);
        }
        occluded_settling(self, departure, dir, skip_above)
    }

    /// [`Tracer::occluded_from`] in `S` alone.
    pub(super) fn occluded_in<S: Scalar>(
        &self,
        departure: &Departure<'_, S>,
        dir: [f64; 3],
        skip_above: bool,
    ) -> Occlusion {
        let origin = &departure.origin;
        let start_triangle = departure.own_triangle(self.terrain, dir);
        let (_, z_max) = self.terrain.z_range();
        if skip_above && dir[2] > 0.0 && origin[2] > S::from_f64(z_max) {
            return Occlusion::default();
        }
        if let Some(short) = self.short_walk(origin, dir, start_triangle) {
            return short;
        }
        let walk = WalkOptions {
            start_triangle,
            exact_start: departure.exact_start(),
            reach: self.reach,
            ..self.walk(Query::Shadow)
        };
        let answer = trace_scalar(self.terrain, origin, &dir.map(S::from_f64), dir, walk);
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
        let (occluded, counters) = super::short_walk::short_walk(
            self.terrain,
            *o,
            dir,
            (self.clear, reach),
            start_triangle,
        )?;
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

/// [`Tracer::occluded_from`] in intervals: a ray with a decision they cannot settle (its
/// own, or one of its start's) is cast again in rationals from the exact hit point (where the
/// start is a hit), and its answer marked as made exactly; otherwise the intervals are left
/// unsettled for the caller to run again.
fn occluded_settling<S: Scalar>(
    tracer: &Tracer<'_>,
    departure: &Departure<'_, S>,
    dir: [f64; 3],
    skip_above: bool,
) -> Occlusion {
    let (answer, is_settled) = settled(|| tracer.occluded_in(departure, dir, skip_above));
    if is_settled && departure.settled {
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
    let again = |from: &Start<'_, Exact>| {
        let departure = tracer.departure(from);
        tracer.occluded_in(&departure, dir, skip_above)
    };
    let again = match departure.from {
        // (The caller runs the whole ray again in rationals, see `run`.)
        Start::Point(_) => None,
        Start::Hit { ray, hit } => exact(ray, hit).map(|hit| again(&Start::Hit { ray, hit: &hit })),
        Start::Near { ray, hit, point } => exact(ray, hit).map(|hit| {
            again(&Start::Near {
                ray,
                hit: &hit,
                point,
            })
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
