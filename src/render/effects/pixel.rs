//! Several camera rays per pixel: stratified positions over the pixel (a low-discrepancy
//! sequence rotated per pixel by a hash of its position, so a pixel's samples are the same on
//! every thread and in every pass), box-filtered in linear light.
//!
//! Adaptive sampling doubles a pixel's samples (4, 8, 16, ...) while their two halves
//! disagree. Every power-of-two prefix of the sequence is stratified over the pixel, and so is
//! each of its halves: the two half means are independent estimates of the same kind, and
//! half their difference estimates the error of the whole prefix's mean, stratification
//! included (the samples' own spread would overstate it where the pixel holds a smooth
//! gradient). A pixel stops at a prefix whose estimate is within [`TOLERANCE`] on every
//! channel, with at least [`FIRST_BATCH`] samples: a stopped pixel has the error of a
//! stratified set, as if its samples had been fixed in advance.

use super::sampling::{mix, point};
use super::Effects;
use crate::render::camera::Camera;
use crate::render::gamma;
use crate::render::shade::Sample;
use crate::Ray;

/// Samples every adaptive pixel takes before it may stop.
pub const FIRST_BATCH: u32 = 4;

/// The error estimate a pixel may stop at, in linear light (0 to 1), on each channel.
const TOLERANCE: f64 = 0.002;

/// The purpose a pixel's positions are seeded with.
const PURPOSE: u64 = 0x05a3_b1e5;

/// The sub-pixel position of sample `index` of pixel `(x, y)`, in pixel units from its corner.
pub fn position(x: u32, y: u32, index: u32) -> (f64, f64) {
    let seed = mix(mix(PURPOSE ^ u64::from(x)) ^ (u64::from(y) << 32));
    let (u, v) = point(index, seed);
    (f64::from(x) + u, f64::from(y) + v)
}

/// The effects each sample of a pixel is shaded with: the rays towards the sun's disc and
/// the sky shared out among the pixel's samples (each takes `ceil(rays / samples)`), so the
/// pixel as a whole still takes at least the rays the scene asks for; adaptive pixels share
/// them out among the first batch, which must not agree only for lack of rays.
pub fn per_sample(effects: &Effects) -> Effects {
    let least = if effects.adaptive {
        effects.samples.min(FIRST_BATCH)
    } else {
        effects.samples
    };
    let share = |rays: u32| rays.div_ceil(least.max(1));
    Effects {
        sun_rays: share(effects.sun_rays),
        sky_rays: share(effects.sky_rays),
        ..*effects
    }
}

/// Shades pixel `(x, y)` with the samples `effects` asks for, each traced by `trace`;
/// returns the pixel's colour (0x00RRGGBB) and the samples taken.
pub fn shade(
    camera: &Camera,
    (x, y): (u32, u32),
    effects: &Effects,
    mut trace: impl FnMut(&Ray) -> Sample,
) -> (u32, u32) {
    let mut estimate = Estimate::default();
    for index in 0..effects.samples.max(1) {
        let (px, py) = position(x, y, index);
        let may_stop = estimate.add(trace(&camera.ray_at(px, py)).rgb);
        if effects.adaptive && may_stop {
            break;
        }
    }
    (estimate.rgb(), estimate.taken)
}

/// A pixel's samples so far, in linear light.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Estimate {
    sum: [f64; 3],
    /// The sum at the last power of two of samples: the first half of the next check.
    half: [f64; 3],
    /// Samples added.
    pub taken: u32,
}

impl Estimate {
    /// Adds a sample (0x00RRGGBB); true where an adaptive pixel may stop here.
    pub fn add(&mut self, rgb: u32) -> bool {
        let channels = [16, 8, 0].map(|shift| (rgb >> shift) as u8);
        for (s, c) in self.sum.iter_mut().zip(channels) {
            *s += gamma::linear(c);
        }
        self.taken += 1;
        let n = self.taken;
        if !n.is_power_of_two() {
            return false;
        }
        let agree = n >= FIRST_BATCH
            && (0..3).all(|k| (2.0 * self.half[k] - self.sum[k]).abs() <= TOLERANCE * f64::from(n));
        self.half = self.sum;
        agree
    }

    /// The samples' mean, 0x00RRGGBB (black before any).
    pub fn rgb(&self) -> u32 {
        let n = f64::from(self.taken.max(1));
        let channel = |s: f64| u32::from(gamma::byte(s / n));
        (channel(self.sum[0]) << 16) | (channel(self.sum[1]) << 8) | channel(self.sum[2])
    }
}
