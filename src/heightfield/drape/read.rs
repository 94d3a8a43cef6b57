//! Reading a drape's image (PNG, JPEG or TIFF, each through its own decoder) and where it
//! says it lies: a GeoTIFF's tags, or a world file beside it (`.pgw`, `.jgw`, `.tfw`, `.wld`:
//! six lines, the pixel size along x, two rotation terms, the pixel size along y (negative
//! for north up), and the map coordinates of the top-left pixel's centre).

use super::tiff_rgba;
use crate::compact::Compact;
use crate::heightfield::georef::{Georef, Georeferencing, MapUnits};
use crate::heightfield::load::geotiff;
use crate::regular_file::{self, OpenError};
use image::{DynamicImage, ImageDecoder, ImageReader};
use std::io::BufReader;
use std::path::{Path, PathBuf};
use thiserror::Error;

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
        /// The decoder's message.
        reason: String,
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
        /// What is wrong with it.
        reason: String,
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
        /// Why not.
        why: String,
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

/// Where an image says its pixels lie.
pub enum OwnPlace {
    /// A GeoTIFF's tags, with their units.
    Map(Georef),
    /// A world file: the map coordinates of the bottom-left pixel's centre and the pixel
    /// size, in the map's units (a world file does not say which).
    WorldFile {
        /// Map coordinates of the bottom-left pixel's centre.
        origin: [f64; 2],
        /// Map units per pixel along x and y.
        spacing: [f64; 2],
    },
}

/// A decoded image and its placement, if it has one.
pub struct Image {
    /// Pixels along x.
    pub width: usize,
    /// Pixels along y.
    pub height: usize,
    /// RGBA bytes by rows, the top row first.
    pub pixels: Vec<u8>,
    /// Where it says it lies.
    pub place: Option<OwnPlace>,
}

/// Decodes the image at `path` and finds its georeferencing.
pub fn read(path: &Path) -> Result<Image, DrapeError> {
    let io = |reason| DrapeError::Io {
        path: path.to_owned(),
        reason,
    };
    let decode = |reason: String| DrapeError::Decode {
        path: path.to_owned(),
        reason,
    };
    let open = || {
        regular_file::open(path).map_err(|error| match error {
            OpenError::NotAFile(what) => DrapeError::NotAFile {
                path: path.to_owned(),
                what,
            },
            OpenError::Io(reason) => io(reason),
        })
    };
    let (file, len) = open()?;
    let reader = ImageReader::new(BufReader::new(file))
        .with_guessed_format()
        .map_err(io)?;
    let format = reader.format();
    let admit = |width: u32, height: u32| {
        if u64::from(width) * u64::from(height) > MOST_OVERLAY_PIXELS {
            return Err(DrapeError::TooLarge {
                path: path.to_owned(),
                width,
                height,
            });
        }
        Ok(())
    };
    let (width, height, pixels) = if format == Some(image::ImageFormat::Tiff) {
        // The `tiff` crate itself: `image` does not turn YCbCr (JPEG-compressed) into RGB.
        drop(reader);
        let (file, _) = open()?;
        let rgba = tiff_rgba::decode(BufReader::new(file)).map_err(decode)?;
        admit(rgba.width, rgba.height)?;
        (rgba.width, rgba.height, rgba.pixels)
    } else if format == Some(image::ImageFormat::Png) {
        let png = super::png::decode(reader.into_inner(), len, admit, decode)?;
        (png.width, png.height, png.rgba)
    } else if format == Some(image::ImageFormat::Jpeg) {
        let jpeg = super::jpeg::decode(reader.into_inner(), len, admit, decode)?;
        (jpeg.width, jpeg.height, jpeg.rgba)
    } else {
        let decoder = reader.into_decoder().map_err(|e| decode(e.to_string()))?;
        let (width, height) = decoder.dimensions();
        if width == 0 || height == 0 {
            return Err(decode(format!("it is {width}x{height} pixels")));
        }
        admit(width, height)?;
        let image = DynamicImage::from_decoder(decoder).map_err(|e| decode(e.to_string()))?;
        (width, height, image.into_rgba8().into_raw())
    };
    let place = if format == Some(image::ImageFormat::Tiff) {
        let (file, _) = open()?;
        tiff_place(file, height).map_err(|reason| DrapeError::Placement {
            path: path.to_owned(),
            reason,
        })?
    } else {
        None
    };
    let place = match place {
        Some(place) => Some(place),
        None => world_file(path, height).map_err(|reason| DrapeError::Placement {
            path: path.to_owned(),
            reason,
        })?,
    };
    Ok(Image {
        width: width as usize,
        height: height as usize,
        pixels,
        place,
    })
}

/// A GeoTIFF's georeferencing, if it has any.
fn tiff_place(file: std::fs::File, height: u32) -> Result<Option<OwnPlace>, String> {
    let mut decoder =
        tiff::decoder::Decoder::new(BufReader::new(file)).map_err(|e| e.to_string())?;
    match geotiff::georeferencing(&mut decoder, height) {
        Georeferencing::None => Ok(None),
        Georeferencing::Map(georef) => Ok(Some(OwnPlace::Map(georef))),
        Georeferencing::Ignored(reason) => Err(format!("its georeferencing is unusable: {reason}")),
    }
}

/// The longest world file read: six numbers take a few hundred bytes at most.
const MOST_WORLD_FILE_BYTES: u64 = 4096;

/// The world file beside `path`, if there is one: `NAME.pgw` for `NAME.png` (the extension's
/// first and last letters and `w`), `NAME.pngw`, or `NAME.wld`.
fn world_file(path: &Path, height: u32) -> Result<Option<OwnPlace>, String> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let mut candidates = vec!["wld".to_owned(), format!("{extension}w")];
    if let (Some(first), Some(last)) = (extension.chars().next(), extension.chars().last()) {
        candidates.insert(0, format!("{first}{last}w"));
    }
    let Some(world) = candidates
        .iter()
        .map(|e| path.with_extension(e))
        .find(|p| p.is_file())
    else {
        return Ok(None);
    };
    let shown = world.display();
    let (file, len) = regular_file::open(&world).map_err(|error| match error {
        OpenError::NotAFile(what) => format!("its world file {shown} is {what}, not a file"),
        OpenError::Io(e) => format!("its world file {shown} cannot be opened: {e}"),
    })?;
    if len > MOST_WORLD_FILE_BYTES {
        return Err(format!(
            "its world file {shown} is too large ({len} bytes; a world file is six numbers, \
             at most {MOST_WORLD_FILE_BYTES} bytes)"
        ));
    }
    let text = std::io::read_to_string(file)
        .map_err(|e| format!("its world file {shown} cannot be read as text: {e}"))?;
    let values: Vec<f64> = text
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| format!("its world file {shown} holds something other than numbers"))?;
    let [sx, rot_y, rot_x, sy, x, y] = values[..] else {
        return Err(format!(
            "its world file {shown} has {} numbers, not 6",
            values.len()
        ));
    };
    if rot_x != 0.0 || rot_y != 0.0 {
        return Err(format!("its world file {shown} is rotated or sheared"));
    }
    // Checked for finite, positive spacing as any georeferencing is (units follow the map's).
    let spacing = [sx, -sy];
    let origin = [x, y + sy * f64::from(height - 1)];
    Georef::new(origin, spacing, MapUnits::Degrees)
        .map_err(|reason| format!("its world file {shown} is unusable: {reason}"))?;
    Ok(Some(OwnPlace::WorldFile { origin, spacing }))
}
