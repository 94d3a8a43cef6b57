//! The way a ray goes in one arithmetic, from its start to its answer: a start far off
//! moved in exactly, exact mode's certified `f64` walk tried first, then the clip to the
//! terrain's box, the clearance and reach cut off, and the walk of the method (near cells
//! first where that is exact).

use super::answer::ScalarTrace;
use super::cell_log::{CellLog, Recorded, Unrecorded};
use super::counters::Counters;
use super::exact_mode::{trace_certified, walk_cleared};
use super::far::{far_start, FarStart};
use super::frame::{clip, Levels};
use super::mipmap::near;
use super::near_ray::f64_ray;
use super::options::{Query, WalkOptions};
use super::search::{new_search, slack, Found};
use super::segment::{after_clearance, clearance_start, first_level, within_reach};
use super::short_walk::first_hit::{first_hit, FirstHit};
use super::walks::{choose, Walk, WithWalk};
use super::wedges::Clearance;
use crate::arith::{unsettled, Scalar};
use crate::geometry::Face;
use crate::heightfield::Terrain;
use num_rational::BigRational;

/// Traces a ray given in the traversal's own arithmetic over the terrain alone (for rays that
/// start where another ray hit: exact mode keeps the exact point). `dir_f64` is the direction
/// as given, which picks the octant and axes identically in every arithmetic. For
/// [`Rational`] the caller sets the bound (see [`run`](crate::arith::run)).
pub(super) fn trace_terrain<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    // A certain miss of the terrain (a clearance over the whole ray): nothing to clip or walk,
    // as the walk from the clearance would find.
    let cleared = walk_options.clearance.is_some_and(|c| c.t == f64::INFINITY);
    if cleared && walk_options.method.is_hierarchical() {
        return ScalarTrace::missed(Counters::default());
    }
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
    if let Some(start) = short_start(o, d, &walk_options) {
        let ray = (o, d, dir_f64);
        // (The answer is made in place: moved whole, it is copied out of line.)
        let mut answer = ScalarTrace::missed(Counters::default());
        let answered = match walk_options.record_cells {
            true => trace_short::<S, Recorded>(terrain, ray, start, walk_options, &mut answer),
            false => trace_short::<S, Unrecorded>(terrain, ray, start, walk_options, &mut answer),
        };
        if answered {
            return answer;
        }
    }
    trace_near(terrain, o, d, dir_f64, walk_options)
}

/// The ray `o + t*d` walked short from `start` (see [`short_start`]), its cells noted in a
/// `C`: its answer in `answer` (a miss with no queries before), handed on to the full walk
/// where the short walk stops; `false` where the full walk must answer it from the start.
#[inline(always)]
fn trace_short<S: Scalar, C: CellLog>(
    terrain: &Terrain,
    (o, d, dir_f64): (&[S; 3], &[S; 3], [f64; 3]),
    (o64, d64, from): ([f64; 3], [f64; 3], f64),
    walk_options: WalkOptions,
    answer: &mut ScalarTrace<S>,
) -> bool {
    let mut log = C::default();
    let Some(found) = first_hit(terrain, o64, d64, from, (&mut answer.counters, &mut log)) else {
        return false;
    };
    answer.cells = log.into_cells();
    match found {
        FirstHit::Hit { t, cell, triangle } => {
            answer.hit = Some(Found {
                t: S::from_f64(t),
                cell,
                triangle,
                face: Face::Terrain,
            });
        }
        FirstHit::Missed => {}
        FirstHit::From(t) => {
            let clearance = Some(Clearance { t, level: 0 });
            let walk_options = WalkOptions {
                clearance,
                ..walk_options
            };
            let rest = trace_near(terrain, o, d, dir_f64, walk_options);
            answer.hit = rest.hit;
            answer.counters += rest.counters;
            answer.cells.extend(rest.cells);
            answer.decided_exactly = rest.decided_exactly;
        }
    }
    true
}

/// Where the short walk may answer a ray ([`first_hit`], with the near walk's switch: the
/// same idea, cheaper to set up): a first-hit ray in `f64` from its clearance, its origin,
/// direction and start `t`.
#[inline(always)]
fn short_start<S: Scalar>(
    o: &[S; 3],
    d: &[S; 3],
    walk_options: &WalkOptions,
) -> Option<([f64; 3], [f64; 3], f64)> {
    let (o, d) = (S::as_f64s(o)?, S::as_f64s(d)?);
    let plain = walk_options.query == Query::FirstHit
        && walk_options.near
        && walk_options.reach.is_none()
        && walk_options.start_triangle.is_none()
        && walk_options.exact_start.is_none()
        // (A path along a grid line, or a vertical one, is the run walk's.)
        && d[0] != 0.0
        && d[1] != 0.0;
    // (A clearance at a block level leaves the ray far from the surface: the block walk's.)
    let (from, _) = clearance_start::<S>(walk_options).filter(|&(_, level)| plain && level == 0)?;
    Some((*o, *d, from))
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
        trace_walk::<S, W>(self)
    }
}

