//! S exports the rendered image: the same pixels `heightray render` makes of a scene written
//! from the viewer's reported camera and light, at the render resolution or at a chosen size,
//! with no panels or overlays; each press a new file, none overwritten.

use super::app::num;
use super::Session;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A scene file for the view in `state`, on the built-in valley, at `size` pixels.
fn scene_of(state: &Value, size: (u32, u32)) -> String {
    let n = |p: &str| format!("{:?}", num(state, p));
    let triple = |p: &str| {
        format!(
            "[{}, {}, {}]",
            n(&format!("{p}/0")),
            n(&format!("{p}/1")),
            n(&format!("{p}/2"))
        )
    };
    let text = |p: &str| {
        state
            .pointer(p)
            .and_then(Value::as_str)
            .unwrap_or_default()
            .to_owned()
    };
    let flag = |p: &str| {
        state
            .pointer(p)
            .and_then(Value::as_bool)
            .unwrap_or_default()
    };
    format!(
        "[heightmap]\npath = \"builtin:valley513\"\nz_scale = {z}\n\n\
         [camera]\norbit = {{ target = {target}, yaw_deg = {yaw}, pitch_deg = {pitch}, distance = {distance} }}\n\
         fov_y_deg = {fov}\nwidth = {w}\nheight = {h}\n\n\
         [sun]\ndirection = {sun}\nintensity = {intensity}\nambient = {ambient}\n\n\
         [effects]\nshadows = {shadows}\nfog = {fog}\n\n\
         [shading]\nnormals = \"{normals}\"\nramp = \"{ramp}\"\n\n\
         [render]\nmethod = \"{method}\"\narith = \"{arith}\"\n",
        z = n("/terrain/z_scale"),
        target = triple("/camera/target"),
        yaw = n("/camera/yaw_deg"),
        pitch = n("/camera/pitch_deg"),
        distance = n("/camera/distance"),
        fov = n("/camera/fov_y_deg"),
        w = size.0,
        h = size.1,
        sun = triple("/sun/direction"),
        intensity = n("/lighting/intensity"),
        ambient = n("/lighting/ambient"),
        shadows = flag("/lighting/shadows"),
        fog = n("/lighting/fog"),
        normals = text("/lighting/normals"),
        ramp = text("/lighting/ramp"),
        method = text("/method"),
        arith = text("/arith"),
    )
}

/// `heightray render` of a scene, as RGB pixels.
fn render(dir: &Path, scene: &str) -> image::RgbImage {
    let (scene_path, out) = (dir.join("export-check.toml"), dir.join("reference.png"));
    std::fs::write(&scene_path, scene).expect("write the scene");
    let status = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .arg("render")
        .arg(&scene_path)
        .arg("-o")
        .arg(&out)
        .stdout(std::process::Stdio::null())
        .status()
        .expect("run heightray render");
    assert!(status.success(), "heightray render failed on\n{scene}");
    image::open(&out).expect("the rendered PNG").to_rgb8()
}

#[test]
fn s_exports_the_render_without_ui_and_never_overwrites() {
    let mut session = Session::start(&[]);
    let state = session.state();
    let folder = PathBuf::from(
        state["export"]["folder"]
            .as_str()
            .expect("an export folder"),
    );
    assert!(folder.is_absolute(), "{folder:?}");
    // A file already there keeps its name and contents.
    let taken = folder.join("heightray-valley513-001.png");
    std::fs::write(&taken, "not an export").expect("write a file");
    session.x.focus(session.window);
    // Two presses in quick succession: two files.
    session.x.key('s' as u32);
    session.x.key('s' as u32);
    let done = session.viewer.wait_for("two exports", |s| {
        s["export"]["saved"] == 2 && s["export"]["running"] == 0
    });
    assert_eq!(done["error"], Value::Null);
    assert_eq!(
        std::fs::read_to_string(&taken).ok().as_deref(),
        Some("not an export")
    );
    let files: Vec<PathBuf> = ["002", "003"]
        .iter()
        .map(|n| folder.join(format!("heightray-valley513-{n}.png")))
        .collect();
    let last = PathBuf::from(done["export"]["last"].as_str().expect("the last export"));
    assert!(files.contains(&last), "{last:?} is not one of {files:?}");
    let images: Vec<image::RgbImage> = files
        .iter()
        .map(|f| image::open(f).expect("an exported PNG").to_rgb8())
        .collect();
    // At the render resolution (the view without the panel), not the window's size.
    let size = (
        num(&done, "/frame/width") as u32,
        num(&done, "/frame/height") as u32,
    );
    assert_eq!(images[0].dimensions(), size);
    assert!(size.0 < num(&done, "/window_size/0") as u32);
    assert_eq!(
        done["camera"], state["camera"],
        "the camera moved while exporting"
    );
    let reference = render(session.viewer.dir.path(), &scene_of(&done, size));
    for (file, image) in files.iter().zip(&images) {
        assert_same(file, image, &reference);
    }
}

