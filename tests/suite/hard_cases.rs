//! A catalogue of numerically hard cases: one test per case, each with its expected answer
//! written down in its doc comment.
//!
//! For every ray of every case:
//! - exact mode, every method, must equal the brute-force reference of
//!   tests/common/reference.rs exactly: hit or miss, exact t, cell, triangle, covered cells,
//!   recorded cells and counters (`common::check_exact_against`); the reference's answer is
//!   also checked against the expectation written in the comment;
//! - `f64` and bounded rationals (bound 2^16 and 2^24), every method, must find the same first
//!   hit as exact: same cell and triangle and `|t - t_exact| <= 1e-9 * max(|t_exact|, 1)`, or
//!   both miss. Where an arithmetic cannot, the comment says why, with its numbers, and the
//!   test asserts exactly what it does instead (a [`Verdict`] per arithmetic).
//!
//! Two tests hold the walks on extreme slopes ("Extreme slopes" below): the run walk of a path
//! with a slope below about 2^-63 must still cover its cells (exact mode included), and the
//! `f64` DDA of a path with a subnormal minor component must stay in its row.
//!
//! The rounded-mode numbers (which rays disagree, by how much) are characterization snapshots
//! of the `f64` and bounded-rational arithmetic as it is, not a promise: a change there that
//! moves them makes these tests fail on purpose, for the numbers and their explanations to be
//! brought up to date.

use crate::common::families::{self, hash, ray, terrain, Family};
use crate::common::reference::{self, q, qi, Answer, Q};
use crate::common::{check_exact_against, describe, options, try_trace, METHODS};
use heightray::traverse::{covered_cells, with_bound, Rational, Scalar};
use heightray::{Arith, Hit, Method, Ray, Terrain};
use num_rational::Ratio;
use num_traits::ToPrimitive;

const F64: Arith = Arith::F64;
const R16: Arith = Arith::Rational { bound: 1 << 16 };
const R24: Arith = Arith::Rational { bound: 1 << 24 };
/// The rounded arithmetics compared with exact.
const ROUNDED: [Arith; 3] = [F64, R16, R24];
/// `|t - t_exact| <= T_TOLERANCE * max(|t_exact|, 1)` counts as the same t.
const T_TOLERANCE: f64 = 1e-9;

// ---------------------------------------------------------------------------------------
// Comparing answers.

/// How a rounded answer compares with the exact one.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Verdict {
    /// Both miss, or both hit the same cell and triangle with t within the tolerance.
    Agrees,
    /// Exact hits; the rounded arithmetic misses.
    Misses,
    /// Exact misses; the rounded arithmetic hits this cell and triangle.
    SpuriousHit([usize; 2], u8),
    /// Both hit, the rounded arithmetic in this other cell or triangle.
    Elsewhere([usize; 2], u8),
    /// Same cell and triangle, but t off by more than the tolerance.
    TOff,
}
use Verdict::*;

/// `|t - t_exact| / max(|t_exact|, 1)`.
fn t_error(t: f64, exact: &Q) -> f64 {
    let e = exact.to_f64().expect("finite t");
    (t - e).abs() / e.abs().max(1.0)
}

fn judge(got: &Option<Hit>, answer: &Answer) -> Verdict {
    match (got, &answer.hit) {
        (None, None) => Agrees,
        (None, Some(_)) => Misses,
        (Some(g), None) => SpuriousHit(g.cell, g.triangle),
        (Some(g), Some(e)) if (g.cell, g.triangle) != (e.cell, e.triangle) => {
            Elsewhere(g.cell, g.triangle)
        }
        (Some(g), Some(e)) if t_error(g.t, &e.t) > T_TOLERANCE => TOff,
        _ => Agrees,
    }
}

fn describe_hit(hit: &Option<Hit>) -> String {
    hit.as_ref().map_or("miss".into(), |h| {
        format!("t={:?} cell={:?} T{}", h.t, h.cell, h.triangle)
    })
}

fn describe_answer(answer: &Answer) -> String {
    answer.hit.as_ref().map_or("miss".into(), |h| {
        format!(
            "t={} (~{:?}) cell={:?} T{}",
            h.t,
            h.t.to_f64().unwrap_or(f64::NAN),
            h.cell,
            h.triangle
        )
    })
}

/// One rounded answer to one ray.
#[derive(Clone, Debug)]
struct Rounded {
    arith: Arith,
    method: Method,
    verdict: Verdict,
    hit: Option<Hit>,
}

impl Rounded {
    fn line(&self) -> String {
        format!(
            "{} {}: {:?} ({})",
            self.arith,
            self.method,
            self.verdict,
            describe_hit(&self.hit)
        )
    }
}

/// The answers of f64, rational:2^16 and rational:2^24, every method, to one ray.
fn rounded(terrain: &Terrain, ray: &Ray, answer: &Answer) -> Vec<Rounded> {
    let mut out = Vec::new();
    for arith in ROUNDED {
        for method in METHODS {
            let got = try_trace(terrain, ray, &options(method, arith))
                .unwrap_or_else(|e| panic!("{}: {e}", describe(ray)));
            out.push(Rounded {
                arith,
                method,
                verdict: judge(&got.hit, answer),
                hit: got.hit,
            });
        }
    }
    out
}

/// Solves the ray with the reference and checks exact mode (every method) against it.
fn exact(terrain: &Terrain, ray: &Ray) -> Answer {
    let answer = reference::solve(terrain.field(), ray);
    let problems = check_exact_against(terrain, ray, &answer);
    assert!(
        problems.is_empty(),
        "exact mode disagrees with the reference on {}:\n  {}",
        describe(ray),
        problems.join("\n  ")
    );
    answer
}

