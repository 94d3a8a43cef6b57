//! Bounds kept for the terrain ahead of occlusion rays: the sun's strip bounds and the sky's
//! sector bounds. Every ray they call clear beyond a point touches no triangle from there on
//! (within the sky's reach), by the exact reference: suns along the axes, the diagonals, a
//! grid line, very steep and very low, sky rays in every sector, climbing and falling, from
//! their start where it lies well inside its triangle, on fields with holes,
//! plateaus and map edges. Frames are the same with the bounds on and off, and with bounds
//! kept from an earlier sun.

use crate::common::random::Rng;
use crate::common::reference::{first_touch, q, ExactField, ExactRay, Q};
use heightray::heightfield::{landscape, NoDataMask, Quantisation, SkyBounds, StripBounds};
use heightray::render::effects::Effects;
use heightray::render::{Camera, Culling, Frame, Lighting, Normals, Ramp, Renderer, Shader};
use heightray::{Arith, Heightfield, Method, Terrain};

/// Suns (grid directions) of every kind the bounds must handle.
pub(crate) const SUNS: [[f64; 3]; 10] = [
    [1.0, 0.0, 0.3],
    [-1.0, 0.0, 0.5],
    [0.0, 1.0, 0.2],
    [0.0, -1.0, 0.7],
    [1.0, 1.0, 0.4],
    [-1.0, 1.0, 0.25],
    [0.4, 0.3, 0.8],
    [-0.3, -0.9, 0.05],
    [0.2, 0.1, 6.0],
    [0.9, -0.2, 0.01],
];

/// A random field: rough, terraced (plateaus) or smooth, some with holes.
pub(crate) fn field(rng: &mut Rng, n: usize) -> Heightfield {
    let (w, h) = (n + rng.below(9), n + rng.below(9));
    let style = rng.below(3);
    let samples: Vec<u16> = (0..w * h)
        .map(|k| {
            let (i, j) = ((k % w) as f64, (k / w) as f64);
            match style {
                0 => rng.below(256) as u16,
                1 => (rng.below(4) * 60) as u16,
                _ => (127.0 + 60.0 * (i * 0.4).sin() * (j * 0.3).cos()) as u16,
            }
        })
        .collect();
    let mask = (rng.below(3) == 0).then(|| {
        let mut mask = NoDataMask::new(w * h);
        for _ in 0..(w * h / 10) {
            mask.insert(rng.below(w * h));
        }
        mask
    });
    let z_scale = [20.0, 255.0, 3.0][rng.below(3)];
    Heightfield::new(w, h, samples, Quantisation::Maxval(255), z_scale, mask).unwrap()
}

/// Whether the ray from `o` in `dir` touches any triangle of the field from `t` on (up to
/// `t_end`), exactly; cells the ray passes far above (by more than a unit of height) or far
/// beside are left out first.
pub(crate) fn touches(
    field: &Heightfield,
    exact: &ExactField,
    ray: ([f64; 3], [f64; 3]),
    t: f64,
    t_end: f64,
) -> bool {
    touches_other(field, exact, ray, (t, t_end), None)
}

/// [`touches`], leaving out triangle `own` (`(cell, triangle)`, the one a ray starts on).
pub(crate) fn touches_other(
    field: &Heightfield,
    exact: &ExactField,
    (o, dir): ([f64; 3], [f64; 3]),
    (t, t_end): (f64, f64),
    own: Option<([usize; 2], u8)>,
) -> bool {
    let ray = ExactRay {
        o: std::array::from_fn(|k| q(o[k]) + q(dir[k]) * q(t)),
        d: dir.map(q),
        dir,
    };
    let from = std::array::from_fn::<f64, 3, _>(|k| o[k] + dir[k] * t);
    for j in 0..field.height() - 1 {
        for i in 0..field.width() - 1 {
            let highest = [(0, 0), (1, 0), (0, 1), (1, 1)]
                .iter()
                .map(|&(a, b)| field.z(i + a, j + b))
                .fold(f64::NEG_INFINITY, f64::max);
            if passes_far_above(from, dir, [i as f64, j as f64], highest) {
                continue;
            }
            let within = |touch: &Q| t_end.is_infinite() || *touch <= q(t_end) - q(t);
            let touched = (0..2)
                .filter(|&k| own != Some(([i, j], k)))
                .any(|k| first_touch(exact, &ray, [i, j], k).is_some_and(|touch| within(&touch)));
            if touched {
                return true;
            }
        }
    }
    false
}

