//! The near walk (the first cells of a ray walked one by one from its clearance, by the
//! short walk where it can, [`Tracer::walking_near`]) gives the block walk's answers: rays
//! from random points and clearances, a ray through a lattice point in its first cell, camera
//! rays from their wedge clearance, and occlusion rays from the surface with a short reach, on
//! random terrains with holes, with both hierarchical methods; and whole
//! frames with shadows, soft shadows and sky light are pixel-identical with it on and off in
//! `f32`, `f64` and exact arithmetic.

use crate::common::families;
use crate::common::random::Rng;
use crate::wedges::random_terrain;
use heightray::bench::sized_scene;
use heightray::render::effects::Effects;
use heightray::render::{Culling, Frame, Lighting, Renderer, Shader};
use heightray::traverse::{Clearance, Start, Tracer, Wedges};
use heightray::{Arith, Method, Ray, Terrain};

/// A direction with each component in `[-1, 1]`, not all near zero.
fn direction(rng: &mut Rng) -> [f64; 3] {
    loop {
        let d = [0, 1, 2].map(|_| rng.within(-1.0, 1.0));
        if d.iter().map(|c| c.abs()).sum::<f64>() > 0.1 {
            return d;
        }
    }
}

#[test]
fn rays_from_any_clearance_hit_the_same_walked_near_or_down_the_mipmap() {
    let mut rng = Rng(0x6e65_6172);
    let mut hits = 0;
    for case in 0..40 {
        let (w, h) = (17 + rng.below(30), 17 + rng.below(30));
        let terrain = random_terrain(&mut rng, w, h, case % 2 == 0);
        let (w, h) = (w as f64, h as f64);
        let (_, top) = terrain.z_range();
        for method in [Method::Mipmap, Method::HierarchicalRuns] {
            let tracer = Tracer::new(&terrain, method);
            for _ in 0..150 {
                let o = [
                    rng.within(0.0, w),
                    rng.within(0.0, h),
                    rng.within(0.0, top * 1.2),
                ];
                let Ok(ray) = Ray::new(o, direction(&mut rng)) else {
                    continue;
                };
                let clearance = Clearance {
                    t: rng.within(0.0, 2.0),
                    level: 0,
                };
                let first = |near: bool| {
                    let hit = tracer
                        .walking_near(near)
                        .trace::<f64>(&ray, Some(clearance));
                    hit.hit.map(|h| (h.t.to_bits(), h.cell, h.triangle))
                };
                let near = first(true);
                assert_eq!(near, first(false), "case {case}, {method:?}, {ray:?}");
                hits += usize::from(near.is_some());
            }
        }
    }
    // Both answers occur often.
    assert!((2_000..10_000).contains(&hits), "{hits} of 12,000 hit");
}

#[test]
fn camera_rays_from_their_clearance_hit_the_same_walked_near_or_down_the_mipmap() {
    let mut rng = Rng(0x7765_6467);
    let mut hits = 0;
    for case in 0..30 {
        let terrain = random_terrain(&mut rng, 33, 33, case % 2 == 1);
        let (_, top) = terrain.z_range();
        let eye = [
            rng.within(-4.0, 36.0),
            rng.within(-4.0, 36.0),
            top + rng.within(1.0, 31.0),
        ];
        let wedges = Wedges::new(&terrain, eye, Arith::F64).expect("wedges");
        for method in [Method::Mipmap, Method::HierarchicalRuns] {
            let tracer = Tracer::new(&terrain, method);
            for _ in 0..100 {
                let target = [
                    rng.within(0.0, 32.0),
                    rng.within(0.0, 32.0),
                    rng.within(0.0, top),
                ];
                let dir = [0, 1, 2].map(|k| target[k] - eye[k]);
                let Ok(ray) = Ray::new(eye, dir) else {
                    continue;
                };
                let (clearance, _) = wedges.clearance(eye, dir);
                let first = |near: bool| {
                    let hit = tracer.walking_near(near).trace::<f64>(&ray, clearance).hit;
                    hit.map(|h| (h.t.to_bits(), h.cell, h.triangle))
                };
                let near = first(true);
                assert_eq!(
                    near,
                    first(false),
                    "case {case}, {method:?}, towards {target:?}"
                );
                hits += usize::from(near.is_some());
            }
        }
    }
    assert!(hits > 3_000, "{hits} of 6,000 hit");
}