/// [`exact`], and the reference's answer is a hit at exactly `t` in `cell`, `triangle`.
fn expect_hit(terrain: &Terrain, ray: &Ray, t: Q, cell: [usize; 2], triangle: u8) -> Answer {
    let answer = exact(terrain, ray);
    expect_hit_in(&answer, ray, cell, triangle);
    let hit = answer.hit.as_ref().expect("checked");
    assert_eq!(hit.t, t, "reference t for {}", describe(ray));
    answer
}

/// The reference's answer is a hit in `cell`, `triangle`.
fn expect_hit_in(answer: &Answer, ray: &Ray, cell: [usize; 2], triangle: u8) {
    let hit = answer
        .hit
        .as_ref()
        .unwrap_or_else(|| panic!("reference misses {}", describe(ray)));
    assert_eq!(
        (hit.cell, hit.triangle),
        (cell, triangle),
        "reference answer for {}: {}",
        describe(ray),
        describe_answer(answer)
    );
}

/// [`exact`], and the reference's answer is a miss.
fn expect_miss(terrain: &Terrain, ray: &Ray) -> Answer {
    let answer = exact(terrain, ray);
    assert!(
        answer.hit.is_none(),
        "reference hits {}: {}",
        describe(ray),
        describe_answer(&answer)
    );
    answer
}

/// Asserts the verdict of every rounded answer: `expected` lists the arithmetics that do not
/// agree (with the verdict of every method); all others must agree. Returns the answers.
fn assert_rounded(
    terrain: &Terrain,
    ray: &Ray,
    answer: &Answer,
    expected: &[(Arith, Verdict)],
) -> Vec<Rounded> {
    let got = rounded(terrain, ray, answer);
    let wanted = |arith: Arith| {
        expected
            .iter()
            .find(|(a, _)| *a == arith)
            .map_or(Agrees, |(_, v)| *v)
    };
    let wrong: Vec<String> = got
        .iter()
        .filter(|r| r.verdict != wanted(r.arith))
        .map(|r| format!("{} (documented: {:?})", r.line(), wanted(r.arith)))
        .collect();
    assert!(
        wrong.is_empty(),
        "{}: exact {}; rounded answers not as documented:\n  {}\nall rounded answers:\n  {}",
        describe(ray),
        describe_answer(answer),
        wrong.join("\n  "),
        got.iter()
            .map(Rounded::line)
            .collect::<Vec<_>>()
            .join("\n  ")
    );
    got
}

fn assert_rounded_agree(terrain: &Terrain, ray: &Ray, answer: &Answer) {
    assert_rounded(terrain, ray, answer, &[]);
}

