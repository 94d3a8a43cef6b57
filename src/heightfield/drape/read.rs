//! Reading a drape's image (PNG, JPEG or TIFF, each through its own decoder) and where it
//! says it lies: a GeoTIFF's tags, or a world file beside it (`.pgw`, `.jgw`, `.tfw`, `.wld`:
//! six lines, the pixel size along x, two rotation terms, the pixel size along y (negative
//! for north up), and the map coordinates of the top-left pixel's centre).

use super::error::{
    DrapeError, ImageFailure, PlacementError, MOST_OVERLAY_PIXELS, MOST_WORLD_FILE_BYTES,
};
use super::tiff_rgba;
use crate::heightfield::georef::{Georef, Georeferencing, MapUnits};
use crate::heightfield::load::geotiff;
use crate::regular_file::{self, OpenError};
use image::{DynamicImage, ImageDecoder, ImageReader};
use std::io::BufReader;
use std::path::Path;

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
    let decode = |reason: ImageFailure| DrapeError::Decode {
        path: path.to_owned(),
        reason: Box::new(reason),
    };
    let decoder_said = |reason: String| decode(ImageFailure::Decoder(reason));
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
        let rgba = tiff_rgba::decode(BufReader::new(file)).map_err(|e| decode(e.into()))?;
        admit(rgba.width, rgba.height)?;
        (rgba.width, rgba.height, rgba.pixels)
    } else if format == Some(image::ImageFormat::Png) {
        let png = super::png::decode(reader.into_inner(), len, admit, decoder_said)?;
        (png.width, png.height, png.rgba)
    } else if format == Some(image::ImageFormat::Jpeg) {
        let jpeg = super::jpeg::decode(reader.into_inner(), len, admit, decoder_said)?;
        (jpeg.width, jpeg.height, jpeg.rgba)
    } else {
        let decoder = reader
            .into_decoder()
            .map_err(|e| decoder_said(e.to_string()))?;
        let (width, height) = decoder.dimensions();
        if width == 0 || height == 0 {
            return Err(decoder_said(format!("it is {width}x{height} pixels")));
        }
        admit(width, height)?;
        let image = DynamicImage::from_decoder(decoder).map_err(|e| decoder_said(e.to_string()))?;
        (width, height, image.into_rgba8().into_raw())
    };
    let place = if format == Some(image::ImageFormat::Tiff) {
        let (file, _) = open()?;
        tiff_place(file, height).map_err(|reason| DrapeError::Placement {
            path: path.to_owned(),
            reason: Box::new(reason),
        })?
    } else {
        None
    };
    let place = match place {
        Some(place) => Some(place),
        None => world_file(path, height).map_err(|reason| DrapeError::Placement {
            path: path.to_owned(),
            reason: Box::new(reason),
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
fn tiff_place(file: std::fs::File, height: u32) -> Result<Option<OwnPlace>, PlacementError> {
    let mut decoder = tiff::decoder::Decoder::new(BufReader::new(file))?;
    match geotiff::georeferencing(&mut decoder, height) {
        Georeferencing::None => Ok(None),
        Georeferencing::Map(georef) => Ok(Some(OwnPlace::Map(georef))),
        Georeferencing::Ignored(reason) => Err(PlacementError::Unusable(reason)),
    }
}

/// The world file beside `path`, if there is one: `NAME.pgw` for `NAME.png` (the extension's
/// first and last letters and `w`), `NAME.pngw`, or `NAME.wld`.
fn world_file(path: &Path, height: u32) -> Result<Option<OwnPlace>, PlacementError> {
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
    let (file, len) = regular_file::open(&world).map_err(|error| match error {
        OpenError::NotAFile(what) => PlacementError::WorldNotAFile {
            world: world.clone(),
            what,
        },
        OpenError::Io(reason) => PlacementError::WorldOpen {
            world: world.clone(),
            reason,
        },
    })?;
    if len > MOST_WORLD_FILE_BYTES {
        return Err(PlacementError::WorldTooLarge { world, len });
    }
    let text = std::io::read_to_string(file).map_err(|reason| PlacementError::WorldNotText {
        world: world.clone(),
        reason,
    })?;
    let values: Vec<f64> = text
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| PlacementError::WorldNotNumbers(world.clone()))?;
    let [sx, rot_y, rot_x, sy, x, y] = values[..] else {
        return Err(PlacementError::WorldCount {
            world,
            count: values.len(),
        });
    };
    if rot_x != 0.0 || rot_y != 0.0 {
        return Err(PlacementError::WorldRotated(world));
    }
    // Checked for finite, positive spacing as any georeferencing is (units follow the map's).
    let spacing = [sx, -sy];
    let origin = [x, y + sy * f64::from(height - 1)];
    Georef::new(origin, spacing, MapUnits::Degrees)
        .map_err(|reason| PlacementError::WorldUnusable { world, reason })?;
    Ok(Some(OwnPlace::WorldFile { origin, spacing }))
}
