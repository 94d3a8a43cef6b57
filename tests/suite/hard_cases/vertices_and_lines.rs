//! Hard cases at lattice points, vertices, grid lines and cell diagonals, where several cells
//! or triangles meet and the tie order decides.

use super::*;

/// Slope 17/41 and its mirrors on the 44x44 integer field of `families::lattice_slope`: 360
/// rays through lattice points (where the path passes a lattice point, four cells meet there),
/// at the vertex height, half a unit above and above everything, level, descending
/// (dz = -1/64) and climbing (dz = 1/128), starting before the lattice point or on it.
///
/// Expected: exact mode (every method) equals the reference on all 360 rays. f64 and
/// rational:2^24 find the same first hit on all of them.
///
/// rational:2^16 cannot on some rays (every method alike): right cell and triangle, but t off
/// by more than 1e-9 relative (up to 1.2e-8). Each climbs or descends (dz != 0): the triangle
/// test shears by dy/dx = 17/41 and dz/dx = 1/5248 (or -1/2624), and its edge functions
/// multiply sheared coordinates with denominators 41 and 5248, whose product is beyond 2^16
/// and gets rounded. Level rays have no such products: their 2^16 traces round nothing at all
/// (asserted: zero rounding events on all 120). Asserted: rational:2^16 only, every method on
/// each such ray, verdict `TOff`, dz != 0, error below 2e-8. How many rays it is (6, as
/// rounding falls today) is a characterization, recorded in `snapshots::` (24 answers of
/// `lattice slope 17/41 / rational:65536`).
#[test]
fn lattice_point_slope_17_41() {
    let family = families::lattice_slope(17, 41);
    assert_eq!(family.rays.len(), 360, "the family changed: re-measure");
    let results = run_family(&family);
    let d = family_disagreements(&results);
    let text = list(&family, &d);
    let mut rays: Vec<usize> = d.iter().map(|(n, _)| *n).collect();
    rays.dedup();
    assert_eq!(
        d.len(),
        rays.len() * METHODS.len(),
        "disagreements:\n  {text}"
    );
    for (n, r) in &d {
        assert_eq!((r.arith, r.verdict), (R16, TOff), "{text}");
        assert_ne!(family.rays[*n].dir()[2], 0.0, "a level ray: {text}");
        let e = &results[*n].0.hit.as_ref().expect("exact hit").t;
        let error = t_error(r.hit.as_ref().expect("rounded hit").t, e);
        assert!(error < 2e-8, "t error {error:e}: {text}");
    }
    let level: Vec<&Ray> = family.rays.iter().filter(|r| r.dir()[2] == 0.0).collect();
    assert_eq!(level.len(), 120);
    for r in level {
        let got = try_trace(&family.terrain, r, &options(Method::Runs, R16)).expect("no panic");
        assert_eq!(got.counters.rational_rounded, 0, "{}", describe(r));
    }
}

/// Vertical rays through grid vertices of `families::hilly` (heights 0.1 * sample, not
/// dyadic). A vertical path is a point: the four cells around an interior vertex (i, j) touch
/// it over the same t range; vertical rays count as x-major with positive components (also
/// -0.0), so the visiting order is (i-1, j-1), (i, j-1), (i-1, j), (i, j). The vertex is P11
/// of the first, in both its triangles: the hit is reported in (i-1, j-1), T0.
///
/// Expected (zmax = 19.8):
/// - down from (1, 1, zmax + 1): t = zmax + 1 - z(1,1) = 12.6, cell (0, 0), T0; the same
///   with d = (-0.0, -0.0, -1);
/// - up from (1, 1, -1): t = 1 + z(1,1) = 9.2, cell (0, 0), T0;
/// - down onto the plateau vertex (3, 2), all six triangles around it flat at 10: t =
///   zmax + 1 - 10 = 10.8, cell (2, 1), T0;
/// - and the 28 rays of `families::vertical_on_corner` (down, up, from below the surface).
///
/// f64 and both rationals agree on all of them.
#[test]
fn vertical_ray_on_corner() {
    let hilly = families::hilly();
    let top = hilly.z_range().1 + 1.0;
    let z = |i, j| q(hilly.field().z(i, j));
    let cases = [
        ([1.0, 1.0, top], [0.0, 0.0, -1.0], q(top) - z(1, 1), [0, 0]),
        (
            [1.0, 1.0, top],
            [-0.0, -0.0, -1.0],
            q(top) - z(1, 1),
            [0, 0],
        ),
        ([1.0, 1.0, -1.0], [0.0, 0.0, 1.0], qi(1) + z(1, 1), [0, 0]),
        ([3.0, 2.0, top], [0.0, 0.0, -1.0], q(top) - z(3, 2), [2, 1]),
    ];
    for (o, d, t, cell) in cases {
        let r = ray(o, d);
        let answer = expect_hit(&hilly, &r, t, cell, 0);
        assert_rounded_agree(&hilly, &r, &answer);
    }
    assert_family_agrees(&families::vertical_on_corner());
}

