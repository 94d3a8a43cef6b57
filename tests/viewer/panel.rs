//! The side panel's size at the default and at small windows, the messages over the view, and
//! the probe of the pixel under the pointer.

use super::app::{num, widget};
use super::{Session, X};
use serde_json::Value;
use std::time::{Duration, Instant};

fn window_size(state: &Value) -> (f64, f64) {
    (num(state, "/window_size/0"), num(state, "/window_size/1"))
}

#[test]
fn the_default_panel_fits_720_pixels_and_keeps_its_width_when_a_section_opens() {
    let mut session = Session::start(&[]);
    let state = session.state();
    let (width, height) = window_size(&state);
    assert_eq!((width, height), (1280.0, 720.0));
    let panel = widget(&state, "side_panel");
    let content = widget(&state, "panel_content");
    session.capture("panel-default.png");
    assert!(
        content[1] >= panel[1] && content[3] <= height - 4.0,
        "the panel's sections reach from {} to {} px in a {height} px window: they need \
         scrolling",
        content[1],
        content[3]
    );
    assert!(
        panel[2] - panel[0] <= 0.3 * width && panel[2] <= width && content[2] <= width,
        "the panel {panel:?} (content {content:?}) in a {width} px window"
    );

    // Opening the widest section changes neither the panel's width nor the view.
    session.click(&state, "traversal_section");
    session
        .viewer
        .wait_for("the Traversal section to open", |s| {
            s["widgets"]["measure_button"].is_array()
        });
    std::thread::sleep(Duration::from_millis(600));
    // The report of the last frame drawn, once the opening animation has ended.
    let opened = session.state();
    session.capture("panel-traversal-open.png");
    assert_eq!(
        widget(&opened, "side_panel"),
        panel,
        "the panel changed width"
    );
    assert_eq!(opened["view_rect"], state["view_rect"], "the view moved");
}

#[test]
fn a_small_window_gets_a_narrower_panel_and_a_tiny_one_none_with_a_hint() {
    let session = Session::start(&["--size", "800x500"]);
    let state = session.state();
    assert_eq!(window_size(&state), (800.0, 500.0));
    let panel = widget(&state, "side_panel");
    let content = widget(&state, "panel_content");
    session.capture("panel-800x500.png");
    assert!(
        panel[2] - panel[0] <= 0.32 * 800.0 && panel[2] <= 800.0 && content[2] <= 800.0,
        "the panel {panel:?} (content {content:?}) in an 800 px window"
    );
    assert!(num(&state, "/view_rect/2") >= 0.68 * 800.0);
    assert!(
        content[1] >= panel[1] && content[3] <= 500.0 - 4.0,
        "the panel's sections reach from {} to {} px in a 500 px window: they need scrolling",
        content[1],
        content[3]
    );
    drop(session);

    let session = Session::start(&["--size", "560x400"]);
    let state = session.state();
    session.capture("panel-560x400.png");
    assert_eq!(
        state["panels_visible"], false,
        "the panel did not hide itself"
    );
    assert_eq!(
        num(&state, "/view_rect/2"),
        560.0,
        "the view is not the whole window"
    );
    let [h0, h1, h2, h3] = widget(&state, "show_panel_hint");
    assert!(
        h0 >= 0.0 && h2 <= 560.0 && h1 >= 0.0 && h3 <= 400.0 && h2 - h0 > 50.0,
        "the hint to bring the panel back is not in the window: {:?}",
        [h0, h1, h2, h3]
    );
}

