//! `[sun] time`: the sun placed by the Solar Position Algorithm over the map's centre or over
//! `lat`/`lon`, against the position computed for the same place and time; a sun below the
//! horizon lights nothing and casts no shadow rays; a place that cannot be found is explained.

use crate::common::files::dem_bytes;
use crate::common::scenes::{load_scene_text, SMALL_SCENE};
use heightray::render::sun_position::SunPosition;
use heightray::render::{Culling, Frame, Lighting, Renderer, Scene, Shader};
use heightray::Terrain;

/// A scene on a 17x17 tile of 1-second cells centred on 60 N, 10 E (or a projected one), with
/// the given `[sun]` keys and shadows on.
fn scene(sun: &str, geographic: bool) -> Result<Scene, String> {
    let dir = tempfile::tempdir().unwrap();
    let second = 1.0 / 3600.0;
    let bytes = if geographic {
        dem_bytes(second, [10.0 - 8.5 * second, 60.0 + 8.5 * second], 2)
    } else {
        dem_bytes(30.0, [500_000.0, 6_650_000.0], 1)
    };
    let map = dir.path().join("tile.tif");
    std::fs::write(&map, bytes).unwrap();
    let text = format!(
        "[heightmap]\npath = {map:?}\n[camera]\neye = [-5.0, -5.0, 20.0]\n\
         target = [8.0, 8.0, 3.0]\nwidth = 16\nheight = 16\n[sun]\n{sun}\n\
         [effects]\nshadows = true\n"
    );
    load_scene_text("scene.toml", &text)
}

#[test]
fn the_sun_at_a_time_stands_where_the_algorithm_puts_it_over_the_maps_centre() {
    let time = "2026-06-21T10:00:00Z";
    let placed = scene(&format!("time = {time:?}"), true).unwrap();
    let expected = SunPosition::at(time, 60.0, 10.0).unwrap();
    assert!(expected.is_up());
    let direction = Lighting::unit(expected.direction());
    for (got, want) in placed.lighting.sun.iter().zip(direction) {
        assert!((got - want).abs() < 1e-9, "{got} against {want}");
    }
    // The morning sun of midsummer stands in the south-east, east of the meridian.
    assert!(placed.lighting.sun[0] > 0.0 && placed.lighting.sun[1] < 0.0);
    assert!(placed.lighting.shadows && placed.lighting.intensity == 1.0);
    // lat and lon place it elsewhere, on a projected map too.
    let there = scene(&format!("time = {time:?}\nlat = -33.9\nlon = 18.4"), false).unwrap();
    let expected = Lighting::unit(SunPosition::at(time, -33.9, 18.4).unwrap().direction());
    assert!((there.lighting.sun[2] - expected[2]).abs() < 1e-9);
}

#[test]
fn a_sun_below_the_horizon_lights_nothing_and_casts_no_shadow_rays() {
    // 02:00 UTC on the winter solstice at 60 N: deep night.
    let night = scene("time = \"2026-12-21T02:00:00Z\"", true).unwrap();
    assert!(night.lighting.sun[2] < 0.0);
    assert_eq!(night.lighting.intensity, 0.0);
    assert!(!night.lighting.shadows);
    let (frame, _) = render(night);
    assert!(frame.totals.primary_hits > 0);
    assert_eq!(frame.totals.shadow_rays, 0);
}

#[test]
fn a_place_or_time_that_cannot_be_used_is_explained() {
    for (sun, geographic, says) in [
        (
            "time = \"2026-12-21T08:00:00Z\"",
            false,
            "needs lat and lon",
        ),
        (
            "time = \"2026-12-21T08:00:00Z\"\nlat = 60.0",
            true,
            "go together",
        ),
        ("time = \"tomorrow\"", true, "is not a time"),
        (
            "time = \"2026-12-21T08:00:00Z\"\nlat = 100.0\nlon = 0.0",
            true,
            "[sun] time",
        ),
    ] {
        let error = scene(sun, geographic).unwrap_err();
        assert!(error.contains(says), "{sun}: {error}");
    }
}

/// Renders `scene` at its own camera, 16x16, and which pixels' camera rays hit the terrain.
fn render(scene: Scene) -> (Frame, Vec<bool>) {
    let terrain = Terrain::new(scene.field);
    let renderer = Renderer {
        shader: Shader::new(&terrain, scene.lighting, scene.method, Culling::default()),
        camera: scene.camera.in_grid(terrain.world_from_grid()),
        arith: scene.arith,
    };
    let mut frame = Frame::new(16, 16);
    renderer.render(&mut frame);
    let hits = renderer
        .camera
        .rays()
        .map(|ray| renderer.shader.traced(&ray, scene.arith).0.hit.is_some())
        .collect();
    (frame, hits)
}

#[test]
fn a_sun_set_below_the_horizon_gives_a_night_sky_and_casts_no_rays_towards_it() {
    // A direction below the horizon, with hard and soft shadows and sky light asked for.
    let effects = "angle_deg = 0.53\n[effects]\nshadows = true\nsky_light = true\n";
    let night = load_scene_text(
        "night.toml",
        &format!(
            "{}[sun]\ndirection = [0.3, 0.2, -0.4]\n{effects}",
            SMALL_SCENE
        ),
    )
    .unwrap();
    assert!(!night.lighting.sun_up());
    // The same view lit by the ambient term alone, under a day sky.
    let ambient_only = load_scene_text(
        "ambient.toml",
        &format!("{}[sun]\nintensity = 0.0\n", SMALL_SCENE),
    )
    .unwrap();
    let ((night, hits), (day, _)) = (render(night), render(ambient_only));
    let totals = &night.totals;
    assert!(
        totals.primary_hits > 0 && totals.primary_hits < 256,
        "{totals:?}"
    );
    assert_eq!(totals.shadow_rays, 0);
    assert_eq!(
        totals.effects.soft_shadow.rays + totals.effects.soft_shadow.directions,
        0
    );
    assert_eq!(
        totals.effects.sky_light.rays + totals.effects.sky_light.directions,
        0
    );
    let mut sky_pixels = 0;
    for (k, (&dark, &lit)) in night.pixels.iter().zip(&day.pixels).enumerate() {
        if hits[k] {
            // The terrain, by the ambient term alone.
            assert_eq!(dark, lit, "pixel {k}");
        } else {
            // The sky: dark (a day sky's channels are all above 0x70), not the day's.
            sky_pixels += 1;
            let channels = [dark >> 16, (dark >> 8) & 0xff, dark & 0xff];
            assert!(channels.iter().all(|&c| c <= 0x40), "pixel {k}: {dark:06x}");
            assert!(lit & 0xff > 0x70, "pixel {k}: day sky {lit:06x}");
        }
    }
    assert!(sky_pixels > 0);
}
