//! Samples per pixel added one round at a time: round `k` traces sample `k` of every pixel
//! still taking samples (the position and effect rays [`pixel::shade`] gives it). Adaptive
//! pixels are settled between rounds, after every batch of [`FIRST_BATCH`], from the whole
//! frame's estimates of the round before ([`pixel::refines`]): the decisions depend on no
//! thread or row order, so the viewer, which shows the frame after each round, ends with the
//! image `render` makes, bit for bit. Where the frame keeps 16-bit words, each pixel's mean of
//! its samples' own linear colours gives them.

use super::effects::nanos_since;
use super::effects::pixel::{self, position, Estimate, FIRST_BATCH};
use super::effects::Effects;
use super::gamma;
use crate::render::deep;
use crate::render::frame::Frame;
use crate::render::passes::{clearance, Renderer};
use crate::render::stats::PixelStats;
use glam::DVec3;
use rayon::prelude::*;
use std::time::Instant;

/// One pixel's samples so far.
#[derive(Clone, Copy, Debug, Default)]
struct Taking {
    estimate: Estimate,
    /// The sum of its samples' linear colours, which the words are the mean of.
    linear: DVec3,
    /// Whether its own samples agree (as of the last full batch).
    agrees: bool,
    /// Whether it stopped taking samples.
    done: bool,
}

/// The running estimates of a frame's pixels.
#[derive(Clone, Debug)]
pub struct Accumulation {
    pixels: Vec<Taking>,
    width: usize,
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
            pixels: vec![Taking::default(); n],
            width: width as usize,
            done: 0,
            total,
            active: n,
        }
    }

    /// Whether every pixel has taken its samples.
    pub fn complete(&self) -> bool {
        self.done >= self.total || self.active == 0
    }

    /// Stops every active pixel that [`pixel::refines`] leaves alone, judged on the means
    /// as they are now.
    fn settle(&mut self) {
        let width = self.width;
        let height = self.pixels.len() / width.max(1);
        let means: Vec<u32> = self.pixels.iter().map(|p| p.estimate.rgb()).collect();
        let mean = |x: usize, y: usize, dx: isize, dy: isize| {
            let (nx, ny) = (x.checked_add_signed(dx), y.checked_add_signed(dy));
            match (nx, ny) {
                (Some(nx), Some(ny)) if nx < width && ny < height => Some(means[ny * width + nx]),
                _ => None,
            }
        };
        for (at, taking) in self.pixels.iter_mut().enumerate() {
            if taking.done {
                continue;
            }
            let (x, y) = (at % width, at / width);
            let edge = pixel::refines(means[at], |dx, dy| mean(x, y, dx, dy));
            if taking.agrees && !edge {
                taking.done = true;
                self.active -= 1;
            }
        }
    }
}

/// How far, in pixels, what lies outside a window can change the window's pixels: each
/// settling looks one pixel further (at the neighbours' means, which depend on their own
/// settling before), and a frame of `effects` settles at most once a batch. Zero without
/// adaptive samples, where every pixel is its own. A tile rendered with this margin around it
/// has the pixels of the whole image.
pub fn reach(effects: &Effects) -> u32 {
    if effects.adaptive && effects.samples > 1 {
        effects.samples.div_ceil(FIRST_BATCH)
    } else {
        0
    }
}

