//! TIFFs as print and GIS workflows take them: 8- or 16-bit RGB (with an alpha band where the
//! picture has transparent parts), 16-bit heights or 32-bit float values; a GeoTIFF's georeferencing
//! (ModelPixelScale, ModelTiepoint and GeoKeyDirectory, GeoTIFF 1.1) where the map has it, and
//! the resolution in dots per inch where asked. Deflate-compressed.

use super::grid::GeoTransform;
use crate::heightfield::geokeys::{
    unit_code, ANGULAR_UNITS, GEOGRAPHIC_TYPE, LINEAR_UNITS, MODEL_GEOGRAPHIC, MODEL_PROJECTED,
    MODEL_TYPE, PROJECTED_TYPE, RASTER_PIXEL_IS_AREA, RASTER_TYPE, UNIT_DEGREE,
};
use crate::heightfield::{Georef, MapUnits};
use std::io::{Seek, Write};
use thiserror::Error;
use tiff::encoder::colortype::{ColorType, Gray16, Gray32Float, RGB16, RGB8, RGBA16, RGBA8};
use tiff::encoder::compression::DeflateLevel;
use tiff::encoder::{Compression, Predictor, Rational, TiffEncoder, TiffValue};
use tiff::tags::{ResolutionUnit, Tag};

/// Where a raster lies on the map, as GeoTIFF tags.
#[derive(Clone, Debug, PartialEq)]
pub struct GeoTags {
    /// ModelPixelScale: pixel width and height in map units.
    pub pixel_scale: [f64; 3],
    /// ModelTiepoint: the top-left corner of pixel (0, 0) and its map coordinates.
    pub tiepoint: [f64; 6],
    /// GeoKeyDirectory: the model type, PixelIsArea, the CRS's EPSG code or its units.
    pub keys: Vec<u16>,
}

impl GeoTags {
    /// The tags of a north-up raster at `transform` on the map of `georef`.
    pub fn new(transform: &GeoTransform, georef: &Georef) -> GeoTags {
        let mut keys = vec![(RASTER_TYPE, RASTER_PIXEL_IS_AREA)];
        match georef.units {
            MapUnits::Degrees => {
                keys.push((MODEL_TYPE, MODEL_GEOGRAPHIC));
                match georef.crs {
                    Some(crs) => keys.push((GEOGRAPHIC_TYPE, crs.epsg)),
                    None => keys.push((ANGULAR_UNITS, UNIT_DEGREE)),
                }
            }
            MapUnits::Linear { metres } => {
                keys.push((MODEL_TYPE, MODEL_PROJECTED));
                match georef.crs {
                    Some(crs) => keys.push((PROJECTED_TYPE, crs.epsg)),
                    None => keys.push((LINEAR_UNITS, unit_code(metres))),
                }
            }
        }
        keys.sort_unstable();
        let mut directory = vec![1, 1, 0, keys.len() as u16];
        for (id, value) in keys {
            directory.extend([id, 0, 1, value]);
        }
        GeoTags {
            pixel_scale: [transform[1], -transform[5], 0.0],
            tiepoint: [0.0, 0.0, 0.0, transform[0], transform[3], 0.0],
            keys: directory,
        }
    }
}

/// The TIFF encoder's error.
#[derive(Debug, Error)]
#[error("the TIFF encoder failed: {0}")]
pub struct EncodeError(#[from] tiff::TiffError);

/// Bits per channel of a colour TIFF.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Depth {
    /// 8 bits.
    Eight,
    /// 16 bits.
    Sixteen,
}

/// What a TIFF says besides its pixels.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TiffTags {
    /// Georeferencing, if any.
    pub geo: Option<GeoTags>,
    /// Dots per inch, if given.
    pub dpi: Option<f64>,
}

/// Writes colour pixels, `[r, g, b, coverage]` from 0 to 65535 row by row from the top, at
/// `depth`, with an alpha band where some pixel is not wholly covered.
pub fn write_colour<W: Write + Seek>(
    out: W,
    (width, height): (u32, u32),
    pixels: &[[u16; 4]],
    depth: Depth,
    tags: &TiffTags,
) -> Result<(), EncodeError> {
    let alpha = pixels.iter().any(|p| p[3] != u16::MAX);
    let bands = if alpha { 4 } else { 3 };
    let channels = pixels.iter().flat_map(|p| p[..bands].iter().copied());
    match (depth, alpha) {
        (Depth::Sixteen, false) => encode::<RGB16, _>(
            out,
            (width, height),
            &channels.collect::<Vec<_>>(),
            tags,
            None,
        ),
        (Depth::Sixteen, true) => encode::<RGBA16, _>(
            out,
            (width, height),
            &channels.collect::<Vec<_>>(),
            tags,
            None,
        ),
        (Depth::Eight, alpha) => {
            let bytes: Vec<u8> = channels
                .map(|c| ((u32::from(c) + 128) / 257) as u8)
                .collect();
            if alpha {
                encode::<RGBA8, _>(out, (width, height), &bytes, tags, None)
            } else {
                encode::<RGB8, _>(out, (width, height), &bytes, tags, None)
            }
        }
    }
}