/// [`trace_terrain`] along walk `W`, the cells it reaches listed if the options ask.
fn trace_walk<S: Scalar, W: Walk>(ray: RayIn<'_, S>) -> ScalarTrace<S> {
    if ray.walk_options.record_cells {
        return trace_recorded::<S, W>(ray);
    }
    trace_logged::<S, Unrecorded, W>(ray)
}

/// [`trace_walk`] listing the cells.
// (Out of line: the renderer's rays list none.)
#[inline(never)]
fn trace_recorded<S: Scalar, W: Walk>(ray: RayIn<'_, S>) -> ScalarTrace<S> {
    trace_logged::<S, Recorded, W>(ray)
}

/// [`trace_walk`] noting the cells it reaches in a `C`: the same walks whatever `C` is.
#[inline(always)]
fn trace_logged<S: Scalar, C: CellLog, W: Walk>(ray: RayIn<'_, S>) -> ScalarTrace<S> {
    let RayIn {
        terrain,
        o,
        d,
        dir_f64,
        walk_options,
    } = ray;
    // (Once per ray: for rationals each component's enclosure is a fraction's subtraction.)
    let near = f64_ray(o, d);
    let certified =
        near.and_then(|near| trace_certified::<S, C, W>(terrain, o, d, near, &walk_options));
    if let Some(answer) = certified {
        return answer;
    }
    let mut counters = Counters::default();
    let mut clipped = clip(terrain, o, d, dir_f64);
    // (Borrowed where it lies: moved out of the option, the frame is copied whole.)
    let Some(frame) = clipped.as_mut() else {
        counters.bbox.record(false);
        return ScalarTrace::missed(counters);
    };
    counters.bbox.record(true);
    let start = clearance_start::<S>(&walk_options);
    // (The clearance covers the whole segment, or it lies beyond the reach.)
    if !after_clearance(frame, start) || !within_reach(frame, &walk_options) {
        return ScalarTrace::missed(counters);
    }
    let mut search = new_search::<S, C>(
        terrain,
        (o, d, dir_f64),
        near,
        &walk_options,
        counters,
        W::TESTS_RUNS,
    );
    search.widen_by(slack(&o[2], &d[2], &frame.t1));
    let cleared = W::CLEARS_WAY
        && S::EXACT
        && walk_options.reach.is_none()
        && near
            .is_some_and(|near| walk_cleared(terrain, (near, start), dir_f64, frame, &mut search));
    let near = !cleared && near::starts_near::<S>(&walk_options, start.is_some(), frame);
    let walked_near = near
        && match near::near_walk(frame, &mut search, near::NEAR_CELLS) {
            near::Near::Done => true,
            near::Near::From(at) => {
                frame.resume(at);
                false
            }
        };
    if !cleared && !walked_near {
        let levels = Levels {
            top: terrain.mipmap().top(),
            start: first_level(&walk_options, start),
        };
        // Ends by itself or at the answer; both are fine here.
        let _ = W::walk(frame, levels, &mut search);
    }
    ScalarTrace {
        hit: search.found,
        counters: search.counters,
        cells: search.cells.into_cells(),
        decided_exactly: search.decided_exactly,
    }
}

/// [`trace_scalar`] for a ray from far off, walked from `origin`, its point at `t` (see
/// [`far_start`]): its hit's `t` is the walk's plus `t`.
// (Out of line: far rays are rare.)
#[inline(never)]
fn trace_moved<S: Scalar>(
    terrain: &Terrain,
    (origin, t): (&[S; 3], BigRational),
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    // (A clearance is a `t` of the ray as given, in `f64`, as a reach is: the walk makes its
    // own way.)
    let walk_options = WalkOptions {
        clearance: None,
        ..walk_options
    };
    let mut answer = trace_near(terrain, origin, d, dir_f64, walk_options);
    if let Some(hit) = answer.hit.as_mut() {
        match S::from_exact(&t) {
            Some(t) => hit.t = t + hit.t.clone(),
            None => unsettled(),
        }
    }
    answer
}
