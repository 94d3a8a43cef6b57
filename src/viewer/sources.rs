//! Where terrains come from: built-ins, height map images (georeferenced ones at true scale,
//! plain ones with a z scale that makes their relief visible) and scene files (with their
//! camera and lighting); rescaling, and laying an image over the map.

use super::orbit::Orbit;
use super::state::{
    Flythrough, LoadFailure, LoadRequest, Loaded, OverlayChange, SceneClock, SceneSetup, Source,
    Stage,
};
use crate::heightfield::{self, relief, Builtin, Drape, HeightfieldError, LoadOptions};
use crate::render::annotate::Annotations;
use crate::render::{local_time, Lighting, Scene, SceneError, SceneFile};
use crate::{Arith, Heightfield, Method, Terrain};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// Loads a request to the end (on the loading thread), or until `superseded` says a newer
/// request makes it pointless (checked while a height map file is decoded).
pub fn load(
    request: LoadRequest,
    report: &dyn Fn(Stage),
    superseded: &dyn Fn() -> bool,
) -> Result<Loaded, LoadFailure> {
    let start = Instant::now();
    report(Stage::Reading);
    let (field, scene) = match (&request.source, &request.from_memory) {
        (_, Some(terrain)) => (terrain.field().clone(), None),
        (Source::Builtin(name), None) => {
            let builtin =
                Builtin::named(name).ok_or_else(|| LoadFailure::NoBuiltin((*name).to_owned()))?;
            (builtin.load()?, None)
        }
        (Source::File(path), None) if request.source.is_scene() => load_scene(path)?,
        (Source::File(path), None) => (
            read_map(std::slice::from_ref(path), &request, superseded)?,
            None,
        ),
        (Source::Tiles(paths), None) => (read_map(paths, &request, superseded)?, None),
    };
    let field = match request.z_scale {
        Some(z) => rescale(field, z)?,
        None => field,
    };
    let field = match &request.overlay {
        None => field,
        Some(OverlayChange::Remove) => field.with_drape(None),
        Some(OverlayChange::Lay { path, opacity }) => {
            let drape = Drape::load(path, &field, *opacity)?;
            field.with_drape(Some(Arc::new(drape)))
        }
    };
    let decode_time = start.elapsed();
    report(Stage::Building);
    let terrain = Arc::new(Terrain::new(field));
    let scene = scene.map(|parts| scene_setup(&parts, &terrain));
    Ok(Loaded {
        request,
        terrain,
        scene,
        decode_time,
    })
}

/// Reads a height map, or tiles joined into one, at its default relief; stops when
/// `superseded` says so.
fn read_map(
    paths: &[PathBuf],
    request: &LoadRequest,
    superseded: &dyn Fn() -> bool,
) -> Result<Heightfield, LoadFailure> {
    let cancel = |_| {
        if superseded() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let options = LoadOptions {
        colour: request.decoding.colour,
        nodata: request.decoding.nodata,
        height_unit: request.decoding.height_unit,
        ..LoadOptions::new(1.0)
    };
    let field = match paths {
        [path] => heightfield::load_with(path, &options, &cancel),
        tiles => heightfield::load_mosaic(tiles, &options, &cancel),
    }?;
    let sensible = relief::default_z_scale(&field);
    Ok(rescale(field, sensible)?)
}

/// A validated scene and the camera section as written (the scene's `Camera` keeps no orbit).
struct SceneParts {
    file: SceneFile,
    lighting: Lighting,
    method: Method,
    arith: Arith,
    annotations: Annotations,
}

/// Reads a scene file: its height field, lighting, traversal and camera section.
fn load_scene(path: &Path) -> Result<(Heightfield, Option<SceneParts>), SceneError> {
    let file = SceneFile::read(path)?;
    // (The file is kept as written as well: the viewer takes its camera's form from it.)
    let Scene {
        field,
        lighting,
        method,
        arith,
        annotations,
        ..
    } = Scene::from_file(&file, Scene::base(path), path)?;
    let parts = SceneParts {
        file,
        lighting,
        method,
        arith,
        annotations,
    };
    Ok((field, Some(parts)))
}

/// The viewer's orbit, lighting and traversal from a scene.
fn scene_setup(parts: &SceneParts, terrain: &Terrain) -> SceneSetup {
    let framing = Orbit::framing(terrain);
    let orbit = match &parts.file.camera {
        // A scene without a camera is framed as a map is.
        None => framing,
        Some(camera) => match (camera.eye, camera.target, &camera.orbit) {
            (Some(eye), Some(target), _) => {
                Orbit::from_eye(eye, target, camera.fov_y_deg, framing.scale)
            }
            (_, _, Some(o)) => Orbit {
                target: o.target,
                yaw_deg: o.yaw_deg,
                pitch_deg: o.pitch_deg.clamp(-89.0, 89.0),
                distance: o.distance,
                fov_y_deg: camera.fov_y_deg,
                scale: framing.scale,
            },
            // Scene::load refused any other form.
            _ => framing,
        },
    };
    let sun = &parts.file.sun;
    // A local time (no offset) is kept as the clock's; an instant leaves the sun as placed.
    let clock = sun
        .time
        .as_deref()
        .and_then(|t| chrono::NaiveDateTime::parse_from_str(t.trim(), "%Y-%m-%dT%H:%M:%S").ok())
        .map(|local| SceneClock {
            local,
            zone: sun
                .zone
                .as_deref()
                .and_then(|z| local_time::zone_named(z).ok()),
            place: sun.lat.zip(sun.lon),
        });
    SceneSetup {
        orbit,
        lighting: parts.lighting,
        method: parts.method,
        arith: parts.arith,
        annotations: parts.annotations.clone(),
        contours: parts.file.overlay.as_ref().and_then(|overlay| {
            let interval = overlay.contours?;
            Some((interval, overlay.index_every))
        }),
        clock,
        flythrough: parts.file.animation.as_ref().map(|section| {
            let fov = parts.file.camera.as_ref().map_or(45.0, |c| c.fov_y_deg);
            Flythrough::from_section(section, fov, framing.scale)
        }),
    }
}

/// The same samples with another z scale.
fn rescale(field: Heightfield, z_scale: f64) -> Result<Heightfield, HeightfieldError> {
    if field.z_scale() == z_scale {
        return Ok(field);
    }
    field.with_z_scale(z_scale)
}