pub(super) fn assert_same(file: &Path, image: &image::RgbImage, reference: &image::RgbImage) {
    assert_eq!(image.dimensions(), reference.dimensions(), "{file:?}");
    let differing = image
        .pixels()
        .zip(reference.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "{file:?} differs from `heightray render` of the same view in {differing} pixels"
    );
}

#[test]
fn an_export_at_a_chosen_size_is_rendered_anew_into_the_export_folder() {
    let mut session = Session::start(&["--export-size", "333x211", "--export-dir", "out/images"]);
    let state = session.state();
    let folder = PathBuf::from(
        state["export"]["folder"]
            .as_str()
            .expect("an export folder"),
    );
    assert_eq!(folder, session.viewer.path("out/images"));
    session.x.focus(session.window);
    session.x.key('s' as u32);
    let done = session.viewer.wait_for("the export", |s| {
        s["export"]["saved"] == 1 && s["export"]["running"] == 0
    });
    assert_eq!(done["error"], Value::Null);
    let file = folder.join("heightray-valley513-001.png");
    assert_eq!(done["export"]["last"].as_str(), file.to_str());
    let image = image::open(&file).expect("an exported PNG").to_rgb8();
    let reference = render(session.viewer.dir.path(), &scene_of(&done, (333, 211)));
    assert_same(&file, &image, &reference);
}

/// `heightray render` of a scene file (or a map alone), at `size` if given.
pub(super) fn render_file(scene: &Path, size: Option<&str>) -> image::RgbImage {
    let out = scene.with_extension("check.png");
    let mut command = Command::new(env!("CARGO_BIN_EXE_heightray"));
    command.arg("render").arg(scene).arg("-o").arg(&out);
    if let Some(size) = size {
        command.args(["--size", size]);
    }
    let status = command
        .stdout(std::process::Stdio::null())
        .status()
        .expect("run heightray render");
    assert!(status.success(), "heightray render failed on {scene:?}");
    image::open(&out).expect("the rendered PNG").to_rgb8()
}

/// Saves the scene and exports the view with S; returns the scene file, and checks that it
/// renders the exported image.
pub(super) fn save_and_export(session: &mut Session) -> PathBuf {
    let state = session.open_section("export_section", "save_scene");
    session.click(&state, "save_scene");
    let saved = session
        .viewer
        .wait_for("the scene saved", |s| s["export"]["scene"].is_string());
    assert_eq!(saved["error"], Value::Null);
    let scene = PathBuf::from(saved["export"]["scene"].as_str().expect("a scene path"));
    session.x.focus(session.window);
    session.x.key('s' as u32);
    let done = session.viewer.wait_for("the export", |s| {
        s["export"]["saved"] == 1 && s["export"]["running"] == 0
    });
    assert_eq!(done["error"], Value::Null);
    assert_eq!(done["camera"], saved["camera"], "the camera moved");
    let file = PathBuf::from(done["export"]["last"].as_str().expect("an export"));
    let exported = image::open(&file).expect("an exported PNG").to_rgb8();
    assert_same(&file, &exported, &render_file(&scene, None));
    scene
}

