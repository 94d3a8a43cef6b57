//! Clock time where the map lies: the IANA time zone of a place (`tzf-rs`'s boundaries) and
//! its rules (`chrono-tz`), so that a sun set for 09:30 stands where it does at half past
//! nine on the map's own clocks, summer time included.

use chrono::{DateTime, LocalResult, NaiveDateTime, TimeZone, Utc};
use chrono_tz::Tz;
use std::sync::LazyLock;
use thiserror::Error;
use tzf_rs::EmbeddedFinder;

/// Why a time or a time zone cannot be read.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum TimeError {
    /// Not an IANA zone name.
    #[error("'{0}' is not a time zone name such as America/New_York, Europe/Oslo or UTC")]
    Zone(String),
    /// A local time the zone's clocks skip.
    #[error("{local} does not occur in {zone}: the clocks skip it as summer time starts")]
    Skipped {
        /// The local time asked for.
        local: NaiveDateTime,
        /// The zone.
        zone: Tz,
    },
    /// Not a time in a form read.
    #[error("'{0}' is not a time such as 2026-06-21T09:30 (local) or 2026-12-21T08:00:00Z")]
    Form(String),
    /// A local time where no zone is known.
    #[error("'{0}' is a local time, but no time zone is known: add zone = \"Area/City\"")]
    NoZone(String),
}

/// The zone boundaries, read in place from the executable's data on first use.
static FINDER: LazyLock<EmbeddedFinder> = LazyLock::new(EmbeddedFinder::new);

/// The time zone at `latitude`, `longitude` in degrees, if one is known there (the sea
/// outside any zone's waters has none).
pub fn zone_at(latitude: f64, longitude: f64) -> Option<Tz> {
    if !(latitude.is_finite() && longitude.is_finite()) {
        return None;
    }
    FINDER.get_tz_name(longitude, latitude).parse().ok()
}

/// A time zone by its IANA name, e.g. `America/New_York` or `UTC`.
pub fn zone_named(name: &str) -> Result<Tz, TimeError> {
    name.trim()
        .parse()
        .map_err(|_| TimeError::Zone(name.to_owned()))
}

/// The instant a clock in `zone` shows `local`; the earlier of two in the hour repeated
/// when summer time ends; an error for the hour skipped when it starts.
pub fn utc_of_local(local: NaiveDateTime, zone: Tz) -> Result<DateTime<Utc>, TimeError> {
    match zone.from_local_datetime(&local) {
        LocalResult::Single(t) | LocalResult::Ambiguous(t, _) => Ok(t.with_timezone(&Utc)),
        LocalResult::None => Err(TimeError::Skipped { local, zone }),
    }
}

/// A time as a scene writes it: with an offset (`2026-12-21T08:00:00Z`,
/// `2026-06-21T10:00:00-04:00`) it is that instant; without one (`2026-06-21T09:30`), the
/// time on the clocks of `zone`.
pub fn parse_time(text: &str, zone: Option<Tz>) -> Result<DateTime<Utc>, TimeError> {
    if let Ok(time) = DateTime::parse_from_rfc3339(text) {
        return Ok(time.with_timezone(&Utc));
    }
    let local = [
        "%Y-%m-%dT%H:%M:%S",
        "%Y-%m-%dT%H:%M",
        "%Y-%m-%d %H:%M:%S",
        "%Y-%m-%d %H:%M",
    ]
    .iter()
    .find_map(|format| NaiveDateTime::parse_from_str(text.trim(), format).ok())
    .ok_or_else(|| TimeError::Form(text.to_owned()))?;
    let zone = zone.ok_or_else(|| TimeError::NoZone(text.to_owned()))?;
    utc_of_local(local, zone)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_have_their_zones_and_local_times_their_offsets() {
        assert_eq!(zone_at(35.96, -83.92), Some(chrono_tz::America::New_York));
        assert_eq!(zone_at(59.91, 10.75), Some(chrono_tz::Europe::Oslo));
        // 09:30 in New York in June is summer time, UTC-4.
        let t = parse_time("2026-06-21T09:30", zone_at(40.7, -74.0)).unwrap();
        assert_eq!(t.to_rfc3339(), "2026-06-21T13:30:00+00:00");
        let t = parse_time("2026-12-21T08:00:00Z", None).unwrap();
        assert_eq!(t.to_rfc3339(), "2026-12-21T08:00:00+00:00");
        assert_eq!(
            parse_time("2026-06-21T09:30", None),
            Err(TimeError::NoZone("2026-06-21T09:30".into()))
        );
        assert_eq!(
            zone_named("Mars/Olympus"),
            Err(TimeError::Zone("Mars/Olympus".into()))
        );
    }
}
