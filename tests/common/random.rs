//! Proptest strategies for random small fields and rays that favour degenerate cases:
//! integer, half and quarter coordinates, sample heights, rays aimed at vertices and edge
//! midpoints, -0.0 components, flat and nearly flat fields, z_scale 0.

use heightray::{Heightfield, Ray};
use proptest::prelude::*;

/// A small deterministic generator (xorshift64*), for tests that draw many values outside
/// proptest.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// A number in `0..n` (0 for `n` 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    /// A number in `[lo, hi)`.
    pub fn within(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn z_scale(maxval: u32) -> BoxedStrategy<f64> {
    let m = f64::from(maxval);
    prop_oneof![Just(m), Just(m / 4.0), Just(1.0), Just(0.0), 0.01f64..100.0].boxed()
}

fn samples(maxval: u32, count: usize) -> BoxedStrategy<Vec<u16>> {
    let m = maxval as u16;
    let sample = prop_oneof![
        (0..=m).boxed(),
        (0u16..=3).boxed(),
        prop_oneof![Just(0), Just(m / 2), Just(m)].boxed(),
    ];
    // Per field, one sample style (so some fields are nearly flat, some very rough).
    (0usize..3)
        .prop_flat_map(move |style| {
            let s = match style {
                0 => (0..=m).boxed(),
                1 => (0u16..=3).boxed(),
                _ => sample.clone().boxed(),
            };
            proptest::collection::vec(s, count)
        })
        .boxed()
}

/// A field of 2..=`n` samples per side.
pub fn field_up_to(n: usize) -> impl Strategy<Value = Heightfield> {
    (
        2usize..=n,
        2usize..=n,
        prop_oneof![Just(255u32), Just(1000u32)],
    )
        .prop_flat_map(|(w, h, maxval)| {
            (
                Just((w, h, maxval)),
                samples(maxval, w * h),
                z_scale(maxval),
            )
        })
        .prop_map(|((w, h, maxval), s, z_scale)| {
            Heightfield::from_fn(w, h, maxval, z_scale, |x, y| s[y * w + x]).expect("valid field")
        })
}

/// A horizontal coordinate on a grid with `n` samples: integers, halves, quarters (which meet
/// grid lines and lattice points) or any f64, from a little outside the grid.
fn coordinate(n: usize) -> BoxedStrategy<f64> {
    let n = n as i32;
    prop_oneof![
        (-2..=n + 1).prop_map(f64::from),
        (-4..=2 * n + 2).prop_map(|k| f64::from(k) / 2.0),
        (-8..=4 * n + 4).prop_map(|k| f64::from(k) / 4.0),
        -2.0..f64::from(n + 1),
    ]
    .boxed()
}

/// A height: quarters of the field's top, a sample height, or any f64.
fn height(field: &Heightfield) -> BoxedStrategy<f64> {
    let top = field.z_scale();
    let heights: Vec<f64> = field
        .samples()
        .iter()
        .map(|&s| field.height_of(s))
        .collect();
    prop_oneof![
        (-1..=5).prop_map(move |k| top * f64::from(k) / 4.0),
        proptest::sample::select(heights),
        -1.0..top + 2.0,
    ]
    .boxed()
}

fn direction_component() -> BoxedStrategy<f64> {
    prop_oneof![
        (-3..=3).prop_map(f64::from),
        (-8..=8).prop_map(|k| f64::from(k) / 4.0),
        -1.0f64..1.0,
        Just(-0.0),
    ]
    .boxed()
}

fn vertical_component(top: f64) -> BoxedStrategy<f64> {
    let top = top.max(1.0);
    prop_oneof![
        (-8..=4).prop_map(move |k| top * f64::from(k) / 8.0),
        Just(0.0),
        Just(-0.0),
        -top..top,
    ]
    .boxed()
}

/// Rays from anywhere, and rays aimed at a vertex or an edge midpoint of the surface (from
/// `k` direction steps before it).
pub fn ray_on(field: &Heightfield) -> BoxedStrategy<Ray> {
    let (w, h) = (field.width(), field.height());
    let top = field.z_scale();
    let direction = (
        direction_component(),
        direction_component(),
        vertical_component(top),
    );
    let free = (
        coordinate(w),
        coordinate(h),
        height(field),
        direction.clone(),
    )
        .prop_map(|(x, y, z, (dx, dy, dz))| ([x, y, z], [dx, dy, dz]));
    let f = field.clone();
    let aimed = (
        0..w,
        0..h,
        0u8..3,
        direction,
        proptest::sample::select(vec![0.0, 0.5, 1.0, 2.0, 3.0]),
    )
        .prop_map(move |(i, j, kind, (dx, dy, dz), k)| {
            let (i1, j1) = ((i + 1).min(w - 1), (j + 1).min(h - 1));
            let target = match kind {
                0 => [i as f64, j as f64, f.z(i, j)],
                1 => [
                    (i + i1) as f64 / 2.0,
                    j as f64,
                    (f.z(i, j) + f.z(i1, j)) / 2.0,
                ],
                _ => [
                    (i + i1) as f64 / 2.0,
                    (j + j1) as f64 / 2.0,
                    (f.z(i, j) + f.z(i1, j1)) / 2.0,
                ],
            };
            let d = [dx, dy, dz];
            ([0, 1, 2].map(|c| target[c] - k * d[c]), d)
        });
    prop_oneof![free, aimed]
        .prop_filter_map("zero direction", |(o, d)| Ray::new(o, d).ok())
        .boxed()
}

pub fn field_and_ray() -> impl Strategy<Value = (Heightfield, Ray)> {
    field_and_ray_up_to(9)
}

/// A field of 2..=`n` samples per side and a ray on it.
pub fn field_and_ray_up_to(n: usize) -> impl Strategy<Value = (Heightfield, Ray)> {
    field_up_to(n).prop_flat_map(|field| {
        let ray = ray_on(&field);
        (Just(field), ray)
    })
}

/// Rays from far off aimed at the map: an origin 1e13 to 1e308 away along one axis (the
/// others a few cells off the target) or off any diagonal, in every octant, the direction
/// `target - origin` (rounded: from far off a diagonal it passes the target at a distance),
/// sometimes scaled down to subnormals.
pub fn far_ray_on(field: &Heightfield) -> BoxedStrategy<Ray> {
    let (w, h) = (field.width(), field.height());
    let target = (coordinate(w), coordinate(h), height(field));
    let distance = (13i32..=307, 1.0f64..9.99).prop_map(|(e, m)| m * 10f64.powi(e));
    let side = (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0, 0usize..4);
    let scale = prop_oneof![Just(0i32), Just(-1000), -1075i32..-1000];
    (target, distance, side, scale)
        .prop_filter_map("zero direction", |((x, y, z), s, (a, b, c, axis), k)| {
            let target = [x, y, z];
            let o = if axis < 3 {
                let mut o = target;
                o[axis] += s * a.signum();
                o[(axis + 1) % 3] += 4.0 * b;
                o[(axis + 2) % 3] += 4.0 * c;
                o
            } else {
                [0, 1, 2].map(|i| target[i] + s * [a, b, c][i])
            };
            let half = k / 2;
            let d = [0, 1, 2].map(|i| (target[i] - o[i]) * 2f64.powi(half) * 2f64.powi(k - half));
            Ray::new(o, d).ok()
        })
        .boxed()
}
