//! The sun at a place and time: its direction from the Solar Position Algorithm of Reda and
//! Andreas (NREL, 2004) through the `solar-positioning` crate, with Delta T estimated (Espenak
//! and Meeus) and refraction for a standard atmosphere, seen from sea level.

use crate::compact::Compact;
use chrono::{DateTime, Utc};
use solar_positioning::{delta_t, Location, RefractionCorrection, SolarPositions};
use thiserror::Error;

/// Why the sun's position cannot be found.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum SunError {
    /// Not an RFC 3339 time.
    #[error("'{time}' is not a time such as 2026-12-21T08:00:00Z ({reason})")]
    Time {
        /// The text given.
        time: String,
        /// What the parser said.
        reason: String,
    },
    /// A latitude or longitude out of range.
    #[error(
        "latitude must be from -90 to 90 and longitude from -180 to 180 degrees, got {} and {}",
        Compact(*latitude),
        Compact(*longitude)
    )]
    Place {
        /// Degrees north.
        latitude: f64,
        /// Degrees east.
        longitude: f64,
    },
    /// The solar position crate refused the instant.
    #[error("{0}")]
    Solar(String),
}

/// Where the sun stands in the sky.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunPosition {
    /// Compass bearing: degrees clockwise from north, 0 to 360.
    pub azimuth_deg: f64,
    /// Degrees above the horizon (negative below it), refraction included.
    pub elevation_deg: f64,
}

impl SunPosition {
    /// The sun at `time` (RFC 3339, e.g. `2026-12-21T08:00:00Z`) seen from `latitude` and
    /// `longitude` in degrees, or why it cannot be found.
    pub fn at(time: &str, latitude: f64, longitude: f64) -> Result<SunPosition, SunError> {
        let time: DateTime<Utc> = time
            .parse()
            .map_err(|e: chrono::ParseError| SunError::Time {
                time: time.to_owned(),
                reason: e.to_string(),
            })?;
        SunPosition::at_utc(time, latitude, longitude)
    }

    /// The sun at instant `time` seen from `latitude` and `longitude` in degrees.
    pub fn at_utc(
        time: DateTime<Utc>,
        latitude: f64,
        longitude: f64,
    ) -> Result<SunPosition, SunError> {
        // Checked here, not by the solar position crate, whose message writes every digit.
        if !((-90.0..=90.0).contains(&latitude) && (-180.0..=180.0).contains(&longitude)) {
            return Err(SunError::Place {
                latitude,
                longitude,
            });
        }
        let solar = |e: solar_positioning::Error| SunError::Solar(e.to_string());
        let delta_t = delta_t::estimate_from_date_like(&time).map_err(solar)?;
        let location = Location {
            latitude,
            longitude,
        };
        let position = SolarPositions::new()
            .at(
                &time,
                location,
                0.0,
                delta_t,
                Some(RefractionCorrection::standard()),
            )
            .map_err(solar)?;
        Ok(SunPosition {
            azimuth_deg: position.azimuth(),
            elevation_deg: position.elevation_angle(),
        })
    }

    /// The sun in the direction `towards_sun` (x east, y north, z up; any length but 0).
    pub fn from_direction([x, y, z]: [f64; 3]) -> SunPosition {
        SunPosition {
            azimuth_deg: x.atan2(y).to_degrees().rem_euclid(360.0),
            elevation_deg: z.atan2(x.hypot(y)).to_degrees(),
        }
    }

    /// Whether the sun is above the horizon.
    pub fn is_up(&self) -> bool {
        self.elevation_deg > 0.0
    }

    /// The unit vector towards the sun with x east, y north and z up (a map's axes).
    pub fn direction(&self) -> [f64; 3] {
        let (azimuth, elevation) = (
            self.azimuth_deg.to_radians(),
            self.elevation_deg.to_radians(),
        );
        [
            azimuth.sin() * elevation.cos(),
            azimuth.cos() * elevation.cos(),
            elevation.sin(),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spa_papers_example_is_matched_to_a_hundredth_of_a_degree() {
        // Reda & Andreas (2004), Table A5.1: 17 October 2003, 12:30:30 at UTC-7, Golden,
        // Colorado (39.742476 N, 105.1786 W, 1830 m, 820 mbar, 11 C, Delta T 67 s):
        // topocentric zenith angle 50.11162 degrees, azimuth 194.34024 degrees. Sea level, a
        // standard atmosphere and an estimated Delta T move the zenith by under 0.01 degree.
        let sun = SunPosition::at("2003-10-17T19:30:30Z", 39.742476, -105.1786).unwrap();
        assert!(
            (90.0 - sun.elevation_deg - 50.11162).abs() < 0.01,
            "{sun:?}"
        );
        assert!((sun.azimuth_deg - 194.34024).abs() < 0.01, "{sun:?}");
        let [x, y, z] = sun.direction();
        assert!(((x * x + y * y + z * z) - 1.0).abs() < 1e-12);
        // South of west of south: the azimuth is past 180 degrees, so x (east) is negative.
        assert!(x < 0.0 && y < 0.0 && z > 0.0);
    }

    #[test]
    fn a_december_morning_in_oslo_is_before_sunrise_and_a_bad_time_is_explained() {
        // 21 December 2026, 08:00 UTC (09:00 local) at 59.91 N, 10.75 E: the sun rises there
        // at about 08:18 UTC.
        let sun = SunPosition::at("2026-12-21T08:00:00Z", 59.91, 10.75).unwrap();
        assert!(!sun.is_up(), "{sun:?}");
        let noon = SunPosition::at("2026-12-21T11:20:00Z", 59.91, 10.75).unwrap();
        // At the solstice the noon sun stands 90 - 59.91 - 23.44 = 6.65 degrees up.
        assert!((noon.elevation_deg - 6.65).abs() < 0.2, "{noon:?}");
        let error = SunPosition::at("21/12/2026 8:00", 59.91, 10.75).unwrap_err();
        assert!(matches!(error, SunError::Time { .. }), "{error}");
        assert!(error.to_string().contains("is not a time"), "{error}");
    }
}
