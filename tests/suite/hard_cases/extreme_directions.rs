//! Hard cases with extreme directions and distances: near-vertical rays, origins far away,
//! and very long shallow rays (signed zeros and extreme scales are in [`super::scales`]).

use super::*;

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
