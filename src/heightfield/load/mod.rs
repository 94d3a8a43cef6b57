//! Loading height fields from files: PNG (grayscale, or RGB as luminance or terrain-RGB), PGM
//! (P2, P5), TIFF (8/16-bit integer and floating-point samples, as DEMs use; GeoTIFF's
//! georeferencing), SRTM `.hgt` tiles and ESRI ASCII grids (`.asc`).
//!
//! Every format's size is checked from its header before decoding (see `limits`); whatever a
//! file holds, loading returns a [`LoadError`] that names the file, never a panic. A path that
//! is not a regular file is refused before it is opened, and files are decoded as streams:
//! memory follows the image's size, never the file's.

mod asc;
pub(super) mod geotiff;
mod hgt;
pub(super) mod mosaic;
mod options;
mod pgm;
mod picture;
mod png;
pub(super) mod raster;
mod tiff;
pub(super) mod tiff_chunks;
mod watched;

use super::limits::{self, MAX_DECODED_BYTES, MAX_SAMPLES};
use super::{Heightfield, HeightfieldError};
use crate::regular_file::{self, OpenError};
use raster::Raster;
use std::io::{Cursor, Read, Seek};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use thiserror::Error;
use watched::{Watch, Watched};

pub use asc::AscError;
pub use mosaic::{load_mosaic, MosaicError};
pub use options::{ColourEncoding, LoadOptions, NoDataValue, OptionError};
pub use pgm::PgmError;
pub use picture::picture_kind;
pub use tiff::ChunkError;

/// Why a file could not be loaded as a height field.
#[derive(Debug, Error)]
pub enum LoadError {
    /// A tile store that could not be opened.
    #[error(transparent)]
    Store(Box<super::store::StoreError>),
    // `reason`, not `source`: the message already says it, error chains must not repeat it.
    /// The file could not be read.
    #[error("cannot read {path}: {reason}; check that the file exists and can be read")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why it could not be read.
        reason: std::io::Error,
    },
    /// The path names a directory, a device, a FIFO or a socket.
    #[error("{path} is {what}, not a file; choose a height map file (PNG, PGM, TIFF, .hgt or .asc) instead")]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it names instead ("a directory", ...).
        what: &'static str,
    },
    /// The file has no bytes.
    #[error("{name} is empty (0 bytes); the file may not have been written completely")]
    Empty {
        /// The file's name in messages.
        name: String,
    },
    /// The file does not start as a PNG, PGM, TIFF or ESRI ASCII grid does.
    #[error("{name} is not a PNG, PGM or TIFF image (its first bytes are {start}); heightray reads grayscale or RGB PNG, PGM and TIFF height maps, SRTM .hgt tiles and ESRI ASCII grids")]
    NotAnImage {
        /// The file's name in messages.
        name: String,
        /// Its first bytes, for the message.
        start: String,
    },
    /// A picture (a JPEG, an RGB TIFF): an overlay, not a height map.
    #[error("{name} is {what}, a picture rather than a height map: lay it over a map as an overlay (a scene's [overlay] path; the viewer does so with a dropped picture); height maps are grayscale or terrain-RGB PNGs, PGMs and single-band TIFFs")]
    Picture {
        /// The file's name in messages.
        name: String,
        /// What kind of picture it is.
        what: String,
    },
    /// A TIFF compressed by a method the decoder does not have.
    #[error("{name} is compressed with {method}, which heightray does not read; convert it with GDAL: gdal_translate -co COMPRESS=DEFLATE {name} converted.tif")]
    Compression {
        /// The file's name in messages.
        name: String,
        /// The compression method's name.
        method: String,
    },
    /// The image is truncated or corrupt.
    #[error("{name} is truncated or corrupt: cannot decode the image ({reason}); export or download it again")]
    Decode {
        /// The file's name in messages.
        name: String,
        /// What the decoder found (boxed: decoders' errors are large).
        reason: Box<DecodeFailure>,
    },
    /// An image whose colour type or sample format is not one heightray reads heights from.
    #[error("{name}: {what} is not a height map; use a grayscale image, or RGB (luminance or a terrain-RGB encoding), or a single-band TIFF")]
    Unsupported {
        /// The file's name in messages.
        name: String,
        /// What kind of image it is.
        what: String,
    },
    /// Fewer than 2 samples along a side.
    #[error("{name} is {width}x{height}: a height field needs at least 2x2 samples")]
    TooSmall {
        /// The file's name in messages.
        name: String,
        /// Pixels along x.
        width: u64,
        /// Pixels along y.
        height: u64,
    },
    /// More samples than [`MAX_SAMPLES`].
    #[error("{name} is {width}x{height} = {} samples, more than the limit of {MAX_SAMPLES} (2^31); crop or downsample it", width.saturating_mul(*height))]
    TooManySamples {
        /// The file's name in messages.
        name: String,
        /// Pixels along x.
        width: u64,
        /// Pixels along y.
        height: u64,
    },
    /// Decoding would take more than [`MAX_DECODED_BYTES`].
    #[error("{name}: decoding this {width}x{height} image would take {:.1} GiB, more than the limit of {} GiB; crop it, or store it as 16-bit grayscale", *bytes as f64 / (1u64 << 30) as f64, MAX_DECODED_BYTES >> 30)]
    TooMuchMemory {
        /// The file's name in messages.
        name: String,
        /// Pixels along x.
        width: u64,
        /// Pixels along y.
        height: u64,
        /// Bytes the decoded image would take.
        bytes: u64,
    },
    /// The decoded samples make no valid height field.
    #[error("{name}: {source}")]
    Field {
        /// The file's name in messages.
        name: String,
        /// Why the field was refused.
        source: HeightfieldError,
    },
    /// Tiles that cannot be joined into one map.
    #[error("cannot join {names} into one map: {reason}")]
    Mosaic {
        /// The tiles' names.
        names: String,
        /// Why not (boxed: it names two tiles).
        reason: Box<MosaicError>,
    },
    /// The progress callback asked to stop.
    #[error("loading {name} was cancelled")]
    Cancelled {
        /// The file's name in messages.
        name: String,
    },
}

