//! Whole frames with effects: each culling rule on or off gives the same image, one thread and
//! two agree, effects left off cost nothing, samples converge to a supersampled reference,
//! and comparisons with exact count what `render` shows.

use super::effects::shader;
use super::*;
use heightray::render::effects::Effects;

/// small49's scene with soft shadows, sky light looking 12 cells far and `samples` samples
/// per pixel.
fn effects_scene(samples: u32, adaptive: bool) -> Scene {
    let mut scene = builtin_scene("small49", 32);
    scene.lighting.effects = Effects {
        sun_angle_deg: 3.0,
        sun_rays: 8,
        sky_light: true,
        sky_rays: 8,
        sky_distance: 12.0,
        samples,
        adaptive,
        water: None,
    };
    scene
}

#[test]
fn each_effect_culling_rule_on_or_off_gives_the_same_image() {
    let scene = effects_scene(2, false);
    let terrain = Terrain::new(scene.field.clone());
    let render = |culling: Culling| {
        render_by(
            Method::Mipmap,
            &terrain,
            scene.camera,
            scene.lighting,
            Arith::F64,
            culling,
            2,
        )
    };
    let all = render(Culling::default());
    let none = super::NO_CULLING;
    for culling in [
        Culling {
            horizon_clear: false,
            ..Culling::default()
        },
        Culling {
            above_terrain: false,
            ..Culling::default()
        },
        Culling {
            cone_blocked: false,
            ..Culling::default()
        },
        Culling {
            near_walk: false,
            ..Culling::default()
        },
        none,
    ] {
        let frame = render(culling);
        assert_eq!(frame.pixels, all.pixels, "{culling:?}");
        let effects = (frame.totals.effects, all.totals.effects);
        assert!(effects.0.sky_light.rays >= effects.1.sky_light.rays);
        assert!(effects.0.soft_shadow.rays >= effects.1.soft_shadow.rays);
    }
    let (culled, brute) = (all.totals, render(none).totals);
    assert!(
        culled.effects.sky_light.rays < brute.effects.sky_light.rays,
        "the scene culls sky rays"
    );
    assert!(
        culled.skipped.horizon_clear > 0,
        "the scene settles whole cones"
    );
}

#[test]
fn effects_give_the_same_image_on_one_thread_and_two() {
    for scene in [effects_scene(8, true), effects_scene(3, false)] {
        let terrain = Terrain::new(scene.field.clone());
        let render = |threads| {
            render_by(
                Method::Mipmap,
                &terrain,
                scene.camera,
                scene.lighting,
                Arith::F64,
                Culling::default(),
                threads,
            )
        };
        let (one, two) = (render(1), render(2));
        assert_eq!(one.pixels, two.pixels);
        assert_eq!(one.totals, two.totals);
    }
}

#[test]
fn effects_off_cast_no_effect_rays_and_change_nothing() {
    let scene = builtin_scene("small49", 32);
    assert_eq!(scene.lighting.effects, Effects::default());
    let terrain = Terrain::new(scene.field.clone());
    let frame = render_scene_by(Method::Mipmap, &scene, 2);
    let effects = frame.totals.effects;
    assert_eq!(
        (
            effects.soft_shadow.rays,
            effects.sky_light.rays,
            effects.soft_shadow.points,
            effects.sky_light.points
        ),
        (0, 0, 0, 0)
    );
    assert_eq!(effects.samples.pixels, 32 * 32);
    assert_eq!(frame.totals.primary_rays, 32 * 32);
    // Adaptive sampling of one sample is one sample.
    let mut lighting = scene.lighting;
    lighting.effects.adaptive = true;
    let adaptive = render_by(
        Method::Mipmap,
        &terrain,
        scene.camera,
        lighting,
        Arith::F64,
        Culling::default(),
        2,
    );
    assert_eq!(adaptive.pixels, frame.pixels);
}

/// Linear light of a 0x00RRGGBB pixel by the display formula.
fn linear(rgb: u32) -> [f64; 3] {
    [16, 8, 0].map(|shift| (f64::from((rgb >> shift) as u8) / 255.0).powf(2.2))
}

/// The root mean square difference, in linear light, of `frame` from `reference` rendered 4
/// times larger and averaged over 4x4 blocks.
fn error_against(frame: &Frame, reference: &Frame) -> f64 {
    let (w, h) = (frame.width as usize, frame.height as usize);
    let mut sum = 0.0;
    for y in 0..h {
        for x in 0..w {
            let mut mean = [0.0; 3];
            for (dx, dy) in (0..16).map(|k| (k % 4, k / 4)) {
                let big = reference.pixels[(4 * y + dy) * 4 * w + 4 * x + dx];
                for (m, l) in mean.iter_mut().zip(linear(big)) {
                    *m += l / 16.0;
                }
            }
            let l = linear(frame.pixels[y * w + x]);
            sum += (0..3).map(|c| (l[c] - mean[c]).powi(2)).sum::<f64>();
        }
    }
    (sum / (3 * w * h) as f64).sqrt()
}

#[test]
fn samples_converge_to_the_supersampled_image() {
    let size = 24;
    let render_at = |size: u32, samples: u32, adaptive: bool| {
        let mut scene = builtin_scene("small49", size);
        scene.lighting.effects.samples = samples;
        scene.lighting.effects.adaptive = adaptive;
        render_scene_by(Method::Mipmap, &scene, 2)
    };
    let reference = render_at(4 * size, 1, false);
    let errors: Vec<f64> = [1, 4, 16]
        .map(|n| error_against(&render_at(size, n, false), &reference))
        .to_vec();
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
    // Adaptive: the error of 16 samples everywhere (within 1%) with under three quarters
    // of their camera rays.
    let adaptive = render_at(size, 16, true);
    let rays = adaptive.totals.primary_rays;
    assert!(4 * rays < 3 * u64::from(16 * size * size), "{rays}");
    let error = error_against(&adaptive, &reference);
    assert!(error <= 1.01 * errors[2], "{error} against {errors:?}");
}