#[test]
fn a_long_error_wraps_inside_the_view_and_dismiss_takes_it_away() {
    let mut session = Session::start(&["--size", "800x500"]);
    let state = session.state();
    let at = session.screen(session.view_centre(&state));

    // A map that loads: the path field shows it, however it was opened.
    let hill = session.viewer.path("hill.pgm");
    super::write_hill(&hill);
    assert_eq!(
        super::xdnd::drag_file(&session.x, &hill, at, false),
        super::xdnd::Outcome::Accepted
    );
    let loaded = session
        .viewer
        .wait_for("the hill to load", |s| s["terrain"]["name"] == "hill.pgm");
    assert_eq!(loaded["path_field"], hill.display().to_string());

    let name = format!("{}.txt", "this-file-is-not-a-height-map-".repeat(6));
    let notes = session.viewer.path(&name);
    std::fs::write(&notes, "not a height map\n").expect("write notes");
    assert_eq!(
        super::xdnd::drag_file(&session.x, &notes, at, false),
        super::xdnd::Outcome::Accepted
    );
    let shown = session.viewer.wait_for("the error over the view", |s| {
        s["error"].is_string() && s["widgets"]["error_message"].is_array()
    });
    let shot = session.capture("long-error.png");
    let error = shown["error"].as_str().unwrap_or_default();
    assert!(error.contains(&name), "{error}");
    let (x0, y0, x1, y1) = session.view(&shown);
    let [e0, f0, e1, f1] = widget(&shown, "error_message");
    assert!(
        e0 >= x0 as f64 && e1 <= x1 as f64 && f0 >= y0 as f64 && f1 <= y1 as f64,
        "the error {:?} leaves the view {:?}",
        [e0, f0, e1, f1],
        (x0, y0, x1, y1)
    );
    // One line of it would be several times wider than the view.
    assert!(f1 - f0 > 60.0, "the error is not wrapped: {f0}..{f1}");
    let red = shot
        .region((e0 as usize, f0 as usize, e1 as usize, f1 as usize))
        .iter()
        .filter(|[r, g, b]| *r > 90 && *g < 50 && *b < 50)
        .count();
    assert!(red > 1000, "no red message where the report puts it");

    session.click(&shown, "error_dismiss");
    // (The report's widgets are those of the last frame drawn, which may come after the
    // report that the error is gone.)
    let gone = session
        .viewer
        .wait_for("Dismiss to take the error off the screen", |s| {
            s["error"].is_null() && s["widgets"]["error_message"].is_null()
        });
    assert_eq!(
        gone["path_field"],
        hill.display().to_string(),
        "the path field no longer shows the map on screen"
    );
}

#[test]
fn reading_a_grey_image_again_is_offered_only_for_what_changes_it() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let hill = dir.path().join("grey-hill.pgm");
    super::write_hill(&hill);
    let file = hill.to_str().expect("a UTF-8 path");
    let mut session = Session::start(&[file]);
    session.open_section("heightmap_section", "decode_mapbox");

    // The colour encoding changes nothing in a grey image.
    session.click(&session.state(), "decode_mapbox");
    session
        .viewer
        .wait_for("Mapbox chosen", |s| s["decoding"]["colour"] == "mapbox");
    std::thread::sleep(Duration::from_millis(300));
    let chosen = session.state();
    assert!(
        chosen["widgets"]["decode_again"].is_null(),
        "reading a grey image again is offered for an RGB encoding"
    );

    // No data does change it.
    session.click(&chosen, "nodata_none");
    session.viewer.wait_for("the read-again button", |s| {
        s["decoding"]["nodata"] == "none" && s["widgets"]["decode_again"].is_array()
    });
}

/// Moves the pointer to `at` (window pixels) by two steps, so that a motion arrives even when
/// it is there already; returns when the second move was made.
fn hover(x: &X, session: &Session, (px, py): (f64, f64)) -> Instant {
    x.move_to(session.screen((px - 3.0, py)));
    std::thread::sleep(Duration::from_millis(30));
    x.move_to(session.screen((px, py)));
    Instant::now()
}

