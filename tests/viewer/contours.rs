//! Contour lines in the viewer: a scene's `[overlay] contours` drawn in the view and its
//! exports as `heightray render` draws them, kept by Save scene, turned off by the panel's
//! checkbox; an interval typed in the panel that is not a height above 0 is refused.

use super::app::num;
use super::export::{assert_same, render_file, save_and_export};
use super::Session;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// A scene of the built-in hill from a fixed orbit, with `overlay` added.
fn hill_scene(dir: &Path, name: &str, overlay: &str) -> PathBuf {
    let scene = dir.join(name);
    let text = format!(
        "[heightmap]\npath = \"builtin:small49\"\nz_scale = 12.0\n\
         [camera]\norbit = {{ target = [24.0, 24.0, 3.0], yaw_deg = -130.0, pitch_deg = 35.0, \
         distance = 70.0 }}\nfov_y_deg = 45.0\nwidth = 640\nheight = 360\n{overlay}"
    );
    std::fs::write(&scene, text).expect("the scene written");
    scene
}

/// The exported image the state names last.
fn last_export(state: &Value) -> (PathBuf, image::RgbImage) {
    let file = PathBuf::from(state["export"]["last"].as_str().expect("an export"));
    let image = image::open(&file).expect("an exported PNG").to_rgb8();
    (file, image)
}

#[test]
fn a_scenes_contours_are_exported_as_render_draws_them_and_kept_by_save_scene() {
    let files = tempfile::tempdir().expect("a temporary directory");
    let lines = "[overlay]\ncontours = 1.5\nindex_every = 4\n";
    let scene = hill_scene(files.path(), "contoured.toml", lines);
    let plain = hill_scene(files.path(), "plain.toml", "");
    let mut session =
        Session::start(&[scene.to_str().expect("a UTF-8 path"), "--export-dir", "out"]);
    let state = session.state();
    assert_eq!(state["contours"]["on"], Value::Bool(true), "{state}");
    assert_eq!(num(&state, "/contours/interval"), 1.5);
    assert_eq!(num(&state, "/contours/index_every"), 4.0);

    // Saved, then exported: `render` of the saved scene makes the export (checked inside).
    let saved = save_and_export(&mut session);
    let text = std::fs::read_to_string(&saved).expect("the saved scene");
    assert!(
        text.contains("\n[overlay]\n") && text.contains(lines),
        "{text}"
    );
    let (file, with_lines) = last_export(&session.state());
    let (w, h) = with_lines.dimensions();
    let size = format!("{w}x{h}");
    // The scene as written gives the same pixels.
    assert_same(&file, &with_lines, &render_file(&scene, Some(&size)));

    // The panel's checkbox turns them off; the next export is the scene without them. (The
    // Export section closes first: open, it pushes the checkbox below the window's edge.)
    let state = session.state();
    session.click(&state, "export_section");
    session.viewer.wait_for("the Export section to close", |s| {
        s["widgets"]["save_scene"].is_null()
    });
    std::thread::sleep(std::time::Duration::from_millis(600));
    let state = session.open_section("heightmap_section", "contours");
    session.click(&state, "contours");
    session.viewer.wait_for("the contours off", |s| {
        s["contours"]["on"] == Value::Bool(false)
    });
    session.x.focus(session.window);
    session.x.key('s' as u32);
    let done = session.viewer.wait_for("the second export", |s| {
        s["export"]["saved"] == 2 && s["export"]["running"] == 0
    });
    assert_eq!(done["error"], Value::Null);
    let (file, without) = last_export(&done);
    assert_same(&file, &without, &render_file(&plain, Some(&size)));
    // Both exports match `render` of their scene, which differ only in the contour keys:
    // pixels that differ here are the lines, so the exports do draw them.
    let differing = with_lines
        .pixels()
        .zip(without.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(differing > 0, "the contours changed no pixel");
    println!("the contour lines cover {differing} of {} pixels", w * h);
}

/// Types `text` into the contour interval field, after deleting what it holds, and Return.
fn type_interval(session: &mut Session, text: &str) {
    let state = session.state();
    session.click(&state, "contour_interval");
    session.x.focus(session.window);
    session.x.key(0xff57); // End
    for _ in 0..12 {
        session.x.key(0xff08); // BackSpace
    }
    for c in text.chars() {
        session.x.key(c as u32);
    }
    session.x.key(0xff0d); // Return
}

#[test]
fn an_interval_typed_that_is_not_a_height_above_0_is_refused_with_a_message() {
    let files = tempfile::tempdir().expect("a temporary directory");
    let scene = hill_scene(
        files.path(),
        "contoured.toml",
        "[overlay]\ncontours = 1.5\n",
    );
    let mut session = Session::start(&[scene.to_str().expect("a UTF-8 path")]);
    session.open_section("heightmap_section", "contour_interval");
    for (typed, said) in [("-5", "not -5"), ("inf", "not inf"), ("0", "not 0")] {
        type_interval(&mut session, typed);
        let refused = session.viewer.wait_for("the message", |s| {
            s["error"].as_str().is_some_and(|e| e.contains(said))
        });
        let error = refused["error"].as_str().unwrap_or_default();
        assert!(error.contains("contour interval"), "{error}");
        assert_eq!(
            num(&refused, "/contours/interval"),
            1.5,
            "{typed} was taken"
        );
    }
    // A height above 0 is taken, and rendered.
    let before = num(&session.state(), "/submitted_generation");
    type_interval(&mut session, "2.5");
    let taken = session
        .viewer
        .wait_for("the new interval", |s| num(s, "/contours/interval") == 2.5);
    assert_eq!(taken["contours"]["on"], Value::Bool(true));
    session.viewer.wait_for("a render with it", |s| {
        num(s, "/submitted_generation") > before
    });
}

#[test]
fn a_dropped_map_keeps_the_lines_at_a_round_interval_for_its_relief() {
    let files = tempfile::tempdir().expect("a temporary directory");
    let lines = "[overlay]\ncontours = 1.5\nindex_every = 4\n";
    let scene = hill_scene(files.path(), "contoured.toml", lines);
    let mut session =
        Session::start(&[scene.to_str().expect("a UTF-8 path"), "--export-dir", "out"]);
    let state = session.state();
    let hill = session.viewer.path("hill.pgm");
    super::write_hill(&hill);
    let at = session.screen(session.view_centre(&state));
    assert_eq!(
        super::xdnd::drag_file(&session.x, &hill, at, false),
        super::xdnd::Outcome::Accepted
    );
    let converged = num(&state, "/converged_frames");
    let loaded = session.viewer.wait_for("the dropped map", |s| {
        s["terrain"]["name"] == "hill.pgm" && num(s, "/converged_frames") > converged
    });
    // The hill rises 16 grid units (a quarter of its 64 samples): 16 / 20 is 0.8, and the
    // round interval below it is 0.5. The lines stay on, with their index lines.
    assert_eq!(num(&loaded, "/terrain/z_scale"), 16.0);
    assert_eq!(loaded["contours"]["on"], Value::Bool(true));
    assert_eq!(num(&loaded, "/contours/interval"), 0.5);
    assert_eq!(num(&loaded, "/contours/index_every"), 4.0);
    // The saved scene says so, and renders the export.
    let saved = std::fs::read_to_string(save_and_export(&mut session)).expect("the scene");
    assert!(
        saved.contains("[overlay]\ncontours = 0.5\nindex_every = 4\n"),
        "{saved}"
    );
}
