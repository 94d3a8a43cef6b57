//! Near slopes: a ray that starts well inside its own flat triangle and climbs faster than
//! the triangles around it can rise is settled over its first cells with no walk. Every ray
//! called clear from its start touches no triangle but its own, by the exact reference (sky
//! rays rising and falling in every sector, the sun's rays and its disc's, on fields with
//! holes, plateaus and map edges); frames are the same with the slopes on and off.

use crate::common::random::Rng;
use crate::common::reference::ExactField;
use crate::far_bounds::{
    each_sky_bounds, field, render_with, sky_frames_the_same_with, touches_other, SUNS,
};
use heightray::heightfield::{landscape, NearStart, StripBounds};
use heightray::render::effects::Effects;
use heightray::render::Culling;
use heightray::{Arith, Heightfield, Terrain};

/// A point well inside triangle `k` of a random cell of `field`, on its plane.
fn start_inside(field: &Heightfield, rng: &mut Rng) -> ((usize, usize), u8, [f64; 3]) {
    let cell = (rng.below(field.width() - 1), rng.below(field.height() - 1));
    let k = rng.below(2) as u8;
    let (a, b) = (rng.within(0.0, 1.0), rng.within(0.0, 1.0));
    // Triangle 0 holds the cell's points with `fx >= fy`.
    let (fx, fy) = if (k == 0) == (a >= b) { (a, b) } else { (b, a) };
    let z = field.surface_z(cell, (fx, fy));
    (cell, k, [cell.0 as f64 + fx, cell.1 as f64 + fy, z])
}

#[test]
fn sky_rays_called_clear_from_their_start_touch_no_triangle_but_their_own() {
    let mut rng = Rng(0x0051_7a11_0c0e);
    let (mut asked, mut clear, mut whole) = (0, 0, 0);
    each_sky_bounds(&mut rng, 12, |rng, (round, reach), case| {
        for _ in 0..80 {
            let (cell, k, start) = start_inside(case.field, rng);
            let room = 1e-12 * (1.0 + start[2].abs());
            let Some(near) = NearStart::on_triangle(case.terrain, (cell, k), start, room) else {
                continue;
            };
            let azimuth = rng.within(0.0, std::f64::consts::TAU);
            let climb = [-0.6, -0.1, 0.05, 0.3, 1.0, 4.0][rng.below(6)];
            let dir = [azimuth.cos(), azimuth.sin(), climb];
            asked += 1;
            let t_end = reach / dir[0].hypot(dir[1]);
            let own = Some(([cell.0, cell.1], k));
            // Clear all the way, or before the part left to walk.
            let clear_to = match case
                .bounds
                .unsettled(case.terrain, start, dir, room, Some(near))
            {
                None => t_end,
                Some(part) if part.from > 0.0 => part.from,
                Some(_) => continue,
            };
            clear += 1;
            whole += usize::from(clear_to == t_end);
            assert!(
                !touches_other(case.field, case.exact, (start, dir), (0.0, clear_to), own),
                "round {round}, reach {reach}, dir {dir:?}, start {start:?} on {own:?}: touches the surface before {clear_to}"
            );
        }
    });
    // (Rough random fields rise steeply near most starts: few rays outclimb them.)
    assert!(clear >= 100, "{clear} of {asked} rays called clear");
    assert!(
        whole >= 20 && whole < clear,
        "{whole} of {clear} rays called clear all the way"
    );
}

