//! Shadow rays: cast only where they can change the pixel (each culling rule on or off gives
//! the same image), no acne, contact and crease shadows kept in float arithmetic, and exact
//! shadow rays that start exactly on the surface.

use super::*;
use heightray::arith::{Plain, Settling};

#[test]
fn shadows_off_cast_no_shadow_rays() {
    let scene = builtin_scene("small49", 48);
    let terrain = Terrain::new(scene.field.clone());
    let mut lighting = scene.lighting;
    lighting.shadows = false;
    let frame = render_by(
        Method::Runs,
        &terrain,
        scene.camera,
        lighting,
        Arith::F64,
        Culling::default(),
        2,
    );
    assert_eq!(frame.totals.shadow_rays, 0);
    assert_eq!(frame.totals.shadow.bbox.total(), 0);
    assert!(frame.totals.primary_hits > 0);
}

#[test]
fn no_shadow_rays_where_no_shadow_is_possible() {
    // The sun stands higher than the steepest slope of the field: every shadow ray is left out,
    // and the image is the one casting them all gives.
    let scene = builtin_scene("small49", 48);
    let terrain = Terrain::new(scene.field.clone());
    let steepest = terrain.max_slope();
    let sun = lighting([1.0, 0.0, steepest * 1.01], true);
    let culled = render_by(
        Method::Runs,
        &terrain,
        scene.camera,
        sun,
        Arith::F64,
        Culling::default(),
        2,
    );
    let none = super::NO_CULLING;
    let brute = render_by(
        Method::Runs,
        &terrain,
        scene.camera,
        sun,
        Arith::F64,
        none,
        2,
    );
    assert_eq!(culled.totals.shadow_rays, 0);
    assert!(culled.totals.skipped.no_shadow_possible > 0);
    assert!(brute.totals.shadow_rays > 0);
    assert_eq!(
        brute.totals.shadowed, 0,
        "brute force finds no shadow either"
    );
    assert_eq!(culled.pixels, brute.pixels);
}

#[test]
fn each_culling_rule_on_or_off_gives_the_same_image() {
    let scene = builtin_scene("small49", 64);
    let terrain = Terrain::new(scene.field.clone());
    let all = render_by(
        Method::Runs,
        &terrain,
        scene.camera,
        scene.lighting,
        Arith::F64,
        Culling::default(),
        2,
    );
    let rules = [
        Culling {
            facing_away: false,
            ..Culling::default()
        },
        Culling {
            no_shadow_possible: false,
            ..Culling::default()
        },
        Culling {
            above_terrain: false,
            ..Culling::default()
        },
        Culling {
            far_bounds: false,
            ..Culling::default()
        },
        super::NO_CULLING,
        Culling {
            near_walk: false,
            ..Culling::default()
        },
    ];
    for culling in rules {
        let frame = render_by(
            Method::Runs,
            &terrain,
            scene.camera,
            scene.lighting,
            Arith::F64,
            culling,
            2,
        );
        assert_eq!(frame.pixels, all.pixels, "{culling:?}");
        assert!(frame.totals.shadow_rays >= all.totals.shadow_rays);
    }
    assert!(
        all.totals.skipped.facing_away > 0,
        "the scene exercises facing-away culling"
    );
}

/// A plane rising towards +x with slope 1/2, lit from -x by a sun that climbs at 0.2:
/// shadow rays are cast (the sun is lower than the slope) yet nothing can shadow the plane.
#[test]
fn gentle_slope_has_no_shadow_acne_in_any_arithmetic() {
    let terrain =
        Terrain::new(Heightfield::from_fn(9, 9, 255, 25.5, |x, _| (x * 5) as u16).unwrap());
    assert_eq!(terrain.max_slope(), 0.5);
    let camera = Camera::look_at(
        [4.0, 4.0, 60.0],
        [4.0, 4.0, 20.0],
        [0.0, 1.0, 0.0],
        8.0,
        (12, 12),
    )
    .unwrap();
    for arith in ARITHS {
        let frame = render_by(
            Method::Runs,
            &terrain,
            camera,
            lighting([-1.0, 0.1, 0.2], true),
            arith,
            Culling::default(),
            2,
        );
        assert_eq!(frame.totals.primary_hits, 144, "{arith}");
        assert_eq!(
            frame.totals.shadow_rays, 144,
            "{arith}: every pixel casts a shadow ray"
        );
        assert_eq!(frame.totals.shadowed, 0, "{arith}: false shadows (acne)");
    }
}

