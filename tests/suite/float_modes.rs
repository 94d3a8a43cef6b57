//! The rounded arithmetics (f32, f64, bounded rationals) against the exact reference where the
//! design promises agreement: the triangle test is watertight, so a ray aimed exactly at a
//! shared vertex or edge of the mesh from above must hit in f64 and f32. (Their disagreements
//! elsewhere are a snapshot, see `snapshots`.)

use crate::common::families::{hash, ray, terrain};
use crate::common::{describe, options, try_trace, METHODS};
use heightray::{trace, Arith, Method, Ray, Terrain, TraceOptions};

/// A point of the mesh shared by several triangles.
#[derive(Clone, Copy, Debug)]
struct Target {
    what: &'static str,
    p: [f64; 3],
}

/// Interior vertices (six triangles) and the midpoints of every edge shared by two
/// triangles: cell diagonals, and horizontal and vertical edges off the boundary. Heights of
/// midpoints are the means of the end points, exact for the dyadic fields used here.
fn shared_points(terrain: &Terrain) -> Vec<Target> {
    let f = terrain.field();
    let (w, h) = (f.width(), f.height());
    let mid = |a: (usize, usize), b: (usize, usize)| {
        let z = (f.z(a.0, a.1) + f.z(b.0, b.1)) / 2.0;
        [(a.0 + b.0) as f64 / 2.0, (a.1 + b.1) as f64 / 2.0, z]
    };
    let mut out = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let interior_i = i > 0 && i + 1 < w;
            let interior_j = j > 0 && j + 1 < h;
            if interior_i && interior_j {
                out.push(Target {
                    what: "vertex",
                    p: [i as f64, j as f64, f.z(i, j)],
                });
            }
            if i + 1 < w && j + 1 < h {
                out.push(Target {
                    what: "diagonal edge",
                    p: mid((i, j), (i + 1, j + 1)),
                });
            }
            if i + 1 < w && interior_j {
                out.push(Target {
                    what: "horizontal edge",
                    p: mid((i, j), (i + 1, j)),
                });
            }
            if j + 1 < h && interior_i {
                out.push(Target {
                    what: "vertical edge",
                    p: mid((i, j), (i, j + 1)),
                });
            }
        }
    }
    out
}

/// Horizontal parts of the directions, in every octant (small dyadics; (0, 0) is vertical).
const HORIZONTAL: [[f64; 2]; 8] = [
    [0.0, 0.0],
    [0.5, 0.25],
    [-0.75, 0.5],
    [1.0, -1.0],
    [-0.25, -0.625],
    [2.0, 1.0],
    [-1.0, 3.0],
    [0.125, -2.0],
];

/// The steepest slope of any triangle along x or y: the largest height difference of two
/// samples next to each other (each triangle's gradient components are such differences).
fn steepest(terrain: &Terrain) -> f64 {
    let f = terrain.field();
    let mut s: f64 = 0.0;
    for j in 0..f.height() {
        for i in 0..f.width() {
            if i + 1 < f.width() {
                s = s.max((f.z(i + 1, j) - f.z(i, j)).abs());
            }
            if j + 1 < f.height() {
                s = s.max((f.z(i, j + 1) - f.z(i, j)).abs());
            }
        }
    }
    s
}

