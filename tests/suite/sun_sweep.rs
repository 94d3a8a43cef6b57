//! The sun's sweep of a terrain against brute force: on random fields, ridges and hills, for
//! suns along the axes, the diagonals, low and at random, no point the sweep settles as lit
//! has the surface rise above its shadow ray, and none it settles as shadowed has its ray
//! clear of the surface. The reference evaluates the surface over the ray where it bends:
//! between crossings of grid lines and cell diagonals the height above the ray is linear.

use crate::common::random::Rng;
use heightray::heightfield::sun_sweep::{SunSweep, SweepStart, Verdict};
use heightray::{Heightfield, Terrain};

/// The height of the surface over `(x, y)` on the map (the surface contract: triangle 0 of
/// a cell holds `P00, P10, P11`, where `x - i >= y - j`).
fn height(terrain: &Terrain, x: f64, y: f64) -> f64 {
    let f = terrain.field();
    let i = (x.floor().max(0.0) as usize).min(f.width() - 2);
    let j = (y.floor().max(0.0) as usize).min(f.height() - 2);
    let [z00, z10, z01, z11] = terrain.corner_heights(i, j);
    let (fx, fy) = (x - i as f64, y - j as f64);
    if fx >= fy {
        z00 + (z10 - z00) * fx + (z11 - z10) * fy
    } else {
        z00 + (z11 - z01) * fx + (z01 - z00) * fy
    }
}