/// Every ray of a family: exact mode against the reference (all must match), and the rounded
/// answers.
fn run_family(family: &Family) -> Vec<(Answer, Vec<Rounded>)> {
    assert!(!family.rays.is_empty(), "{}: no rays", family.name);
    let mut problems = Vec::new();
    let mut out = Vec::new();
    for r in &family.rays {
        let answer = reference::solve(family.terrain.field(), r);
        let p = check_exact_against(&family.terrain, r, &answer);
        if !p.is_empty() {
            problems.push(format!("{}\n    {}", describe(r), p.join("\n    ")));
        }
        let got = rounded(&family.terrain, r, &answer);
        out.push((answer, got));
    }
    assert!(
        problems.is_empty(),
        "{}: {} of {} rays disagree with the reference in exact mode; the first ones:\n{}",
        family.name,
        problems.len(),
        family.rays.len(),
        problems
            .iter()
            .take(8)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
    out
}

/// The rounded answers of a family that do not agree with exact: (ray index, answer).
fn family_disagreements(results: &[(Answer, Vec<Rounded>)]) -> Vec<(usize, Rounded)> {
    results
        .iter()
        .enumerate()
        .flat_map(|(n, (_, got))| {
            got.iter()
                .filter(|r| r.verdict != Agrees)
                .map(move |r| (n, r.clone()))
        })
        .collect()
}

fn list(family: &Family, disagreements: &[(usize, Rounded)]) -> String {
    disagreements
        .iter()
        .map(|(n, r)| format!("{}: {}", describe(&family.rays[*n]), r.line()))
        .collect::<Vec<_>>()
        .join("\n  ")
}

/// Exact mode matches the reference and every rounded answer agrees, on every ray.
fn assert_family_agrees(family: &Family) {
    let results = run_family(family);
    let d = family_disagreements(&results);
    assert!(
        d.is_empty(),
        "{}: {} rounded answers disagree with exact:\n  {}",
        family.name,
        d.len(),
        list(family, &d)
    );
}

/// `x` as a bounded rational under `bound`.
fn rational(bound: u32, x: f64) -> Ratio<i64> {
    with_bound(bound, || Rational::from_f64(x).ratio()).0
}

/// Whether the point (x, y) lies in the closed triangle `triangle` of `cell`.
fn in_triangle([x, y]: [f64; 2], [i, j]: [usize; 2], triangle: u8) -> bool {
    let (u, v) = (x - i as f64, y - j as f64);
    if triangle == 0 {
        0.0 <= v && v <= u && u <= 1.0
    } else {
        0.0 <= u && u <= v && v <= 1.0
    }
}

// ---------------------------------------------------------------------------------------
// Fields.

/// 8x5, heights 0.1 * sample (`z_scale` 25.5, maxval 255): 0 everywhere except a plateau of
/// `sample` over samples x 3..=5, y 1..=3 (its four cells are flat; the cells around them
/// ramp up to it).
fn mesa(sample: u16) -> Terrain {
    terrain(8, 5, 255, 25.5, move |x, y| {
        if (3..=5).contains(&x) && (1..=3).contains(&y) {
            sample
        } else {
            0
        }
    })
}

/// 3x3 integer heights (y up): y=0: 4 2 1, y=1: 3 3 3, y=2: 4 4 0 (the smallest watertightness
/// case of tests/suite/float_modes.rs).
fn three_by_three() -> Terrain {
    let samples = [4, 2, 1, 3, 3, 3, 4, 4, 0];
    terrain(3, 3, 255, 255.0, move |x, y| samples[y * 3 + x])
}

/// 6x5 integer heights 0..=3, except z(3, 2) = 5: a single peak on the grid lines x = 3, y = 2.
fn peak_on_grid_lines() -> Terrain {
    terrain(6, 5, 255, 255.0, |x, y| {
        if (x, y) == (3, 2) {
            5
        } else {
            hash(x, y, 3, 4)
        }
    })
}

/// The 16385x3 strip: 16384x2 cells, flat 0 except a spike of 255 at sample (16383, 1).
fn strip() -> Terrain {
    terrain(16385, 3, 255, 255.0, |x, y| {
        if (x, y) == (16383, 1) {
            255
        } else {
            0
        }
    })
}

// ---------------------------------------------------------------------------------------
// The catalogue.

/// Slope 17/41 and its mirrors on the 44x44 integer field of `families::lattice_slope`: 360
/// rays through lattice points (where the path passes a lattice point, four cells meet there),
/// at the vertex height, half a unit above and above everything, level, descending
/// (dz = -1/64) and climbing (dz = 1/128), starting before the lattice point or on it.
///
/// Expected: exact mode (every method) equals the reference on all 360 rays. f64 and
/// rational:2^24 find the same first hit on all of them.
///
/// rational:2^16 cannot on 6 rays (one answer per method, every method alike): right cell and
/// triangle, but t off by more than 1e-9 relative (up to 1.2e-8). All 6 climb or descend
/// (dz != 0): the triangle test shears by dy/dx = 17/41 and dz/dx = 1/5248 (or -1/2624), and
/// its edge functions multiply sheared coordinates with denominators 41 and 5248, whose
/// product is beyond 2^16 and gets rounded. Level rays have no such products: their 2^16
/// traces round nothing at all (asserted: zero rounding events on all 120). Asserted: exactly
/// 6 rays, rational:2^16 only, verdict `TOff`, dz != 0, error below 2e-8.
#[test]
fn lattice_point_slope_17_41() {
    let family = families::lattice_slope(17, 41);
    assert_eq!(family.rays.len(), 360, "the family changed: re-measure");
    let results = run_family(&family);
    let d = family_disagreements(&results);
    let text = list(&family, &d);
    assert_eq!(d.len(), 6 * METHODS.len(), "disagreements:\n  {text}");
    let mut rays: Vec<usize> = d.iter().map(|(n, _)| *n).collect();
    rays.dedup();
    assert_eq!(rays.len(), 6, "disagreements:\n  {text}");
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

/// Nearly vertical rays, horizontal part about 1e-12, on `families::hilly`.
///
/// Specific rays, down from z = zmax + 1 = 20.8 (the box is entered at t = 1, by then the path
/// has moved about 1e-12 off its start):
/// - o = (3, 2, 20.8) on the plateau vertex, d = (1e-12, 1e-12, -1): the path enters the flat
///   cell (3, 2) along its diagonal: t = 20.8 - 10, cell (3, 2), T0 (exact, f64);
/// - o = (2.3, 1.6, 20.8) inside a triangle, d = (1e-12, 0, -1): t = 20.8 - 10, cell (2, 1),
///   T1; everybody agrees.
///
/// Rationals cannot follow the first one: 1e-12, 3e-13 and 7e-13 round to 0 under 2^16 and
/// 2^24 (they are below 1/2^25), so the ray becomes vertical and is answered like the
/// vertical ray of [`vertical_ray_on_corner`]: the first cell around the vertex in visiting
/// order, (2, 1), T0, same t. Asserted: `Elsewhere([2, 1], 0)` for both bounds.
///
/// The 72 rays of `families::near_vertical` (six tiny directions in every octant, down and
/// up, from points inside a triangle, on a diagonal, on a vertex, on the grid's corner and
/// boundary, on an edge): exact matches the reference and f64 agrees on all 72. Rationals
/// disagree on 38 rays (both bounds, every method: 76 answers per method), exactly those whose
/// start point is on a vertex or an edge of the mesh (or on the grid's boundary, where the
/// exact ray may leave the box and miss), never for the point inside a triangle. Asserted for
/// every rational answer: it hits or misses like the vertical ray through the same start point,
/// at that ray's t (within the tolerance), in a triangle containing the start point's (x, y):
/// the rounded ray is that vertical ray, only the choice among the triangles sharing the point
/// follows the signs of the original direction.
#[test]
fn near_vertical_ray_1e_12() {
    let hilly = families::hilly();
    let top = hilly.z_range().1 + 1.0;
    for bound in [1 << 16, 1 << 24] {
        for tiny in [1e-12, -1e-12, 3e-13, 7e-13, -7e-13] {
            assert_eq!(rational(bound, tiny), Ratio::from_integer(0));
        }
    }
    let r = ray([3.0, 2.0, top], [1e-12, 1e-12, -1.0]);
    let answer = expect_hit(&hilly, &r, q(top) - qi(10), [3, 2], 0);
    let vertical = Elsewhere([2, 1], 0);
    assert_rounded(&hilly, &r, &answer, &[(R16, vertical), (R24, vertical)]);

    let r = ray([2.3, 1.6, top], [1e-12, 0.0, -1.0]);
    let answer = expect_hit(&hilly, &r, q(top) - qi(10), [2, 1], 1);
    assert_rounded_agree(&hilly, &r, &answer);

    let family = families::near_vertical();
    assert_eq!(family.rays.len(), 72, "the family changed: re-measure");
    let results = run_family(&family);
    let d = family_disagreements(&results);
    let text = list(&family, &d);
    assert!(d.iter().all(|(_, r)| r.arith != F64), "f64:\n  {text}");
    let mut rays: Vec<usize> = d.iter().map(|(n, _)| *n).collect();
    rays.dedup();
    assert_eq!(
        (d.len(), rays.len()),
        (76 * METHODS.len(), 38),
        "disagreements:\n  {text}"
    );
    for (n, (_, got)) in results.iter().enumerate() {
        let r = &family.rays[n];
        let [x, y, _] = r.origin();
        let on_mesh_edge = x.fract() == 0.0 || y.fract() == 0.0 || x.fract() == y.fract();
        assert!(
            on_mesh_edge || !rays.contains(&n),
            "rationals disagree on a ray starting inside a triangle: {}",
            describe(r)
        );
        let vertical = ray(r.origin(), [0.0, 0.0, r.dir()[2]]);
        let v = reference::solve(family.terrain.field(), &vertical);
        for g in got.iter().filter(|g| g.arith != F64) {
            match (&g.hit, &v.hit) {
                (None, None) => {}
                (Some(h), Some(e)) => {
                    assert!(
                        t_error(h.t, &e.t) <= T_TOLERANCE
                            && in_triangle([x, y], h.cell, h.triangle),
                        "{}: {} is not the vertical ray's hit {}",
                        describe(r),
                        g.line(),
                        describe_answer(&v)
                    );
                }
                _ => panic!(
                    "{}: {} but the vertical ray: {}",
                    describe(r),
                    g.line(),
                    describe_answer(&v)
                ),
            }
        }
    }
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

/// Origin about 1e6 units away, shallow angle: d = (1, 0.3141592653589793,
/// -0.002718281828459045) (a descent of 1 in 368), o = p - 1e6 d rounded to f64, on
/// `families::integer_hills(9, 9, 6, 11)`; the box is entered at t = 1e6 (x = 0).
/// - p = (0, 1.7, 2.5): t = 1000002.6232173..., cell (2, 2), T0; everybody agrees
///   (rational:2^16 within 3e-11 relative);
/// - p = (0, 1.7, 1.7): t = 1000002.4119069..., cell (2, 2), T1; f64 and rational:2^24 agree.
///
/// rational:2^16 cannot on the second: it stores dy = 0.3141592653589793 as 71/226 (2.7e-8
/// too large; the best fraction with a denominator up to 2^16) and dz as -141/51871, so at
/// t = 1e6 its path is 0.027 off in y; the triangle slopes across the path and the hit moves
/// by 7.9e-3 in t: 7.9e-9 relative, same cell and triangle. Asserted: `TOff` for
/// rational:2^16 (every method), error between 1e-9 and 1e-8. (Under 2^24 dy is
/// 4220840/13435351, off by less than 1e-14.)
#[test]
fn long_distance_origin_far_away() {
    let field = families::integer_hills(9, 9, 6, 11);
    let d = [1.0, 0.3141592653589793, -0.002718281828459045];
    assert_eq!(rational(1 << 16, d[1]), Ratio::new(71, 226));
    assert_eq!(rational(1 << 16, d[2]), Ratio::new(-141, 51871));
    let drift = (q(71.0) / q(226.0) - q(d[1])) * q(1e6);
    assert!((0.026..0.027).contains(&drift.to_f64().unwrap()));
    let r24 = rational(1 << 24, d[1]);
    let r24 = q(*r24.numer() as f64) / q(*r24.denom() as f64) - q(d[1]);
    assert!(r24.to_f64().unwrap().abs() < 1e-14);

    let cases = [(2.5, [2, 2], 0, false), (1.7, [2, 2], 1, true)];
    for (pz, cell, triangle, r16_off) in cases {
        let p = [0.0, 1.7, pz];
        let r = ray([0, 1, 2].map(|k| p[k] - 1e6 * d[k]), d);
        let answer = exact(&field, &r);
        expect_hit_in(&answer, &r, cell, triangle);
        let t = answer.hit.as_ref().expect("hit").t.clone();
        assert!((1_000_002.0..1_000_003.0).contains(&t.to_f64().unwrap()));
        let expected: &[(Arith, Verdict)] = if r16_off { &[(R16, TOff)] } else { &[] };
        let got = assert_rounded(&field, &r, &answer, expected);
        for g in got.iter().filter(|g| g.arith == R16 && r16_off) {
            let error = t_error(g.hit.as_ref().expect("hit").t, &t);
            assert!((1e-9..1e-8).contains(&error), "{error:e}: {}", g.line());
        }
    }
}

/// The 16385x3 strip ([`strip`]: 16384x2 cells, flat 0, a spike of 255 at sample
/// (16383, 1)); shallow rays at z = 1 cross the whole strip (slope about 1/16666, an awkward
/// rational 3/49999 in y per x, from the non-dyadic intercept 0.3) and must hit the spike, not
/// anything before it. The run walk skips the flat part run by run; DDA visits every cell.
/// - o = (0, 0.3, 1), d = (49999, 3, 0): crosses y = 1 at x = 11666.4; hits the spike's west
///   face at x = 16382.3 (t = 0.32765229...): cell (16382, 1), T0;
/// - o = (0, 1.7, 1), d = (49999, -3, 0): mirrored: cell (16382, 0), T1;
/// - o = (0, 0.3, 2), d = (49999, 3, -3): descending from 2 to 1.02: cell (16382, 1), T0;
/// - o = (-1, 0.3, 1), d = (1, 3/49999 rounded to f64, 0): from outside, t ≈ 16383.29:
///   cell (16382, 1), T0.
///
/// Exact mode matches the reference (all 16385 covered cells and the counters). f64 and
/// both rationals find the same hit; rational:2^16 rounds (17 to 35 rounding events per
/// trace) and its t is off by up to 6.8e-10 relative, within the tolerance.
#[test]
fn shallow_ray_16384_cells() {
    let strip = strip();
    let cases = [
        ([0.0, 0.3, 1.0], [49999.0, 3.0, 0.0], [16382, 1], 0),
        ([0.0, 1.7, 1.0], [49999.0, -3.0, 0.0], [16382, 0], 1),
        ([0.0, 0.3, 2.0], [49999.0, 3.0, -3.0], [16382, 1], 0),
        ([-1.0, 0.3, 1.0], [1.0, 3.0 / 49999.0, 0.0], [16382, 1], 0),
    ];
    for (o, d, cell, triangle) in cases {
        let r = ray(o, d);
        let answer = exact(&strip, &r);
        assert_eq!(answer.cells.len(), 16385, "{}", describe(&r));
        expect_hit_in(&answer, &r, cell, triangle);
        assert_rounded_agree(&strip, &r, &answer);
    }
}

/// "Long walks must not drift: the run recurrence in rational and exact modes lands on the
/// exact cells at the far end." Compares `covered_cells` (runs, and DDA too) in exact,
/// rational:2^16, rational:2^24 (and f64) with the reference's cell list, whole and its last
/// 100 cells.
///
/// Representable rays: slope 1/16384 and intercept 0.5 + 1/65536 on [`strip`]: o =
/// (0, 0.5 + 2^-16, 1), with d = (16384, 1, 0) and with d = (1, 2^-14, 0). Under both bounds
/// the slope is exactly 1/16384 and the first intercept (at x = 1) 32773/65536, a multiple of
/// 1/(16384 * 4): the recurrence is exact, and the walks round nothing at all (zero rounding
/// events, asserted). The path crosses y = 1 at x = 8191.75. Also slope 1/512 with the same
/// intercept on a 16385x33 field: 32 runs of 512 cells. Expected and asserted: every
/// arithmetic and method gives exactly the reference's cells (16385, 16385 and 16159).
///
/// A slope NOT representable within 2^16: d = (65537, 4, 0), o = (0, 0.00514, 1). rational:2^16
/// rounds the slope 4/65537 to 3/49153 (3.1e-10 per column too small) and the first
/// intercept to 256/49153, which puts the rounded path's crossing of y = 1 exactly on the
/// lattice point (16300, 1) (16299 runs of 3/49153 from 256/49153). The exact path crosses at
/// x = 16300.035, passing 2.1e-6 below that lattice point. So the 2^16 run walk also covers
/// (16299, 1), which touches its path at the lattice point and not the exact one: 16386 cells
/// instead of 16385, the same cells up to index 16300, the extra (16299, 1) at index 16301,
/// then the same 84 last cells. Asserted exactly that; compared position by
/// position from the end, 16 of the last 100 cells differ (the extra one, 85th from the end,
/// and the 15 before it, shifted by one place), the last 84 are right. The 2^16 DDA (asserted
/// too) instead steps its u crossings by 1/du rounded to 1/65536: after 16300 steps they are
/// 3.8e-6 late in t, a quarter column, so it crosses y = 1 in column 16299: same length, one
/// cell differs, at index 16300: (16299, 1) instead of (16300, 0). rational:2^24 (which keeps
/// 4/65537 and an intercept on a 1/(65537 * 255) grid), exact and f64, every method: the
/// reference's cells.
#[test]
fn shallow_ray_16384_cells_lands_on_exact_cells() {
    const TAIL: usize = 100;
    let tail = |cells: &[[usize; 2]]| cells[cells.len().saturating_sub(TAIL)..].to_vec();
    let modes = [Arith::Exact, R16, R24, F64];
    let strip = strip();
    let tall = terrain(16385, 33, 255, 255.0, |x, y| {
        if (x, y) == (16383, 31) {
            255
        } else {
            0
        }
    });
    let y0 = 0.5 + 2f64.powi(-16);

    // Representable within both bounds.
    for bound in [1 << 16, 1 << 24] {
        let ((slope, beta), events) = with_bound(bound, || {
            let a = Rational::from_f64(1.0) / Rational::from_f64(16384.0);
            let beta = (Rational::from_f64(y0) + a).align_to(&a);
            (a.ratio(), beta.ratio())
        });
        assert_eq!(
            (slope, beta),
            (Ratio::new(1, 16384), Ratio::new(32773, 65536))
        );
        assert_eq!(events.rounded, 0);
    }
    let representable = [
        (&strip, ray([0.0, y0, 1.0], [16384.0, 1.0, 0.0]), 16385),
        (
            &strip,
            ray([0.0, y0, 1.0], [1.0, 2f64.powi(-14), 0.0]),
            16385,
        ),
        (&tall, ray([0.0, y0, 1.0], [512.0, 1.0, 0.0]), 16159),
    ];
    for (field, r, count) in representable {
        let expected = reference::solve(field.field(), &r).cell_list();
        assert_eq!(expected.len(), count, "{}", describe(&r));
        for arith in modes {
            for method in METHODS {
                let (got, events) = match arith {
                    Arith::Rational { bound } => {
                        with_bound(bound, || covered_cells(field, &r, method, arith))
                    }
                    _ => (covered_cells(field, &r, method, arith), Default::default()),
                };
                assert_eq!(events.rounded, 0, "{arith} {method}: {}", describe(&r));
                assert_eq!(
                    tail(&got),
                    tail(&expected),
                    "{arith} {method}: last cells of {}",
                    describe(&r)
                );
                assert!(got == expected, "{arith} {method}: {}", describe(&r));
            }
        }
    }

    // Not representable within 2^16.
    let ((slope, beta), events) = with_bound(1 << 16, || {
        let a = Rational::from_f64(4.0) / Rational::from_f64(65537.0);
        let beta = (Rational::from_f64(0.00514) + a).align_to(&a);
        (a.ratio(), beta.ratio())
    });
    assert_eq!(
        (slope, beta),
        (Ratio::new(3, 49153), Ratio::new(256, 49153))
    );
    assert!(events.rounded > 0);
    assert_eq!(
        1 + (49153 - 256) / 3,
        16300,
        "lattice crossing of the rounded path"
    );
    let r = ray([0.0, 0.00514, 1.0], [65537.0, 4.0, 0.0]);
    let exact_crossing = (qi(1) - q(0.00514)) * qi(65537) / qi(4);
    assert!((16300.03..16300.04).contains(&exact_crossing.to_f64().unwrap()));
    let expected = reference::solve(strip.field(), &r).cell_list();
    assert_eq!(expected.len(), 16385);
    assert_eq!(
        &expected[16299..16302],
        &[[16299, 0], [16300, 0], [16300, 1]]
    );
    for arith in modes {
        for method in METHODS {
            let got = covered_cells(&strip, &r, method, arith);
            let what = format!("{arith} {method}: {}", describe(&r));
            match (arith, method) {
                // The hierarchies cover a path with the run walk.
                (R16, Method::Runs | Method::Mipmap | Method::HierarchicalRuns) => {
                    assert_eq!(got.len(), expected.len() + 1, "{what}");
                    assert_eq!(got[..16301], expected[..16301], "{what}");
                    assert_eq!(got[16301], [16299, 1], "{what}");
                    assert_eq!(got[16302..], expected[16301..], "{what}");
                    // The last 100 cells, position by position from the end: the last 84
                    // are equal, the 85th from the end is the extra cell, and the 15 before
                    // it are the right cells shifted by one place: 16 differ.
                    let (far, right) = (tail(&got), tail(&expected));
                    let differing: Vec<usize> = (0..TAIL).filter(|&k| far[k] != right[k]).collect();
                    assert_eq!(differing, (0..16).collect::<Vec<_>>(), "{what}");
                    assert_eq!(far[TAIL - 85], [16299, 1], "{what}");
                    assert_eq!(far[..TAIL - 85], right[1..TAIL - 84], "{what}");
                }
                (R16, Method::Dda) => {
                    assert_eq!(got.len(), expected.len(), "{what}");
                    let differing: Vec<usize> =
                        (0..got.len()).filter(|&k| got[k] != expected[k]).collect();
                    assert_eq!(differing, vec![16300], "{what}");
                    assert_eq!(got[16300], [16299, 1], "{what}");
                }
                _ => {
                    assert_eq!(tail(&got), tail(&expected), "{what}: last cells");
                    assert!(got == expected, "{what}");
                }
            }
        }
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

/// -0.0 components. The contract counts -0.0 as positive, so negating the zero components of
/// a direction changes nothing: same hit, same covered cells, in every arithmetic. Pairs
/// (d, d with every 0.0 made -0.0), each answer as documented in its own test:
/// - vertical onto vertex (1, 1) of `hilly` (cell (0, 0), T0);
/// - level along the grid line y = 2 onto the peak of [`peak_on_grid_lines`] (cell (2, 1),
///   T0), and along x = 3 (cell (2, 1), T0);
/// - level at the plateau height of `mesa(77)` (cell (2, 2), T0);
/// - straight down from a vertex of [`three_by_three`] (t = 0, cell (0, 0), T0).
///
/// Also the 40 rays of `families::negative_zero` (-0.0 in directions and origins), on which
/// f64 and both rationals agree with exact.
#[test]
fn negative_zero_directions() {
    let negate_zeros = |d: [f64; 3]| d.map(|c| if c == 0.0 { -0.0 } else { c });
    let hilly = families::hilly();
    let peak = peak_on_grid_lines();
    let mesa = mesa(77);
    let h = mesa.field().z(3, 1);
    let t3 = three_by_three();
    let top = hilly.z_range().1 + 1.0;
    let cases: [(&Terrain, [f64; 3], [f64; 3]); 5] = [
        (&hilly, [1.0, 1.0, top], [0.0, 0.0, -1.0]),
        (&peak, [-1.0, 2.0, 5.0], [1.0, 0.0, 0.0]),
        (&peak, [3.0, -1.0, 5.0], [0.0, 1.0, 0.0]),
        (&mesa, [-1.0, 2.5, h], [1.0, 0.0, 0.0]),
        (&t3, [1.0, 1.0, 3.0], [0.0, 0.0, -1.0]),
    ];
    for (field, o, d) in cases {
        let (plus, minus) = (ray(o, d), ray(o, negate_zeros(d)));
        assert!(minus
            .dir()
            .iter()
            .any(|c| c.is_sign_negative() && *c == 0.0));
        let (a, b) = (exact(field, &plus), exact(field, &minus));
        assert_eq!(a.hit, b.hit, "{} vs {}", describe(&plus), describe(&minus));
        assert!(a.hit.is_some(), "{}", describe(&plus));
        assert_eq!(a.cell_list(), b.cell_list(), "{}", describe(&minus));
        for arith in [Arith::Exact, F64, R16, R24] {
            for method in METHODS {
                let (x, y) = (
                    try_trace(field, &plus, &options(method, arith)).expect("no panic"),
                    try_trace(field, &minus, &options(method, arith)).expect("no panic"),
                );
                assert_eq!(x.hit, y.hit, "{arith} {method}: {}", describe(&minus));
                assert_eq!(x.cells, y.cells, "{arith} {method}: {}", describe(&minus));
            }
        }
        assert_rounded_agree(field, &minus, &b);
    }
    assert_family_agrees(&families::negative_zero());
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

/// Directions scaled to the ends of the f64 range, on `families::hilly`, from
/// o = (2.3, 1.6, zmax + 1):
/// - d = (0, 0, -1e-300): t = 1.08e301, cell (2, 1), T1;
/// - d = (1e300, 5e299, -1e300): t = 2.67e-300, cell (4, 2), T0.
///
/// Bounded rationals cannot represent either direction as given: -1e-300 rounds to 0 (the
/// direction would become (0, 0, 0), which clips to nothing), and 1e300 saturates at i64::MAX.
/// Directions far from unit length are traced rescaled by a power of two (the same line),
/// without which both bounds would miss both rays with every method; so they hit the exact
/// answer's triangle, and every arithmetic agrees on both rays but for `rational:65536` on the
/// first, whose `t` is off by a relative 1.4e-9 (1.0799999985e301: it rounds every result to a
/// denominator of at most 65536). Asserted, with the rounding of the components as given.
#[test]
fn extreme_direction_scales() {
    let hilly = families::hilly();
    let top = hilly.z_range().1 + 1.0;
    for bound in [1 << 16, 1 << 24] {
        assert_eq!(rational(bound, -1e-300), Ratio::from_integer(0));
        assert_eq!(rational(bound, 1e300), Ratio::from_integer(i64::MAX));
    }
    let cases: [(_, _, _, _, &[_]); 2] = [
        ([0.0, 0.0, -1e-300], [2, 1], 1, 1.08e301, &[(R16, TOff)]),
        (
            [1e300, 5e299, -1e300],
            [4, 2],
            0,
            2.6733668341708542e-300,
            &[],
        ),
    ];
    for (d, cell, triangle, t, not_agreeing) in cases {
        let r = ray([2.3, 1.6, top], d);
        let answer = exact(&hilly, &r);
        expect_hit_in(&answer, &r, cell, triangle);
        let exact_t = answer.hit.as_ref().expect("hit").t.to_f64().unwrap();
        assert_eq!(exact_t, t, "{}", describe(&r));
        assert_rounded(&hilly, &r, &answer, not_agreeing);
    }
}

// ---------------------------------------------------------------------------------------
// Extreme slopes: paths whose minor component is tiny or subnormal.

/// Paths with a slope (minor over major horizontal component) below about 2^-63: a level or
/// near-vertical ray whose minor component is tiny but not zero.
///
/// Expected (the reference), on `families::hilly`:
/// - o = (-1, 1.6, 15), d = (1, 1e-25, 0): t = 5.5208333..., cell (4, 1), T1, covered
///   (0..=5, 1);
/// - o = (2.3, -1, 15), d = (-1e-25, 1, -0.5) (y-major): t = 4.2941176..., cell (2, 3), T0;
/// - o = (2.3, 1.6, zmax + 1), d = (1e-12, 1e-40, -1) (near vertical): t = zmax + 1 - 10,
///   cell (2, 1), T1.
///
/// Exact mode (every method) must match the reference, and f64 and both rationals (which
/// round the tiny component to 0: a path along the row, hitting the same triangle) agree.
///
/// What it guards: the first run's step count `((1 - beta) / a).ceil_i64()` saturates at
/// i64::MAX (here 4e24 and more), and `exit_after(i64::MAX)` is still negative. Were the
/// step count's `steps += 1` in runs.rs not to saturate, it would overflow (a panic with
/// overflow checks, a wrap to i64::MIN in release); the run's span
/// `(lo, col.saturating_add(i64::MIN))` would be empty, `Frame::emit` would drop it, and as
/// the path never leaves its row the walk would end there: no cell covered, and a miss, in
/// exact mode and f64 alike.
#[test]
fn slope_below_2_pow_minus_63_runs_walk_the_path() {
    let hilly = families::hilly();
    let top = hilly.z_range().1 + 1.0;
    let cases = [
        ([-1.0, 1.6, 15.0], [1.0, 1e-25, 0.0], [4, 1], 1),
        ([2.3, -1.0, 15.0], [-1e-25, 1.0, -0.5], [2, 3], 0),
        ([2.3, 1.6, top], [1e-12, 1e-40, -1.0], [2, 1], 1),
    ];
    let mut problems = Vec::new();
    for (o, d, cell, triangle) in cases {
        let r = ray(o, d);
        let answer = reference::solve(hilly.field(), &r);
        expect_hit_in(&answer, &r, cell, triangle);
        let p = check_exact_against(&hilly, &r, &answer);
        if !p.is_empty() {
            problems.push(format!("{}\n    {}", describe(&r), p.join("\n    ")));
        }
        for g in rounded(&hilly, &r, &answer) {
            if g.verdict != Agrees {
                problems.push(format!("{}: {}", describe(&r), g.line()));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "slopes below 2^-63 (run walk step count overflow):\n{}",
        problems.join("\n")
    );
}

/// A path with a subnormal minor component. 6x4 field, heights 1 except 9 on column x = 4;
/// o = (0, 0.25, 5), d = (1, 5e-324, 0): level, y grows by 5e-324 per unit, the path stays in
/// row 0.
///
/// Expected (the reference): hit at t = 3.5 on the ramp up to x = 4, at (3.5, 0.25): cell
/// (3, 0), T0; covered cells (0..=4, 0). Exact mode (every method) must match it; f64 and
/// both rationals (which round 5e-324 to 0), every method, must find the same hit and cover
/// exactly these cells. (At y = 0.5 the hit point would be on the cell's diagonal for the
/// rationals only, while the exact path is 1.7e-323 above it, in T1: they would disagree on
/// the triangle for that reason alone, so this ray avoids it.)
///
/// What it guards: in f64, inv_dv = 1 / 5e-324 = +inf, so the DDA's next v crossing is at
/// t = +inf. Infinities are near nothing but themselves; were `nearly_equal(next_u, +inf)`
/// true (|inf - x| <= 1e-9 * inf), every u crossing would be taken for a lattice corner and
/// the walk would step diagonally, covering (0, 0), (1, 0), (0, 1), (1, 1), (2, 1), (1, 2),
/// (2, 2), (3, 2), rows the path never enters, and miss. (The run walk, exact mode included,
/// needs the saturating step count of the test above on this ray.)
#[test]
fn subnormal_slope_f64_dda_stays_in_its_row() {
    let field = terrain(6, 4, 255, 255.0, |x, _| if x == 4 { 9 } else { 1 });
    let r = ray([0.0, 0.25, 5.0], [1.0, 5e-324, 0.0]);
    let answer = reference::solve(field.field(), &r);
    expect_hit_in(&answer, &r, [3, 0], 0);
    assert_eq!(answer.hit.as_ref().unwrap().t, q(3.5));
    let expected: Vec<[usize; 2]> = (0..=4).map(|i| [i, 0]).collect();
    assert_eq!(answer.cell_list(), expected);
    let mut problems: Vec<String> = check_exact_against(&field, &r, &answer);
    for arith in ROUNDED {
        for method in METHODS {
            let got = try_trace(&field, &r, &options(method, arith)).expect("no panic");
            let verdict = judge(&got.hit, &answer);
            let cells = covered_cells(&field, &r, method, arith);
            if verdict != Agrees || cells != expected {
                problems.push(format!(
                    "{arith} {method}: {verdict:?} ({}), covered {cells:?}",
                    describe_hit(&got.hit)
                ));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "{}: expected t = 3.5, cell (3, 0), T0, covered {expected:?}:\n{}",
        describe(&r),
        problems.join("\n")
    );
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

/// Directions far from unit length: the ray of `ray_along_grid_line` o = (-1, 2, 6),
/// d = (1, 0, -0.25), which meets the peak at (3, 2, 5) (t = 4, cell (2, 1), T0), with its
/// direction scaled by tiny and huge factors. The line is the same, so every arithmetic and
/// method must hit the same triangle at the same point, with `t = 4 / scale` (exactly, in
/// exact mode) where that fits an `f64`, and `t` infinite where it does not (2^-1030: t =
/// 2^1032). Directions are rescaled by a power of two for the walk: unscaled, `f64` would
/// miss this ray for every scale below about 1e-307 (its walk's parameters would overflow),
/// and `f32` for every scale outside its range (a direction of 1e-200 or 1e100 rounds to zero
/// or infinity in `f32`).
#[test]
fn directions_far_from_unit_length() {
    let field = peak_on_grid_lines();
    // (The subnormal scales are powers of two, so that a quarter of them is exact too.)
    let subnormal = [2f64.powi(-1062), 2f64.powi(-1030)];
    for scale in subnormal
        .into_iter()
        .chain([1e-300, 1e-200, 1e-12, 1e12, 1e200, 1e300])
    {
        let r = ray([-1.0, 2.0, 6.0], [scale, 0.0, -0.25 * scale]);
        let t = qi(4) / q(scale);
        let answer = expect_hit(&field, &r, t.clone(), [2, 1], 0);
        let exact_t = (qi(4) / q(scale)).to_f64().filter(|t| t.is_finite());
        for arith in [Arith::F32, F64, R16, R24, Arith::Exact] {
            for method in METHODS {
                let got = try_trace(&field, &r, &options(method, arith))
                    .unwrap_or_else(|e| panic!("{}: {e}", describe(&r)));
                let what = format!(
                    "{method} {arith}, scale {scale:e}: {}",
                    describe_hit(&got.hit)
                );
                let hit = got.hit.unwrap_or_else(|| panic!("{what}: a miss"));
                assert_eq!((hit.cell, hit.triangle), ([2, 1], 0), "{what}");
                let off = hit
                    .point
                    .iter()
                    .zip([3.0, 2.0, 5.0])
                    .map(|(a, b)| (a - b).abs());
                assert!(off.fold(0.0, f64::max) < 1e-5, "{what}");
                match exact_t {
                    Some(e) => assert!((hit.t - e).abs() <= 1e-6 * e, "{what}: t {e}"),
                    None => assert_eq!(hit.t, f64::INFINITY, "{what}"),
                }
                if arith == Arith::Exact {
                    assert_eq!(
                        hit.t_exact,
                        Some(answer.hit.clone().expect("hit").t),
                        "{what}"
                    );
                }
            }
        }
    }
}

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
            let got = try_trace(&field, &r, &options(method, arith))
                .unwrap_or_else(|e| panic!("{}: {e}", describe(&r)));
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
            let got = try_trace(&field, &r, &options(method, arith))
                .unwrap_or_else(|e| panic!("{}: {e}", describe(&r)));
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
