//! A cone towards the sun that provably clears the terrain, or that the terrain provably
//! blocks whole.
//!
//! Clear: over a first short stretch from the start every direction rises faster than any
//! triangle under it along its azimuth, and beyond it a march along the cone finds the cone's
//! lowest point over each stretch above the surface under the stretch's footprint (the
//! triangles' own planes under a small footprint, the mipmap's maxima under a large one),
//! until the cone leaves the map or climbs above all terrain.
//!
//! Blocked: every direction is above the surface at one horizontal distance from the start
//! and below it at a farther one, so each crosses the surface in between and touches it after
//! its start.
//!
//! Why the shadow ray's answer is then "occluded", in every arithmetic: the surface is
//! continuous over a map without holes, so a ray above it at `r1` and below it at `r2` meets a
//! triangle at a point between, strictly after its start. Both heights are compared with a
//! margin far above the rounding of a walk in `f64`, so the crossing is a clear one that the
//! watertight triangle test finds. The ray's own triangle, which the walk may leave untested,
//! is not the one crossed: every direction rises away from its plane and is above it at `r1`.
//!
//! Where to look for `r2` is a guess, checked: just past where the cone's highest direction
//! first meets the surface, traced once.

use super::horizon::Sector;
use crate::geometry::{gradient, plane_height};
use crate::heightfield::Terrain;
use crate::traverse::highest_under;
use glam::{DVec2, DVec3};

/// Height margin of the comparisons, relative to the terrain's height span plus one.
const MARGIN: f64 = 1e-6;

/// Room added to a horizontal distance for rounding, in cells.
const ROOM: f64 = 1e-6;

/// Horizontal distances past the highest direction's first touch at which the cone is
/// looked for below the surface, in cells.
const PAST_TOUCH: [f64; 4] = [0.25, 1.0, 4.0, 16.0];

/// Horizontal distances from the start at which the cone is looked for above the surface.
const NEAR_START: [f64; 3] = [1.0 / 64.0, 1.0 / 8.0, 1.0];

/// The most stretches one march tests (a few dozen settle it; this bounds one that cannot).
const MARCH_STEPS: u32 = 200;

/// The first stretch of a march, and the shortest one it tests, in cells: where a stretch
/// this short may touch the surface, the cone is left to its rays.
const SHORTEST_STRETCH: f64 = 0.125;

/// A footprint spanning at most this many cells each way is compared with the triangles'
/// planes, a larger one with the mipmap's maxima.
const PLANES_UP_TO: f64 = 2.0;

/// The directions within `half` (radians) of the unit vector `axis`, as seen from a start on
/// the surface, with what the proof needs of them.
#[derive(Clone, Copy, Debug)]
pub struct Cone {
    /// The start (in grid coordinates, on or near the surface).
    pub start: DVec3,
    /// The axis's horizontal direction, unit.
    along: DVec2,
    /// The most any direction's azimuth differs from the axis's (radians, with room).
    across: f64,
    /// The azimuths of the directions.
    sector: Sector,
    /// The least and the greatest elevation's tangent over the directions.
    lowest: f64,
    highest: f64,
}

impl Cone {
    /// The cone of half-angle `half` around `axis` from `start`; `None` where it holds the
    /// zenith or nearly (no azimuth bound) or reaches up to it.
    pub fn new(start: DVec3, axis: DVec3, half: f64) -> Option<Cone> {
        let horizontal = DVec2::new(axis.x, axis.y);
        let across = half.sin() / horizontal.length();
        if across.is_nan() || across >= 0.9 {
            return None;
        }
        let elevation = axis.z.clamp(-1.0, 1.0).asin();
        let spread = half * (1.0 + 1e-9) + 1e-12;
        let (low, high) = (elevation - spread, elevation + spread);
        if high >= 1.5 {
            return None;
        }
        let across = across.asin() * (1.0 + 1e-6) + 1e-9;
        Some(Cone {
            start,
            along: horizontal.normalize(),
            across,
            sector: Sector::around(horizontal, across),
            lowest: low.tan(),
            highest: high.tan(),
        })
    }

    /// The same cone from `start`.
    pub fn moved_to(self, start: DVec3) -> Cone {
        Cone { start, ..self }
    }

