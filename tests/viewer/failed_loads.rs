//! A load that fails on the loading thread is reported, and the files dropped after it still
//! load: two tiles of which one lies 1e300 m away are refused with the reason, then a good
//! map dropped onto the same window loads and shows. A JPEG dropped as a height map is
//! draped over the map instead, and the notice says why.

use super::app::num;
use super::{write_hill, xdnd, Session};
use serde_json::Value;

/// A 4x4 ESRI ASCII tile of 1 m cells with its lower-left corner at `(x, 0)`.
fn write_tile(path: &std::path::Path, x: f64) {
    let rows = "1 2 3 4\n".repeat(4);
    let text = format!("ncols 4\nnrows 4\nxllcorner {x:e}\nyllcorner 0\ncellsize 1\n{rows}");
    std::fs::write(path, text).expect("write the tile");
}

#[test]
fn a_refused_mosaic_leaves_the_loader_loading_the_next_drop() {
    let mut session = Session::start(&[]);
    let state = session.state();
    let at = session.screen(session.view_centre(&state));
    let (near, far, hill) = (
        session.viewer.path("near.asc"),
        session.viewer.path("far.asc"),
        session.viewer.path("hill.pgm"),
    );
    write_tile(&near, 0.0);
    write_tile(&far, 1e300);
    write_hill(&hill);

    assert_eq!(
        xdnd::drag_files(&session.x, &[&near, &far], at, false),
        xdnd::Outcome::Accepted
    );
    let refused = session.viewer.wait_for("the mosaic to be refused", |s| {
        s["loading"] == Value::Null
            && s["error"]
                .as_str()
                .is_some_and(|e| e.contains("far.asc lies 1e300 cells from the first tile"))
    });
    assert_ne!(refused["terrain"]["name"], "near.asc (+1 tiles)");

    let converged = num(&refused, "/converged_frames") as u64;
    assert_eq!(
        xdnd::drag_file(&session.x, &hill, at, false),
        xdnd::Outcome::Accepted
    );
    let loaded = session
        .viewer
        .wait_for("the map dropped next to load", |s| {
            s["terrain"]["name"] == "hill.pgm" && s["converged_frames"].as_u64() > Some(converged)
        });
    assert_eq!(
        (
            loaded["terrain"]["width"].as_u64(),
            loaded["terrain"]["height"].as_u64()
        ),
        (Some(64), Some(40))
    );
    session.capture("after-a-refused-mosaic.png");
}

#[test]
fn a_jpeg_dropped_as_a_height_map_is_draped_as_an_overlay_saying_so() {
    let mut session = Session::start(&[]);
    let state = session.state();
    let at = session.screen(session.view_centre(&state));
    let photo = session.viewer.path("photo.jpg");
    image::RgbImage::from_fn(64, 40, |x, y| image::Rgb([x as u8 * 4, y as u8 * 6, 90]))
        .save(&photo)
        .expect("the JPEG written");
    assert_eq!(
        xdnd::drag_file(&session.x, &photo, at, false),
        xdnd::Outcome::Accepted
    );
    let draped = session.viewer.wait_for("the photo draped", |s| {
        s["terrain"]["overlay"]
            .as_str()
            .is_some_and(|o| o.ends_with("photo.jpg"))
    });
    assert_eq!(draped["error"], Value::Null);
    assert_eq!(draped["terrain"]["name"], state["terrain"]["name"]);
    let notice = draped["notice"].as_str().unwrap_or_default();
    assert!(
        notice.contains("it is a JPEG image, not a height map"),
        "{notice}"
    );
}