/// Vertical rays onto edges of `families::hilly`, down from zmax + 1 (the point's height is
/// the mean of the edge's end heights, exact in rationals):
/// - (2.25, 1.25): on the diagonal of the flat plateau cell (2, 1), the edge T0 and T1 share:
///   cell (2, 1), T0 (T0 before T1), t = zmax + 1 - 10;
/// - (1.5, 3): on the horizontal edge between cells (1, 2) and (1, 3); (1, 2) comes first
///   (lower row) and its top edge belongs to T1 only: cell (1, 2), T1,
///   t = zmax + 1 - (z(1,3) + z(2,3)) / 2;
/// - (4, 2.25): on the vertical edge between cells (3, 2) and (4, 2); (3, 2) comes first and
///   its right edge belongs to T0 only: cell (3, 2), T0, t = zmax + 1 - 10 (plateau edge);
/// - and the 42 rays of `families::vertical_on_edge`.
///
/// f64 and both rationals agree on all of them.
#[test]
fn vertical_ray_on_edge() {
    let hilly = families::hilly();
    let top = hilly.z_range().1 + 1.0;
    let z = |i, j| q(hilly.field().z(i, j));
    let two = qi(2);
    let cases = [
        ([2.25, 1.25], q(top) - z(2, 1), [2, 1], 0),
        ([1.5, 3.0], q(top) - (z(1, 3) + z(2, 3)) / two, [1, 2], 1),
        ([4.0, 2.25], q(top) - z(4, 2), [3, 2], 0),
    ];
    for ([x, y], t, cell, triangle) in cases {
        let r = ray([x, y, top], [0.0, 0.0, -1.0]);
        let answer = expect_hit(&hilly, &r, t, cell, triangle);
        assert_rounded_agree(&hilly, &r, &answer);
    }
    assert_family_agrees(&families::vertical_on_edge());
}

/// Rays along grid lines onto a peak sitting on them: [`peak_on_grid_lines`], z(3, 2) = 5,
/// all other heights 0..=3. A path on a grid line touches the cells on both sides; they are
/// visited column by column (row by row for y-major paths), the lower index first.
/// - level along y = 2 at z = 5 from (-1, 2, 5), d = (1, 0, 0): touches the peak at t = 4;
///   first cell containing it: (2, 1) (before (2, 2)), where it is P11: T0. The same with
///   d = (1, -0.0, 0);
/// - descending along y = 2, o = (-1, 2, 6), d = (1, 0, -0.25): also at the peak, t = 4,
///   cell (2, 1), T0;
/// - level along y = 2 from (6, 2, 5), d = (-1, 0, 0): the peak at t = 3; in order for -x the
///   column 3 cells come first, (3, 1) before (3, 2); the peak is P01 of (3, 1): T1;
/// - level along x = 3 from (3, -1, 5), d = (0, 1, 0): the peak at t = 3, cell (2, 1), T0;
/// - and the 288 rays of `families::grid_lines` on an integer field (both directions, with
///   -0.0 zero components, from outside and inside).
///
/// f64 and both rationals agree on all of them.
#[test]
fn ray_along_grid_line() {
    let field = peak_on_grid_lines();
    let cases = [
        ([-1.0, 2.0, 5.0], [1.0, 0.0, 0.0], 4, [2, 1], 0),
        ([-1.0, 2.0, 5.0], [1.0, -0.0, 0.0], 4, [2, 1], 0),
        ([-1.0, 2.0, 6.0], [1.0, 0.0, -0.25], 4, [2, 1], 0),
        ([6.0, 2.0, 5.0], [-1.0, 0.0, 0.0], 3, [3, 1], 1),
        ([3.0, -1.0, 5.0], [0.0, 1.0, 0.0], 3, [2, 1], 0),
    ];
    for (o, d, t, cell, triangle) in cases {
        let r = ray(o, d);
        let answer = expect_hit(&field, &r, qi(t), cell, triangle);
        assert_rounded_agree(&field, &r, &answer);
    }
    assert_family_agrees(&families::grid_lines(
        "grid lines (integer)",
        families::integer_hills(6, 5, 6, 3),
    ));
}

