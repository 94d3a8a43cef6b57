//! The viewer under Xvfb, driven as a user would: the real window, event loop and drawing,
//! with pointer and keys from XTEST and files dropped through the XDND protocol by a drag
//! source written here. The viewer's `--report-state` JSON says what it did.
//!
//! Each test starts its own Xvfb on a free display; they run one at a time (the machine has
//! two cores and each viewer uses both). Without Xvfb they fail and say what to install.

mod accuracy;
mod app;
mod contours;
mod decoding;
mod export;
mod failed_loads;
mod flythrough;
mod fog;
mod georeferenced;
mod huge_window;
mod navigation;
mod panel;
mod special_paths;
mod x11;
mod xdnd;

use app::{artifacts, num, widget, Viewer};
use serde_json::Value;
use std::collections::HashSet;
use std::sync::{Mutex, MutexGuard};
use x11::{Shot, Xvfb, X};

static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// A display with a viewer on it that has shown a fully refined frame. Fields drop in
/// order: the viewer before its display.
struct Session {
    viewer: Viewer,
    x: X,
    _xvfb: Xvfb,
    window: u32,
    origin: (i16, i16),
    _turn: MutexGuard<'static, ()>,
}

impl Session {
    fn start(extra: &[&str]) -> Session {
        let turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
        let xvfb = Xvfb::start();
        let mut viewer = Viewer::start(&xvfb.display, extra);
        let state = viewer.wait_converged(0);
        let window = num(&state, "/x11_window") as u32;
        let x = X::connect(&xvfb.display);
        let origin = x.origin(window);
        Session {
            viewer,
            x,
            _xvfb: xvfb,
            window,
            origin,
            _turn: turn,
        }
    }

    fn state(&self) -> Value {
        self.viewer.state().expect("a state report")
    }

    /// A point of the window (window pixels) in screen coordinates.
    fn screen(&self, (x, y): (f64, f64)) -> (i16, i16) {
        (self.origin.0 + x as i16, self.origin.1 + y as i16)
    }

    /// The view's rectangle: x0, y0, x1, y1 in window pixels.
    fn view(&self, state: &Value) -> (usize, usize, usize, usize) {
        let r = |k: usize| num(state, &format!("/view_rect/{k}")) as usize;
        (r(0), r(1), r(0) + r(2), r(1) + r(3))
    }

    fn view_centre(&self, state: &Value) -> (f64, f64) {
        let (x0, y0, x1, y1) = self.view(state);
        ((x0 + x1) as f64 / 2.0, (y0 + y1) as f64 / 2.0)
    }

    /// Clicks on a named widget's middle, as a hand does: egui decides from the previous
    /// frame's hover whether a press is its own, so the press waits until a frame has seen the
    /// pointer.
    fn click(&mut self, state: &Value, name: &str) {
        let [x0, y0, x1, y1] = widget(state, name);
        let (x, y) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
        // Two moves: the pointer may already rest on the spot, and then no motion would arrive.
        self.x.move_to(self.screen((x - 2.0, y)));
        std::thread::sleep(std::time::Duration::from_millis(30));
        let frames = num(&self.state(), "/frames_presented");
        self.x.move_to(self.screen((x, y)));
        self.viewer
            .wait_for("a frame after the pointer moved", |s| {
                num(s, "/frames_presented") > frames
            });
        std::thread::sleep(std::time::Duration::from_millis(100));
        self.x.press(1);
        std::thread::sleep(std::time::Duration::from_millis(40));
        self.x.release(1);
    }

    /// Opens a closed panel section by its header and returns the state once `inside` (a
    /// widget the section holds) can be clicked.
    fn open_section(&mut self, header: &str, inside: &str) -> Value {
        let state = self.state();
        self.click(&state, header);
        self.viewer.wait_for(&format!("the {header} to open"), |s| {
            s["widgets"][inside].is_array()
        });
        // Let the section finish opening: what it holds is not clickable until then.
        std::thread::sleep(std::time::Duration::from_millis(600));
        self.state()
    }

    fn capture(&self, name: &str) -> Shot {
        let shot = self.x.capture(self.window);
        shot.save(&artifacts().join(name));
        shot
    }
}

/// Share of pixels coloured like terrain (green, brown, grey: red or green above blue),
/// where the sky and the egui panel are bluish or grey.
fn terrain_share(pixels: &[[u8; 3]]) -> f64 {
    let terrain = pixels
        .iter()
        .filter(|[r, g, b]| i32::from(*r.max(g)) > i32::from(*b) + 6)
        .count();
    terrain as f64 / pixels.len().max(1) as f64
}