/// A wall on flat ground with the sun low behind it: the contact shadow at the wall's foot is
/// found by every arithmetic exactly where exact arithmetic finds it.
#[test]
fn contact_shadows_are_kept_in_float_arithmetic() {
    let terrain = Terrain::new(
        Heightfield::from_fn(12, 12, 255, 25.5, |x, _| if x >= 6 { 200 } else { 0 }).unwrap(),
    );
    let camera = Camera::look_at(
        [3.0, 5.5, 80.0],
        [3.0, 5.5, 0.0],
        [0.0, 1.0, 0.0],
        6.0,
        (16, 16),
    )
    .unwrap();
    let sun = lighting([1.0, 0.0, 0.3], true);
    let exact = render_by(
        Method::Runs,
        &terrain,
        camera,
        sun,
        Arith::Exact,
        Culling::default(),
        2,
    );
    assert!(exact.totals.shadowed > 0, "the wall casts a shadow");
    for arith in [Arith::F32, Arith::F64] {
        let frame = render_by(
            Method::Runs,
            &terrain,
            camera,
            sun,
            arith,
            Culling::default(),
            2,
        );
        assert_eq!(frame.pixels, exact.pixels, "{arith}");
    }
}

/// The valley's creases, where a triangle facing the sun is shadowed by its neighbour just past
/// the shared edge: float shadow rays start above the surface by their rounding only, so they
/// find those shadows as exact arithmetic does (a start lifted much higher would lose many of
/// them on this view).
#[test]
fn shadows_at_creases_are_kept_in_float_arithmetic() {
    let scene = builtin_scene("valley513", 96);
    let terrain = Terrain::new(scene.field.clone());
    let render = |arith| {
        render_by(
            Method::Mipmap,
            &terrain,
            scene.camera,
            scene.lighting,
            arith,
            Culling::default(),
            2,
        )
    };
    let exact = render(Arith::Exact);
    assert!(exact.totals.shadowed > 200, "{}", exact.totals.shadowed);
    for arith in [Arith::F32, Arith::F64] {
        let frame = render(arith);
        let (got, want) = (frame.totals.shadowed, exact.totals.shadowed);
        assert!(
            got * 100 >= want * 95,
            "{arith}: {got} shadowed, exact {want}"
        );
        let differing = frame
            .pixels
            .iter()
            .zip(&exact.pixels)
            .filter(|(a, b)| a != b)
            .count();
        assert!(
            differing * 200 <= frame.pixels.len(),
            "{arith}: {differing} pixels differ"
        );
    }
}

/// A shadow ray from a terrace's top starts at the highest sample of the runs and cells around
/// it: intervals settle the run and cell tests there only if they hold the start's height
/// exactly, which they do on a flat triangle. Exact mode's `f64` walk answers most shadow
/// rays without them; not a ray whose path runs along a grid row, which it leaves to the
/// interval walk: so here the sun lies in the x-z plane. No pixel of this view of valley513
/// (terraced slopes, a flat crater floor) then needs its shadow ray cast again in rationals,
/// with any method. (Without the exact height, about one pixel in seven would, at a
/// millisecond each.)
#[test]
fn exact_shadow_rays_from_flat_ground_are_settled_by_intervals() {
    let mut scene = builtin_scene("valley513", 96);
    scene.lighting.sun = [0.6, 0.0, 0.8];
    let terrain = Terrain::new(scene.field.clone());
    for method in Method::ALL {
        let frame = render_exact(method, &scene, &terrain);
        assert!(
            frame.totals.shadow_rays > 1000,
            "{method}: shadow rays cast"
        );
        assert_eq!(
            frame.totals.redone, 0,
            "{method}: pixels cast again in rationals"
        );
    }
}

/// Exact mode decides a shadow ray's triangle test that intervals cannot settle exactly on its
/// own, from the exact hit point: the pixel, its shadow and the shadow ray's queries are those
/// of the pixel traced wholly in rationals. (In this view they are shadow rays that run within
/// 1e-14 of their start triangle's plane and meet its far edge within rounding.)
#[test]
fn shadow_ray_tests_decided_exactly_give_the_rational_pixel() {
    let scene = builtin_scene("valley513", 512);
    let terrain = Terrain::new(scene.field.clone());
    let shader = Shader::new(&terrain, scene.lighting, Method::Mipmap, Culling::default());
    let mut again = 0;
    for py in 0..512 {
        for px in 0..512 {
            let ray = scene.camera.ray(px, py);
            let sample = shader.recorded::<Settling>(&ray, None);
            if !sample.redone {
                continue;
            }
            again += 1;
            let rational = shader.recorded::<Plain<Exact>>(&ray, None);
            assert_eq!(
                (sample.rgb, sample.shadow, sample.primary, sample.secondary),
                (
                    rational.rgb,
                    rational.shadow,
                    rational.primary,
                    rational.secondary
                ),
                "pixel ({px}, {py})"
            );
        }
    }
    assert!(again > 0, "no shadow ray had a test decided exactly");
}

