//! Deterministic ray families, each on the field it is about. The exact tests check every
//! ray against the reference; the float-mode tests count how often the rounded arithmetics
//! disagree on the same rays.

mod degenerate;
mod far;

pub use degenerate::*;
pub use far::*;
use heightray::{Heightfield, Ray, Terrain};

/// Rays on one terrain.
pub struct Family {
    pub name: String,
    pub terrain: Terrain,
    pub rays: Vec<Ray>,
}

impl Family {
    fn new(name: impl Into<String>, terrain: Terrain) -> Self {
        Family {
            name: name.into(),
            terrain,
            rays: Vec::new(),
        }
    }

    /// Adds the ray `o + t*d` (both must be valid) unless the family has it already (bit for
    /// bit: -0.0 and 0.0 are different rays here).
    fn push(&mut self, o: [f64; 3], d: [f64; 3]) {
        let bits = |r: &Ray| [r.origin(), r.dir()].map(|v| v.map(f64::to_bits));
        let r = ray(o, d);
        if !self.rays.iter().any(|old| bits(old) == bits(&r)) {
            self.rays.push(r);
        }
    }

    fn field(&self) -> &Heightfield {
        self.terrain.field()
    }

    fn zmax(&self) -> f64 {
        self.terrain.z_range().1
    }
}

pub fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
    Ray::new(o, d).unwrap_or_else(|e| panic!("bad test ray o={o:?} d={d:?}: {e}"))
}

pub fn terrain(
    w: usize,
    h: usize,
    maxval: u32,
    z_scale: f64,
    f: impl Fn(usize, usize) -> u16,
) -> Terrain {
    Terrain::new(Heightfield::from_fn(w, h, maxval, z_scale, f).expect("valid test field"))
}

/// A deterministic pseudo-random value in `0..n` for sample (x, y).
pub fn hash(x: usize, y: usize, salt: u64, n: u16) -> u16 {
    let mut v = (x as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (y as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ salt.wrapping_mul(0x1656_67B1_9E37_79F9);
    v ^= v >> 29;
    v = v.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    v ^= v >> 32;
    (v % u64::from(n)) as u16
}

/// 7x6 samples, heights `0.1 * sample` (not dyadic), with a plateau of sample 100 over
/// samples x 2..=4, y 1..=3 (2x2 flat cells) and two equal neighbours.
pub fn hilly() -> Terrain {
    terrain(7, 6, 255, 25.5, |x, y| {
        let plateau = (2..=4).contains(&x) && (1..=3).contains(&y);
        if plateau || (x, y) == (5, 4) || (x, y) == (6, 4) {
            100
        } else {
            hash(x, y, 1, 200)
        }
    })
}

/// Integer heights 0..=`top` (unit 1): rays with small integer or dyadic components meet its
/// vertices and edges exactly.
pub fn integer_hills(w: usize, h: usize, top: u16, salt: u64) -> Terrain {
    terrain(w, h, 255, 255.0, |x, y| hash(x, y, salt, top + 1))
}

/// The plateau height of [`hilly`].
pub fn plateau_height(terrain: &Terrain) -> f64 {
    terrain.field().z(3, 2)
}

/// The eight octants of the projected direction: signs of (dx, dy) and the major axis, each
/// with horizontal slopes 1/2 and 0.3.
fn octant_directions() -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
        for x_major in [true, false] {
            for m in [0.5, 0.3] {
                let (a, b) = if x_major { (1.0, m) } else { (m, 1.0) };
                out.push([sx * a, sy * b]);
            }
        }
    }
    out
}

/// For each octant, rays entering the box through each side it can enter by (west, east,
/// south, north) and from above.
pub fn octant_entries(name: &str, terrain: Terrain) -> Family {
    let mut f = Family::new(name, terrain);
    let (w, h) = (
        (f.field().width() - 1) as f64,
        (f.field().height() - 1) as f64,
    );
    let zmax = f.zmax();
    for [dx, dy] in octant_directions() {
        for dz in [-zmax / 4.0, 0.0, zmax / 16.0] {
            let d = [dx, dy, dz];
            // Entry points on each side this direction can enter by.
            let along_y = [0.0, 1.0, 1.5, 2.3, h];
            let along_x = [0.0, 1.0, 1.5, 2.3, w];
            let mut entries: Vec<[f64; 2]> = Vec::new();
            if dx > 0.0 {
                entries.extend(along_y.iter().map(|&y| [0.0, y]));
            }
            if dx < 0.0 {
                entries.extend(along_y.iter().map(|&y| [w, y]));
            }
            if dy > 0.0 {
                entries.extend(along_x.iter().map(|&x| [x, 0.0]));
            }
            if dy < 0.0 {
                entries.extend(along_x.iter().map(|&x| [x, h]));
            }
            for [x, y] in entries {
                let vertex = (x.fract() == 0.0 && y.fract() == 0.0)
                    .then(|| f.field().z(x as usize, y as usize));
                for z in [zmax * 0.5, zmax].into_iter().chain(vertex) {
                    let p = [x, y, z];
                    f.push([0, 1, 2].map(|k| p[k] - 1.5 * d[k]), d);
                }
            }
        }
        // From above, through the top face.
        for dz in [-zmax / 4.0, -zmax * 2.0] {
            let d = [dx, dy, dz];
            for [x, y] in [[1.5, 2.5], [2.0, 3.0], [3.25, 1.0]] {
                let p = [x, y, zmax];
                f.push([0, 1, 2].map(|k| p[k] - 2.0 * d[k]), d);
            }
        }
    }
    f
}

