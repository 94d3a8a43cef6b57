// (The summary line of this module's docs is its `pub mod` line in lib.rs; the empty line
// below starts the rest as a paragraph of its own.)
//!
//! Four methods walk the grid ([`Method`](crate::traverse::Method)): the min-max mipmap's
//! blocks, the hierarchical run walk, the run walk and the cell DDA. Each is one
//! implementation, generic over the arithmetics of [`Scalar`](crate::arith::Scalar)
//! ([`Arith`](crate::arith::Arith)), and counts its queries
//! ([`Counters`](crate::traverse::Counters)).
//!
//! Two questions, one way in each: [`trace`](crate::traverse::trace) (the first hit) and
//! [`occluded`](crate::traverse::occluded) (any hit after the start; from a hit on the surface,
//! [`occluded_from_hit`](crate::traverse::occluded_from_hit)). Both pick the arithmetic once,
//! through [`run`](crate::arith::run), and answer with a
//! [`Tracer`](crate::traverse::Tracer), the same generic inside the renderer runs per pixel.

mod approximation;
mod cell_log;
mod certified;
mod counters;
mod cover;
mod dda;
mod degenerate;
mod exact_mode;
mod exact_start;
mod far;
mod frame;
mod mipmap;
mod options;
mod packet;
mod runs;
mod search;
mod segment;
mod short_walk;
mod surface;
mod tracer;
mod walks;
mod wedges;

pub use counters::{Counters, HitMiss};
pub use cover::covered_cells;
pub use exact_mode::{crosses_plane, plane_t_exact};
use exact_mode::{exact_t, f64_ray, point_over, trace_certified, walk_cleared, F64Ray};
pub use exact_start::PlanePoint;
pub use options::{Hit, Method, Trace, TraceOptions};
use options::{Query, WalkOptions};
pub use packet::{clear_packet, clear_packet_on, PacketClearance, SimdPath, LANES, SIMD_VARIABLE};
pub use tracer::{occluded_from_hit, Occlusion, Start, Tracer};
pub use wedges::{highest_under, Clearance, Profiles, Wedges, WEDGES};
// The number layer, re-exported: every traversal is generic over these.
pub use crate::arith::{
    scalar, settled, Arith, Exact, Interval, Rational, RationalEvents, Scalar, DEFAULT_BOUND,
};
use crate::arith::{unsettled, Generic};

use crate::geometry::{plane_crossing, times_power_of_two, CertainMiss, Face, Ray};
use crate::heightfield::Terrain;
use approximation::Approximation;
use cell_log::{CellLog, Recorded, Unrecorded};
use far::{far_start, trace_moved, FarStart};
use frame::{clip, clip_grown, Frame};
use num_rational::BigRational;
pub use search::Found;
use search::{LazyRaySpace, Search};
use segment::{after_clearance, clearance_start, first_level, within_reach};
use std::ops::ControlFlow;
use std::time::Duration;
use surface::{base_t_exact, trace_scalar};
use walks::{choose, Walk, WithWalk};

/// The first hit of `ray` (the least `t >= 0` at which it touches the surface), in the
/// options' method and arithmetic.
pub fn trace(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    ask(terrain, ray, options, Query::FirstHit)
}

/// Whether `ray` touches the surface at some `t > 0` (its start does not count), in the
/// options' method and arithmetic: a shadow or any later effect ray. For a ray that starts
/// on the surface where another hit it, exactly there in exact arithmetic, see
/// [`occluded_from_hit`].
pub fn occluded(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    ask(terrain, ray, options, Query::Shadow)
}