/// Rounds of one sample, as the viewer adds them, end with `render`'s image: uniform, and
/// adaptive (which `render` takes a batch per pixel at a time).
#[test]
fn samples_added_in_rounds_give_the_rendered_image() {
    for (samples, adaptive) in [(5, false), (10, true)] {
        samples_in_rounds(samples, adaptive);
    }
}

fn samples_in_rounds(samples: u32, adaptive: bool) {
    let scene = effects_scene(samples, adaptive);
    let terrain = Terrain::new(scene.field.clone());
    let rendered = render_by(
        Method::Mipmap,
        &terrain,
        scene.camera,
        scene.lighting,
        Arith::F64,
        Culling::default(),
        2,
    );
    let renderer = Renderer {
        shader: shader(&terrain, scene.lighting),
        camera: scene.camera,
        arith: Arith::F64,
    };
    let (w, h) = scene.camera.size();
    let mut frame = Frame::new(w, h);
    let mut sums = heightray::render::Accumulation::new(w, h, samples);
    while !sums.complete() {
        assert!(renderer.accumulate(&mut sums, &mut frame, &|| false));
    }
    assert_eq!(frame.pixels, rendered.pixels, "{samples} samples");
    assert_eq!(frame.totals.primary_rays, rendered.totals.primary_rays);
    if adaptive {
        assert!(rendered.totals.primary_rays < u64::from(samples * w * h));
    } else {
        assert_eq!(sums.done, samples);
    }
}

#[test]
fn effect_keys_are_read_and_checked() {
    let with =
        |sections: &str| load_scene_text("effects.toml", &format!("{SMALL_SCENE}\n{sections}"));
    let scene = with(
        "[sun]\ndirection = [1.0, 0.0, 1.0]\nangle_deg = 0.53\nrays = 32\n\
         [effects]\nsky_light = true\nsky_rays = 8\nsky_distance = 20.5\n[render]\nsamples = 16\nadaptive = true\n",
    )
    .unwrap();
    let expected = Effects {
        sun_angle_deg: 0.53,
        sun_rays: 32,
        sky_light: true,
        sky_rays: 8,
        sky_distance: 20.5,
        samples: 16,
        adaptive: true,
        water: None,
    };
    assert_eq!(scene.lighting.effects, expected);
    for (sections, key) in [
        (
            "[sun]\ndirection = [1.0, 0.0, 1.0]\nangle_deg = -1.0\n",
            "angle_deg",
        ),
        (
            "[sun]\ndirection = [1.0, 0.0, 1.0]\nangle_deg = nan\n",
            "angle_deg",
        ),
        ("[effects]\nsky_rays = 0\n", "sky_rays"),
        ("[render]\nsamples = 5000\n", "samples"),
        ("[effects]\nsky_distance = 0.0\n", "sky_distance"),
        ("[effects]\nsky_distance = nan\n", "sky_distance"),
        ("[effects]\nsky_reach = 5.0\n", "sky_reach"),
    ] {
        let error = with(sections).unwrap_err();
        assert!(error.contains(key), "{error}");
    }
}

/// Effects against exact, as `bench accuracy` and the viewer measure them: each
/// arithmetic's row counts the pixels whose colour differs from the exact render and the
/// largest difference of a channel, as a byte-by-byte comparison of `Renderer::render`'s
/// images finds (adaptive samples taken as `render` takes them, not uniformly).
#[test]
fn effects_compared_with_exact_count_what_render_shows() {
    use heightray::render::{view_pixel_differences, View};
    // (More samples than the first batch, so adaptive pixels stop at different counts.)
    let scene = effects_scene(8, true);
    let terrain = Terrain::new(scene.field.clone());
    let view = View {
        terrain: &terrain,
        camera: scene.camera,
        lighting: scene.lighting,
        method: Method::Mipmap,
    };
    let ariths = [Arith::F32, Arith::F64, Arith::Exact];
    let rows = view_pixel_differences(&view, &ariths, &|| false, &mut |_| {}).unwrap();
    let renderer = |arith| Renderer {
        shader: shader(&terrain, scene.lighting),
        camera: scene.camera,
        arith,
    };
    let (w, h) = scene.camera.size();
    let render = |arith| {
        let mut frame = Frame::new(w, h);
        renderer(arith).render(&mut frame);
        frame
    };
    let exact = render(Arith::Exact);
    // The comparison's own renders are `render`'s images, cancellable.
    let mut cancellable = Frame::new(w, h);
    assert!(renderer(Arith::Exact).render_cancellable(&mut cancellable, &|| false));
    assert_eq!(cancellable.pixels, exact.pixels);
    for row in rows {
        let frame = render(row.arith);
        let pairs = frame.pixels.iter().zip(&exact.pixels);
        let differing = pairs.clone().filter(|(a, b)| a != b).count() as u64;
        let bytes = |rgb: u32| rgb.to_be_bytes();
        let largest = pairs
            .flat_map(|(a, b)| bytes(*a).into_iter().zip(bytes(*b)))
            .map(|(a, b)| a.abs_diff(b))
            .max()
            .unwrap_or(0);
        assert_eq!(row.differing, differing, "{}", row.arith);
        assert_eq!(row.largest_difference, largest, "{}", row.arith);
        assert_eq!(row.pixels, frame.pixels.len() as u64);
    }
}
