//! A frame being rendered: its pixels as bytes (and, where 16-bit output is asked, as 16-bit
//! words from the same linear colours), each pixel's statistics, and the totals.

use super::stats::{FrameStats, PixelStats};

/// An image with its per-pixel statistics and running totals.
#[derive(Debug)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// 0x00RRGGBB, row-major from the top.
    pub pixels: Vec<u32>,
    /// The pixels' 16-bit display values (red, green, blue), in the order of `pixels`, made
    /// from their linear colours as the bytes are (see [`Frame::with_words`]); empty unless
    /// asked, so that an 8-bit frame costs nothing more.
    pub words: Vec<[u16; 3]>,
    /// Each pixel's queries, in the order of `pixels`.
    pub stats: Vec<PixelStats>,
    /// Totals over the pixels traced so far.
    pub totals: FrameStats,
    /// Passes completed.
    pub passes_done: usize,
}

impl Frame {
    /// A black frame of `width x height` pixels with no pass rendered.
    pub fn new(width: u32, height: u32) -> Frame {
        let n = width as usize * height as usize;
        Frame {
            width,
            height,
            pixels: vec![0; n],
            words: Vec::new(),
            stats: vec![PixelStats::default(); n],
            totals: FrameStats::default(),
            passes_done: 0,
        }
    }

    /// A black frame that also keeps each pixel's 16-bit display values ([`Frame::words`]):
    /// the same bytes, and words as fine as the linear colours they come from.
    pub fn with_words(width: u32, height: u32) -> Frame {
        Frame {
            words: vec![[0; 3]; width as usize * height as usize],
            ..Frame::new(width, height)
        }
    }
}

impl Clone for Frame {
    fn clone(&self) -> Frame {
        let mut copy = Frame::new(0, 0);
        copy.clone_from(self);
        copy
    }

    /// Copies into `self`'s buffers: the viewer refines a copy of every pass it shows, and
    /// a frame is tens of megabytes that need not be allocated and paged in again.
    fn clone_from(&mut self, source: &Frame) {
        // (Destructured, so that a field added later is copied or left out on purpose.)
        let Frame {
            width,
            height,
            pixels,
            words,
            stats,
            totals,
            passes_done,
        } = source;
        self.width = *width;
        self.height = *height;
        self.pixels.clone_from(pixels);
        self.words.clone_from(words);
        self.stats.clone_from(stats);
        self.totals = *totals;
        self.passes_done = *passes_done;
    }
}
