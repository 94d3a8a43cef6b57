//! Rays from far off in exact mode: origins from 1e13 to 1e308 in every octant, directions
//! down to subnormals, rays grazing the box, and random far origins aimed at the map, every
//! method against the brute-force reference (hit, exact `t`, cell, triangle, covered cells).

use crate::common::families::{far_off, hilly, integer_hills, ray};
use crate::common::random::{far_ray_on, field_up_to};
use crate::common::{assert_family, check_exact, describe};
use crate::exact_reference::{check_random, config};
use heightray::heightfield::Builtin;
use heightray::Terrain;
use proptest::prelude::*;

#[test]
fn far_off_rays_on_integer_hills_match_the_reference() {
    assert_family(&far_off(
        "far off, integer hills",
        integer_hills(9, 8, 8, 5),
    ));
}

#[test]
fn far_off_rays_on_non_dyadic_heights_match_the_reference() {
    assert_family(&far_off("far off, hilly", hilly()));
}

/// The diagonal `x = y = z` from 1e17 to 1e308 onto small49 (z scale 12): it hits cell
/// [5, 5]. From 1e80 to 1e150 the run walk in intervals once counted rows from `i64::MIN`;
/// each ray now simply returns, with the reference's answer.
#[test]
fn the_far_diagonal_onto_small49_hits_cell_5_5_with_every_method() {
    let field = Builtin::named("small49")
        .expect("small49 is built in")
        .load_scaled(12.0)
        .expect("small49 loads");
    let terrain = Terrain::new(field);
    for s in [1e17, 1e20, 1e80, 1e90, 1e100, 1e150, 1e200, 1e300, 1e308] {
        let r = ray([s; 3], [-1.0; 3]);
        let answer = crate::common::reference::solve(terrain.field(), &r);
        assert_eq!(answer.hit.as_ref().map(|h| h.cell), Some([5, 5]), "{s:e}");
        let problems = check_exact(&terrain, &r);
        assert!(
            problems.is_empty(),
            "{}\n{}",
            describe(&r),
            problems.join("\n")
        );
    }
}

proptest! {
    #![proptest_config(config(1_500, 0x4641_524f_4646))]

    /// Random far origins aimed at random small fields.
    #[test]
    fn random_far_rays_match_the_reference(
        (field, ray) in field_up_to(12).prop_flat_map(|field| {
            let ray = far_ray_on(&field);
            (Just(field), ray)
        })
    ) {
        check_random(&field, &ray)?;
    }
}
