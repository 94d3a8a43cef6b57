//! Smooth normals and shadows agree: a convex bump lit at a grazing angle has no shadowed
//! triangles on the side its smooth shading lights.

use heightray::render::effects::Effects;
use heightray::render::{Camera, Culling, Frame, Lighting, Normals, Ramp, Renderer, Shader};
use heightray::{trace, Arith, Heightfield, Method, Terrain, TraceOptions};

/// Radius and height of the cap, and its centre, in samples.
const RADIUS: f64 = 8.0;
const TOP: f64 = 7.0;
const CENTRE: f64 = 12.0;

/// A paraboloid cap `z = TOP (1 - r²/RADIUS²)` on flat ground: a coarse mesh of a smooth
/// convex surface. Where its tangent plane faces the sun, nothing of the cap rises above that
/// plane, so no point of the cap whose normal faces the sun is in shadow.
fn cap() -> Terrain {
    let field = Heightfield::from_fn(25, 25, 65535, TOP, |i, j| {
        let r2 = (i as f64 - CENTRE).powi(2) + (j as f64 - CENTRE).powi(2);
        let z = (1.0 - r2 / (RADIUS * RADIUS)).max(0.0);
        (z * 65535.0).round() as u16
    });
    Terrain::new(field.unwrap())
}

fn looking_down(size: u32) -> Camera {
    Camera::look_at(
        [CENTRE, CENTRE, 200.0],
        [CENTRE, CENTRE, 0.0],
        [0.0, 1.0, 0.0],
        5.8,
        (size, size),
    )
    .unwrap()
}

fn render(terrain: &Terrain, camera: Camera, arith: Arith, shadows: bool) -> Frame {
    // Ten degrees above the horizon, and off the grid's axes and diagonals.
    let sun = [-1.0f64, -0.35, 0.19];
    let length = sun.iter().map(|c| c * c).sum::<f64>().sqrt();
    let lighting = Lighting {
        sun: sun.map(|c| c / length),
        intensity: 1.0,
        ambient: 0.25,
        shadows,
        fog: 0.0,
        normals: Normals::Smooth,
        ramp: Ramp::Gray,
        effects: Effects::default(),
        base: heightray::render::BaseStyle::default(),
    };
    let renderer = Renderer {
        shader: Shader::new(terrain, lighting, Method::Mipmap, Culling::default()),
        camera,
        arith,
    };
    let (w, h) = camera.size();
    let mut frame = Frame::new(w, h);
    renderer.render(&mut frame);
    frame
}

/// The pixels that see the cap well inside its rim (where the vertex normals still belong
/// to the paraboloid, not to the crease around its foot).
fn on_the_cap(terrain: &Terrain, camera: Camera) -> Vec<usize> {
    let (w, h) = camera.size();
    let options = TraceOptions::new(Method::Mipmap, Arith::F64);
    (0..w * h)
        .filter(|&k| {
            let ray = camera.ray(k % w, k / w);
            trace(terrain, &ray, &options).hit.is_some_and(|hit| {
                let [x, y, _] = hit.point;
                (x - CENTRE).hypot(y - CENTRE) < RADIUS - 1.5
            })
        })
        .map(|k| k as usize)
        .collect()
}

/// How much darker than the unshadowed render each cap pixel is, worst first: (pixel, levels).
fn darkened(on: &Frame, off: &Frame, cap: &[usize]) -> Vec<(usize, u8)> {
    let green = |p: u32| (p >> 8) as u8;
    let mut dark: Vec<(usize, u8)> = cap
        .iter()
        .map(|&k| (k, green(off.pixels[k]).saturating_sub(green(on.pixels[k]))))
        .filter(|&(_, d)| d > 0)
        .collect();
    dark.sort_by_key(|&(_, d)| std::cmp::Reverse(d));
    dark
}

#[test]
fn a_convex_bump_under_a_grazing_sun_has_no_shadowed_triangles() {
    let terrain = cap();
    let camera = looking_down(160);
    let cap = on_the_cap(&terrain, camera);
    assert!(cap.len() > 5000, "{} pixels on the cap", cap.len());
    for arith in [Arith::F32, Arith::F64, Arith::Exact] {
        let on = render(&terrain, camera, arith, true);
        let off = render(&terrain, camera, arith, false);
        let dark = darkened(&on, &off, &cap);
        assert!(
            on.totals.shadow_rays > 1000,
            "{arith}: the cap casts shadow rays"
        );
        assert!(
            on.totals.shadowed > 500,
            "{arith}: the cap still shadows the ground behind it"
        );
        assert!(
            dark.is_empty(),
            "{arith}: {} of {} pixels of the cap darker with shadows, worst (pixel, levels): {:?}",
            dark.len(),
            cap.len(),
            &dark[..dark.len().min(8)]
        );
    }
}
