//! An exact brute-force reference for the ray/terrain contract, written from the contract
//! alone: plane formulas and half-planes for the triangles, slabs for the box and the cells,
//! all in `BigRational` on the exact values of the `f64` inputs. It uses the crate only to
//! read the ray's components and the field's heights.
//!
//! Contract summary (what is computed here):
//! - cell (i, j) is the closed square [i, i+1] x [j, j+1]; T0 = (P00, P10, P11) is the part
//!   with 0 <= y-j <= x-i <= 1, T1 = (P00, P11, P01) the part with 0 <= x-i <= y-j <= 1;
//! - the first hit is the least t >= 0 at which the ray touches a closed triangle (a ray in a
//!   triangle's plane hits where it first touches the triangle);
//! - the covered cells are the cells whose closed square the projected, box-clipped segment
//!   touches, sorted by (t_enter, t_exit, minor, major) with indices negated on axes the ray
//!   travels towards negative (a component of 0 or -0.0 counts as positive);
//! - a hole cell (a corner holds no data) has no triangles: the ray passes through it;
//! - a hit point shared by several (cell, triangle) pairs is reported in the first cell in
//!   that order, T0 before T1;
//! - the query counters follow the span/cell/triangle rules (see [`counters`]).

mod base;
mod cells;
mod counters;
mod numbers;

pub use base::{solve_with_base, SurfaceHit};
pub use cells::{passes_near, passes_near_box};
pub use counters::counters;
pub use numbers::{q, qi, ExactField, ExactRay, Q};

use cells::{clip, covered};
use heightray::{Heightfield, Ray};
use num_traits::Zero;
use numbers::Interval;
use std::collections::HashMap;

/// A covered cell and the closed parameter interval in which the projected segment touches
/// its square.
#[derive(Clone, Debug, PartialEq)]
pub struct Contact {
    pub cell: [usize; 2],
    pub t_enter: Q,
    pub t_exit: Q,
}

/// The reported hit.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactHit {
    pub t: Q,
    pub cell: [usize; 2],
    pub triangle: u8,
}

/// Everything the contract says about one ray.
#[derive(Clone, Debug)]
pub struct Answer {
    pub field: ExactField,
    pub ray: ExactRay,
    /// The ray (t >= 0) clipped to the box [0,W-1] x [0,H-1] x [zmin,zmax].
    pub clip: Option<(Q, Q)>,
    /// Covered cells in visiting order.
    pub cells: Vec<Contact>,
    /// First touch (t) of T0 and T1 of every covered cell, by cell.
    pub touches: HashMap<[usize; 2], [Option<Q>; 2]>,
    pub hit: Option<ExactHit>,
}

impl Answer {
    pub fn cell_list(&self) -> Vec<[usize; 2]> {
        self.cells.iter().map(|c| c.cell).collect()
    }

    /// Whether the ray runs obliquely over the grid: along both axes, not along a row or
    /// column, nor vertically.
    pub fn is_oblique(&self) -> bool {
        self.ray.dir[0] != 0.0 && self.ray.dir[1] != 0.0
    }
}

/// Solves one ray exactly.
pub fn solve(field: &Heightfield, ray: &Ray) -> Answer {
    let field = ExactField::new(field);
    let ray = ExactRay::new(ray);
    let clip = clip(&field, &ray);
    let cells = match &clip {
        Some((t0, t1)) => covered(&field, &ray, t0, t1),
        None => Vec::new(),
    };
    // A hit point lies on a triangle, hence in the box and in a covered cell's square; still,
    // small fields are searched over every triangle so the hit does not depend on `covered`.
    let candidates: Vec<[usize; 2]> = if field.cell_count() <= 100 {
        (0..field.h - 1)
            .flat_map(|j| (0..field.w - 1).map(move |i| [i, j]))
            .collect()
    } else {
        cells.iter().map(|c| c.cell).collect()
    };
    let touches: HashMap<[usize; 2], [Option<Q>; 2]> = candidates
        .iter()
        .map(|&cell| (cell, [0, 1].map(|k| first_touch(&field, &ray, cell, k))))
        .collect();
    let hit = first_hit(&cells, &touches);
    Answer {
        field,
        ray,
        clip,
        cells,
        touches,
        hit,
    }
}

/// The least `t >= 0` at which the ray touches triangle `k` of `cell`, from the plane formula
/// and the triangle's three half-planes.
pub fn first_touch(field: &ExactField, ray: &ExactRay, [i, j]: [usize; 2], k: u8) -> Option<Q> {
    if field.is_hole([i, j]) {
        return None;
    }
    let (z00, z10) = (field.z(i, j), field.z(i + 1, j));
    let (z01, z11) = (field.z(i, j + 1), field.z(i + 1, j + 1));
    // z = a + b*(x-i) + c*(y-j) over the triangle.
    let (a, b, c) = if k == 0 {
        (z00.clone(), z10 - z00, z11 - z10)
    } else {
        (z00.clone(), z11 - z01, z01 - z00)
    };
    let one = qi(1);
    // Cell-relative position: X(t) = x0 + dx t, Y(t) = y0 + dy t.
    let (x0, y0) = (&ray.o[0] - qi(i as i64), &ray.o[1] - qi(j as i64));
    let (dx, dy, dz) = (&ray.d[0], &ray.d[1], &ray.d[2]);
    let half_planes = if k == 0 {
        // Y >= 0, X - Y >= 0, 1 - X >= 0.
        [
            (y0.clone(), dy.clone()),
            (&x0 - &y0, dx - dy),
            (&one - &x0, -dx),
        ]
    } else {
        // X >= 0, Y - X >= 0, 1 - Y >= 0.
        [
            (x0.clone(), dx.clone()),
            (&y0 - &x0, dy - dx),
            (&one - &y0, -dy),
        ]
    };
    let mut inside = Interval::nonnegative();
    for (g0, g1) in &half_planes {
        if !inside.keep(g0, g1) {
            return None;
        }
    }
    // The ray's height above the plane: h0 + h1 t.
    let h0 = &ray.o[2] - &a - &b * &x0 - &c * &y0;
    let h1 = dz - &b * dx - &c * dy;
    if h1.is_zero() {
        // Parallel: in the plane (touches where it enters the triangle) or never.
        return h0.is_zero().then_some(inside.lo);
    }
    let t = -h0 / h1;
    inside.contains(&t).then_some(t)
}

/// The least touch over all candidate triangles; ties go to the first covered cell in
/// visiting order, T0 before T1.
fn first_hit(cells: &[Contact], touches: &HashMap<[usize; 2], [Option<Q>; 2]>) -> Option<ExactHit> {
    let t = touches.values().flatten().flatten().min()?.clone();
    let position: HashMap<[usize; 2], usize> =
        cells.iter().enumerate().map(|(n, c)| (c.cell, n)).collect();
    let (n, k) = touches
        .iter()
        .flat_map(|(cell, ts)| (0..2u8).map(move |k| (cell, k, &ts[k as usize])))
        .filter(|(_, _, tk)| tk.as_ref() == Some(&t))
        .map(|(cell, k, _)| {
            let n = *position
                .get(cell)
                .unwrap_or_else(|| panic!("reference: hit cell {cell:?} is not covered"));
            (n, k)
        })
        .min()?;
    Some(ExactHit {
        t,
        cell: cells[n].cell,
        triangle: k,
    })
}
