//! The reference's numbers: exact rationals of `f64` inputs, closed sets of ray parameters
//! cut by half-planes and slabs, and the ray and the field's heights as rationals.

use heightray::{Heightfield, Ray};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

pub type Q = BigRational;

/// The exact value of a finite `f64`.
pub fn q(x: f64) -> Q {
    BigRational::from_float(x).expect("finite f64")
}

/// An integer as a rational.
pub fn qi(n: i64) -> Q {
    BigRational::from_integer(BigInt::from(n))
}

pub(super) fn floor_i64(x: &Q) -> i64 {
    x.floor()
        .to_integer()
        .to_i64()
        .expect("grid coordinate fits i64")
}

/// A closed set of ray parameters `lo <= t <= hi` (`hi == None`: unbounded), possibly empty.
#[derive(Clone, Debug)]
pub(super) struct Interval {
    pub(super) lo: Q,
    pub(super) hi: Option<Q>,
    empty: bool,
}

impl Interval {
    /// `t >= 0`.
    pub(super) fn nonnegative() -> Self {
        Interval {
            lo: Q::zero(),
            hi: None,
            empty: false,
        }
    }

    pub(super) fn closed(lo: Q, hi: Q) -> Self {
        let empty = lo > hi;
        Interval {
            lo,
            hi: Some(hi),
            empty,
        }
    }

    /// Keeps the `t` with `g0 + g1*t >= 0`; returns whether anything is left.
    pub(super) fn keep(&mut self, g0: &Q, g1: &Q) -> bool {
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
    pub(super) fn slab(&mut self, o: &Q, d: &Q, lo: &Q, hi: &Q) -> bool {
        self.keep(&(o - lo), d) && self.keep(&(hi - o), &-d)
    }

    pub(super) fn contains(&self, t: &Q) -> bool {
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

    pub(super) fn cell_count(&self) -> usize {
        (self.w - 1) * (self.h - 1)
    }
}
