//! Both triangles of a cell against one `f64` ray at once, in SIMD lanes: the cell's four
//! corners move into ray space a lane each, once for both triangles, and the six edge
//! functions are worked out side by side (one AVX-512 register, two AVX2 registers, or as the
//! compiler vectorises the portable steps: [`SimdPath`]).
//!
//! Why the answers are the scalar test's bit for bit ([`RaySpace::intersect`]): each lane
//! makes the scalar test's operations in its order (subtractions, multiplications, never
//! fused), so every ray-space vertex and rounded edge function has the same bits; a lane
//! whose rounded edge function lies in the band where its sign may be wrong is worked out
//! again by [`Scalar::det2`], exactly as the scalar test decides it; and the rest of each
//! triangle's test is the scalar test's own ([`RaySpace::decide`]).

use super::triangle::{triangle_corners, CellTriangles, RaySpace, TriangleHit};
use crate::arith::scalar::{DET2_ABSOLUTE, DET2_RELATIVE};
use crate::arith::{Scalar, SimdPath};

/// The corners `[P00, P10, P01, P11]` in ray space: x, y and z, a lane per corner.
type Images = [[f64; 4]; 3];

/// The corners' heights in ray space, a lane per corner.
type Heights = [f64; 4];

/// The six edge functions in lanes, `[u0, v0, w0, u1, v1, w1]` of `T0` and `T1`, and two lanes
/// of padding.
type Edges = [f64; 8];

/// What the lanes take: the ray in ray space (its axes, shear and origin) and the cell (its
/// indices and corner heights).
#[derive(Clone, Copy)]
struct Input<'a> {
    axes: [usize; 3],
    shear: &'a [f64; 3],
    origin: &'a [f64; 3],
    cell: (usize, usize),
    heights: [f64; 4],
}

/// The corners `(A, B)` of each edge function `A.x * B.y - A.y * B.x`, lane by lane: for the
/// corners `[a, b, c]` of a triangle, `u` takes `(c, b)`, `v` `(a, c)` and `w` `(b, a)`.
const EDGE_CORNERS: [(usize, usize); 6] = [(3, 1), (0, 3), (1, 0), (2, 3), (0, 2), (3, 0)];

impl<S: Scalar> RaySpace<S> {
    /// Both triangles of cell `(i, j)` with corner heights `[z00, z10, z01, z11]`, as
    /// [`CellTriangles::intersect`] answers each, worked out in `f64` lanes on `path` (which
    /// the processor must have): `None` where `S` is not `f64`.
    #[inline(always)]
    pub fn cell_in_lanes(
        &self,
        path: SimdPath,
        (i, j): (usize, usize),
        heights: [f64; 4],
    ) -> Option<[Option<TriangleHit<S>>; 2]> {
        let shear = S::as_f64s(&self.shear)?;
        let origin = S::as_f64s(self.origin())?;
        let input = Input {
            axes: self.axes,
            shear,
            origin,
            cell: (i, j),
            heights,
        };
        let (q, e) = match path {
            // SAFETY: the caller picks a path the processor has the instructions of.
            #[cfg(target_arch = "x86_64")]
            SimdPath::Avx512 => unsafe { x86::lanes_avx512(input) },
            #[cfg(target_arch = "x86_64")]
            SimdPath::Avx2 => unsafe { x86::lanes_avx2(input) },
            _ => portable(input),
        };
        // (Each triangle in straight code: mapped over `[0, 1]`, the pair of answers goes
        // through the stack in an out-of-line loop that costs more than the lanes.)
        let lanes = (&q, &e);
        Some([
            self.lane_triangle(0, lanes, (i, j), heights),
            self.lane_triangle(1, lanes, (i, j), heights),
        ])
    }

    /// Triangle `k` of cell `(i, j)` from the lanes' heights and edge functions `(q, e)`, as
    /// [`CellTriangles::intersect`] answers it.
    #[inline(always)]
    fn lane_triangle(
        &self,
        k: u8,
        (q, e): (&Heights, &Edges),
        (i, j): (usize, usize),
        heights: [f64; 4],
    ) -> Option<TriangleHit<S>> {
        let at = 3 * usize::from(k);
        let [a, b, c] = triangle_corners(k);
        let (u, v, w) = (e[at], e[at + 1], e[at + 2]);
        let coplanar = || {
            let cell = CellTriangles::new(self, i, j, heights.map(S::from_f64));
            cell.intersect(self, k)
        };
        let (az, bz, cz) = (S::from_f64(q[a]), S::from_f64(q[b]), S::from_f64(q[c]));
        let uv = [S::from_f64(u), S::from_f64(v)];
        self.decide(uv, || S::from_f64(w), [&az, &bz, &cz], coplanar)
    }
}

