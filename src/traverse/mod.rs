// (The summary line of this module's docs is its `pub mod` line in lib.rs; the empty line
// below starts the rest as a paragraph of its own.)
//!
//! Four methods walk the grid ([`Method`](crate::traverse::Method)): the min-max mipmap's
//! blocks, the hierarchical run walk, the run walk and the cell DDA. Each is one
//! implementation, generic over the arithmetics of [`Scalar`](crate::arith::Scalar)
//! ([`Arith`](crate::arith::Arith)), and counts its queries
//! ([`Counters`](crate::traverse::Counters)).

mod approximation;
mod beam;
mod certified;
mod counters;
mod dda;
mod degenerate;
mod exact_start;
mod frame;
mod mipmap;
mod options;
mod runs;
mod search;

pub use beam::{Beam, Clearance};
pub use counters::{Counters, HitMiss};
pub use exact_start::PlanePoint;
pub use options::{Hit, Method, Query, Trace, TraceOptions, WalkOptions};
// The number layer, re-exported: every traversal is generic over these.
pub use crate::arith::{
    scalar, settled, with_bound, Arith, Exact, Interval, Rational, RationalEvents, Scalar,
    DEFAULT_BOUND,
};

use crate::arith::dyadic::Dyadic;
use crate::geometry::{clip_to_box, plane_crossing, times_power_of_two, CertainMiss, Ray};
use crate::heightfield::Terrain;
use approximation::Approximation;
use frame::{Frame, Span};
use num_rational::BigRational;
pub use search::Found;
use search::{span_cells, LazyRaySpace, Search};
use std::ops::ControlFlow;
use std::time::Duration;

