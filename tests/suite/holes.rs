//! No-data samples make holes: a ray passes through a cell with a no-data corner and hits
//! what lies beyond, in every arithmetic and method, and exact mode still equals the
//! reference (which skips hole cells the same way).

use crate::common::files::tiff;
use crate::common::random::field_and_ray_up_to;
use crate::common::{check_exact, describe, options, METHODS};
use heightray::heightfield::{
    load_bytes, load_with, LoadOptions, NoDataMask, NoDataValue, Quantisation,
};
use heightray::{trace, Arith, Heightfield, Ray, Terrain};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use tiff::encoder::colortype::GrayI16;

const ARITHS: [Arith; 4] = [
    Arith::F32,
    Arith::F64,
    Arith::Rational { bound: 1 << 16 },
    Arith::Exact,
];

/// A 6x2 signed raster, both rows `0 0 1000 0 0 10`: 1000 is a spike, or no data.
fn spike_tiff() -> Vec<u8> {
    let row = [0i16, 0, 1000, 0, 0, 10];
    tiff::<GrayI16>(6, 2, &[row, row].concat(), None)
}

fn load_spike(nodata: NoDataValue) -> Terrain {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("spike.tif");
    std::fs::write(&path, spike_tiff()).unwrap();
    let options = LoadOptions {
        nodata,
        ..LoadOptions::new(1.0)
    };
    let field = load_with(&path, &options, &|_| std::ops::ControlFlow::Continue(())).unwrap();
    Terrain::new(field)
}

/// Every method and arithmetic hits `triangle` of `cell`, exact mode at `t_exact`, and exact
/// mode agrees with the reference; returns each answer's `t`, named by method and arithmetic.
fn assert_hits_everywhere(
    terrain: &Terrain,
    ray: &Ray,
    cell: [usize; 2],
    triangle: u8,
    t_exact: &str,
) -> Vec<(String, f64)> {
    let mut answers = Vec::new();
    for method in METHODS {
        for arith in ARITHS {
            let hit = trace(terrain, ray, &options(method, arith))
                .hit
                .unwrap_or_else(|| panic!("{method} {arith}: no hit"));
            assert_eq!(
                (hit.cell, hit.triangle),
                (cell, triangle),
                "{method} {arith}"
            );
            if arith == Arith::Exact {
                assert_eq!(hit.t_exact.unwrap().to_string(), t_exact);
            }
            answers.push((format!("{method} {arith}"), hit.t));
        }
    }
    assert_eq!(check_exact(terrain, ray), Vec::<String>::new());
    answers
}

/// Worked by hand: the ray `(-1, 0.25, 5) + t (1, 0, 0)` flies level at z = 5 over a raster
/// whose no-data value, read as data, would be a spike.
/// - With 1000 as data, cell (1, 0) rises from 0 at x = 1 to 1000 at x = 2; at y - j = 0.25
///   the ray is in T1 (x - i < y - j) while x < 1.25, whose height is 1000 (x - 1): 5 at
///   x = 1.005, so t = 2.005 = 401/200.
/// - With 1000 as no data, cells (1, 0) and (2, 0) are holes; cells (3, 0) is flat at 0 and
///   cell (4, 0) rises from 0 to 10 over x in [4, 5]: T0 (x - i >= y - j) at x = 4.5 is at
///   10 * 0.5 = 5, so t = 5.5 = 11/2.
#[test]
fn a_nodata_value_is_a_hole_not_a_spike() {
    let ray = Ray::new([-1.0, 0.25, 5.0], [1.0, 0.0, 0.0]).unwrap();
    let spike = load_spike(NoDataValue::Off);
    let holed = load_spike(NoDataValue::Value(1000.0));
    assert_eq!(spike.field().nodata_count(), 0);
    assert_eq!(holed.field().nodata_count(), 2);
    assert!(holed.field().is_hole_cell(1, 0) && holed.field().is_hole_cell(2, 0));
    assert!(!holed.field().is_hole_cell(0, 0) && !holed.field().is_hole_cell(3, 0));
    for (terrain, t, cell, triangle, t_exact) in [
        (&spike, 2.005, [1, 0], 1, "401/200"),
        (&holed, 5.5, [4, 0], 0, "11/2"),
    ] {
        for (what, hit_t) in assert_hits_everywhere(terrain, &ray, cell, triangle, t_exact) {
            assert!((hit_t - t).abs() < 1e-6, "{what}: t {hit_t}");
        }
    }
}

