//! The Traversal panel's accuracy tools: measuring every arithmetic on the view, and
//! comparing the frame on screen with its exact render.

use super::app::{artifacts, num, widget};
use super::Session;
use serde_json::Value;
use std::path::Path;
use std::process::Command;

/// Every arithmetic the measurement renders.
const ARITHS: [&str; 8] = [
    "exact",
    "f32",
    "f64",
    "rational:16",
    "rational:256",
    "rational:4096",
    "rational:65536",
    "rational:16777216",
];

/// Opens the Traversal section and scrolls the panel until `name` is on screen.
fn reveal(session: &mut Session, name: &str) -> Value {
    let state = session.state();
    session.click(&state, "traversal_section");
    let state = session
        .viewer
        .wait_for("the Traversal section to open", |s| {
            s["widgets"][name].is_array()
        });
    // Let the section finish opening: what it holds is clipped and not clickable until then.
    std::thread::sleep(std::time::Duration::from_millis(600));
    let height = num(&state, "/window_size/1");
    let [x0, _, x1, _] = widget(&state, "traversal_section");
    session
        .x
        .move_to(session.screen(((x0 + x1) / 2.0, height / 2.0)));
    std::thread::sleep(std::time::Duration::from_millis(100));
    for _ in 0..40 {
        let [_, y0, _, y1] = widget(&session.state(), name);
        if y0 >= 0.0 && y1 <= height - 4.0 {
            break;
        }
        // Wheel down (button 5) or up (4), a notch at a time.
        let button = if y1 > height - 4.0 { 5 } else { 4 };
        session.x.press(button);
        session.x.release(button);
        std::thread::sleep(std::time::Duration::from_millis(60));
    }
    // Scrolling is animated: wait until the widget stays put.
    let mut state = session.state();
    loop {
        std::thread::sleep(std::time::Duration::from_millis(250));
        let now = session.state();
        if now["widgets"][name] == state["widgets"][name] {
            break;
        }
        state = now;
    }
    let [_, y0, _, y1] = widget(&state, name);
    assert!(y0 >= 0.0 && y1 <= height, "cannot scroll {name} into view");
    state
}

fn measure_state(s: &Value) -> &str {
    s["accuracy"]["measure"]["state"].as_str().unwrap_or("")
}

#[test]
fn measuring_fills_a_table_of_every_arithmetic_while_the_window_answers() {
    let mut session = Session::start(&[]);
    let state = reveal(&mut session, "measure_button");
    session.click(&state, "measure_button");
    let running = session.viewer.wait_for("the measurement to start", |s| {
        measure_state(s) == "running"
    });

    // A second click cancels it, a third starts it again.
    session.click(&running, "measure_button");
    session.viewer.wait_for("the second click to cancel", |s| {
        measure_state(s) == "cancelled"
    });
    session.click(&running, "measure_button");
    let running = session
        .viewer
        .wait_for("the measurement to start again", |s| {
            measure_state(s) == "running"
        });

    // The window answers keys while it measures: F1 opens the help.
    let frames = num(&running, "/frames_presented");
    session.x.focus(session.window);
    session.x.key(0xffbe); // F1
    let answered = session
        .viewer
        .wait_for("F1 to open the help", |s| s["help_open"] == true);
    assert_eq!(
        measure_state(&answered),
        "running",
        "the measurement ended before the window answered F1"
    );
    assert!(num(&answered, "/frames_presented") > frames);

    let done = session
        .viewer
        .wait_for("the measurement to finish", |s| measure_state(s) == "done");
    session.capture("measured.png");
    let rows = done["accuracy"]["measure"]["rows"]
        .as_array()
        .expect("rows");
    let names: Vec<&str> = rows.iter().filter_map(|r| r["arith"].as_str()).collect();
    assert_eq!(names, ARITHS, "one row per arithmetic");
    let size = &done["accuracy"]["measure"]["size"];
    let pixels = num(size, "/0") * num(size, "/1");
    assert!((1000.0..=2304.0).contains(&pixels), "measured at {size}");
    for row in rows {
        assert!(num(row, "/ns_per_ray") > 0.0, "{row}");
        assert_eq!(num(row, "/pixels"), pixels, "{row}");
    }
    let differing = |arith: &str| {
        let row = rows.iter().find(|r| r["arith"] == arith).expect("row");
        num(row, "/differing")
    };
    assert_eq!(differing("exact"), 0.0);
    assert!(differing("f64") <= pixels / 100.0, "f64 is not near exact");
    eprintln!(
        "measured the default view at {size}: {}",
        serde_json::to_string(rows).unwrap_or_default()
    );
}

