//! Soft shadows, sky light and several samples per pixel against analytic values and brute
//! force: the open sky's mean colour, a V valley's sky-view factor, a straight edge's
//! penumbra, convergence to a supersampled reference; each culling rule on or off gives the
//! same image, and effects left off cost nothing.

use super::*;
use heightray::arith::Plain;
use heightray::render::effects::Effects;
use heightray::render::Shadow;
use heightray::Ray;

/// A shader over `terrain` with `lighting`, the mipmap walk and every culling rule.
fn shader(terrain: &Terrain, lighting: Lighting) -> Shader<'_> {
    Shader {
        terrain,
        lighting,
        method: Method::Mipmap,
        culling: Culling::default(),
    }
}

/// Straight down onto `(x, y)` from above the terrain.
fn down_at(x: f64, y: f64) -> Ray {
    Ray::new([x, y, 500.0], [0.0, 0.0, -1.0]).unwrap()
}

/// Lighting with sky light of `rays` rays per point, looking for terrain without end, and
/// no sun.
fn sky_only(rays: u32) -> Lighting {
    let mut lighting = lighting([0.0, 0.0, 1.0], false);
    lighting.intensity = 0.0;
    lighting.effects = Effects {
        sky_light: true,
        sky_rays: rays,
        sky_distance: f64::INFINITY,
        ..Effects::default()
    };
    lighting
}

#[test]
fn an_open_plane_sees_the_analytic_mean_sky() {
    // The sky's gradient (shade.rs): horizon (0.78, 0.85, 0.93) to zenith (0.28, 0.46, 0.82)
    // by sqrt(sin(elevation)). Under cosine-weighted directions sin(elevation)^2 is uniform on
    // [0, 1], so the mean of sqrt(sin) is E[U^(1/4)] = 4/5.
    let horizon = [0.78, 0.85, 0.93];
    let zenith = [0.28, 0.46, 0.82];
    let mean: [f64; 3] = std::array::from_fn(|k| horizon[k] + 0.8 * (zenith[k] - horizon[k]));
    let brightness = mean.iter().sum::<f64>() / 3.0;
    let terrain = Terrain::new(Heightfield::from_fn(65, 65, 255, 25.5, |_, _| 10).unwrap());
    let (rays, points) = (64, 64);
    let lighting = sky_only(rays);
    let shader = shader(&terrain, lighting);
    let mut sum = [0.0; 3];
    for n in 0..points {
        let (x, y) = (8.0 + f64::from(n % 8) * 6.3, 8.0 + f64::from(n / 8) * 6.1);
        let (light, sky) = shader.sky_light_at(&down_at(x, y)).unwrap();
        assert_eq!(
            (sky.open, sky.of),
            (rays as u16, rays as u16),
            "nothing blocks"
        );
        for (k, s) in sum.iter_mut().enumerate() {
            *s += light[k] / lighting.ambient * brightness / f64::from(points);
        }
    }
    // Each ray's colour lies between the zenith's and the horizon's: with N independent rays
    // the standard error is at most (range / 2) / sqrt(N); the points' samples are rotated
    // independently and stratified within a point, which only lowers it. Four of those.
    let n = f64::from(rays * points);
    for k in 0..3 {
        let bound = 4.0 * (horizon[k] - zenith[k]) / 2.0 / n.sqrt();
        assert!(
            (sum[k] - mean[k]).abs() <= bound,
            "channel {k}: {} against {} (bound {bound})",
            sum[k],
            mean[k]
        );
    }
}

/// A valley along x: a flat floor `FLOOR` wide around y = 32, walls rising at 45 degrees for
/// `WALL` cells, plateaus beyond, on a 257 x 65 grid of unit steps and unit heights.
const FLOOR: f64 = 8.0;
const WALL: f64 = 24.0;

fn valley_height(y: f64) -> f64 {
    ((y - 32.0).abs() - FLOOR / 2.0).clamp(0.0, WALL)
}

/// The cosine-weighted sky fraction at floor point `(x, 32)` by brute force: the horizon's
/// elevation in each of 4096 azimuths by marching the analytic surface to the map's edge, or
/// `reach` away, in steps of 1/64, then the mean of `cos^2(horizon)`.
fn valley_sky_fraction(x: f64, reach: f64) -> f64 {
    let azimuths = 4096;
    (0..azimuths)
        .map(|k| {
            let phi = (f64::from(k) + 0.5) / f64::from(azimuths) * std::f64::consts::TAU;
            let (dx, dy) = (phi.cos(), phi.sin());
            let mut tan_horizon = 0.0f64;
            let mut r = 1.0 / 64.0;
            loop {
                let (qx, qy) = (x + r * dx, 32.0 + r * dy);
                let inside = (0.0..=256.0).contains(&qx) && (0.0..=64.0).contains(&qy);
                if !inside || r > reach {
                    break;
                }
                tan_horizon = tan_horizon.max(valley_height(qy) / r);
                r += 1.0 / 64.0;
            }
            1.0 / (1.0 + tan_horizon * tan_horizon)
        })
        .sum::<f64>()
        / f64::from(azimuths)
}

