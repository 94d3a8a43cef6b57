//! A scene file's `[heightmap]` section: the map, how to read it, and how high to show its
//! relief (a z scale, or an exaggeration of a georeferenced map's true scale).

use crate::compact::Compact;
use crate::heightfield::{
    self, relief, Builtin, HeightUnit, Heightfield, LoadError, LoadOptions, NoDataValue,
};
use serde::Deserialize;
use std::ops::ControlFlow;
use std::path::Path;

/// A scene file's `[heightmap]` section.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct HeightmapSection {
    /// A file, relative to the scene file; or `builtin:NAME` for a built-in terrain.
    #[serde(default)]
    pub path: String,
    /// Instead of `path`: georeferenced tiles joined into one map (a mosaic).
    #[serde(default)]
    pub paths: Vec<String>,
    /// Height of the largest sample value (maxval); for float and signed rasters, the factor
    /// applied to their values. Left out, a georeferenced map is shown at true scale and a
    /// plain image with its relief a quarter of its larger side.
    #[serde(default)]
    pub z_scale: Option<f64>,
    /// For a georeferenced map instead of `z_scale`: how many times its true scale its heights
    /// are shown.
    #[serde(default)]
    pub exaggeration: Option<f64>,
    /// How RGB images become heights: `luminance` (the default), `mapbox` or `terrarium`.
    #[serde(default)]
    pub rgb: Option<String>,
    /// Which raster value means no data: `"auto"` (the default), `"none"` or a number.
    #[serde(default)]
    pub nodata: Option<NoDataKey>,
    /// A georeferenced map's height unit, `m`, `ft` or `us-ft`, instead of the one its file
    /// implies (its vertical unit, else a CRS in feet's foot, else metres).
    #[serde(default)]
    pub height_unit: Option<String>,
}

/// `nodata` as written: a number, or a word.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum NoDataKey {
    /// This raster value means no data.
    Value(f64),
    /// `auto` or `none`.
    Word(String),
}

/// Why a `[heightmap]` section gives no field.
pub enum HeightmapError {
    /// A key's value is wrong; the message names it.
    Invalid(String),
    /// The map could not be loaded.
    Load(LoadError),
}

impl HeightmapSection {
    /// Loads the map, relative paths from `base`, at the section's z scale or exaggeration.
    pub fn load(&self, base: &Path) -> Result<Heightfield, HeightmapError> {
        let invalid = HeightmapError::Invalid;
        let z_scale = match (self.z_scale, self.exaggeration) {
            (Some(_), Some(_)) => {
                return Err(invalid(
                    "[heightmap] has both z_scale and exaggeration; give one".into(),
                ))
            }
            (_, Some(e)) if !(e.is_finite() && e >= 0.0) => {
                return Err(invalid(format!(
                    "[heightmap] exaggeration must be a finite number >= 0, got {}",
                    Compact(e)
                )))
            }
            (z, _) => z,
        };
        let field = match self.path.strip_prefix("builtin:") {
            _ if self.path.is_empty() == self.paths.is_empty() => {
                return Err(invalid(
                    "[heightmap] needs path (a map) or paths (tiles joined into one map), not \
                     both"
                        .into(),
                ))
            }
            Some(name) => {
                let builtin = Builtin::named(name).ok_or_else(|| {
                    invalid(format!("[heightmap] path: no built-in terrain '{name}'"))
                })?;
                builtin.load_scaled(z_scale.unwrap_or(builtin.z_scale))
            }
            None => {
                let mut options = LoadOptions::new(z_scale.unwrap_or(1.0));
                if let Some(rgb) = &self.rgb {
                    options.colour = rgb
                        .parse()
                        .map_err(|e| invalid(format!("[heightmap] rgb: {e}")))?;
                }
                options.nodata = match &self.nodata {
                    None => NoDataValue::Auto,
                    Some(NoDataKey::Value(v)) => NoDataValue::Value(*v),
                    Some(NoDataKey::Word(w)) => w
                        .parse()
                        .map_err(|e| invalid(format!("[heightmap] nodata: {e}")))?,
                };
                options.height_unit = self
                    .height_unit
                    .as_deref()
                    .map(|name| {
                        HeightUnit::named(name).ok_or_else(|| {
                            invalid(format!(
                                "[heightmap] height_unit must be m, ft or us-ft, got '{name}'"
                            ))
                        })
                    })
                    .transpose()?;
                let keep_going = |_| ControlFlow::Continue(());
                if self.paths.is_empty() {
                    heightfield::load_with(&base.join(&self.path), &options, &keep_going)
                } else {
                    let tiles: Vec<_> = self.paths.iter().map(|p| base.join(p)).collect();
                    heightfield::load_mosaic(&tiles, &options, &keep_going)
                }
            }
        }
        .map_err(HeightmapError::Load)?;
        let z_scale = match (z_scale, self.exaggeration) {
            (Some(_), _) => return Ok(field),
            (None, Some(e)) => relief::true_z_scale(&field, e).ok_or_else(|| {
                invalid(
                    "[heightmap] exaggeration needs a georeferenced map; give z_scale for a \
                     plain image"
                        .into(),
                )
            })?,
            // A built-in is loaded at its own z scale.
            (None, None) if self.path.starts_with("builtin:") => return Ok(field),
            (None, None) => relief::default_z_scale(&field),
        };
        field
            .with_z_scale(z_scale)
            .map_err(|e| invalid(format!("[heightmap] {e}")))
    }
}
