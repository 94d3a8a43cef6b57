//! A decoded raster in image order, and how it becomes a height field: unsigned integer
//! samples as they are; other values (floats, signed integers, terrain-RGB) onto 16 bits over
//! their finite range; no-data values marked.

use super::{LoadOptions, NoDataValue};
use crate::heightfield::georef::Georeferencing;
use crate::heightfield::{Heightfield, HeightfieldError, NoDataMask, Quantisation};

/// SRTM's no-data value, the default for signed and floating-point rasters.
const SRTM_NODATA: f64 = -32768.0;

/// Pixels in image order (row 0 is the northern edge).
pub struct Raster {
    pub width: usize,
    pub height: usize,
    pub values: Values,
    /// The no-data value the file itself declares.
    pub file_nodata: Option<f64>,
    /// Where the file says its samples lie.
    pub georef: Georeferencing,
}

/// The values of a raster, as decoded.
pub enum Values {
    /// Unsigned integers up to `maxval`: heights are `sample / maxval * z_scale`.
    Unsigned {
        samples: Vec<u16>,
        maxval: u16,
    },
    I8(Vec<i8>),
    I16(Vec<i16>),
    I32(Vec<i32>),
    U32(Vec<u32>),
    F32(Vec<f32>),
    F64(Vec<f64>),
    /// 8-bit RGB or RGBA pixels in a terrain-RGB encoding.
    TerrainRgb {
        bytes: Vec<u8>,
        channels: usize,
        encoding: TerrainRgb,
    },
}

/// The terrain-RGB encodings of heights in 8-bit RGB pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TerrainRgb {
    /// Mapbox: `-10000 + (R * 65536 + G * 256 + B) * 0.1` metres.
    Mapbox,
    /// Terrarium (Mapzen): `R * 256 + G + B / 256 - 32768` metres.
    Terrarium,
}

impl Values {
    fn len(&self) -> usize {
        match self {
            Values::Unsigned { samples, .. } => samples.len(),
            Values::I8(v) => v.len(),
            Values::I16(v) => v.len(),
            Values::I32(v) => v.len(),
            Values::U32(v) => v.len(),
            Values::F32(v) => v.len(),
            Values::F64(v) => v.len(),
            Values::TerrainRgb {
                bytes, channels, ..
            } => bytes.len() / channels,
        }
    }
}

impl Raster {
    /// The height field, with the options' z scale, no-data value and height unit.
    pub fn into_field(self, options: &LoadOptions) -> Result<Heightfield, HeightfieldError> {
        let georef = placed(&self.georef, options, self.width, self.height);
        Ok(self.into_samples(options)?.with_georeferencing(georef))
    }

    /// The height field's samples and holes.
    fn into_samples(self, options: &LoadOptions) -> Result<Heightfield, HeightfieldError> {
        let (width, height) = (self.width, self.height);
        // Decoders promise one value per pixel; a short buffer must not index out of bounds.
        if self.values.len() != width * height {
            return Err(HeightfieldError::SampleCount {
                expected: width * height,
                got: self.values.len(),
            });
        }
        let unsigned = matches!(
            self.values,
            Values::Unsigned { .. } | Values::TerrainRgb { .. }
        );
        let nodata = nodata_value(options, unsigned, self.file_nodata);
        let quantise =
            |value: &dyn Fn(usize) -> f64| quantise(width, height, value, nodata, options.z_scale);
        match self.values {
            Values::Unsigned {
                mut samples,
                maxval,
            } => {
                flip_rows(&mut samples, width);
                let mask = nodata.map(|v| mask_where(&samples, |s| f64::from(s) == v));
                let q = Quantisation::Maxval(maxval);
                Heightfield::new(width, height, samples, q, options.z_scale, mask)
            }
            Values::I8(v) => quantise(&|k| f64::from(v[k])),
            Values::I16(v) => quantise(&|k| f64::from(v[k])),
            Values::I32(v) => quantise(&|k| f64::from(v[k])),
            Values::U32(v) => quantise(&|k| f64::from(v[k])),
            Values::F32(v) => quantise(&|k| f64::from(v[k])),
            Values::F64(v) => quantise(&|k| v[k]),
            Values::TerrainRgb {
                bytes,
                channels,
                encoding,
            } => quantise(&|k| {
                let p = &bytes[k * channels..];
                terrain_rgb(encoding, p[0], p[1], p[2])
            }),
        }
    }
}

/// Where a raster of `width` x `height` samples that `georef` places lies, with the options'
/// height unit; ignored where its cells are of no size a map has.
pub(super) fn placed(
    georef: &Georeferencing,
    options: &LoadOptions,
    width: usize,
    height: usize,
) -> Georeferencing {
    let georef = match (georef, options.height_unit) {
        (Georeferencing::Map(g), Some(unit)) => Georeferencing::Map(g.with_height_unit(unit)),
        (georef, _) => georef.clone(),
    };
    georef.with_cells_checked(width, height)
}

/// The raster value that means no data, as `options` say, for a raster of `unsigned` samples
/// (or terrain-RGB pixels) or not, whose file declares `file_nodata`.
pub(super) fn nodata_value(
    options: &LoadOptions,
    unsigned: bool,
    file_nodata: Option<f64>,
) -> Option<f64> {
    match options.nodata {
        NoDataValue::Off => None,
        NoDataValue::Value(v) => Some(v),
        NoDataValue::Auto if unsigned => file_nodata,
        NoDataValue::Auto => file_nodata.or(Some(SRTM_NODATA)),
    }
}

