//! Contour lines drawn into the surface's colour as it is shaded: they lie on the terrain, so
//! they follow it and hide behind ridges like the ground they are drawn on.
//!
//! **Constant width on screen.** A line is drawn where the hit lies within half a line width
//! of a contour height, measured in pixels: the height's change from one pixel to the next
//! comes from ray differentials on the hit triangle's plane (Igehy 1999). With pixel `(x, y)`'s
//! ray `F + x R + y U` (the camera's [`pixel_steps`](super::Camera::pixel_steps), in grid
//! coordinates), a hit at `o + τ d` on a plane of normal `n` moves by
//! `τ (R - d (n·R) / (n·d))` for a step `R` of the direction, and the height by its `z`. Where
//! contours crowd closer than a few pixels they fade out, rather than fill the ground.

use super::Camera;
use crate::geometry::gradient;
use crate::geometry::Ray;
use crate::heightfield::Terrain;
use glam::DVec3;

/// The lines' colour (linear light): a dark brown, as printed maps draw contours.
const INK: DVec3 = DVec3::new(0.09, 0.05, 0.02);
/// How much of the ground's colour a line covers: ordinary and index lines.
const STRENGTH: [f64; 2] = [0.55, 0.8];
/// Contours closer than this many pixels fade out, and are gone at half of it.
const CROWDED_PX: f64 = 6.0;
/// The output height whose lines are one pixel wide; taller images draw wider lines, so a
/// large export looks like a small one.
const ONE_PIXEL_HEIGHT: f64 = 900.0;

/// Contour lines at every multiple of an interval of height, every `index`-th one wider.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contours {
    /// Grid height between lines.
    interval_z: f64,
    /// Every this many lines is an index line (0: none).
    index: u32,
    /// The camera's pixel steps in grid coordinates, and the line width in pixels.
    view: Option<ContourView>,
}

/// How a camera's pixels see the surface (see the module's note).
#[derive(Clone, Copy, Debug, PartialEq)]
struct ContourView {
    forward: DVec3,
    across: DVec3,
    up: DVec3,
    /// The image plane's normal, `across x up`.
    normal: DVec3,
    /// An ordinary line's width in pixels.
    width_px: f64,
}

impl Contours {
    /// Lines every `interval_z` of grid height (the interval in the map's height unit through
    /// [`level_z`](super::level_z)), every `index`-th one an index line; `None` unless the
    /// interval is finite and above 0.
    pub fn new(interval_z: f64, index: u32) -> Option<Contours> {
        (interval_z.is_finite() && interval_z > 0.0).then_some(Contours {
            interval_z,
            index,
            view: None,
        })
    }

    /// Grid height between lines.
    pub fn interval_z(&self) -> f64 {
        self.interval_z
    }

    /// Every this many lines is an index line (0: none).
    pub fn index_every(&self) -> u32 {
        self.index
    }

    /// The same lines as `camera` sees them (a camera in grid coordinates, see
    /// [`Camera::in_grid`]); without a camera no line is drawn.
    pub fn seen_by(self, camera: &Camera) -> Contours {
        let [forward, across, up] = camera.pixel_steps().map(DVec3::from);
        let height = f64::from(camera.whole_size().1);
        Contours {
            view: Some(ContourView {
                forward,
                across,
                up,
                normal: across.cross(up),
                width_px: (height / ONE_PIXEL_HEIGHT).max(1.0),
            }),
            ..self
        }
    }

    /// How much of the line's ink covers a hit at grid height `z`, where the height changes by
    /// `per_pixel` from one pixel to the next, 0 to 1.
    pub fn cover(&self, z: f64, per_pixel: f64) -> f64 {
        let Some(view) = &self.view else {
            return 0.0;
        };
        if !(per_pixel.is_finite() && per_pixel > 0.0) {
            return 0.0;
        }
        let spacing = self.interval_z / per_pixel;
        let crowding = ((spacing - 0.5 * CROWDED_PX) / (0.5 * CROWDED_PX)).clamp(0.0, 1.0);
        let nearest = (z / self.interval_z).round();
        let index = self.index > 0 && (nearest as i64).rem_euclid(i64::from(self.index)) == 0;
        let width = view.width_px * if index { 2.0 } else { 1.0 };
        let distance = (z - nearest * self.interval_z).abs() / per_pixel;
        // The share of a pixel a line of that width centred `distance` away covers.
        let covered = (0.5 * width + 0.5 - distance).clamp(0.0, 1.0);
        covered * crowding * STRENGTH[usize::from(index)]
    }

    /// How fast the height of the plane of normal `n` changes from pixel to pixel at its hit
    /// `t` along `dir` (all in grid coordinates).
    pub fn height_per_pixel(&self, dir: DVec3, t: f64, n: DVec3) -> f64 {
        let Some(view) = &self.view else {
            return f64::INFINITY;
        };
        // The pixel's direction on the camera's scale: `dir * lambda` is `F + x R + y U`.
        let lambda = view.normal.dot(view.forward) / view.normal.dot(dir);
        let tau = t / lambda;
        let closing = n.dot(dir);
        let step = |s: DVec3| tau * (s.z - dir.z * n.dot(s) / closing);
        step(view.across).hypot(step(view.up))
    }
}

/// The unnormalised normal of the triangle under grid point `p` (on the terrain).
fn plane_normal(terrain: &Terrain, p: DVec3) -> DVec3 {
    let field = terrain.field();
    let last = |n: usize| n.saturating_sub(2) as f64;
    let x = p.x.clamp(0.0, last(field.width()));
    let y = p.y.clamp(0.0, last(field.height()));
    let (i, j) = (x.floor(), y.floor());
    let triangle = u8::from(p.x - i < p.y - j);
    let (gx, gy) = gradient(triangle, terrain.corner_heights(i as usize, j as usize));
    DVec3::new(-gx, -gy, 1.0)
}

impl Contours {
    /// `albedo` at `p` on the terrain with the contour lines over it, `p` seen `t` along
    /// `ray`.
    #[inline(always)]
    pub(super) fn mark(
        &self,
        terrain: &Terrain,
        albedo: DVec3,
        ray: &Ray,
        p: DVec3,
        t: f64,
    ) -> DVec3 {
        let n = plane_normal(terrain, p);
        let per_pixel = self.height_per_pixel(DVec3::from(ray.dir()), t, n);
        albedo.lerp(INK, self.cover(p.z, per_pixel))
    }
}
