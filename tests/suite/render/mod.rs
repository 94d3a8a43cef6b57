//! The renderer: determinism, golden images, a hand-computed shade, scene-file errors, and
//! exact frames; shadow rays and their culling in [`shadows`].
//!
//! Golden images are regenerated with `HEIGHTRAY_BLESS=1 cargo test --profile release-tests --test suite render::`.

use crate::common::scenes::{load_scene_text, SMALL_SCENE};
use heightray::arith::Exact;
use heightray::render::effects::Effects;
use heightray::render::{
    Camera, Culling, Frame, Lighting, Normals, Ramp, Renderer, Scene, SceneFile, Shader,
};
use heightray::{Arith, Heightfield, Method, Terrain};
use std::path::{Path, PathBuf};

/// Every culling rule off: the frames each rule must reproduce.
pub(crate) const NO_CULLING: Culling = Culling {
    facing_away: false,
    no_shadow_possible: false,
    above_terrain: false,
    horizon_clear: false,
    cone_blocked: false,
    far_bounds: false,
    probes: false,
    near_slopes: false,
    camera_clearance: false,
    near_walk: false,
};

mod base;
mod effects;
mod effects_frames;
mod shadows;

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
        shader: Shader::new(terrain, lighting, method, culling),
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
    file.size = Some((size, size));
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
/// the whole frame, painting each pixel's block. Both end in the same frame, the same
/// statistics (one wedge look-up per camera ray) included.
#[test]
fn a_frame_rendered_pass_by_pass_is_the_whole_frame() {
    let scene = builtin_scene("valley513", 80);
    let whole = render_scene(&scene, 2);
    let terrain = Terrain::new(scene.field.clone());
    let renderer = Renderer {
        shader: Shader::new(&terrain, scene.lighting, scene.method, Culling::default()),
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
    let looked_up = whole.totals.primary.wedge;
    assert_eq!(
        looked_up.total(),
        80 * 80,
        "one wedge look-up per camera ray"
    );
    assert_eq!(frame.totals, whole.totals);
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
        effects: Effects::default(),
        base: heightray::render::BaseStyle::default(),
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

/// The message a scene file's text is refused with.
fn scene_error(text: &str) -> String {
    match load_scene_text("bad.toml", text) {
        Ok(_) => panic!("scene loaded:\n{text}"),
        Err(e) => e,
    }
}

#[test]
fn scene_errors_name_the_key_and_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("good.toml");
    std::fs::write(&path, SMALL_SCENE).unwrap();
    let scene = Scene::load(&path).unwrap();
    assert_eq!(scene.camera.size(), (16, 16));

    let unknown = scene_error(&SMALL_SCENE.replace("width = 16", "width = 16\nfov = 30.0"));
    assert!(
        unknown.contains("fov") && unknown.contains("bad.toml"),
        "{unknown}"
    );
    // Only the map's path is required; a built-in without z_scale keeps its own.
    let missing = scene_error(&SMALL_SCENE.replace("path = \"builtin:small49\"\n", ""));
    assert!(
        missing.contains("path") && missing.contains("bad.toml"),
        "{missing}"
    );
    let own_scale = load_scene_text("good.toml", &SMALL_SCENE.replace("z_scale = 12.0\n", ""));
    let builtin = heightray::heightfield::Builtin::named("small49").unwrap();
    assert_eq!(own_scale.unwrap().field.z_scale(), builtin.z_scale);
    let unknown_section = scene_error(&format!("{SMALL_SCENE}\n[lights]\nsun = 1\n"));
    assert!(unknown_section.contains("lights"), "{unknown_section}");
    let bad_method = scene_error(&format!("{SMALL_SCENE}\n[render]\nmethod = \"bvh\"\n"));
    assert!(
        bad_method.contains("method") && bad_method.contains("bvh"),
        "{bad_method}"
    );
    let no_map = scene_error(&SMALL_SCENE.replace("builtin:small49", "missing.png"));
    assert!(no_map.contains("missing.png"), "{no_map}");
    let bad_camera = scene_error(&SMALL_SCENE.replace(
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
