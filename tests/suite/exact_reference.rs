//! Exact mode against the brute-force reference of tests/common/reference/: for every
//! method, the hit (exact t, cell, triangle) and `covered_cells` must match the contract
//! exactly, and the recorded cells and query counters as `common::check_exact_against` says.

use crate::common;

use crate::common::families::{self, ray, terrain};
use crate::common::random::{field_and_ray, field_and_ray_up_to};
use crate::common::reference::{self, q, Q};
use crate::common::{assert_family, check_exact, describe, options};
use heightray::arith::{settled, Exact, Interval, Scalar};
use heightray::traverse::{covered_cells, occluded, occluded_from_hit, HitMiss, Start, Tracer};
use heightray::{trace, Arith, Counters, Heightfield, Method, Ray, Terrain, TraceOptions};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use proptest::test_runner::TestCaseError;

/// Every deterministic ray family against the reference, one table (`families::all`): octant
/// entries and rays along grid lines and cell diagonals on non-dyadic and integer heights,
/// lattice-point slopes, vertical rays in a cell, on an edge, a corner and the grid's
/// boundary, rays starting inside the grid, below the surface and on a vertex or edge, level
/// rays at a plateau's height, near-vertical rays, a shallow ray along a 4000-cell strip,
/// negative-zero components, single-point segments at the box's corner, and oblique rays that
/// touch a flat field at one point.
#[test]
fn every_ray_family_matches_the_reference() {
    for family in families::all() {
        assert_family(&family);
    }
}

#[test]
fn oblique_rays_touch_a_flat_field_at_one_point() {
    let family = families::flat_field_single_point();
    // Every one of them hits, at t = 1 (the aimed point).
    for ray in &family.rays {
        let answer = reference::solve(family.terrain.field(), ray);
        let hit = answer
            .hit
            .unwrap_or_else(|| panic!("reference misses {}", describe(ray)));
        assert_eq!(hit.t, q(1.0), "{}", describe(ray));
    }
}

/// A level path (minor component 0) clipped to one lattice point (the ray meets the flat
/// field's zero-height box there): the four cells all have contact [0, 0], so the key orders
/// them by minor index first.
#[test]
fn single_point_level_segment_on_a_lattice_point() {
    let flat = terrain(3, 3, 255, 255.0, |_, _| 0);
    let cases = [
        // y-major: minor is x.
        (
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 1.0],
            vec![[0, 0], [0, 1], [1, 0], [1, 1]],
        ),
        (
            [1.0, 1.0, 0.0],
            [-0.0, -1.0, 1.0],
            vec![[0, 1], [0, 0], [1, 1], [1, 0]],
        ),
        // x-major: minor is y.
        (
            [1.0, 1.0, 0.0],
            [1.0, 0.0, 1.0],
            vec![[0, 0], [1, 0], [0, 1], [1, 1]],
        ),
        (
            [1.0, 1.0, 0.0],
            [-1.0, 0.0, -1.0],
            vec![[1, 0], [0, 0], [1, 1], [0, 1]],
        ),
    ];
    for (o, d, expected) in cases {
        let r = ray(o, d);
        assert_eq!(
            reference::solve(flat.field(), &r).cell_list(),
            expected,
            "reference"
        );
        for method in common::METHODS {
            let got = covered_cells(&flat, &r, method, Arith::Exact);
            assert_eq!(got, expected, "{method}: {}", describe(&r));
        }
    }
}

#[test]
fn slope_1_3777_strip_finds_the_far_spike() {
    let family = families::strip_slope_1_3777();
    assert_family(&family);
    for ray in &family.rays {
        for method in common::METHODS {
            let got = trace(&family.terrain, ray, &options(method, Arith::Exact));
            let hit = got
                .hit
                .unwrap_or_else(|| panic!("{method} misses the spike: {}", describe(ray)));
            assert!(
                families::strip_spike_cells().contains(&hit.cell),
                "{method}: hit {hit:?} is not next to the spike: {}",
                describe(ray)
            );
        }
    }
}

