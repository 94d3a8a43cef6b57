//! GeoTIFF's GeoKey ids and the values heightray reads and writes (GeoTIFF 1.1, OGC 19-008r4,
//! section 7), and the EPSG codes of the linear units it knows.

use super::georef::{METRES_PER_FOOT, METRES_PER_US_SURVEY_FOOT};

/// GTModelTypeGeoKey.
pub const MODEL_TYPE: u16 = 1024;
/// GTRasterTypeGeoKey.
pub const RASTER_TYPE: u16 = 1025;
/// GeodeticCRSGeoKey (GeographicTypeGeoKey).
pub const GEOGRAPHIC_TYPE: u16 = 2048;
/// GeogAngularUnitsGeoKey.
pub const ANGULAR_UNITS: u16 = 2054;
/// ProjectedCRSGeoKey (ProjectedCSTypeGeoKey).
pub const PROJECTED_TYPE: u16 = 3072;
/// ProjLinearUnitsGeoKey.
pub const LINEAR_UNITS: u16 = 3076;
/// VerticalUnitsGeoKey.
pub const VERTICAL_UNITS: u16 = 4099;
/// A projected model.
pub const MODEL_PROJECTED: u16 = 1;
/// A geographic model.
pub const MODEL_GEOGRAPHIC: u16 = 2;
/// Pixels are areas, the tiepoint a pixel's corner (the default).
pub const RASTER_PIXEL_IS_AREA: u16 = 1;
/// Pixels are points, the tiepoint a sample.
pub const RASTER_PIXEL_IS_POINT: u16 = 2;
/// The metre (EPSG 9001).
pub const UNIT_METRE: u16 = 9001;
/// The international foot (EPSG 9002).
pub const UNIT_FOOT: u16 = 9002;
/// The US survey foot (EPSG 9003).
pub const UNIT_US_SURVEY_FOOT: u16 = 9003;
/// The degree (EPSG 9102).
pub const UNIT_DEGREE: u16 = 9102;

/// Metres in a linear unit by its EPSG code (metre, foot, US survey foot).
pub fn unit_metres(code: u16) -> Option<f64> {
    match code {
        UNIT_METRE => Some(1.0),
        UNIT_FOOT => Some(METRES_PER_FOOT),
        UNIT_US_SURVEY_FOOT => Some(METRES_PER_US_SURVEY_FOOT),
        _ => None,
    }
}

/// The EPSG code of a unit of `metres` metres: a foot where it is one, else the metre.
pub fn unit_code(metres: f64) -> u16 {
    match super::georef::unit_symbol(metres) {
        "ft" => UNIT_FOOT,
        "US ft" => UNIT_US_SURVEY_FOOT,
        _ => UNIT_METRE,
    }
}