/// A sun that runs exactly in a slope's plane grazes it: every shadow ray runs along the
/// surface and touches it after its start, even one that starts on the last triangle before
/// the grid's edge (it runs along its own triangle), so the whole slope is in shadow in exact
/// arithmetic. Tilted up by a millionth of a millionth, each ray leaves the plane at once and
/// the slope is lit.
#[test]
fn a_sun_in_the_slope_plane_shadows_it_exactly() {
    // z = x, in whole steps.
    let slope = Terrain::new(Heightfield::from_fn(9, 9, 255, 255.0, |i, _| i as u16).unwrap());
    let whole_grid = Camera::look_at(
        [4.0, 4.0, 30.0],
        [4.0, 4.0, 0.0],
        [0.0, 1.0, 0.0],
        18.0,
        (32, 32),
    )
    .unwrap();
    let shadows = |sun: [f64; 3]| {
        let frame = render_by(
            Method::Mipmap,
            &slope,
            whole_grid,
            lighting(sun, true),
            Arith::Exact,
            // (The grazing sun does not face the slope: its shadow rays would be culled.)
            Culling {
                facing_away: false,
                ..Culling::default()
            },
            1,
        );
        (frame.totals.shadow_rays, frame.totals.shadowed)
    };
    let (cast, shadowed) = shadows([1.0, 0.0, 1.0]);
    assert!(cast > 500, "{cast} shadow rays");
    assert_eq!(shadowed, cast, "shadowed of cast, sun in the plane");
    let (cast, shadowed) = shadows([1.0, 0.0, 1.0 + 1e-12]);
    assert!(cast > 500, "{cast} shadow rays");
    assert_eq!(shadowed, 0, "shadowed, sun tilted");
}

/// A frame counts its pixels' rays straight into its totals and heat-map queries: the same
/// figures as each pixel's sample recorded on its own ([`Shader::traced`]) and added up, with
/// shadow rays, sky-light rays and water's reflected rays, in `f64` and exact arithmetic (where a pixel traced again
/// in rationals counts only that trace). The run walk traces every pixel without a clearance, as
/// a recorded sample is traced.
#[test]
fn a_frame_counts_what_its_samples_record() {
    let scene = builtin_scene("valley513", 40);
    let terrain = Terrain::new(scene.field.clone());
    let sky = Effects {
        sky_light: true,
        sky_rays: 4,
        ..Effects::default()
    };
    // A lake over the valley floor: its pixels cast reflected rays instead of shadow rays.
    let water = Effects {
        water: Some(heightray::render::effects::Water {
            level: 50.0,
            colour: [0.05, 0.2, 0.3],
        }),
        ..Effects::default()
    };
    for (effects, arith) in [
        (Effects::default(), Arith::F64),
        (Effects::default(), Arith::Exact),
        (sky, Arith::F64),
        (sky, Arith::Exact),
        (water, Arith::F64),
        (water, Arith::Exact),
    ] {
        let lighting = Lighting {
            effects,
            ..scene.lighting
        };
        let camera = scene.camera;
        let frame = render_by(
            Method::Runs,
            &terrain,
            camera,
            lighting,
            arith,
            Culling::default(),
            1,
        );
        let shader = Shader::new(&terrain, lighting, Method::Runs, Culling::default());
        let mut totals = heightray::render::FrameStats::default();
        let (width, height) = camera.size();
        for y in 0..height {
            for x in 0..width {
                let (sample, _) = shader.traced(&camera.ray(x, y), arith);
                let at = (y * width + x) as usize;
                assert_eq!(sample.rgb, frame.pixels[at], "({x}, {y}) {arith}");
                let stats = heightray::render::PixelStats::of(&sample);
                assert_eq!(stats, frame.stats[at], "({x}, {y}) {arith}");
                totals.add(&sample);
                totals.effects.add_pixel(1);
            }
        }
        assert_eq!(
            totals, frame.totals,
            "{arith} sky light {}",
            effects.sky_light
        );
        // Shadow rays and (with sky light) sky rays were counted.
        assert!(totals.shadow_rays > 100, "{arith}: {totals:?}");
        assert_eq!(
            totals.effects.sky_light.rays > 0,
            effects.sky_light,
            "{arith}"
        );
        let reflected = totals.effects.water.rays;
        assert_eq!(reflected > 0, effects.water.is_some(), "{arith}");
    }
}
