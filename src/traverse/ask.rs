//! The public questions' way in: a ray scaled to near unit length, its arithmetic picked
//! once, answered by a [`Tracer`], and an exact hit's `t` solved exactly.

use super::exact_plane::{exact_t, point_over};
use super::options::Query;
use super::options::{Hit, Trace, TraceOptions};
use super::packet::{clear_packet, PacketClearance, LANES};
use super::surface::base_t_exact;
use super::tracer::Tracer;
use super::wedges::Clearance;
use crate::arith::{unsettled, Arith, Generic, Scalar};
use crate::geometry::{times_power_of_two, Face, Ray};
use crate::heightfield::Terrain;
use num_rational::BigRational;

/// The first hit of `ray` (the least `t >= 0` at which it touches the surface), in the
/// options' method and arithmetic.
pub fn trace(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    ask(terrain, ray, options, Query::FirstHit)
}

/// Whether `ray` touches the surface at some `t > 0` (its start does not count), in the
/// options' method and arithmetic: a shadow or any later effect ray. For a ray that starts
/// on the surface where another hit it, exactly there in exact arithmetic, see
/// [`occluded_from_hit`](super::occluded_from_hit).
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