/// The first hits of `rays`, as [`trace`] answers each: with [`TraceOptions::packets`],
/// neighbours in the slice walk the mipmap together in packets of [`LANES`] (where the
/// arithmetic is `f64` and the method hierarchical), the packet's node tests counted with its
/// first ray's queries.
pub fn trace_packets(terrain: &Terrain, rays: &[Ray], options: &TraceOptions) -> Vec<Trace> {
    let scaled: Vec<(Ray, i32)> = rays.iter().map(Ray::at_unit_scale).collect();
    let packs = options.packets && options.arith == Arith::F64 && options.method.is_hierarchical();
    let mut traces = Vec::with_capacity(rays.len());
    for packet in scaled.chunks(LANES) {
        let lanes: Vec<Ray> = packet.iter().map(|(ray, _)| *ray).collect();
        let cleared = if packs {
            clear_packet(terrain, &lanes, None)
        } else {
            PacketClearance::default()
        };
        for (l, &(ray, k)) in packet.iter().enumerate() {
            let mut trace = ask_behind(
                terrain,
                (&ray, k),
                options,
                Query::FirstHit,
                cleared.lanes[l],
            );
            if l == 0 {
                trace.counters.block += cleared.tests;
            }
            traces.push(trace);
        }
    }
    traces
}

/// Answers `query` for `ray`, its direction scaled to near unit length by a power of two (the
/// same ray, with `t` scaled back).
fn ask(terrain: &Terrain, ray: &Ray, options: &TraceOptions, query: Query) -> Trace {
    if options.packets && query == Query::FirstHit {
        return trace_packets(terrain, std::slice::from_ref(ray), options).remove(0);
    }
    let (scaled, k) = ray.at_unit_scale();
    ask_behind(terrain, (&scaled, k), options, query, None)
}

/// [`ask`] for the ray `scaled` (the ray scaled by `2^k`), from `clearance` if given.
fn ask_behind(
    terrain: &Terrain,
    (scaled, k): (&Ray, i32),
    options: &TraceOptions,
    query: Query,
    clearance: Option<Clearance>,
) -> Trace {
    let mut tracer = Tracer::new(terrain, options.method).with_base(options.base);
    if options.record_cells {
        tracer = tracer.recording_cells();
    }
    let ask = Ask {
        terrain,
        tracer,
        ray: scaled,
        query,
        clearance,
    };
    let (ran, rational) = crate::arith::run(options.arith, &ask);
    let mut trace = ran.output;
    trace.counters.rational_rounded = rational.rounded;
    trace.counters.rational_saturated = rational.saturated;
    if let Some(hit) = trace.hit.as_mut().filter(|_| k != 0) {
        // (The point is the same: only `t` depends on the direction's length.)
        hit.t = times_power_of_two(hit.t, -k);
        if let Some(t) = &mut hit.t_exact {
            let scale =
                BigRational::from_integer(num_bigint::BigInt::from(2).pow(k.unsigned_abs()));
            *t = if k > 0 { &*t / scale } else { &*t * scale };
            hit.t = num_traits::ToPrimitive::to_f64(t).unwrap_or(f64::INFINITY);
        }
    }
    trace
}

/// One ray's query, in whichever arithmetic [`run`](crate::arith::run) picks.
struct Ask<'a> {
    terrain: &'a Terrain,
    tracer: Tracer<'a>,
    ray: &'a Ray,
    query: Query,
    clearance: Option<Clearance>,
}

impl Generic for Ask<'_> {
    type Output = Trace;
    fn run<S: Scalar>(&self) -> Trace {
        let ray = self.ray;
        let (o, d) = (ray.origin().map(S::from_f64), ray.dir().map(S::from_f64));
        let answer = self
            .tracer
            .ask(&o, &d, ray.dir(), self.query, self.clearance);
        let hit = answer.hit.and_then(|found| {
            let cell = [found.cell.0, found.cell.1];
            let hit = |t: f64, t_exact, point| Hit {
                t,
                t_exact,
                point,
                cell,
                triangle: found.triangle,
                face: found.face,
            };
            if !S::ENCLOSES {
                let point = found.point(&o, &d).map(|c| c.to_f64());
                return Some(hit(found.t.to_f64(), found.t.to_exact(), point));
            }
            // Settled decisions are the exact ones: only the hit's `t` remains to be solved
            // exactly, on the one face hit; a ray in a triangle's plane is left to rationals.
            if let Some(base) = self.tracer.base.filter(|_| found.face != Face::Terrain) {
                let shadow = self.query == Query::Shadow;
                let exact = base_t_exact(self.terrain, &base, ray, found.face, shadow);
                let Some((t, t_f64, point)) = exact else {
                    unsettled();
                    return None;
                };
                return Some(hit(t_f64, Some(t), point));
            }
            let Some((above, closing)) = exact_t(self.terrain, ray, cell, found.triangle) else {
                unsettled();
                return None;
            };
            let point = point_over(ray, &above, &closing).map(|n| n.over_to_f64(&closing));
            let t = above.over(&closing);
            let t_f64 = num_traits::ToPrimitive::to_f64(&t).unwrap_or(f64::NAN);
            Some(hit(t_f64, Some(t), point))
        });
        Trace {
            hit,
            counters: answer.counters,
            cells: answer.cells,
        }
    }
}

