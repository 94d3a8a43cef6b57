//! Rays worked by hand over a base.

use super::{holed, with_base};
use crate::common::METHODS;
use heightray::{occluded, trace, Arith, Base, Face, Heightfield, Ray, Side, Terrain};

const ARITHS: [Arith; 4] = [
    Arith::F32,
    Arith::F64,
    Arith::Rational { bound: 1 << 16 },
    Arith::Exact,
];

/// 3x3 samples at height `10 + i` (sample heights are the samples: maxval 255, z_scale 255).
fn ramp() -> Terrain {
    let field = Heightfield::from_fn(3, 3, 255, 255.0, |i, _| 10 + i as u16).unwrap();
    Terrain::new(field)
}

/// 4x4 samples at height 10, sample (1, 1) no data: cells (0, 0) to (1, 1), the square
/// `[0, 2] x [0, 2]`, are holes.
fn holed_plain() -> Terrain {
    let field = Heightfield::from_fn(4, 4, 255, 255.0, |_, _| 10).unwrap();
    let mut holes = [false; 16];
    holes[4 + 1] = true;
    Terrain::new(holed(&field, &holes).unwrap())
}

/// Every method and arithmetic hits `face` at `t` (exactly `t_exact` in exact mode).
fn assert_hits(terrain: &Terrain, base: Base, ray: &Ray, face: Face, t_exact: &str, t: f64) {
    for method in METHODS {
        for arith in ARITHS {
            let hit = trace(terrain, ray, &with_base(method, arith, base))
                .hit
                .unwrap_or_else(|| panic!("{method} {arith}: no hit"));
            assert_eq!(hit.face, face, "{method} {arith}");
            assert!((hit.t - t).abs() < 1e-5, "{method} {arith}: t {}", hit.t);
            if arith == Arith::Exact {
                assert_eq!(hit.t_exact.unwrap().to_string(), t_exact, "{method}");
            }
        }
    }
}

/// The ramp's lowest sample is 10, so a depth of 5 puts the floor at 5. The ray
/// `(-4, 1, 7) + t (1, 0, 0)` reaches the west wall's plane `x = 0` at t = 4, at height 7:
/// above the floor, below the edge (10 all along x = 0).
#[test]
fn a_ray_from_outside_below_the_edge_hits_the_wall() {
    let terrain = ramp();
    let base = Base::under(&terrain, 5.0, true).unwrap();
    assert_eq!(base.floor(), 5.0);
    let ray = Ray::new([-4.0, 1.0, 7.0], [1.0, 0.0, 0.0]).unwrap();
    assert_hits(&terrain, base, &ray, Face::Wall(Side::West), "4", 4.0);
    // Without walls it passes under the terrain, over the floor, and out.
    let floor_only = Base::under(&terrain, 5.0, false).unwrap();
    for method in METHODS {
        let options = with_base(method, Arith::Exact, floor_only);
        assert_eq!(trace(&terrain, &ray, &options).hit, None);
    }
}

/// The same ray at the edge's height 10 touches the edge at (0, 0.5, 10) at t = 4, where the
/// wall's top meets the terrain: the terrain wins the tie (cell (0, 0), T1 holds x - i <=
/// y - j).
#[test]
fn a_ray_at_the_edge_profile_hits_the_terrain() {
    let terrain = ramp();
    let base = Base::under(&terrain, 5.0, true).unwrap();
    let ray = Ray::new([-4.0, 0.5, 10.0], [1.0, 0.0, 0.0]).unwrap();
    for method in METHODS {
        for arith in ARITHS {
            let hit = trace(&terrain, &ray, &with_base(method, arith, base))
                .hit
                .unwrap();
            assert_eq!(
                (hit.face, hit.cell, hit.triangle),
                (Face::Terrain, [0, 0], 1),
                "{method} {arith}"
            );
            assert_eq!(hit.t, 4.0, "{method} {arith}");
        }
    }
}

/// Down the hole of `holed_plain` (floor at 10 - 5 = 5): from (0.5, 0.5, 20) along
/// (1, 1, -10) the ray stays over the holes until x = y = 2, where it reaches z = 5 at
/// t = 3/2, on the floor below the hole's corner (the terrain there is at 10).
#[test]
fn a_ray_through_a_hole_hits_the_floor() {
    let terrain = holed_plain();
    let base = Base::under(&terrain, 5.0, false).unwrap();
    let ray = Ray::new([0.5, 0.5, 20.0], [1.0, 1.0, -10.0]).unwrap();
    assert_hits(&terrain, base, &ray, Face::Floor, "3/2", 1.5);
    // Without the base it passes through the hole and leaves the map.
    for method in METHODS {
        let options = heightray::TraceOptions::new(method, Arith::Exact);
        assert_eq!(trace(&terrain, &ray, &options).hit, None);
    }
}

/// From below, the floor is hit too (a closed face): from (1, 2.5, 0) straight up it is met
/// at z = 5, t = 5. From (1, 3, 0), in the north wall's plane `y = 3`, the ray meets the wall
/// where it meets the floor, at their common edge: the tie goes to the wall.
#[test]
fn a_ray_from_below_hits_the_floor() {
    let terrain = holed_plain();
    let base = Base::under(&terrain, 5.0, true).unwrap();
    let ray = Ray::new([1.0, 2.5, 0.0], [0.0, 0.0, 1.0]).unwrap();
    assert_hits(&terrain, base, &ray, Face::Floor, "5", 5.0);
    let in_wall = Ray::new([1.0, 3.0, 0.0], [0.0, 0.0, 1.0]).unwrap();
    assert_hits(&terrain, base, &in_wall, Face::Wall(Side::North), "5", 5.0);
}

/// Shadow rays count the base and start on it: from the floor under the hole at (1, 1, 5),
/// straight up leaves through the hole (open), towards (1, 1, 1) it meets the terrain from
/// below past x = 2 (blocked); from outside the map below the edge, towards the map, the
/// west wall blocks it.
#[test]
fn shadow_rays_see_the_base() {
    let terrain = holed_plain();
    let base = Base::under(&terrain, 5.0, true).unwrap();
    let cases = [
        ([1.0, 1.0, 5.0], [0.0, 0.0, 1.0], false),
        ([1.0, 1.0, 5.0], [1.0, 1.0, 1.0], true),
        ([-3.0, 2.5, 6.0], [1.0, 0.0, 0.5], true),
        ([-3.0, 2.5, 6.0], [1.0, 0.0, 2.0], false),
    ];
    for (origin, dir, blocked) in cases {
        let ray = Ray::new(origin, dir).unwrap();
        for method in METHODS {
            for arith in ARITHS {
                let answer = occluded(&terrain, &ray, &with_base(method, arith, base));
                assert_eq!(
                    answer.hit.is_some(),
                    blocked,
                    "{method} {arith} {origin:?} {dir:?}"
                );
            }
        }
    }
}
