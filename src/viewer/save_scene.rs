//! "Save scene": the current view as a scene file that `heightray render` turns into the same
//! image: the map and how it was read, its z scale, the orbit at the export size, the light,
//! effects, traversal and arithmetic. Saved beside the exported images, under a name no other
//! file has.

use super::export::create_numbered;
use super::state::{ExportError, KeysError, Model, Source};
use crate::heightfield::place;
use crate::heightfield::{HeightUnitSource, NoDataValue, OptionError};
use crate::output_file;
use crate::render::{
    bytes_from_linear, level_in_map_units, NoDataKey, Scene, SceneError, SceneFile,
};
use std::path::Path;
use thiserror::Error;

/// Why the view could not be saved as a scene.
#[derive(Debug, Error)]
enum SaveSceneError {
    /// The scene on screen could not be read again for its map's keys.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Its no-data word is not one.
    #[error(transparent)]
    NoData(#[from] OptionError),
    /// The flythrough's keys.
    #[error(transparent)]
    Keys(#[from] KeysError),
    /// The file could not be written.
    #[error(transparent)]
    Export(#[from] ExportError),
}

/// Writes the view at `size` pixels as `heightray-MAP-NNN.toml` in the export folder.
pub fn save(model: &mut Model, size: (u32, u32)) {
    let saved = scene_text(model, size).and_then(|text| {
        let stem = super::export::stem(model);
        let (_, path) = create_numbered(&model.export.folder(), &stem, "toml")?;
        output_file::write_bytes(&path, text.as_bytes())
            .inspect_err(|_| {
                let _ = std::fs::remove_file(&path);
            })
            .map_err(ExportError::from)?;
        Ok(path)
    });
    match saved {
        Ok(path) => {
            model.notify(format!("Saved the scene as {}", path.display()));
            model.export.last_scene = Some(path);
        }
        Err(refused) => model.error = Some(refused.to_string()),
    }
}

/// The scene file's text for the view at `size` pixels.
fn scene_text(model: &Model, (width, height): (u32, u32)) -> Result<String, SaveSceneError> {
    let orbit = &model.orbit;
    let lighting = model.settings.lighting();
    let z_scale = model.shown.terrain.field().z_scale();
    let heightmap = heightmap_keys(&model.shown.source, model)?;
    let [tx, ty, tz] = orbit.target;
    let effects = lighting.effects;
    let animation = model.flythrough.scene_text()?;
    Ok(format!(
        "[heightmap]\n{heightmap}z_scale = {z_scale:?}\n\n\
         [camera]\norbit = {{ target = [{tx:?}, {ty:?}, {tz:?}], yaw_deg = {:?}, \
         pitch_deg = {:?}, distance = {:?} }}\nfov_y_deg = {:?}\nwidth = {width}\n\
         height = {height}\n\n\
         [sun]\n{}intensity = {:?}\nambient = {:?}\n\
         angle_deg = {:?}\nrays = {}\n\n\
         [effects]\nshadows = {}\nfog = {:?}\nsky_light = {}\nsky_rays = {}\nsky_distance = {:?}\n\n\
         [shading]\nnormals = \"{}\"\nramp = \"{}\"\nbase = {}\n{}\n\
         [render]\nmethod = \"{}\"\narith = \"{}\"\nsamples = {}\nadaptive = {}\n{}{}{animation}",
        orbit.yaw_deg,
        orbit.pitch_deg,
        orbit.distance,
        orbit.fov_y_deg,
        sun_keys(model),
        lighting.intensity,
        lighting.ambient,
        effects.sun_angle_deg,
        effects.sun_rays,
        lighting.shadows,
        lighting.fog,
        effects.sky_light,
        effects.sky_rays,
        effects.sky_distance,
        format!("{:?}", lighting.normals).to_lowercase(),
        format!("{:?}", lighting.ramp).to_lowercase(),
        lighting.base.walls,
        lighting
            .base
            .depth
            .map_or(String::new(), |depth| format!("base_depth = {depth:?}\n")),
        model.settings.method,
        model.settings.arith(),
        effects.samples,
        effects.adaptive,
        overlay_keys(model),
        water_keys(model),
    ) + &annotation_keys(model))
}

/// The `[annotations]` section and the `[[vector]]` layers that exports draw, if any.
fn annotation_keys(model: &Model) -> String {
    let marks = &model.export.marks;
    let (title, attribution) = (model.export.title.trim(), model.export.attribution.trim());
    let mut keys = String::new();
    if marks.scale_bar
        || marks.north_arrow
        || marks.legend
        || !(title.is_empty() && attribution.is_empty())
    {
        keys += &format!(
            "\n[annotations]\nscale_bar = {}\nnorth_arrow = {}\nlegend = {}\n",
            marks.scale_bar, marks.north_arrow, marks.legend
        );
    }
    if !title.is_empty() {
        keys += &format!("title = {title:?}\n");
    }
    if !attribution.is_empty() {
        keys += &format!("attribution = {attribution:?}\n");
    }
    for layer in &marks.vectors {
        let section = &layer.section;
        let [r, g, b] = layer.colour;
        keys += &format!(
            "\n[[vector]]\npath = {:?}\ncoordinates = \"{}\"\ncolour = \"#{r:02x}{g:02x}{b:02x}\"\nlift = {:?}\n",
            section.path,
            format!("{:?}", section.coordinates).to_lowercase(),
            layer.lift
        );
    }
    keys
}

/// The `[sun]` keys that place the sun: the local time and zone the clock set it by; a
/// scene's direction, as given; or the compass bearing and elevation of the sliders.
fn sun_keys(model: &Model) -> String {
    let settings = &model.settings;
    if model.sun_clock.on {
        let place = model.sun_clock.place(model.shown.terrain.field());
        let zone = model.sun_clock.zone(place).unwrap_or(chrono_tz::Tz::UTC);
        let own_place = place::centre_degrees(model.shown.terrain.field()).is_some();
        let lat_lon = if own_place {
            String::new()
        } else {
            format!("lat = {:?}\nlon = {:?}\n", place.0, place.1)
        };
        return format!(
            "time = \"{}\"\nzone = \"{}\"\n{lat_lon}",
            model.sun_clock.time_key(),
            zone.name()
        );
    }
    match settings.given_sun() {
        Some([x, y, z]) => format!("direction = [{x:?}, {y:?}, {z:?}]\n"),
        None => format!(
            "azimuth_deg = {:?}\nelevation_deg = {:?}\n",
            settings.sun_azimuth_deg, settings.sun_elevation_deg
        ),
    }
}

/// The `[water]` section, if the view shows water.
fn water_keys(model: &Model) -> String {
    let Some(water) = model.settings.effects.water else {
        return String::new();
    };
    let level = level_in_map_units(model.shown.terrain.field(), water.level);
    let [r, g, b] = bytes_from_linear(water.colour);
    format!("\n[water]\nlevel = {level:?}\ncolour = \"#{r:02x}{g:02x}{b:02x}\"\n")
}

/// The `[overlay]` section of the image draped over the map and the contour lines, if any.
fn overlay_keys(model: &Model) -> String {
    let field = model.shown.terrain.field();
    let drape = field.drape().map(|drape| {
        format!(
            "path = {:?}\nopacity = {:?}\n",
            absolute(drape.path()),
            drape.opacity()
        )
    });
    let contours = model.widgets.contours.scene_keys(field);
    if drape.is_none() && contours.is_none() {
        return String::new();
    }
    format!(
        "\n[overlay]\n{}{}",
        drape.unwrap_or_default(),
        contours.unwrap_or_default()
    )
}

/// The `[heightmap]` keys but the z scale: the map's path in full (a scene's own map, when a
/// scene is shown) and how it was read.
fn heightmap_keys(source: &Source, model: &Model) -> Result<String, SaveSceneError> {
    let (paths, rgb, nodata) = match source {
        Source::Builtin(name) => return Ok(format!("path = \"builtin:{name}\"\n")),
        Source::File(path) if SceneFile::is_scene_path(path) => {
            let file = SceneFile::read(path)?;
            let map = file.heightmap;
            if map.path.starts_with("builtin:") {
                return Ok(format!("path = {:?}\n", map.path));
            }
            let nodata = match map.nodata {
                None => NoDataValue::Auto,
                Some(NoDataKey::Value(v)) => NoDataValue::Value(v),
                Some(NoDataKey::Word(w)) => w.parse::<NoDataValue>()?,
            };
            let rgb = map.rgb.unwrap_or_else(|| "luminance".into());
            let base = Scene::base(path);
            let paths = if map.paths.is_empty() {
                vec![base.join(map.path)]
            } else {
                map.paths.iter().map(|p| base.join(p)).collect()
            };
            (paths, rgb, nodata)
        }
        Source::File(path) => {
            let decoding = model.shown.decoding;
            (
                vec![path.clone()],
                decoding.colour.to_string(),
                decoding.nodata,
            )
        }
        Source::Tiles(paths) => {
            let decoding = model.shown.decoding;
            (paths.clone(), decoding.colour.to_string(), decoding.nodata)
        }
    };
    let path = match &paths[..] {
        [path] => format!("path = {:?}", absolute(path)),
        tiles => format!(
            "paths = {:?}",
            tiles.iter().map(|p| absolute(p)).collect::<Vec<_>>()
        ),
    };
    let nodata = match nodata {
        NoDataValue::Value(v) => format!("{v:?}"),
        word => format!("\"{word}\""),
    };
    // The unit the map is shown in, as a key, whatever chose it.
    let unit = match model.shown.terrain.field().georef().map(|g| g.height_unit) {
        Some(unit) if unit.source == HeightUnitSource::Chosen => {
            format!("height_unit = \"{}\"\n", unit.key())
        }
        _ => String::new(),
    };
    Ok(format!(
        "{path}\nrgb = \"{rgb}\"\nnodata = {nodata}\n{unit}"
    ))
}

/// `path` in full, so the scene works from any folder.
fn absolute(path: &Path) -> String {
    std::path::absolute(path)
        .unwrap_or_else(|_| path.to_owned())
        .display()
        .to_string()
}
