//! A pixel of a frame traced by Embree, shaded as heightray shades it: the camera ray's hit,
//! its cell and triangle give the colour, and a shadow ray where the surface faces the sun
//! gives the light. Single rays and packets share it, so their frames differ only in how
//! the rays were traced.

use super::EmbreeHit;
use crate::render::effects::{EffectTime, Outcomes};
use crate::render::{Frame, FrameStats, PixelStats, Sample, Shader, Shadow, ShadowSkip};
use crate::traverse::Counters;
use crate::Face;
use crate::Ray;
use glam::DVec3;
use rayon::prelude::*;

/// A pixel whose camera ray is answered, before its shadow ray.
pub(super) struct Pixel {
    ray: Ray,
    surface: Option<Surface>,
}

/// The surface a camera ray hit.
struct Surface {
    p: DVec3,
    t: f64,
    /// The cosine of the sun against the triangle's normal.
    facing: f64,
    /// The shadow ray's fate where it is not cast.
    shadow: Shadow,
    /// Where the shadow ray starts, where one is cast.
    start: Option<[f64; 3]>,
}

impl Pixel {
    /// The pixel of camera ray `ray`, which Embree answered with `hit`.
    pub fn new(shader: &Shader<'_>, ray: Ray, hit: Option<EmbreeHit>) -> Pixel {
        let surface = hit.map(|hit| {
            let p = DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * hit.t;
            let facing = shader.facing(Face::Terrain, hit.cell, hit.triangle, p);
            let (shadow, start) = if !shader.lighting.shadows {
                (Shadow::NotAsked, None)
            } else if facing <= 0.0 {
                (Shadow::Skipped(ShadowSkip::FacingAway), None)
            } else {
                // Started off the surface by several `f32` roundings of the hit point's size,
                // the usual offset that keeps a shadow ray off the triangle it starts on.
                let room = 1e-6 * p.abs().max_element().max(1.0);
                let start = p + hit.up * room;
                (Shadow::Cast { shadowed: false }, Some(start.into()))
            };
            Surface {
                p,
                t: hit.t,
                facing,
                shadow,
                start,
            }
        });
        Pixel { ray, surface }
    }

    /// Where its shadow ray towards the sun starts, if it casts one.
    pub fn shadow_start(&self) -> Option<[f64; 3]> {
        self.surface.as_ref().and_then(|s| s.start)
    }

    /// The pixel's sample, given whether its shadow ray (if it cast one) was blocked.
    pub fn sample(&self, shader: &Shader<'_>, shadowed: bool) -> Sample {
        let missed = Sample {
            rgb: shader.sky_rgb(&self.ray),
            hit: None,
            shadow: Shadow::NotAsked,
            primary: Counters::default(),
            secondary: Counters::default(),
            effects: Outcomes::default(),
            redone: false,
            time: EffectTime::default(),
        };
        let Some(surface) = &self.surface else {
            return missed;
        };
        let shadow = match surface.start {
            Some(_) => Shadow::Cast { shadowed },
            None => surface.shadow,
        };
        Sample {
            rgb: shader.surface_rgb(
                &self.ray,
                (Face::Terrain, surface.p),
                surface.t,
                surface.facing,
                shadow,
            ),
            hit: Some(Face::Terrain),
            shadow,
            ..missed
        }
    }
}

/// Renders `frame` in bands of `rows` rows on the current rayon pool: `band(y0, put)` traces
/// and shades the band's pixels from row `y0` and hands each to `put(x, y, sample)`.
pub(super) fn render_in_bands(
    frame: &mut Frame,
    rows: u32,
    band: impl Fn(u32, &mut dyn FnMut(u32, u32, Sample)) + Sync,
) {
    let width = frame.width as usize;
    let chunk = width * rows as usize;
    let bands: Vec<FrameStats> = frame
        .pixels
        .par_chunks_mut(chunk)
        .zip(frame.stats.par_chunks_mut(chunk))
        .enumerate()
        .map(|(k, (pixels, stats))| {
            let mut totals = FrameStats::default();
            let y0 = k as u32 * rows;
            band(y0, &mut |x, y, sample| {
                let at = (y - y0) as usize * width + x as usize;
                totals.add(&sample);
                (pixels[at], stats[at]) = (sample.rgb, PixelStats::of(&sample));
            });
            totals
        })
        .collect();
    for totals in bands {
        frame.totals += totals;
    }
    frame.passes_done = crate::render::PASS_BLOCKS.len();
}
