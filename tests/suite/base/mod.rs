//! The base under a terrain (a floor below the lowest sample, walls from the map's edge down
//! to it): every method in exact mode against the reference of tests/common/reference/base.rs
//! on random terrains with and without holes, `f64` within rounding of it, and hand-worked
//! rays.

mod hand_worked;

use crate::common::random::{field_up_to, Rng};
use crate::common::reference::{solve_with_base, SurfaceHit};
use crate::common::{describe, METHODS};
use heightray::heightfield::{NoDataMask, Quantisation};
use heightray::{trace, Arith, Base, Face, Heightfield, Ray, Terrain, TraceOptions};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

/// `field` with the no-data samples `holes` says, if any sample is left.
pub fn holed(field: &Heightfield, holes: &[bool]) -> Option<Heightfield> {
    let mut mask = NoDataMask::new(field.samples().len());
    for (k, _) in holes.iter().enumerate().filter(|(_, &hole)| hole) {
        mask.insert(k);
    }
    Heightfield::new(
        field.width(),
        field.height(),
        field.samples().to_vec(),
        Quantisation::Maxval(field.maxval()),
        field.z_scale(),
        Some(mask),
    )
    .ok()
}

/// Options tracing over `base` in `method` and `arith`.
pub fn with_base(method: heightray::Method, arith: Arith, base: Base) -> TraceOptions {
    TraceOptions {
        base: Some(base),
        ..TraceOptions::new(method, arith)
    }
}

/// Rays that meet the base: from outside the footprint below its edge, down through holes,
/// up from below the floor, at the edge profile exactly, in a wall's plane, and anywhere;
/// each marked if it grazes a face by construction (where rounding may change the answer).
fn rays(terrain: &Terrain, base: &Base, rng: &mut Rng) -> Vec<(Ray, bool)> {
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let (lo, hi) = terrain.z_range();
    let f = base.floor();
    let quarter = |rng: &mut Rng, n: f64| (rng.below((4.0 * n) as usize + 1) as f64) / 4.0;
    let mut rays = Vec::new();
    let mut push = |o: [f64; 3], d: [f64; 3], grazing: bool| {
        if let Ok(ray) = Ray::new(o, d) {
            rays.push((ray, grazing));
        }
    };
    // From the west, below the edge, into the footprint.
    let z = f + (hi - f) * rng.within(0.0, 1.0);
    push(
        [-1.5, quarter(rng, h), z],
        [1.0, rng.within(-0.5, 0.5), rng.within(-0.3, 0.3)],
        false,
    );
    // From the north-east, level or falling.
    push(
        [w + 2.0, h + 1.0, lo + (hi - lo) * rng.within(0.0, 1.0)],
        [-1.0, -0.5, -0.125 * rng.below(3) as f64],
        false,
    );
    // Down through the middle of some cell (a hole, where the field has one).
    let holes: Vec<(usize, usize)> = (0..field.height() - 1)
        .flat_map(|j| (0..field.width() - 1).map(move |i| (i, j)))
        .filter(|&(i, j)| field.is_hole_cell(i, j))
        .collect();
    let (i, j) = match holes.len() {
        0 => (rng.below(field.width() - 1), rng.below(field.height() - 1)),
        n => holes[rng.below(n)],
    };
    push(
        [i as f64 + 0.5, j as f64 + 0.25, hi + 2.0],
        [rng.within(-0.5, 0.5), rng.within(-0.5, 0.5), -1.0],
        false,
    );
    // Up from below the floor.
    push(
        [quarter(rng, w), quarter(rng, h), f - 1.0],
        [rng.within(-1.0, 1.0), rng.within(-1.0, 1.0), 0.5],
        false,
    );
    // At the edge profile exactly: a boundary sample at its height, or a segment's midpoint,
    // from outside.
    let k = rng.below(field.height());
    let target = [0.0, k as f64, field.z(0, k)];
    push(
        [-2.0, target[1] - 0.5, target[2] + 0.5],
        [2.0, 0.5, -0.5],
        true,
    );
    let k = rng.below(field.width() - 1);
    let mid = (field.z(k, 0) + field.z(k + 1, 0)) / 2.0;
    push([k as f64 + 0.5, -1.0, mid], [0.0, 1.0, 0.0], true);
    // In a wall's plane: along the west edge, and across the south edge's plane.
    push(
        [0.0, -1.0, f + (hi - f) * rng.within(0.0, 1.0)],
        [0.0, 1.0, rng.within(-0.25, 0.25)],
        true,
    );
    push(
        [-1.0, 0.0, hi + 1.0],
        [1.0, 0.0, -rng.within(0.0, 2.0)],
        true,
    );
    // In the floor's plane.
    push(
        [-1.0, quarter(rng, h), f],
        [1.0, rng.within(-0.5, 0.5), 0.0],
        true,
    );
    // Anywhere.
    push(
        [
            rng.within(-2.0, w + 2.0),
            rng.within(-2.0, h + 2.0),
            rng.within(f - 2.0, hi + 3.0),
        ],
        [
            rng.within(-1.0, 1.0),
            rng.within(-1.0, 1.0),
            rng.within(-1.0, 1.0),
        ],
        false,
    );
    rays
}

