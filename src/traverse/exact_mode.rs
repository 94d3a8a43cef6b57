//! Exact arithmetic's strategy beyond intervals first and rationals where they cannot settle
//! (see [`Settling`](crate::arith::Settling)): an `f64` walk that answers exact rays alone
//! where it can certify them ([`certified`](super::certified)), or clears the way for the
//! exact walk; the hit's `t` solved exactly from its triangle's plane; and a shadow ray from a
//! hit cast again in rationals from the exact hit point when intervals cannot settle it (its
//! single unsettled triangle tests are decided in [`exact_start`](super::exact_start)).

use super::cell_log::CellLog;
use super::walks::Walk;
use super::*;
use crate::arith::dyadic::Dyadic;
use crate::arith::settled;

/// [`Tracer::occluded`] in intervals: a ray with a decision they cannot settle is cast again
/// in rationals from the exact hit point (where the start is a hit), and its answer marked
/// as made exactly; otherwise the intervals are left unsettled for the caller to run again.
pub(super) fn occluded_settling<S: Scalar>(
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
pub(super) fn exact_t(
    terrain: &Terrain,
    ray: &Ray,
    [i, j]: [usize; 2],
    k: u8,
) -> Option<(Dyadic, Dyadic)> {
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
pub(super) fn point_over(ray: &Ray, above: &Dyadic, closing: &Dyadic) -> [Dyadic; 3] {
    let (o, d) = (ray.origin(), ray.dir());
    [0, 1, 2]
        .map(|k| Dyadic::from_f64(o[k]) * closing.clone() + Dyadic::from_f64(d[k]) * above.clone())
}

/// A ray in an arithmetic without rounding, answered from an `f64` walk alone (see
/// [`certified::certify`]), its cells noted in a `C`: `None` where that cannot answer (the
/// path crosses no blocks, or two triangles are hit at the same `t`, which the exact walk's
/// order of cells decides).
pub(super) fn trace_certified<S: Scalar, C: CellLog, W: Walk>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    near: F64Ray,
    options: &WalkOptions,
) -> Option<ScalarTrace<S>> {
    // (Its `f64` walk knows no reach: the exact walk answers a ray with one.)
    if options.reach.is_some() {
        return None;
    }
    let dir = near.2;
    let mut counters = Counters::default();
    let Some(mut frame) = clip_near(terrain, &near, dir) else {
        counters.bbox.record(false);
        return Some(ScalarTrace::missed(counters));
    };
    counters.bbox.record(true);
    if !mipmap::has_blocks(&frame) {
        return None;
    }
    let start = clearance_start::<S>(options);
    // (The clearance covers the whole segment.)
    if !after_clearance(&mut frame, start) {
        return Some(ScalarTrace::missed(counters));
    }
    let near_ray = Approximation::along(frame, near, start);
    let mut search = new_search::<S, C, W>(terrain, o, d, dir, Some(near), options, counters);
    // Ends by itself or at the answer; both are fine here.
    let _ = certified::certify::<S, C, W>(&near_ray, &mut search)?;
    if search.tied && options.query == Query::FirstHit {
        return None;
    }
    Some(ScalarTrace {
        hit: search.found,
        counters: search.counters,
        cells: search.cells.into_cells(),
        decided_exactly: search.decided_exactly,
    })
}

/// The mipmap walk in an arithmetic without rounding, where an `f64` walk clears the way
/// (see [`mipmap::clear_way`]): the exact walk follows only the stretches the `f64` walk
/// could not clear (the cells it reaches noted, as the exact walk's everywhere). `false` where
/// it cannot help (the ray is not near enough an `f64` ray).
pub(super) fn walk_cleared<S: Scalar, C: CellLog>(
    terrain: &Terrain,
    near: (F64Ray, Option<(f64, u32)>),
    dir_f64: [f64; 3],
    frame: &Frame<S>,
    search: &mut Search<'_, S, C>,
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
pub(super) type F64Ray = ([f64; 3], [f64; 3], [f64; 3]);

/// An `f64` ray near one in an arithmetic without rounding: its origin, how far the exact
/// origin may be from it per axis, and its direction, which must be the exact one. `None`
/// for the rounding arithmetics, and where the direction is not an `f64` exactly.
pub(super) fn f64_ray<S: Scalar>(o: &[S; 3], d: &[S; 3]) -> Option<F64Ray> {
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
/// from the exact walk's clearance start and level if it has them.
fn approximation(
    terrain: &Terrain,
    (near, start): (F64Ray, Option<(f64, u32)>),
    dir_f64: [f64; 3],
) -> Option<Approximation> {
    let mut frame = clip_near(terrain, &near, dir_f64)?;
    if !after_clearance(&mut frame, start) {
        return None;
    }
    Some(Approximation::along(frame, near, start))
}
