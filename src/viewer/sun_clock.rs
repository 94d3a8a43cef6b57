//! The Light panel's date and time of day: the sun where the Solar Position Algorithm puts it
//! over the map's centre (a map in longitude and latitude) or over a latitude and longitude
//! given here.

use super::model::Model;
use crate::heightfield::place;
use crate::render::sun_position::SunPosition;
use chrono::{Datelike, NaiveDate};
use egui::{DragValue, Slider, Ui};

/// The date and time the sun is placed at, and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunClock {
    /// Whether the date and time set the sun (else its sliders do).
    pub on: bool,
    pub year: i32,
    /// Day of the year, 1 = 1 January.
    pub day: u32,
    /// Hours after midnight, UTC.
    pub hour: f64,
    /// The place when the map does not give one, in degrees.
    pub latitude: f64,
    pub longitude: f64,
}

impl Default for SunClock {
    fn default() -> Self {
        // The winter solstice at eight in the morning.
        SunClock {
            on: false,
            year: 2026,
            day: 355,
            hour: 8.0,
            latitude: 0.0,
            longitude: 0.0,
        }
    }
}

impl SunClock {
    /// The time as RFC 3339, e.g. `2026-12-21T08:00:00Z`.
    pub fn time(&self) -> Option<String> {
        let date = NaiveDate::from_yo_opt(self.year, self.day)?;
        let minutes = (self.hour.clamp(0.0, 24.0) * 60.0).round() as u32;
        let (hour, minute) = (
            (minutes / 60).min(23),
            if minutes >= 1440 { 59 } else { minutes % 60 },
        );
        Some(format!(
            "{:04}-{:02}-{:02}T{hour:02}:{minute:02}:00Z",
            date.year(),
            date.month(),
            date.day()
        ))
    }
}

/// The date and time controls; when they change, the sun moves to where they put it.
pub fn sun_clock_ui(ui: &mut Ui, model: &mut Model) {
    let centre = place::centre_degrees(model.shown.terrain.field());
    let clock = &mut model.sun_clock;
    let mut changed = ui
        .checkbox(&mut clock.on, "sun at a date and time (UTC)")
        .changed();
    if !clock.on {
        return;
    }
    ui.horizontal(|ui| {
        changed |= ui
            .add(
                DragValue::new(&mut clock.year)
                    .range(1..=3000)
                    .prefix("year "),
            )
            .changed();
        let date = clock.time().map(|t| t[..10].to_owned()).unwrap_or_default();
        ui.label(date);
    });
    changed |= ui
        .add(Slider::new(&mut clock.day, 1..=366).text("day of the year"))
        .changed();
    changed |= ui
        .add(
            Slider::new(&mut clock.hour, 0.0..=24.0)
                .step_by(0.25)
                .text("hour (UTC)"),
        )
        .changed();
    let (latitude, longitude) = match centre {
        Some(centre) => {
            ui.weak(format!(
                "over the map's centre, {:.3}, {:.3}",
                centre.0, centre.1
            ));
            centre
        }
        None => {
            ui.horizontal(|ui| {
                changed |= ui
                    .add(
                        DragValue::new(&mut clock.latitude)
                            .range(-90.0..=90.0)
                            .prefix("lat "),
                    )
                    .changed();
                changed |= ui
                    .add(
                        DragValue::new(&mut clock.longitude)
                            .range(-180.0..=180.0)
                            .prefix("lon "),
                    )
                    .changed();
            });
            (clock.latitude, clock.longitude)
        }
    };
    if !changed {
        return;
    }
    let placed = clock
        .time()
        .ok_or_else(|| format!("day {} is not in {}", clock.day, clock.year))
        .and_then(|time| SunPosition::at(&time, latitude, longitude));
    match placed {
        Ok(sun) => {
            let settings = &mut model.settings;
            // The panel's azimuth turns from +x (east) towards +y (north); the sky's from north
            // towards east.
            settings.sun_azimuth_deg = (90.0 - sun.azimuth_deg + 180.0).rem_euclid(360.0) - 180.0;
            settings.sun_elevation_deg = sun.elevation_deg;
            if !sun.is_up() {
                model.notify(format!(
                    "The sun is {:.1}° below the horizon: night",
                    -sun.elevation_deg
                ));
            }
        }
        Err(message) => model.error = Some(message),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_clock_names_its_date_and_time() {
        let clock = SunClock::default();
        assert_eq!(clock.time().as_deref(), Some("2026-12-21T08:00:00Z"));
        let leap = SunClock {
            year: 2028,
            day: 60,
            hour: 23.99,
            ..clock
        };
        assert_eq!(leap.time().as_deref(), Some("2028-02-29T23:59:00Z"));
        assert_eq!(SunClock { day: 366, ..clock }.time(), None);
    }
}
