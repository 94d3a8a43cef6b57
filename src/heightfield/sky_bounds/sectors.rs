//! The sky's sectors of azimuth: which sector a direction lies in, and the sectors as cones
//! of directions, widened for rounding.

use super::{ANGLE_PAD, SKY_SECTORS};
use std::f64::consts::PI;

/// The sector of the horizontal direction `(x, y)` (not both zero): its quadrant from the
/// signs, then its quarter of the quadrant from the tangents of the quarters' edges. A
/// direction within rounding of an edge may be put on either side: the sectors' patterns are
/// widened by [`ANGLE_PAD`], far more than that. (No `atan2`, which costs a sky ray more than
/// its look-up.)
pub(super) fn sector_of(x: f64, y: f64) -> usize {
    // The direction in its quadrant's own axes `(a, b)`, both non-negative, `a` along the
    // quadrant's first edge.
    // (Each quadrant holds its first edge, as the angle's sectors do.)
    let (quadrant, a, b) = if x > 0.0 && y >= 0.0 {
        (0, x, y)
    } else if x <= 0.0 && y > 0.0 {
        (1, y, -x)
    } else if x < 0.0 {
        (2, -x, -y)
    } else {
        (3, -y, x)
    };
    // tan(pi/8) and tan(3pi/8): the quarters' inner edges (the middle one is the diagonal).
    const LOW: f64 = std::f64::consts::SQRT_2 - 1.0;
    const HIGH: f64 = std::f64::consts::SQRT_2 + 1.0;
    const _: () = assert!(SKY_SECTORS == 16, "four sectors a quadrant");
    let quarter = usize::from(b > LOW * a) + usize::from(b > a) + usize::from(b > HIGH * a);
    quadrant * 4 + quarter
}

/// The sectors, each widened by [`ANGLE_PAD`] on both sides.
pub(super) fn sector_cones() -> [Cone; SKY_SECTORS] {
    let width = 2.0 * PI / SKY_SECTORS as f64;
    std::array::from_fn(|s| {
        Cone::new(
            s as f64 * width - ANGLE_PAD,
            (s + 1) as f64 * width + ANGLE_PAD,
        )
    })
}

/// The directions between two azimuths (less than a half turn apart).
#[derive(Debug)]
pub(super) struct Cone {
    pub(super) lo: [f64; 2],
    pub(super) hi: [f64; 2],
}

impl Cone {
    fn new(from: f64, to: f64) -> Cone {
        Cone {
            lo: [from.cos(), from.sin()],
            hi: [to.cos(), to.sin()],
        }
    }

    /// Whether direction `c` lies inside (edges included).
    pub(super) fn inside(&self, c: [f64; 2]) -> bool {
        cross(self.lo, c) >= 0.0 && cross(c, self.hi) >= 0.0
    }

    /// Whether the rectangle `[x0, y0, x1, y1]` may hold a point of the cone (false only
    /// where it certainly does not).
    pub(super) fn meets(&self, [x0, y0, x1, y1]: [f64; 4]) -> bool {
        if x0 <= 0.0 && x1 >= 0.0 && y0 <= 0.0 && y1 >= 0.0 {
            return true;
        }
        let corners = [[x0, y0], [x1, y0], [x0, y1], [x1, y1]];
        corners.iter().any(|&c| self.inside(c))
            || [self.lo, self.hi]
                .iter()
                .any(|&u| ray_meets(u, [x0, y0, x1, y1]))
    }
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Whether the ray `t * u` (`t >= 0`) meets the rectangle (a slab test, edges included).
fn ray_meets(u: [f64; 2], [x0, y0, x1, y1]: [f64; 4]) -> bool {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for (k, (lo, hi)) in [(x0, x1), (y0, y1)].into_iter().enumerate() {
        if u[k] == 0.0 {
            if lo > 0.0 || hi < 0.0 {
                return false;
            }
            continue;
        }
        let (a, b) = (lo / u[k], hi / u[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 <= t1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sector found by the quadrant and tangents is the one the angle gives, for
    /// directions all round, away from the edges by more than the sectors are widened.
    #[test]
    fn sector_of_agrees_with_the_angle() {
        let width = 2.0 * PI / SKY_SECTORS as f64;
        for k in 0..100_000 {
            let angle = (k as f64 + 0.37) * 2.0 * PI / 100_000.0;
            let from_edge = (angle / width - (angle / width).round()).abs() * width;
            if from_edge < 10.0 * ANGLE_PAD {
                continue;
            }
            let expected = (angle / width) as usize % SKY_SECTORS;
            for length in [1e-3, 1.0, 7.5e5] {
                let (x, y) = (length * angle.cos(), length * angle.sin());
                assert_eq!(sector_of(x, y), expected, "angle {angle}, length {length}");
            }
        }
        // The axes lie in the sectors that start there.
        assert_eq!(sector_of(1.0, 0.0), 0);
        assert_eq!(sector_of(0.0, 1.0), 4);
        assert_eq!(sector_of(-1.0, 0.0), 8);
        assert_eq!(sector_of(0.0, -1.0), 12);
    }
}