/// A ray whose projection runs along the cell diagonals (through a lattice point at every
/// step, so each step also covers the two cells touching the path only there). 6x6 field, 0
/// except z(2, 2) = 2 and z(3, 3) = 4: the diagonal edge of cell (2, 2) climbs from 2 to 4.
/// The ray o = (0, 0, 0.5), d = (1, 1, 1) (z = x + 0.5) stays above the surface until it
/// meets that edge at (2.5, 2.5, 3): t = 5/2, in cell (2, 2), on the edge T0 and T1 share:
/// T0. Covered: 10 cells (the path ends at t = 3.5 where it leaves the box's top z = 4).
/// Also the 312 rays of `families::cell_diagonals` on an integer field.
///
/// f64 and both rationals agree on all of them.
#[test]
fn ray_along_cell_diagonal() {
    let field = terrain(6, 6, 255, 255.0, |x, y| match (x, y) {
        (2, 2) => 2,
        (3, 3) => 4,
        _ => 0,
    });
    let r = ray([0.0, 0.0, 0.5], [1.0, 1.0, 1.0]);
    let answer = expect_hit(&field, &r, q(2.5), [2, 2], 0);
    assert_eq!(answer.cells.len(), 10);
    assert_rounded_agree(&field, &r, &answer);
    assert_family_agrees(&families::cell_diagonals(
        "cell diagonals (integer)",
        families::integer_hills(6, 5, 6, 3),
    ));
}

/// Oblique rays from above exactly through shared vertices.
///
/// [`three_by_three`], all inputs small integers, through vertex (1, 1, 3) at t = 3 (from
/// tests/suite/float_modes.rs, the smallest case of its watertightness test):
/// - o = (-5, -14, 90), d = (2, 5, -29): y-major; the first cell around the vertex in visiting
///   order is (0, 0), where the vertex is P11: t = 3, cell (0, 0), T0;
/// - o = (7, -14, 90), d = (-2, 5, -29): first (1, 0), vertex P01: t = 3, cell (1, 0), T1.
///
/// Rationals agree (exact arithmetic on small integers). f64 cannot: the watertight test hits,
/// but t = t_scaled / det is rounded differently in each triangle around the vertex, and a
/// triangle later in visiting order gets a t one or two ulps below 3, which wins as the
/// earlier hit. Asserted (every method): the first ray in cell (0, 1), T0, at
/// t = 2.9999999999999996 (one ulp below 3); the second in cell (1, 1), T1, at
/// t = 2.999999999999999 (two ulps below 3). t is within the tolerance; the cell is not the
/// first in visiting order.
///
/// Non-dyadic heights: `families::hilly`, rays o = p - d, d = (h, -z) through the vertices
/// p = (i, j, z) (1,1), (3,2) (plateau), (5,4), (2,4), (4,3) at t = 1, horizontal parts
/// (0.5, 0.25), (-0.75, 0.5), (0.125, -0.0625), (-0.03125, -0.0625): the exact vertical
/// coordinate of o is 2z, so the ray passes exactly through the vertex. Everybody agrees on
/// all 20 (hit at t = 1, the first cell around the vertex in visiting order).
#[test]
fn ray_through_shared_vertex_from_above() {
    let field = three_by_three();
    // (o, d, cell, triangle, f64's cell, triangle and ulps below 3)
    let cases = [
        (
            [-5.0, -14.0, 90.0],
            [2.0, 5.0, -29.0],
            [0, 0],
            0,
            ([0, 1], 0, 1.0),
        ),
        (
            [7.0, -14.0, 90.0],
            [-2.0, 5.0, -29.0],
            [1, 0],
            1,
            ([1, 1], 1, 2.0),
        ),
    ];
    for (o, d, cell, triangle, (f64_cell, f64_triangle, ulps)) in cases {
        let r = ray(o, d);
        let answer = expect_hit(&field, &r, qi(3), cell, triangle);
        let got = assert_rounded(
            &field,
            &r,
            &answer,
            &[(F64, Elsewhere(f64_cell, f64_triangle))],
        );
        // One ulp of 3 is 2^-51 = 2 * f64::EPSILON.
        let t = 3.0 - ulps * 2.0 * f64::EPSILON;
        for g in got.iter().filter(|g| g.arith == F64) {
            assert_eq!(g.hit.as_ref().map(|h| h.t), Some(t), "{}", g.line());
        }
    }

    let hilly = families::hilly();
    for [i, j] in [[1, 1], [3, 2], [5, 4], [2, 4], [4, 3]] {
        let z = hilly.field().z(i, j);
        for [dx, dy] in [
            [0.5, 0.25],
            [-0.75, 0.5],
            [0.125, -0.0625],
            [-0.03125, -0.0625],
        ] {
            let r = ray([i as f64 - dx, j as f64 - dy, 2.0 * z], [dx, dy, -z]);
            let answer = exact(&hilly, &r);
            let hit = answer.hit.as_ref().expect("hits the vertex");
            assert_eq!(hit.t, qi(1), "{}", describe(&r));
            assert_rounded_agree(&hilly, &r, &answer);
        }
    }
}

