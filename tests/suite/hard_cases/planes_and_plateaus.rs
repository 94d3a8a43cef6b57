//! Hard cases in or just above a triangle's plane: grazing plateaus, coplanar rays.

use super::*;

/// Level rays exactly at the height H of a plateau, entering it over its edge: `mesa(77)`,
/// H = 7.7 (the f64 8669429282688205 / 2^50, not a decimal fraction). The plateau is the
/// highest thing on the field, so the rays run in the box's top face. They reach the
/// plateau's west edge x = 3 at t = 4 and touch the surface first there: on the right edge of
/// the ramp cell (2, 2) (X = 1, which only T0 reaches), which comes before the plateau cell
/// (3, 2) in visiting order. Expected: t = 4, cell (2, 2), T0, for
/// - o = (-1, 2.5, H), d = (1, 0, 0);
/// - o = (-1, 1.5, H), d = (1, 0.25, 0) (at x = 3, y = 2.5);
/// - and the 94 rays of `families::plateau_level` (level rays at the plateau height of
///   `hilly`, across it, along its edges and diagonal, from outside and on it).
///
/// f64 and both rationals agree on all: for a level ray the sheared height of every vertex
/// is its height minus H, exact in f64 (Sterbenz); rationals round H and the ray's height to
/// the same 77/10.
#[test]
fn grazing_flat_plateau() {
    let mesa = mesa(77);
    let h = mesa.field().z(3, 1);
    assert_eq!(mesa.z_range().1, h);
    for bound in [1 << 16, 1 << 24] {
        assert_eq!(rational(bound, h), Ratio::new(77, 10));
    }
    for (o, d) in [
        ([-1.0, 2.5, h], [1.0, 0.0, 0.0]),
        ([-1.0, 1.5, h], [1.0, 0.25, 0.0]),
    ] {
        let r = ray(o, d);
        let answer = expect_hit(&mesa, &r, qi(4), [2, 2], 0);
        assert_rounded_agree(&mesa, &r, &answer);
    }
    assert_family_agrees(&families::plateau_level());
}

/// The rays of [`grazing_flat_plateau`] one ulp higher, at z = next_up(H) = 7.700000000000001
/// (8.9e-16 above the plateau): they pass above the box's top face, so exact misses (no
/// covered cells at all). f64 misses too (the slab test compares the exact inputs).
///
/// Rationals cannot: from_f64 rounds both H and next_up(H) to 77/10 (under 2^16 and 2^24), so
/// the rounded ray lies exactly at the plateau's height and grazes it like the ray of
/// [`grazing_flat_plateau`]. Asserted: rational:2^16 and rational:2^24, every method, report a
/// spurious hit at t = 4 in cell (2, 2), T0.
#[test]
fn grazing_above_plateau_by_one_ulp() {
    let mesa = mesa(77);
    let h = mesa.field().z(3, 1);
    let above = h.next_up();
    assert_eq!(q(above) - q(h), q(2f64.powi(-50)), "one ulp of 7.7");
    for bound in [1 << 16, 1 << 24] {
        assert_eq!(rational(bound, above), rational(bound, h));
    }
    for (o, d) in [
        ([-1.0, 2.5, above], [1.0, 0.0, 0.0]),
        ([-1.0, 1.5, above], [1.0, 0.25, 0.0]),
    ] {
        let r = ray(o, d);
        let answer = expect_miss(&mesa, &r);
        assert!(answer.cells.is_empty());
        let spurious = SpuriousHit([2, 2], 0);
        let got = assert_rounded(&mesa, &r, &answer, &[(R16, spurious), (R24, spurious)]);
        for g in got.iter().filter(|g| g.arith != F64) {
            assert_eq!(g.hit.as_ref().map(|h| h.t), Some(4.0), "{}", g.line());
        }
    }
}

