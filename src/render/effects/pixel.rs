//! Several camera rays per pixel: stratified positions over the pixel (a low-discrepancy
//! sequence rotated per pixel by a hash of its position, so a pixel's samples are the same on
//! every thread and in every pass), box-filtered in linear light. Adaptive sampling takes a
//! first batch everywhere, then more batches where the two halves of a pixel's own samples
//! disagree ([`Estimate`]) or where its neighbours say an edge is near
//! ([`refines`]): a pixel whose first samples all missed an edge is found by the pixels
//! beside it. The rounds are in [`Accumulation`](crate::render::Accumulation).

use super::sampling::{mix, point};
use super::time::nanos_since;
use super::Effects;
use crate::geometry::Ray;
use crate::render::camera::Camera;
use crate::render::gamma;
use serde_json::{json, Value};
use std::ops::AddAssign;
use std::time::Instant;

/// Samples every adaptive pixel takes before it may stop; also the batch it adds at a time.
/// Two: about half of a terrain frame's pixels show one colour to any two samples, and a
/// pixel that stops at two instead of four frees half its rays for the pixels that need 16.
pub const FIRST_BATCH: u32 = 2;

/// How far apart the means of a pixel's two halves of samples may lie on each channel, in
/// display bytes: under one, so that two samples agree only when they show the same bytes.
const TOLERANCE: f64 = 0.75;

/// How far a pixel's mean may stray from the line through two opposite neighbours' means, in
/// display bytes, before an edge is taken to run near it.
const EDGE_STEP: i32 = 2;

/// The four lines through a pixel and two opposite neighbours: across, down and diagonally.
const LINES: [(isize, isize); 4] = [(1, 0), (0, 1), (1, 1), (1, -1)];

/// Whether a pixel of mean `own` (0x00RRGGBB) takes more samples for its neighbours' sake:
/// on some line through it, its mean strays by more than `EDGE_STEP` on a channel from the
/// midpoint of the neighbours' means (`neighbour(dx, dy)`, `None` off the frame, which counts
/// as `own`). A smooth ramp of shading passes; an edge that crosses the pixel, or one beside
/// it the pixel's first samples missed, does not.
pub fn refines(own: u32, neighbour: impl Fn(isize, isize) -> Option<u32>) -> bool {
    let byte = |rgb: u32, shift: u32| i32::from((rgb >> shift) as u8);
    LINES.iter().any(|&(dx, dy)| {
        let a = neighbour(dx, dy).unwrap_or(own);
        let b = neighbour(-dx, -dy).unwrap_or(own);
        [16, 8, 0].into_iter().any(|shift| {
            let stray = byte(a, shift) + byte(b, shift) - 2 * byte(own, shift);
            stray.abs() > 2 * EDGE_STEP
        })
    })
}

/// The purpose a pixel's positions are seeded with.
const PURPOSE: u64 = 0x05a3_b1e5;

/// Spreads frame numbers over the seed's bits (an odd constant: frame 0 adds nothing, so a
/// still keeps its samples).
const FRAME_STRIDE: u64 = 0x9e37_79b9_7f4a_7c15;

/// The position of sample `index` of pixel `(x, y)` of `camera`'s window, in pixel units from
/// the whole image's corner: seeded by the pixel's place in the whole image and the camera's
/// frame, so a tile, a band or a frame rendered alone takes the samples of the whole.
pub fn position(camera: &Camera, x: u32, y: u32, index: u32) -> (f64, f64) {
    let (x, y) = camera.in_image(x, y);
    let frame = camera.frame().wrapping_mul(FRAME_STRIDE);
    let seed = mix(mix(PURPOSE ^ frame ^ u64::from(x)) ^ (u64::from(y) << 32));
    let (u, v) = point(index, seed);
    (f64::from(x) + u, f64::from(y) + v)
}

/// The effects each sample of a pixel is shaded with: the rays towards the sun's disc and
/// the sky shared out among the pixel's samples (each takes `ceil(rays / samples)`), so a
/// pixel that takes every sample takes at least the rays the scene asks for; an adaptive
/// pixel whose few rays disagree takes more samples, as one whose positions do.
pub fn per_sample(effects: &Effects) -> Effects {
    let share = |rays: u32| rays.div_ceil(effects.samples.max(1));
    Effects {
        sun_rays: share(effects.sun_rays),
        sky_rays: share(effects.sky_rays),
        ..*effects
    }
}