/// The 4x3 field of the hand-worked ray: heights 0 except z(0,0) = 1 and z(2,2) = 4.
fn hand_worked_terrain() -> Terrain {
    terrain(4, 3, 255, 255.0, |x, y| match (x, y) {
        (0, 0) => 1,
        (2, 2) => 4,
        _ => 0,
    })
}

fn hit_miss(hit: u64, miss: u64) -> HitMiss {
    HitMiss { hit, miss }
}

/// Field (y up; cell maxima in brackets):
///
/// ```text
///   y=2   0   0   4   0
///   y=1   0   0   0   0        cells: (0,1)[0] (1,1)[4] (2,1)[4]
///   y=0   1   0   0   0               (0,0)[1] (1,0)[0] (2,0)[0]
/// ```
///
/// Ray o = (0, 0.25, 3), d = (2, 1, -2): x = 2t, y = 0.25 + t, z = 3 - 2t; x-major, slope 1/2.
/// Clip: x in [0,3] gives t in [0, 1.5], y in [0,2] gives [-0.25, 1.75], z in [0,4] gives
/// [-0.5, 1.5]; so [t0, t1] = [0, 1.5]. The path goes from (0, 0.25) to (3, 1.75), crossing
/// x = 1 at t = 0.5, y = 1 at t = 0.75 (x = 1.5), x = 2 at t = 1 (y = 1.25). Covered cells:
/// (0,0) [0, .5], (1,0) [.5, .75], (1,1) [.75, 1], (2,1) [1, 1.5].
///
/// Triangles of (1,1) (z00 = z10 = z01 = 0, z11 = 4; X = 2t-1, Y = t-0.75):
/// - T0: z = 4Y; 3 - 2t = 4t - 3 gives t = 1, (X, Y) = (1, 0.25), 0 <= Y <= X <= 1: hit.
/// - T1: z = 4X; 3 - 2t = 8t - 4 gives t = 0.7, Y = -0.05 < 0: miss.
///
/// The hit point (2, 1.25, 1) is also on T1 of (2,1) (z = 4Y - 4X there, X = 0, Y = .25);
/// (1,1) comes first in visiting order, so the answer is cell (1,1), T0, t = 1.
///
/// Runs: bbox hit. Span row 0 = {(0,0),(1,0)}, t in [0, .75]: lowest z = 1.5 > max(1, 0):
/// run miss, cells skipped. Span row 1 = {(1,1),(2,1)}, t in [.75, 1.5]: lowest z = 0 <= 4:
/// run hit. Cell (1,1): lowest z over [.75, 1] = 1 <= 4: hit; T0 hit (t = 1), T1 miss.
/// Cell (2,1): t_enter = 1 >= 1: stop.
///   bbox 1/0, run 1/1, cell 1/0, triangle 1/1 (hit/miss).
/// DDA: cell (0,0): lowest z over [0, .5] = 2 > 1: miss. Cell (1,0): lowest over [.5, .75] =
/// 1.5 > 0: miss. Cell (1,1): hit, T0 hit, T1 miss. Cell (2,1): stop.
///   bbox 1/0, run 0/0, cell 1/2, triangle 1/1.
/// Hierarchical runs: the mipmap's top is level 2 (the 3x2 cells fit one 4x4 block), so the
/// walk starts three levels below it, at the cells, and its runs are the run walk's: the same
/// counts, without the run walk's recurrence.
#[test]
fn hand_worked_counters_on_4x3_field() {
    let terrain = hand_worked_terrain();
    let ray = ray([0.0, 0.25, 3.0], [2.0, 1.0, -2.0]);
    let expected_cells = vec![[0, 0], [1, 0], [1, 1], [2, 1]];
    let runs = Counters {
        bbox: hit_miss(1, 0),
        run: hit_miss(1, 1),
        cell: hit_miss(1, 0),
        triangle: hit_miss(1, 1),
        ..Counters::default()
    };
    let dda = Counters {
        bbox: hit_miss(1, 0),
        run: hit_miss(0, 0),
        cell: hit_miss(1, 2),
        triangle: hit_miss(1, 1),
        ..Counters::default()
    };
    // The reference agrees with the hand computation.
    let answer = reference::solve(terrain.field(), &ray);
    assert_eq!(answer.cell_list(), expected_cells);
    let hit = answer.hit.clone().expect("reference hit");
    assert_eq!((hit.t.clone(), hit.cell, hit.triangle), (q(1.0), [1, 1], 0));
    assert_eq!(reference::counters(&answer, true), runs);
    assert_eq!(reference::counters(&answer, false), dda);

    for (method, counters) in [
        (Method::Runs, runs),
        (Method::HierarchicalRuns, runs),
        (Method::Dda, dda),
    ] {
        let got = trace(&terrain, &ray, &options(method, Arith::Exact));
        let hit = got.hit.unwrap_or_else(|| panic!("{method}: no hit"));
        assert_eq!(hit.t_exact, Some(q(1.0)), "{method}");
        assert_eq!(hit.t, 1.0, "{method}");
        assert_eq!(hit.point, [2.0, 1.25, 1.0], "{method}");
        assert_eq!((hit.cell, hit.triangle), ([1, 1], 0), "{method}");
        assert_eq!(got.counters.bbox, counters.bbox, "{method} bbox");
        assert_eq!(got.counters.run, counters.run, "{method} run");
        assert_eq!(got.counters.cell, counters.cell, "{method} cell");
        assert_eq!(
            got.counters.triangle, counters.triangle,
            "{method} triangle"
        );
        assert_eq!(got.counters, counters, "{method}");
        assert_eq!(
            covered_cells(&terrain, &ray, method, Arith::Exact),
            expected_cells,
            "{method}"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Random rays on random small fields (strategies in tests/common/random.rs).

pub(crate) fn config(cases: u32, seed: u64) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        max_shrink_iters: 4096,
        ..ProptestConfig::default()
    }
}

/// Fails with the field and the ray when the crate disagrees with the reference.
pub(crate) fn check_random(field: &Heightfield, ray: &Ray) -> Result<(), TestCaseError> {
    let problems = check_exact(&Terrain::new(field.clone()), ray);
    prop_assert!(
        problems.is_empty(),
        "field {}x{} maxval {} z_scale {:?} samples (y up, by j*w+i) {:?}\n{}\n{}",
        field.width(),
        field.height(),
        field.maxval(),
        field.z_scale(),
        field.samples(),
        describe(ray),
        problems.join("\n")
    );
    Ok(())
}

proptest! {
    #![proptest_config(config(30_000, 0x4845_4947_4854))]

    #[test]
    fn random_rays_on_random_small_fields((field, ray) in field_and_ray()) {
        check_random(&field, &ray)?;
    }
}

proptest! {
    #![proptest_config(config(3_000, 0x5241_5953))]

    /// Up to 40 samples per side: long walks, many runs.
    #[test]
    fn random_rays_on_random_medium_fields((field, ray) in field_and_ray_up_to(40)) {
        check_random(&field, &ray)?;
    }
}

/// A field large enough for a deep hierarchy (9 levels, odd sizes, blocks cut by the far
/// edges), where the brute-force reference would be slow: the mipmap and the hierarchical
/// run walk must give exactly the run walk's answer, which the tests above hold to the
/// reference.
fn large_field() -> Heightfield {
    let t = terrain(301, 221, 4095, 97.0, |x, y| {
        let hills = ((x as f64 / 23.0).sin() * (y as f64 / 17.0).cos() + 1.0) * 1500.0;
        let plateau = if (120..180).contains(&x) && (60..140).contains(&y) {
            2600.0
        } else {
            0.0
        };
        (hills.max(plateau) as u16).max(families::hash(x, y, 7, 300))
    });
    t.field().clone()
}

proptest! {
    #![proptest_config(config(2_000, 0x4d49_504d))]

    #[test]
    fn hierarchies_equal_runs_on_a_large_field(ray in common::random::ray_on(&large_field())) {
        let terrain = Terrain::new(large_field());
        let answer = |method, record_cells| {
            let options = TraceOptions { record_cells, ..options(method, Arith::Exact) };
            trace(&terrain, &ray, &options).hit
        };
        let runs = answer(Method::Runs, true);
        // Listing their cells, and without (an f64 walk answers, or clears the way first).
        for method in [Method::Mipmap, Method::HierarchicalRuns] {
            prop_assert_eq!(&answer(method, true), &runs, "{} {}", method, describe(&ray));
            prop_assert_eq!(&answer(method, false), &runs, "{} {}", method, describe(&ray));
        }
    }
}

/// Whether a shadow query of `method` in `arith` finds the surface.
fn in_shadow(terrain: &Terrain, ray: &Ray, method: Method, arith: Arith) -> bool {
    let options = TraceOptions {
        record_cells: false,
        ..options(method, arith)
    };
    occluded(terrain, ray, &options).hit.is_some()
}

proptest! {
    #![proptest_config(config(3_000, 0x5348_4144))]

    /// A shadow query finds the surface exactly when the reference's first touch comes after
    /// the start (a touch at the start itself says nothing of later ones: not asked here).
    /// Each method walks shadow rays its own way (the mipmap from among cells up).
    #[test]
    fn shadow_queries_match_the_reference((field, ray) in field_and_ray_up_to(24)) {
        let answer = reference::solve(&field, &ray);
        let touched_after_start = match &answer.hit {
            Some(hit) if hit.t == q(0.0) => return Ok(()),
            hit => hit.is_some(),
        };
        let terrain = Terrain::new(field);
        for method in Method::ALL {
            prop_assert_eq!(
                in_shadow(&terrain, &ray, method, Arith::Exact),
                touched_after_start,
                "{} {}", method, describe(&ray)
            );
        }
    }
}

proptest! {
    #![proptest_config(config(1_000, 0x5348_4c47))]

    /// On the deep hierarchy, the mipmap's shadow answers are the run walk's, exactly and in
    /// `f64`.
    #[test]
    fn mipmap_shadow_queries_equal_runs_on_a_large_field(
        ray in common::random::ray_on(&large_field())
    ) {
        let terrain = Terrain::new(large_field());
        for arith in [Arith::Exact, Arith::F64] {
            prop_assert_eq!(
                in_shadow(&terrain, &ray, Method::Mipmap, arith),
                in_shadow(&terrain, &ray, Method::Runs, arith),
                "{} {}", arith, describe(&ray)
            );
        }
    }
}

/// Whether a shadow query from `origin` towards `sun`, walked by `method`, finds the surface.
fn in_shadow_from<S: Scalar>(
    terrain: &Terrain,
    origin: &[S; 3],
    sun: [f64; 3],
    method: Method,
) -> bool {
    let tracer = Tracer::new(terrain, method);
    tracer.occluded(&Start::Point(origin), sun, false).occluded == Some(true)
}

/// The exact `t` of `ray`'s first hit on `terrain`, if it hits.
fn exact_t(terrain: &Terrain, ray: &Ray) -> Option<Q> {
    let hit = trace(terrain, ray, &options(Method::Runs, Arith::Exact)).hit?;
    Some(hit.t_exact.expect("exact t"))
}

/// The point `o + t d` of `ray`, exactly.
fn exact_point(ray: &Ray, t: &Q) -> [Exact; 3] {
    let (o, d) = (ray.origin(), ray.dir());
    [0, 1, 2].map(|k| Exact(q(o[k]) + q(d[k]) * t.clone()))
}

proptest! {
    #![proptest_config(config(1_000, 0x5348_5850))]

    /// Shadow rays start where camera rays hit: a point that is no `f64`, exactly (or, in
    /// intervals, a box around it). The mipmap's `f64` walk clears their way with room for
    /// the distance to an `f64` origin; its answers are the run walk's, which follows every
    /// cell exactly, in rationals and in intervals.
    #[test]
    fn shadow_queries_from_exact_points_equal_runs(
        ray in common::random::ray_on(&large_field()),
        (sx, sy, sz) in (-1.0f64..1.0, -1.0f64..1.0, 0.05f64..1.0),
    ) {
        let terrain = Terrain::new(large_field());
        let sun = [sx, sy, sz];
        let Some(t) = exact_t(&terrain, &ray) else {
            return Ok(());
        };
        let (o, d) = (ray.origin(), ray.dir());
        let at = |t: &Q| exact_point(&ray, t);
        // On the surface, and a third of the way there (above it, or below it for rays that
        // start below the surface).
        let third = t.clone() / Q::from_integer(3.into());
        for origin in [at(&t), at(&third)] {
            prop_assert_eq!(
                in_shadow_from(&terrain, &origin, sun, Method::Mipmap),
                in_shadow_from(&terrain, &origin, sun, Method::Runs),
                "{} sun {:?}", describe(&ray), sun
            );
        }
        // The renderer's way: the hit point in intervals.
        let ((mipmap, runs), settled) = settled(|| {
            let tracer = Tracer::new(&terrain, Method::Runs);
            // (Unsettled, it may find none.)
            let Some(found) = tracer.trace::<Interval>(&ray, None).hit else {
                return (false, false);
            };
            let (o, d) = (o.map(Interval::from_f64), d.map(Interval::from_f64));
            let point = found.point(&o, &d);
            (
                in_shadow_from(&terrain, &point, sun, Method::Mipmap),
                in_shadow_from(&terrain, &point, sun, Method::Runs),
            )
        });
        if settled {
            prop_assert_eq!(mipmap, runs, "intervals: {} sun {:?}", describe(&ray), sun);
        }
    }
}

proptest! {
    #![proptest_config(config(500, 0x5348_4854))]

    /// A shadow ray from where a camera ray hits, in exact arithmetic (`occluded_from_hit`:
    /// intervals from the hit, a test they cannot settle decided from the exact start, the
    /// ray cast again in rationals if still unsettled), answers as the same ray does traced
    /// in rationals alone from the exact hit point `o + t_exact d`, for every method.
    #[test]
    fn shadow_rays_from_hits_answer_as_rationals_from_the_exact_point(
        ray in common::random::ray_on(&large_field()),
        (sx, sy, sz) in (-1.0f64..1.0, -1.0f64..1.0, 0.05f64..1.0),
    ) {
        let terrain = Terrain::new(large_field());
        let sun = [sx, sy, sz];
        let Some(t) = exact_t(&terrain, &ray) else {
            return Ok(());
        };
        let point = exact_point(&ray, &t);
        let expected = in_shadow_from(&terrain, &point, sun, Method::Runs);
        for method in Method::ALL {
            let options = TraceOptions {
                record_cells: false,
                ..options(method, Arith::Exact)
            };
            let got = occluded_from_hit(&terrain, &ray, sun, &options).expect("a hit");
            prop_assert_eq!(
                got.occluded, Some(expected),
                "{} {} sun {:?}", method, describe(&ray), sun
            );
        }
    }
}

/// A level shadow ray whose origin is known only within 0.01 in height, across a plateau it
/// passes 0.005 above from the middle of that range: from the bottom it hits the plateau,
/// from the top it misses, so no answer holds for every origin in the range and intervals
/// must not settle one. (The mipmap's `f64` walk follows the middle; without room for the
/// origin's range it would skip the plateau and settle "lit".)
#[test]
fn a_shadow_ray_from_an_uncertain_origin_settles_nothing_it_cannot_tell() {
    let plateau = |x, y| (3..=8).contains(&x) && (2..=9).contains(&y);
    // (A tall spike off the path keeps the box's top above the plateau.)
    let terrain = terrain(12, 12, 20, 20.0, |x, y| match (x, y) {
        (0, 11) => 20,
        _ if plateau(x, y) => 10,
        _ => 0,
    });
    let sun = [1.0, 0.37, 0.0];
    let [x, y] = [0.5, 3.1].map(Interval::from_f64);
    let z = Interval::between(9.995, 10.015).expect("an interval");
    for method in Method::ALL {
        let (_, settled) = settled(|| in_shadow_from(&terrain, &[x, y, z], sun, method));
        assert!(!settled, "{method}");
    }
    // The ends of the range, exactly.
    for (z, shadowed) in [(9.995, true), (10.015, false)] {
        let origin = [0.5, 3.1, z].map(Interval::from_f64);
        for method in Method::ALL {
            let (answer, settled) = settled(|| in_shadow_from(&terrain, &origin, sun, method));
            assert!(settled, "{method} from z = {z}");
            assert_eq!(answer, shadowed, "{method} from z = {z}");
        }
    }
}