/// Level rays exactly along a cell's diagonal edge at the edge's height: 6x6 fields, 0 except
/// z(2, 2) = z(3, 3) = H (the flat diagonal edge of cell (2, 2)) and z(3, 2) = z(2, 3) = L
/// below it; integer heights H = 5, L = 1, and non-dyadic ones H = 7.7, L = 1 (0.1 * sample).
/// The ray lies in the planes of both triangles of cell (2, 2) (coplanar case) and passes
/// through the vertices (2, 2) and (3, 3). On both fields:
/// - o = (0, 0, H), d = (1, 1, 0): first touch at vertex (2, 2), t = 2; the first cell around
///   it in visiting order is (1, 1), where it is P11: cell (1, 1), T0;
/// - o = (5, 5, H), d = (-1, -1, -0.0): first touch at vertex (3, 3), t = 2; the first cell
///   is (3, 3) (P00): T0;
/// - o = (2.5, 2.5, H), d = (1, 1, 0), starting in the middle of the edge: t = 0, cell
///   (2, 2), T0;
/// - on the non-dyadic field also o = (0.3, 0.3, H), d = (0.7, 0.7, 0): first touch at vertex
///   (2, 2), t = (2 - 0.3) / 0.7 on the exact f64 values, cell (1, 1), T0.
///
/// f64 and both rationals agree on all of them.
#[test]
fn level_ray_along_a_diagonal_edge_at_its_height() {
    let integer = terrain(6, 6, 255, 255.0, |x, y| match (x, y) {
        (2, 2) | (3, 3) => 5,
        (3, 2) | (2, 3) => 1,
        _ => 0,
    });
    let decimal = terrain(6, 6, 255, 25.5, |x, y| match (x, y) {
        (2, 2) | (3, 3) => 77,
        (3, 2) | (2, 3) => 10,
        _ => 0,
    });
    for field in [&integer, &decimal] {
        let h = field.field().z(2, 2);
        let cases = [
            ([0.0, 0.0, h], [1.0, 1.0, 0.0], 2, [1, 1]),
            ([5.0, 5.0, h], [-1.0, -1.0, -0.0], 2, [3, 3]),
            ([2.5, 2.5, h], [1.0, 1.0, 0.0], 0, [2, 2]),
        ];
        for (o, d, t, cell) in cases {
            let r = ray(o, d);
            let answer = expect_hit(field, &r, qi(t), cell, 0);
            assert_rounded_agree(field, &r, &answer);
        }
    }
    let h = decimal.field().z(2, 2);
    let r = ray([0.3, 0.3, h], [0.7, 0.7, 0.0]);
    let answer = expect_hit(&decimal, &r, (qi(2) - q(0.3)) / q(0.7), [1, 1], 0);
    assert_rounded_agree(&decimal, &r, &answer);
}

/// A ray lying in the plane of sloped triangles: 4x4 field z = x + 2y + 1 (one plane,
/// integer heights).
/// - o = (-1, 0.5, 1), d = (1, 0.25, 1.5): in the plane (all inputs dyadic); it touches the
///   surface first where it enters the grid, (0, 0.75) at t = 1: cell (0, 0), in T1 (X <= Y).
///   Rationals agree (the inputs are small fractions). f64 cannot: the triangle test shears
///   by dx/dz = 2/3 and dy/dz = 1/6, which round, so in ray space the triangles are thin
///   slivers instead of segments through the ray: the coplanar case is not recognised and t
///   comes out of a near-zero determinant. Asserted (every method): f64 reports
///   cell (0, 0), T0, at t = 2.0 (the cell's far edge), `Elsewhere([0, 0], 0)`.
/// - o = (-1, 0.3, 0.6), d = (1, 0.3, 1.6): the same in decimal, but not in f64: the origin is
///   exactly in the plane (0.6 = 2 * 0.3 in f64) and the direction climbs 1.6 - 1 - 2 * 0.3
///   = 2^-53 per unit t faster than the plane: the exact ray is above the surface for every
///   t > 0 and misses. Rationals round 0.3, 0.6, 1.6 to 3/10, 3/5, 8/5, back into the plane,
///   and hit where it enters the grid: `SpuriousHit([0, 0], 1)` at t = 1 (both bounds). f64:
///   `SpuriousHit([1, 1], 0)` at t = 3.0. All asserted.
#[test]
fn ray_in_the_plane_of_a_sloped_surface() {
    let plane = terrain(4, 4, 255, 255.0, |x, y| (x + 2 * y + 1) as u16);

    let r = ray([-1.0, 0.5, 1.0], [1.0, 0.25, 1.5]);
    let answer = expect_hit(&plane, &r, qi(1), [0, 0], 1);
    let got = assert_rounded(&plane, &r, &answer, &[(F64, Elsewhere([0, 0], 0))]);
    for g in got.iter().filter(|g| g.arith == F64) {
        assert_eq!(g.hit.as_ref().map(|h| h.t), Some(2.0), "{}", g.line());
    }

    let r = ray([-1.0, 0.3, 0.6], [1.0, 0.3, 1.6]);
    assert_eq!(q(0.6) - (q(-1.0) + qi(2) * q(0.3) + qi(1)), qi(0));
    assert_eq!(q(1.6) - qi(1) - qi(2) * q(0.3), q(2f64.powi(-53)));
    let answer = expect_miss(&plane, &r);
    let got = assert_rounded(
        &plane,
        &r,
        &answer,
        &[
            (F64, SpuriousHit([1, 1], 0)),
            (R16, SpuriousHit([0, 0], 1)),
            (R24, SpuriousHit([0, 0], 1)),
        ],
    );
    for g in &got {
        let t = if g.arith == F64 { 3.0 } else { 1.0 };
        assert_eq!(g.hit.as_ref().map(|h| h.t), Some(t), "{}", g.line());
    }
}