/// The valley's floor seen with sky rays that look `reach` far: the mean open share at 16
/// floor points and the brute-force fraction, and the Monte Carlo bound between them.
fn valley_floor_sky(reach: f64) -> (f64, f64, f64) {
    let field = Heightfield::from_fn(257, 65, 255, 255.0, |_, y| valley_height(y as f64) as u16);
    let terrain = Terrain::new(field.unwrap());
    let rays = 1024;
    let mut lighting = sky_only(rays);
    lighting.effects.sky_distance = reach;
    let shader = shader(&terrain, lighting);
    let xs: Vec<f64> = (0..16).map(|k| 120.0 + f64::from(k) * 1.07).collect();
    let measured = xs
        .iter()
        .map(|&x| {
            shader
                .sky_light_at(&down_at(x, 32.0))
                .unwrap()
                .1
                .open_share()
        })
        .sum::<f64>()
        / xs.len() as f64;
    let reference = xs
        .iter()
        .map(|&x| valley_sky_fraction(x, reach))
        .sum::<f64>()
        / xs.len() as f64;
    // Open or not per ray: the standard error of N independent rays is sqrt(v (1 - v) / N).
    let n = f64::from(rays) * xs.len() as f64;
    let bound = 4.0 * (reference * (1.0 - reference) / n).sqrt();
    (measured, reference, bound)
}

#[test]
fn a_v_valley_floor_sees_the_sky_fraction_of_its_horizon() {
    let (measured, reference, bound) = valley_floor_sky(f64::INFINITY);
    // An infinitely long valley of infinite 45-degree walls would give cos(45) = 0.7071; the
    // finite walls let more sky in.
    assert!(
        reference > std::f64::consts::FRAC_1_SQRT_2 && reference < 0.9,
        "{reference}"
    );
    assert!(
        (measured - reference).abs() <= bound,
        "{measured} against {reference} (bound {bound})"
    );
}

/// Sky rays that look 10 cells far see the walls' lower part only: the horizon of the
/// surface within 10 cells, by brute force; more sky than the whole walls leave.
#[test]
fn sky_rays_look_only_as_far_as_the_sky_distance() {
    let (measured, reference, bound) = valley_floor_sky(10.0);
    let (_, whole, _) = valley_floor_sky(f64::INFINITY);
    assert!(reference > whole + 0.05, "{reference} against {whole}");
    assert!(
        (measured - reference).abs() <= bound,
        "{measured} against {reference} (bound {bound})"
    );
}

/// Ground at height 0 for x up to 60, a plateau 20 high from x = 61 on: its edge at x = 61
/// casts a shadow towards -x from a sun in +x at `elevation_deg`.
fn edge_terrain() -> Terrain {
    Terrain::new(
        Heightfield::from_fn(128, 32, 255, 255.0, |x, _| if x >= 61 { 20 } else { 0 }).unwrap(),
    )
}

/// The share of the sun seen from ground points `x` (at y = 16.3) on [`edge_terrain`].
fn sun_seen(terrain: &Terrain, elevation_deg: f64, angle_deg: f64, xs: &[f64]) -> Vec<f64> {
    let e = elevation_deg.to_radians();
    let mut lighting = lighting([e.cos(), 0.0, e.sin()], true);
    lighting.effects.sun_angle_deg = angle_deg;
    lighting.effects.sun_rays = 256;
    let shader = shader(terrain, lighting);
    xs.iter()
        .map(|&x| {
            match shader
                .recorded::<Plain<f64>>(&down_at(x, 16.3), None)
                .shadow
            {
                Shadow::Soft(soft) => soft.visible(),
                Shadow::Cast { shadowed } => f64::from(u8::from(!shadowed)),
                Shadow::Skipped(_) | Shadow::NotAsked => 1.0,
            }
        })
        .collect()
}

