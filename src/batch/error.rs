//! Why a share, a frame range or a tile grid asked for cannot be used.

use thiserror::Error;

/// A batch option that cannot be used; each message says what is expected.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum BatchError {
    /// Not `I/N` with `I < N`.
    #[error("expected I/N, worker I of N counted from 0 (0/4 to 3/4 for four), got '{0}'")]
    Share(String),
    /// Not a frame range.
    #[error(
        "expected N, A..B (B not included), A..=B, A..B/STEP or all, with whole numbers, got \
         '{0}'"
    )]
    Frames(String),
    /// A frame range that takes no frame.
    #[error("--frames {0} takes no frame: the end must be after the start")]
    NoFrames(String),
    /// Frames past the scene path's last.
    #[error("--frames {asked}: the scene's path has frames 0..{frames} (0 to {})", frames.saturating_sub(1))]
    Beyond {
        /// The frames asked for.
        asked: String,
        /// The path's frames.
        frames: u64,
    },
    /// Not `COLUMNSxROWS` within the limits.
    #[error("expected COLUMNSxROWS, 1 to 256 each (4x4 for 16 tiles), got '{0}'")]
    Tiles(String),
    /// A tile index past the grid's last.
    #[error("there is no tile {index} of {columns}x{rows} ({} tiles, 0 to {})", columns * rows, columns * rows - 1)]
    NoSuchTile {
        /// The index asked for.
        index: u64,
        /// The grid's columns.
        columns: u64,
        /// The grid's rows.
        rows: u64,
    },
    /// An image with fewer pixels along a side than the grid has tiles.
    #[error(
        "a {width}x{height} image cannot be cut into {columns}x{rows} tiles: each needs a pixel"
    )]
    TooSmall {
        /// The image's width.
        width: u32,
        /// The image's height.
        height: u32,
        /// The grid's columns.
        columns: u32,
        /// The grid's rows.
        rows: u32,
    },
}
