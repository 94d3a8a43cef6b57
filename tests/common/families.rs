//! Deterministic ray families, each on the field it is about. The exact tests check every
//! ray against the reference; the float-mode tests count how often the rounded arithmetics
//! disagree on the same rays.

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

/// Vertical rays down from above the field and up from below it, and (downwards) starting
/// below the surface, at each `(x, y)`.
fn vertical(name: &str, terrain: Terrain, points: &[[f64; 2]]) -> Family {
    let mut f = Family::new(name, terrain);
    let zmax = f.zmax();
    for &[x, y] in points {
        for zero in [0.0, -0.0] {
            f.push([x, y, zmax + 1.0], [zero, zero, -1.0]);
            f.push([x, y, -1.0], [zero, -zero, 1.0]);
            f.push([x, y, zmax], [zero, zero, -0.5]);
        }
        f.push([x, y, -0.5], [0.0, 0.0, -1.0]);
    }
    f
}

pub fn vertical_in_cell() -> Family {
    let points = [[2.3, 1.6], [2.7, 1.2], [0.1, 0.9], [5.9, 4.05], [3.5, 2.5]];
    vertical("vertical in a cell", hilly(), &points)
}

pub fn vertical_on_edge() -> Family {
    // Diagonal (T0/T1) edges, horizontal edges, vertical edges; plateau edges included.
    let points = [
        [1.5, 0.5],
        [2.25, 1.25],
        [3.5, 2.0],
        [1.5, 3.0],
        [4.0, 2.25],
        [1.0, 3.75],
    ];
    vertical("vertical on an edge", hilly(), &points)
}

pub fn vertical_on_corner() -> Family {
    let points = [[1.0, 1.0], [3.0, 2.0], [5.0, 4.0], [2.0, 4.0]];
    vertical("vertical on a corner", hilly(), &points)
}

pub fn vertical_on_grid_boundary() -> Family {
    let points = [
        [0.0, 0.5],
        [6.0, 2.5],
        [1.5, 0.0],
        [2.5, 5.0],
        [0.0, 0.0],
        [6.0, 0.0],
        [0.0, 5.0],
        [6.0, 5.0],
        [0.0, 3.0],
        [-0.5, 1.0],
        [6.000000001, 1.0],
        [3.0, -1e-300],
    ];
    vertical("vertical on the grid boundary", hilly(), &points)
}

/// All directions used for rays that start somewhere inside the box.
fn inner_directions(zmax: f64) -> Vec<[f64; 3]> {
    let mut dirs = Vec::new();
    for [dx, dy] in octant_directions() {
        for dz in [-zmax / 4.0, 0.0, zmax / 8.0] {
            dirs.push([dx, dy, dz]);
        }
    }
    dirs.extend([
        [1.0, 1.0, -1.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.5],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ]);
    dirs
}

pub fn starts_inside_above_surface(name: &str, terrain: Terrain) -> Family {
    let mut f = Family::new(name, terrain);
    let zmax = f.zmax();
    for [x, y] in [[1.5, 1.5], [2.25, 3.75], [4.0, 1.0], [0.5, 0.0]] {
        let z = (f.field().z(x as usize, y as usize) + zmax) / 2.0;
        for d in inner_directions(zmax) {
            f.push([x, y, z.max(zmax * 0.75)], d);
        }
    }
    f
}

pub fn starts_below_surface(name: &str, terrain: Terrain) -> Family {
    let mut f = Family::new(name, terrain);
    let zmax = f.zmax();
    for [i, j] in [[1, 1], [2, 3], [4, 2], [0, 0]] {
        let cell_min = [
            f.field().z(i, j),
            f.field().z(i + 1, j),
            f.field().z(i, j + 1),
            f.field().z(i + 1, j + 1),
        ]
        .into_iter()
        .fold(f64::INFINITY, f64::min);
        for d in inner_directions(zmax) {
            f.push([i as f64 + 0.5, j as f64 + 0.25, cell_min - 0.5], d);
        }
    }
    f
}

/// Rays starting exactly on a vertex, on an edge midpoint (heights are integers, midpoints
/// halves: exact) and on a cell's centre.
pub fn starts_on_vertex(name: &str, terrain: Terrain) -> Family {
    let mut f = Family::new(name, terrain);
    let zmax = f.zmax();
    let z = |f: &Family, i: usize, j: usize| f.field().z(i, j);
    let mut starts = Vec::new();
    for [i, j] in [[1, 1], [2, 3], [0, 0], [3, 0], [4, 4]] {
        starts.push([i as f64, j as f64, z(&f, i, j)]);
        starts.push([
            i as f64 + 0.5,
            j as f64,
            (z(&f, i, j) + z(&f, i + 1, j)) / 2.0,
        ]);
        starts.push([
            i as f64 + 0.5,
            j as f64 + 0.5,
            (z(&f, i, j) + z(&f, i + 1, j + 1)) / 2.0,
        ]);
    }
    for o in starts {
        for d in inner_directions(zmax.max(1.0)) {
            f.push(o, d);
        }
    }
    f
}

