//! A window resized far beyond any screen (8000x8000): the view renders at the capped size,
//! scaled up to the window and saying so, within a bounded time and memory.

use super::app::{artifacts, num, Viewer};
use super::x11::{Xvfb, X};
use super::{luminance, terrain_share, ONE_AT_A_TIME};
use std::time::{Duration, Instant};

/// The most pixels the viewer renders a view at (`quality::MOST_VIEW_PIXELS`).
const MOST_VIEW_PIXELS: u64 = 1 << 22;
/// The whole viewer's memory at any window size, as the hostile-input limits ask.
const MOST_BYTES: u64 = 1_000_000_000;
/// From the resize to the first fully refined frame at the new size.
const MOST_TIME: Duration = Duration::from_secs(20);

#[test]
fn a_huge_window_renders_at_the_capped_size_scaled_up_and_stays_under_a_gigabyte() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let xvfb = Xvfb::with_screen("8192x8192x24");
    let mut viewer = Viewer::start(&xvfb.display, &[]);
    let start = viewer.wait_converged(0);
    assert!(start["capped"].is_null(), "a 1280x720 window is capped");
    let window = num(&start, "/x11_window") as u32;
    let x = X::connect(&xvfb.display);

    let resized_at = Instant::now();
    x.resize(window, (8000, 8000));
    let converged = num(&start, "/converged_frames") as u64;
    let state = viewer.wait_for("a refined frame of the 8000x8000 window", |s| {
        s["window_size"] == serde_json::json!([8000, 8000])
            && s["converged_frames"].as_u64() > Some(converged)
            && s["rendering"] == false
            && s["frame"]["width"] == s["capped"]["render"][0]
    });
    let took = resized_at.elapsed();
    assert!(took < MOST_TIME, "the huge window took {took:?} to refine");

    let render = [
        num(&state, "/capped/render/0"),
        num(&state, "/capped/render/1"),
    ];
    let shown = [
        num(&state, "/capped/shown/0"),
        num(&state, "/capped/shown/1"),
    ];
    let view = [num(&state, "/view_rect/2"), num(&state, "/view_rect/3")];
    assert_eq!(shown, view, "the capped size is the view's");
    assert!(
        render[0] * render[1] <= MOST_VIEW_PIXELS as f64,
        "{render:?}"
    );
    // The largest frame of the view's shape within the limit: one more row and column do not fit.
    assert!((render[0] + 1.0) * (render[1] + 1.0) > MOST_VIEW_PIXELS as f64);
    assert!((render[0] / render[1] - view[0] / view[1]).abs() < 0.01);
    assert_eq!(
        [num(&state, "/frame/width"), num(&state, "/frame/height")],
        render,
        "the frame on screen is rendered at the capped size"
    );
    let text = state["capped"]["text"].as_str().unwrap_or_default();
    let says = format!(
        "rendering at {}x{}, shown at {}x{}",
        render[0], render[1], view[0], view[1]
    );
    assert!(text.starts_with(&says), "{text}");

    // On screen: the status in the view's corner, and terrain scaled up to fill the view.
    let [x0, y0, x1, y1] = super::app::widget(&state, "view_status");
    let status = x.capture_part(
        window,
        (x0 as i16, y0 as i16),
        ((x1 - x0) as u16, (y1 - y0) as u16),
    );
    status.save(&artifacts().join("huge-window-status.png"));
    let bright = status.rgb.iter().filter(|&&p| luminance(p) > 150.0).count();
    assert!(
        bright > status.rgb.len() / 50,
        "no status text on screen ({bright} bright pixels)"
    );
    let centre = (view[0] as i16 / 2, view[1] as i16 / 2);
    let middle = x.capture_part(window, (centre.0 - 400, centre.1 - 400), (800, 800));
    middle.save(&artifacts().join("huge-window-middle.png"));
    assert!(
        terrain_share(&middle.rgb) > 0.5,
        "the middle of the view shows no terrain"
    );

    let peak = viewer.peak_memory();
    eprintln!(
        "8000x8000 window: refined in {took:?} at {}x{}, peak memory {} MB",
        render[0],
        render[1],
        peak / 1_000_000
    );
    assert!(peak < MOST_BYTES, "the viewer held {peak} bytes at once");
}
