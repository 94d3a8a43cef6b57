//! Clipping a ray to an axis-aligned box (slabs), in any arithmetic.

use crate::arith::scalar::Scalar;

/// The part of a ray inside a box: `t0..=t1` (with `t0 >= 0`), and for each end the box face
/// it lies on, if a face and not the ray's origin fixes it: `(axis, value)`. The end point's
/// coordinate on that axis is exactly `value`, which arithmetic that rounds cannot tell from
/// `o + t*d` alone.
#[derive(Clone, Debug, PartialEq)]
pub struct Clipped<S> {
    /// Where the ray enters the box (0 where it starts inside).
    pub t0: S,
    /// Where the ray leaves the box.
    pub t1: S,
    /// The face the entry point lies on, `(axis, value)`; `None` where the ray starts inside.
    pub entry_face: Option<(usize, S)>,
    /// The face the exit point lies on, `(axis, value)`.
    pub exit_face: Option<(usize, S)>,
}

/// Clips `o + t*d` (t >= 0) to the closed box `[lo, hi]`, or `None` if it never meets it.
#[inline]
pub fn clip_to_box<S: Scalar>(
    o: &[S; 3],
    d: &[S; 3],
    lo: &[S; 3],
    hi: &[S; 3],
) -> Option<Clipped<S>> {
    // The faces are named by axis until the end: each slab's crossings are compared, and only
    // the two faces that fix the segment are taken.
    let (mut t0, mut entry) = (S::zero(), None);
    let mut exit: Option<(S, usize)> = None;
    for axis in 0..3 {
        if d[axis].is_zero() {
            // Parallel to this slab: inside it for every t, or never.
            if o[axis] < lo[axis] || o[axis] > hi[axis] {
                return None;
            }
            continue;
        }
        let (near, far) = near_far(d, lo, hi, axis);
        let t_near = (near.clone() - o[axis].clone()) / d[axis].clone();
        let t_far = (far.clone() - o[axis].clone()) / d[axis].clone();
        if t_near > t0 {
            (t0, entry) = (t_near, Some(axis));
        }
        if exit.as_ref().is_none_or(|(t, _)| t_far < *t) {
            exit = Some((t_far, axis));
        }
    }
    // A box is bounded, so some axis has a non-zero direction component (rays are validated).
    let (t1, exit) = exit?;
    (t0 <= t1).then(|| Clipped {
        t0,
        t1,
        entry_face: entry.map(|axis| (axis, near_far(d, lo, hi, axis).0.clone())),
        exit_face: Some((exit, near_far(d, lo, hi, exit).1.clone())),
    })
}

/// The faces of the slab of `axis` the ray crosses first and last.
#[inline(always)]
fn near_far<'a, S: Scalar>(
    d: &[S; 3],
    lo: &'a [S; 3],
    hi: &'a [S; 3],
    axis: usize,
) -> (&'a S, &'a S) {
    if d[axis].is_negative() {
        (&hi[axis], &lo[axis])
    } else {
        (&lo[axis], &hi[axis])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn range(c: Option<Clipped<f64>>) -> Option<(f64, f64)> {
        c.map(|c| (c.t0, c.t1))
    }

    #[test]
    fn clips_and_misses() {
        let (lo, hi) = ([0.0, 0.0, 0.0], [4.0, 4.0, 1.0]);
        let through = clip_to_box(&[-1.0, 1.0, 0.5], &[1.0, 0.0, 0.0], &lo, &hi);
        assert_eq!(range(through.clone()), Some((1.0, 5.0)));
        let through = through.unwrap();
        assert_eq!(
            (through.entry_face, through.exit_face),
            (Some((0, 0.0)), Some((0, 4.0)))
        );
        assert_eq!(
            range(clip_to_box(&[-1.0, 1.0, 2.0], &[1.0, 0.0, 0.0], &lo, &hi)),
            None
        );
        // Starting inside: t0 = 0 at the origin, no entry face.
        let inside = clip_to_box(&[1.0, 1.0, 0.5], &[0.0, 0.0, -1.0], &lo, &hi).unwrap();
        assert_eq!((inside.t0, inside.t1, inside.entry_face), (0.0, 0.5, None));
        // Pointing away.
        assert_eq!(
            range(clip_to_box(&[5.0, 1.0, 0.5], &[1.0, 0.0, 0.0], &lo, &hi)),
            None
        );
    }
}
