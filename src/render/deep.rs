//! What the passes paint: a sample's packed bytes alone, or, where the frame keeps 16-bit
//! words ([`Frame::with_words`](super::Frame::with_words)), its linear colour, from which both
//! the bytes and the words are made. A pixel of several samples is their mean in linear light
//! either way: the bytes as [`pixel::shade`] makes them, the words from the samples' own
//! colours, not from their bytes.

use super::camera::Camera;
use super::effects::pixel;
use super::effects::Effects;
use super::gamma;
use crate::geometry::Ray;
use glam::DVec3;

/// A pixel's colour as painted into a frame.
pub(super) trait Painted: Copy {
    /// 0x00RRGGBB.
    fn rgb(self) -> u32;
    /// The 16-bit display values, where this colour has them.
    fn words(self) -> Option<[u16; 3]>;
}

/// A sample's colour, and how several make a pixel.
pub(super) trait Sampled: Painted {
    /// What a pixel of several samples paints.
    type Mean: Painted;
    /// Shades pixel `(x, y)` with every sample `effects` asks for, each traced by `trace`, as
    /// [`pixel::shade`] does; returns its colour and the nanoseconds its samples after the
    /// first took.
    fn shade(
        camera: &Camera,
        at: (u32, u32),
        effects: &Effects,
        trace: impl FnMut(&Ray) -> Self,
    ) -> (Self::Mean, u64);
}

impl Painted for u32 {
    #[inline(always)]
    fn rgb(self) -> u32 {
        self
    }
    #[inline(always)]
    fn words(self) -> Option<[u16; 3]> {
        None
    }
}

impl Sampled for u32 {
    type Mean = u32;
    fn shade(
        camera: &Camera,
        at: (u32, u32),
        effects: &Effects,
        trace: impl FnMut(&Ray) -> u32,
    ) -> (u32, u64) {
        pixel::shade(camera, at, effects, trace)
    }
}

impl Painted for DVec3 {
    #[inline(always)]
    fn rgb(self) -> u32 {
        gamma::pack(self.to_array())
    }
    #[inline(always)]
    fn words(self) -> Option<[u16; 3]> {
        Some(gamma::words(self.to_array()))
    }
}

impl Sampled for DVec3 {
    type Mean = Mean;
    fn shade(
        camera: &Camera,
        at: (u32, u32),
        effects: &Effects,
        mut trace: impl FnMut(&Ray) -> DVec3,
    ) -> (Mean, u64) {
        let (mut sum, mut taken) = (DVec3::ZERO, 0u32);
        let (rgb, later) = pixel::shade(camera, at, effects, |ray| {
            let colour = trace(ray);
            (sum, taken) = (
                sum + DVec3::from(gamma::shown(colour.to_array())),
                taken + 1,
            );
            colour.rgb()
        });
        let words = gamma::words((sum / f64::from(taken.max(1))).to_array());
        (Mean { rgb, words }, later)
    }
}

/// A pixel of several samples: the bytes of their mean as the 8-bit frame has them, and the
/// words of the mean of their linear colours.
#[derive(Clone, Copy, Debug)]
pub(super) struct Mean {
    rgb: u32,
    words: [u16; 3],
}

impl Painted for Mean {
    fn rgb(self) -> u32 {
        self.rgb
    }
    fn words(self) -> Option<[u16; 3]> {
        Some(self.words)
    }
}

/// A frame's `words` cut as its pixels are, into chunks of `size` of `pixels` in all: the
/// chunks, or as many `None` where the frame keeps no words.
pub(super) fn chunks<T>(words: &mut [T], size: usize, pixels: usize) -> Vec<Option<&mut [T]>> {
    if words.is_empty() {
        return (0..pixels.div_ceil(size.max(1))).map(|_| None).collect();
    }
    words.chunks_mut(size.max(1)).map(Some).collect()
}
