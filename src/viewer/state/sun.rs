//! The Light panel's date and time, and the sun they place.

use super::loads::SceneClock;
use crate::heightfield::{place, Heightfield};
use crate::render::local_time::{self, TimeError};
use crate::render::sun_position::{SunError, SunPosition};
use chrono::{DateTime, Datelike, NaiveDate, NaiveDateTime, NaiveTime, Timelike, Utc};
use chrono_tz::Tz;
use thiserror::Error;

/// Why the clock places no sun.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ClockError {
    /// The date field.
    #[error("date '{0}' is not a date such as 2026-06-21")]
    Date(String),
    /// The time field.
    #[error("time '{0}' is not a time such as 09:30")]
    Time(String),
    /// The zone typed, or a local time its clocks skip.
    #[error(transparent)]
    Zone(#[from] TimeError),
    /// The place or instant.
    #[error(transparent)]
    Sun(#[from] SunError),
}

/// The date and time the sun is placed at, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct SunClock {
    /// Whether the date and time set the sun (else its sliders do).
    pub on: bool,
    /// The local date and time, to the minute.
    pub local: NaiveDateTime,
    /// The date and time fields as typed.
    pub date_text: String,
    pub time_text: String,
    /// A time zone typed (an IANA name); empty: the place's own.
    pub zone_text: String,
    /// The place when the map does not give one, in degrees.
    pub latitude: f64,
    pub longitude: f64,
}

impl Default for SunClock {
    fn default() -> Self {
        let local = default_local(0.0);
        SunClock {
            on: false,
            local,
            date_text: local.format("%Y-%m-%d").to_string(),
            time_text: clock_text(local),
            zone_text: String::new(),
            latitude: 0.0,
            longitude: 0.0,
        }
    }
}

/// A time when the sun is up almost anywhere: 10:00 on the clocks on this year's summer
/// solstice of the place's hemisphere (21 June north of the equator, 21 December south).
pub fn default_local(latitude: f64) -> NaiveDateTime {
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let year = i64::try_from(now)
        .ok()
        .and_then(|secs| DateTime::<Utc>::from_timestamp(secs, 0))
        .map_or(2026, |t| t.year());
    let month = if latitude < 0.0 { 12 } else { 6 };
    let date = NaiveDate::from_ymd_opt(year, month, 21).unwrap_or_default();
    date.and_time(NaiveTime::from_hms_opt(10, 0, 0).unwrap_or_default())
}

impl SunClock {
    /// The zone the clock reads: the one typed, else the place's, else UTC.
    pub fn zone(&self, (latitude, longitude): (f64, f64)) -> Result<Tz, TimeError> {
        if self.zone_text.trim().is_empty() {
            Ok(local_time::zone_at(latitude, longitude).unwrap_or(Tz::UTC))
        } else {
            local_time::zone_named(&self.zone_text)
        }
    }

    /// The date and time fields, read; or why they cannot be.
    fn typed(&self) -> Result<NaiveDateTime, ClockError> {
        let date = NaiveDate::parse_from_str(self.date_text.trim(), "%Y-%m-%d")
            .map_err(|_| ClockError::Date(self.date_text.clone()))?;
        let text = self.time_text.trim();
        let time = NaiveTime::parse_from_str(text, "%H:%M:%S")
            .or_else(|_| NaiveTime::parse_from_str(text, "%H:%M"))
            .map_err(|_| ClockError::Time(self.time_text.clone()))?;
        Ok(date.and_time(time))
    }

    /// Where the clock's sun stands over `field`: the map's centre, or the place typed.
    pub fn place(&self, field: &Heightfield) -> (f64, f64) {
        place::centre_degrees(field).unwrap_or((self.latitude, self.longitude))
    }

    /// The sun over `place` at the date and time typed, which the clock then reads; or why it
    /// cannot be placed.
    pub fn sun_at(&mut self, place: (f64, f64)) -> Result<SunPosition, ClockError> {
        let local = self.typed()?;
        let zone = self.zone(place)?;
        let instant = local_time::utc_of_local(local, zone)?;
        self.local = local;
        Ok(SunPosition::at_utc(instant, place.0, place.1)?)
    }

    /// Takes a scene's local time, zone and place, and sets the sun by them.
    pub fn set(&mut self, clock: SceneClock) {
        self.on = true;
        self.local = clock.local;
        self.date_text = clock.local.format("%Y-%m-%d").to_string();
        self.time_text = clock_text(clock.local);
        self.zone_text = clock.zone.map(|z| z.name().to_owned()).unwrap_or_default();
        if let Some((lat, lon)) = clock.place {
            self.latitude = lat;
            self.longitude = lon;
        }
    }

    /// The local time as a scene writes it, e.g. `2026-06-21T09:30:00`.
    pub fn time_key(&self) -> String {
        self.local.format("%Y-%m-%dT%H:%M:%S").to_string()
    }
}

/// The time of day as the field shows it: to the minute, or the second where it has any.
pub fn clock_text(local: NaiveDateTime) -> String {
    let format = if local.second() == 0 {
        "%H:%M"
    } else {
        "%H:%M:%S"
    };
    local.format(format).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_ten_in_the_morning_at_midsummer() {
        let north = default_local(36.0);
        assert_eq!((north.month(), north.day()), (6, 21));
        assert_eq!(north.format("%H:%M").to_string(), "10:00");
        assert_eq!(default_local(-33.0).month(), 12);
        let clock = SunClock {
            date_text: "2026-13-01".into(),
            ..SunClock::default()
        };
        assert_eq!(clock.typed(), Err(ClockError::Date("2026-13-01".into())));
    }
}
