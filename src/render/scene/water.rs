//! A scene file's `[water]` section: the level, in the map's height units (a DEM's metres,
//! shown exaggerated as its heights are) or, on a plain image, in scene units; and the
//! water's colour as `#RRGGBB`.

use crate::compact::Compact;
use crate::heightfield::{Heightfield, Quantisation};
use crate::render::effects::Water;
use serde::Deserialize;
use thiserror::Error;

/// The water's colour when the scene does not say: a deep blue-green.
pub const DEFAULT_WATER_COLOUR: &str = "#1e4d6b";

/// Which `[water]` key is wrong.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum WaterError {
    /// A level that is not finite.
    #[error("[water] level must be a finite number, got {}", Compact(*.0))]
    Level(f64),
    /// A colour not written `#RRGGBB`.
    #[error("[water] colour must be written #RRGGBB, got {0:?}")]
    Colour(String),
}

/// A scene file's `[water]` section.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct WaterSection {
    /// The water's height: in the map's own units where its heights have them (a DEM in
    /// metres), else in scene units.
    pub level: f64,
    /// `#RRGGBB` (default [`DEFAULT_WATER_COLOUR`]).
    #[serde(default)]
    pub colour: Option<String>,
}

impl WaterSection {
    /// The water on `field`, or which key is wrong.
    pub fn validate(&self, field: &Heightfield) -> Result<Water, WaterError> {
        if !self.level.is_finite() {
            return Err(WaterError::Level(self.level));
        }
        let text = self.colour.as_deref().unwrap_or(DEFAULT_WATER_COLOUR);
        let colour = parse_colour(text).ok_or_else(|| WaterError::Colour(text.to_owned()))?;
        Ok(Water {
            level: level_z(field, self.level),
            colour,
        })
    }
}

/// The height `z` of a level given in the map's units (see [`WaterSection::level`]).
pub fn level_z(field: &Heightfield, level: f64) -> f64 {
    match field.quantisation() {
        Quantisation::Offset { .. } => level * field.z_scale(),
        Quantisation::Maxval(_) => level,
    }
}

/// The level in the map's units of the height `z` (the inverse of [`level_z`]).
pub fn level_in_map_units(field: &Heightfield, z: f64) -> f64 {
    match field.quantisation() {
        Quantisation::Offset { .. } if field.z_scale() > 0.0 => z / field.z_scale(),
        _ => z,
    }
}

/// `#RRGGBB` as display bytes.
pub fn bytes_from_hex(text: &str) -> Option<[u8; 3]> {
    // Six hex digits and nothing else: `from_str_radix` alone would take a sign ("#+fffff").
    let hex = text
        .strip_prefix('#')
        .filter(|h| h.len() == 6 && h.bytes().all(|b| b.is_ascii_hexdigit()))?;
    let value = u32::from_str_radix(hex, 16).ok()?;
    Some([16, 8, 0].map(|shift| (value >> shift) as u8))
}

/// Display bytes in linear light (through a gamma of 2.2, as the renderer writes bytes).
pub fn linear_from_bytes(bytes: [u8; 3]) -> [f64; 3] {
    bytes.map(|b| (f64::from(b) / 255.0).powf(2.2))
}

/// Linear light as the nearest display bytes (the inverse of [`linear_from_bytes`]).
pub fn bytes_from_linear(colour: [f64; 3]) -> [u8; 3] {
    colour.map(|c| (c.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8)
}

/// `#RRGGBB` in linear light.
fn parse_colour(text: &str) -> Option<[f64; 3]> {
    bytes_from_hex(text).map(linear_from_bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_are_read_as_display_bytes() {
        assert_eq!(parse_colour("#ff0000"), Some([1.0, 0.0, 0.0]));
        let grey = parse_colour("#808080").unwrap();
        assert!((grey[0] - (128.0f64 / 255.0).powf(2.2)).abs() < 1e-15);
        for bad in [
            "ff0000", "#ff00", "#gg0000", "#ff00001", "#+fffff", "#-00000", "# fffff",
        ] {
            assert_eq!(parse_colour(bad), None, "{bad}");
        }
        for byte in 0..=255 {
            let bytes = [byte, 255 - byte, byte / 2];
            assert_eq!(bytes_from_linear(linear_from_bytes(bytes)), bytes);
        }
    }
}
