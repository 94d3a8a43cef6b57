//! Recording a flythrough: K adds the view as a key, *Save scene* writes the keys, and
//! `heightray render --frames` flies them: the last frame is the view the scene was saved at,
//! pixel for pixel as the scene's still.

use super::Session;
use std::process::Command;

/// The Up arrow's keysym.
const UP: u32 = 0xff52;

#[test]
fn keys_recorded_in_the_viewer_render_as_frames() {
    let mut session = Session::start(&["--export-dir", "out"]);
    session.x.focus(session.window);
    session.x.key('k' as u32);
    session
        .viewer
        .wait_for("a key", |s| s["flythrough"]["keys"] == 1);
    for _ in 0..4 {
        session.x.key(UP);
    }
    session.x.key('k' as u32);
    session
        .viewer
        .wait_for("two keys", |s| s["flythrough"]["keys"] == 2);
    let state = session.open_section("export_section", "save_scene");
    session.click(&state, "save_scene");
    let saved = session
        .viewer
        .wait_for("the scene saved", |s| s["export"]["scene"].is_string());
    let scene = std::path::PathBuf::from(saved["export"]["scene"].as_str().expect("a path"));
    let text = std::fs::read_to_string(&scene).expect("the saved scene");
    assert_eq!(text.matches("[[animation.key]]").count(), 2, "{text}");
    assert!(text.contains("time_s = 2.0"), "{text}");

    // Two seconds at 30 frames a second: frames 0 to 60; the last is the saved view.
    let run = |args: &[&str]| {
        let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
            .arg("render")
            .arg(&scene)
            .args(args)
            .args(["--size", "96x64"])
            .output()
            .expect("run heightray render");
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
    };
    let frames = scene.with_extension("frames");
    run(&[
        "--frames",
        "0..=60/30",
        "-o",
        frames.to_str().expect("UTF-8"),
    ]);
    let still = scene.with_extension("still.png");
    run(&["-o", still.to_str().expect("UTF-8")]);
    let last = image::open(frames.join("frame-00060.png"))
        .expect("frame 60")
        .to_rgb8();
    assert_eq!(last, image::open(&still).expect("the still").to_rgb8());
    let first = image::open(frames.join("frame-00000.png"))
        .expect("frame 0")
        .to_rgb8();
    assert_ne!(first, last, "the camera moved between the keys");
}
