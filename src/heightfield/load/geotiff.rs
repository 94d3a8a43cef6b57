//! A GeoTIFF's georeferencing, read through the `tiff` crate's tag API: ModelPixelScale with
//! ModelTiepoint, or ModelTransformation, and the GeoKeyDirectory's model type, raster type
//! and units, and the CRS's EPSG code (GeoTIFF 1.1, OGC 19-008r4).
//!
//! Only north-up grids are used; a rotated or sheared transform, a geocentric model or a unit
//! that is not a metre, a foot or a degree leaves the field a plain image, with the reason.

use crate::heightfield::crs::Crs;
use crate::heightfield::geokeys::{
    unit_metres, ANGULAR_UNITS, GEOGRAPHIC_TYPE, LINEAR_UNITS, MODEL_GEOGRAPHIC, MODEL_PROJECTED,
    MODEL_TYPE, PROJECTED_TYPE, RASTER_PIXEL_IS_POINT, RASTER_TYPE, UNIT_DEGREE, VERTICAL_UNITS,
};
use crate::heightfield::georef::{
    Georef, GeorefError, Georeferencing, HeightUnit, HeightUnitSource, MapUnits,
};
use std::io::{Read, Seek};
use thiserror::Error;
use tiff::decoder::Decoder;
use tiff::tags::Tag;

/// Why a GeoTIFF's tags place no north-up grid.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum GeoTiffError {
    /// A transformation matrix of the wrong length.
    #[error("its ModelTransformation has {0} values, not 16")]
    TransformLength(usize),
    /// A transformation that is not north up.
    #[error("its ModelTransformation is rotated or sheared")]
    Rotated,
    /// A scale without a tiepoint, or a tiepoint without a scale.
    #[error("it has ModelPixelScale or ModelTiepoint without the other")]
    Unpaired,
    /// A scale or tiepoint with too few values.
    #[error("its ModelPixelScale or ModelTiepoint is too short")]
    TooShort,
    /// More than one tiepoint.
    #[error("it has several tiepoints (a warped grid)")]
    Tiepoints,
    /// An angular unit other than the degree.
    #[error("its angular unit (EPSG {0}) is not degrees")]
    AngularUnit(u16),
    /// A linear unit not known.
    #[error("its linear unit (EPSG {0}) is unknown")]
    LinearUnit(u16),
    /// A model type neither projected nor geographic.
    #[error("its model type {0} is neither projected nor geographic")]
    ModelType(u16),
    /// No model type key.
    #[error("it has no GeoKeyDirectory saying the CRS's units")]
    NoKeys,
    /// Degrees beyond the poles.
    #[error(
        "it is in degrees, but its samples span latitudes {} to {}, outside -90..90",
        latitude(*.bottom),
        latitude(*.top)
    )]
    Latitudes {
        /// The southern samples' latitude.
        bottom: f64,
        /// The northern samples'.
        top: f64,
    },
    /// The corner and scale make no georeferencing.
    #[error(transparent)]
    Georef(#[from] GeorefError),
}

/// The georeferencing of the current image of `decoder`, `height` rows high.
pub fn georeferencing<R: Read + Seek>(decoder: &mut Decoder<R>, height: u32) -> Georeferencing {
    let mut doubles = |tag| {
        decoder
            .find_tag(tag)
            .ok()
            .flatten()
            .and_then(|v| v.into_f64_vec().ok())
    };
    let scale = doubles(Tag::ModelPixelScaleTag);
    let tiepoint = doubles(Tag::ModelTiepointTag);
    let transformation = doubles(Tag::ModelTransformationTag);
    let keys = decoder
        .find_tag(Tag::GeoKeyDirectoryTag)
        .ok()
        .flatten()
        .and_then(|v| v.into_u16_vec().ok());
    if scale.is_none() && tiepoint.is_none() && transformation.is_none() {
        return Georeferencing::None;
    }
    let keys = GeoKeys(keys.unwrap_or_default());
    Georeferencing::from_result(
        corner_transform(scale, tiepoint, transformation)
            .and_then(|corner| georef(&corner, &keys, height)),
    )
}

/// The affine map from raster space (column, row; corners of pixel `(0, 0)` at `(0, 0)`) to
/// the model: `X = x0 + column * sx`, `Y = y0 - row * sy`, north up.
struct Corner {
    x0: f64,
    y0: f64,
    sx: f64,
    sy: f64,
}

/// The north-up affine map the tags describe, or why there is none.
fn corner_transform(
    scale: Option<Vec<f64>>,
    tiepoint: Option<Vec<f64>>,
    transformation: Option<Vec<f64>>,
) -> Result<Corner, GeoTiffError> {
    if let Some(m) = transformation {
        let [a, b, _, d, e, f, _, h, ..] = m[..] else {
            return Err(GeoTiffError::TransformLength(m.len()));
        };
        if b != 0.0 || e != 0.0 {
            return Err(GeoTiffError::Rotated);
        }
        return Ok(Corner {
            x0: d,
            y0: h,
            sx: a,
            sy: -f,
        });
    }
    let (Some(scale), Some(tie)) = (scale, tiepoint) else {
        return Err(GeoTiffError::Unpaired);
    };
    let [sx, sy, ..] = scale[..] else {
        return Err(GeoTiffError::TooShort);
    };
    let [i, j, _, x, y, ..] = tie[..] else {
        return Err(GeoTiffError::TooShort);
    };
    if tie.len() > 6 {
        return Err(GeoTiffError::Tiepoints);
    }
    Ok(Corner {
        x0: x - i * sx,
        y0: y + j * sy,
        sx,
        sy,
    })
}

