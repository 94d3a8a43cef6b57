//! A look in `f64` that proves a ray misses a face of the base, so that the arithmetics
//! without rounding (each of whose operations costs many `f64` ones) test only the faces the
//! ray may touch. Each value carries a bound on how far the exact one may lie from it: the
//! radius of the ray's enclosure and eight units of rounding per operation, far more than the
//! one or two each makes.

use crate::arith::Scalar;

/// Eight units of rounding.
const ROUNDING: f64 = 8.0 * f64::EPSILON;

/// A ray near an exact one in `f64`, and the `t` before which a touch counts.
pub(super) struct Screen {
    o: [f64; 3],
    radius: [f64; 3],
    d: [f64; 3],
    /// The exact `t` a touch must come before is at most this.
    limit: f64,
}

impl Screen {
    /// The screen of the ray `o + t*d` in an arithmetic without rounding, touches counting
    /// before `before`; `None` in the others, and where the direction is not an `f64`
    /// exactly.
    pub(super) fn new<S: Scalar>(o: &[S; 3], d: &[S; 3], before: Option<&S>) -> Option<Screen> {
        if !S::EXACT {
            return None;
        }
        let exact = |c: &S| c.f64_enclosure().filter(|&(_, r)| r == 0.0).map(|(x, _)| x);
        let d = [exact(&d[0])?, exact(&d[1])?, exact(&d[2])?];
        let [x, y, z] = [&o[0], &o[1], &o[2]].map(|c| c.f64_enclosure());
        let [(x, rx), (y, ry), (z, rz)] = [x?, y?, z?];
        let limit = match before {
            Some(t) => t.f64_enclosure().map_or(f64::INFINITY, |(t, r)| t + r),
            None => f64::INFINITY,
        };
        Some(Screen {
            o: [x, y, z],
            radius: [rx, ry, rz],
            d,
            limit,
        })
    }

    /// Whether the ray certainly misses, at `0 <= t <` the limit, the box `lo <= p <= hi` of
    /// the plane `p[axis] = at` (the bounds on `axis` itself are not read). A ray running
    /// parallel to the plane is not screened.
    pub(super) fn misses(&self, axis: usize, at: f64, lo: [f64; 3], hi: [f64; 3]) -> bool {
        let (o, d) = (self.o[axis], self.d[axis]);
        if d == 0.0 {
            return false;
        }
        let t = (at - o) / d;
        let t_off = (self.radius[axis] + ROUNDING * (at.abs() + o.abs())) / d.abs()
            * (1.0 + ROUNDING)
            + ROUNDING * t.abs();
        if !(t.is_finite() && t_off.is_finite()) {
            return false;
        }
        if t + t_off < 0.0 || t - t_off > self.limit {
            return true;
        }
        (0..3).filter(|&k| k != axis).any(|k| {
            let p = self.o[k] + self.d[k] * t;
            let off = self.radius[k]
                + self.d[k].abs() * t_off
                + ROUNDING * (self.o[k].abs() + (self.d[k] * t).abs())
                + f64::MIN_POSITIVE;
            p + off < lo[k] || p - off > hi[k]
        })
    }
}
