//! The renderer: determinism, golden images, a hand-computed shade, effect culling, no shadow
//! acne, and scene-file errors.
//!
//! Golden images are regenerated with `HEIGHTRAY_BLESS=1 cargo test --profile release-tests --test suite render::`.

use heightray::render::{
    Camera, Culling, Frame, Lighting, Normals, Ramp, Renderer, Scene, SceneFile, Shader,
};
use heightray::traverse::Exact;
use heightray::{Arith, Heightfield, Method, Terrain};
use std::path::{Path, PathBuf};

const ARITHS: [Arith; 4] = [
    Arith::F32,
    Arith::F64,
    Arith::Rational { bound: 1 << 16 },
    Arith::Exact,
];

fn render_by(
    method: Method,
    terrain: &Terrain,
    camera: Camera,
    lighting: Lighting,
    arith: Arith,
    culling: Culling,
    threads: usize,
) -> Frame {
    let renderer = Renderer {
        shader: Shader {
            terrain,
            lighting,
            method,
            culling,
        },
        camera,
        arith,
    };
    let (w, h) = camera.size();
    let mut frame = Frame::new(w, h);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| renderer.render(&mut frame));
    frame
}

/// A built-in scene file at a smaller size.
fn builtin_scene(name: &str, size: u32) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets")
        .join(format!("{name}.toml"));
    let mut file: SceneFile = toml::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    file.camera.width = size;
    file.camera.height = size;
    Scene::from_file(&file, path.parent().unwrap(), &path).unwrap()
}

/// The scene's view and light in exact arithmetic with `method`, on two threads.
fn render_exact(method: Method, scene: &Scene, terrain: &Terrain) -> Frame {
    let (camera, lighting) = (scene.camera, scene.lighting);
    render_by(
        method,
        terrain,
        camera,
        lighting,
        Arith::Exact,
        Culling::default(),
        2,
    )
}

/// The scene as its file says, with `method`.
fn render_scene_by(method: Method, scene: &Scene, threads: usize) -> Frame {
    let terrain = Terrain::new(scene.field.clone());
    render_by(
        method,
        &terrain,
        scene.camera,
        scene.lighting,
        scene.arith,
        Culling::default(),
        threads,
    )
}

/// The scene as its file says.
fn render_scene(scene: &Scene, threads: usize) -> Frame {
    render_scene_by(scene.method, scene, threads)
}

#[test]
fn same_image_and_statistics_on_one_and_two_threads() {
    for name in ["small49", "valley513"] {
        let scene = builtin_scene(name, 96);
        let (one, two) = (render_scene(&scene, 1), render_scene(&scene, 2));
        assert_eq!(one.pixels, two.pixels, "{name}");
        assert_eq!(one.stats, two.stats, "{name}");
        assert_eq!(one.totals, two.totals, "{name}");
        assert_eq!(
            one.totals.primary_rays,
            96 * 96,
            "every pixel traced exactly once"
        );
    }
}

/// `render` runs each tile's passes one after another; the viewer runs one pass at a time over
/// the whole frame, painting each pixel's block. Both end in the same frame; only the viewer
/// marches each tile's beam twice, once for each fine pass, where `render` marches it once for
/// both.
#[test]
fn a_frame_rendered_pass_by_pass_is_the_whole_frame() {
    let scene = builtin_scene("valley513", 80);
    let whole = render_scene(&scene, 2);
    let terrain = Terrain::new(scene.field.clone());
    let renderer = Renderer {
        shader: Shader {
            terrain: &terrain,
            lighting: scene.lighting,
            method: scene.method,
            culling: Culling::default(),
        },
        camera: scene.camera,
        arith: scene.arith,
    };
    let mut frame = Frame::new(80, 80);
    let mut passes = 0;
    while !frame.complete() {
        assert!(renderer.render_pass(&mut frame, &|| false));
        passes += 1;
    }
    assert_eq!(passes, 4);
    assert_eq!(frame.pixels, whole.pixels);
    assert_eq!(frame.stats, whole.stats);
    let once = whole.totals.primary.beam;
    assert!(
        once.hit + once.miss > 0,
        "the tiles' rays traced behind beams"
    );
    let mut marched_once = frame.totals;
    let twice = &mut marched_once.primary.beam;
    assert_eq!((twice.hit, twice.miss), (2 * once.hit, 2 * once.miss));
    *twice = once;
    assert_eq!(marched_once, whole.totals);
    // A pass after the last changes nothing.
    let done = frame.totals;
    assert!(renderer.render_pass(&mut frame, &|| false));
    assert_eq!(frame.totals, done);
}

