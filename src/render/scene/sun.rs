//! `[sun]`: a direction; or a compass bearing and an elevation; or where the sun stands at a
//! time over a place, the place the map's centre (a map in longitude and latitude, or in a
//! CRS known by its EPSG code) or the `lat` and `lon` keys, a local time read on the clocks of
//! `zone` or of the place's own time zone. (A sun below the horizon lights nothing:
//! [`Lighting::after_dark`].)

use super::{Lighting, SunSection};
use crate::compact::Compact;
use crate::heightfield::{place, Heightfield};
use crate::render::local_time::{self, TimeError};
use crate::render::sun_position::{SunError, SunPosition};
use thiserror::Error;

/// Which `[sun]` keys place no sun.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum PlaceSunError {
    /// A bearing and a time.
    #[error("[sun] gives both azimuth_deg and time: give one")]
    BearingAndTime,
    /// A bearing out of range.
    #[error(
        "[sun] azimuth_deg must be finite and elevation_deg from -90 to 90, got {} and {}",
        Compact(*azimuth_deg),
        Compact(*elevation_deg)
    )]
    Bearing {
        /// Degrees clockwise from north.
        azimuth_deg: f64,
        /// Degrees above the horizon.
        elevation_deg: f64,
    },
    /// Only one of azimuth and elevation.
    #[error("[sun] azimuth_deg and elevation_deg go together: give both")]
    HalfBearing,
    /// A time on a map whose place is unknown.
    #[error(
        "[sun] time needs lat and lon keys: the map's place is not known (it is not \
         georeferenced by longitude and latitude or an EPSG code)"
    )]
    NoPlace,
    /// Only one of latitude and longitude.
    #[error("[sun] lat and lon go together: give both or neither")]
    HalfPlace,
    /// A zone name not known.
    #[error("[sun] zone: {0}")]
    Zone(TimeError),
    /// A time that cannot be read.
    #[error("[sun] time: {0}")]
    Time(#[from] TimeError),
    /// A time or place the sun's position cannot be found for.
    #[error("[sun] time: {0}")]
    Sun(#[from] SunError),
}

/// `lighting` with its sun placed by the section's bearing or time, if it gives either.
pub fn place_sun(
    section: &SunSection,
    field: &Heightfield,
    lighting: Lighting,
) -> Result<Lighting, PlaceSunError> {
    let sun = match (section.azimuth_deg, section.elevation_deg, &section.time) {
        (None, None, None) => return Ok(lighting),
        (Some(_), Some(_), Some(_)) => return Err(PlaceSunError::BearingAndTime),
        (Some(azimuth_deg), Some(elevation_deg), None) => {
            if !(azimuth_deg.is_finite() && (-90.0..=90.0).contains(&elevation_deg)) {
                return Err(PlaceSunError::Bearing {
                    azimuth_deg,
                    elevation_deg,
                });
            }
            SunPosition {
                azimuth_deg,
                elevation_deg,
            }
        }
        (Some(_), None, _) | (None, Some(_), _) => return Err(PlaceSunError::HalfBearing),
        (None, None, Some(time)) => {
            let (latitude, longitude) = match (section.lat, section.lon) {
                (Some(lat), Some(lon)) => (lat, lon),
                (None, None) => place::centre_degrees(field).ok_or(PlaceSunError::NoPlace)?,
                _ => return Err(PlaceSunError::HalfPlace),
            };
            let zone = match &section.zone {
                Some(name) => Some(local_time::zone_named(name).map_err(PlaceSunError::Zone)?),
                None => local_time::zone_at(latitude, longitude),
            };
            let instant = local_time::parse_time(time, zone)?;
            SunPosition::at_utc(instant, latitude, longitude)?
        }
    };
    Ok(Lighting {
        sun: Lighting::unit(sun.direction()),
        ..lighting
    })
}