/// The cell's corners `[P00, P10, P01, P11]` and the ray's origin, with their coordinates in
/// the order of ray space's axes (a lane per corner), before the shear.
#[inline(always)]
fn placed(input: Input<'_>) -> (Images, [f64; 3]) {
    let (i, j) = input.cell;
    let (x0, y0) = (i as i64 as f64, j as i64 as f64);
    let (x1, y1) = ((i as i64 + 1) as f64, (j as i64 + 1) as f64);
    let p = [[x0, x1, x0, x1], [y0, y0, y1, y1], input.heights];
    (
        input.axes.map(|k| p[k]),
        input.axes.map(|k| input.origin[k]),
    )
}

/// Settles the edge functions the rounded lanes leave in doubt (`doubt`: a bit per lane), by
/// the scalar test's own [`Scalar::det2`].
#[inline(always)]
fn settle(q: &Images, e: &mut Edges, mut doubt: u32) {
    while doubt != 0 {
        let n = doubt.trailing_zeros() as usize;
        doubt &= doubt - 1;
        let (a, b) = EDGE_CORNERS[n];
        e[n] = f64::det2(&q[0][a], &q[1][b], &q[1][a], &q[0][b]);
    }
}

/// The ray-space heights and edge functions in plain steps (which the compiler may
/// vectorise).
#[inline(always)]
fn portable(input: Input<'_>) -> (Heights, Edges) {
    let ((p, o), shear) = (placed(input), input.shear);
    let mut q = [[0.0; 4]; 3];
    for n in 0..4 {
        let (x, y, z) = (p[0][n] - o[0], p[1][n] - o[1], p[2][n] - o[2]);
        q[0][n] = x - shear[0] * z;
        q[1][n] = y - shear[1] * z;
        q[2][n] = shear[2] * z;
    }
    let mut e = [0.0; 8];
    let mut doubt = 0;
    for (n, &(a, b)) in EDGE_CORNERS.iter().enumerate() {
        let (p, r) = (q[0][a] * q[1][b], q[1][a] * q[0][b]);
        e[n] = p - r;
        let bound = DET2_RELATIVE * (p.abs() + r.abs()) + DET2_ABSOLUTE;
        // (As `det2` asks: a NaN is in doubt.)
        doubt |= u32::from(e[n].abs() <= bound || e[n].is_nan()) << n;
    }
    settle(&q, &mut e, doubt);
    (q[2], e)
}

#[cfg(target_arch = "x86_64")]
mod x86 {
    //! The lanes in explicit AVX2 and AVX-512 instructions, step for step the portable ones.

    use super::{placed, settle, Edges, Heights, Images, Input, DET2_ABSOLUTE, DET2_RELATIVE};
    use std::arch::x86_64::*;

    /// The corners moved into ray space, a lane per corner: x, y and z.
    #[inline]
    #[target_feature(enable = "avx2")]
    fn images(input: Input<'_>) -> [__m256d; 3] {
        let ((p, o), shear) = (placed(input), input.shear);
        // SAFETY: each corner row holds four values: one register.
        let load = |k: usize| unsafe { _mm256_loadu_pd(p[k].as_ptr()) };
        let rel = |k: usize| _mm256_sub_pd(load(k), _mm256_set1_pd(o[k]));
        let (x, y, z) = (rel(0), rel(1), rel(2));
        [
            _mm256_sub_pd(x, _mm256_mul_pd(_mm256_set1_pd(shear[0]), z)),
            _mm256_sub_pd(y, _mm256_mul_pd(_mm256_set1_pd(shear[1]), z)),
            _mm256_mul_pd(_mm256_set1_pd(shear[2]), z),
        ]
    }

    /// Stores four lanes.
    #[inline]
    #[target_feature(enable = "avx2")]
    fn store(lanes: __m256d) -> [f64; 4] {
        let mut out = [0.0; 4];
        // SAFETY: four values: one register.
        unsafe { _mm256_storeu_pd(out.as_mut_ptr(), lanes) };
        out
    }

    /// Settles the lanes in `doubt` (rare: the images are stored for it only then).
    #[inline]
    #[target_feature(enable = "avx2")]
    fn settle_lanes(q: [__m256d; 3], e: &mut Edges, doubt: u32) {
        if doubt != 0 {
            let images: Images = [store(q[0]), store(q[1]), store(q[2])];
            settle(&images, e, doubt);
        }
    }