/// Builds what `method` needs beyond the terrain's shared data (the run walk's row and column
/// maxima are built on first use otherwise); returns the time the method's data took in all,
/// the terrain's shared part included, and its bytes beyond the samples.
pub fn prepare(terrain: &Terrain, method: Method) -> (Duration, usize) {
    match method {
        Method::Mipmap | Method::HierarchicalRuns => (terrain.build_time(), terrain.accel_bytes()),
        Method::Runs => {
            let lines = terrain.lines();
            (terrain.build_time() + lines.build_time(), lines.bytes())
        }
        // The cell test reads the four corner samples: nothing to build.
        Method::Dda => (terrain.build_time(), 0),
    }
}

/// The answer for one ray, in the arithmetic it was traced in.
#[derive(Clone, Debug)]
pub struct ScalarTrace<S> {
    /// The hit, if any, with `t` in the traversal's arithmetic.
    pub hit: Option<Found<S>>,
    /// The queries the ray made.
    pub counters: Counters,
    /// Cells covered, in order (when asked for).
    pub cells: Vec<[usize; 2]>,
    /// A triangle test intervals could not settle was decided exactly, from a start on the
    /// surface given exactly (see [`Start::Hit`]).
    pub decided_exactly: bool,
}

impl<S> ScalarTrace<S> {
    /// No hit, after the queries counted.
    fn missed(counters: Counters) -> Self {
        ScalarTrace {
            hit: None,
            counters,
            cells: Vec::new(),
            decided_exactly: false,
        }
    }
}

/// Traces a ray given in the traversal's own arithmetic over the terrain alone (for rays that
/// start where another ray hit: exact mode keeps the exact point). `dir_f64` is the direction
/// as given, which picks the octant and axes identically in every arithmetic. For
/// [`Rational`] the caller sets the bound (see [`run`](crate::arith::run)).
fn trace_terrain<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    // (A shadow ray from a hit given exactly starts on the surface, never far off.)
    if walk_options.exact_start.is_none() {
        match far_start(terrain, o, d) {
            FarStart::Given => {}
            FarStart::Misses => {
                let mut counters = Counters::default();
                counters.bbox.record(false);
                return ScalarTrace::missed(counters);
            }
            // A reach is a `t` of the ray as given, in `f64`, which a start moved by a
            // fraction keeps only approximately: rationals walk such a ray as given.
            FarStart::Moved { .. } if walk_options.reach.is_some() => {
                if S::ENCLOSES {
                    unsettled();
                    return ScalarTrace::missed(Counters::default());
                }
            }
            FarStart::Moved { origin, t } => {
                return trace_moved(terrain, (&origin, t), d, dir_f64, walk_options);
            }
        }
    }
    trace_near(terrain, o, d, dir_f64, walk_options)
}

/// [`trace_terrain`] from the ray's own origin.
#[inline(always)]
fn trace_near<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    let ray = RayIn {
        terrain,
        o,
        d,
        dir_f64,
        walk_options,
    };
    choose(walk_options.method, ray)
}

