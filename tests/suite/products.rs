//! Map products against analytic values: the sky-view factor of an open plane is 1 and of a V
//! valley the sum RVT's definition gives for its two planar flanks; horizons of random fields
//! against a dense brute-force search along the line; hours of sun on flat ground
//! at the equator on an equinox are 12 within the step, and a slope facing away from a low
//! winter sun gets none.

use crate::common::random::Rng;
use chrono::NaiveDate;
use heightray::products::{Horizon, SkyView, SunPath, Sunlight};
use heightray::{Arith, Heightfield, Method, Terrain, TraceOptions};

/// RVT's sum for horizons whose tangents are `rise(direction)`: 1 - mean of sin(max(angle, 0)).
fn rvt_sky_view(n: u32, rise: impl Fn(f64) -> f64) -> f64 {
    let blocked: f64 = (0..n)
        .map(|k| {
            let bearing = std::f64::consts::TAU * f64::from(k) / f64::from(n);
            rise(bearing).max(0.0).atan().sin()
        })
        .sum();
    1.0 - blocked / f64::from(n)
}

#[test]
fn an_open_plane_sees_the_whole_sky_everywhere() {
    let terrain = Terrain::new(Heightfield::from_fn(12, 9, 100, 30.0, |_, _| 40).unwrap());
    let horizon = Horizon::new(&terrain);
    let measure = SkyView::default();
    for at in [[0.0, 0.0], [5.5, 4.25], [11.0, 8.0], [3.0, 0.0], [7.0, 4.0]] {
        assert_eq!(measure.at(&horizon, at), Some(1.0), "at {at:?}");
    }
    assert_eq!(measure.at(&horizon, [12.5, 3.0]), None);
}

#[test]
fn a_v_valley_matches_rvts_sum_over_its_flanks() {
    // Flanks rising 0.5 per cell either side of the floor x = 20, running north-south.
    let slope = 0.5;
    let field = Heightfield::from_fn(41, 41, 20, 20.0 * slope, |i, _| {
        (i as i32 - 20).unsigned_abs() as u16
    });
    let terrain = Terrain::new(field.unwrap());
    let horizon = Horizon::new(&terrain);
    for (directions, radius) in [(16, 10.0), (7, 10.0), (64, 15.0)] {
        let measure = SkyView::new(directions, radius).unwrap();
        // On the floor every direction climbs a flank at once, at slope * |east component|.
        let floor = measure.at(&horizon, [20.0, 20.0]).unwrap();
        let expected = rvt_sky_view(directions, |b| slope * b.sin().abs());
        assert!(
            (floor - expected).abs() < 1e-12,
            "{floor} against {expected}"
        );
        // Four cells up the east flank: uphill as before; downhill the line crosses the floor
        // and climbs the far flank, its steepest rise at the radius: slope * (|ux| - 2a/R).
        let a = 4.0;
        let flank = measure.at(&horizon, [20.0 + a, 20.0]).unwrap();
        let expected = rvt_sky_view(directions, |b| {
            let ux = b.sin();
            if ux >= 0.0 {
                slope * ux
            } else {
                slope * (-ux - 2.0 * a / radius)
            }
        });
        assert!(
            (flank - expected).abs() < 1e-12,
            "{flank} against {expected}"
        );
        assert!(flank > floor);
    }
}

#[test]
fn flat_ground_on_the_equator_at_an_equinox_has_twelve_hours_of_sun_within_the_step() {
    let terrain = Terrain::new(Heightfield::from_fn(9, 9, 10, 5.0, |_, _| 3).unwrap());
    let date = NaiveDate::from_ymd_opt(2026, 3, 20).unwrap();
    for step in [5, 10, 30] {
        let path = SunPath::over_day(date, (0.0, 0.0), chrono_tz::UTC, step).unwrap();
        assert_eq!(path.steps, 24 * 60 / step as usize);
        let hours = path.daylight_hours();
        // Sunrise to sunset of the refracted centre is a few minutes over 12 hours.
        assert!(
            (hours - 12.0).abs() <= f64::from(step) / 60.0,
            "{step} min: {hours} h"
        );
        let options = TraceOptions::new(Method::Mipmap, Arith::F64);
        let sunlight = Sunlight::new(&terrain, &path, options);
        for at in [[0.0, 0.0], [4.0, 4.0], [2.5, 7.25], [8.0, 8.0]] {
            assert_eq!(sunlight.hours_at(at), Some(hours), "at {at:?}");
        }
    }
}