#[test]
fn a_saved_scene_renders_the_exported_image_and_renders_at_any_size() {
    let mut session = Session::start(&["--export-dir", "out"]);
    let scene = save_and_export(&mut session);
    let out = session.viewer.path("out");
    assert_eq!(scene, out.join("heightray-valley513-001.toml"));
    assert_eq!(
        render_file(&scene, Some("320x180")).dimensions(),
        (320, 180)
    );
}

#[test]
fn a_saved_scene_keeps_the_overlay_and_the_water() {
    let files = tempfile::tempdir().expect("a temporary directory");
    let overlay = files.path().join("ortho.png");
    image::RgbImage::from_fn(64, 64, |x, y| image::Rgb([x as u8 * 4, y as u8 * 4, 128]))
        .save(&overlay)
        .expect("the overlay written");
    let scene = files.path().join("draped.toml");
    let text = format!(
        "[heightmap]\npath = \"builtin:small49\"\nz_scale = 12.0\n\
         [overlay]\npath = {overlay:?}\nopacity = 0.7\n[water]\nlevel = 3.5\n"
    );
    std::fs::write(&scene, text).expect("the scene written");
    let mut session =
        Session::start(&[scene.to_str().expect("a UTF-8 path"), "--export-dir", "out"]);
    let saved = std::fs::read_to_string(save_and_export(&mut session)).expect("the saved scene");
    let overlay_keys = format!(
        "[overlay]\npath = {:?}\nopacity = 0.7\n",
        overlay.display().to_string()
    );
    assert!(saved.contains(&overlay_keys), "{saved}");
    assert!(
        saved.contains("[water]\nlevel = 3.5\ncolour = \"#1e4d6b\""),
        "{saved}"
    );
}

#[test]
fn a_saved_scene_keeps_the_base() {
    let files = tempfile::tempdir().expect("a temporary directory");
    let scene = files.path().join("based.toml");
    let text = "[heightmap]\npath = \"builtin:small49\"\nz_scale = 12.0\n\
                [shading]\nbase = true\nbase_depth = 3.0\n";
    std::fs::write(&scene, text).expect("the scene written");
    let mut session =
        Session::start(&[scene.to_str().expect("a UTF-8 path"), "--export-dir", "out"]);
    // (The export, walls and all, is what `render` makes of the saved scene.)
    let saved = std::fs::read_to_string(save_and_export(&mut session)).expect("the saved scene");
    assert!(saved.contains("base = true\nbase_depth = 3.0\n"), "{saved}");
}

#[test]
fn a_saved_scene_keeps_the_annotations_and_the_places_exports_draw() {
    let files = tempfile::tempdir().expect("a temporary directory");
    let places = files.path().join("places.geojson");
    let geojson = r#"{"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"name": "Middle"},
         "geometry": {"type": "Point", "coordinates": [24.0, 24.0]}},
        {"type": "Feature", "properties": {},
         "geometry": {"type": "LineString", "coordinates": [[5.0, 5.0], [40.0, 30.0]]}}]}"#;
    std::fs::write(&places, geojson).expect("the places written");
    let scene = files.path().join("annotated.toml");
    let text = "[heightmap]\npath = \"builtin:small49\"\nz_scale = 12.0\n\
                [annotations]\nscale_bar = true\nnorth_arrow = true\ntitle = \"A \\\"quoted\\\" hill\"\n\
                [[vector]]\npath = \"places.geojson\"\ncoordinates = \"grid\"\ncolour = \"#20a040\"\n";
    std::fs::write(&scene, text).expect("the scene written");
    let mut session =
        Session::start(&[scene.to_str().expect("a UTF-8 path"), "--export-dir", "out"]);
    // (The export draws the marks and places; `render` of the saved scene must draw the same.)
    let saved = std::fs::read_to_string(save_and_export(&mut session)).expect("the saved scene");
    assert!(
        saved.contains("[annotations]\nscale_bar = true\nnorth_arrow = true\nlegend = false\n"),
        "{saved}"
    );
    assert!(
        saved.contains("title = \"A \\\"quoted\\\" hill\"\n"),
        "{saved}"
    );
    let vector = format!(
        "[[vector]]\npath = {:?}\ncoordinates = \"grid\"\ncolour = \"#20a040\"\nlift = 0.5\n",
        places.display().to_string()
    );
    assert!(saved.contains(&vector), "{saved}");
}

