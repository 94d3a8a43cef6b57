//! Camera wedge profiles ([`Wedges`]): no camera ray touches the surface before its
//! clearance, and every ray called a certain miss misses, checked against the exact
//! reference's first hit (rationals over every cell, no mipmap or wedge involved) on random
//! terrains with holes and random cameras (the eye inside and outside the map, below and
//! above its highest point, looking straight down); and frames are pixel-identical with the
//! clearances on and off in `f32`, `f64` and exact arithmetic.

use crate::common::families::{hash, integer_hills};
use crate::common::random::Rng;
use crate::common::reference::{q, solve};
use heightray::bench::sized_scene;
use heightray::heightfield::{NoDataMask, Quantisation};
use heightray::render::{Camera, Culling, Frame, Lighting, Renderer, Shader};
use heightray::traverse::{Clearance, Wedges};
use heightray::{Arith, Heightfield, Method, Ray, Terrain};

/// A random field of `w x h` samples, a share of them no data (holes) where `holes`.
pub(crate) fn random_terrain(rng: &mut Rng, w: usize, h: usize, holes: bool) -> Terrain {
    let salt = rng.next();
    let top = [3u16, 40, 1000][rng.below(3)];
    let samples: Vec<u16> = (0..w * h)
        .map(|k| hash(k % w, k / w, salt, top + 1))
        .collect();
    let mut mask = NoDataMask::new(w * h);
    if holes {
        // (Never the first sample: a field must keep one.)
        for k in 1..w * h {
            if rng.below(6) == 0 {
                mask.insert(k);
            }
        }
    }
    let z_scale = [1.0, 10.0, 60.0][rng.below(3)];
    let field = Heightfield::new(
        w,
        h,
        samples,
        Quantisation::Maxval(top),
        z_scale,
        Some(mask),
    )
    .expect("a valid field");
    Terrain::new(field)
}

/// What the clearances of one camera's rays came to against the reference.
#[derive(Default)]
struct Tally {
    /// Rays that the reference says hit, and how many of them had a clearance.
    hits: usize,
    cleared_hits: usize,
    /// Rays that miss, and how many of them the wedges called certain misses.
    misses: usize,
    certain_misses: usize,
}

/// Checks every pixel's clearance in `wedges` against the exact first hit.
fn check_camera(name: &str, terrain: &Terrain, camera: &Camera, wedges: &Wedges) -> Tally {
    let (w, h) = camera.size();
    let mut tally = Tally::default();
    for y in 0..h {
        for x in 0..w {
            let ray = camera.ray(x, y);
            let (clearance, asked) = wedges.clearance(ray.origin(), ray.dir());
            assert!(asked.total() <= 1, "{name}: one look-up a ray");
            let hit = solve(terrain.field(), &ray).hit;
            let at = format!("{name}: pixel ({x}, {y}), ray {ray:?}");
            match (&hit, clearance) {
                (None, certain) => {
                    tally.misses += 1;
                    if certain.is_some_and(|c| c.t == f64::INFINITY) {
                        tally.certain_misses += 1;
                    }
                }
                (Some(hit), Some(Clearance { t, .. })) => {
                    assert!(
                        t.is_finite() && q(t) <= hit.t,
                        "{at} hits at {}, but its clearance is {t}",
                        hit.t
                    );
                    tally.hits += 1;
                    tally.cleared_hits += 1;
                }
                (Some(_), None) => tally.hits += 1,
            }
        }
    }
    tally
}

