//! `[sun] time`: the sun where it stands at a place and time, the place the map's centre (on a
//! map in longitude and latitude) or the `lat` and `lon` keys. (A sun below the horizon lights
//! nothing: [`Lighting::after_dark`].)

use super::{Lighting, SunSection};
use crate::heightfield::{place, Heightfield};
use crate::render::sun_position::SunPosition;

/// `lighting` with its sun placed by the section's time, if it gives one.
pub fn place_sun(
    section: &SunSection,
    field: &Heightfield,
    lighting: Lighting,
) -> Result<Lighting, String> {
    let Some(time) = &section.time else {
        return Ok(lighting);
    };
    let (latitude, longitude) = match (section.lat, section.lon) {
        (Some(lat), Some(lon)) => (lat, lon),
        (None, None) => place::centre_degrees(field)
            .ok_or("[sun] time needs lat and lon keys: the map is not in longitude and latitude")?,
        _ => return Err("[sun] lat and lon go together: give both or neither".into()),
    };
    let sun = SunPosition::at(time, latitude, longitude).map_err(|e| format!("[sun] time: {e}"))?;
    Ok(Lighting {
        sun: Lighting::unit(sun.direction()),
        ..lighting
    })
}
