//! A scene's light, shading and effects, validated: the sun (above the horizon or not), the
//! ambient term, shadows, fog, normals, the ramp and the effects.

use super::{EffectsSection, Normals, ShadingSection, SunSection};
use crate::geometry::Base;
use crate::heightfield::Terrain;
use crate::render::effects::{Effects, DEFAULT_RAYS, DEFAULT_SKY_DISTANCE};
use crate::render::ramp::Ramp;

/// Lighting and effects, validated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lighting {
    /// Unit vector towards the sun.
    pub sun: [f64; 3],
    /// Direct light at full facing: light is `ambient + intensity * cos(angle to the sun)`.
    pub intensity: f64,
    /// Light everywhere, facing the sun or not.
    pub ambient: f64,
    /// Whether shadow rays are cast.
    pub shadows: bool,
    /// Fog density per unit of distance; 0 is off.
    pub fog: f64,
    /// Flat or smooth normals.
    pub normals: Normals,
    /// The colour ramp by elevation.
    pub ramp: Ramp,
    /// Soft shadows, sky light and samples per pixel.
    pub effects: Effects,
    /// The base under the terrain.
    pub base: BaseStyle,
}

/// Which base a scene shows under its terrain: a floor wherever the map has holes (so holes
/// show ground, not sky through the terrain), and the floor with side walls where asked.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BaseStyle {
    /// A solid base: walls from the map's edge down to the floor.
    pub walls: bool,
    /// How far the floor lies below the lowest sample (default [`Base::default_depth`]).
    pub depth: Option<f64>,
}

impl BaseStyle {
    /// The base of `terrain` in this style: none on a map without holes unless it has walls.
    pub fn for_terrain(&self, terrain: &Terrain) -> Option<Base> {
        if !self.walls && terrain.field().nodata_count() == 0 {
            return None;
        }
        let depth = self.depth.unwrap_or_else(|| Base::default_depth(terrain));
        Base::under(terrain, depth, self.walls)
    }
}

impl Lighting {
    /// `direction` scaled to unit length, as a scene's sun is: the viewer scales its sun the
    /// same way, so a scene written from the viewer's sun renders the same image.
    pub fn unit(direction: [f64; 3]) -> [f64; 3] {
        let length = direction.iter().map(|c| c * c).sum::<f64>().sqrt();
        direction.map(|c| c / length)
    }

    /// Whether the sun stands above the horizon.
    pub fn sun_up(&self) -> bool {
        self.sun[2] > 0.0
    }

    /// This lighting as the sun's place allows: a sun on or below the horizon lights nothing
    /// directly, and no shadow, soft-shadow or sky-light rays are cast (the sky is the night's,
    /// see [`Shader`](crate::render::Shader)); the ambient term stays, as moonlight would.
    pub fn after_dark(self) -> Lighting {
        if self.sun_up() {
            return self;
        }
        Lighting {
            intensity: 0.0,
            shadows: false,
            effects: Effects {
                sky_light: false,
                ..self.effects
            },
            ..self
        }
    }

    /// The lighting a scene file's sections describe (the sun's direction non-zero: scene
    /// files are checked for that first), with the direction normalised.
    pub fn from_sections(
        sun: &SunSection,
        effects: &EffectsSection,
        shading: &ShadingSection,
    ) -> Lighting {
        Lighting {
            sun: Lighting::unit(sun.direction),
            intensity: sun.intensity,
            ambient: sun.ambient,
            shadows: effects.shadows,
            fog: effects.fog,
            normals: shading.normals,
            ramp: shading.ramp,
            effects: Effects {
                sun_angle_deg: sun.angle_deg,
                sun_rays: sun.rays.unwrap_or(DEFAULT_RAYS),
                sky_light: effects.sky_light,
                sky_rays: effects.sky_rays.unwrap_or(DEFAULT_RAYS),
                sky_distance: effects.sky_distance.unwrap_or(DEFAULT_SKY_DISTANCE),
                ..Effects::default()
            },
            // (Checked by the scene, see `BaseStyle::from_section`.)
            base: BaseStyle::default(),
        }
    }
}

/// A base depth that is not a finite number above 0.
#[derive(Clone, Debug, thiserror::Error, PartialEq)]
#[error("[shading] base_depth must be a finite number > 0, got {0}")]
pub struct BaseDepthError(pub f64);

impl BaseStyle {
    /// The base a scene's `[shading]` section asks for, its depth checked.
    pub fn from_section(shading: &ShadingSection) -> Result<BaseStyle, BaseDepthError> {
        if let Some(depth) = shading.base_depth.filter(|d| !(d.is_finite() && *d > 0.0)) {
            return Err(BaseDepthError(depth));
        }
        Ok(BaseStyle {
            walls: shading.base,
            depth: shading.base_depth,
        })
    }
}