#[test]
fn a_straight_edge_casts_a_penumbra_as_wide_as_the_sun() {
    let terrain = edge_terrain();
    let (elevation, angle, step) = (30.0f64, 2.0f64, 0.02);
    let xs: Vec<f64> = (0..2000).map(|k| 10.0 + f64::from(k) * step).collect();
    // The ground point at distance r from the edge sees it at elevation atan(20 / r): fully
    // lit below the disc's lowest edge, fully shadowed above its highest.
    let half = angle / 2.0;
    let lit_until = 61.0 - 20.0 / (elevation - half).to_radians().tan();
    let dark_from = 61.0 - 20.0 / (elevation + half).to_radians().tan();
    let seen = sun_seen(&terrain, elevation, angle, &xs);
    let first = |f: &dyn Fn(f64) -> bool| {
        xs.iter()
            .zip(&seen)
            .find(|(_, &s)| f(s))
            .map(|(&x, _)| x)
            .unwrap()
    };
    let (penumbra_start, dark_start) = (first(&|s| s < 1.0), first(&|s| s == 0.0));
    // Within a pixel of 0.1 units (five steps): the disc's outermost samples lie just
    // inside its rim.
    let pixel = 0.1;
    assert!(
        (penumbra_start - lit_until).abs() <= pixel,
        "{penumbra_start} against {lit_until}"
    );
    assert!(
        (dark_start - dark_from).abs() <= pixel,
        "{dark_start} against {dark_from}"
    );
    // About the distance along the sun's rays times the angle, seen on the ground.
    let along = 20.0 / elevation.to_radians().sin();
    let width = along * angle.to_radians().tan() / elevation.to_radians().sin();
    assert!(((dark_start - penumbra_start) - width).abs() <= pixel);

    // Angle 0: the hard shadow, whose edge lies where the disc's centre passes the edge.
    let hard = sun_seen(&terrain, elevation, 0.0, &xs);
    let edge = 61.0 - 20.0 / elevation.to_radians().tan();
    for (&x, &h) in xs.iter().zip(&hard) {
        assert!(h == 0.0 || h == 1.0);
        if (x - edge).abs() > step {
            assert_eq!(h == 1.0, x < edge, "hard shadow at {x}, edge at {edge}");
        }
    }
}

/// Behind the plateau's edge, cones settled as blocked whole by one more ray: each point's
/// colour and share of the sun are those of casting every direction, in every arithmetic.
#[test]
fn cones_settled_as_blocked_are_blocked_in_every_arithmetic() {
    let terrain = edge_terrain();
    let e = 30.0f64.to_radians();
    let mut lighting = lighting([e.cos(), 0.0, e.sin()], true);
    lighting.effects.sun_angle_deg = 2.0;
    lighting.effects.sun_rays = 16;
    let settling = shader(&terrain, lighting);
    let casting = Shader {
        culling: Culling {
            cone_blocked: false,
            ..Culling::default()
        },
        ..shader(&terrain, lighting)
    };
    // Fully shadowed from x = 61 - 20 / tan(31 degrees) = 27.7 on, lit below 24.9.
    let xs: Vec<f64> = (0..100).map(|k| 20.0 + f64::from(k) * 0.4).collect();
    for arith in [Arith::F32, Arith::F64, Arith::Exact] {
        let mut settled = 0;
        for &x in &xs {
            let ray = down_at(x, 16.3);
            let (with, without) = (
                settling.traced(&ray, arith).0,
                casting.traced(&ray, arith).0,
            );
            assert_eq!(with.rgb, without.rgb, "{arith} at {x}");
            let (Shadow::Soft(a), Shadow::Soft(b)) = (with.shadow, without.shadow) else {
                // Settled as clear by the same rules either way.
                assert_eq!(with.shadow, without.shadow, "{arith} at {x}");
                continue;
            };
            assert_eq!(a.clear, b.clear, "{arith} at {x}");
            assert!(!b.blocked);
            if a.blocked {
                settled += 1;
                assert!(x > 27.7, "{arith}: {x} is in the penumbra");
                assert_eq!((a.cast, b.cast), (1, 16), "{arith} at {x}");
            }
        }
        // Every point from 28 to 59.6 (the cliff's foot at 60).
        assert!(settled >= 78, "{arith}: {settled} settled");
    }
}

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
    let none = Culling {
        facing_away: false,
        no_shadow_possible: false,
        above_terrain: false,
        horizon_clear: false,
        cone_blocked: false,
    };
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
        none,
    ] {
        let frame = render(culling);
        assert_eq!(frame.pixels, all.pixels, "{culling:?}");
        let effects = (frame.totals.effects, all.totals.effects);
        assert!(effects.0.sky.rays >= effects.1.sky.rays);
        assert!(effects.0.soft.rays >= effects.1.soft.rays);
    }
    let (culled, brute) = (all.totals, render(none).totals);
    assert!(
        culled.effects.sky.rays < brute.effects.sky.rays,
        "the scene culls sky rays"
    );
    assert!(
        culled.skipped.horizon_clear > 0,
        "the scene settles whole cones"
    );
}

#[test]
fn effects_give_the_same_image_on_one_thread_and_two() {
    for scene in [effects_scene(4, true), effects_scene(3, false)] {
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
            effects.soft.rays,
            effects.sky.rays,
            effects.soft.points,
            effects.sky.points
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
    // Adaptive: fewer camera rays than 16 everywhere, and better than 4 everywhere.
    let adaptive = render_at(size, 16, true);
    let rays = adaptive.totals.primary_rays;
    assert!(rays < u64::from(16 * size * size), "{rays}");
    let error = error_against(&adaptive, &reference);
    assert!(error < errors[1], "{error} against {errors:?}");
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
    let mut sums = heightray::render::effects::Accumulation::new(w, h, samples);
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
