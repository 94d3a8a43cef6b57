//! Samples per pixel added one round at a time, for a view that refines while its camera
//! rests: round `k` traces sample `k` of every pixel (the position and effect rays
//! [`pixel::shade`] gives it), so after the last round the image is the one `render` makes
//! with uniform samples, bit for bit.

use super::pixel::{self, position};
use crate::render::gamma;
use crate::render::passes::{Frame, Renderer};
use crate::render::scene::Lighting;
use crate::render::shade::Shader;
use crate::render::stats::PixelStats;
use rayon::prelude::*;

/// The running sums of a frame's samples, in linear light.
#[derive(Clone, Debug)]
pub struct Accumulation {
    sums: Vec<[f64; 3]>,
    /// Rounds added.
    pub done: u32,
    /// Rounds asked (the scene's samples per pixel).
    pub total: u32,
}

impl Accumulation {
    /// No round yet, for a `width x height` frame taking `total` samples per pixel.
    pub fn new(width: u32, height: u32, total: u32) -> Accumulation {
        Accumulation {
            sums: vec![[0.0; 3]; width as usize * height as usize],
            done: 0,
            total,
        }
    }

    /// Whether every round has been added.
    pub fn complete(&self) -> bool {
        self.done >= self.total
    }
}

impl Renderer<'_> {
    /// Adds the next round of samples to `sums` and paints their mean into `frame` (on the
    /// current rayon pool). Returns false when `cancelled` turned true (asked before each
    /// row): the round is then partly added, and both are to be dropped.
    pub fn accumulate(
        &self,
        sums: &mut Accumulation,
        frame: &mut Frame,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> bool {
        let width = frame.width as usize;
        let index = sums.done;
        let shader = Shader {
            lighting: Lighting {
                effects: pixel::per_sample(&self.shader.lighting.effects),
                ..self.shader.lighting
            },
            ..self.shader
        };
        let rows = frame
            .pixels
            .par_chunks_mut(width)
            .zip(frame.stats.par_chunks_mut(width))
            .zip(sums.sums.par_chunks_mut(width))
            .enumerate()
            .map(|(y, ((pixels, stats), sums))| {
                if cancelled() {
                    return None;
                }
                let mut totals = crate::render::FrameStats::default();
                for (x, ((pixel, stat), sum)) in pixels.iter_mut().zip(stats).zip(sums).enumerate()
                {
                    let (px, py) = position(x as u32, y as u32, index);
                    let (sample, _) = shader.traced(&self.camera.ray_at(px, py), self.arith);
                    totals.add(&sample);
                    let channels = [16, 8, 0].map(|shift| (sample.rgb >> shift) as u8);
                    for (s, c) in sum.iter_mut().zip(channels) {
                        *s += gamma::linear(c);
                    }
                    let n = f64::from(index + 1);
                    let byte = |s: f64| u32::from(gamma::byte(s / n));
                    *pixel = (byte(sum[0]) << 16) | (byte(sum[1]) << 8) | byte(sum[2]);
                    let mut traced = PixelStats::of(&sample);
                    if index > 0 {
                        traced += *stat;
                        traced.samples = index + 1;
                    }
                    *stat = traced;
                }
                Some(totals)
            })
            .collect::<Vec<_>>();
        let mut totals = crate::render::FrameStats::default();
        for row in rows {
            let Some(row) = row else { return false };
            totals += row;
        }
        frame.totals += totals;
        sums.done += 1;
        true
    }
}
