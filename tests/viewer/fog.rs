//! Fog as a visibility distance: the haze the toggle sets and the shortest visibility the
//! slider offers both leave the terrain readable, and shorter visibility means more haze.

use super::app::{num, widget};
use super::{luminance, Session};

/// Standard deviation of the luminance: how much the picture still varies under the haze.
fn contrast(pixels: &[[u8; 3]]) -> f64 {
    let n = pixels.len().max(1) as f64;
    let mean = pixels.iter().map(|p| luminance(*p)).sum::<f64>() / n;
    let var = pixels
        .iter()
        .map(|p| (luminance(*p) - mean).powi(2))
        .sum::<f64>()
        / n;
    var.sqrt()
}

/// A fully refined frame newer than `converged` refined frames, with nothing rendering.
fn refined_after(state: &serde_json::Value, converged: u64) -> bool {
    state["converged_frames"].as_u64() > Some(converged) && state["rendering"] == false
}

#[test]
fn every_visibility_the_slider_offers_leaves_the_terrain_readable() {
    let mut session = Session::start(&[]);
    let state = session.open_section("effects_section", "fog_toggle");
    // The left 60% of the view: away from the legend in the bottom-right corner.
    let (x0, y0, x1, y1) = session.view(&state);
    let area = (x0, y0, x0 + (x1 - x0) * 3 / 5, y1);
    let clear = contrast(&session.capture("fog-off.png").region(area));

    let converged = num(&state, "/converged_frames") as u64;
    session.click(&state, "fog_toggle");
    let state = session.viewer.wait_for("a frame with fog", |s| {
        num(s, "/lighting/fog") > 0.0 && refined_after(s, converged)
    });
    let hazy = contrast(&session.capture("fog-default.png").region(area));
    let default_fog = num(&state, "/lighting/fog");

    // A press at the slider's left end: the shortest visibility it offers.
    let [sx0, sy0, _, sy1] = widget(&state, "fog_visibility");
    let y = (sy0 + sy1) / 2.0;
    let converged = num(&state, "/converged_frames") as u64;
    session.x.move_to(session.screen((sx0 + 1.0, y)));
    std::thread::sleep(std::time::Duration::from_millis(150));
    session.x.press(1);
    std::thread::sleep(std::time::Duration::from_millis(40));
    session.x.release(1);
    let state = session.viewer.wait_for("a frame with thicker fog", |s| {
        num(s, "/lighting/fog") > default_fog && refined_after(s, converged)
    });
    let thick = contrast(&session.capture("fog-thickest.png").region(area));
    let eye_distance = num(&state, "/camera/distance");
    let visibility = 3.0 / num(&state, "/lighting/fog");
    assert!(
        (visibility - 2.0 * eye_distance).abs() < 0.02 * eye_distance,
        "the slider's shortest visibility is {visibility:.1} seen from {eye_distance:.1} away"
    );
    assert!(
        clear > hazy && hazy > thick,
        "contrast without fog {clear:.1}, default fog {hazy:.1}, thickest {thick:.1}: \
         shorter visibility must mean more haze"
    );
    assert!(
        hazy > 0.5 * clear && thick > 0.1 * clear,
        "contrast without fog {clear:.1}, default fog {hazy:.1}, thickest {thick:.1}: the \
         terrain is washed out"
    );
}