    /// `A.x * B.y - A.y * B.x` for the corners picked into `ax`, `ay`, `bx`, `by`, and the
    /// lanes whose rounded value may have the wrong sign.
    #[inline]
    #[target_feature(enable = "avx2")]
    fn edges_avx2(ax: __m256d, ay: __m256d, bx: __m256d, by: __m256d) -> (__m256d, u32) {
        let (p, r) = (_mm256_mul_pd(ax, by), _mm256_mul_pd(ay, bx));
        let value = _mm256_sub_pd(p, r);
        let sign = _mm256_set1_pd(-0.0);
        let size = _mm256_add_pd(_mm256_andnot_pd(sign, p), _mm256_andnot_pd(sign, r));
        let bound = _mm256_add_pd(
            _mm256_mul_pd(_mm256_set1_pd(DET2_RELATIVE), size),
            _mm256_set1_pd(DET2_ABSOLUTE),
        );
        let sure = _mm256_cmp_pd::<_CMP_GT_OQ>(_mm256_andnot_pd(sign, value), bound);
        (value, !(_mm256_movemask_pd(sure) as u32) & 0b0111)
    }

    /// The images and edge functions, four lanes to a register.
    #[inline]
    #[target_feature(enable = "avx2")]
    pub(super) fn lanes_avx2(input: Input<'_>) -> (Heights, Edges) {
        let [qx, qy, qz] = images(input);
        // Lanes `(A, B)` of T0: (3, 1), (0, 3), (1, 0); of T1: (2, 3), (0, 2), (3, 0) (the
        // fourth lane repeats the third).
        const A0: i32 = 3 | (1 << 4) | (1 << 6);
        const B0: i32 = 1 | (3 << 2);
        const A1: i32 = 2 | (3 << 4) | (3 << 6);
        const B1: i32 = 3 | (2 << 2);
        let (e0, d0) = edges_avx2(
            _mm256_permute4x64_pd::<A0>(qx),
            _mm256_permute4x64_pd::<A0>(qy),
            _mm256_permute4x64_pd::<B0>(qx),
            _mm256_permute4x64_pd::<B0>(qy),
        );
        let (e1, d1) = edges_avx2(
            _mm256_permute4x64_pd::<A1>(qx),
            _mm256_permute4x64_pd::<A1>(qy),
            _mm256_permute4x64_pd::<B1>(qx),
            _mm256_permute4x64_pd::<B1>(qy),
        );
        let mut e = [0.0; 8];
        // SAFETY: eight values: two registers.
        unsafe {
            _mm256_storeu_pd(e.as_mut_ptr(), e0);
            _mm256_storeu_pd(e.as_mut_ptr().add(3), e1);
        }
        settle_lanes([qx, qy, qz], &mut e, d0 | (d1 << 3));
        (store(qz), e)
    }

    /// The images four lanes to a register, the six edge functions in one register.
    #[inline]
    #[target_feature(enable = "avx512f,avx2")]
    pub(super) fn lanes_avx512(input: Input<'_>) -> (Heights, Edges) {
        let [qx, qy, qz] = images(input);
        let (x, y) = (_mm512_castpd256_pd512(qx), _mm512_castpd256_pd512(qy));
        // The corners `(A, B)` of the six lanes (the last two repeat the first).
        let a = _mm512_setr_epi64(3, 0, 1, 2, 0, 3, 3, 3);
        let b = _mm512_setr_epi64(1, 3, 0, 3, 2, 0, 1, 1);
        let (ax, ay) = (_mm512_permutexvar_pd(a, x), _mm512_permutexvar_pd(a, y));
        let (bx, by) = (_mm512_permutexvar_pd(b, x), _mm512_permutexvar_pd(b, y));
        let (p, r) = (_mm512_mul_pd(ax, by), _mm512_mul_pd(ay, bx));
        let value = _mm512_sub_pd(p, r);
        let size = _mm512_add_pd(_mm512_abs_pd(p), _mm512_abs_pd(r));
        let bound = _mm512_add_pd(
            _mm512_mul_pd(_mm512_set1_pd(DET2_RELATIVE), size),
            _mm512_set1_pd(DET2_ABSOLUTE),
        );
        let sure = _mm512_cmp_pd_mask::<_CMP_GT_OQ>(_mm512_abs_pd(value), bound);
        let mut e = [0.0; 8];
        // SAFETY: eight values: one register.
        unsafe { _mm512_storeu_pd(e.as_mut_ptr(), value) };
        settle_lanes([qx, qy, qz], &mut e, !u32::from(sure) & 0b11_1111);
        (store(qz), e)
    }
}