fn distinct_colours(pixels: &[[u8; 3]]) -> usize {
    pixels
        .iter()
        .map(|[r, g, b]| (r >> 3, g >> 3, b >> 3))
        .collect::<HashSet<_>>()
        .len()
}

fn luminance([r, g, b]: [u8; 3]) -> f64 {
    0.3 * f64::from(r) + 0.59 * f64::from(g) + 0.11 * f64::from(b)
}

#[test]
fn it_starts_and_the_window_shows_terrain_beside_the_panel() {
    let session = Session::start(&[]);
    let state = session.state();
    let shot = session.capture("start.png");
    let view = session.view(&state);
    assert_eq!(
        (view.0, view.1),
        (0, 0),
        "the view fills the left of the window"
    );
    assert!(
        view.2 > shot.width / 2,
        "the view is most of the window: {view:?}"
    );
    let terrain = shot.region(view);
    let share = terrain_share(&terrain);
    assert!(
        share > 0.2,
        "terrain covers only {share:.2} of the view (see {:?})",
        artifacts()
    );
    assert!(distinct_colours(&terrain) > 200, "the view looks flat");
    let panel = shot.region((view.2 + 4, 0, shot.width, shot.height));
    assert!(!panel.is_empty(), "no panel beside the view");
    let mean = panel.iter().map(|&p| luminance(p)).sum::<f64>() / panel.len() as f64;
    let text = panel.iter().filter(|&&p| luminance(p) > 150.0).count() as f64 / panel.len() as f64;
    assert!(
        mean < 90.0,
        "the panel is not the dark egui panel (mean luminance {mean:.0})"
    );
    assert!(
        text > 0.004,
        "the panel shows no text ({text:.4} bright pixels)"
    );
    assert_eq!(state["terrain"]["name"], "valley513 (built-in)");
    assert_eq!(state["frame"]["complete"], true);
}

#[test]
fn exit_after_frames_saves_the_window_and_quits() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let xvfb = Xvfb::start();
    let mut viewer = Viewer::start(
        &xvfb.display,
        &["--exit-after-frames", "1", "--screenshot", "shot.png"],
    );
    let status = viewer.wait_exit();
    assert!(
        status.success(),
        "exit {status}; stderr:\n{}",
        viewer.stderr()
    );
    let image = image::open(viewer.path("shot.png"))
        .expect("the screenshot is a PNG")
        .to_rgb8();
    assert_eq!(image.dimensions(), (1280, 720));
    let left: Vec<[u8; 3]> = image
        .enumerate_pixels()
        .filter(|(x, _, _)| *x < 640)
        .map(|(_, _, p)| p.0)
        .collect();
    assert!(
        terrain_share(&left) > 0.2,
        "the saved window shows no terrain"
    );
}

#[test]
fn dragging_the_terrain_orbits_and_dragging_a_slider_does_not() {
    let mut session = Session::start(&[]);
    let before = session.state();
    let shot_before = session.capture("before-drag.png");
    let (cx, cy) = session.view_centre(&before);
    let (from, to) = (
        session.screen((cx - 100.0, cy)),
        session.screen((cx + 50.0, cy + 40.0)),
    );
    session.x.drag(from, to, 1, 25);
    let yaw_before = num(&before, "/camera/yaw_deg");
    let pitch_before = num(&before, "/camera/pitch_deg");
    let converged = num(&before, "/converged_frames") as u64;
    // 150 pixels right turn the terrain right (yaw down), 40 down lift the eye. The viewer
    // may show a frame before the last motion events arrive, so it is waited on until the
    // whole drag has turned it (or the wait times out).
    let near = |s: &Value, key: &str, from: f64, by: f64, within: f64| {
        s["camera"][key]
            .as_f64()
            .is_some_and(|v| (v - from - by).abs() < within)
    };
    session.viewer.wait_for("the drag to turn the camera", |s| {
        near(s, "yaw_deg", yaw_before, -45.0, 10.0)
            && near(s, "pitch_deg", pitch_before, 12.0, 5.0)
            && s["converged_frames"].as_u64() > Some(converged)
    });
    let after = session.viewer.wait_converged(converged);
    let shot_after = session.capture("after-drag.png");
    let view = session.view(&after);
    let changed = shot_before
        .region(view)
        .iter()
        .zip(shot_after.region(view))
        .filter(|(a, b)| **a != *b)
        .count();
    assert!(
        changed > (view.2 - view.0) * (view.3 - view.1) / 5,
        "the view hardly changed"
    );
    report_latency(&after);

    // The sun's azimuth slider: the drag moves the slider, never the camera.
    let [x0, y0, _, y1] = widget(&after, "sun_azimuth");
    let y = (y0 + y1) / 2.0;
    session.x.drag(
        session.screen((x0 + 12.0, y)),
        session.screen((x0 + 90.0, y)),
        1,
        10,
    );
    let azimuth = num(&after, "/sun/azimuth_deg");
    let moved = session.viewer.wait_for("the slider to move the sun", |s| {
        s["sun"]["azimuth_deg"].as_f64() != Some(azimuth)
    });
    assert_eq!(
        moved["camera"], after["camera"],
        "a slider drag moved the camera"
    );
}

