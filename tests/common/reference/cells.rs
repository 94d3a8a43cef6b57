//! The cells a ray's path covers: the ray clipped to the terrain's box, and the closed cells
//! its projected segment touches, in visiting order.

use super::numbers::{floor_i64, qi, ExactField, ExactRay, Interval, Q};
use super::{Answer, Contact};
use num_traits::Zero;

pub(super) fn clip(field: &ExactField, ray: &ExactRay) -> Option<(Q, Q)> {
    let lo = [Q::zero(), Q::zero(), field.zmin.clone()];
    let hi = [
        qi(field.w as i64 - 1),
        qi(field.h as i64 - 1),
        field.zmax.clone(),
    ];
    let mut range = Interval::nonnegative();
    for k in 0..3 {
        if !range.slab(&ray.o[k], &ray.d[k], &lo[k], &hi[k]) {
            return None;
        }
    }
    let t1 = range.hi.expect("a non-zero direction leaves a bounded box");
    Some((range.lo, t1))
}

/// The covered cells in visiting order. Candidates come column by column: within a column's
/// parameter range the path's y lies between its values at the range's ends, so the rows
/// `floor(ymin)-1 ..= floor(ymax)` contain every touched cell; each candidate is then
/// decided exactly.
pub(super) fn covered(field: &ExactField, ray: &ExactRay, t0: &Q, t1: &Q) -> Vec<Contact> {
    let mut cells = Vec::new();
    for i in 0..field.w - 1 {
        let mut column = Interval::closed(t0.clone(), t1.clone());
        if !column.slab(&ray.o[0], &ray.d[0], &qi(i as i64), &qi(i as i64 + 1)) {
            continue;
        }
        let hi = column.hi.clone().expect("bounded");
        let (ya, yb) = (ray.at(1, &column.lo), ray.at(1, &hi));
        let (ymin, ymax) = if ya <= yb { (ya, yb) } else { (yb, ya) };
        let first = (floor_i64(&ymin) - 1).max(0);
        let last = floor_i64(&ymax).min(field.h as i64 - 2);
        for j in first..=last {
            let mut cell = column.clone();
            if cell.slab(&ray.o[1], &ray.d[1], &qi(j), &qi(j + 1)) {
                cells.push(Contact {
                    cell: [i, j as usize],
                    t_exit: cell.hi.clone().expect("bounded"),
                    t_enter: cell.lo,
                });
            }
        }
    }
    let x_major = ray.x_major();
    let signed = |index: usize, component: f64| {
        if component < 0.0 {
            -(index as i64)
        } else {
            index as i64
        }
    };
    let key = |c: &Contact| {
        let x = signed(c.cell[0], ray.dir[0]);
        let y = signed(c.cell[1], ray.dir[1]);
        let (minor, major) = if x_major { (y, x) } else { (x, y) };
        (c.t_enter.clone(), c.t_exit.clone(), minor, major)
    };
    cells.sort_by_cached_key(key);
    cells
}

/// Whether the ray passes within `delta` of cell `[i, j]` inside the terrain's box grown by
/// `delta`: at some `t >= 0` it lies over the cell's square grown by `delta` on every side, at
/// a height within `delta` of the box's.
pub fn passes_near(answer: &Answer, [i, j]: [usize; 2], delta: &Q) -> bool {
    passes_near_rectangle(answer, ([i, j], [i + 1, j + 1]), delta)
}

/// Whether the ray passes within `delta` of the terrain's box.
pub fn passes_near_box(answer: &Answer, delta: &Q) -> bool {
    let far = [answer.field.w - 1, answer.field.h - 1];
    passes_near_rectangle(answer, ([0, 0], far), delta)
}

/// Whether at some `t >= 0` the ray lies over the rectangle from corner `lo` to corner `hi`
/// grown by `delta` on every side, at a height within `delta` of the terrain's box.
fn passes_near_rectangle(answer: &Answer, (lo, hi): ([usize; 2], [usize; 2]), delta: &Q) -> bool {
    let (field, ray) = (&answer.field, &answer.ray);
    let lo = [lo[0], lo[1]].map(|c| qi(c as i64) - delta);
    let hi = [hi[0], hi[1]].map(|c| qi(c as i64) + delta);
    let z = (&field.zmin - delta, &field.zmax + delta);
    let mut near = Interval::nonnegative();
    (0..2).all(|k| near.slab(&ray.o[k], &ray.d[k], &lo[k], &hi[k]))
        && near.slab(&ray.o[2], &ray.d[2], &z.0, &z.1)
}