#[test]
fn a_steep_north_slope_gets_no_winter_sun_and_a_wall_shades_its_foot() {
    // At 60 N on the winter solstice the sun climbs 6.6 degrees, rising between south-east and
    // south-west: a slope falling 20 degrees to the north faces away from it all day.
    let date = NaiveDate::from_ymd_opt(2026, 12, 21).unwrap();
    let path = SunPath::over_day(date, (60.0, 10.0), chrono_tz::UTC, 10).unwrap();
    let flat_hours = path.daylight_hours();
    assert!((5.0..7.0).contains(&flat_hours), "{flat_hours}");
    let rise = 20f64.to_radians().tan();
    let slope = Heightfield::from_fn(21, 21, 2000, 20.0 * rise, |_, j| (100 * (20 - j)) as u16);
    let terrain = Terrain::new(slope.unwrap());
    let options = TraceOptions::new(Method::Mipmap, Arith::Exact);
    let sunlight = Sunlight::new(&terrain, &path, options);
    assert_eq!(sunlight.hours_at([10.0, 10.0]), Some(0.0));
    assert_eq!(sunlight.hours_at([3.5, 17.25]), Some(0.0));
    // A wall 10 high along the south edge of flat ground (a ramp down to 0 over the first
    // cell): 3 cells north of it the sun would have to stand above atan(10 / 3), 73 degrees;
    // 200 cells north, above 2 to 3 degrees, depending on its bearing.
    let walled = Heightfield::from_fn(1001, 201, 10, 10.0, |_, j| if j == 0 { 10 } else { 0 });
    let terrain = Terrain::new(walled.unwrap());
    let sunlight = Sunlight::new(&terrain, &path, options);
    assert_eq!(sunlight.hours_at([500.0, 3.0]), Some(0.0));
    let far = sunlight.hours_at([500.0, 200.0]).unwrap();
    // The steps whose sun stands higher than the wall's top seen along its bearing, counted
    // from the sun's directions alone: the ray meets the wall's row 200 / |y| cells away.
    let expected = path
        .sun_up
        .iter()
        .filter(|[x, y, z]| {
            let across = x.hypot(*y);
            let to_wall = 200.0 / (-y / across);
            z / across > 10.0 / to_wall
        })
        .count() as f64
        * path.step_hours;
    assert_eq!(far, expected);
    assert!(far > 0.0 && far < flat_hours, "{far} of {flat_hours}");
}

#[test]
fn horizons_of_random_fields_match_a_dense_search_along_the_line() {
    let mut rng = Rng(0x5eed_cafe);
    for _ in 0..20 {
        let (w, h) = (5 + rng.below(12), 5 + rng.below(12));
        let heights: Vec<u16> = (0..w * h).map(|_| rng.below(1000) as u16).collect();
        let field = Heightfield::from_fn(w, h, 999, 6.0, |i, j| heights[j * w + i]).unwrap();
        let terrain = Terrain::new(field.clone());
        let horizon = Horizon::new(&terrain);
        // The surface by its definition: the triangle of the cell holding the point.
        let z = |x: f64, y: f64| {
            let (i, j) = (
                (x.floor() as usize).min(w - 2),
                (y.floor() as usize).min(h - 2),
            );
            field.surface_z((i, j), (x - i as f64, y - j as f64))
        };
        for _ in 0..10 {
            let at = [
                rng.within(0.0, (w - 1) as f64),
                rng.within(0.0, (h - 1) as f64),
            ];
            let bearing = rng.within(0.0, std::f64::consts::TAU);
            let toward = [bearing.sin(), bearing.cos()];
            let (reach, z0) = (rng.within(0.5, 8.0), z(at[0], at[1]));
            let exact = horizon.rise(at, z0, toward, reach);
            // Every 1/4000 of the reach, as far as the line stays on the map.
            let dense = (1..=4000)
                .map(|k| reach * f64::from(k) / 4000.0)
                .map(|d| (d, [at[0] + d * toward[0], at[1] + d * toward[1]]))
                .take_while(|(_, [x, y])| {
                    (0.0..=(w - 1) as f64).contains(x) && (0.0..=(h - 1) as f64).contains(y)
                })
                .map(|(d, [x, y])| (z(x, y) - z0) / d)
                .fold(None, |best: Option<f64>, r| {
                    Some(best.map_or(r, |b| b.max(r)))
                });
            let (Some(exact), Some(dense)) = (exact, dense) else {
                continue;
            };
            // The exact maximum is never below a sample of it, and a dense search comes close.
            assert!(
                exact >= dense - 1e-9 * (1.0 + dense.abs()),
                "{exact} below {dense}"
            );
            assert!(
                exact - dense < 0.02 * (1.0 + exact.abs()),
                "{exact} against {dense}"
            );
        }
    }
}