#[test]
fn built_in_scenes_match_their_golden_images() {
    for (name, method) in ["small49", "valley513"]
        .into_iter()
        .flat_map(|name| Method::ALL.map(|method| (name, method)))
    {
        let frame = render_scene_by(method, &builtin_scene(name, 128), 2);
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/golden")
            .join(format!("{name}.png"));
        let rgb: Vec<u8> = frame
            .pixels
            .iter()
            .flat_map(|p| [(p >> 16) as u8, (p >> 8) as u8, *p as u8])
            .collect();
        if std::env::var_os("HEIGHTRAY_BLESS").is_some() && method == Method::ALL[0] {
            image::save_buffer(&path, &rgb, 128, 128, image::ColorType::Rgb8).unwrap();
        }
        let golden = image::open(&path)
            .unwrap_or_else(|e| {
                panic!("{}: {e}; regenerate with HEIGHTRAY_BLESS=1", path.display())
            })
            .to_rgb8();
        assert_eq!(golden.dimensions(), (128, 128));
        // Small tolerance: a channel may differ by 2 levels (libm differences), and at most
        // 0.5% of pixels may differ at all.
        let differing = golden
            .as_raw()
            .chunks(3)
            .zip(rgb.chunks(3))
            .filter(|(a, b)| a != b)
            .count();
        let worst = golden
            .as_raw()
            .iter()
            .zip(&rgb)
            .map(|(a, b)| a.abs_diff(*b))
            .max()
            .unwrap_or(0);
        assert!(
            worst <= 2 && differing * 200 <= 128 * 128,
            "{name} ({method}): {differing} pixels differ, worst by {worst}"
        );
    }
}

fn flat_field(level: u16) -> Terrain {
    Terrain::new(Heightfield::from_fn(9, 9, 255, 25.5, |_, _| level).unwrap())
}

fn lighting(sun: [f64; 3], shadows: bool) -> Lighting {
    let n = sun.iter().map(|c| c * c).sum::<f64>().sqrt();
    Lighting {
        sun: sun.map(|c| c / n),
        intensity: 1.0,
        ambient: 0.25,
        shadows,
        fog: 0.0,
        normals: Normals::Flat,
        ramp: Ramp::Gray,
    }
}

fn looking_down(size: u32) -> Camera {
    Camera::look_at(
        [4.0, 4.0, 30.0],
        [4.0, 4.0, 0.0],
        [0.0, 1.0, 0.0],
        10.0,
        (size, size),
    )
    .unwrap()
}

#[test]
fn flat_lit_plane_has_the_lambert_shade() {
    // Gray ramp on a flat field: albedo 0.25; light = ambient + intensity * (n . s) with
    // n = +z, so s_z = 0.8/|(0.4, 0.3, 0.8)|; then gamma 2.2 to 8 bits.
    let sun = [0.4, 0.3, 0.8];
    let s_z = 0.8 / (0.16f64 + 0.09 + 0.64).sqrt();
    let level = ((0.25 * (0.25 + s_z)).powf(1.0 / 2.2) * 255.0 + 0.5) as u32;
    let expected = level << 16 | level << 8 | level;
    for arith in ARITHS {
        let frame = render_by(
            Method::Runs,
            &flat_field(10),
            looking_down(8),
            lighting(sun, true),
            arith,
            Culling::default(),
            1,
        );
        assert!(
            frame.pixels.iter().all(|&p| p == expected),
            "{arith}: {:06x?} vs {expected:06x}",
            &frame.pixels[..4]
        );
    }
}

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
    let none = Culling {
        facing_away: false,
        no_shadow_possible: false,
        above_terrain: false,
    };
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
            facing_away: false,
            no_shadow_possible: false,
            above_terrain: false,
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