/// Traces one ray.
pub fn trace(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    let (scaled, k) = ray.at_unit_scale();
    let mut trace = trace_as_given(terrain, &scaled, options);
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

/// Traces one ray with its direction as given.
fn trace_as_given(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    match options.arith {
        Arith::F32 => trace_in::<f32>(terrain, ray, options),
        Arith::F64 => trace_in::<f64>(terrain, ray, options),
        Arith::Exact => trace_exact(terrain, ray, options),
        Arith::Rational { bound } => {
            let (mut trace, events) =
                with_bound(bound, || trace_in::<Rational>(terrain, ray, options));
            trace.counters.rational_rounded = events.rounded;
            trace.counters.rational_saturated = events.saturated;
            trace
        }
    }
}

/// Every cell the walk of `method` covers for the whole clipped ray, in order, with no culling
/// and no stop at a hit: in exact arithmetic, exactly the cells the projected segment touches.
pub fn covered_cells(
    terrain: &Terrain,
    ray: &Ray,
    method: Method,
    arith: Arith,
) -> Vec<[usize; 2]> {
    fn cover<S: Scalar>(terrain: &Terrain, ray: &Ray, method: Method) -> Vec<[usize; 2]> {
        let (o, d) = (ray.origin().map(S::from_f64), ray.dir().map(S::from_f64));
        let Some(frame) = clip(terrain, &o, &d, ray.dir()) else {
            return Vec::new();
        };
        let mut cells = Vec::new();
        walk(&frame, method, &mut |span: Span<S>| {
            cells.extend(span_cells(&frame, &span).map(|(i, j)| [i, j]));
            ControlFlow::Continue(())
        });
        cells
    }
    match arith {
        Arith::F32 => cover::<f32>(terrain, ray, method),
        Arith::F64 => cover::<f64>(terrain, ray, method),
        Arith::Exact => match settled(|| cover::<Interval>(terrain, ray, method)) {
            (cells, true) => cells,
            (_, false) => cover::<Exact>(terrain, ray, method),
        },
        Arith::Rational { bound } => {
            with_bound(bound, || cover::<Rational>(terrain, ray, method)).0
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

/// The ray clipped to the terrain's box, in the octant frame.
fn clip<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
) -> Option<Frame<S>> {
    clip_grown(terrain, o, d, dir_f64, [0.0; 3])
}

/// The ray clipped to the terrain's box grown by `grow` on every side.
fn clip_grown<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    grow: [f64; 3],
) -> Option<Frame<S>> {
    let field = terrain.field();
    let (w, h) = (field.width(), field.height());
    let (z_lo, z_hi) = terrain.z_range();
    // Rounded outwards: the grown box contains every point within `grow` of the box.
    let outwards = |x: f64, by: f64, step: fn(f64) -> f64| if by > 0.0 { step(x) } else { x };
    let (lo, hi) = ([0.0, 0.0, z_lo], [(w - 1) as f64, (h - 1) as f64, z_hi]);
    let lo = [0, 1, 2].map(|k| S::from_f64(outwards(lo[k] - grow[k], grow[k], f64::next_down)));
    let hi = [0, 1, 2].map(|k| S::from_f64(outwards(hi[k] + grow[k], grow[k], f64::next_up)));
    let mut clipped = clip_to_box(o, d, &lo, &hi)?;
    // Floats lengthen the segment by their own rounding, so that the last cells before a box
    // face (flat ground at the lowest height) are not cut off.
    clipped.t1 = clipped.t1.past_rounding();
    Some(Frame::new(o, d, dir_f64, clipped, (w, h)))
}

fn walk<S: Scalar>(
    frame: &Frame<S>,
    method: Method,
    visit: &mut impl FnMut(Span<S>) -> ControlFlow<()>,
) {
    // Either walk ends by itself or because `visit` broke; both are fine here.
    let _ = match method {
        // Without culling the hierarchies have nothing to skip: their cells are the run walk's.
        Method::Runs | Method::Mipmap | Method::HierarchicalRuns => runs::walk(frame, visit),
        Method::Dda => dda::walk(frame, visit),
    };
}

/// Exact arithmetic: intervals first; only a ray with a decision they cannot settle is traced
/// again in rationals. Settled decisions are the exact ones, so only the hit's `t` remains to
/// be computed exactly, on the one triangle hit.
fn trace_exact(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    let (mut fast, is_settled) = settled(|| trace_in::<Interval>(terrain, ray, options));
    if !is_settled {
        return trace_in::<Exact>(terrain, ray, options);
    }
    let Some(hit) = fast.hit.take() else {
        return fast;
    };
    match exact_t(terrain, ray, hit.cell, hit.triangle) {
        Some((above, closing)) => {
            let point = point_over(ray, &above, &closing).map(|n| n.over_to_f64(&closing));
            let t = above.over(&closing);
            fast.hit = Some(Hit {
                t: num_traits::ToPrimitive::to_f64(&t).unwrap_or(f64::NAN),
                point,
                t_exact: Some(t),
                ..hit
            });
            fast
        }
        // The ray lies in the triangle's plane (or, impossibly, misses it): rationals decide.
        None => trace_in::<Exact>(terrain, ray, options),
    }
}

/// The `t` where the ray meets the plane of triangle `k` of `cell`, exactly; `None` if it
/// runs parallel.
pub fn plane_t_exact(
    terrain: &Terrain,
    ray: &Ray,
    cell: (usize, usize),
    k: u8,
) -> Option<BigRational> {
    let (above, closing) = exact_t(terrain, ray, [cell.0, cell.1], k)?;
    Some(above.over(&closing))
}

/// Whether a ray of direction `dir` crosses the plane of triangle `k` of `cell` (does not
/// run parallel to it), decided exactly.
pub fn crosses_plane(terrain: &Terrain, cell: (usize, usize), k: u8, dir: [f64; 3]) -> bool {
    let zero = || Dyadic::from_i64(0);
    let (_, closing) = plane_crossing(
        k,
        terrain.corner_heights(cell.0, cell.1).map(Dyadic::from_f64),
        (zero(), zero()),
        [zero(), zero(), zero()],
        dir.map(Dyadic::from_f64),
    );
    !closing.is_zero()
}

/// Where the ray meets the plane of triangle `k` of `cell`, exactly, as `t = above / closing`;
/// `None` if it runs parallel.
fn exact_t(terrain: &Terrain, ray: &Ray, [i, j]: [usize; 2], k: u8) -> Option<(Dyadic, Dyadic)> {
    let (above, closing) = plane_crossing(
        k,
        terrain.corner_heights(i, j).map(Dyadic::from_f64),
        (Dyadic::from_i64(i as i64), Dyadic::from_i64(j as i64)),
        ray.origin().map(Dyadic::from_f64),
        ray.dir().map(Dyadic::from_f64),
    );
    (!closing.is_zero()).then_some((above, closing))
}

/// The point `o + d * above/closing` of `ray`: each coordinate's numerator over `closing`,
/// exactly.
fn point_over(ray: &Ray, above: &Dyadic, closing: &Dyadic) -> [Dyadic; 3] {
    let (o, d) = (ray.origin(), ray.dir());
    [0, 1, 2]
        .map(|k| Dyadic::from_f64(o[k]) * closing.clone() + Dyadic::from_f64(d[k]) * above.clone())
}

fn trace_in<S: Scalar>(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    let (o, d) = (ray.origin().map(S::from_f64), ray.dir().map(S::from_f64));
    let answer = trace_scalar(terrain, &o, &d, ray.dir(), options.walk());
    let hit = answer.hit.map(|found| {
        let point = found.point(&o, &d).map(|c| c.to_f64());
        Hit {
            t: found.t.to_f64(),
            t_exact: found.t.to_exact(),
            point,
            cell: [found.cell.0, found.cell.1],
            triangle: found.triangle,
        }
    });
    Trace {
        hit,
        counters: answer.counters,
        cells: answer.cells,
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
    /// A triangle test intervals could not settle was decided exactly (see
    /// [`WalkOptions::exact_start`]).
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

/// Traces a ray given in the traversal's own arithmetic (for rays that start where another
/// ray hit: exact mode keeps the exact point). `dir_f64` is the direction as given, which
/// picks the octant and axes identically in every arithmetic. For [`Rational`] the caller
/// sets the bound, see [`with_bound`].
pub fn trace_scalar<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    // (Once per ray: for rationals each component's enclosure is a fraction's subtraction.)
    let near = f64_ray(o, d);
    let certified = near.and_then(|near| trace_certified(terrain, o, d, near, &walk_options));
    if let Some(answer) = certified {
        return answer;
    }
    let mut counters = Counters::default();
    let frame = clip(terrain, o, d, dir_f64);
    let Some(frame) = frame else {
        counters.bbox.record(false);
        return ScalarTrace::missed(counters);
    };
    counters.bbox.record(true);
    let start = beam_start::<S>(&walk_options);
    // (The beam cleared the whole segment.)
    let Some(frame) = after_beam(frame, start) else {
        return ScalarTrace::missed(counters);
    };
    let mut search = new_search(terrain, o, d, dir_f64, near, &walk_options, counters);
    search.widen_by(search::slack(&o[2], &d[2], &frame.t1));
    if walk_options.method == Method::Mipmap {
        // (A walk asked to list its cells walks them all.)
        let cleared = S::EXACT
            && !walk_options.record_cells
            && near.is_some_and(|near| {
                walk_cleared(terrain, (near, start), dir_f64, &frame, &mut search)
            });
        if !cleared {
            let level = first_level(&walk_options, start);
            // Ends by itself or at the answer; both are fine here.
            let _ = mipmap::walk(&frame, &mut search, level);
        }
    } else if walk_options.method == Method::HierarchicalRuns {
        let level = first_level(&walk_options, start);
        // Ends by itself or at the answer; both are fine here.
        let _ = mipmap::walk_runs(&frame, &mut search, level);
    } else {
        walk(&frame, walk_options.method, &mut |span| {
            search.span(&frame, span)
        });
    }
    ScalarTrace {
        hit: search.found,
        counters: search.counters,
        cells: search.cells.unwrap_or_default(),
        decided_exactly: search.decided_exactly,
    }
}

/// A search for the ray's answer, before any walk.
// (Inlined by hand: called once per ray, but `Search` is large, and out of line its
// construction costs every ray.)
#[inline(always)]
fn new_search<'a, S: Scalar>(
    terrain: &'a Terrain,
    o: &'a [S; 3],
    d: &'a [S; 3],
    dir_f64: [f64; 3],
    near: Option<F64Ray>,
    options: &WalkOptions,
    counters: Counters,
) -> Search<'a, S> {
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
        run_test: options.method == Method::Runs,
        counters,
        found: None,
        tied: false,
        cells: options.record_cells.then(Vec::new),
        start_triangle: options.start_triangle,
        // (`S::EXACT` is asked here as well as where the start is used, which compiles it out
        // of the rounding arithmetics, `f64` included.)
        exact_start: options
            .exact_start
            .filter(|_| S::EXACT && options.query == Query::Shadow),
        decided_exactly: false,
    }
}

