//! The cell kernel (`RaySpace::cell_in_lanes`): both triangles of a cell tested in `f64` SIMD
//! lanes answer as the scalar watertight test answers each (hit or miss, the bits of `t`, the
//! last touch of a ray in the triangle's plane), on every SIMD path the processor has, for
//! random cells and rays aimed anywhere in the cell, at its corners, along its edges and its
//! diagonal, and lying in a flat cell's plane.

use crate::common::random::Rng;
use heightray::geometry::{CellTriangles, RaySpace, TriangleHit};
use heightray::traverse::SimdPath;

/// A hit down to the bits of its first and last touch.
type Bits = Option<(u64, Option<u64>)>;

fn bits(hit: &Option<TriangleHit<f64>>) -> Bits {
    hit.as_ref()
        .map(|h| (h.t_first.to_bits(), h.t_last.map(f64::to_bits)))
}

/// Where in the cell a ray is aimed: anywhere, at a corner, on an edge or on the diagonal.
fn target(r: &mut Rng, (i, j): (usize, usize), kind: usize) -> [f64; 2] {
    let (x, y) = (i as f64, j as f64);
    let s = r.within(0.0, 1.0);
    match kind {
        0 => [x + r.within(0.0, 1.0), y + r.within(0.0, 1.0)],
        1 => [x + r.below(2) as f64, y + r.below(2) as f64],
        2 => [x + s, y + r.below(2) as f64],
        3 => [x + r.below(2) as f64, y + s],
        _ => [x + s, y + s],
    }
}

/// Corner heights: random, small integers (shared edges and flat triangles), or one level.
fn heights(r: &mut Rng) -> [f64; 4] {
    match r.below(3) {
        0 => [0; 4].map(|_| r.within(-5.0, 5.0)),
        1 => [0; 4].map(|_| r.below(3) as f64),
        _ => [r.below(4) as f64; 4],
    }
}

/// The answers of the scalar test and of the kernel on `path`, for one cell and ray.
fn both(
    space: &RaySpace<f64>,
    path: SimdPath,
    cell: (usize, usize),
    z: [f64; 4],
) -> ([Bits; 2], [Bits; 2]) {
    let scalar = CellTriangles::new(space, cell.0, cell.1, z);
    let want = [0, 1].map(|k| bits(&scalar.intersect(space, k)));
    let lanes = space
        .cell_in_lanes(path, cell, z)
        .expect("f64 rays are tested in lanes");
    (want, lanes.map(|hit| bits(&hit)))
}

#[test]
fn every_simd_path_answers_as_the_scalar_test() {
    let paths = [SimdPath::Scalar, SimdPath::Avx2, SimdPath::Avx512];
    let paths: Vec<SimdPath> = paths
        .into_iter()
        .filter(|&p| p <= SimdPath::detected())
        .collect();
    let mut r = Rng(45);
    let (mut hits, mut both_hit, mut in_plane) = (0, 0, 0);
    let cases = 40_000;
    for case in 0..cases {
        let cell = (r.below(40), r.below(40));
        let z = heights(&mut r);
        let [tx, ty] = target(&mut r, cell, case % 5);
        let level = case % 11 == 0;
        let tz = if level || case % 7 == 0 {
            // On the cell's plane where it is flat.
            z[0]
        } else {
            r.within(-6.0, 6.0)
        };
        let origin = if level {
            // A level ray: in a flat cell's plane at its height.
            [tx - r.within(-9.0, 9.0), ty - r.within(-9.0, 9.0), tz]
        } else {
            [
                tx + r.within(-30.0, 30.0),
                ty + r.within(-30.0, 30.0),
                tz + r.within(-30.0, 30.0),
            ]
        };
        let dir = [tx - origin[0], ty - origin[1], tz - origin[2]];
        if dir == [0.0; 3] {
            continue;
        }
        let space = RaySpace::new(origin, dir, dir);
        let mut first = None;
        for &path in &paths {
            let (want, got) = both(&space, path, cell, z);
            assert_eq!(
                got, want,
                "{path} cell {cell:?} heights {z:?} origin {origin:?} dir {dir:?}"
            );
            first = Some(want);
        }
        let want = first.expect("the portable path runs everywhere");
        hits += want.iter().filter(|h| h.is_some()).count();
        both_hit += usize::from(want.iter().all(Option::is_some));
        in_plane += want
            .iter()
            .flatten()
            .filter(|(t, last)| *last != Some(*t))
            .count();
    }
    // The families reach what they are for: hits, rays through the shared diagonal or a
    // corner (both triangles hit), rays in a triangle's plane.
    assert!(hits > cases / 4, "{hits} hits");
    assert!(both_hit > cases / 20, "{both_hit} rays hit both triangles");
    assert!(in_plane > 100, "{in_plane} rays ran in a triangle's plane");
}

#[test]
fn only_f64_is_tested_in_lanes() {
    let space = RaySpace::new([0.5f32, 0.5, 9.0], [0.0, 0.0, -1.0], [0.0, 0.0, -1.0]);
    assert!(space
        .cell_in_lanes(SimdPath::Scalar, (0, 0), [1.0; 4])
        .is_none());
    let space = RaySpace::new([0.5, 0.5, 9.0], [0.0, 0.0, -1.0], [0.0, 0.0, -1.0]);
    let hits = space.cell_in_lanes(SimdPath::Scalar, (0, 0), [1.0; 4]);
    // Straight down onto the diagonal of a level cell at height 1: both triangles at t = 8.
    let t = |hit: &Option<TriangleHit<f64>>| hit.as_ref().map(|h| h.t_first);
    assert_eq!(hits.map(|h| h.map(|hit| t(&hit))), Some([Some(8.0); 2]));
}
