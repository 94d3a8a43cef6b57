//! Embree on the effects' rays: from where each camera ray hits, the rays an effect asks for,
//! every one of them cast (no culling), so `bench effects --embree` sets heightray's effect
//! frames against a general-purpose tracer casting the same kinds and numbers of rays: the
//! sun's shadow ray, soft-shadow rays over the sun's disc and cosine-weighted sky rays within
//! the sky distance, drawn as heightray draws them.

use super::pixel::{render_in_bands, Pixel};
use super::single::segment;
use super::{ffi, EmbreeScene};
use crate::render::effects::pixel::per_sample;
use crate::render::effects::sampling::{point, seed_of, ConeDirections, Hemisphere};
use crate::render::{Frame, Renderer};
use crate::Face;
use glam::DVec3;
use std::sync::atomic::{AtomicU64, Ordering};

/// The purpose each pixel's directions are seeded with.
const PURPOSE: u64 = 0x00e1_b7ee;

impl EmbreeScene {
    /// Whether anything lies on the ray from `origin` towards `dir` before `t_far`.
    fn occluded_within(&self, origin: [f64; 3], dir: [f64; 3], t_far: f64) -> bool {
        let mut ray = ffi::Ray {
            tfar: t_far as f32,
            ..segment(origin, dir)
        };
        let mut context = ffi::IntersectContext::new();
        // SAFETY: a committed scene, and a context and ray that live through the call.
        unsafe { ffi::rtcOccluded1(self.scene, &mut context, &mut ray) };
        ray.tfar < 0.0
    }

    /// Renders `renderer`'s view into `frame` as [`EmbreeScene::render`] does (a camera ray
    /// per pixel, shaded with the sun's hard shadow where the scene has shadows and no sun's
    /// disc), casting besides every ray of the scene's soft shadows and sky light for one
    /// sample per pixel; returns the occlusion rays cast (shadow, soft and sky).
    pub fn render_effects(&self, renderer: &Renderer<'_>, frame: &mut Frame) -> u64 {
        let shader = &renderer.shader;
        let effects = per_sample(&shader.lighting.effects);
        let soft = effects.sun_angle_deg > 0.0;
        let axis = shader.grid_dir(DVec3::from(shader.lighting.sun));
        let half = (effects.sun_angle_deg / 2.0).to_radians();
        let cone = ConeDirections::around(axis, half);
        let scale = shader.terrain.world_from_grid().unwrap_or([1.0; 3]);
        let cast = AtomicU64::new(0);
        let width = frame.width;
        render_in_bands(frame, 1, |y, put| {
            let mut rays = 0;
            for x in 0..width {
                let ray = renderer.camera.ray(x, y);
                let hit = self.intersect(&ray);
                let pixel = Pixel::new(shader, ray, hit);
                let start = pixel.shadow_start();
                let seed = seed_of(ray.origin(), ray.dir(), PURPOSE);
                let shadowed = match start {
                    Some(s) if soft => {
                        for k in 0..effects.sun_rays {
                            let (u, v) = point(k, seed);
                            self.occluded(s, cone.at(u, v).into());
                        }
                        rays += u64::from(effects.sun_rays);
                        false
                    }
                    Some(s) => {
                        rays += 1;
                        self.occluded(s, shader.grid_sun())
                    }
                    None => false,
                };
                if let (true, Some(hit)) = (effects.sky_light, hit) {
                    let p = DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * hit.t;
                    let from = p + hit.up * (1e-6 * p.abs().max_element().max(1.0));
                    let normal = shader.normal(Face::Terrain, hit.cell, hit.triangle, p);
                    let hemisphere = Hemisphere::around(normal);
                    for k in 0..effects.sky_rays {
                        let (u, v) = point(k, seed ^ 1);
                        let grid = shader.grid_dir(hemisphere.cosine(u, v));
                        let across = (grid.x * scale[0]).hypot(grid.y * scale[1]);
                        let t_far = (effects.sky_distance / across).min(f64::from(f32::MAX));
                        self.occluded_within(from.into(), grid.into(), t_far);
                    }
                    rays += u64::from(effects.sky_rays);
                }
                put(x, y, pixel.sample(shader, shadowed));
            }
            cast.fetch_add(rays, Ordering::Relaxed);
        });
        cast.into_inner()
    }
}
