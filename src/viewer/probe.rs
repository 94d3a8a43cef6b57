//! The hovered pixel's rays, traced again on demand by the renderer's own code for a pixel
//! ([`Shader::traced`]): the same primary ray and the same shadow ray from the same start,
//! so every query they made can be shown.

use crate::render::{Sample, Shader, Shadow};
use crate::traverse::plane_t_exact;
use crate::{Arith, Face, Hit, Ray, TraceOptions};
use std::time::{Duration, Instant};

/// One pixel's rays and what they asked.
#[derive(Clone, Debug)]
pub struct Probe {
    /// The pixel in the rendered frame.
    pub pixel: (u32, u32),
    /// The frame generation the pixel belonged to.
    pub generation: u64,
    /// Where the primary ray hit (with its exact `t` in exact arithmetic).
    pub hit: Option<Hit>,
    /// The pixel as the renderer traces it: its shadow and both rays' queries.
    pub sample: Sample,
    /// Time both rays took.
    pub elapsed: Duration,
}

/// The exact `t` of `hit` of `ray`: on the terrain from its triangle's plane, on the base
/// from the exact trace over it.
fn exact_t(shader: &Shader<'_>, ray: &Ray, hit: &Hit) -> Option<num_rational::BigRational> {
    if hit.face == Face::Terrain {
        let cell = (hit.cell[0], hit.cell[1]);
        return plane_t_exact(shader.terrain, ray, cell, hit.triangle);
    }
    let options = TraceOptions {
        base: shader.base,
        ..TraceOptions::new(shader.method, Arith::Exact)
    };
    let exact = crate::trace(shader.terrain, ray, &options).hit?;
    (exact.face == hit.face).then_some(exact.t_exact).flatten()
}

impl Probe {
    /// Traces `ray` (pixel `pixel` of frame `generation`) as `shader` renders it in `arith`.
    pub fn trace(
        shader: &Shader<'_>,
        arith: Arith,
        ray: Ray,
        pixel: (u32, u32),
        generation: u64,
    ) -> Probe {
        let start = Instant::now();
        // From the clearance the frame's ray had: the same walk, the same queries.
        let wedges = shader.wedges(ray.origin(), arith);
        let clearance = wedges.and_then(|w| w.clearance(ray.origin(), ray.dir()).0);
        let (sample, hit) = shader.traced_from(&ray, arith, clearance);
        let elapsed = start.elapsed();
        let hit = hit.map(|hit| Hit {
            t_exact: (arith == Arith::Exact)
                .then(|| exact_t(shader, &ray, &hit))
                .flatten(),
            ..hit
        });
        Probe {
            pixel,
            generation,
            hit,
            sample,
            elapsed,
        }
    }

    /// Whether the hit point is in shadow (None without a hit, or where no shadow ray was
    /// cast).
    pub fn shadowed(&self) -> Option<bool> {
        match self.sample.shadow {
            Shadow::Cast { shadowed } => Some(shadowed),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::Builtin;
    use crate::render::effects::Effects;
    use crate::render::{
        BaseStyle, Camera, Culling, Frame, Lighting, Normals, PixelStats, Ramp, Renderer,
    };
    use crate::{Method, Terrain};

    /// A low afternoon sun over the valley, so that many pixels lie in shadow and many shadow
    /// rays graze the slopes they start on.
    fn low_sun(normals: Normals) -> Lighting {
        Lighting {
            sun: Lighting::unit([0.8, 0.3, 0.25]),
            intensity: 1.0,
            ambient: 0.25,
            shadows: true,
            fog: 0.0,
            normals,
            ramp: Ramp::Gray,
            effects: Effects::default(),
            base: BaseStyle::default(),
        }
    }

    /// The probe of every pixel is the renderer's pixel: the frame rendered in passes has the
    /// probe's colour at every pixel, so the same hit and the same shadow (a shadow ray from
    /// another start would light or darken some grazing pixels), and the same queries,
    /// primary and shadow ray's together (each ray from its wedge's clearance).
    #[test]
    fn the_probe_traces_the_renderers_rays_for_each_pixel() {
        let field = Builtin::named("valley513")
            .and_then(|b| b.load().ok())
            .expect("decodes");
        let terrain = Terrain::new(field);
        let size = 48;
        let camera = Camera::look_at(
            [-40.0, -60.0, 180.0],
            [256.0, 256.0, 40.0],
            [0.0, 0.0, 1.0],
            45.0,
            (size, size),
        )
        .expect("a camera");
        for normals in [Normals::Flat, Normals::Smooth] {
            for arith in [Arith::F64, Arith::Exact] {
                let renderer = Renderer {
                    shader: Shader::new(
                        &terrain,
                        low_sun(normals),
                        Method::Mipmap,
                        Culling::default(),
                    ),
                    camera,
                    arith,
                };
                let mut frame = Frame::new(size, size);
                renderer.render(&mut frame);
                let mut shadowed = [0, 0];
                for y in 0..size {
                    for x in 0..size {
                        let ray = camera.ray(x, y);
                        let probe = Probe::trace(&renderer.shader, arith, ray, (x, y), 0);
                        let at = (y * size + x) as usize;
                        let pixel = format!("({x}, {y}) {arith} {normals:?}");
                        assert_eq!(probe.sample.rgb, frame.pixels[at], "colour of {pixel}");
                        let stats = PixelStats::of(&probe.sample);
                        assert_eq!(stats, frame.stats[at], "queries of {pixel}");
                        if let Some(dark) = probe.shadowed() {
                            shadowed[usize::from(dark)] += 1;
                        }
                    }
                }
                // Both answers asked of many shadow rays: the comparison saw shadows.
                assert!(shadowed.iter().all(|&n| n > 100), "{shadowed:?}");
            }
        }
    }

    #[test]
    fn a_ray_down_onto_the_terrain_hits_and_casts_a_shadow_ray() {
        let field = Builtin::named("small49")
            .and_then(|b| b.load().ok())
            .expect("decodes");
        let terrain = Terrain::new(field);
        let lighting = Lighting {
            sun: [0.0, 0.0, 1.0],
            intensity: 1.0,
            ambient: 0.25,
            shadows: true,
            fog: 0.0,
            normals: Normals::Flat,
            ramp: Ramp::Gray,
            effects: Effects::default(),
            base: BaseStyle::default(),
        };
        let culling = Culling {
            no_shadow_possible: false,
            ..Culling::default()
        };
        let shader = Shader::new(&terrain, lighting, Method::Runs, culling);
        let ray = Ray::new([20.5, 20.25, 100.0], [0.0, 0.0, -1.0]).expect("valid ray");
        let probe = Probe::trace(&shader, Arith::F64, ray, (3, 4), 7);
        let hit = probe.hit.as_ref().expect("hits the terrain");
        assert_eq!(hit.cell, [20, 20]);
        // Straight up from a height field nothing is in the way.
        assert_eq!(probe.shadowed(), Some(false));
        assert!(probe.sample.primary.triangle.total() > 0);
    }
}