/// Prints the input-to-first-frame latency the viewer measured during the drag.
fn report_latency(state: &Value) {
    let latency = &state["latency_ms"];
    let count = latency["count"].as_u64().unwrap_or(0);
    assert!(count > 0, "no input latency was measured: {latency}");
    let median = num(state, "/latency_ms/median");
    let full = num(state, "/frame/elapsed_ms");
    eprintln!(
        "input to first frame over {count} moves: median {median:.1} ms, p95 {:.1} ms, max {:.1} ms; \
         a full frame of {}x{} takes {full:.0} ms",
        num(state, "/latency_ms/p95"),
        num(state, "/latency_ms/max"),
        state["frame"]["width"],
        state["frame"]["height"]
    );
    // The window shows a coarse pass long before a full frame could land.
    assert!(
        median < 250.0 && median < full,
        "median latency {median} ms"
    );
}

/// A 64x40 height map with a round hill, as a plain PGM.
fn write_hill(path: &std::path::Path) {
    let mut text = String::from("P2\n64 40\n255\n");
    for r in 0..40 {
        let row: Vec<String> = (0..64)
            .map(|c| {
                let d = ((c as f64 - 32.0).powi(2) + (r as f64 - 20.0).powi(2)).sqrt();
                ((255.0 * (1.0 - d / 24.0)).clamp(0.0, 255.0) as u8).to_string()
            })
            .collect();
        text += &(row.join(" ") + "\n");
    }
    std::fs::write(path, text).expect("write the height map");
}

#[test]
fn dropping_a_height_map_loads_it_and_a_non_image_keeps_it_with_an_error() {
    let mut session = Session::start(&[]);
    let state = session.state();
    let at = session.screen(session.view_centre(&state));
    let (hill, notes) = (
        session.viewer.path("hill.pgm"),
        session.viewer.path("notes.txt"),
    );
    write_hill(&hill);
    std::fs::write(&notes, "not a height map\n").expect("write notes");

    let converged = num(&state, "/converged_frames") as u64;
    assert_eq!(
        xdnd::drag_file(&session.x, &hill, at, false),
        xdnd::Outcome::Accepted
    );
    let loaded = session.viewer.wait_for("the dropped map to load", |s| {
        s["terrain"]["name"] == "hill.pgm" && s["converged_frames"].as_u64() > Some(converged)
    });
    assert_eq!(
        (
            loaded["terrain"]["width"].as_u64(),
            loaded["terrain"]["height"].as_u64()
        ),
        (Some(64), Some(40))
    );
    // A plain image gets a quarter of its larger side as z scale, and the camera frames it.
    assert_eq!(loaded["terrain"]["z_scale"].as_f64(), Some(16.0));
    assert_eq!(loaded["camera"]["framed"], true);
    assert!((0.0..=63.0).contains(&num(&loaded, "/camera/target/0")));
    assert_eq!(loaded["error"], Value::Null);
    let shot = session.capture("dropped-hill.png");
    let view = session.view(&loaded);
    assert!(
        terrain_share(&shot.region(view)) > 0.05,
        "the hill is not on screen"
    );

    drop_a_non_image(&mut session, &notes, at, &loaded);
}