/// A ray in an arithmetic without rounding, answered from an `f64` walk alone (see
/// [`certified::certify`]): `None` where that cannot answer (the path crosses no blocks, a
/// walk must list its cells, or two triangles are hit at the same `t`, which the exact walk's
/// order of cells decides).
fn trace_certified<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    near: F64Ray,
    options: &WalkOptions,
) -> Option<ScalarTrace<S>> {
    if options.record_cells {
        return None;
    }
    let dir = near.2;
    let mut counters = Counters::default();
    let Some(frame) = clip_near(terrain, &near, dir) else {
        counters.bbox.record(false);
        return Some(ScalarTrace::missed(counters));
    };
    counters.bbox.record(true);
    if !mipmap::has_blocks(&frame) {
        return None;
    }
    let start = beam_start::<S>(options);
    // (The beam cleared the whole segment.)
    let Some(frame) = after_beam(frame, start) else {
        return Some(ScalarTrace::missed(counters));
    };
    let near_ray = Approximation::along(frame, near, start);
    let mut search = new_search(terrain, o, d, dir, Some(near), options, counters);
    // Ends by itself or at the answer; both are fine here.
    let _ = certified::certify(options.method, &near_ray, &mut search);
    if search.tied && options.query == Query::FirstHit {
        return None;
    }
    Some(ScalarTrace {
        hit: search.found,
        counters: search.counters,
        cells: Vec::new(),
        decided_exactly: search.decided_exactly,
    })
}

