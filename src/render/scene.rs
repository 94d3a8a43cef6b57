//! Scene files (README, 'Formats'): TOML, paths relative to the file, unknown keys refused by
//! name.

use super::animation::Animation;
use super::annotate::{Annotations, VectorLayer};
use super::camera::Camera;
use super::contours::Contours;
use crate::arith::Arith;
use crate::heightfield::{Drape, Heightfield};
use crate::traverse::Method;
use std::path::Path;
use std::sync::Arc;

mod effects;
mod error;
mod file;
mod heightmap;
mod lighting;
mod orbit;
mod sections;
mod sun;
mod surface;
mod triple;
mod view;
mod water;

use crate::compact::Compact;
pub use effects::EffectsError;
pub use error::{SceneError, SectionError};
pub use file::SceneFile;
use heightmap::HeightmapError;
pub use heightmap::{HeightmapSection, NoDataKey};
pub use lighting::{BaseDepthError, BaseStyle, Lighting};
pub use orbit::Orbit;
pub use sections::{EffectsSection, RenderSection, SunSection};
pub use sun::PlaceSunError;
pub use surface::{ContoursError, Normals, OverlaySection, ShadingSection};
pub use view::{CameraSection, DEFAULT_SIZE};
pub use water::{
    bytes_from_hex, bytes_from_linear, level_in_map_units, level_z, linear_from_bytes, WaterError,
    WaterSection, DEFAULT_WATER_COLOUR,
};

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The loaded height map.
    pub field: Heightfield,
    /// The validated camera.
    pub camera: Camera,
    /// Sun, shading and effects.
    pub lighting: Lighting,
    /// The traversal method.
    pub method: Method,
    /// The arithmetic.
    pub arith: Arith,
    /// The camera path, if the scene has one.
    pub animation: Option<Animation>,
    /// What is drawn over the picture.
    pub annotations: Annotations,
    /// Contour lines on the terrain (not yet seen by a camera, see [`Contours::seen_by`]).
    pub contours: Option<Contours>,
}

impl Scene {
    /// Reads and validates a scene file, loading its height map.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        Scene::from_file(&SceneFile::read(path)?, Scene::base(path), path)
    }

    /// The folder a scene file's relative paths start from.
    pub fn base(path: &Path) -> &Path {
        path.parent().unwrap_or(Path::new("."))
    }

    /// Validates a parsed scene; `base` resolves relative paths, `path` names the file in errors.
    pub fn from_file(file: &SceneFile, base: &Path, path: &Path) -> Result<Scene, SceneError> {
        let invalid = |message: String| SceneError::Invalid {
            path: path.to_owned(),
            message,
        };
        let field = file.heightmap.load(base).map_err(|error| match error {
            HeightmapError::Invalid(message) => invalid(message),
            HeightmapError::Load(source) => SceneError::Heightmap {
                path: path.to_owned(),
                source,
            },
        })?;
        let drape_path = file
            .overlay
            .as_ref()
            .and_then(|o| Some((o.path.as_ref()?, o)));
        let field = match drape_path {
            Some((drape_path, overlay)) => {
                let drape = Drape::load(&base.join(drape_path), &field, overlay.opacity).map_err(
                    |source| SceneError::Overlay {
                        path: path.to_owned(),
                        source,
                    },
                )?;
                field.with_drape(Some(Arc::new(drape)))
            }
            None => field,
        };
        let (field, camera) = view::camera(file.camera.as_ref(), file.size, field, path)?;
        let sun = &file.sun;
        let length = sun.direction.iter().map(|c| c * c).sum::<f64>().sqrt();
        if !(length.is_finite() && length > 0.0) {
            return Err(invalid(
                "[sun] direction must be a finite non-zero vector".into(),
            ));
        }
        for (key, value) in [
            ("[sun] intensity", sun.intensity),
            ("[sun] ambient", sun.ambient),
            ("[effects] fog", file.effects.fog),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(format!(
                    "{key} must be a finite number >= 0, got {}",
                    Compact(value)
                )));
            }
        }
        let method = file
            .render
            .method
            .parse()
            .map_err(|e| invalid(format!("[render] method: {e}")))?;
        let arith = file
            .render
            .arith
            .parse()
            .map_err(|e| invalid(format!("[render] arith: {e}")))?;
        let section = |source: SectionError| SceneError::Section {
            path: path.to_owned(),
            source,
        };
        let mut lighting = Lighting::from_sections(sun, &file.effects, &file.shading);
        lighting.base = BaseStyle::from_section(&file.shading).map_err(|e| section(e.into()))?;
        let mut lighting = sun::place_sun(sun, &field, lighting).map_err(|e| section(e.into()))?;
        lighting.effects =
            effects::effects_of(sun, &file.effects, &file.render).map_err(|e| section(e.into()))?;
        lighting.effects.water = file
            .water
            .as_ref()
            .map(|water| water.validate(&field))
            .transpose()
            .map_err(|e| section(e.into()))?;
        let lighting = lighting.after_dark();
        let animation = file
            .animation
            .as_ref()
            .map(|section| {
                let camera = file.camera.as_ref();
                let fov = camera.map_or(45.0, |c| c.fov_y_deg);
                let up = camera.map_or([0.0, 0.0, 1.0], |c| c.up);
                let map = Some((base, &field));
                Animation::new(section, camera.and_then(|c| c.orbit), fov, up, map)
            })
            .transpose()
            .map_err(|e| section(e.into()))?;
        let contours = file
            .overlay
            .as_ref()
            .map(|overlay| overlay.contours(&field))
            .transpose()
            .map_err(|e| section(e.into()))?
            .flatten();
        let vectors = file
            .vector
            .iter()
            .map(|vector| VectorLayer::load(vector, base, &field))
            .collect::<Result<_, _>>()
            .map_err(|e| section(e.into()))?;
        let annotations = Annotations::new(file.annotations.as_ref(), vectors);
        Ok(Scene {
            field,
            camera,
            lighting,
            method,
            arith,
            animation,
            annotations,
            contours,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::BUILTINS;

    /// Every built-in terrain has its scene, and the embedded scene is the one in `assets/`
    /// with the map embedded: the same samples, camera and lighting.
    #[test]
    fn builtin_scenes_are_the_asset_files_on_the_embedded_maps() {
        let builtins = SceneFile::builtins().unwrap();
        let names: Vec<&str> = builtins.iter().map(|(name, _)| *name).collect();
        assert_eq!(names, BUILTINS.map(|b| b.name));
        for (name, file) in builtins {
            let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("assets/{name}.toml"));
            let on_disk = Scene::load(&path).unwrap();
            let embedded = Scene::from_file(&file, Path::new(""), Path::new(name)).unwrap();
            assert_eq!(embedded.field.samples(), on_disk.field.samples(), "{name}");
            assert_eq!(embedded.field.step(), on_disk.field.step(), "{name}");
            assert_eq!(embedded.camera.size(), on_disk.camera.size(), "{name}");
            assert_eq!(
                embedded.camera.ray(7, 9),
                on_disk.camera.ray(7, 9),
                "{name}"
            );
            assert_eq!(embedded.lighting, on_disk.lighting, "{name}");
        }
    }
}
