//! Why a height field could not be built.

use super::{MAX_SAMPLES, MOST_HEIGHT};
use crate::compact::Compact;
use thiserror::Error;

/// Why a height field could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum HeightfieldError {
    /// Fewer than 2 samples along a side: not a single cell.
    #[error("a height field needs at least 2x2 samples, this one is {width}x{height}")]
    TooSmall {
        /// Samples along x.
        width: usize,
        /// Samples along y.
        height: usize,
    },
    /// More samples than [`MAX_SAMPLES`].
    #[error("{width}x{height} is {} samples, more than the limit of {MAX_SAMPLES}", *width as u64 * *height as u64)]
    TooLarge {
        /// Samples along x.
        width: usize,
        /// Samples along y.
        height: usize,
    },
    /// A window that is not all inside its map.
    #[error(
        "the window {},{},{},{} (x,y,width,height) is not inside the {size}x{size} map",
        window[0], window[1], window[2], window[3]
    )]
    Window {
        /// Its column, row, width and height.
        window: [usize; 4],
        /// The map's samples per side.
        size: usize,
    },
    /// A z scale that is negative, NaN or infinite.
    #[error("z scale must be a finite number >= 0, got {}", Compact(*.0))]
    BadZScale(f64),
    /// A z scale whose heights would reach beyond [`MOST_HEIGHT`].
    #[error(
        "z scale {0:e} is out of range: heights would reach beyond ±{MOST_HEIGHT:e}; give a z \
         scale or exaggeration that keeps them within it"
    )]
    HeightsOutOfRange(f64),
    /// A maxval of 0 or above 65535.
    #[error("maxval must be between 1 and 65535, got {0}")]
    BadMaxval(u32),
    /// Fewer or more samples than width times height.
    #[error("expected {expected} samples for the given size, got {got}")]
    SampleCount {
        /// Width times height.
        expected: usize,
        /// Samples given.
        got: usize,
    },
    /// A sample above the raster's maxval.
    #[error("sample {sample} at x={x}, y={y} exceeds maxval {maxval}")]
    SampleAboveMaxval {
        /// The sample value.
        sample: u16,
        /// Its column.
        x: usize,
        /// Its row.
        y: usize,
        /// The raster's maxval.
        maxval: u16,
    },
    /// An offset mapping ([`Quantisation::Offset`](super::Quantisation::Offset)) whose heights are not finite (scaled or
    /// not), or whose step is negative.
    #[error(
        "heights must be finite with a step >= 0, got lowest {} and step {}",
        Compact(*lowest),
        Compact(*step)
    )]
    BadOffset {
        /// The raster value of sample 0.
        lowest: f64,
        /// The raster value of one sample step.
        step: f64,
    },
    /// Every sample holds no data.
    #[error("every sample is no-data: there is no terrain to show")]
    AllNoData,
}