/// Where the hierarchical walk starts when a beam around the ray cleared the way
/// ([`WalkOptions::beam`]): `t` moved down by more than the rounding to `S` (the walk may
/// start early, never late), and the level. The other methods walk the whole segment: they
/// are what the hierarchy is measured against.
fn beam_start<S: Scalar>(options: &WalkOptions) -> Option<(f64, u32)> {
    let Clearance { t, level } = options.beam.filter(|b| b.t > 0.0)?;
    (options.method.is_hierarchical()).then(|| (t - 4.0 * S::rounding_error(t), level))
}

/// The level a hierarchical walk starts at where it knows better than the default: a shadow
/// ray starts on the surface, where every block around it fails its test; a camera ray at
/// the level its beam stopped at.
fn first_level(options: &WalkOptions, start: Option<(f64, u32)>) -> Option<u32> {
    match start {
        _ if options.query == Query::Shadow => Some(0),
        Some((_, level)) => Some(level),
        None => None,
    }
}

/// The part of the segment from [`beam_start`]'s `t` on (all of it without a beam); `None` if
/// the beam cleared it all.
fn after_beam<S: Scalar>(frame: Frame<S>, start: Option<(f64, u32)>) -> Option<Frame<S>> {
    match start {
        Some((from, _)) => frame.stretch(from, f64::INFINITY),
        None => Some(frame),
    }
}