#[test]
fn the_probe_is_off_until_ticked_then_shows_only_where_the_pointer_rests() {
    let mut session = Session::start(&[]);
    let state = session.state();
    let centre = session.view_centre(&state);
    hover(&session.x, &session, centre);
    std::thread::sleep(Duration::from_millis(1200));
    let resting = session.state();
    assert!(resting["probe"].is_null(), "the probe is on by default");

    session.click(&resting, "statistics_section");
    let opened = session.viewer.wait_for("the Statistics section", |s| {
        s["widgets"]["probe_toggle"].is_array()
    });
    std::thread::sleep(Duration::from_millis(600));
    session.click(&session.state(), "probe_toggle");
    session
        .viewer
        .wait_for("the probe to be ticked", |s| s["show_probe"] == true);
    drop(opened);

    let moved = hover(&session.x, &session, centre);
    let probed = session
        .viewer
        .wait_for("the probe under the resting pointer", |s| {
            s["probe"].is_array()
        });
    let waited = moved.elapsed();
    assert!(
        waited >= Duration::from_millis(450),
        "the probe showed {waited:?} after the pointer stopped"
    );
    session.capture("probe.png");

    // Dragging hides it, and letting go does not bring it back at once.
    let (cx, cy) = centre;
    session.x.press(1);
    for step in 1..=8 {
        session
            .x
            .move_to(session.screen((cx + 10.0 * f64::from(step), cy)));
        std::thread::sleep(Duration::from_millis(30));
    }
    let dragging = session
        .viewer
        .wait_for("the drag to hide the probe", |s| s["probe"].is_null());
    session.x.release(1);
    let released = Instant::now();
    let back = session
        .viewer
        .wait_for("the probe after the drag", |s| s["probe"].is_array());
    assert!(
        released.elapsed() >= Duration::from_millis(450),
        "the probe came back at once after the drag"
    );
    assert_ne!(
        back["probe"], probed["probe"],
        "the probe did not follow the pointer"
    );
    drop(dragging);
}

#[test]
fn a_heat_map_the_method_cannot_fill_cannot_be_chosen() {
    let mut session = Session::start(&[]);
    let state = session.state();
    assert_eq!(state["heat_map"], "off (shaded image)");
    session.click(&state, "statistics_section");
    session.viewer.wait_for("the Statistics section", |s| {
        s["widgets"]["heat_map"].is_array()
    });
    std::thread::sleep(Duration::from_millis(600));
    session.click(&session.state(), "heat_map");
    let open = session.viewer.wait_for("the heat-map list", |s| {
        s["widgets"]["heat_runs"].is_array()
    });
    std::thread::sleep(Duration::from_millis(300));

    // The default method, the mipmap, makes no run queries.
    session.click(&open, "heat_runs");
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(
        session.state()["heat_map"],
        "off (shaded image)",
        "a run-query map was chosen under the mipmap"
    );
    let state = session.state();
    if !state["widgets"]["heat_blocks"].is_array() {
        session.click(&state, "heat_map");
        session.viewer.wait_for("the heat-map list again", |s| {
            s["widgets"]["heat_blocks"].is_array()
        });
        std::thread::sleep(Duration::from_millis(300));
    }
    session.click(&session.state(), "heat_blocks");
    session.viewer.wait_for("the block-query map", |s| {
        s["heat_map"] == "block queries (mipmap)"
    });
}

#[test]
fn ticking_and_unticking_compare_with_exact_moves_nothing_below_it() {
    let mut session = Session::start(&[]);
    let state = session.state();
    session.click(&state, "traversal_section");
    session.viewer.wait_for("the Traversal section", |s| {
        s["widgets"]["compare_toggle"].is_array()
    });
    std::thread::sleep(Duration::from_millis(600));
    let before = session.state();
    let below = widget(&before, "effects_section");
    session.click(&before, "compare_toggle");
    let on = session.viewer.wait_for("the comparison to run", |s| {
        s["accuracy"]["compare"]["on"] == true
    });
    assert_eq!(
        widget(&on, "effects_section"),
        below,
        "ticking moved the panel"
    );
    let done = session.viewer.wait_for("the comparison's count", |s| {
        s["accuracy"]["compare"]["differing"].is_u64()
    });
    assert_eq!(
        widget(&done, "effects_section"),
        below,
        "the count moved the panel"
    );
    session.click(&done, "compare_toggle");
    let off = session.viewer.wait_for("the comparison to be off", |s| {
        s["accuracy"]["compare"]["on"] == false
    });
    assert_eq!(
        widget(&off, "effects_section"),
        below,
        "unticking moved the panel"
    );
}
