//! A catalogue of numerically hard cases: one test per case, each with its expected answer
//! written down in its doc comment.
//!
//! For every ray of every case:
//! - exact mode, every method, must equal the brute-force reference of
//!   tests/common/reference/ exactly: hit or miss, exact t, cell, triangle, covered cells,
//!   and the recorded cells and counters as `common::check_exact_against` holds them; the
//!   reference's answer is also checked against the expectation written in the comment;
//! - `f64` and bounded rationals (bound 2^16 and 2^24), every method, must find the same first
//!   hit as exact: same cell and triangle and `|t - t_exact| <= 1e-9 * max(|t_exact|, 1)`, or
//!   both miss. Where an arithmetic cannot, the comment says why, with its numbers, and the
//!   test asserts exactly what it does instead (a [`Verdict`] per arithmetic), each derived
//!   from the rounding the comment works out (and the test asserts). How many rays of a family
//!   a rounded arithmetic misses, where no rule says, is a characterization snapshot
//!   (`snapshots::`), not a case's assertion.
//!
//! The cases, by what makes them hard: [`vertices_and_lines`] (rays through lattice points,
//! vertices, along grid lines and cell diagonals), [`planes_and_plateaus`] (rays in or just
//! above a triangle's plane), [`extreme_directions`] (near-vertical, very long and shallow
//! rays) and [`scales`] (signed zeros, far-from-unit directions, tiny slopes); and, apart,
//! the cases that also hold a walk to a query budget, [`query_budgets`] (rays under the
//! surface, blocks and runs of blocks skipped whole).
//!
//! Two tests hold the walks on extreme slopes: the run walk of a path
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
use heightray::arith::with_bound;
use heightray::arith::{Rational, Scalar};
use heightray::traverse::covered_cells;
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

mod extreme_directions;
mod planes_and_plateaus;
mod query_budgets;
mod scales;
mod vertices_and_lines;

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