    /// The direction of the highest elevation at the axis's azimuth, unit.
    pub fn highest_direction(&self) -> DVec3 {
        DVec3::new(self.along.x, self.along.y, self.highest).normalize()
    }

    /// Where the cone's directions are at horizontal distance `r`: the centre of a square
    /// holding every one of them, and its half-width.
    fn footprint(&self, r: f64) -> (DVec2, f64) {
        let centre = DVec2::new(self.start.x, self.start.y) + self.along * r;
        (centre, r * self.across + ROOM)
    }
}

/// Whether every direction of `cone` provably clears the surface (none touches it after its
/// start).
pub fn clear(terrain: &Terrain, cone: &Cone) -> bool {
    let (z_lo, z_hi) = terrain.z_range();
    let margin = MARGIN * (1.0 + z_hi - z_lo);
    let o = DVec2::new(cone.start.x, cone.start.y);
    // Over the first stretch the cone stays above the surface under it, or it starts on or
    // above the surface and the surface there (a convex footprint holding the segment from
    // the start to each of its points) rises no faster than its steepest triangle along the
    // cone's azimuths.
    let first = stretch(cone, 0.0, SHORTEST_STRETCH);
    let lowest_first = cone.start.z + SHORTEST_STRETCH * cone.lowest.min(0.0);
    let above =
        surface_extreme(terrain, first, f64::max, false).is_some_and(|z| lowest_first > z + margin);
    let at_start = surface_extreme(terrain, (o - ROOM, o + ROOM), f64::max, false);
    let on = at_start.is_some_and(|z| cone.start.z >= z - ROOM * (1.0 + z.abs()));
    let steeper = || cone.lowest > rise_under(terrain, first, &cone.sector) * (1.0 + 1e-9) + 1e-9;
    if !(above || (on && steeper())) {
        return false;
    }
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let lowest_at = |r: f64| cone.start.z + r * cone.lowest;
    let (mut r, mut step) = (SHORTEST_STRETCH, SHORTEST_STRETCH);
    for _ in 0..MARCH_STEPS {
        if cone.lowest >= 0.0 && lowest_at(r) > z_hi + margin {
            return true;
        }
        let end = r + step;
        let (lo, hi) = stretch(cone, r, end);
        if hi.x < 0.0 || hi.y < 0.0 || lo.x > w || lo.y > h {
            // Every direction has left the map, which it started in, for good (a convex
            // region).
            return true;
        }
        let lowest = lowest_at(r).min(lowest_at(end));
        let highest = if (hi - lo).max_element() <= PLANES_UP_TO {
            surface_extreme(terrain, (lo, hi), f64::max, false)
        } else {
            highest_under(terrain, [lo.x, hi.x], [lo.y, hi.y]).map(|(z, _)| z)
        };
        if highest.is_none_or(|z| lowest > z + margin) {
            (r, step) = (end, 2.0 * step);
        } else if step <= SHORTEST_STRETCH {
            return false;
        } else {
            step /= 2.0;
        }
    }
    false
}

/// The box holding every direction's points from horizontal distance `r` to `end`: they lie
/// between their ends, in the two footprints.
fn stretch(cone: &Cone, r: f64, end: f64) -> (DVec2, DVec2) {
    let ((a, a_half), (b, b_half)) = (cone.footprint(r), cone.footprint(end));
    let half = a_half.max(b_half);
    (a.min(b) - half, a.max(b) + half)
}

/// How fast the steepest triangle of the cells meeting the box `[lo, hi]` rises along the
/// azimuths of `sector` (holes have none).
fn rise_under(terrain: &Terrain, (lo, hi): (DVec2, DVec2), sector: &Sector) -> f64 {
    let mut steepest = f64::NEG_INFINITY;
    for_cells(terrain, lo, hi, |_, heights| {
        for triangle in 0..2 {
            let rise = sector.steepest_rise(DVec2::from(gradient(triangle, heights)));
            steepest = steepest.max(rise);
        }
    });
    steepest
}

