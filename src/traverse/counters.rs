//! Query counters: one struct, summed per frame, kept per pixel.

use derive_more::AddAssign;
use serde::Serialize;

/// Queries of one kind, split into hits ("exists", E) and misses (N).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, AddAssign)]
pub struct HitMiss {
    /// Queries answered "may be hit" (E).
    pub hit: u64,
    /// Queries answered "certainly missed" (N).
    pub miss: u64,
}

impl HitMiss {
    /// Counts one query and passes its answer through. Building with `--features uncounted`
    /// compiles counting out, to measure what it costs (README, 'Performance').
    #[inline]
    pub fn record(&mut self, hit: bool) -> bool {
        if cfg!(feature = "uncounted") {
            return hit;
        }
        if hit {
            self.hit += 1;
        } else {
            self.miss += 1;
        }
        hit
    }
    /// Hits and misses together.
    pub fn total(&self) -> u64 {
        self.hit + self.miss
    }
}

/// What one ray (or a frame of rays) asked of the height field.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, AddAssign)]
pub struct Counters {
    /// Ray against the height field's bounding box.
    pub bbox: HitMiss,
    /// A block of the max-mipmap (the hierarchical method): the ray's lowest height over the
    /// block's part of the path against the block's highest sample.
    pub block: HitMiss,
    /// A camera ray's look-up in its wedge's profile ([`Wedges`](super::Wedges)): its slope
    /// against the profile's bounds; a miss is a certain miss, settled with no walk.
    pub wedge: HitMiss,
    /// A bound kept for the terrain ahead of an occlusion ray (the sun's
    /// [`StripBounds`](crate::heightfield::StripBounds), the sky's
    /// [`SkyBounds`](crate::heightfield::SkyBounds)): a miss is a ray certainly clear beyond
    /// its first cells, which alone are walked.
    pub bound: HitMiss,
    /// A run as a whole: the ray's lowest height over it against its highest sample.
    pub run: HitMiss,
    /// A cell: the ray's lowest height over it against its highest sample, and its highest
    /// height against its lowest sample.
    pub cell: HitMiss,
    /// A triangle test.
    pub triangle: HitMiss,
    /// Bounded-rational results rounded to the denominator bound.
    pub rational_rounded: u64,
    /// Bounded-rational results clamped to the `i64` range.
    pub rational_saturated: u64,
}