/// The most the surface rises above the ray from `p` towards `d` for `t > 0` on the map
/// (negative infinity where the ray leaves the map at once).
fn highest_above(terrain: &Terrain, p: [f64; 3], d: [f64; 3]) -> f64 {
    let f = terrain.field();
    let top = [(f.width() - 1) as f64, (f.height() - 1) as f64];
    let exit = (0..2)
        .map(|k| match d[k] {
            c if c > 0.0 => (top[k] - p[k]) / c,
            c if c < 0.0 => -p[k] / c,
            _ => f64::INFINITY,
        })
        .fold(f64::INFINITY, f64::min);
    let mut ts = vec![exit];
    // Grid lines x = k and y = k, and diagonals x - y = k.
    let lines = [(p[0], d[0]), (p[1], d[1]), (p[0] - p[1], d[0] - d[1])];
    for (from, rate) in lines {
        if rate == 0.0 {
            continue;
        }
        let to = from + rate * exit;
        let (lo, hi) = (from.min(to).floor() as i64, from.max(to).ceil() as i64);
        ts.extend((lo..=hi).map(|k| (k as f64 - from) / rate));
    }
    ts.into_iter()
        .filter(|&t| t > 0.0 && t <= exit)
        .map(|t| height(terrain, p[0] + t * d[0], p[1] + t * d[1]) - (p[2] + t * d[2]))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// Test fields of 33 x 29 samples: noise, ridges across the grid, hills, a terrace.
fn fields() -> Vec<(&'static str, Terrain)> {
    let mut rng = Rng(0x005e_ed0f_5a11);
    let noise: Vec<u16> = (0..33 * 29).map(|_| rng.below(200) as u16).collect();
    let field = |f: &dyn Fn(usize, usize) -> u16| {
        Terrain::new(Heightfield::from_fn(33, 29, 255, 25.5, f).unwrap())
    };
    vec![
        ("noise", field(&|x, y| noise[y * 33 + x])),
        ("ridges", field(&|x, y| ((x * 3 + y * 2) % 17 * 12) as u16)),
        (
            "axis ridges",
            field(&|x, _| if x % 8 == 4 { 200 } else { 20 }),
        ),
        (
            "hills",
            field(&|x, y| {
                let (x, y) = (x as f64 / 5.0, y as f64 / 4.0);
                (120.0 + 60.0 * x.sin() * y.cos() + 40.0 * (x + y).sin()) as u16
            }),
        ),
        ("terrace", field(&|x, _| if x < 16 { 0 } else { 90 })),
    ]
}

/// Directions towards the sun: along the axes and diagonals, low, steep and at random.
fn suns(rng: &mut Rng) -> Vec<[f64; 3]> {
    let mut suns = Vec::new();
    for (x, y) in [
        (1.0, 0.0),
        (-1.0, 0.0),
        (0.0, 1.0),
        (0.0, -1.0),
        (1.0, 1.0),
        (-1.0, 1.0),
    ] {
        for s in [0.01, 0.3, 1.5] {
            suns.push([x, y, s * f64::hypot(x, y)]);
        }
    }
    for _ in 0..8 {
        let a = rng.within(0.0, std::f64::consts::TAU);
        suns.push([a.cos(), a.sin(), rng.within(0.02, 2.0)]);
    }
    suns
}

/// Points of triangle `k` of cell `(i, j)`: corners, edge midpoints, centroid, random ones.
fn points(rng: &mut Rng, (i, j): (usize, usize), k: u8) -> Vec<[f64; 2]> {
    let corners = if k == 0 {
        [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]
    } else {
        [[0.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    };
    let at = |w: [f64; 3]| {
        let c = |a: usize| (0..3).map(|v| w[v] * corners[v][a]).sum::<f64>();
        [i as f64 + c(0), j as f64 + c(1)]
    };
    let mut weights = vec![
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.5, 0.5, 0.0],
        [0.0, 0.5, 0.5],
        [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    ];
    let (a, b) = (rng.within(0.0, 1.0), rng.within(0.0, 1.0));
    let (a, b) = if a + b > 1.0 {
        (1.0 - a, 1.0 - b)
    } else {
        (a, b)
    };
    weights.push([1.0 - a - b, a, b]);
    weights.into_iter().map(at).collect()
}

#[test]
fn sweep_verdicts_agree_with_brute_force() {
    let mut rng = Rng(0x0000_050f_5ee9);
    for (name, terrain) in fields() {
        let f = terrain.field();
        let (mut lit, mut shadowed) = (0u64, 0u64);
        let suns = suns(&mut rng);
        for (s, &sun) in suns.iter().enumerate() {
            // Blocks of 2, 4 and 8 cells, taking turns across the suns.
            let sweep = SunSweep::build_on_level(&terrain, sun, 1 + (s % 3) as u32).unwrap();
            for j in 0..f.height() - 1 {
                for i in 0..f.width() - 1 {
                    for k in 0..2u8 {
                        for [x, y] in points(&mut rng, (i, j), k) {
                            // On the surface (flat shading), and above it (smooth shading).
                            let z = height(&terrain, x, y);
                            for (rise, on_plane) in [(0.0, true), (0.0, false), (0.05, false)] {
                                let point = [x, y, z + rise];
                                let start = SweepStart {
                                    point,
                                    cell: (i, j),
                                    triangle: k,
                                    on_plane,
                                    relative: 1e-9,
                                    largest: 300.0,
                                };
                                let above = highest_above(&terrain, point, sun);
                                match sweep.verdict(&terrain, &start) {
                                    Verdict::Lit => {
                                        lit += 1;
                                        assert!(above < 0.0, "{name} {sun:?} {point:?}: {above}");
                                    }
                                    Verdict::Shadowed => {
                                        shadowed += 1;
                                        assert!(above > 0.0, "{name} {sun:?} {point:?}: {above}");
                                    }
                                    Verdict::Unknown => {}
                                }
                            }
                        }
                    }
                }
            }
        }
        // Every field has points the sweep settles as lit. In shadow it settles points only
        // behind broad rises (hills, the terrace): `L` is built from the lowest samples of
        // blocks of cells, which on noise and narrow ridges lie on the ground.
        assert!(lit > 1000, "{name}: {lit} lit");
        let broad = matches!(name, "hills" | "terrace");
        assert_eq!(shadowed > 1000, broad, "{name}: {shadowed} shadowed");
    }
}

#[test]
fn no_sweep_without_a_sun_above_the_horizon_or_a_height_range() {
    let flat = Terrain::new(Heightfield::from_fn(9, 9, 255, 25.5, |_, _| 7).unwrap());
    assert!(SunSweep::build(&flat, [1.0, 0.0, 0.5]).is_none());
    let (_, hills) = fields().swap_remove(3);
    assert!(SunSweep::build(&hills, [0.0, 0.0, 1.0]).is_none());
    assert!(SunSweep::build(&hills, [1.0, 0.5, 0.0]).is_none());
    assert!(SunSweep::build(&hills, [1.0, 0.5, -0.1]).is_none());
    assert!(SunSweep::build(&hills, [1.0, 0.5, 0.1]).is_some());
}
