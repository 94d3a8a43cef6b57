//! Clipping a ray to an axis-aligned box (slabs), in any arithmetic.

use crate::traverse::scalar::{max, min, Scalar};

/// The parameter range `[t0, t1]` (with `t0 >= 0`) in which `o + t*d` lies in the closed box
/// `[lo, hi]`, or `None` if it never does.
pub fn clip_to_box<S: Scalar>(o: &[S; 3], d: &[S; 3], lo: &[S; 3], hi: &[S; 3]) -> Option<(S, S)> {
    let mut t0 = S::zero();
    let mut t1: Option<S> = None;
    for axis in 0..3 {
        if d[axis].is_zero() {
            // Parallel to this slab: inside it for every t, or never.
            if o[axis] < lo[axis] || o[axis] > hi[axis] {
                return None;
            }
            continue;
        }
        let ta = (lo[axis].clone() - o[axis].clone()) / d[axis].clone();
        let tb = (hi[axis].clone() - o[axis].clone()) / d[axis].clone();
        let (near, far) = if d[axis].is_negative() {
            (tb, ta)
        } else {
            (ta, tb)
        };
        t0 = max(t0, near);
        t1 = Some(match t1 {
            Some(t) => min(t, far),
            None => far,
        });
    }
    // A box is bounded, so some axis has a non-zero direction component (rays are validated).
    let t1 = t1?;
    (t0 <= t1).then_some((t0, t1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clips_and_misses() {
        let (lo, hi) = ([0.0, 0.0, 0.0], [4.0, 4.0, 1.0]);
        let got = clip_to_box(&[-1.0, 1.0, 0.5], &[1.0, 0.0, 0.0], &lo, &hi);
        assert_eq!(got, Some((1.0, 5.0)));
        assert_eq!(
            clip_to_box(&[-1.0, 1.0, 2.0], &[1.0, 0.0, 0.0], &lo, &hi),
            None
        );
        // Starting inside: t0 = 0.
        assert_eq!(
            clip_to_box(&[1.0, 1.0, 0.5], &[0.0, 0.0, -1.0], &lo, &hi),
            Some((0.0, 0.5))
        );
        // Pointing away.
        assert_eq!(
            clip_to_box(&[5.0, 1.0, 0.5], &[1.0, 0.0, 0.0], &lo, &hi),
            None
        );
    }
}
