//! A cone towards the sun that the terrain provably blocks whole: every direction of it is
//! above the surface at one horizontal distance from the start and below it at a farther
//! one, so each crosses the surface in between and touches it after its start.
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

use crate::geometry::{gradient, plane_height};
use crate::heightfield::Terrain;
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
        Some(Cone {
            start,
            along: horizontal.normalize(),
            across: across.asin() * (1.0 + 1e-6) + 1e-9,
            lowest: low.tan(),
            highest: high.tan(),
        })
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
        let highest = surface_extreme(terrain, centre, half, f64::max)
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
        surface_extreme(terrain, centre, half, f64::min).is_some_and(|h| below < h - margin)
    })
}

/// The corners of the square of half-width `half` around `centre`.
fn box_corners(centre: DVec2, half: f64) -> [DVec2; 4] {
    [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
        .map(|(a, b)| centre + DVec2::new(a, b) * half)
}

/// The highest (`pick` = max) or lowest (min) height of the surface over the square of
/// half-width `half` around `centre`: each triangle's plane at the corners of the square
/// clipped to its cell (a plane's extremes over a rectangle are at its corners, and the
/// triangle lies within). `None` where the square leaves the map.
fn surface_extreme(
    terrain: &Terrain,
    centre: DVec2,
    half: f64,
    pick: fn(f64, f64) -> f64,
) -> Option<f64> {
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let (lo, hi) = (centre - half, centre + half);
    if lo.x < 0.0 || lo.y < 0.0 || hi.x > w || hi.y > h {
        return None;
    }
    let cells_x = (lo.x as usize)..=((hi.x as usize).min(w as usize - 1));
    let cells_y = (lo.y as usize)..=((hi.y as usize).min(h as usize - 1));
    let mut extreme = None;
    for j in cells_y {
        for i in cells_x.clone() {
            let heights = terrain.corner_heights(i, j);
            let (x0, x1) = (lo.x.max(i as f64), hi.x.min(i as f64 + 1.0));
            let (y0, y1) = (lo.y.max(j as f64), hi.y.min(j as f64 + 1.0));
            for triangle in 0..2 {
                for (x, y) in [(x0, y0), (x1, y0), (x0, y1), (x1, y1)] {
                    let z = plane_height(triangle, (i, j), heights, x, y);
                    extreme = Some(extreme.map_or(z, |e| pick(e, z)));
                }
            }
        }
    }
    extreme
}