/// Traces every ray in f64 and f32 (every method) and fails on any miss.
fn assert_no_holes(label: &str, terrain: &Terrain, rays: &[(Target, Ray)]) {
    let mut holes = Vec::new();
    let mut counted = 0;
    for (target, ray) in rays {
        for arith in [Arith::F64, Arith::F32] {
            for method in METHODS {
                counted += 1;
                let got = try_trace(terrain, ray, &options(method, arith));
                if !matches!(&got, Ok(t) if t.hit.is_some()) {
                    holes.push(format!(
                        "{method} {arith}: {} at {:?}: {} -> {}",
                        target.what,
                        target.p,
                        describe(ray),
                        got.map_or_else(|e| e, |_| "miss".into())
                    ));
                }
            }
        }
    }
    println!(
        "watertight {label}: {} holes in {counted} traces",
        holes.len()
    );
    assert!(
        holes.is_empty(),
        "{label}: {} of {counted} traces aimed at shared vertices/edges missed:\n{}",
        holes.len(),
        holes
            .iter()
            .take(12)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// The smallest hole found: rays from above through vertex (1,1) of a 3x3 field, all inputs
/// integers. Exact: the first one hits at t = 3 in cell (0,0), T0; the second at t = 3 in
/// cell (1,0), T1.
#[test]
fn watertight_ray_through_the_vertex_of_a_3x3_field() {
    // Samples by row, y up: y=0: 4 2 1, y=1: 3 3 3, y=2: 4 4 0 (heights = samples).
    let samples = [4, 2, 1, 3, 3, 3, 4, 4, 0];
    let t = terrain(3, 3, 255, 255.0, |x, y| samples[y * 3 + x]);
    let target = Target {
        what: "vertex",
        p: [1.0, 1.0, 3.0],
    };
    // Steepest slope 4, |dx| + |dy| = 7: dz = -29 comes down on the front of every triangle.
    let rays = [
        (target, ray([-5.0, -14.0, 90.0], [2.0, 5.0, -29.0])),
        (target, ray([7.0, -14.0, 90.0], [-2.0, 5.0, -29.0])),
    ];
    assert_no_holes("3x3 field", &t, &rays);
}

/// "From above" means more than dz < 0: the ray must come down onto the front of every
/// triangle around the target (d . n < 0 for the upward normals n = (-gx, -gy, 1)); otherwise
/// the target is a silhouette point, which the ray only grazes, and rounding may legitimately
/// decide either way. With |gx|, |gy| <= S, dz < -S (|dx| + |dy|) guarantees it.
#[test]
fn watertight_rays_at_shared_vertices_and_edges_of_dyadic_fields() {
    let fields = [
        // Heights are quarters (z_scale / maxval = 0.25): every aimed ray is exact in f64
        // and f32. Rough (0..=63.75) and gentle (0..=4).
        terrain(12, 10, 255, 63.75, |x, y| hash(x, y, 1, 256)),
        terrain(12, 10, 255, 63.75, |x, y| hash(x, y, 2, 256)),
        terrain(11, 13, 255, 63.75, |x, y| hash(x, y, 3, 17)),
        terrain(9, 9, 1000, 250.0, |x, y| 200 + hash(x, y, 4, 9)),
    ];
    for (n, t) in fields.iter().enumerate() {
        let s = steepest(t);
        let mut rays = Vec::new();
        for target in shared_points(t) {
            for [dx, dy] in HORIZONTAL {
                let d = [dx, dy, -(s * (dx.abs() + dy.abs()) + 1.0)];
                let o = [0, 1, 2].map(|k| target.p[k] - 2.0 * d[k]);
                rays.push((target, ray(o, d)));
            }
        }
        assert_no_holes(&format!("dyadic field {n}"), t, &rays);
    }
}

#[test]
fn watertight_rays_at_shared_vertices_of_non_dyadic_fields() {
    // Heights 0.1 * sample (1..=999). Aimed from o = p - d with d = (h, -z): o.z = 2z and
    // o.z - z = z are exact (Sterbenz), so the ray passes exactly through the vertex at t = 1;
    // h is scaled down by powers of two until S |h| < z (front-facing, see above). Vertical
    // rays from far above go to every shared point.
    let t = terrain(10, 9, 1000, 100.0, |x, y| 1 + hash(x, y, 11, 999));
    let s = steepest(&t);
    let mut rays = Vec::new();
    for target in shared_points(&t) {
        let [x, y, z] = target.p;
        rays.push((target, ray([x, y, 1e3], [0.0, 0.0, -1.0])));
        if target.what != "vertex" {
            continue;
        }
        for [mut dx, mut dy] in HORIZONTAL {
            while s * (dx.abs() + dy.abs()) >= z {
                (dx, dy) = (dx / 2.0, dy / 2.0);
            }
            rays.push((target, ray([x - dx, y - dy, 2.0 * z], [dx, dy, -z])));
        }
    }
    assert_no_holes("non-dyadic field", &t, &rays);
}

/// Rays coming down onto flat ground at the field's lowest height end exactly on the bottom
/// of the bounding box; rounding must not lift the ray's lowest point over the last cells
/// above the ground, which would show as lines of sky across the flat border of this hill in
/// the viewer; the first ray is one of them.
#[test]
fn rounded_rays_find_flat_ground_at_the_lowest_height() {
    let hill = include_bytes!("../data/hill.pgm");
    let terrain = Terrain::new(heightray::heightfield::load_bytes(hill, 16.0, "hill.pgm").unwrap());
    let reported = (
        [-7.042785426744196, -26.43350300091015, 49.98579514089657],
        [0.6969209130310196, 0.5280471059744715, -0.5259796411768727],
    );
    let mut rays = vec![Ray::new(reported.0, reported.1).unwrap()];
    for k in 1..300 {
        let (a, b) = (k as f64 * 0.7391, k as f64 * 0.3217);
        let dir = [
            reported.1[0] + 0.05 * a.cos(),
            reported.1[1] + 0.05 * b.sin(),
            reported.1[2],
        ];
        rays.push(Ray::new(reported.0, dir).unwrap());
    }
    let mut misses = Vec::new();
    for ray in &rays {
        if trace(
            &terrain,
            ray,
            &TraceOptions::new(Method::Runs, Arith::Exact),
        )
        .hit
        .is_none()
        {
            continue;
        }
        for arith in [Arith::F32, Arith::F64, Arith::Rational { bound: 1 << 16 }] {
            for method in Method::ALL {
                if trace(&terrain, ray, &TraceOptions::new(method, arith))
                    .hit
                    .is_none()
                {
                    misses.push(format!("{method} {arith}: {}", describe(ray)));
                }
            }
        }
    }
    assert!(
        misses.is_empty(),
        "rounded walks missed ground exact arithmetic hits:\n{}",
        misses.join("\n")
    );
}
