//! Exact arithmetic's walks before intervals and rationals (see
//! [`Settling`](crate::arith::Settling)): an `f64` walk that answers exact rays alone where it
//! can certify them ([`certified`](super::certified)), or clears the way for the exact walk.
//! (The hit's `t` is solved exactly in [`exact_plane`](super::exact_plane); a shadow ray that
//! intervals cannot settle is cast again from the exact hit point by the
//! [`Tracer`](super::Tracer).)

use super::answer::ScalarTrace;
use super::approximation::Approximation;
use super::cell_log::CellLog;
use super::certified;
use super::counters::Counters;
use super::frame::{clip_grown, Frame, Levels};
use super::mipmap;
use super::mipmap::stretches;
use super::near_ray::F64Ray;
use super::options::{Query, WalkOptions};
use super::search::{new_search, Search};
use super::segment::{after_clearance, clearance_start};
use super::walks::Walk;
use crate::arith::Scalar;
use crate::heightfield::Terrain;
use std::ops::ControlFlow;

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
    let dir = near.2;
    let mut counters = Counters::default();
    let Some(mut frame) = clip_near(terrain, &near, dir) else {
        counters.bbox.record(false);
        return Some(ScalarTrace::missed(counters));
    };
    counters.bbox.record(true);
    // The exact segment ends at the reach: the walk covers it, and a little past it.
    if let Some(reach) = options.reach {
        if !frame.keep(f64::NEG_INFINITY, reach + 4.0 * f64::EPSILON * reach.abs()) {
            return None;
        }
    }
    if !mipmap::has_blocks(&frame) {
        return None;
    }
    let start = clearance_start::<S>(options);
    // (The clearance covers the whole segment.)
    if !after_clearance(&mut frame, start) {
        return Some(ScalarTrace::missed(counters));
    }
    let near_ray = Approximation::along(frame, near, start);
    let mut search = new_search::<S, C>(
        terrain,
        (o, d, dir),
        Some(near),
        options,
        counters,
        W::TESTS_RUNS,
    );
    // Ends by itself or at the answer; both are fine here.
    let _ = certified::certify(&near_ray, &mut search, W::certify)?;
    if search.tied && options.query == Query::FirstHit {
        return None;
    }
    // A hit past the reach counts where the exact walk reaches its cell before the reach,
    // which only the exact walk knows: it answers such a ray. Every hit up to the reach it
    // finds too, and no other: the cells whose triangles it tests are among this walk's.
    if let (Some(reach), Some(found)) = (options.reach, &search.found) {
        let (t, radius) = found.t.f64_enclosure()?;
        let within = (t + radius).next_up() <= reach;
        if !within {
            return None;
        }
    }
    Some(ScalarTrace {
        hit: search.found,
        counters: search.counters,
        cells: search.cells.into_cells(),
        decided_exactly: search.decided_exactly,
    })
}

/// The mipmap walk in an arithmetic without rounding, where an `f64` walk clears the way
/// (see [`clear_way`](stretches::clear_way)): the exact walk follows only the stretches the `f64` walk
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
    let _ = stretches::clear_way(
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
                let levels = Levels {
                    top: search.terrain.mipmap().top(),
                    start: Some(0),
                };
                mipmap::walk(&part, search, levels)?;
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
