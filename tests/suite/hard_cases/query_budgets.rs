//! Query budgets: hard cases under and beside the surface whose answers are held to the
//! reference like every case, and whose walks are held to the queries they may make (the
//! triangles tested, the cells and runs of blocks skipped whole).

use super::*;
use heightray::TraceOptions;

/// A ray under the surface: the grid's edge does not close the terrain off, so a ray can pass
/// into it from the side, under the surface, and touch it only where it comes up through it
/// from below. On the 12x3 field of samples 200 at x <= 4, 0 at 5..=8 and 200 again from 9
/// (heights = samples), o = (-1, 1.5, 50), d = (1, 0, 0) runs level under the plateau over
/// cells (0..=3, 1) and meets the ramp of cell (4, 1) from below where 200 - 200 (x - 4) = 50:
/// x = 4.75, t = 5.75, T0 (fx = 0.75 >= fy = 0.5).
///
/// Every arithmetic and method agrees. The cells the ray passes under are not tested in the
/// float arithmetics: it runs below their lowest sample, so the only triangles tested are the
/// hit cell's.
#[test]
fn ray_under_the_surface_from_the_grids_edge() {
    let field = terrain(12, 3, 255, 255.0, |x, _| match x {
        0..=4 => 200,
        5..=8 => 0,
        _ => 200,
    });
    let r = ray([-1.0, 1.5, 50.0], [1.0, 0.0, 0.0]);
    let answer = expect_hit(&field, &r, qi(23) / qi(4), [4, 1], 0);
    assert_rounded_agree(&field, &r, &answer);
    for arith in [Arith::F32, F64] {
        for method in METHODS {
            // (The walk's own run tests: no packet clears the way first.)
            let walking = TraceOptions {
                packets: false,
                ..options(method, arith)
            };
            let got =
                try_trace(&field, &r, &walking).unwrap_or_else(|e| panic!("{}: {e}", describe(&r)));
            assert_eq!(
                got.counters.triangle.total(),
                2,
                "{method} {arith}: {:?}",
                got.counters
            );
        }
    }
}

/// A ray under the surface past blocks of the mipmap: on the 48x16 field of samples 200 at
/// x <= 39 and 0 from 40 on, o = (-1, 0.5, 50), d = (1, 1/4, -1/1024) runs under the plateau
/// and meets the ramp of column 39 from below where 200 (40 - x) = 50 - (x + 1) / 1024:
/// 204799 x = 8140801, t = x + 1 = 8345600 / 204799 (x = 39.75, y = 0.5 + t/4 = 10.69), in
/// cell (39, 10), T0 (fx = 0.75 >= fy = 0.69).
///
/// Every arithmetic and method agrees. The mipmap walk skips every block of 4x4 cells the
/// ray passes under whole, as it skips those it passes over: in the float arithmetics and in
/// exact mode's certified walk it queries only cells of the last block column, 36 to 39,
/// whose blocks hold the pit's first samples (5 cell queries in `f64`, 6 in exact mode).
#[test]
fn ray_under_the_surface_skips_blocks() {
    let field = terrain(48, 16, 255, 255.0, |x, _| if x <= 39 { 200 } else { 0 });
    let r = ray([-1.0, 0.5, 50.0], [1.0, 0.25, -1.0 / 1024.0]);
    let answer = expect_hit(&field, &r, qi(8345600) / qi(204799), [39, 10], 0);
    assert_rounded_agree(&field, &r, &answer);
    for arith in [Arith::F32, F64, Arith::Exact] {
        let got = try_trace(&field, &r, &options(Method::Mipmap, arith))
            .unwrap_or_else(|e| panic!("{}: {e}", describe(&r)));
        let cells = got.counters.cell.total();
        assert!(
            cells <= 10,
            "{arith}: {cells} cell queries, {:?}",
            got.counters
        );
        assert_eq!(
            got.counters.triangle.total(),
            2,
            "{arith}: {:?}",
            got.counters
        );
    }
}

/// A run of coarse blocks is a run of runs: on the 257x97 field of samples 0 at x < 250 and
/// 200 from 250 on, o = (-1, 0.5, 50), d = (1, 1/4, -1/1024) passes about 50 above the flat
/// ground and meets the wall's ramp in column 249 where 200 (x - 249) = 50 - (x + 1) / 1024:
/// 204801 x = 51046399, t = x + 1 = 51251200 / 204801 (x = 249.25, y = 0.5 + t/4 = 63.06),
/// in cell (249, 63), T0 (fx = 0.25 >= fy = 0.06).
///
/// The path crosses 64 rows of cells, and the run walk tests each row's run. The hierarchical
/// run walk starts at level 5 (blocks of 32x32 cells, three below the top): row of blocks 0
/// is cleared whole; row 1 holds the wall, so its two rows of level-4 blocks are walked, the
/// first cleared, the second split again; and so on down to the cells: a cleared run and a
/// split one at each of the levels 5 to 1 and the two runs of cells of the last split one,
/// 12 run tests in all. Every arithmetic and method agrees.
#[test]
fn runs_of_coarse_blocks_are_skipped_whole() {
    let field = terrain(257, 97, 255, 255.0, |x, _| if x >= 250 { 200 } else { 0 });
    let r = ray([-1.0, 0.5, 50.0], [1.0, 0.25, -1.0 / 1024.0]);
    let answer = expect_hit(&field, &r, qi(51251200) / qi(204801), [249, 63], 0);
    assert_rounded_agree(&field, &r, &answer);
    for arith in [Arith::F32, F64, Arith::Exact] {
        let runs = |method| {
            // (The walk's own run tests: no packet clears the way first.)
            let walking = TraceOptions {
                packets: false,
                ..options(method, arith)
            };
            let got =
                try_trace(&field, &r, &walking).unwrap_or_else(|e| panic!("{}: {e}", describe(&r)));
            let hit = got.hit.expect("a hit");
            assert_eq!((hit.cell, hit.triangle), ([249, 63], 0), "{method} {arith}");
            got.counters.run
        };
        let (flat, hierarchical) = (runs(Method::Runs), runs(Method::HierarchicalRuns));
        assert_eq!(flat.total(), 64, "{arith}: {flat:?}");
        assert_eq!(
            (hierarchical.hit, hierarchical.miss),
            (7, 5),
            "{arith}: {hierarchical:?}"
        );
    }
}
