//! Samples per pixel added one round at a time, for a view that refines while its camera
//! rests: round `k` traces sample `k` of every pixel still taking samples (the position and
//! effect rays [`pixel::shade`] gives it, and its stopping rule when adaptive), so after the
//! last round the image is the one `render` makes, bit for bit.

use super::pixel::{self, position, Estimate};
use crate::render::passes::{Frame, Renderer};
use crate::render::scene::Lighting;
use crate::render::shade::Shader;
use crate::render::stats::PixelStats;
use rayon::prelude::*;

/// The running estimates of a frame's pixels.
#[derive(Clone, Debug)]
pub struct Accumulation {
    /// Each pixel's samples, and whether it stopped taking more.
    pixels: Vec<(Estimate, bool)>,
    /// Rounds added.
    pub done: u32,
    /// Rounds asked (the scene's samples per pixel).
    pub total: u32,
    /// Pixels still taking samples.
    pub active: usize,
}

impl Accumulation {
    /// No round yet, for a `width x height` frame taking `total` samples per pixel.
    pub fn new(width: u32, height: u32, total: u32) -> Accumulation {
        let n = width as usize * height as usize;
        Accumulation {
            pixels: vec![(Estimate::default(), false); n],
            done: 0,
            total,
            active: n,
        }
    }

    /// Whether every pixel has taken its samples.
    pub fn complete(&self) -> bool {
        self.done >= self.total || self.active == 0
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
        let effects = &self.shader.lighting.effects;
        let last = index + 1 >= effects.samples.max(1);
        let rows = frame
            .pixels
            .par_chunks_mut(width)
            .zip(frame.stats.par_chunks_mut(width))
            .zip(sums.pixels.par_chunks_mut(width))
            .enumerate()
            .map(|(y, ((pixels, stats), estimates))| {
                if cancelled() {
                    return None;
                }
                let mut totals = crate::render::FrameStats::default();
                let mut stopped = 0;
                let row = pixels.iter_mut().zip(stats).zip(estimates).enumerate();
                for (x, ((pixel, stat), (estimate, done))) in row {
                    if *done {
                        continue;
                    }
                    let (px, py) = position(x as u32, y as u32, index);
                    let (sample, _) = shader.traced(&self.camera.ray_at(px, py), self.arith);
                    totals.add(&sample);
                    let may_stop = estimate.add(sample.rgb);
                    *pixel = estimate.rgb();
                    let mut traced = PixelStats::of(&sample);
                    if index > 0 {
                        traced += *stat;
                        traced.samples = index + 1;
                    }
                    *stat = traced;
                    if last || (effects.adaptive && may_stop) {
                        *done = true;
                        stopped += 1;
                    }
                }
                Some((totals, stopped))
            })
            .collect::<Vec<_>>();
        let mut totals = crate::render::FrameStats::default();
        for row in rows {
            let Some((row, stopped)) = row else {
                return false;
            };
            totals += row;
            sums.active -= stopped;
        }
        frame.totals += totals;
        sums.done += 1;
        true
    }
}