impl Renderer<'_> {
    /// Renders the frame in rounds of samples to the end, each pixel's batch of a round taken
    /// at once (the terrain its rays cross is then still in the caches): the image of
    /// [`Renderer::accumulate`]'s rounds of one sample, whose decisions wait for a batch too.
    pub fn render_in_rounds(&self, frame: &mut Frame) {
        self.render_in_rounds_until(frame, &|| false);
    }

    /// The image [`Renderer::render`] makes, adaptive samples or not, asking `cancelled`
    /// before each row or band; false when it said yes (the frame is then to be dropped).
    pub fn render_cancellable(
        &self,
        frame: &mut Frame,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> bool {
        let effects = &self.shader.lighting.effects;
        if effects.adaptive && effects.samples > 1 {
            return self.render_in_rounds_until(frame, cancelled);
        }
        while !frame.complete() {
            if !self.render_pass(frame, cancelled) {
                return false;
            }
        }
        true
    }

    /// [`Renderer::render_in_rounds`], cancellable as [`Renderer::render_cancellable`].
    fn render_in_rounds_until(
        &self,
        frame: &mut Frame,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> bool {
        let effects = &self.shader.lighting.effects;
        let mut sums = Accumulation::new(frame.width, frame.height, effects.samples.max(1));
        while !sums.complete() {
            if !self.add_round(&mut sums, frame, cancelled, FIRST_BATCH) {
                return false;
            }
        }
        for taking in &sums.pixels {
            frame.totals.effects.add_pixel(taking.estimate.taken);
        }
        frame.passes_done = crate::render::passes::PASS_BLOCKS.len();
        true
    }

    /// Adds the next round of samples to `sums` and paints their mean into `frame` (on the
    /// current rayon pool). Returns false when `cancelled` turned true (asked before each
    /// row): the round is then partly added, and both are to be dropped.
    pub fn accumulate(
        &self,
        sums: &mut Accumulation,
        frame: &mut Frame,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> bool {
        self.add_round(sums, frame, cancelled, 1)
    }

    /// [`Renderer::accumulate`] adding up to `count` samples to each pixel, up to the end of
    /// the current batch.
    fn add_round(
        &self,
        sums: &mut Accumulation,
        frame: &mut Frame,
        cancelled: &(dyn Fn() -> bool + Sync),
        count: u32,
    ) -> bool {
        let width = frame.width as usize;
        let first = sums.done;
        let total = self.shader.lighting.effects.samples.max(1);
        let batch_end = (first / FIRST_BATCH + 1) * FIRST_BATCH;
        let end = (first + count).min(batch_end).min(total);
        let shader = self.shader.per_sample();
        let effects = &self.shader.lighting.effects;
        let last = end >= total;
        let wedges = self.shader.wedges(self.camera.eye(), self.arith);
        let words = deep::chunks(&mut frame.words, width, frame.pixels.len());
        let rows = frame
            .pixels
            .par_chunks_mut(width)
            .zip(frame.stats.par_chunks_mut(width))
            .zip(sums.pixels.par_chunks_mut(width))
            .zip(words)
            .enumerate()
            .map(|(y, (((pixels, stats), takings), mut words))| {
                if cancelled() {
                    return None;
                }
                let row_start = Instant::now();
                let mut totals = crate::render::FrameStats::default();
                let mut stopped = 0;
                let row = pixels.iter_mut().zip(stats).zip(takings).enumerate();
                for (x, ((pixel, stat), taking)) in row {
                    if taking.done {
                        continue;
                    }
                    // The samples after a pixel's first, where this round holds both.
                    let mut later = None;
                    for index in first..end {
                        if index == 1 && first == 0 {
                            later = Some(Instant::now());
                        }
                        let (px, py) = position(&self.camera, x as u32, y as u32, index);
                        let ray = self.camera.ray_at(px, py);
                        let clearance = clearance(wedges.as_ref(), &ray, &mut totals);
                        let (sample, _, colour) = shader.traced_linear(&ray, self.arith, clearance);
                        taking.linear += colour;
                        totals.add(&sample);
                        if let Some(agrees) = taking.estimate.add(sample.rgb) {
                            taking.agrees = agrees;
                        }
                        let mut traced = PixelStats::of(&sample);
                        if index > 0 {
                            traced += *stat;
                            traced.samples = index + 1;
                        }
                        *stat = traced;
                    }
                    totals.time.later_samples += later.map_or(0, nanos_since);
                    *pixel = taking.estimate.rgb();
                    if let Some(words) = words.as_deref_mut() {
                        let taken = f64::from(taking.estimate.taken.max(1));
                        words[x] = gamma::words((taking.linear / taken).to_array());
                    }
                    if last {
                        taking.done = true;
                        stopped += 1;
                    }
                }
                let row_time = nanos_since(row_start);
                totals.time.traced += row_time;
                if first > 0 {
                    totals.time.later_samples += row_time;
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
        sums.done = end;
        if effects.adaptive && !last && sums.done.is_multiple_of(FIRST_BATCH) {
            sums.settle();
        }
        true
    }
}