/// With "a drop opens: an overlay", a dropped image is draped over the map on screen, which
/// stays; a dropped non-image is refused with a message and the overlay stays.
#[test]
fn a_dropped_image_is_draped_when_drops_open_overlays() {
    let mut session = Session::start(&[]);
    let state = session.open_section("heightmap_section", "drop_overlay");
    session.click(&state, "drop_overlay");
    let state = session.state();
    let at = session.screen(session.view_centre(&state));
    let (ortho, notes) = (
        session.viewer.path("ortho.png"),
        session.viewer.path("notes.txt"),
    );
    image::RgbImage::from_fn(32, 32, |x, _| image::Rgb([x as u8 * 8, 0, 0]))
        .save(&ortho)
        .expect("write the overlay");
    std::fs::write(&notes, "not an image\n").expect("write notes");
    assert_eq!(
        xdnd::drag_file(&session.x, &ortho, at, false),
        xdnd::Outcome::Accepted
    );
    let ortho_name = ortho.display().to_string();
    let draped = session.viewer.wait_for("the overlay to be draped", |s| {
        s["terrain"]["overlay"] == ortho_name.as_str()
    });
    assert_eq!(draped["terrain"]["name"], state["terrain"]["name"]);
    assert_eq!(draped["error"], Value::Null);
    assert_eq!(
        xdnd::drag_file(&session.x, &notes, at, false),
        xdnd::Outcome::Accepted
    );
    let refused = session
        .viewer
        .wait_for("the error", |s| s["error"].is_string());
    let error = refused["error"].as_str().unwrap_or_default();
    assert!(error.contains("cannot be decoded"), "{error}");
    assert_eq!(refused["terrain"]["overlay"], ortho_name.as_str());
}

/// Drops a text file: the terrain stays and the window says why.
fn drop_a_non_image(
    session: &mut Session,
    notes: &std::path::Path,
    at: (i16, i16),
    loaded: &Value,
) {
    assert_eq!(
        xdnd::drag_file(&session.x, notes, at, false),
        xdnd::Outcome::Accepted
    );
    let refused = session
        .viewer
        .wait_for("the error message", |s| s["error"].is_string());
    let error = refused["error"].as_str().unwrap_or_default();
    assert!(
        error.contains("notes.txt") && error.contains("not a PNG, PGM or TIFF"),
        "{error}"
    );
    assert_eq!(
        refused["terrain"], loaded["terrain"],
        "the old terrain must stay"
    );
    let shot = session.capture("dropped-notes.png");
    let view = session.view(&refused);
    let banner = shot.region((view.0, view.1, view.2, view.1 + 60));
    let red = banner
        .iter()
        .filter(|[r, g, b]| *r > 90 && *g < 50 && *b < 50)
        .count();
    assert!(red > 500, "no error banner on screen");
}

#[test]
fn a_file_dragged_over_the_window_shows_the_drop_hint_until_it_leaves() {
    use std::sync::atomic::{AtomicBool, Ordering};
    let session = Session::start(&[]);
    let state = session.state();
    let at = session.screen(session.view_centre(&state));
    let file = session.viewer.path("hover.pgm");
    write_hill(&file);
    let seen = AtomicBool::new(false);
    let dragging = AtomicBool::new(true);
    let outcome = std::thread::scope(|scope| {
        scope.spawn(|| {
            while dragging.load(Ordering::SeqCst) {
                if session
                    .viewer
                    .state()
                    .is_some_and(|s| s["drop_hover"] == true)
                {
                    seen.store(true, Ordering::SeqCst);
                }
                std::thread::sleep(std::time::Duration::from_millis(10));
            }
        });
        let outcome = xdnd::drag_file(&session.x, &file, at, true);
        dragging.store(false, Ordering::SeqCst);
        outcome
    });
    assert!(matches!(outcome, xdnd::Outcome::NotAccepted(_)));
    assert!(seen.load(Ordering::SeqCst), "the drop hint never showed");
    let mut session = session;
    let left = session
        .viewer
        .wait_for("the hint to go", |s| s["drop_hover"] == false);
    assert_eq!(left["terrain"]["name"], "valley513 (built-in)");
}

#[test]
fn keys_hide_the_panels_and_reset_the_view() {
    let mut session = Session::start(&[]);
    let home = session.state();
    session.x.focus(session.window);
    session.x.key('h' as u32);
    let hidden = session
        .viewer
        .wait_for("H to hide the panels", |s| s["panels_visible"] == false);
    let full = num(&hidden, "/window_size/0");
    session.viewer.wait_for("the view to fill the window", |s| {
        num(s, "/view_rect/2") == full
    });
    let (cx, cy) = session.view_centre(&hidden);
    session.x.drag(
        session.screen((cx, cy)),
        session.screen((cx + 80.0, cy)),
        1,
        8,
    );
    session
        .viewer
        .wait_for("the drag", |s| s["camera"] != home["camera"]);
    // R frames the whole map from the start's direction, for the view's new shape.
    session.x.key('r' as u32);
    session.viewer.wait_for("R to reset the view", |s| {
        s["camera"]["framed"] == true
            && s["camera"]["yaw_deg"] == home["camera"]["yaw_deg"]
            && s["camera"]["pitch_deg"] == home["camera"]["pitch_deg"]
    });
    session.x.key(0xffbe); // F1
    session
        .viewer
        .wait_for("F1 to open the help", |s| s["help_open"] == true);
}