/// Level rays exactly at the plateau height of [`hilly`]: across it, along its edges and
/// diagonal, from outside the grid and from on the plateau.
pub fn plateau_level() -> Family {
    let mut f = Family::new("level rays at the plateau height", hilly());
    let z = plateau_height(&f.terrain);
    let dirs = [
        [1.0, 0.0],
        [0.0, 1.0],
        [1.0, 1.0],
        [1.0, 0.5],
        [-1.0, 0.25],
        [-1.0, -1.0],
        [0.0, -1.0],
        [-0.5, 1.0],
    ];
    let starts = [[3.0, 2.0], [2.0, 1.0], [4.0, 3.0], [2.5, 1.5], [3.5, 3.0]];
    for [dx, dy] in dirs {
        for [x, y] in starts {
            f.push([x, y, z], [dx, dy, 0.0]);
            f.push([x - 10.0 * dx, y - 10.0 * dy, z], [dx, dy, 0.0]);
        }
    }
    // Along the plateau's edges and through the rest of the field, from outside.
    for y in [1.0, 2.0, 3.0, 4.0] {
        f.push([-1.0, y, z], [1.0, 0.0, 0.0]);
        f.push([7.0, y, z], [-1.0, -0.0, 0.0]);
    }
    for x in [2.0, 4.0, 5.0] {
        f.push([x, -1.0, z], [0.0, 1.0, 0.0]);
        f.push([x, 6.0, z], [0.0, -1.0, 0.0]);
    }
    f
}

/// Nearly vertical rays (horizontal part about 1e-12) in every octant, on interior points,
/// edges and corners.
pub fn near_vertical() -> Family {
    let mut f = Family::new("near-vertical rays", hilly());
    let zmax = f.zmax();
    let tiny = [
        [1e-12, 0.0],
        [-1e-12, 3e-13],
        [1e-12, 1e-12],
        [-3e-13, -1e-12],
        [0.0, -1e-12],
        [7e-13, -7e-13],
    ];
    for [x, y] in [
        [2.3, 1.6],
        [1.5, 0.5],
        [3.0, 2.0],
        [0.0, 0.0],
        [6.0, 2.5],
        [1.0, 3.75],
    ] {
        for [dx, dy] in tiny {
            f.push([x, y, zmax + 1.0], [dx, dy, -1.0]);
            f.push([x, y, -1.0], [dx, dy, 1.0]);
        }
    }
    f
}

/// A 4000x3 strip, flat 0 except a spike of 255 at sample (3998, 1); level and slightly
/// descending rays with slope 1/3777 (and -1/3777) across the strip must find the spike.
pub fn strip_slope_1_3777() -> Family {
    let strip = terrain(4000, 3, 255, 255.0, |x, y| {
        if (x, y) == (3998, 1) {
            255
        } else {
            0
        }
    });
    let mut f = Family::new("slope 1/3777 across a 4000x3 strip", strip);
    f.push([0.0, 0.5, 1.0], [3777.0, 1.0, 0.0]);
    f.push([-3777.0, -0.5, 1.0], [3777.0, 1.0, 0.0]);
    f.push([0.0, 0.25, 2.0], [3777.0, 1.0, -0.25]);
    f.push([0.0, 0.0, 3.0], [3777.0, 1.0, 0.0]);
    f.push([0.0, 1.9, 3.0], [3777.0, -1.0, 0.0]);
    f
}

/// The cells around the spike of [`strip_slope_1_3777`]: its rays must hit one of them.
pub fn strip_spike_cells() -> [[usize; 2]; 4] {
    [[3997, 0], [3998, 0], [3997, 1], [3998, 1]]
}

/// Components of -0.0 in the direction and the origin.
pub fn negative_zero() -> Family {
    let mut f = Family::new("negative zero components", hilly());
    let zmax = f.zmax();
    let dirs = [
        [-0.0, 1.0, -0.5],
        [1.0, -0.0, 0.0],
        [-0.0, -0.0, -1.0],
        [0.0, -1.0, -0.0],
        [-0.0, -1.0, -0.25],
        [-1.0, -0.0, -0.125],
        [-0.0, 0.0, 1.0],
        [1.0, 1.0, -0.0],
    ];
    let origins = [
        [-0.0, 2.0, zmax],
        [3.0, -0.0, zmax],
        [-0.0, -0.0, zmax * 0.5],
        [2.5, 2.0, zmax + 1.0],
        [6.0, 5.0, -0.0],
    ];
    for d in dirs {
        for o in origins {
            f.push(o, d);
        }
    }
    f
}

/// Rays whose clipped segment is a single point: level rays through a corner of the grid's
/// box, and a rising ray starting on the box's top face.
pub fn single_point_segments() -> Family {
    let mut f = Family::new("single-point segments", hilly());
    let zmax = f.zmax();
    for z in [f.field().z(6, 0), zmax, zmax * 0.5] {
        f.push([5.0, -1.0, z], [1.0, 1.0, 0.0]);
        f.push([-1.0, 4.0, z], [1.0, 1.0, 0.0]);
        f.push([7.0, -2.0, z], [-1.0, 2.0, 0.0]);
        f.push([1.0, 6.0, z], [-1.0, -1.0, 0.0]);
    }
    f.push([2.0, 3.0, zmax], [0.5, 0.25, 1.0]);
    f
}

/// Oblique rays meeting a flat field (whose box has zero height) at one point: inside a cell,
/// on an edge, on a vertex, on the boundary.
pub fn flat_field_single_point() -> Family {
    let flat = terrain(5, 4, 1000, 3.0, |_, _| 700);
    let z = flat.field().z(0, 0);
    let mut f = Family::new("oblique rays on a flat field", flat);
    for [x, y] in [
        [1.25, 1.5],
        [2.0, 1.5],
        [1.5, 2.0],
        [2.5, 2.5],
        [3.0, 2.0],
        [0.0, 0.0],
        [4.0, 1.0],
    ] {
        for [dx, dy] in [
            [1.0, 0.5],
            [-0.5, 1.0],
            [-1.0, -1.0],
            [1.0, -1.0],
            [0.0, 1.0],
        ] {
            f.push([x - dx, y - dy, z + 1.0], [dx, dy, -1.0]);
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
