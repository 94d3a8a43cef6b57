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

use heightray::{Counters, Heightfield, Ray};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};
use std::collections::HashMap;

pub type Q = BigRational;

/// The exact value of a finite `f64`.
pub fn q(x: f64) -> Q {
    BigRational::from_float(x).expect("finite f64")
}

/// An integer as a rational.
pub fn qi(n: i64) -> Q {
    BigRational::from_integer(BigInt::from(n))
}

fn floor_i64(x: &Q) -> i64 {
    x.floor()
        .to_integer()
        .to_i64()
        .expect("grid coordinate fits i64")
}

/// A closed set of ray parameters `lo <= t <= hi` (`hi == None`: unbounded), possibly empty.
#[derive(Clone, Debug)]
struct Interval {
    lo: Q,
    hi: Option<Q>,
    empty: bool,
}

impl Interval {
    /// `t >= 0`.
    fn nonnegative() -> Self {
        Interval {
            lo: Q::zero(),
            hi: None,
            empty: false,
        }
    }

    fn closed(lo: Q, hi: Q) -> Self {
        let empty = lo > hi;
        Interval {
            lo,
            hi: Some(hi),
            empty,
        }
    }

    /// Keeps the `t` with `g0 + g1*t >= 0`; returns whether anything is left.
    fn keep(&mut self, g0: &Q, g1: &Q) -> bool {
        if self.empty {
            return false;
        }
        if g1.is_zero() {
            if g0.is_negative() {
                self.empty = true;
            }
        } else {
            let root = -g0 / g1;
            if g1.is_positive() {
                if root > self.lo {
                    self.lo = root;
                }
            } else if self.hi.as_ref().is_none_or(|hi| root < *hi) {
                self.hi = Some(root);
            }
            if self.hi.as_ref().is_some_and(|hi| *hi < self.lo) {
                self.empty = true;
            }
        }
        !self.empty
    }

    /// Keeps the `t` with `lo <= o + d*t <= hi`.
    fn slab(&mut self, o: &Q, d: &Q, lo: &Q, hi: &Q) -> bool {
        self.keep(&(o - lo), d) && self.keep(&(hi - o), &-d)
    }

    fn contains(&self, t: &Q) -> bool {
        !self.empty && *t >= self.lo && self.hi.as_ref().is_none_or(|hi| t <= hi)
    }
}

/// A ray as exact rationals, with its `f64` direction (for the sign and axis rules).
#[derive(Clone, Debug)]
pub struct ExactRay {
    pub o: [Q; 3],
    pub d: [Q; 3],
    pub dir: [f64; 3],
}

impl ExactRay {
    pub fn new(ray: &Ray) -> Self {
        ExactRay {
            o: ray.origin().map(q),
            d: ray.dir().map(q),
            dir: ray.dir(),
        }
    }

    /// Component `k` of `o + t*d`.
    pub fn at(&self, k: usize, t: &Q) -> Q {
        &self.o[k] + &self.d[k] * t
    }

    /// Major axis: x if |dx| >= |dy| (so vertical rays are x-major), else y.
    pub fn x_major(&self) -> bool {
        self.dir[0].abs() >= self.dir[1].abs()
    }
}

/// The exact heights of a field.
#[derive(Clone, Debug)]
pub struct ExactField {
    pub w: usize,
    pub h: usize,
    z: Vec<Q>,
    /// Cells with a no-data corner, by `j * (w-1) + i`.
    holes: Vec<bool>,
    pub zmin: Q,
    pub zmax: Q,
}

impl ExactField {
    pub fn new(field: &Heightfield) -> Self {
        let (w, h) = (field.width(), field.height());
        let z: Vec<Q> = (0..h)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| q(field.z(i, j)))
            .collect();
        let holes = (0..h - 1)
            .flat_map(|j| (0..w - 1).map(move |i| (i, j)))
            .map(|(i, j)| field.is_hole_cell(i, j))
            .collect();
        let zmin = z.iter().min().expect("non-empty field").clone();
        let zmax = z.iter().max().expect("non-empty field").clone();
        ExactField {
            w,
            h,
            z,
            holes,
            zmin,
            zmax,
        }
    }

    pub fn z(&self, i: usize, j: usize) -> &Q {
        &self.z[j * self.w + i]
    }

    /// Whether the cell is a hole (a corner holds no data).
    pub fn is_hole(&self, [i, j]: [usize; 2]) -> bool {
        self.holes[j * (self.w - 1) + i]
    }

    /// Highest of the cell's four corner heights.
    pub fn cell_max(&self, cell: [usize; 2]) -> &Q {
        self.corners(cell).max().expect("four corners")
    }

    /// Lowest of the cell's four corner heights.
    pub fn cell_min(&self, cell: [usize; 2]) -> &Q {
        self.corners(cell).min().expect("four corners")
    }

    fn corners(&self, [i, j]: [usize; 2]) -> impl Iterator<Item = &Q> {
        [
            self.z(i, j),
            self.z(i + 1, j),
            self.z(i, j + 1),
            self.z(i + 1, j + 1),
        ]
        .into_iter()
    }

    fn cell_count(&self) -> usize {
        (self.w - 1) * (self.h - 1)
    }
}

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