/// A scene of the built-in terrain seen from the default orbit, in `arith`.
fn write_scene(path: &Path, arith: &str, size: (u64, u64), sun: [f64; 3]) {
    let text = format!(
        "[heightmap]\npath = \"builtin:valley513\"\nz_scale = 120.0\n\
         [camera]\norbit = {{ target = [256.0, 256.0, 60.0], yaw_deg = -130.0, pitch_deg = 35.0, \
         distance = 700.0 }}\nfov_y_deg = 45.0\nwidth = {}\nheight = {}\n\
         [sun]\ndirection = [{:?}, {:?}, {:?}]\n[effects]\nshadows = true\n\
         [render]\nmethod = \"runs\"\narith = \"{arith}\"\n",
        size.0, size.1, sun[0], sun[1], sun[2]
    );
    std::fs::write(path, text).expect("write a scene");
}

/// Pixels that differ between the CLI's renders of `scene` in `arith` and in exact.
fn cli_differences(scene: &Path, arith: &str) -> u64 {
    let render = |arith: &str| {
        let out = scene.with_file_name(format!("cli-{arith}.png"));
        let status = Command::new(env!("CARGO_BIN_EXE_heightray"))
            .arg("render")
            .arg(scene)
            .arg("-o")
            .arg(&out)
            .args(["--arith", arith])
            .stdout(std::process::Stdio::null())
            .status()
            .expect("run heightray render");
        assert!(status.success(), "heightray render --arith {arith} failed");
        image::open(&out).expect("a PNG").to_rgb8()
    };
    let (shown, exact) = (render(arith), render("exact"));
    assert_eq!(shown.dimensions(), exact.dimensions());
    shown
        .pixels()
        .zip(exact.pixels())
        .filter(|(a, b)| a != b)
        .count() as u64
}

/// Opens the viewer on the built-in terrain in `arith`, switches the comparison on, checks
/// its count against the CLI's renders of the same view, and returns the running viewer and
/// its state.
fn compare(arith: &str) -> (Session, Value) {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let scene = dir.path().join(format!("{arith}.toml"));
    write_scene(&scene, arith, (64, 64), [0.4, 0.3, 0.8]);
    let scene_arg = scene.to_string_lossy().into_owned();
    let mut session = Session::start(&[&scene_arg, "--render-scale", "0.5"]);
    let state = reveal(&mut session, "compare_toggle");
    assert_eq!(state["arith"], arith);
    session.click(&state, "compare_toggle");
    let compared = session.viewer.wait_for("the comparison with exact", |s| {
        s["accuracy"]["compare"]["differing"].is_u64()
    });
    let differing = num(&compared, "/accuracy/compare/differing") as u64;
    let pixels = num(&compared, "/accuracy/compare/pixels") as u64;
    let size = (
        num(&compared, "/frame/width") as u64,
        num(&compared, "/frame/height") as u64,
    );
    assert_eq!(pixels, size.0 * size.1);

    // The same view through the command line: the frame's size and the window's sun.
    let sun = [0, 1, 2].map(|k| num(&compared, &format!("/sun/direction/{k}")));
    let cli_scene = dir.path().join("same-view.toml");
    write_scene(&cli_scene, arith, size, sun);
    let expected = cli_differences(&cli_scene, arith);
    eprintln!("{arith}: {differing} of {pixels} pixels differ from exact (the CLI: {expected})");
    assert_eq!(
        differing, expected,
        "the viewer and `heightray render` disagree on the pixels that differ"
    );
    (session, compared)
}

/// Window pixels of the view in the overlay's magenta.
fn magenta_pixels(session: &Session, state: &Value, name: &str) -> usize {
    let shot = session.capture(name);
    shot.region(session.view(state))
        .iter()
        .filter(|&&p| p == [255, 0, 255])
        .count()
}

#[test]
fn comparing_f32_with_exact_counts_and_shows_what_the_cli_finds() {
    let (mut session, compared) = compare("f32");
    let differing = num(&compared, "/accuracy/compare/differing") as usize;
    assert!(differing > 0, "f32 should differ somewhere in this view");
    // Each frame pixel covers about 2 x 2 window pixels at render scale 0.5.
    let magenta = magenta_pixels(&session, &compared, "compare-f32.png");
    assert!(
        magenta >= differing,
        "{magenta} magenta window pixels for {differing} differing frame pixels (see {:?})",
        artifacts()
    );

    // Moving the camera drops the overlay; the new view is compared once it has converged.
    let generation = num(&compared, "/accuracy/compare/generation");
    let (cx, cy) = session.view_centre(&compared);
    session.x.drag(
        session.screen((cx, cy)),
        session.screen((cx + 60.0, cy)),
        1,
        6,
    );
    let again = session
        .viewer
        .wait_for("the comparison of the new view", |s| {
            s["accuracy"]["compare"]["generation"]
                .as_f64()
                .is_some_and(|g| g != generation)
        });
    assert!(again["accuracy"]["compare"]["differing"].is_u64());
}

#[test]
fn comparing_f64_with_exact_finds_few_differences() {
    let (session, compared) = compare("f64");
    let differing = num(&compared, "/accuracy/compare/differing");
    let pixels = num(&compared, "/accuracy/compare/pixels");
    assert!(
        differing <= pixels / 1000.0,
        "{differing} of {pixels} pixels differ in f64"
    );
    session.capture("compare-f64.png");
}
