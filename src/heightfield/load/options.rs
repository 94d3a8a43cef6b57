//! How to read a height map: its z scale, how RGB becomes heights, which value means no data,
//! and the unit of its heights.

use crate::heightfield::HeightUnit;

/// How the three channels of an RGB image become heights.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ColourEncoding {
    /// Rec. 709 luminance `(2126 R + 7152 G + 722 B) / 10000`, rounded, as a grayscale sample.
    #[default]
    Luminance,
    /// Mapbox terrain-RGB: `-10000 + (R * 65536 + G * 256 + B) * 0.1` metres.
    Mapbox,
    /// Terrarium (Mapzen): `R * 256 + G + B / 256 - 32768` metres.
    Terrarium,
}

/// Which raster value means "no data" (NaN and infinities always do).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum NoDataValue {
    /// The file's own (a GeoTIFF's GDAL_NODATA tag), else SRTM's -32768 for signed and
    /// floating-point rasters; none for unsigned ones.
    #[default]
    Auto,
    /// No value means no data.
    Off,
    /// This raster value means no data.
    Value(f64),
}

/// A name that is not a colour encoding's, or a no-data value that is not one.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum OptionError {
    /// Not `luminance`, `mapbox` or `terrarium`.
    #[error("expected luminance, mapbox or terrarium, got '{0}'")]
    Encoding(String),
    /// Not `auto`, `none` or a number.
    #[error("expected auto, none or a number, got '{0}'")]
    NoData(String),
}

impl std::str::FromStr for ColourEncoding {
    type Err = OptionError;
    /// `luminance`, `mapbox` or `terrarium`.
    fn from_str(s: &str) -> Result<Self, OptionError> {
        match s {
            "luminance" => Ok(ColourEncoding::Luminance),
            "mapbox" => Ok(ColourEncoding::Mapbox),
            "terrarium" => Ok(ColourEncoding::Terrarium),
            _ => Err(OptionError::Encoding(s.to_owned())),
        }
    }
}

impl std::str::FromStr for NoDataValue {
    type Err = OptionError;
    /// `auto`, `none` or a number.
    fn from_str(s: &str) -> Result<Self, OptionError> {
        match s {
            "auto" => Ok(NoDataValue::Auto),
            "none" => Ok(NoDataValue::Off),
            _ => s
                .parse::<f64>()
                .map(NoDataValue::Value)
                .map_err(|_| OptionError::NoData(s.to_owned())),
        }
    }
}

/// The name [`ColourEncoding::from_str`](std::str::FromStr) reads.
impl std::fmt::Display for ColourEncoding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ColourEncoding::Luminance => "luminance",
            ColourEncoding::Mapbox => "mapbox",
            ColourEncoding::Terrarium => "terrarium",
        })
    }
}

/// What [`NoDataValue::from_str`](std::str::FromStr) reads.
impl std::fmt::Display for NoDataValue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NoDataValue::Auto => f.write_str("auto"),
            NoDataValue::Off => f.write_str("none"),
            NoDataValue::Value(v) => write!(f, "{v}"),
        }
    }
}

/// How to read a height map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadOptions {
    /// Height of the largest sample value (maxval); for float and signed rasters, the factor
    /// applied to their values.
    pub z_scale: f64,
    /// How RGB images become heights.
    pub colour: ColourEncoding,
    /// Which raster value means no data.
    pub nodata: NoDataValue,
    /// The unit of a georeferenced map's heights, instead of the one its file implies.
    pub height_unit: Option<HeightUnit>,
}

impl LoadOptions {
    /// The defaults with this z scale.
    pub fn new(z_scale: f64) -> Self {
        LoadOptions {
            z_scale,
            colour: ColourEncoding::default(),
            nodata: NoDataValue::default(),
            height_unit: None,
        }
    }
}