#[test]
fn occlusion_rays_with_a_reach_answer_the_same_walked_short_or_down_the_mipmap() {
    let mut rng = Rng(0x7368_6f72);
    let (mut asked, mut occluded, mut short, mut later) = (0, 0, 0, 0);
    for case in 0..40 {
        let (w, h) = (17 + rng.below(30), 17 + rng.below(30));
        let terrain = random_terrain(&mut rng, w, h, case % 2 == 0);
        let (_, top) = terrain.z_range();
        let (w, h) = (w as f64, h as f64);
        for method in [Method::Mipmap, Method::HierarchicalRuns] {
            let tracer = Tracer::new(&terrain, method);
            for _ in 0..100 {
                // From where a ray from above hits the surface (its own triangle left out),
                // towards a random direction, asked a few cells far, or across blocks the
                // short walk skips.
                let o = [rng.within(0.0, w), rng.within(0.0, h), top * 1.5 + 1.0];
                let target = [rng.within(0.0, w), rng.within(0.0, h), 0.0];
                let Ok(ray) = Ray::new(o, std::array::from_fn(|k| target[k] - o[k])) else {
                    continue;
                };
                let Some(found) = tracer.trace::<f64>(&ray, None).hit else {
                    continue;
                };
                let dir = direction(&mut rng);
                let reach = match rng.below(2) {
                    0 => rng.within(0.0, 5.0),
                    _ => rng.within(5.0, 60.0),
                };
                let from = Start::Hit {
                    ray: &ray,
                    hit: &found,
                };
                let answer = |near: bool| {
                    tracer
                        .within(reach)
                        .walking_near(near)
                        .occluded::<f64>(&from, dir, false)
                };
                let (walked_short, walked_down) = (answer(true), answer(false));
                assert_eq!(
                    walked_short.occluded, walked_down.occluded,
                    "case {case}, {method:?}, {ray:?} towards {dir:?} within {reach}"
                );
                asked += 1;
                occluded += usize::from(walked_short.occluded == Some(true));
                // (A ray the short walk gives back is walked down the mipmap alone.)
                short += usize::from(walked_short.counters != walked_down.counters);
                // Known clear before a point (the mipmap walk finds nothing up to it), the
                // ray walked short from there answers the same.
                let clear = rng.within(0.0, reach);
                let clear_to_there = tracer
                    .within(clear)
                    .walking_near(false)
                    .occluded::<f64>(&from, dir, false);
                if clear_to_there.occluded == Some(false) {
                    let from_there = tracer
                        .within(reach)
                        .clear_before(clear)
                        .occluded::<f64>(&from, dir, false);
                    assert_eq!(
                        from_there.occluded, walked_down.occluded,
                        "case {case}, {method:?}, {ray:?} towards {dir:?} within {reach}, clear before {clear}"
                    );
                    later += usize::from(from_there.counters.cell != walked_short.counters.cell);
                }
            }
        }
    }
    assert!(later * 4 > asked, "{later} of {asked} walked from later on");
    // Both answers occur often, and most rays take the short walk.
    assert!(
        occluded * 5 > asked && occluded * 5 < asked * 4,
        "{occluded} of {asked} occluded"
    );
    assert!(short * 2 > asked, "{short} of {asked} walked short");
}

/// A frame of `lighting` over `terrain`, walking near the surface or not.
fn frame(terrain: &Terrain, lighting: Lighting, arith: Arith, near_walk: bool) -> Frame {
    let scene = sized_scene(65, 20).expect("a scene");
    let culling = Culling {
        near_walk,
        ..Culling::default()
    };
    let renderer = Renderer {
        shader: Shader::new(terrain, lighting, Method::Mipmap, culling),
        camera: scene.camera,
        arith,
    };
    let mut frame = Frame::new(20, 20);
    renderer.render(&mut frame);
    frame
}

#[test]
fn frames_with_every_effect_are_the_same_walked_near_or_not() {
    let scene = sized_scene(65, 20).expect("a scene");
    let terrain = Terrain::new(scene.field.clone());
    let hard = scene.lighting;
    let effects = Effects {
        sun_angle_deg: 3.0,
        sun_rays: 8,
        sky_light: true,
        sky_rays: 8,
        sky_distance: 12.0,
        ..hard.effects
    };
    let soft = Lighting { effects, ..hard };
    for (name, lighting) in [("hard shadows", hard), ("soft shadows and sky", soft)] {
        for arith in [Arith::F32, Arith::F64, Arith::Exact] {
            let near = frame(&terrain, lighting, arith, true);
            let far = frame(&terrain, lighting, arith, false);
            assert_eq!(near.pixels, far.pixels, "{name} in {arith}");
            let (totals, effects) = (near.totals, near.totals.effects);
            let cast = totals.shadow_rays + effects.soft_shadow.rays + effects.sky_light.rays;
            assert!(cast > 0, "{name}: shadow and effect rays cast");
        }
    }
}

#[test]
fn a_ray_through_a_lattice_point_in_its_first_cell_touches_the_vertex_there() {
    // Flat at 0 but for the vertex (2, 2) at height 5 (one unit a sample); the ray runs
    // level at height 5 from (1.25, 1.5) and reaches x = 2 and y = 2 together at t = 1,
    // in its first cell: it touches the vertex there.
    let terrain = families::terrain(8, 8, 5, 5.0, |x, y| if (x, y) == (2, 2) { 5 } else { 0 });
    let ray = families::ray([1.25, 1.5, 5.0], [0.75, 0.5, 0.0]);
    let clearance = Clearance { t: 0.25, level: 0 };
    for method in [Method::Mipmap, Method::HierarchicalRuns] {
        let first = |near: bool| {
            let tracer = Tracer::new(&terrain, method).walking_near(near);
            let hit = tracer.trace::<f64>(&ray, Some(clearance)).hit;
            hit.map(|h| (h.t, h.cell, h.triangle))
        };
        let near = first(true);
        assert_eq!(near.map(|(t, ..)| t), Some(1.0), "{method:?}");
        assert_eq!(near, first(false), "{method:?}");
    }
}
