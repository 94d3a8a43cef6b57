//! Colour ramps: scene files name them (an unknown name is an error listing the valid ones),
//! and a map reaching below height 0 is coloured as land and sea by the land ramps.

use crate::common::scenes::{load_scene_text, SMALL_SCENE as SCENE};
use crate::common::top_down::render_top_down;
use heightray::heightfield::Quantisation;
use heightray::render::Ramp;
use heightray::{Heightfield, Terrain};

#[test]
fn scene_files_name_every_ramp_and_an_unknown_one_is_refused_with_the_valid_names() {
    for ramp in Ramp::ALL {
        let text = format!("{SCENE}[shading]\nramp = \"{}\"\n", ramp.name());
        let scene =
            load_scene_text("ramp.toml", &text).unwrap_or_else(|e| panic!("{}: {e}", ramp.name()));
        assert_eq!(scene.lighting.ramp, ramp);
    }
    assert_eq!(
        load_scene_text("ramp.toml", SCENE).unwrap().lighting.ramp,
        Ramp::Terrain
    );
    let error = load_scene_text(
        "ramp.toml",
        &format!("{SCENE}[shading]\nramp = \"rainbow\"\n"),
    )
    .unwrap_err();
    assert!(
        error.contains("ramp.toml") && error.contains("rainbow"),
        "{error}"
    );
    for ramp in Ramp::ALL {
        assert!(error.contains(ramp.name()), "{error}");
    }
}

/// A coast in metres, as a signed or float raster holds it: the western half a sea floor at
/// -1600, the eastern half a plain at sea level, on a 9 x 9 grid (`z_scale` shrinks both
/// alike, to -6.25 and 0, and keeps sea level at 0).
fn coast() -> Terrain {
    let samples = (0..9)
        .flat_map(|_| (0..9).map(|x| if x < 4 { 0 } else { 1600 }))
        .collect();
    let quantisation = Quantisation::Offset {
        lowest: -1600.0,
        step: 1.0,
    };
    let field = Heightfield::new(9, 9, samples, quantisation, 1.0 / 256.0, None).unwrap();
    Terrain::new(field)
}

fn bytes(pixel: u32) -> [u8; 3] {
    [(pixel >> 16) as u8, (pixel >> 8) as u8, pixel as u8]
}

#[test]
fn the_land_ramps_colour_below_sea_level_as_sea() {
    let terrain = coast();
    assert_eq!(terrain.z_range(), (-6.25, 0.0));
    // Columns 1 and 14 of the middle row: over x < 3 (the sea floor) and x > 5 (the plain).
    let row = 8 * 16;
    let (west, east) = (row + 1, row + 14);
    // The hypsometric ramp's lowest tint (Wikipedia's 0 m, #ACD0A5) on the plain; a dark
    // blue on the sea floor.
    let hypsometric = render_top_down(&terrain, Ramp::Hypsometric, 40.0, 11.0);
    assert_eq!(bytes(hypsometric.pixels[east]), [172, 208, 165]);
    let [r, g, b] = bytes(hypsometric.pixels[west]);
    assert!(b > 90 && b > g + 30 && g > r + 30, "sea floor {r} {g} {b}");
    // The default ramp: its own lowest colour on land (0.18, 0.32, 0.14 in linear light), the
    // same sea.
    let terrain_ramp = render_top_down(&terrain, Ramp::Terrain, 40.0, 11.0);
    let lowland = [0.18f64, 0.32, 0.14].map(|v| (v.powf(1.0 / 2.2) * 255.0 + 0.5) as u8);
    assert_eq!(bytes(terrain_ramp.pixels[east]), lowland);
    assert_eq!(terrain_ramp.pixels[west], hypsometric.pixels[west]);
    // A data ramp spans the heights without a sea: matplotlib's viridis from its first
    // colour (#440154) at the lowest height to its last (#FDE725) at the highest.
    let viridis = render_top_down(&terrain, Ramp::Viridis, 40.0, 11.0);
    assert_eq!(bytes(viridis.pixels[west]), [68, 1, 84]);
    assert_eq!(bytes(viridis.pixels[east]), [253, 231, 37]);
}
