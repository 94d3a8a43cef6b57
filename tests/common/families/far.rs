//! Rays from far off: origins from 1e13 to 1e308 on every side of the box, aimed at the map
//! or along lines that stay exact at any distance, directions down to subnormals, and rays
//! that graze the box's edges and corners.

use super::Family;
use heightray::Terrain;

/// How far the origins lie from the map.
pub const FAR_DISTANCES: [f64; 10] = [
    1e13, 3.7e14, 1e17, 1e20, 1e40, 1e80, 1e100, 1e150, 1e300, 1e308,
];

/// Rays from far off on `terrain` (see the module doc).
pub fn far_off(name: &str, terrain: Terrain) -> Family {
    let mut f = Family::new(name, terrain);
    let (w, h) = (
        (f.field().width() - 1) as f64,
        (f.field().height() - 1) as f64,
    );
    let (z_lo, z_hi) = f.terrain.z_range();
    let targets = [
        [w / 2.0 + 0.25, h / 3.0, (z_lo + z_hi) / 2.0],
        [1.0, 1.0, f.field().z(1, 1)],
        [w - 0.5, h - 0.5, z_lo],
    ];
    for s in FAR_DISTANCES {
        for target in targets {
            aimed_along_an_axis(&mut f, s, target);
            if s <= 1e17 {
                aimed_from_a_diagonal(&mut f, s, target);
            }
        }
        exact_diagonals(&mut f, s);
        grazing(&mut f, s, [w, h], [z_lo, z_hi]);
    }
    f
}

/// From `s` away along each axis, both ways, a little off the target on the other axes: the
/// direction is `target - origin`, whose other components are exact, so the ray passes
/// within a rounding of the target; again with the direction scaled down to subnormals.
fn aimed_along_an_axis(f: &mut Family, s: f64, target: [f64; 3]) {
    for axis in 0..3 {
        for sign in [1.0, -1.0] {
            for off in [[2.5, -3.0], [-1.25, 0.75]] {
                let mut o = target;
                o[axis] += sign * s;
                let others = [(axis + 1) % 3, (axis + 2) % 3];
                o[others[0]] += off[0];
                o[others[1]] += off[1];
                let d = [0, 1, 2].map(|k| target[k] - o[k]);
                f.push(o, d);
                let tiny = d.map(|c| c * 2f64.powi(-1000) * 2f64.powi(-40));
                if tiny.iter().any(|&c| c != 0.0) {
                    f.push(o, tiny);
                }
            }
        }
    }
}

/// From `s` away on each diagonal: the direction `target - origin` is rounded, so from past
/// about 1e15 the ray passes the target at a distance of cells.
fn aimed_from_a_diagonal(f: &mut Family, s: f64, target: [f64; 3]) {
    for v in [
        [1.0, 1.0, 1.0],
        [-1.0, 0.5, 2.0],
        [0.75, -1.0, -0.5],
        [-1.0, -1.0, 1.0],
    ] {
        let o = [0, 1, 2].map(|k| target[k] + s * v[k]);
        f.push(o, [0, 1, 2].map(|k| target[k] - o[k]));
    }
}

/// Lines that stay exact at any distance: `x = y = z` and its mirror images (through every
/// octant; most meet the box at a corner or not at all), and `x = y` at a fixed height.
fn exact_diagonals(f: &mut Family, s: f64) {
    for sx in [1.0, -1.0] {
        for sy in [1.0, -1.0] {
            for sz in [1.0, -1.0] {
                f.push([sx * s, sy * s, sz * s], [-sx, -sy, -sz]);
            }
        }
    }
    f.push([s, s, 1.5], [-1.0, -1.0, 0.0]);
    f.push([-s, -s, 2.0], [1.0, 1.0, -0.0]);
}

/// Rays along the box's edges and top face and through its corners from `s` away, and
/// vertical rays from `s` above and below onto a corner and an edge.
fn grazing(f: &mut Family, s: f64, [w, h]: [f64; 2], [z_lo, z_hi]: [f64; 2]) {
    f.push([s, 0.0, z_hi], [-1.0, 0.0, 0.0]);
    f.push([-s, h, z_lo], [1.0, 0.0, 0.0]);
    f.push([w / 2.0, s, z_hi], [0.0, -1.0, 0.0]);
    // (The line x + y = 0 meets the box only on its edge over the corner (0, 0).)
    f.push([s, -s, z_hi], [-1.0, 1.0, 0.0]);
    f.push([w + s, h + s, z_hi + s], [-1.0, -1.0, -1.0]);
    f.push([0.0, 0.0, s], [0.0, 0.0, -1.0]);
    f.push([w, 1.5, s], [0.0, -0.0, -1.0]);
    f.push([w / 2.0 + 0.5, h / 2.0, -s], [0.0, 0.0, 1.0]);
}