fn scene_error(text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, text).unwrap();
    match Scene::load(&path) {
        Ok(_) => panic!("scene loaded:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const GOOD: &str = r#"
[heightmap]
path = "builtin:small49"
z_scale = 12.0
[camera]
eye = [-10.0, -10.0, 30.0]
target = [24.0, 24.0, 0.0]
width = 16
height = 16
"#;

#[test]
fn scene_errors_name_the_key_and_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("good.toml");
    std::fs::write(&path, GOOD).unwrap();
    let scene = Scene::load(&path).unwrap();
    assert_eq!(scene.camera.size(), (16, 16));

    let unknown = scene_error(&GOOD.replace("width = 16", "width = 16\nfov = 30.0"));
    assert!(
        unknown.contains("fov") && unknown.contains("bad.toml"),
        "{unknown}"
    );
    let missing = scene_error(&GOOD.replace("z_scale = 12.0\n", ""));
    assert!(
        missing.contains("z_scale") && missing.contains("bad.toml"),
        "{missing}"
    );
    let unknown_section = scene_error(&format!("{GOOD}\n[lights]\nsun = 1\n"));
    assert!(unknown_section.contains("lights"), "{unknown_section}");
    let bad_method = scene_error(&format!("{GOOD}\n[render]\nmethod = \"bvh\"\n"));
    assert!(
        bad_method.contains("method") && bad_method.contains("bvh"),
        "{bad_method}"
    );
    let no_map = scene_error(&GOOD.replace("builtin:small49", "missing.png"));
    assert!(no_map.contains("missing.png"), "{no_map}");
    let bad_camera = scene_error(&GOOD.replace(
        "target = [24.0, 24.0, 0.0]",
        "target = [-10.0, -10.0, 30.0]",
    ));
    assert!(
        bad_camera.contains("camera") && bad_camera.contains("coincide"),
        "{bad_camera}"
    );
}

/// Exact frames are the same whichever method walks the grid: the mipmap's shadow rays start
/// where the camera rays hit exactly (not at an `f64` point), and an `f64` walk clears their
/// way with room for that; the run walk and the DDA follow every cell exactly.
#[test]
fn exact_frames_are_the_same_with_every_method() {
    for name in ["small49", "valley513"] {
        let scene = builtin_scene(name, 80);
        let terrain = Terrain::new(scene.field.clone());
        let render = |method| render_exact(method, &scene, &terrain);
        let mipmap = render(Method::Mipmap);
        assert!(mipmap.totals.shadow_rays > 1000, "{name}: shadow rays cast");
        assert!(mipmap.totals.shadowed > 0, "{name}: some pixels in shadow");
        for method in [Method::HierarchicalRuns, Method::Runs, Method::Dda] {
            let other = render(method);
            assert_eq!(
                (other.totals.primary_hits, other.totals.shadowed),
                (mipmap.totals.primary_hits, mipmap.totals.shadowed),
                "{name}, {method}: hits and shadows"
            );
            assert!(other.pixels == mipmap.pixels, "{name}, {method}: pixels");
        }
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
    let shader = Shader {
        terrain: &terrain,
        lighting: scene.lighting,
        method: Method::Mipmap,
        culling: Culling::default(),
    };
    let mut again = 0;
    for py in 0..512 {
        for px in 0..512 {
            let ray = scene.camera.ray(px, py);
            let sample = shader.sample_exact(&ray, None);
            if !sample.redone {
                continue;
            }
            again += 1;
            let rational = shader.sample::<Exact>(&ray, None);
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