/// Whether the value `v` of a raster whose no-data value is `nodata` has data.
pub(super) fn has_data(v: f64, nodata: Option<f64>) -> bool {
    v.is_finite() && Some(v) != nodata
}

/// The height in metres a terrain-RGB pixel encodes.
fn terrain_rgb(encoding: TerrainRgb, r: u8, g: u8, b: u8) -> f64 {
    let (r, g, b) = (f64::from(r), f64::from(g), f64::from(b));
    match encoding {
        TerrainRgb::Mapbox => -10000.0 + (r * 65536.0 + g * 256.0 + b) * 0.1,
        TerrainRgb::Terrarium => r * 256.0 + g + b / 256.0 - 32768.0,
    }
}

/// Values onto 16-bit samples over their finite range `[lo, hi]`: exactly (step 1) when they
/// are whole numbers spanning at most 65535, else in 65536 levels. Values that are not
/// finite or equal `nodata` become holes.
fn quantise(
    width: usize,
    height: usize,
    value: &dyn Fn(usize) -> f64,
    nodata: Option<f64>,
    z_scale: f64,
) -> Result<Heightfield, HeightfieldError> {
    let valid = |v: f64| has_data(v, nodata);
    let mut range = ValueRange::EMPTY;
    for v in (0..width * height).map(value).filter(|&v| valid(v)) {
        range.include(v);
    }
    if range.is_empty() {
        return Err(HeightfieldError::AllNoData);
    }
    let (lo, step) = (range.lo, range.step());
    // Samples in field order (y up): image row `height - 1 - j` is field row `j`.
    let mut samples = Vec::with_capacity(width * height);
    let mut mask = NoDataMask::new(0);
    for j in 0..height {
        let row = (height - 1 - j) * width;
        for i in 0..width {
            let v = value(row + i);
            if valid(v) {
                samples.push(ValueRange::sample(v, lo, step));
            } else {
                if mask.count() == 0 {
                    mask = NoDataMask::new(width * height);
                }
                mask.insert(j * width + i);
                samples.push(0);
            }
        }
    }
    let q = Quantisation::Offset { lowest: lo, step };
    Heightfield::new(width, height, samples, q, z_scale, Some(mask))
}

/// The range of a raster's valid values, and whether they are all whole numbers: what their
/// 16-bit samples are quantised over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(in crate::heightfield) struct ValueRange {
    /// The lowest value.
    pub lo: f64,
    /// The highest value.
    pub hi: f64,
    /// Whether every value is a whole number.
    pub whole: bool,
}

impl ValueRange {
    /// The range of no values.
    pub const EMPTY: ValueRange = ValueRange {
        lo: f64::INFINITY,
        hi: f64::NEG_INFINITY,
        whole: true,
    };

    /// Takes in the valid value `v`.
    pub fn include(&mut self, v: f64) {
        self.lo = self.lo.min(v);
        self.hi = self.hi.max(v);
        self.whole &= v.fract() == 0.0;
    }

    /// The range of both ranges' values.
    pub fn join(self, other: ValueRange) -> ValueRange {
        ValueRange {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
            whole: self.whole && other.whole,
        }
    }

    /// Whether no value was taken in.
    pub fn is_empty(&self) -> bool {
        self.lo > self.hi
    }

    /// The value of one sample step: exactly 1 when the values are whole numbers spanning at
    /// most 65535, else the range in 65536 levels.
    pub fn step(&self) -> f64 {
        if self.whole && self.hi - self.lo <= 65535.0 {
            1.0
        } else {
            (self.hi - self.lo) / 65535.0
        }
    }

    /// The sample of the valid value `v` over a range from `lo` in steps of `step`.
    pub fn sample(v: f64, lo: f64, step: f64) -> u16 {
        let level = if step > 0.0 { (v - lo) / step } else { 0.0 };
        level.round().min(65535.0) as u16
    }
}

/// The samples for which `is_nodata` holds.
fn mask_where(samples: &[u16], is_nodata: impl Fn(u16) -> bool) -> NoDataMask {
    let mut mask = NoDataMask::new(samples.len());
    for (k, _) in samples.iter().enumerate().filter(|(_, &s)| is_nodata(s)) {
        mask.insert(k);
    }
    mask
}

/// Reverses the order of rows in place (image order to y up), without a second buffer.
fn flip_rows(samples: &mut [u16], width: usize) {
    let height = samples.len() / width;
    for r in 0..height / 2 {
        let (top, bottom) = samples.split_at_mut((height - 1 - r) * width);
        top[r * width..(r + 1) * width].swap_with_slice(&mut bottom[..width]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flipping_rows_reverses_them() {
        let mut samples: Vec<u16> = (0..15).collect();
        flip_rows(&mut samples, 5);
        assert_eq!(samples, [10, 11, 12, 13, 14, 5, 6, 7, 8, 9, 0, 1, 2, 3, 4]);
    }

    #[test]
    fn terrain_rgb_encodings_decode_known_pixels() {
        // Mapbox: 0 m is code 100000 = (1, 134, 160).
        assert!((terrain_rgb(TerrainRgb::Mapbox, 1, 134, 160)).abs() < 1e-9);
        // Terrarium: 0 m is (128, 0, 0); 1.5 m is (128, 1, 128).
        assert_eq!(terrain_rgb(TerrainRgb::Terrarium, 128, 0, 0), 0.0);
        assert_eq!(terrain_rgb(TerrainRgb::Terrarium, 128, 1, 128), 1.5);
    }
}