fn clip(field: &ExactField, ray: &ExactRay) -> Option<(Q, Q)> {
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
fn covered(field: &ExactField, ray: &ExactRay, t0: &Q, t1: &Q) -> Vec<Contact> {
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

/// The query counters the contract prescribes for `answer` (exact arithmetic):
/// - bbox: one query, a hit iff the clip range is non-empty;
/// - cells are walked in visiting order, grouped in spans (maximal runs of consecutive cells
///   with the same minor index; a path with minor component 0 and positive length is one
///   span). The walk stops
///   at the first span or cell whose t_enter >= the best hit so far;
/// - `runs`: each span first gets a run query (the ray's lowest z over the span's t-range <=
///   highest cell maximum of its cells); a missed span's cells are skipped;
/// - each remaining cell gets a cell query (lowest z over its contact interval <= its
///   maximum); a hit cell gets a T0 and a T1 query (hit iff the ray touches it at t >= 0),
///   unless it is a hole.
pub fn counters(answer: &Answer, runs: bool) -> Counters {
    let mut counters = Counters::default();
    if !counters.bbox.record(answer.clip.is_some()) {
        return counters;
    }
    let ray = &answer.ray;
    let lowest = |lo: &Q, hi: &Q| ray.at(2, lo).min(ray.at(2, hi));
    let highest = |lo: &Q, hi: &Q| ray.at(2, lo).max(ray.at(2, hi));
    let spans = spans(answer);
    let mut best: Option<Q> = None;
    let done = |best: &Option<Q>, t: &Q| best.as_ref().is_some_and(|b| b <= t);
    'spans: for span in spans {
        if done(&best, &span[0].t_enter) {
            break;
        }
        if runs {
            let t_lo = span
                .iter()
                .map(|c| &c.t_enter)
                .min()
                .expect("non-empty span");
            let t_hi = span
                .iter()
                .map(|c| &c.t_exit)
                .max()
                .expect("non-empty span");
            let highest = span
                .iter()
                .map(|c| answer.field.cell_max(c.cell))
                .max()
                .expect("non-empty span");
            if !counters.run.record(lowest(t_lo, t_hi) <= *highest) {
                continue;
            }
        }
        for contact in span {
            if done(&best, &contact.t_enter) {
                break 'spans;
            }
            // (A ray above the cell's highest corner or below its lowest misses it.)
            let (t_enter, t_exit) = (&contact.t_enter, &contact.t_exit);
            let may_hit = lowest(t_enter, t_exit) <= *answer.field.cell_max(contact.cell)
                && highest(t_enter, t_exit) >= *answer.field.cell_min(contact.cell);
            if !counters.cell.record(may_hit) || answer.field.is_hole(contact.cell) {
                continue;
            }
            let touches = answer
                .touches
                .get(&contact.cell)
                .cloned()
                .unwrap_or_else(|| {
                    [0, 1].map(|k| first_touch(&answer.field, ray, contact.cell, k))
                });
            for t in touches.into_iter() {
                if !counters.triangle.record(t.is_some()) {
                    continue;
                }
                let t = t.expect("recorded as a hit");
                if best.as_ref().is_none_or(|b| t < *b) {
                    best = Some(t);
                }
            }
        }
    }
    counters
}

/// The covered cells grouped in spans.
fn spans(answer: &Answer) -> Vec<&[Contact]> {
    let ray = &answer.ray;
    let (major, minor) = if ray.x_major() { (0, 1) } else { (1, 0) };
    if answer.cells.is_empty() {
        return Vec::new();
    }
    // A level path of positive length walks its one or two rows as a single span; a path
    // clipped to a single point is walked like a point, row by row.
    let single_point = answer.clip.as_ref().is_some_and(|(t0, t1)| t0 == t1);
    if ray.dir[minor] == 0.0 && ray.dir[major] != 0.0 && !single_point {
        return vec![&answer.cells[..]];
    }
    answer
        .cells
        .chunk_by(|a, b| a.cell[minor] == b.cell[minor])
        .collect()
}
