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

mod answer;
mod approximation;
mod cell_log;
mod certified;
mod counters;
mod cover;
mod dda;
mod degenerate;
mod engine;
mod exact_mode;
mod exact_plane;
mod exact_start;
mod far;
mod frame;
mod mipmap;
mod near_ray;
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
pub use exact_plane::{crosses_plane, plane_t_exact};
use exact_plane::{exact_t, point_over};
pub use exact_start::PlanePoint;
use options::Query;
pub use options::{Hit, Method, Trace, TraceOptions};
pub use packet::{clear_packet, clear_packet_on, PacketClearance, SimdPath, LANES, SIMD_VARIABLE};
pub use tracer::{occluded_from_hit, Occlusion, Start, Tracer};
pub use wedges::{highest_under, Clearance, Profiles, Wedges, WEDGES};
// The number layer, re-exported: every traversal is generic over these.
pub use crate::arith::{
    scalar, settled, Arith, Exact, Interval, Rational, RationalEvents, Scalar, DEFAULT_BOUND,
};
use crate::arith::{unsettled, Generic};

use crate::geometry::{times_power_of_two, Face, Ray};
use crate::heightfield::Terrain;
pub use answer::ScalarTrace;
use num_rational::BigRational;
pub use search::Found;
use std::time::Duration;
use surface::base_t_exact;

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
