//! Several camera rays per pixel: stratified positions over the pixel (a low-discrepancy
//! sequence rotated per pixel by a hash of its position, so a pixel's samples are the same on
//! every thread and in every pass), box-filtered in linear light. Adaptive sampling takes a
//! first batch, then more batches only while the samples' mean is not yet known to within a
//! display byte. The decision is the pixel's own ([`Estimate`]), so a view that adds one
//! sample of every pixel at a time stops each pixel where `render` does.

use super::sampling::{mix, point};
use super::Effects;
use crate::render::camera::Camera;
use crate::render::gamma;
use crate::Ray;

/// Samples every adaptive pixel takes before it may stop; also the batch it adds at a time.
pub const FIRST_BATCH: u32 = 4;

/// Half-width of the confidence interval allowed on each channel's mean, in display bytes.
const TOLERANCE: f64 = 1.0;

/// Student's t at 95% two-sided for the degrees of freedom of a pixel's samples (n - 1,
/// looked up from 3 on; 2.0 from 30 on).
fn student_t(dof: u32) -> f64 {
    const T: [f64; 8] = [3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228];
    match dof {
        0..=2 => 4.303,
        3..=10 => T[dof as usize - 3],
        11..=29 => 2.1,
        _ => 2.0,
    }
}

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

/// Shades pixel `(x, y)` with the samples `effects` asks for, each traced by `trace` (which
/// gives its colour); returns the pixel's colour (0x00RRGGBB) and the samples taken.
pub fn shade(
    camera: &Camera,
    (x, y): (u32, u32),
    effects: &Effects,
    mut trace: impl FnMut(&Ray) -> u32,
) -> (u32, u32) {
    let mut estimate = Estimate::default();
    for index in 0..effects.samples.max(1) {
        let (px, py) = position(x, y, index);
        let may_stop = estimate.add(trace(&camera.ray_at(px, py)));
        if effects.adaptive && may_stop {
            break;
        }
    }
    (estimate.rgb(), estimate.taken)
}

/// A pixel's samples so far: their sum in linear light, and their display bytes' moments.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Estimate {
    sum: [f64; 3],
    bytes: [f64; 3],
    squares: [f64; 3],
    /// Samples added.
    pub taken: u32,
}

impl Estimate {
    /// Adds a sample (0x00RRGGBB); true where an adaptive pixel may stop here: at the end of
    /// a batch whose samples pin every channel's mean to within [`TOLERANCE`] bytes at 95%
    /// confidence (Student's t on the samples' own spread).
    pub fn add(&mut self, rgb: u32) -> bool {
        let channels = [16, 8, 0].map(|shift| (rgb >> shift) as u8);
        for (k, c) in channels.into_iter().enumerate() {
            self.sum[k] += gamma::linear(c);
            let c = f64::from(c);
            self.bytes[k] += c;
            self.squares[k] += c * c;
        }
        self.taken += 1;
        let n = self.taken;
        if !n.is_multiple_of(FIRST_BATCH) {
            return false;
        }
        let count = f64::from(n);
        (0..3).all(|k| {
            let mean = self.bytes[k] / count;
            let variance = ((self.squares[k] - count * mean * mean) / (count - 1.0)).max(0.0);
            student_t(n - 1) * (variance / count).sqrt() <= TOLERANCE
        })
    }

    /// The samples' mean, 0x00RRGGBB (black before any).
    pub fn rgb(&self) -> u32 {
        let n = f64::from(self.taken.max(1));
        gamma::pack(self.sum.map(|s| s / n))
    }
}
