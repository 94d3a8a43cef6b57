//! The node test ([`Lanes::test`]) in explicit AVX2 and AVX-512 instructions: the same steps
//! in the same order (`maxpd` and `minpd` are `larger` and `smaller`, a blend is the `if`),
//! never fused, so every lane's values are the portable test's, bit for bit.

use super::lanes::{Lanes, NodeTest, ROOM};
use super::LANES;
use std::arch::x86_64::*;

/// [`Lanes::test`] four lanes to an AVX2 register.
#[inline]
#[target_feature(enable = "avx2")]
pub(super) fn test_avx2(l: &Lanes, room: f64, faces: [f64; 4], highest: f64) -> NodeTest {
    let mut test = NodeTest {
        touch: 0,
        may: 0,
        enter: [0.0; LANES],
    };
    for at in [0, 4] {
        let (touch, may) = quarter_avx2(l, at, room, faces, highest, &mut test.enter);
        test.touch |= touch << at;
        test.may |= may << at;
    }
    test
}

/// Lanes `at..at + 4` of [`test_avx2`]: their touch and may bits, their entries into `enter`.
#[inline]
#[target_feature(enable = "avx2")]
fn quarter_avx2(
    l: &Lanes,
    at: usize,
    room: f64,
    [u0, u1, v0, v1]: [f64; 4],
    highest: f64,
    enter: &mut [f64; LANES],
) -> (u32, u32) {
    assert!(at + 4 <= LANES);
    // SAFETY: lanes `at..at + 4` lie inside every array (asserted above).
    let load = |a: &[f64; LANES]| unsafe { _mm256_loadu_pd(a.as_ptr().add(at)) };
    let (ou, ov, iu, iv) = (load(&l.ou), load(&l.ov), load(&l.inv_du), load(&l.inv_dv));
    let (oz, dz, t_lo, t_hi) = (load(&l.oz), load(&l.dz), load(&l.t_lo), load(&l.t_hi));
    let tu0 = _mm256_mul_pd(_mm256_sub_pd(_mm256_set1_pd(u0 - room), ou), iu);
    let tu1 = _mm256_mul_pd(_mm256_sub_pd(_mm256_set1_pd(u1 + room), ou), iu);
    let tv0 = _mm256_mul_pd(_mm256_sub_pd(_mm256_set1_pd(v0 - room), ov), iv);
    let tv1 = _mm256_mul_pd(_mm256_sub_pd(_mm256_set1_pd(v1 + room), ov), iv);
    let t_enter = _mm256_max_pd(_mm256_max_pd(tu0, tv0), t_lo);
    let t_exit = _mm256_min_pd(_mm256_min_pd(tu1, tv1), t_hi);
    let descends = _mm256_cmp_pd::<_CMP_LT_OQ>(dz, _mm256_setzero_pd());
    let dz_t = _mm256_mul_pd(dz, _mm256_blendv_pd(t_enter, t_exit, descends));
    let sign = _mm256_set1_pd(-0.0);
    let size = _mm256_add_pd(_mm256_andnot_pd(sign, oz), _mm256_andnot_pd(sign, dz_t));
    let lowest = _mm256_sub_pd(
        _mm256_add_pd(oz, dz_t),
        _mm256_mul_pd(_mm256_set1_pd(ROOM), size),
    );
    let touch = _mm256_cmp_pd::<_CMP_LE_OQ>(t_enter, t_exit);
    let below = _mm256_cmp_pd::<_CMP_LE_OQ>(lowest, _mm256_set1_pd(highest));
    let may = _mm256_and_pd(touch, below);
    // SAFETY: as the loads.
    unsafe { _mm256_storeu_pd(enter.as_mut_ptr().add(at), t_enter) };
    let bits = |mask| _mm256_movemask_pd(mask) as u32;
    (bits(touch), bits(may))
}

/// [`Lanes::test`] in one AVX-512 register.
#[inline]
#[target_feature(enable = "avx512f")]
pub(super) fn test_avx512(
    l: &Lanes,
    room: f64,
    [u0, u1, v0, v1]: [f64; 4],
    highest: f64,
) -> NodeTest {
    // SAFETY: every array holds `LANES`, eight, values: one register.
    let load = |a: &[f64; LANES]| unsafe { _mm512_loadu_pd(a.as_ptr()) };
    let (ou, ov, iu, iv) = (load(&l.ou), load(&l.ov), load(&l.inv_du), load(&l.inv_dv));
    let (oz, dz, t_lo, t_hi) = (load(&l.oz), load(&l.dz), load(&l.t_lo), load(&l.t_hi));
    let tu0 = _mm512_mul_pd(_mm512_sub_pd(_mm512_set1_pd(u0 - room), ou), iu);
    let tu1 = _mm512_mul_pd(_mm512_sub_pd(_mm512_set1_pd(u1 + room), ou), iu);
    let tv0 = _mm512_mul_pd(_mm512_sub_pd(_mm512_set1_pd(v0 - room), ov), iv);
    let tv1 = _mm512_mul_pd(_mm512_sub_pd(_mm512_set1_pd(v1 + room), ov), iv);
    let t_enter = _mm512_max_pd(_mm512_max_pd(tu0, tv0), t_lo);
    let t_exit = _mm512_min_pd(_mm512_min_pd(tu1, tv1), t_hi);
    let descends = _mm512_cmp_pd_mask::<_CMP_LT_OQ>(dz, _mm512_setzero_pd());
    let dz_t = _mm512_mul_pd(dz, _mm512_mask_blend_pd(descends, t_enter, t_exit));
    let size = _mm512_add_pd(_mm512_abs_pd(oz), _mm512_abs_pd(dz_t));
    let lowest = _mm512_sub_pd(
        _mm512_add_pd(oz, dz_t),
        _mm512_mul_pd(_mm512_set1_pd(ROOM), size),
    );
    let touch = _mm512_cmp_pd_mask::<_CMP_LE_OQ>(t_enter, t_exit);
    let may = _mm512_mask_cmp_pd_mask::<_CMP_LE_OQ>(touch, lowest, _mm512_set1_pd(highest));
    let mut enter = [0.0; LANES];
    // SAFETY: as the loads.
    unsafe { _mm512_storeu_pd(enter.as_mut_ptr(), t_enter) };
    NodeTest {
        touch: u32::from(touch),
        may: u32::from(may),
        enter,
    }
}