/// The mipmap walk in an arithmetic without rounding, where an `f64` walk clears the way
/// (see [`mipmap::clear_way`]): the exact walk follows only the stretches the `f64` walk
/// could not clear. `false` where it cannot help (the ray is not near enough an `f64` ray).
fn walk_cleared<S: Scalar>(
    terrain: &Terrain,
    near: (F64Ray, Option<(f64, u32)>),
    dir_f64: [f64; 3],
    frame: &Frame<S>,
    search: &mut Search<'_, S>,
) -> bool {
    let Some(near) = approximation(terrain, near, dir_f64) else {
        return false;
    };
    let mut clearing = Counters::default();
    // Ends by itself or at the answer; both are fine here.
    let _ = mipmap::clear_way(
        &near,
        terrain,
        search.query,
        &mut clearing,
        &mut |stretch| {
            let (from, to) = stretch.widened();
            // A hit before the stretch is the first.
            if search.found.as_ref().is_some_and(|f| f.t.to_f64() < from) {
                return ControlFlow::Break(());
            }
            if let Some(part) = frame.stretch(from, to) {
                mipmap::walk(&part, search, Some(0))?;
            }
            // The walk covered every cell the path touches up to `to`: a hit before that is
            // the first. One past it (in a cell the walk ended in) waits for the next
            // stretch, whose cells may be touched before it.
            match &search.found {
                Some(f) if f.t.to_f64() < to - stretch.margin / 2.0 => ControlFlow::Break(()),
                _ => ControlFlow::Continue(()),
            }
        },
    );
    search.counters += clearing;
    true
}

/// Origin, radius per axis and direction of an `f64` ray near an exact one (see [`f64_ray`]).
type F64Ray = ([f64; 3], [f64; 3], [f64; 3]);

/// An `f64` ray near one in an arithmetic without rounding: its origin, how far the exact
/// origin may be from it per axis, and its direction, which must be the exact one. `None`
/// for the rounding arithmetics, and where the direction is not an `f64` exactly.
fn f64_ray<S: Scalar>(o: &[S; 3], d: &[S; 3]) -> Option<F64Ray> {
    if !S::EXACT {
        return None;
    }
    let exact = |c: &S| c.f64_enclosure().filter(|&(_, r)| r == 0.0).map(|(x, _)| x);
    let dir = [exact(&d[0])?, exact(&d[1])?, exact(&d[2])?];
    let [x, y, z] = [&o[0], &o[1], &o[2]].map(|c| c.f64_enclosure());
    let [(x, rx), (y, ry), (z, rz)] = [x?, y?, z?];
    Some(([x, y, z], [rx, ry, rz], dir))
}

/// The `f64` ray near an exact one (see [`f64_ray`]) clipped to the terrain's box grown so
/// that its segment covers the exact one's: every point of the exact segment is within
/// `radius` of the `f64` ray at the same `t`, and the clip's face crossings `(face - o) / d`
/// are rounded (twice, a relative `EPSILON` in all), which the growth of each face by
/// `2 * EPSILON * (|face| + |o|)` covers. (Without that room, a ray that touches the box only
/// at an edge, exactly, could be clipped away.)
fn clip_near(
    terrain: &Terrain,
    (origin, radius, dir): &F64Ray,
    dir_f64: [f64; 3],
) -> Option<Frame<f64>> {
    let field = terrain.field();
    let (z_lo, z_hi) = terrain.z_range();
    let faces = [
        (field.width() - 1) as f64,
        (field.height() - 1) as f64,
        z_lo.abs().max(z_hi.abs()),
    ];
    let grow = [0, 1, 2].map(|k| {
        let rounding = 2.0 * f64::EPSILON * (faces[k] + origin[k].abs()) + f64::MIN_POSITIVE;
        radius[k] + rounding
    });
    clip_grown(terrain, origin, dir, dir_f64, grow)
}

/// The `f64` ray an `f64` walk follows to clear the way for the mipmap, from [`f64_ray`]'s,
/// from the exact walk's beam start and level if it has them.
fn approximation(
    terrain: &Terrain,
    (near, start): (F64Ray, Option<(f64, u32)>),
    dir_f64: [f64; 3],
) -> Option<Approximation> {
    let frame = clip_near(terrain, &near, dir_f64)?;
    let frame = after_beam(frame, start)?;
    Some(Approximation::along(frame, near, start))
}