#[test]
fn render_of_a_map_alone_is_what_the_viewer_shows_on_opening_it() {
    // A georeferenced DEM: a 30 m UTM grid with a wall steeper than the default sun, so that
    // shadows show (the viewer opens it at true scale, shadows on).
    let files = tempfile::tempdir().expect("a temporary directory");
    let map = files.path().join("wall.asc");
    let rows: Vec<String> = (0..65)
        .map(|r| {
            (0..65)
                .map(|c| {
                    let x = (c as f64 - 32.0) / 3.0;
                    format!("{:.2}", 300.0 + 1500.0 * (-x * x).exp() + r as f64)
                })
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    let text = format!(
        "ncols 65\nnrows 65\nxllcorner 500000\nyllcorner 4000000\ncellsize 30\n{}\n",
        rows.join("\n")
    );
    std::fs::write(&map, text).expect("the map written");
    let mut session = Session::start(&[map.to_str().expect("a UTF-8 path"), "--export-dir", "out"]);
    session.x.focus(session.window);
    session.x.key('s' as u32);
    let done = session.viewer.wait_for("the export", |s| {
        s["export"]["saved"] == 1 && s["export"]["running"] == 0
    });
    assert_eq!(done["error"], Value::Null);
    assert_eq!(
        done["shadows"],
        Value::Bool(true),
        "the viewer opens with shadows"
    );
    let file = PathBuf::from(done["export"]["last"].as_str().expect("an export"));
    let exported = image::open(&file).expect("an exported PNG").to_rgb8();
    let (w, h) = exported.dimensions();
    let size = format!("{w}x{h}");
    let rendered = render_file(&map, Some(&size));
    assert_same(&file, &exported, &rendered);
    // The map casts shadows: the same view without them differs.
    let scene = files.path().join("no_shadows.toml");
    std::fs::write(
        &scene,
        "[heightmap]\npath = \"wall.asc\"\n[effects]\nshadows = false\n",
    )
    .expect("the scene written");
    let unshadowed = render_file(&scene, Some(&size));
    assert_ne!(
        unshadowed, rendered,
        "no shadow on the map: the test shows nothing"
    );
}

#[test]
fn a_scene_set_by_local_time_is_saved_with_its_time_and_zone() {
    let files = tempfile::tempdir().expect("a temporary directory");
    let scene = files.path().join("morning.toml");
    // 09:30 in Oslo on 21 June is 07:30 UTC (summer time, UTC+2).
    let text = "[heightmap]\npath = \"builtin:small49\"\nz_scale = 12.0\n\
                [sun]\ntime = \"2026-06-21T09:30:00\"\nzone = \"Europe/Oslo\"\nlat = 59.91\nlon = 10.75\n";
    std::fs::write(&scene, text).expect("the scene written");
    let mut session =
        Session::start(&[scene.to_str().expect("a UTF-8 path"), "--export-dir", "out"]);
    let state = session.state();
    assert_eq!(state["sun"]["clock"], "2026-06-21T09:30:00");
    // The same instant given in UTC places the same sun.
    let utc = files.path().join("utc.toml");
    std::fs::write(
        &utc,
        "[heightmap]\npath = \"builtin:small49\"\nz_scale = 12.0\n\
         [sun]\ntime = \"2026-06-21T07:30:00Z\"\nlat = 59.91\nlon = 10.75\n",
    )
    .expect("the scene written");
    let saved = std::fs::read_to_string(save_and_export(&mut session)).expect("the saved scene");
    assert!(
        saved.contains(
            "time = \"2026-06-21T09:30:00\"\nzone = \"Europe/Oslo\"\nlat = 59.91\nlon = 10.75\n"
        ),
        "{saved}"
    );
    let by_utc = heightray::render::Scene::load(&utc).expect("the UTC scene");
    let by_local = heightray::render::Scene::load(&scene).expect("the local scene");
    assert_eq!(by_utc.lighting.sun, by_local.lighting.sun);
}