#[test]
fn no_camera_ray_hits_before_its_clearance_and_certain_misses_miss() {
    let mut rng = Rng(0x5745_4447_4553);
    let mut total = Tally::default();
    for case in 0..60 {
        let (w, h) = (2 + rng.below(30), 2 + rng.below(30));
        let terrain = random_terrain(&mut rng, w, h, case % 2 == 1);
        let (_, z_hi) = terrain.z_range();
        let (fw, fh) = (w as f64 - 1.0, h as f64 - 1.0);
        // Inside the map or around it, below the highest point or far above it.
        let outside = rng.below(2) == 0;
        let spread = if outside { 2.0 } else { 1.0 };
        let eye = [
            fw * (0.5 + spread * rng.within(-0.5, 0.5)),
            fh * (0.5 + spread * rng.within(-0.5, 0.5)),
            z_hi * rng.within(-0.2, 2.5) + rng.within(0.0, 3.0),
        ];
        let target = [
            rng.within(0.0, fw),
            rng.within(0.0, fh),
            rng.within(-0.5, 1.0) * z_hi,
        ];
        let fov = rng.within(10.0, 120.0);
        let Ok(camera) = Camera::look_at(eye, target, [0.0, 0.0, 1.0], fov, (10, 10)) else {
            continue;
        };
        for arith in [Arith::F32, Arith::F64, Arith::Exact] {
            let wedges = Wedges::new(&terrain, eye, arith).expect("wedges");
            let name = format!("case {case} ({w}x{h}, eye {eye:?}, {arith})");
            let tally = check_camera(&name, &terrain, &camera, &wedges);
            total.hits += tally.hits;
            total.cleared_hits += tally.cleared_hits;
            total.misses += tally.misses;
            total.certain_misses += tally.certain_misses;
        }
    }
    // The test saw both kinds of answer, and the wedges settled most of them.
    let (hits, misses) = (total.hits, total.misses);
    assert!(hits > 2000 && misses > 2000, "{hits} hits, {misses} misses");
    assert!(
        total.cleared_hits * 2 > hits,
        "{} of {hits} hits had a clearance",
        total.cleared_hits
    );
    assert!(
        total.certain_misses * 2 > misses,
        "{} of {misses} misses settled",
        total.certain_misses
    );
}

#[test]
fn hard_views_clear_only_what_is_clear() {
    let hills = integer_hills(13, 13, 6, 5);
    let views = [
        // Along grid lines and through lattice points from a lattice eye.
        ([0.0, 6.0, 9.0], [12.0, 6.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 10.0], [12.0, 12.0, 0.0], [0.0, 0.0, 1.0]),
        // Straight down from above the middle, and grazing level at the hills' top.
        ([6.0, 6.0, 40.0], [6.0, 6.0, 0.0], [0.0, 1.0, 0.0]),
        ([-3.0, 6.0, 6.0], [20.0, 6.0, 6.0], [0.0, 0.0, 1.0]),
        // Below the highest point, inside the map, and from far away.
        ([6.5, 6.5, 2.0], [0.0, 12.0, 3.0], [0.0, 0.0, 1.0]),
        ([-3.0e4, -2.0e4, 9.0e3], [6.0, 6.0, 3.0], [0.0, 0.0, 1.0]),
    ];
    for (eye, target, up) in views {
        let camera = Camera::look_at(eye, target, up, 40.0, (11, 11)).expect("a camera");
        let wedges = Wedges::new(&hills, eye, Arith::Exact).expect("wedges");
        check_camera(&format!("view from {eye:?}"), &hills, &camera, &wedges);
    }
}

#[test]
fn rays_the_wedges_cannot_tell_about_get_no_clearance() {
    let hills = integer_hills(9, 9, 8, 3);
    let eye = [4.0, 4.0, 20.0];
    let wedges = Wedges::new(&hills, eye, Arith::F64).expect("wedges");
    // Straight down, from elsewhere than the eye.
    assert_eq!(wedges.clearance(eye, [0.0, 0.0, -1.0]).0, None);
    assert_eq!(wedges.clearance([4.0, 4.0, 21.0], [1.0, 0.0, -1.0]).0, None);
    // Up and away: a certain miss, and nothing is looked up twice.
    let (up, asked) = wedges.clearance(eye, [1.0, 0.5, 1.0]);
    assert_eq!(up.map(|c| c.t), Some(f64::INFINITY));
    assert_eq!((asked.hit, asked.miss), (0, 1));
    // Bounded rationals round by steps of their own: no wedges.
    let rational = Arith::Rational { bound: 1 << 16 };
    assert!(Wedges::new(&hills, eye, rational).is_none());
}