/// Whether every direction of `cone` provably touches the surface after its start, where its
/// own triangle `own` (of `cell`) may be left untested; `first_touch` traces a direction from
/// a point and gives the horizontal distance it travels to its first touch, if any.
pub fn blocked(
    terrain: &Terrain,
    cone: &Cone,
    (cell, own): ((usize, usize), u8),
    first_touch: impl FnOnce(DVec3, DVec3) -> Option<f64>,
) -> bool {
    if terrain.field().nodata_count() > 0 {
        return false;
    }
    let (z_lo, z_hi) = terrain.z_range();
    let margin = MARGIN * (1.0 + z_hi - z_lo);
    // Every direction rises away from its own triangle's plane.
    let heights = terrain.corner_heights(cell.0, cell.1);
    let (gx, gy) = gradient(own, heights);
    let rises = |tan: f64| {
        // Along the cone's azimuths the plane rises at most this fast.
        let g = DVec2::new(gx, gy);
        let steepest = g.dot(cone.along) + g.length() * cone.across;
        tan > steepest + 1e-9
    };
    if !rises(cone.lowest) {
        return false;
    }
    let own_plane = |p: DVec2| plane_height(own, cell, heights, p.x, p.y);
    let Some(r1) = NEAR_START.into_iter().find(|&r| {
        let (centre, half) = cone.footprint(r);
        let above = cone.start.z + r * cone.lowest;
        let own = box_corners(centre, half).map(own_plane);
        let highest = surface_extreme(terrain, (centre - half, centre + half), f64::max, true)
            .map(|h| own.into_iter().fold(h, f64::max));
        highest.is_some_and(|h| above > h + margin)
    }) else {
        return false;
    };
    let from = cone.start + DVec3::new(cone.along.x, cone.along.y, cone.highest) * r1;
    let Some(touch) = first_touch(from, cone.highest_direction()) else {
        return false;
    };
    PAST_TOUCH.iter().any(|&past| {
        let r2 = r1 + touch + past;
        let (centre, half) = cone.footprint(r2);
        let below = cone.start.z + r2 * cone.highest;
        surface_extreme(terrain, (centre - half, centre + half), f64::min, true)
            .is_some_and(|h| below < h - margin)
    })
}

/// The corners of the square of half-width `half` around `centre`.
fn box_corners(centre: DVec2, half: f64) -> [DVec2; 4] {
    [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
        .map(|(a, b)| centre + DVec2::new(a, b) * half)
}

/// The highest (`pick` = max) or lowest (min) height of the surface over the box
/// `[lo, hi]`: each triangle's plane at the corners of the box clipped to its cell (a plane's
/// extremes over a rectangle are at its corners, and the triangle lies within); holes have
/// none. Over the part inside the map, unless `whole` asks for all of it; `None` where the
/// box meets no triangle, or (`whole`) leaves the map.
fn surface_extreme(
    terrain: &Terrain,
    (lo, hi): (DVec2, DVec2),
    pick: fn(f64, f64) -> f64,
    whole: bool,
) -> Option<f64> {
    let mut extreme = None;
    let inside = for_cells(terrain, lo, hi, |(i, j), heights| {
        let (x0, x1) = (lo.x.max(i as f64), hi.x.min(i as f64 + 1.0));
        let (y0, y1) = (lo.y.max(j as f64), hi.y.min(j as f64 + 1.0));
        for triangle in 0..2 {
            for (x, y) in [(x0, y0), (x1, y0), (x0, y1), (x1, y1)] {
                let z = plane_height(triangle, (i, j), heights, x, y);
                extreme = Some(extreme.map_or(z, |e| pick(e, z)));
            }
        }
    });
    extreme.filter(|_| inside || !whole)
}

/// Calls `visit` with each cell meeting the box `[lo, hi]` clipped to the map that is not a
/// hole, and its corner heights; returns whether the box lies inside the map.
fn for_cells(
    terrain: &Terrain,
    lo: DVec2,
    hi: DVec2,
    mut visit: impl FnMut((usize, usize), [f64; 4]),
) -> bool {
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let cell = |x: f64, n: f64| x.clamp(0.0, n - 1.0) as usize;
    for j in cell(lo.y, h)..=cell(hi.y, h) {
        for i in cell(lo.x, w)..=cell(hi.x, w) {
            if !field.is_hole_cell(i, j) {
                visit((i, j), terrain.corner_heights(i, j));
            }
        }
    }
    lo.x >= 0.0 && lo.y >= 0.0 && hi.x <= w && hi.y <= h
}