/// What a decoder found wrong in a file's bytes.
#[derive(Debug, Error)]
pub enum DecodeFailure {
    /// Reading the file failed.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// The PNG decoder's error.
    #[error("{0}")]
    Png(#[from] ::png::DecodingError),
    /// The TIFF decoder's error.
    #[error("{0}")]
    Tiff(#[from] ::tiff::TiffError),
    /// A PNG whose pixels would not fit in memory.
    #[error("the image does not fit in memory")]
    PngTooLarge,
    /// No memory could be had for a PNG's pixels.
    #[error("no memory for its {0} bytes of pixels")]
    NoMemory(usize),
    /// A PGM's header or raster.
    #[error(transparent)]
    Pgm(#[from] PgmError),
    /// An ESRI ASCII grid's header or values.
    #[error(transparent)]
    Asc(#[from] AscError),
    /// A TIFF's strips or tiles.
    #[error(transparent)]
    Chunks(#[from] ChunkError),
    /// An `.hgt` file of a size no tile has.
    #[error(
        "an .hgt tile holds n x n 16-bit samples (2 n^2 bytes), and {0} bytes is no such size"
    )]
    HgtSize(u64),
}

/// Called with the fraction of the file decoding has reached, each time it moves on by 1/256
/// of the file or 64 KiB, whichever is less; breaking cancels the load, even while reading.
pub type Progress<'a> = &'a dyn Fn(f64) -> ControlFlow<()>;

/// Loads a height field from a file with the default options.
pub fn load(path: &Path, z_scale: f64) -> Result<Heightfield, LoadError> {
    load_with(path, &LoadOptions::new(z_scale), &|_| {
        ControlFlow::Continue(())
    })
}

/// Loads a height field from a file, reporting progress. Only a regular file is opened, and
/// only as much of it is read as its image needs.
pub fn load_with(
    path: &Path,
    options: &LoadOptions,
    progress: Progress,
) -> Result<Heightfield, LoadError> {
    let (file, len) = open_regular(path)?;
    if super::store::is_store(&file) {
        return super::store::open(&file, len, path, options)
            .map_err(|e| LoadError::Store(Box::new(e)));
    }
    load_from(file, len, options, &path.display().to_string(), progress)
}

/// Opens the regular file at `path`, with its length.
fn open_regular(path: &Path) -> Result<(std::fs::File, u64), LoadError> {
    regular_file::open(path).map_err(|error| match error {
        OpenError::NotAFile(what) => LoadError::NotAFile {
            path: path.to_owned(),
            what,
        },
        OpenError::Io(reason) => LoadError::Io {
            path: path.to_owned(),
            reason,
        },
    })
}

/// Loads a height field from the bytes of a file with the default options; `name` labels
/// error messages.
pub fn load_bytes(bytes: &[u8], z_scale: f64, name: &str) -> Result<Heightfield, LoadError> {
    load_bytes_with(bytes, &LoadOptions::new(z_scale), name, &|_| {
        ControlFlow::Continue(())
    })
}

/// Loads a height field from the bytes of a file, reporting progress.
pub fn load_bytes_with(
    bytes: &[u8],
    options: &LoadOptions,
    name: &str,
    progress: Progress,
) -> Result<Heightfield, LoadError> {
    load_from(
        Cursor::new(bytes),
        bytes.len() as u64,
        options,
        name,
        progress,
    )
}

/// Loads a height field from `file`, `len` bytes long, through a buffer.
fn load_from(
    file: impl Read + Seek,
    len: u64,
    options: &LoadOptions,
    name: &str,
    progress: Progress,
) -> Result<Heightfield, LoadError> {
    if len == 0 {
        return Err(LoadError::Empty { name: name.into() });
    }
    let watch = Watch::new(len, progress);
    let input = watch.reader(file);
    let raster = match decode(input, len, name, options.colour) {
        Err(_) if watch.cancelled() => Err(LoadError::Cancelled { name: name.into() }),
        Err(error) => Err(match watch.take_failure() {
            Some(reason) => LoadError::Io {
                path: name.into(),
                reason,
            },
            None => error,
        }),
        ok => ok,
    }?;
    raster
        .into_field(options)
        .map_err(|source| LoadError::Field {
            name: name.into(),
            source,
        })
}

/// Decodes the image of a file, `len` bytes long, in whichever format its first bytes say.
fn decode<R: Read + Seek>(
    mut input: Watched<R>,
    len: u64,
    name: &str,
    colour: ColourEncoding,
) -> Result<Raster, LoadError> {
    let mut start = Vec::with_capacity(8);
    // Back to the start within the buffer: the decoders begin with what was just read.
    (&mut input)
        .take(8)
        .read_to_end(&mut start)
        .and_then(|count| input.back(count as u64))
        .map_err(|e| decode_error(name, e))?;
    match Format::of(&start, name) {
        Some(Format::Pgm) => pgm::decode(input, len, name),
        Some(Format::Png) => png::decode(input, name, colour),
        Some(Format::Tiff) => decode_tiff(input, len, name),
        Some(Format::Hgt) => hgt::decode(input, len, name),
        Some(Format::Asc) => asc::decode(input, len, name),
        None if picture::is_jpeg(&start) => Err(LoadError::Picture {
            name: name.into(),
            what: "a JPEG image".into(),
        }),
        None => Err(LoadError::NotAnImage {
            name: name.into(),
            start: first_bytes(&start),
        }),
    }
}

/// Whether the file at `path` is a TIFF, as loading tells the formats apart (a file that
/// cannot be read is not).
pub(super) fn is_tiff(path: &Path) -> bool {
    let Ok((file, _)) = regular_file::open(path) else {
        return false;
    };
    let mut start = Vec::with_capacity(8);
    file.take(8).read_to_end(&mut start).is_ok()
        && Format::of(&start, &path.display().to_string()) == Some(Format::Tiff)
}

/// The longest TIFF read whole before decoding.
const MOST_TIFF_READ_WHOLE: u64 = 64 << 20;

/// Decodes a TIFF, `len` bytes long. Its strips or tiles may lie in any order in the file, and
/// a decoder jumping between millions of them would make a system call or two at each: a
/// file of up to [`MOST_TIFF_READ_WHOLE`] bytes is read whole first, and jumps cost nothing.
fn decode_tiff<R: Read + Seek>(
    mut input: Watched<R>,
    len: u64,
    name: &str,
) -> Result<Raster, LoadError> {
    if len > MOST_TIFF_READ_WHOLE {
        return tiff::decode(input, len, name);
    }
    let mut bytes = Vec::with_capacity(len as usize);
    (&mut input)
        .take(len)
        .read_to_end(&mut bytes)
        .map_err(|e| decode_error(name, e))?;
    tiff::decode(Cursor::new(bytes), len, name)
}

/// The formats read, told apart by their first bytes (an `.hgt` tile, which has no header, by
/// its name).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Png,
    Pgm,
    Tiff,
    Hgt,
    Asc,
}

impl Format {
    fn of(bytes: &[u8], name: &str) -> Option<Format> {
        if hgt::is_hgt(name) {
            Some(Format::Hgt)
        } else if asc::starts_asc(bytes) {
            Some(Format::Asc)
        } else if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            Some(Format::Png)
        } else if bytes.starts_with(b"P2") || bytes.starts_with(b"P5") {
            Some(Format::Pgm)
        } else if [b"II*\0", b"MM\0*", b"II+\0", b"MM\0+"]
            .iter()
            .any(|magic| bytes.starts_with(*magic))
        {
            Some(Format::Tiff)
        } else {
            None
        }
    }
}

/// Up to 8 leading bytes, for a message about a file that is not an image: as text when all
/// are printable, else in hex.
fn first_bytes(bytes: &[u8]) -> String {
    let start = &bytes[..bytes.len().min(8)];
    if start.iter().all(|b| b.is_ascii_graphic() || *b == b' ') {
        format!("\"{}\"", String::from_utf8_lossy(start))
    } else {
        let hex: Vec<String> = start.iter().map(|b| format!("{b:02x}")).collect();
        format!("{} in hex", hex.join(" "))
    }
}

/// A decoder's error as `LoadError::Decode`.
fn decode_error(name: &str, reason: impl Into<DecodeFailure>) -> LoadError {
    LoadError::Decode {
        name: name.into(),
        reason: Box::new(reason.into()),
    }
}