/// Two rows `0 10 X 10 40 40` (heights = samples), X no data or its stand-in, the lowest
/// valid sample 0. Worked by hand for the ray `(1.5, 0.25, 1) + t (1, 0, 8)`, which starts
/// inside the hole, below the stand-in surface, and climbs (z = 8x - 11):
/// - without the mask, cell (1, 0) falls from 10 at x = 1 to 0 at x = 2; the ray is in T0
///   (x - i >= y - j), height 20 - 10x: they meet at x = 31/18, t = 2/9;
/// - with it, cells (1, 0) and (2, 0) are holes; the ray leaves them at x = 3, z = 13 above
///   the rim at 10, and cell (3, 0) rises as 10 + 30 (x - 3) (T1 while x - i < 0.25): they
///   meet at x = 69/22, t = 18/11.
#[test]
fn a_ray_passes_through_a_hole_and_hits_what_lies_beyond() {
    let row = [0u16, 10, 0, 10, 40, 40];
    let samples = [row, row].concat();
    let field = |mask| {
        Heightfield::new(
            6,
            2,
            samples.clone(),
            Quantisation::Maxval(255),
            255.0,
            mask,
        )
        .unwrap()
    };
    let mut mask = NoDataMask::new(12);
    mask.insert(2);
    mask.insert(8);
    let ray = Ray::new([1.5, 0.25, 1.0], [1.0, 0.0, 8.0]).unwrap();
    for (terrain, t, cell, triangle) in [
        (Terrain::new(field(None)), "2/9", [1, 0], 0),
        (Terrain::new(field(Some(mask))), "18/11", [3, 0], 1),
    ] {
        assert_hits_everywhere(&terrain, &ray, cell, triangle, t);
    }
}

#[test]
fn holes_do_not_count_in_the_height_range_or_the_slope() {
    let holed = load_spike(NoDataValue::Value(1000.0));
    assert_eq!(holed.z_range(), (0.0, 10.0));
    // The steepest triangle left is cell (4, 0)'s: 10 per unit of x.
    assert_eq!(holed.max_slope(), 10.0);
    // The no-data samples hold the lowest valid sample.
    assert_eq!(holed.field().z(2, 0), 0.0);
    assert!(
        holed.summary().contains("2 no-data samples"),
        "{}",
        holed.summary()
    );
}

#[test]
fn nan_samples_are_holes_and_counted() {
    let nan = f32::NAN;
    let values = [1.0, 2.0, nan, 4.0, 5.0, 6.0, 7.0, nan, 9.0];
    let bytes = tiff::<tiff::encoder::colortype::Gray32Float>(3, 3, &values, None);
    let field = load_bytes(&bytes, 2.0, "nan.tif").unwrap();
    assert_eq!(field.nodata_count(), 2);
    // Image row 0 is y = 2: the NaN at column 2 of row 0 is sample (2, 2); of row 2, (1, 0).
    assert!(field.is_nodata(2, 2) && field.is_nodata(1, 0));
    assert!(field.is_hole_cell(1, 1) && field.is_hole_cell(0, 0));
    assert!(!Terrain::new(field).summary().contains("no holes"));
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 3_000,
        rng_seed: RngSeed::Fixed(0x484f_4c45),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn exact_mode_equals_the_reference_on_fields_with_holes(
        (field, ray) in field_and_ray_up_to(12),
        holes in proptest::collection::vec(proptest::bool::weighted(0.2), 144),
    ) {
        let Some(field) = crate::base::holed(&field, &holes[..field.samples().len()]) else {
            return Ok(()); // every sample was a hole: nothing to load
        };
        let problems = check_exact(&Terrain::new(field.clone()), &ray);
        prop_assert!(
            problems.is_empty(),
            "{}x{} field {:?}, holes {}, ray {}:\n{}",
            field.width(),
            field.height(),
            field.samples(),
            field.nodata_count(),
            describe(&ray),
            problems.join("\n")
        );
    }
}
