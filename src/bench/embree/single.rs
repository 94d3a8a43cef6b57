//! Embree's single-ray API, `rtcIntersect1` and `rtcOccluded1`: one ray at a time, as
//! heightray traces them, and a frame traced that way.

use super::pixel::{render_in_bands, Pixel};
use super::{ffi, EmbreeHit, EmbreeScene, Geometry};
use crate::render::{Frame, Renderer};
use crate::Ray;
use glam::DVec3;

impl EmbreeScene {
    /// The first hit of `ray`.
    pub fn intersect(&self, ray: &Ray) -> Option<EmbreeHit> {
        let mut query = ffi::RayHit {
            ray: segment(ray.origin(), ray.dir()),
            hit: ffi::Hit {
                geom_id: ffi::INVALID_GEOMETRY_ID,
                ..ffi::Hit::default()
            },
        };
        let mut context = ffi::IntersectContext::new();
        // SAFETY: a committed scene, and a context and ray that live through the call.
        unsafe { ffi::rtcIntersect1(self.scene, &mut context, &mut query) };
        let (ray_out, hit) = (&query.ray, &query.hit);
        self.hit(ray, hit.geom_id, hit.prim_id, ray_out.tfar, hit.ng)
    }

    /// Whether anything lies on the ray from `origin` towards `dir`.
    pub fn occluded(&self, origin: [f64; 3], dir: [f64; 3]) -> bool {
        let mut ray = segment(origin, dir);
        let mut context = ffi::IntersectContext::new();
        // SAFETY: as in `intersect`.
        unsafe { ffi::rtcOccluded1(self.scene, &mut context, &mut ray) };
        // Embree marks an occluded ray by setting its far end to minus infinity.
        ray.tfar < 0.0
    }

    /// Embree's answer for `ray` as a hit of the terrain: `None` where the geometry id is
    /// invalid (a miss), else the cell and triangle of primitive `prim_id`, hit at `tfar`
    /// where the geometric normal is `ng`.
    pub(super) fn hit(
        &self,
        ray: &Ray,
        geom_id: u32,
        prim_id: u32,
        tfar: f32,
        ng: [f32; 3],
    ) -> Option<EmbreeHit> {
        if geom_id == ffi::INVALID_GEOMETRY_ID {
            return None;
        }
        let t = f64::from(tfar);
        let (cell, triangle) = match self.geometry {
            Geometry::Triangles => {
                let prim = prim_id as usize;
                let columns = self.cells.0;
                ((prim / 2 % columns, prim / 2 / columns), (prim % 2) as u8)
            }
            // A grid's hit names only the grid: the cell is the one under the hit point, and
            // the triangle heightray's on that side of its diagonal.
            Geometry::Grid => {
                let p = DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * t;
                let floor = |c: f64, cells: usize| (c.floor().max(0.0) as usize).min(cells - 1);
                let (i, j) = (floor(p.x, self.cells.0), floor(p.y, self.cells.1));
                let below_diagonal = p.x - i as f64 >= p.y - j as f64;
                ((i, j), u8::from(!below_diagonal))
            }
        };
        // The surface faces up; Embree's normal may not.
        let normal = DVec3::from(ng.map(f64::from)).normalize_or(DVec3::Z);
        Some(EmbreeHit {
            cell,
            triangle,
            t,
            up: normal * normal.z.signum(),
        })
    }

    /// Renders `renderer`'s view into `frame` (every pixel, on the current rayon pool): the
    /// same pixels, shading and shadow rays as [`Renderer::render`], each ray traced alone.
    pub fn render(&self, renderer: &Renderer<'_>, frame: &mut Frame) {
        let shader = &renderer.shader;
        let width = frame.width;
        render_in_bands(frame, 1, |y, put| {
            for x in 0..width {
                let ray = renderer.camera.ray(x, y);
                let pixel = Pixel::new(shader, ray, self.intersect(&ray));
                let start = pixel.shadow_start();
                let shadowed = start.is_some_and(|s| self.occluded(s, shader.lighting.sun));
                put(x, y, pixel.sample(shader, shadowed));
            }
        });
    }
}

/// An Embree ray from `origin` along `dir` (not normalised, as heightray's).
pub(super) fn segment(origin: [f64; 3], dir: [f64; 3]) -> ffi::Ray {
    ffi::Ray {
        org: origin.map(|c| c as f32),
        dir: dir.map(|c| c as f32),
        tfar: f32::INFINITY,
        mask: u32::MAX,
        ..ffi::Ray::default()
    }
}
