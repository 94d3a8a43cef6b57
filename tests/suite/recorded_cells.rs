//! Listing a walk's cells (`trace --cells`) observes the walk: the answer and every query
//! counted are the same with the cells listed and without, for every method and arithmetic,
//! and the cells listed lie on or within rounding of the ray's path
//! (`common::check_exact_against`).

use crate::common::families;
use crate::common::random::Rng;
use crate::common::{check_exact, describe, options};
use heightray::heightfield::landscape;
use heightray::{trace, Arith, Method, Ray, Terrain, TraceOptions};

#[test]
fn recording_cells_changes_no_answer_and_no_query() {
    let ariths = [
        Arith::F32,
        Arith::F64,
        Arith::Rational { bound: 1 << 16 },
        Arith::Exact,
    ];
    let mut hits = 0;
    for family in families::all() {
        for ray in &family.rays {
            for method in Method::ALL {
                for arith in ariths {
                    for packets in [false, true] {
                        let listing = TraceOptions {
                            packets,
                            ..options(method, arith)
                        };
                        let quiet = TraceOptions {
                            record_cells: false,
                            ..listing
                        };
                        let listed = trace(&family.terrain, ray, &listing);
                        let plain = trace(&family.terrain, ray, &quiet);
                        let at = format!("{} {method} {arith} {packets} {ray:?}", family.name);
                        assert_eq!(listed.hit, plain.hit, "{at}");
                        assert_eq!(listed.counters, plain.counters, "{at}");
                        assert!(plain.cells.is_empty(), "{at}");
                        let ends_in_grid =
                            listed.hit.is_none_or(|h| listed.cells.contains(&h.cell));
                        assert!(ends_in_grid, "{at}: the hit's cell is not listed");
                        hits += usize::from(plain.hit.is_some());
                    }
                }
            }
        }
    }
    // The families hit the surface as well as miss it.
    assert!(hits > 100, "{hits} hits");
}

/// Random rays over terrains of four kinds (small hills on non-dyadic heights, integer hills, a
/// lattice of slopes, the built-in generator's landscape, deep enough for blocks to skip), from outside and inside the box, in exact mode: every method
/// answers as the reference does with its cells listed and without, with the same queries, and
/// lists only cells within rounding of the path, the hit's among them.
#[test]
fn random_rays_list_cells_near_their_path_and_answer_alike() {
    let terrains = [
        ("hilly", families::hilly()),
        ("integer hills", families::integer_hills(23, 17, 40, 7)),
        ("lattice", families::lattice_terrain()),
        (
            "landscape",
            Terrain::new(landscape(65, 3, 16.0).expect("a landscape")),
        ),
    ];
    let mut rng = Rng(0x5eed_ce11);
    let mut hits = 0;
    for (name, terrain) in &terrains {
        let field = terrain.field();
        let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
        let (z_lo, z_hi) = terrain.z_range();
        for _ in 0..48 {
            let origin = [
                rng.within(-3.0, w + 3.0),
                rng.within(-3.0, h + 3.0),
                rng.within(z_lo - 1.0, z_hi + 8.0),
            ];
            let target = [
                rng.within(0.0, w),
                rng.within(0.0, h),
                rng.within(z_lo, z_hi),
            ];
            let dir = [0, 1, 2].map(|k| target[k] - origin[k]);
            let Ok(ray) = Ray::new(origin, dir) else {
                continue;
            };
            let problems = check_exact(terrain, &ray);
            assert!(
                problems.is_empty(),
                "{name}: {}\n  {}",
                describe(&ray),
                problems.join("\n  ")
            );
            hits += usize::from(
                trace(terrain, &ray, &options(Method::Mipmap, Arith::Exact))
                    .hit
                    .is_some(),
            );
        }
    }
    // Aimed below the highest terrain, most rays hit.
    assert!(hits > 96, "{hits} hits");
}