/// Writes one band of 32-bit float values row by row from the top, NaN marked as no data.
pub fn write_values<W: Write + Seek>(
    out: W,
    (width, height): (u32, u32),
    values: &[f32],
    tags: &TiffTags,
) -> Result<(), EncodeError> {
    encode::<Gray32Float, _>(out, (width, height), values, tags, Some("nan"))
}

/// Writes one band of 16-bit samples row by row from the top (heights in whole map units).
pub fn write_gray16<W: Write + Seek>(
    out: W,
    (width, height): (u32, u32),
    samples: &[u16],
    tags: &TiffTags,
) -> Result<(), EncodeError> {
    encode::<Gray16, _>(out, (width, height), samples, tags, None)
}

/// Writes an image of colour type `C` with the tags, compressed.
fn encode<C: ColorType, W: Write + Seek>(
    out: W,
    (width, height): (u32, u32),
    data: &[C::Inner],
    tags: &TiffTags,
    nodata: Option<&str>,
) -> Result<(), EncodeError>
where
    [C::Inner]: TiffValue,
{
    let floats = C::SAMPLE_FORMAT[0] == tiff::tags::SampleFormat::IEEEFP;
    let predictor = if floats {
        Predictor::None
    } else {
        Predictor::Horizontal
    };
    let mut encoder = TiffEncoder::new(out)?
        .with_compression(Compression::Deflate(DeflateLevel::Balanced))
        .with_predictor(predictor);
    let mut image = encoder.new_image::<C>(width, height)?;
    if C::BITS_PER_SAMPLE.len() == 4 {
        // Unassociated alpha: GDAL and QGIS read the fourth band as the mask.
        image.encoder().write_tag(Tag::ExtraSamples, 2u16)?;
    }
    if let Some(dpi) = tags.dpi {
        // Whole resolutions as n/1, others to a hundredth of a dot.
        let value = if dpi.fract() == 0.0 {
            Rational {
                n: dpi as u32,
                d: 1,
            }
        } else {
            Rational {
                n: (dpi * 100.0).round() as u32,
                d: 100,
            }
        };
        image.resolution(ResolutionUnit::Inch, value);
    }
    if let Some(geo) = &tags.geo {
        let directory = image.encoder();
        directory
            .write_tag(Tag::ModelPixelScaleTag, &geo.pixel_scale[..])
            .and_then(|()| directory.write_tag(Tag::ModelTiepointTag, &geo.tiepoint[..]))
            .and_then(|()| directory.write_tag(Tag::GeoKeyDirectoryTag, &geo.keys[..]))?;
    }
    if let Some(text) = nodata {
        image.encoder().write_tag(Tag::GdalNodata, text)?;
    }
    image.write_data(data).map_err(EncodeError)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::geokeys::{unit_metres, UNIT_FOOT};
    use crate::heightfield::{load_bytes, Georeferencing, Heightfield};
    use crate::products::OrthoGrid;
    use std::io::Cursor;

    #[test]
    fn tags_read_back_as_the_maps_georeferencing_in_each_unit() {
        let foot = unit_metres(UNIT_FOOT).unwrap();
        let cases = [
            (
                [500_000.5, 4_200_000.25],
                [2.0, 3.0],
                MapUnits::Linear { metres: 1.0 },
            ),
            (
                [1_000.0, 2_000.0],
                [5.0, 5.0],
                MapUnits::Linear { metres: foot },
            ),
            ([7.25, 46.5], [0.001, 0.002], MapUnits::Degrees),
        ];
        for (origin, spacing, units) in cases {
            let georef = Georef::new(origin, spacing, units).unwrap();
            let field = Heightfield::from_fn(4, 3, 1, 1.0, |_, _| 0)
                .unwrap()
                .with_georeferencing(Georeferencing::Map(georef));
            let grid = OrthoGrid::over(&field, None).unwrap();
            let tags = TiffTags {
                geo: Some(GeoTags::new(&grid.geotransform().unwrap(), &georef)),
                dpi: None,
            };
            let mut bytes = Cursor::new(Vec::new());
            write_values(&mut bytes, (4, 3), &[1.0; 12], &tags).unwrap();
            let back = load_bytes(bytes.get_ref(), 1.0, "product.tif").unwrap();
            let read = back.georef().expect("georeferenced");
            assert_eq!((read.units, read.spacing), (units, spacing));
            for (got, want) in read.origin.iter().zip(origin) {
                assert!((got - want).abs() <= 1e-9 * want.abs(), "{read:?}");
            }
        }
    }
}