/// Whether the ray from `o` stays more than a unit above `highest` wherever its path comes
/// within a cell of the cell at `corner` (a filter with room far beyond rounding).
fn passes_far_above(o: [f64; 3], dir: [f64; 3], corner: [f64; 2], highest: f64) -> bool {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for k in 0..2 {
        let (lo, hi) = (corner[k] - 1.0, corner[k] + 2.0);
        if dir[k] == 0.0 {
            if o[k] < lo || o[k] > hi {
                return true;
            }
            continue;
        }
        let (a, b) = ((lo - o[k]) / dir[k], (hi - o[k]) / dir[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    let lowest = if dir[2] < 0.0 { t1 } else { t0 };
    t0 > t1 || o[2] + dir[2] * lowest > highest + 1.0
}

#[test]
fn rays_called_clear_beyond_a_point_touch_nothing_from_there_on() {
    let mut rng = Rng(0x005e_ed0f_5742);
    let (mut asked, mut clear) = (0, 0);
    for round in 0..14 {
        let field = if round == 0 {
            landscape(33, 3, 12.0).unwrap()
        } else {
            field(&mut rng, 8 + round)
        };
        let exact = ExactField::new(&field);
        for sun in SUNS {
            let bounds = StripBounds::build(&field, sun, 0.0).expect("the sun climbs");
            for _ in 0..40 {
                let start = start_on(&field, &mut rng);
                asked += 1;
                let Some(t) = bounds.clear_beyond(start, sun, 0.0) else {
                    continue;
                };
                clear += 1;
                assert!(
                    !touches(&field, &exact, (start, sun), t, f64::INFINITY),
                    "round {round}, sun {sun:?}, start {start:?}: touches the surface beyond t = {t}"
                );
            }
        }
    }
    // A good share of the rays is settled: the test is not vacuous.
    assert!(clear * 3 > asked, "{clear} of {asked} rays called clear");
}

/// A random point on the surface of `field` (or a little or well above it).
pub(crate) fn start_on(field: &Heightfield, rng: &mut Rng) -> [f64; 3] {
    let (x, y) = (
        rng.within(0.0, (field.width() - 1) as f64),
        rng.within(0.0, (field.height() - 1) as f64),
    );
    let (i, j) = (
        (x as usize).min(field.width() - 2),
        (y as usize).min(field.height() - 2),
    );
    let ground = field.surface_z((i, j), (x - i as f64, y - j as f64));
    [x, y, ground + [0.0, 0.0, 0.3, 5.0][rng.below(4)]]
}

/// One field's sky bounds for one reach, with what the checks need.
pub(crate) struct SkyCase<'a> {
    pub field: &'a Heightfield,
    pub exact: &'a ExactField,
    pub terrain: &'a Terrain,
    pub bounds: &'a SkyBounds,
}

/// `check` (given the round and the reach) on sky bounds for reaches unlimited, 9 and 20 over `rounds` fields: a landscape,
/// then random ones of growing size (rough, terraced or smooth, some with holes).
pub(crate) fn each_sky_bounds(
    rng: &mut Rng,
    rounds: usize,
    mut check: impl FnMut(&mut Rng, (usize, f64), SkyCase<'_>),
) {
    for round in 0..rounds {
        let field = if round == 0 {
            landscape(33, 5, 12.0).unwrap()
        } else {
            field(rng, 10 + 2 * round)
        };
        let exact = ExactField::new(&field);
        let terrain = Terrain::new(field.clone());
        for reach in [f64::INFINITY, 9.0, 20.0] {
            let bounds = SkyBounds::new(&terrain, reach).expect("a reach beyond the walked part");
            let (field, exact, terrain, bounds) = (&field, &exact, &terrain, &bounds);
            let case = SkyCase {
                field,
                exact,
                terrain,
                bounds,
            };
            check(rng, (round, reach), case);
        }
    }
}

#[test]
fn sky_rays_called_clear_beyond_a_point_touch_nothing_from_there_on_within_the_reach() {
    let mut rng = Rng(0x0051_7a11_b0d5);
    let (mut asked, mut clear) = (0, 0);
    each_sky_bounds(&mut rng, 10, |rng, (round, reach), case| {
        for _ in 0..60 {
            let start = start_on(case.field, rng);
            let azimuth = rng.within(0.0, std::f64::consts::TAU);
            // Along the axes and the sectors' edges too.
            let azimuth = match rng.below(3) {
                0 => (azimuth / std::f64::consts::FRAC_PI_8).round() * std::f64::consts::FRAC_PI_8,
                _ => azimuth,
            };
            let climb = [-0.4, -0.05, 0.02, 0.2, 0.7, 2.5][rng.below(6)];
            let dir = [azimuth.cos(), azimuth.sin(), climb];
            asked += 1;
            let unsettled = case.bounds.unsettled(case.terrain, start, dir, 0.0, None);
            // (Without a near start, the near part is always left to walk.)
            let part = unsettled.expect("a near part to walk");
            assert_eq!(part.from, 0.0);
            let Some(t) = part.to else {
                continue;
            };
            clear += 1;
            let t_end = reach / dir[0].hypot(dir[1]);
            assert!(
                !touches(case.field, case.exact, (start, dir), t, t_end),
                "round {round}, reach {reach}, dir {dir:?}, start {start:?}: touches the surface beyond t = {t}"
            );
        }
    });
    assert!(clear * 4 > asked, "{clear} of {asked} rays called clear");
}

#[test]
fn a_sun_that_does_not_climb_or_a_flat_field_builds_no_bounds() {
    let field = landscape(17, 1, 8.0).unwrap();
    assert!(StripBounds::build(&field, [1.0, 0.0, 0.0], 0.0).is_none());
    assert!(StripBounds::build(&field, [1.0, 0.5, -0.1], 0.0).is_none());
    assert!(StripBounds::build(&field, [0.0, 0.0, 1.0], 0.0).is_none());
    assert!(StripBounds::build(&field, [f64::NAN, 0.0, 1.0], 0.0).is_none());
    let flat = Heightfield::from_fn(9, 9, 255, 0.0, |_, _| 7).unwrap();
    assert!(StripBounds::build(&flat, [1.0, 0.0, 0.5], 0.0).is_none());
}

fn render(terrain: &Terrain, sun: [f64; 3], arith: Arith, culling: Culling) -> Frame {
    render_with(terrain, sun, Effects::default(), arith, culling)
}

pub(crate) fn render_with(
    terrain: &Terrain,
    sun: [f64; 3],
    effects: Effects,
    arith: Arith,
    culling: Culling,
) -> Frame {
    let lighting = Lighting {
        sun: Lighting::unit(sun),
        intensity: 1.0,
        ambient: 0.25,
        shadows: true,
        fog: 0.0,
        normals: Normals::Flat,
        ramp: Ramp::Gray,
        effects,
        base: heightray::render::BaseStyle::default(),
    };
    let (eye, target, up) = ([-12.0, -20.0, 40.0], [32.0, 32.0, 4.0], [0.0, 0.0, 1.0]);
    let camera = Camera::look_at(eye, target, up, 45.0, (64, 64)).unwrap();
    let renderer = Renderer {
        shader: Shader::new(terrain, lighting, Method::Mipmap, culling),
        camera,
        arith,
    };
    let mut frame = Frame::new(64, 64);
    renderer.render(&mut frame);
    frame
}

#[test]
fn frames_are_the_same_with_strip_bounds_on_and_off() {
    let terrain = Terrain::new(landscape(65, 7, 16.0).unwrap());
    let off = Culling {
        far_bounds: false,
        ..Culling::default()
    };
    for arith in [Arith::F32, Arith::F64, Arith::Exact] {
        for sun in [[0.4, 0.3, 0.5], [-1.0, 0.0, 0.3], [0.7, -0.7, 0.2]] {
            let on = render(&terrain, sun, arith, Culling::default());
            let walked = render(&terrain, sun, arith, off);
            assert_eq!(on.pixels, walked.pixels, "{arith:?}, sun {sun:?}");
            assert!(
                on.totals.shadow.bound.miss > 0,
                "{arith:?}, sun {sun:?}: the bounds settle rays"
            );
            assert_eq!(walked.totals.shadow.bound.total(), 0);
            assert!(
                on.totals.shadowed > 0,
                "{arith:?}, sun {sun:?}: has shadows"
            );
        }
    }
}

#[test]
fn soft_shadow_frames_are_the_same_with_strip_bounds_on_and_off() {
    let terrain = Terrain::new(landscape(65, 7, 16.0).unwrap());
    let off = Culling {
        far_bounds: false,
        ..Culling::default()
    };
    for (sun_angle_deg, sun_rays) in [(0.53, 8), (4.0, 16)] {
        let effects = Effects {
            sun_angle_deg,
            sun_rays,
            ..Effects::default()
        };
        for arith in [Arith::F32, Arith::F64, Arith::Exact] {
            for sun in [[0.4, 0.3, 0.5], [-1.0, 0.0, 0.3], [0.7, -0.7, 0.2]] {
                let on = render_with(&terrain, sun, effects, arith, Culling::default());
                let walked = render_with(&terrain, sun, effects, arith, off);
                let what = format!("{arith:?}, sun {sun:?}, disc {sun_angle_deg} deg");
                assert_eq!(on.pixels, walked.pixels, "{what}");
                assert!(
                    on.totals.shadow.bound.miss > 0,
                    "{what}: the bounds settle rays"
                );
                assert_eq!(walked.totals.shadow.bound.total(), 0);
            }
        }
    }
}

#[test]
fn bounds_kept_from_another_sun_give_the_frame_of_fresh_ones() {
    let field = landscape(65, 9, 16.0).unwrap();
    let kept = Terrain::new(field.clone());
    let (first, second) = ([0.4, 0.3, 0.5], [-0.2, 0.9, 0.3]);
    let _ = render(&kept, first, Arith::F64, Culling::default());
    let moved = render(&kept, second, Arith::F64, Culling::default());
    let fresh = render(&Terrain::new(field), second, Arith::F64, Culling::default());
    assert_eq!(moved.pixels, fresh.pixels);
    assert_eq!(moved.totals, fresh.totals);
}

/// Sky-light frames with `off` and with every rule on, in each arithmetic (exact too), for a
/// few sky rays and distances: the same pixels; `check` looks at the frame with every rule
/// on.
pub(crate) fn sky_frames_the_same_with(off: Culling, check: impl Fn(&Frame, &str, Arith, f64)) {
    let terrain = Terrain::new(landscape(65, 7, 16.0).unwrap());
    for (sky_rays, sky_distance) in [(16, 64.0), (4, 12.0), (8, f64::INFINITY)] {
        let effects = Effects {
            sky_light: true,
            sky_rays,
            sky_distance,
            ..Effects::default()
        };
        for arith in [Arith::F32, Arith::F64, Arith::Exact] {
            let sun = [0.4, 0.3, 0.5];
            let on = render_with(&terrain, sun, effects, arith, Culling::default());
            let walked = render_with(&terrain, sun, effects, arith, off);
            let what = format!("{arith:?}, {sky_rays} rays to {sky_distance}");
            assert_eq!(on.pixels, walked.pixels, "{what}");
            check(&on, &what, arith, sky_distance);
        }
    }
}

#[test]
fn sky_light_frames_are_the_same_with_sky_bounds_on_and_off() {
    let off = Culling {
        far_bounds: false,
        ..Culling::default()
    };
    sky_frames_the_same_with(off, |on, what, arith, _| {
        // (`f32`'s room for the rounding of its start is too wide to settle many.)
        if arith != Arith::F32 {
            let bound = on.totals.effects.sky_light.queries.bound;
            assert!(bound.miss > 0, "{what}: the sky's bounds settle rays");
        }
    });
}

/// Probes under the surface settle sky rays as blocked without changing a pixel: the walk,
/// in each arithmetic, finds every ray they settle blocked.
#[test]
fn sky_light_frames_are_the_same_with_probes_on_and_off() {
    let off = Culling {
        probes: false,
        ..Culling::default()
    };
    sky_frames_the_same_with(off, |on, what, arith, sky_distance| {
        if arith != Arith::F32 && sky_distance.is_finite() {
            let probed = on.totals.effects.sky_light.probed_blocked;
            assert!(probed > 0, "{what}: probes settle rays");
        }
    });
}