/// Renders `camera`'s frame of `terrain` with the camera clearances on or off.
fn frame(terrain: &Terrain, camera: Camera, lighting: Lighting, arith: Arith, on: bool) -> Frame {
    let culling = Culling {
        camera_clearance: on,
        ..Culling::default()
    };
    let renderer = Renderer {
        shader: Shader::new(terrain, lighting, Method::Mipmap, culling),
        camera,
        arith,
    };
    let (w, h) = camera.size();
    let mut frame = Frame::new(w, h);
    renderer.render(&mut frame);
    frame
}

#[test]
fn frames_are_the_same_with_camera_clearances_on_and_off() {
    let scene = sized_scene(65, 24).expect("a scene");
    let mut rng = Rng(0x4f4e_4f46);
    let holed = random_terrain(&mut rng, 33, 29, true);
    let plain = Terrain::new(scene.field.clone());
    let look = |eye, target, fov| {
        Camera::look_at(eye, target, [0.0, 0.0, 1.0], fov, (24, 24)).expect("a camera")
    };
    let views = [
        (&plain, scene.camera),
        // Over the holed map, low and looking across it; from below its highest point.
        (&holed, look([16.0, -4.0, 30.0], [16.0, 20.0, 0.0], 60.0)),
        (&holed, look([16.0, 14.0, 5.0], [0.0, 28.0, 0.0], 90.0)),
    ];
    for (k, (terrain, camera)) in views.into_iter().enumerate() {
        for arith in [Arith::F32, Arith::F64, Arith::Exact] {
            let on = frame(terrain, camera, scene.lighting, arith, true);
            let off = frame(terrain, camera, scene.lighting, arith, false);
            assert_eq!(on.pixels, off.pixels, "view {k} in {arith}");
            let looked_up = on.totals.primary.wedge;
            assert_eq!(looked_up.total(), 24 * 24, "view {k} in {arith}");
            assert_eq!(off.totals.primary.wedge.total(), 0);
            // The clearances shorten the walks.
            let blocks = |f: &Frame| f.totals.primary.block.total();
            assert!(blocks(&on) < blocks(&off), "view {k} in {arith}");
        }
    }
}

#[test]
fn a_ray_over_a_map_seen_from_far_away_starts_near_it() {
    let rough = heightray::bench::sized_scene(33, 8).expect("a scene").field;
    let terrain = Terrain::new(rough);
    let eye = [-3.0e4, -2.0e4, 9.0e3];
    let wedges = Wedges::new(&terrain, eye, Arith::F64).expect("wedges");
    let ray = Ray::new(eye, [3.0e4 + 16.0, 2.0e4 + 16.0, -9.0e3]).expect("a ray");
    let hit = solve(terrain.field(), &ray)
        .hit
        .expect("aimed at the map's middle");
    let (clearance, _) = wedges.clearance(ray.origin(), ray.dir());
    let t = clearance.expect("a clearance").t;
    // The map is 32 cells across, 36,000 away: the walk starts within a few percent of it.
    assert!(
        q(t) <= hit.t && t > 0.99,
        "cleared to {t}, hit at {}",
        hit.t
    );
}

#[test]
fn adaptive_sample_rounds_start_from_clearances_and_give_the_same_frames() {
    let scene = sized_scene(65, 24).expect("a scene");
    let terrain = Terrain::new(scene.field.clone());
    let mut lighting = scene.lighting;
    lighting.effects.samples = 4;
    lighting.effects.adaptive = true;
    for arith in [Arith::F64, Arith::Exact] {
        let on = frame(&terrain, scene.camera, lighting, arith, true);
        let off = frame(&terrain, scene.camera, lighting, arith, false);
        assert_eq!(on.pixels, off.pixels, "{arith}");
        // Every sample of the rounds looked its clearance up, more than one a pixel.
        assert!(on.totals.primary.wedge.total() > 24 * 24, "{arith}");
        assert_eq!(off.totals.primary.wedge.total(), 0);
    }
}