/// A ray to trace, in the traversal's arithmetic, and how.
struct RayIn<'a, S> {
    terrain: &'a Terrain,
    o: &'a [S; 3],
    d: &'a [S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
}

impl<S: Scalar> WithWalk for RayIn<'_, S> {
    type Output = ScalarTrace<S>;
    #[inline(always)]
    fn with<W: Walk>(self) -> ScalarTrace<S> {
        let RayIn {
            terrain,
            o,
            d,
            dir_f64,
            walk_options,
        } = self;
        trace_walk::<S, W>(terrain, o, d, dir_f64, walk_options)
    }
}

/// [`trace_terrain`] along walk `W`, the cells it reaches listed if the options ask.
fn trace_walk<S: Scalar, W: Walk>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    if walk_options.record_cells {
        return trace_recorded::<S, W>(terrain, o, d, dir_f64, walk_options);
    }
    trace_logged::<S, Unrecorded, W>(terrain, o, d, dir_f64, walk_options)
}

/// [`trace_walk`] listing the cells.
// (Out of line: the renderer's rays list none.)
#[inline(never)]
fn trace_recorded<S: Scalar, W: Walk>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    trace_logged::<S, Recorded, W>(terrain, o, d, dir_f64, walk_options)
}

/// [`trace_walk`] noting the cells it reaches in a `C`: the same walks whatever `C` is.
#[inline(always)]
fn trace_logged<S: Scalar, C: CellLog, W: Walk>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    // (Once per ray: for rationals each component's enclosure is a fraction's subtraction.)
    let near = f64_ray(o, d);
    let certified =
        near.and_then(|near| trace_certified::<S, C, W>(terrain, o, d, near, &walk_options));
    if let Some(answer) = certified {
        return answer;
    }
    let mut counters = Counters::default();
    let frame = clip(terrain, o, d, dir_f64);
    let Some(mut frame) = frame else {
        counters.bbox.record(false);
        return ScalarTrace::missed(counters);
    };
    counters.bbox.record(true);
    let start = clearance_start::<S>(&walk_options);
    // (The clearance covers the whole segment, or it lies beyond the reach.)
    if !after_clearance(&mut frame, start) || !within_reach(&mut frame, &walk_options) {
        return ScalarTrace::missed(counters);
    }
    let mut search = new_search::<S, C, W>(terrain, o, d, dir_f64, near, &walk_options, counters);
    search.widen_by(search::slack(&o[2], &d[2], &frame.t1));
    let cleared = W::CLEARS_WAY
        && S::EXACT
        && walk_options.reach.is_none()
        && near
            .is_some_and(|near| walk_cleared(terrain, (near, start), dir_f64, &frame, &mut search));
    let near = !cleared && mipmap::starts_near::<S>(&walk_options, start.is_some(), &frame);
    let walked_near = near
        && match mipmap::near_walk(&frame, &mut search, mipmap::NEAR_CELLS) {
            mipmap::Near::Done => true,
            mipmap::Near::From(at) => {
                frame.resume(at);
                false
            }
        };
    if !cleared && !walked_near {
        let level = first_level(&walk_options, start);
        // Ends by itself or at the answer; both are fine here.
        let _ = W::walk(&frame, level, &mut search);
    }
    ScalarTrace {
        hit: search.found,
        counters: search.counters,
        cells: search.cells.into_cells(),
        decided_exactly: search.decided_exactly,
    }
}

/// A search for the ray's answer, before any walk.
// (Inlined by hand: called once per ray, but `Search` is large, and out of line its
// construction costs every ray.)
#[inline(always)]
fn new_search<'a, S: Scalar, C: CellLog, W: Walk>(
    terrain: &'a Terrain,
    o: &'a [S; 3],
    d: &'a [S; 3],
    dir_f64: [f64; 3],
    near: Option<F64Ray>,
    options: &WalkOptions,
    counters: Counters,
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
        moves_away: search::moves_away(&d[2], false),
        query: options.query,
        run_test: W::TESTS_RUNS,
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
