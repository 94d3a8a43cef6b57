//! Rays that stand vertical or nearly, start inside the box, under the surface or on a vertex,
//! run level with a plateau, or shrink to a single point of the grid.

use super::{hilly, octant_directions, plateau_height, terrain, Family};
use heightray::Terrain;

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
