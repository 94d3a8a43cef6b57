//! Hard cases at extreme scales: signed zeros, directions far from unit length, and slopes too
//! small for the run recurrence or subnormal.

use super::*;

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
