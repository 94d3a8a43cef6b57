//! The Light panel's date and time: the sun where the Solar Position Algorithm puts it over
//! the map's centre (or a latitude and longitude given here) at a date and time on the
//! clocks of the map's time zone (or a zone typed here). Fields apply on Enter or when they
//! lose focus, not at every keystroke.

use super::state::{clock_text, default_local, Action, SunClock};
use chrono::{Offset, TimeZone};
use egui::{DragValue, TextEdit, Ui};

/// The date, time and zone controls over a map centred at `centre` (latitude and longitude,
/// if known); when they are applied, asks for the sun to move to where they put it.
pub fn sun_clock_ui(
    ui: &mut Ui,
    clock: &mut SunClock,
    centre: Option<(f64, f64)>,
) -> Option<Action> {
    let switched = ui
        .checkbox(&mut clock.on, "sun at a local date and time")
        .changed();
    if !clock.on {
        return None;
    }
    if switched {
        // A time when the sun is up at the map.
        clock.local = default_local(centre.map_or(clock.latitude, |c| c.0));
        clock.date_text = clock.local.format("%Y-%m-%d").to_string();
        clock.time_text = clock_text(clock.local);
    }
    let mut apply = switched;
    ui.horizontal(|ui| {
        let date = ui.add(TextEdit::singleline(&mut clock.date_text).desired_width(80.0));
        let time = ui.add(TextEdit::singleline(&mut clock.time_text).desired_width(40.0));
        apply |= date.lost_focus() || time.lost_focus();
        ui.label("date, time");
    });
    let place = centre.unwrap_or((clock.latitude, clock.longitude));
    ui.horizontal(|ui| {
        let hint = clock
            .zone(place)
            .map(|z| z.name().to_owned())
            .unwrap_or_default();
        let zone = ui.add(
            TextEdit::singleline(&mut clock.zone_text)
                .hint_text(hint)
                .desired_width(140.0),
        );
        apply |= zone.lost_focus();
        // The offset the zone's rules give at the clock's time, summer time included.
        let offset = clock.zone(place).ok().and_then(|z| {
            z.offset_from_local_datetime(&clock.local)
                .earliest()
                .map(|o| o.fix().to_string())
        });
        ui.label(format!("zone, UTC{}", offset.unwrap_or_default()));
    });
    match centre {
        Some((lat, lon)) => {
            ui.weak(format!("over the map's centre, {lat:.3}, {lon:.3}"));
        }
        None => {
            ui.horizontal(|ui| {
                for (value, range, prefix) in [
                    (&mut clock.latitude, -90.0..=90.0, "lat "),
                    (&mut clock.longitude, -180.0..=180.0, "lon "),
                ] {
                    apply |= ui
                        .add(DragValue::new(value).range(range).prefix(prefix))
                        .lost_focus();
                }
            });
        }
    }
    apply.then_some(Action::ApplyClock)
}