/// A 44x44 integer field for the lattice slopes (41/17 needs 42 rows to pass two lattice
/// points).
pub fn lattice_terrain() -> Terrain {
    integer_hills(44, 44, 3, 7)
}

/// Rays with horizontal slope `p/q` (direction `(q, p)` and its four sign mirrors) through
/// lattice points, at the vertex height, half a unit above, and above everything, level,
/// descending and climbing, starting before the lattice point or on it.
pub fn lattice_slope(p: i32, q: i32) -> Family {
    let mut f = Family::new(format!("lattice slope {p}/{q}"), lattice_terrain());
    let zmax = f.zmax();
    let (w, h) = (f.field().width() - 1, f.field().height() - 1);
    for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
        for [lx, ly] in [[3, 3], [20, 11], [0, 0], [w, h], [w / 2, 0]] {
            let z_vertex = f.field().z(lx, ly);
            for z in [z_vertex, z_vertex + 0.5, zmax + 0.25] {
                for dz in [0.0, -1.0 / 64.0, 1.0 / 128.0] {
                    let d = [sx * f64::from(q), sy * f64::from(p), dz];
                    let l = [lx as f64, ly as f64, z];
                    for k in [2.0, 0.0] {
                        f.push([0, 1, 2].map(|c| l[c] - k * d[c]), d);
                    }
                }
            }
        }
    }
    f
}

/// Rays along the grid lines x = k and y = k (both directions, also with -0.0 as the zero
/// component), at several heights, from outside and from inside the grid.
pub fn grid_lines(name: &str, terrain: Terrain) -> Family {
    let mut f = Family::new(name, terrain);
    let (w, h) = (
        (f.field().width() - 1) as f64,
        (f.field().height() - 1) as f64,
    );
    let zmax = f.zmax();
    let heights = |f: &Family, i: usize, j: usize| [f.field().z(i, j), zmax * 0.5, zmax];
    for k in [0, 1, 3, w as usize] {
        for (s, zero) in [(1.0, 0.0), (-1.0, -0.0), (-1.0, 0.0), (1.0, -0.0)] {
            for dz in [0.0, -zmax / 8.0] {
                // Along x = k, travelling in y.
                let d = [zero, s, dz];
                for z in heights(&f, k, 2) {
                    let start = if s > 0.0 { -1.0 } else { h + 1.0 };
                    f.push([k as f64, start, z - dz], d);
                    f.push([k as f64, 2.5, z], d);
                }
                // Along y = k (k < h), travelling in x.
                if (k as f64) <= h {
                    let d = [s, zero, dz];
                    for z in heights(&f, 2, k) {
                        let start = if s > 0.0 { -1.0 } else { w + 1.0 };
                        f.push([start, k as f64, z - dz], d);
                        f.push([2.5, k as f64, z], d);
                    }
                }
            }
        }
    }
    f
}

/// Rays along cell diagonals (the T0/T1 edge, slope +1) and anti-diagonals (slope -1),
/// through lattice points, at vertex heights and above.
pub fn cell_diagonals(name: &str, terrain: Terrain) -> Family {
    let mut f = Family::new(name, terrain);
    let zmax = f.zmax();
    for (sx, sy) in [(1.0, 1.0), (-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0)] {
        for [lx, ly] in [[0, 0], [2, 0], [0, 2], [2, 2], [3, 1]] {
            let z_vertex = f.field().z(lx, ly);
            for z in [z_vertex, zmax * 0.5, zmax] {
                for dz in [0.0, -zmax / 8.0, zmax / 16.0] {
                    let d = [sx, sy, dz];
                    let l = [lx as f64, ly as f64, z];
                    f.push([0, 1, 2].map(|c| l[c] - 3.0 * d[c]), d);
                    f.push(l, d);
                }
            }
        }
    }
    f
}

/// Every deterministic family (for the float-mode counts).
pub fn all() -> Vec<Family> {
    let mut out = vec![
        octant_entries("octant entries (hilly)", hilly()),
        octant_entries("octant entries (integer)", integer_hills(6, 5, 6, 3)),
    ];
    out.extend(
        [(0, 1), (1, 1), (1, 2), (2, 3), (17, 41), (41, 17)].map(|(p, q)| lattice_slope(p, q)),
    );
    out.extend([
        grid_lines("grid lines (hilly)", hilly()),
        grid_lines("grid lines (integer)", integer_hills(6, 5, 6, 3)),
        cell_diagonals("cell diagonals (integer)", integer_hills(6, 5, 6, 3)),
        cell_diagonals("cell diagonals (hilly)", hilly()),
        vertical_in_cell(),
        vertical_on_edge(),
        vertical_on_corner(),
        vertical_on_grid_boundary(),
        starts_inside_above_surface("starts inside", hilly()),
        starts_below_surface("starts below the surface", hilly()),
        starts_on_vertex("starts on a vertex", integer_hills(6, 6, 6, 5)),
        plateau_level(),
        near_vertical(),
        strip_slope_1_3777(),
        negative_zero(),
        single_point_segments(),
        flat_field_single_point(),
    ]);
    out
}