/// Straight down (d = (0, 0, -1), or with -0.0) onto vertices of [`three_by_three`] from
/// z = 10; the hit is the first cell around the vertex in visiting order, T0 wherever the
/// vertex is that cell's P00, P10 or P11:
/// - interior vertex (1, 1), z = 3: t = 7, cell (0, 0), T0 (P11); the same with
///   d = (-0.0, -0.0, -1) (-0.0 counts as positive);
/// - boundary vertex (2, 1), z = 3, d = (-0.0, 0, -1): cells (1, 0) and (1, 1) touch it;
///   t = 7, cell (1, 0), T0 (P11);
/// - grid corner (0, 0), z = 4: only cell (0, 0) (P00, in both triangles): t = 6, T0;
/// - grid corner (2, 2), z = 0: only cell (1, 1) (P11): t = 10, T0.
///
/// f64 and both rationals agree on all of them.
#[test]
fn ray_straight_down_onto_a_vertex() {
    let field = three_by_three();
    let cases = [
        ([1.0, 1.0], [0.0, 0.0], 7, [0, 0]),
        ([1.0, 1.0], [-0.0, -0.0], 7, [0, 0]),
        ([2.0, 1.0], [-0.0, 0.0], 7, [1, 0]),
        ([0.0, 0.0], [0.0, 0.0], 6, [0, 0]),
        ([2.0, 2.0], [0.0, 0.0], 10, [1, 1]),
    ];
    for ([x, y], [dx, dy], t, cell) in cases {
        let r = ray([x, y, 10.0], [dx, dy, -1.0]);
        let answer = expect_hit(&field, &r, qi(t), cell, 0);
        assert_rounded_agree(&field, &r, &answer);
    }
}

/// A ray starting exactly on a vertex, on the surface, pointing down into the terrain: it
/// touches the surface at t = 0. The hit is the first cell around the vertex in visiting
/// order: the cells touching the path only at its start come first (their contact is [0, 0]),
/// ordered by row, then column, indices negated along negative direction components.
/// [`three_by_three`], vertex (1, 1, 3):
/// - d = (0.5, 0.25, -1): the path continues into (1, 1); first (0, 0) (P11): t = 0, T0;
/// - d = (-0.5, -0.25, -1): continues into (0, 0); first (1, 1) (P00): t = 0, T0;
/// - d = (0, 0, -1): a point; first (0, 0): t = 0, T0;
///
/// `families::hilly`, vertex (1, 1) at its non-dyadic height 8.2, d = (0.5, -0.25, -1):
/// continues into (1, 0); first (0, 1), where the vertex is P10: t = 0, T0.
///
/// f64 and both rationals agree on all of them (f64 reports t = -0.0, which is 0).
#[test]
fn origin_on_a_vertex_pointing_down_into_the_terrain() {
    let field = three_by_three();
    let cases = [
        ([0.5, 0.25, -1.0], [0, 0]),
        ([-0.5, -0.25, -1.0], [1, 1]),
        ([0.0, 0.0, -1.0], [0, 0]),
    ];
    for (d, cell) in cases {
        let r = ray([1.0, 1.0, 3.0], d);
        let answer = expect_hit(&field, &r, qi(0), cell, 0);
        assert_rounded_agree(&field, &r, &answer);
    }
    let hilly = families::hilly();
    let r = ray([1.0, 1.0, hilly.field().z(1, 1)], [0.5, -0.25, -1.0]);
    let answer = expect_hit(&hilly, &r, qi(0), [0, 1], 0);
    assert_rounded_agree(&hilly, &r, &answer);
}

/// A ray along the grid's edge `y = 0` that reaches the box only at its end: it comes down
/// onto the corner sample `(1, 0)`, the field's highest, at `t = 3` exactly, where it leaves
/// the box too. Exact mode's `f64` walk clips the ray to the box in floats: without room for
/// that clip's rounding, the segment would come out empty and every method would miss.
/// (`f64` misses it: it touches at one point, within rounding.)
#[test]
fn ray_touching_the_box_only_at_its_highest_corner() {
    let samples = [104, 816, 365, 308];
    let field = terrain(2, 2, 1000, 1.0, |x, y| samples[y * 2 + x]);
    let r = ray(
        [0.25, 0.0, 3.0335707396316147],
        [0.25, 0.0, -0.7391902465438716],
    );
    expect_hit(&field, &r, q(3.0), [0, 0], 0);
}