/// The sample positions of an image `height` rows high under `corner`, in the keys' units.
fn georef(corner: &Corner, keys: &GeoKeys, height: u32) -> Result<Georef, GeoTiffError> {
    let crs = match keys.get(MODEL_TYPE) {
        Some(MODEL_GEOGRAPHIC) => keys.get(GEOGRAPHIC_TYPE).and_then(Crs::from_epsg),
        Some(MODEL_PROJECTED) => keys.get(PROJECTED_TYPE).and_then(Crs::from_epsg),
        _ => None,
    };
    let units = match keys.get(MODEL_TYPE) {
        Some(MODEL_GEOGRAPHIC) => match keys.get(ANGULAR_UNITS) {
            None | Some(UNIT_DEGREE) => MapUnits::Degrees,
            Some(unit) => return Err(GeoTiffError::AngularUnit(unit)),
        },
        Some(MODEL_PROJECTED) => {
            // GDAL writes the unit key only where the CRS is not an EPSG code; an EPSG
            // code's definition says its unit.
            let metres = match keys.get(LINEAR_UNITS) {
                Some(unit) => unit_metres(unit).ok_or(GeoTiffError::LinearUnit(unit))?,
                None => crs.and_then(|c| c.metres_per_unit()).unwrap_or(1.0),
            };
            MapUnits::Linear { metres }
        }
        Some(other) => return Err(GeoTiffError::ModelType(other)),
        None => return Err(GeoTiffError::NoKeys),
    };
    // PixelIsArea (the default): the tiepoint is a pixel's corner, samples sit at centres.
    let half = if keys.get(RASTER_TYPE) == Some(RASTER_PIXEL_IS_POINT) {
        0.0
    } else {
        0.5
    };
    // Sample (0, 0) of the field is the image's bottom-left pixel, row height - 1.
    let bottom = f64::from(height) - 1.0 + half;
    let origin = [corner.x0 + half * corner.sx, corner.y0 - bottom * corner.sy];
    if units == MapUnits::Degrees {
        let top = origin[1] + (f64::from(height) - 1.0) * corner.sy;
        if !(origin[1] >= -90.0 && top <= 90.0) {
            return Err(GeoTiffError::Latitudes {
                bottom: origin[1],
                top,
            });
        }
    }
    let georef = Georef::new(origin, [corner.sx, corner.sy], units)?.with_crs(crs);
    Ok(match keys.get(VERTICAL_UNITS).and_then(unit_metres) {
        Some(metres) => georef.with_height_unit(HeightUnit {
            metres,
            source: HeightUnitSource::VerticalKey,
        }),
        None => georef,
    })
}

/// A latitude for a message: in degrees to six places, or in scientific notation when it is
/// far beyond any (a forged or broken file's).
fn latitude(degrees: f64) -> String {
    if degrees.abs() < 1e6 {
        format!("{degrees:.6}")
    } else {
        format!("{degrees:.3e}")
    }
}

/// A GeoKeyDirectory: a header of four shorts, then (id, location, count, value) per key.
struct GeoKeys(Vec<u16>);

impl GeoKeys {
    /// A key's short value stored in the directory itself (location 0).
    fn get(&self, id: u16) -> Option<u16> {
        self.0
            .get(4..)?
            .chunks_exact(4)
            .find(|key| key[0] == id && key[1] == 0)
            .map(|key| key[3])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keys(pairs: &[(u16, u16)]) -> GeoKeys {
        let mut v = vec![1, 1, 0, pairs.len() as u16];
        for &(id, value) in pairs {
            v.extend([id, 0, 1, value]);
        }
        GeoKeys(v)
    }

    #[test]
    fn geo_keys_are_found_by_id() {
        let k = keys(&[(MODEL_TYPE, 1), (LINEAR_UNITS, 9002)]);
        assert_eq!(k.get(MODEL_TYPE), Some(1));
        assert_eq!(k.get(LINEAR_UNITS), Some(9002));
        assert_eq!(k.get(RASTER_TYPE), None);
        assert_eq!(GeoKeys(vec![1, 1]).get(MODEL_TYPE), None);
    }

    #[test]
    fn a_rotated_transformation_is_refused() {
        let mut m = vec![0.0; 16];
        m[0] = 1.0;
        m[1] = 0.5;
        m[5] = -1.0;
        let error = corner_transform(None, None, Some(m)).err();
        assert_eq!(error, Some(GeoTiffError::Rotated));
    }
}
