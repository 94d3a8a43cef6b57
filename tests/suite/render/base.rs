//! The base in rendered frames: each culling rule on or off gives the same image with walls
//! and a floor under holes (in `f32`, `f64` and exact arithmetic, with and without effects),
//! the base shows, and the scene keys are read, checked and named.

use super::*;
use crate::common::scenes::{load_scene_text, SMALL_SCENE};
use heightray::heightfield::{landscape, NoDataMask, Quantisation};
use heightray::render::BaseStyle;

/// The built-in generator's 33x33 landscape with two holes, one at the south edge.
fn holed_landscape() -> Terrain {
    let field = landscape(33, 3, 10.0).unwrap();
    let mut mask = NoDataMask::new(field.samples().len());
    for j in 0..33 {
        for i in 0..33 {
            let inner = (i as i32 - 20).pow(2) + (j as i32 - 16).pow(2) < 16;
            let edge = (8..12).contains(&i) && j < 3;
            if inner || edge {
                mask.insert(j * 33 + i);
            }
        }
    }
    let field = Heightfield::new(
        33,
        33,
        field.samples().to_vec(),
        Quantisation::Maxval(field.maxval()),
        field.z_scale(),
        Some(mask),
    )
    .unwrap();
    Terrain::new(field)
}

/// A low view from the south-west over the map, the sun low from the south-east.
fn low_view(walls: bool, effects: Effects) -> (Camera, Lighting) {
    let camera = Camera::look_at(
        [-14.0, -22.0, 16.0],
        [16.0, 16.0, 0.0],
        [0.0, 0.0, 1.0],
        40.0,
        (40, 40),
    )
    .unwrap();
    let lighting = Lighting {
        effects,
        base: BaseStyle { walls, depth: None },
        ..lighting([0.6, -0.5, 0.35], true)
    };
    (camera, lighting)
}

const NONE: Culling = super::NO_CULLING;

fn each_rule() -> Vec<Culling> {
    let off = |f: fn(&mut Culling)| {
        let mut culling = Culling::default();
        f(&mut culling);
        culling
    };
    vec![
        off(|c| c.facing_away = false),
        off(|c| c.no_shadow_possible = false),
        off(|c| c.above_terrain = false),
        off(|c| c.horizon_clear = false),
        off(|c| c.cone_blocked = false),
        off(|c| c.far_bounds = false),
        off(|c| c.probes = false),
        off(|c| c.camera_clearance = false),
        off(|c| c.near_walk = false),
        NONE,
    ]
}

#[test]
fn each_culling_rule_on_or_off_gives_the_same_image_over_the_base() {
    let terrain = holed_landscape();
    let (camera, lit) = low_view(true, Effects::default());
    for arith in [Arith::F32, Arith::F64, Arith::Exact] {
        let render = |culling| render_by(Method::Mipmap, &terrain, camera, lit, arith, culling, 2);
        let all = render(Culling::default());
        for culling in each_rule() {
            let frame = render(culling);
            assert_eq!(frame.pixels, all.pixels, "{arith} {culling:?}");
            assert_eq!(
                frame.totals.base_hits, all.totals.base_hits,
                "{arith} {culling:?}"
            );
        }
        assert!(
            all.totals.base_hits > 100,
            "{arith}: the view shows the base"
        );
        // The walls show: without them their pixels are sky or the floor beyond.
        let (_, no_walls) = low_view(false, Effects::default());
        let without = render_by(Method::Runs, &terrain, camera, no_walls, arith, NONE, 2);
        let differing = without
            .pixels
            .iter()
            .zip(&all.pixels)
            .filter(|(a, b)| a != b)
            .count();
        assert!(
            differing > 100,
            "{arith}: {differing} pixels show the walls"
        );
    }
}

/// A map with holes has a floor under them by default, walls or not; one without holes has
/// none unless it has walls.
#[test]
fn holes_show_the_floor_by_default() {
    let terrain = holed_landscape();
    let (_, lit) = low_view(false, Effects::default());
    let shader = Shader::new(&terrain, lit, Method::Mipmap, Culling::default());
    let down = heightray::Ray::new([20.5, 16.5, 30.0], [0.0, 0.0, -1.0]).unwrap();
    let found = shader.tracer().trace::<f64>(&down, None).hit.unwrap();
    let floor = shader.base.unwrap().floor();
    assert_eq!(found.face, heightray::Face::Floor);
    assert_eq!(found.t, 30.0 - floor);
    let whole = Terrain::new(landscape(33, 3, 10.0).unwrap());
    let plain = Shader::new(&whole, lit, Method::Mipmap, Culling::default());
    assert_eq!(plain.base, None);
    let (_, walled) = low_view(true, Effects::default());
    let walled = Shader::new(&whole, walled, Method::Mipmap, Culling::default());
    assert!(walled.base.is_some_and(|base| base.walls()));
}

#[test]
fn effects_culling_on_or_off_gives_the_same_image_over_the_base() {
    let terrain = holed_landscape();
    let effects = Effects {
        sun_angle_deg: 3.0,
        sun_rays: 8,
        sky_light: true,
        sky_rays: 8,
        sky_distance: 12.0,
        ..Effects::default()
    };
    let (camera, lit) = low_view(true, effects);
    let render = |culling| {
        render_by(
            Method::Mipmap,
            &terrain,
            camera,
            lit,
            Arith::F64,
            culling,
            2,
        )
    };
    let all = render(Culling::default());
    for culling in each_rule() {
        assert_eq!(render(culling).pixels, all.pixels, "{culling:?}");
    }
}

#[test]
fn every_method_renders_the_same_exact_frame_over_the_base() {
    let terrain = holed_landscape();
    let (camera, lit) = low_view(true, Effects::default());
    let mipmap = render_by(
        Method::Mipmap,
        &terrain,
        camera,
        lit,
        Arith::Exact,
        Culling::default(),
        2,
    );
    for method in [Method::HierarchicalRuns, Method::Runs, Method::Dda] {
        let frame = render_by(
            method,
            &terrain,
            camera,
            lit,
            Arith::Exact,
            Culling::default(),
            2,
        );
        assert_eq!(frame.pixels, mipmap.pixels, "{method}");
    }
}

#[test]
fn the_base_keys_are_read_and_checked() {
    let with = |keys: &str| format!("{SMALL_SCENE}[shading]\n{keys}\n");
    let scene = load_scene_text("a.toml", &with("base = true\nbase_depth = 2.5")).unwrap();
    assert_eq!(
        scene.lighting.base,
        BaseStyle {
            walls: true,
            depth: Some(2.5)
        }
    );
    let plain = load_scene_text("a.toml", SMALL_SCENE).unwrap();
    assert_eq!(plain.lighting.base, BaseStyle::default());
    for (keys, named) in [
        ("base_depth = -1.0", "base_depth"),
        ("base_depth = 0.0", "base_depth"),
        ("base_depth = nan", "base_depth"),
        ("base = \"yes\"", "base"),
    ] {
        let message = load_scene_text("bad.toml", &with(keys)).unwrap_err();
        assert!(
            message.contains(named) && message.contains("bad.toml"),
            "{keys}: {message}"
        );
    }
}
