//! Decoding choices for height map images: given on the command line, shown in the height map
//! panel, and applied to the image on screen with one click.

use super::app::num;
use super::Session;
use serde_json::Value;
use std::path::Path;

/// A 48x32 Mapbox terrain-RGB image of a cone from 100 m to 600 m, with its 4x4 corner at
/// `(0, 0, 0)`, which is -10000 m: the no-data marker of the test.
fn write_terrain_rgb(path: &Path) {
    let image = image::RgbImage::from_fn(48, 32, |x, y| {
        if x < 4 && y < 4 {
            return image::Rgb([0, 0, 0]);
        }
        let d = (f64::from(x) - 24.0).hypot(f64::from(y) - 16.0);
        let metres = 100.0 + 500.0 * (1.0 - d / 20.0).max(0.0);
        // height = -10000 + code * 0.1
        let code = ((metres + 10000.0) * 10.0).round() as u32;
        image::Rgb([(code >> 16) as u8, (code >> 8) as u8, code as u8])
    });
    image.save(path).expect("write the terrain-RGB image");
}

#[test]
fn decoding_choices_apply_to_the_image_on_screen() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let path = dir.path().join("cone-rgb.png");
    write_terrain_rgb(&path);
    let file = path.to_str().expect("a UTF-8 path");
    let mut session = Session::start(&[file, "--rgb", "mapbox", "--nodata", "-10000"]);

    // Read as asked: the corner is a hole, the cone the highest point.
    let state = session.state();
    assert_eq!(state["terrain"]["decoded_as"]["colour"], "mapbox");
    assert_eq!(state["terrain"]["decoded_as"]["nodata"], "-10000");
    assert_eq!(num(&state, "/terrain/nodata_count"), 16.0);
    assert_eq!(state["decoding"], state["terrain"]["decoded_as"]);
    session.capture("decoded-mapbox.png");

    // Choose luminance and no marker: the button to read it again appears, and reads it so.
    let state = session.open_section("heightmap_section", "decode_luminance");
    session.click(&state, "decode_luminance");
    let state = session.viewer.wait_for("luminance chosen", |s| {
        s["decoding"]["colour"] == "luminance"
    });
    session.click(&state, "nodata_none");
    let state = session.viewer.wait_for("the read-again button", |s| {
        s["decoding"]["nodata"] == "none" && s["widgets"]["decode_again"].is_array()
    });
    let converged = num(&state, "/converged_frames");
    session.click(&state, "decode_again");
    let read = session.viewer.wait_for("the image read again", |s| {
        s["terrain"]["decoded_as"]["colour"] == "luminance"
            && num(s, "/converged_frames") > converged
    });
    assert_eq!(read["terrain"]["decoded_as"]["nodata"], "none");
    assert_eq!(num(&read, "/terrain/nodata_count"), 0.0);
    assert_eq!(read["terrain"]["name"], "cone-rgb.png");
    assert_eq!(read["error"], Value::Null);
    session.capture("decoded-luminance.png");
}