/// Shades pixel `(x, y)` with every sample `effects` asks for, each traced by `trace` (which
/// gives its colour); returns the pixel's colour (0x00RRGGBB) and the nanoseconds its samples
/// after the first took.
pub fn shade(
    camera: &Camera,
    (x, y): (u32, u32),
    effects: &Effects,
    mut trace: impl FnMut(&Ray) -> u32,
) -> (u32, u64) {
    let mut estimate = Estimate::default();
    let mut later = None;
    for index in 0..effects.samples.max(1) {
        let (px, py) = position(camera, x, y, index);
        estimate.add(trace(&camera.ray_at(px, py)));
        later.get_or_insert_with(Instant::now);
    }
    (estimate.rgb(), later.map_or(0, nanos_since))
}

/// A pixel's samples so far: their sum in linear light, and their display bytes summed in
/// two halves (see [`Estimate::add`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Estimate {
    sum: [f64; 3],
    halves: [[f64; 3]; 2],
    /// Samples added.
    pub taken: u32,
}

impl Estimate {
    /// Adds a sample (0x00RRGGBB); at the end of a batch, whether the samples agree: the
    /// means of its two halves (the samples of even index, and of odd) lie within
    /// `TOLERANCE` display bytes on every channel. The even samples fill one half of the
    /// pixel (rotated with its positions) and the odd ones the other, each batch putting a
    /// sample in each, so the halves agree where both halves of the pixel show the same
    /// colour: a flat pixel passes at its first batch, an edge, a ramp or a texture the
    /// halves see differently does not. (A spread test that takes the samples as
    /// independent spends more rays for the same error on the terrain scenes: it asks for
    /// samples a stratified set does not need.)
    pub fn add(&mut self, rgb: u32) -> Option<bool> {
        let half = (self.taken % 2) as usize;
        let channels = [16, 8, 0].map(|shift| (rgb >> shift) as u8);
        for (k, c) in channels.into_iter().enumerate() {
            self.sum[k] += gamma::linear(c);
            self.halves[half][k] += f64::from(c);
        }
        self.taken += 1;
        if !self.taken.is_multiple_of(FIRST_BATCH) {
            return None;
        }
        let each = f64::from(self.taken / 2);
        let [a, b] = self.halves;
        Some((0..3).all(|k| (a[k] - b[k]).abs() / each <= TOLERANCE))
    }

    /// The samples' mean, 0x00RRGGBB (black before any).
    pub fn rgb(&self) -> u32 {
        let n = f64::from(self.taken.max(1));
        gamma::pack(self.sum.map(|s| s / n))
    }
}

/// Samples per pixel: how many pixels took how many camera rays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SampleStats {
    /// Pixels finished.
    pub pixels: u64,
    /// Pixels by samples taken: entry `k` counts those that took `2^k` to `2^(k+1) - 1`.
    pub histogram: [u64; 11],
}

impl SampleStats {
    /// Counts one finished pixel that took `samples` camera rays.
    pub fn add(&mut self, samples: u32) {
        self.pixels += 1;
        let bucket = (31 - samples.max(1).leading_zeros()) as usize;
        self.histogram[bucket.min(10)] += 1;
    }

    /// The samples as JSON; `camera_rays` is the frame's primary rays (for their mean).
    pub fn to_json(&self, camera_rays: u64) -> Value {
        json!({
            "mean": camera_rays as f64 / self.pixels.max(1) as f64,
            "pixels_by_power_of_two": self.histogram,
        })
    }
}

impl AddAssign for SampleStats {
    fn add_assign(&mut self, rhs: SampleStats) {
        self.pixels += rhs.pixels;
        for (a, b) in self.histogram.iter_mut().zip(rhs.histogram) {
            *a += b;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The batch's end, after adding `samples` (0x00RRGGBB) one after another.
    fn agree(samples: &[u32]) -> Option<bool> {
        let mut estimate = Estimate::default();
        samples
            .iter()
            .map(|&rgb| estimate.add(rgb))
            .last()
            .flatten()
    }

    /// Two samples of one colour agree at the first batch; a byte apart on one channel they
    /// do not. Later, the even and the odd samples are the halves: a step between them shows
    /// however the samples pair up, and an alternation within each half cancels.
    #[test]
    fn halves_are_the_even_and_the_odd_samples() {
        assert_eq!(agree(&[0x80_40_20, 0x80_40_20]), Some(true));
        assert_eq!(agree(&[0x80_40_20, 0x80_41_20]), Some(false));
        assert_eq!(agree(&[0x80_40_20]), None);
        assert_eq!(agree(&[0x10, 0x11, 0x10, 0x11]), Some(false));
        assert_eq!(agree(&[0x10, 0x11, 0x11, 0x10]), Some(true));
    }
}