#[test]
fn sun_rays_called_clear_from_their_start_touch_no_triangle_but_their_own() {
    let mut rng = Rng(0x005e_ed0f_0c0e);
    let (mut asked, mut clear) = (0, 0);
    for round in 0..12 {
        let field = if round == 0 {
            landscape(33, 3, 12.0).unwrap()
        } else {
            field(&mut rng, 8 + round)
        };
        let exact = ExactField::new(&field);
        let terrain = Terrain::new(field.clone());
        for sun in SUNS {
            for half in [0.0, 0.05] {
                // (A disc around a sun this low dips under the horizon: no bounds.)
                let Some(bounds) = StripBounds::build(&field, sun, half) else {
                    assert!(half > 0.0, "the sun climbs");
                    continue;
                };
                for _ in 0..30 {
                    let (cell, k, start) = start_inside(&field, &mut rng);
                    let room = 1e-12 * (1.0 + start[2].abs());
                    let Some(near) = NearStart::on_triangle(&terrain, (cell, k), start, room)
                    else {
                        continue;
                    };
                    // The axis, or a direction of the disc.
                    let dir = match half > 0.0 {
                        true => tilted(sun, rng.within(-half, half), rng.within(-half, half)),
                        false => sun,
                    };
                    asked += 1;
                    let Some(t) = bounds.clear_beyond(start, dir, room) else {
                        continue;
                    };
                    if !bounds.clear_before(start, dir, t, near) {
                        continue;
                    }
                    clear += 1;
                    let own = Some(([cell.0, cell.1], k));
                    assert!(
                        !touches_other(&field, &exact, (start, dir), (0.0, f64::INFINITY), own),
                        "round {round}, sun {sun:?} (disc {half}), dir {dir:?}, start {start:?} on {own:?}: touches the surface"
                    );
                }
            }
        }
    }
    // (Rough random fields rise steeply near most starts: few rays outclimb them.)
    assert!(clear >= 100, "{clear} of {asked} rays called clear");
}

/// `dir` turned by about `a` and `b` radians about two axes across it (a direction of a
/// disc around it of half-angle at least `|a| + |b|`, within rounding).
fn tilted(dir: [f64; 3], a: f64, b: f64) -> [f64; 3] {
    let d = glam::DVec3::from(dir).normalize();
    let (p, q) = d.any_orthonormal_pair();
    // (Scaled so that the angle off the axis stays within `a` and `b`'s sum.)
    let turned = d + p * a.tan() * 0.7 + q * b.tan() * 0.7;
    turned.normalize().into()
}

#[test]
fn shadow_frames_are_the_same_with_near_slopes_on_and_off() {
    let terrain = Terrain::new(landscape(65, 7, 16.0).unwrap());
    let off = Culling {
        near_slopes: false,
        ..Culling::default()
    };
    for (sun_angle_deg, sun_rays) in [(0.0, 1), (0.53, 8), (4.0, 16)] {
        let effects = Effects {
            sun_angle_deg,
            sun_rays,
            ..Effects::default()
        };
        for arith in [Arith::F32, Arith::F64, Arith::Exact] {
            // Rays settled whole walk no cell.
            let (mut cells_on, mut cells_walked) = (0, 0);
            for sun in [[0.4, 0.3, 0.5], [-1.0, 0.0, 0.3], [0.7, -0.7, 0.2]] {
                let on = render_with(&terrain, sun, effects, arith, Culling::default());
                let walked = render_with(&terrain, sun, effects, arith, off);
                let what = format!("{arith:?}, sun {sun:?}, disc {sun_angle_deg} deg");
                assert_eq!(on.pixels, walked.pixels, "{what}");
                cells_on += on.totals.shadow.cell.total();
                cells_walked += walked.totals.shadow.cell.total();
            }
            if arith != Arith::F32 {
                let what = format!("{arith:?}, disc {sun_angle_deg} deg");
                assert!(cells_on < cells_walked, "{what}: the slopes settle rays");
            }
        }
    }
}

#[test]
fn sky_light_frames_are_the_same_with_near_slopes_on_and_off() {
    let off = Culling {
        near_slopes: false,
        ..Culling::default()
    };
    sky_frames_the_same_with(off, |on, what, arith, sky_distance| {
        if arith != Arith::F32 && sky_distance.is_finite() {
            let settled = on.totals.effects.sky_light.culled_horizon_clear;
            assert!(settled > 0, "{what}: the near slopes settle rays");
        }
    });
}