/// Whether every method in exact mode answers the reference's hit, bit for bit, and `f64`
/// within rounding unless the ray grazes a face; the problems found.
fn check(terrain: &Terrain, base: &Base, ray: &Ray, grazing: bool) -> Vec<String> {
    let expected = solve_with_base(terrain.field(), ray, base.floor(), base.walls());
    let mut problems = Vec::new();
    for method in METHODS {
        let got = trace(terrain, ray, &with_base(method, Arith::Exact, *base)).hit;
        let same = match (&got, &expected) {
            (None, None) => true,
            (Some(g), Some(SurfaceHit::Terrain(e))) => {
                g.face == Face::Terrain
                    && g.t_exact.as_ref() == Some(&e.t)
                    && (g.cell, g.triangle) == (e.cell, e.triangle)
            }
            (Some(g), Some(SurfaceHit::Base { t, face })) => {
                g.face == *face && g.t_exact.as_ref() == Some(t)
            }
            _ => false,
        };
        if !same {
            problems.push(format!(
                "{method} exact: got {got:?}, expected {expected:?}"
            ));
        }
        let rounded = trace(terrain, ray, &with_base(method, Arith::F64, *base)).hit;
        if let (Some(g), Some(e), false) = (&rounded, &expected, grazing) {
            let t = num_traits::ToPrimitive::to_f64(e.t()).unwrap();
            if (g.t - t).abs() > 1e-6 * (1.0 + t.abs()) {
                problems.push(format!("{method} f64: t {} against {t}", g.t));
            }
        }
    }
    problems
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 400,
        rng_seed: RngSeed::Fixed(0x4241_5345),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn exact_mode_equals_the_reference_over_the_base(
        field in field_up_to(7),
        holes in proptest::collection::vec(proptest::bool::weighted(0.15), 49),
        with_holes: bool,
        walls: bool,
        depth in prop_oneof![Just(None), Just(Some(0.5)), Just(Some(3.0))],
        seed in 1u64..u64::MAX,
    ) {
        let field = if with_holes { holed(&field, &holes[..field.samples().len()]) } else { Some(field) };
        let Some(field) = field else {
            return Ok(()); // every sample was a hole
        };
        let terrain = Terrain::new(field);
        let depth = depth.unwrap_or_else(|| Base::default_depth(&terrain));
        let base = Base::under(&terrain, depth, walls).expect("a floor below the terrain");
        let mut rng = Rng(seed);
        for (ray, grazing) in rays(&terrain, &base, &mut rng) {
            let problems = check(&terrain, &base, &ray, grazing);
            prop_assert!(
                problems.is_empty(),
                "{}x{} field {:?}, holes {}, floor {}, walls {walls}, ray {}:\n{}",
                terrain.field().width(),
                terrain.field().height(),
                terrain.field().samples(),
                terrain.field().nodata_count(),
                base.floor(),
                describe(&ray),
                problems.join("\n")
            );
        }
    }
}

/// The ray families reach every face: on the built-in generator's terrains, with and without
/// holes, the reference's answers include the terrain, each wall and the floor, and exact
/// mode equals them.
#[test]
fn the_families_reach_every_face() {
    let mut seen = std::collections::HashSet::new();
    let mut rng = Rng(0x6261_7365);
    for seed in 0..40u64 {
        let field = heightray::heightfield::landscape(9, seed, 8.0).unwrap();
        let holes: Vec<bool> = (0..81)
            .map(|_| seed % 2 == 1 && rng.below(8) == 0)
            .collect();
        let terrain = Terrain::new(holed(&field, &holes).unwrap());
        let base = Base::under(&terrain, Base::default_depth(&terrain), true).unwrap();
        for (ray, grazing) in rays(&terrain, &base, &mut rng) {
            let expected = solve_with_base(terrain.field(), &ray, base.floor(), true);
            seen.insert(match expected {
                Some(SurfaceHit::Terrain(_)) => Face::Terrain,
                Some(SurfaceHit::Base { face, .. }) => face,
                None => continue,
            });
            let problems = check(&terrain, &base, &ray, grazing);
            assert!(problems.is_empty(), "{}: {problems:?}", describe(&ray));
        }
    }
    for side in heightray::Side::ALL {
        assert!(
            seen.contains(&Face::Wall(side)),
            "no ray hit the {side:?} wall"
        );
    }
    assert!(seen.contains(&Face::Floor) && seen.contains(&Face::Terrain));
}
