//! Why an image could not be draped over the map, and the limit on an overlay's size.

use crate::compact::Compact;
use crate::heightfield::crs::CrsError;
use crate::heightfield::georef::GeorefError;
use std::path::PathBuf;
use thiserror::Error;
use tiff::ColorType;

/// The most pixels an overlay may have: its colours are kept as 4 bytes a pixel (256 MiB at
/// the limit), several times finer than any window shows a map.
pub const MOST_OVERLAY_PIXELS: u64 = 1 << 26;

/// Why an image could not be draped over the map.
#[derive(Debug, Error)]
pub enum DrapeError {
    /// The opacity is not a number from 0 to 1.
    #[error("overlay opacity must be a number from 0 to 1, got {}", Compact(*.0))]
    Opacity(f64),
    /// The file could not be read.
    #[error("cannot read overlay {path}: {reason}; check that the file exists and can be read")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why it could not be read.
        reason: std::io::Error,
    },
    /// The path names a directory, a device, a FIFO or a socket.
    #[error("overlay {path} is {what}, not a file; choose an image (PNG, JPEG or TIFF)")]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it names instead.
        what: &'static str,
    },
    /// Not an image the decoders read, or a broken one.
    #[error("overlay {path} cannot be decoded as a PNG, JPEG or TIFF image: {reason}")]
    Decode {
        /// The file.
        path: PathBuf,
        /// What the decoder found (boxed: a TIFF decoder's error is large).
        reason: Box<ImageFailure>,
    },
    /// More pixels than an overlay may have.
    #[error(
        "overlay {path} is {width}x{height} pixels, more than the limit of \
         {MOST_OVERLAY_PIXELS} (8192x8192) for an overlay; downsample it"
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Pixels along x.
        width: u32,
        /// Pixels along y.
        height: u32,
    },
    /// Its georeferencing cannot place it on the map.
    #[error("overlay {path}: {reason}")]
    Placement {
        /// The file.
        path: PathBuf,
        /// What is wrong with it (boxed: a TIFF decoder's error is large).
        reason: Box<PlacementError>,
    },
    /// It and the map are in different coordinate systems, and it cannot be reprojected.
    #[error(
        "overlay {path} is in {own}, the map in {map}, and it cannot be reprojected ({why}); \
         reproject it to the map's CRS (gdalwarp -t_srs)"
    )]
    Crs {
        /// The file.
        path: PathBuf,
        /// The overlay's coordinate system.
        own: String,
        /// The map's.
        map: String,
        /// Why not (boxed: PROJ's error is large).
        why: Box<ReprojectError>,
    },
    /// Placed by its georeferencing, it covers none of the map.
    #[error(
        "overlay {path} lies outside the map: its georeferencing places it over none of \
         the map's cells"
    )]
    Outside {
        /// The file.
        path: PathBuf,
    },
}

/// What a decoder found wrong with an overlay's image.
#[derive(Debug, Error)]
pub enum ImageFailure {
    /// A TIFF's pixels.
    #[error(transparent)]
    Tiff(#[from] TiffRgbaError),
    /// The PNG, JPEG or `image` decoder's message.
    #[error("{0}")]
    Decoder(String),
}

/// Why a TIFF's pixels cannot be read as an overlay's.
#[derive(Debug, Error)]
pub enum TiffRgbaError {
    /// The decoder's error.
    #[error("{0}")]
    Tiff(#[from] tiff::TiffError),
    /// More pixels than an overlay may have.
    #[error("it is {width}x{height} pixels, too many for an overlay")]
    TooLarge {
        /// Pixels along x.
        width: u32,
        /// Pixels along y.
        height: u32,
    },
    /// Samples neither 8 nor 16-bit integers.
    #[error("its {0:?} samples are not 8 or 16-bit integers")]
    Samples(ColorType),
    /// A colour type overlays do not use.
    #[error("its colour type {0:?} is not read for overlays")]
    Colour(ColorType),
    /// Fewer samples than the image's size.
    #[error("it holds fewer samples than its size says")]
    Short,
}

/// Why an overlay's own georeferencing cannot place it.
#[derive(Debug, Error)]
pub enum PlacementError {
    /// Its TIFF tags could not be read.
    #[error("{0}")]
    Tiff(#[from] tiff::TiffError),
    /// Its GeoTIFF tags place no north-up grid.
    #[error("its georeferencing is unusable: {0}")]
    Unusable(String),
    /// The world file names a directory or a device.
    #[error("its world file {} is {what}, not a file", world.display())]
    WorldNotAFile {
        /// The world file.
        world: PathBuf,
        /// What it names instead.
        what: &'static str,
    },
    /// The world file could not be opened.
    #[error("its world file {} cannot be opened: {reason}", world.display())]
    WorldOpen {
        /// The world file.
        world: PathBuf,
        /// Why not.
        reason: std::io::Error,
    },
    /// Longer than any world file.
    #[error(
        "its world file {} is too large ({len} bytes; a world file is six numbers, at most \
         {MOST_WORLD_FILE_BYTES} bytes)",
        world.display()
    )]
    WorldTooLarge {
        /// The world file.
        world: PathBuf,
        /// Its bytes.
        len: u64,
    },
    /// The world file is not UTF-8 text.
    #[error("its world file {} cannot be read as text: {reason}", world.display())]
    WorldNotText {
        /// The world file.
        world: PathBuf,
        /// Why not.
        reason: std::io::Error,
    },
    /// Something other than numbers.
    #[error("its world file {} holds something other than numbers", .0.display())]
    WorldNotNumbers(PathBuf),
    /// Not six numbers.
    #[error("its world file {} has {count} numbers, not 6", world.display())]
    WorldCount {
        /// The world file.
        world: PathBuf,
        /// How many numbers it holds.
        count: usize,
    },
    /// Rotation terms.
    #[error("its world file {} is rotated or sheared", .0.display())]
    WorldRotated(PathBuf),
    /// A pixel size or corner that makes no georeferencing.
    #[error("its world file {} is unusable: {reason}", world.display())]
    WorldUnusable {
        /// The world file.
        world: PathBuf,
        /// Why not.
        reason: GeorefError,
    },
}

/// The longest world file read: six numbers take a few hundred bytes at most.
pub const MOST_WORLD_FILE_BYTES: u64 = 4096;

/// Why an overlay cannot be reprojected onto the map.
#[derive(Debug, Error)]
pub enum ReprojectError {
    /// A coordinate system without an EPSG code.
    #[error("{0} has no EPSG code to reproject by")]
    NoCode(String),
    /// PROJ could not make the transformation.
    #[error(transparent)]
    Crs(#[from] CrsError),
}
