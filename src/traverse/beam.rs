//! Beams: rays that share an origin and whose directions lie between four corner directions
//! (a camera's tile of pixels). One march of the whole beam over the max-mipmap finds how far
//! every ray of it travels before any may touch the surface, so each ray's own walk starts
//! there instead of at the eye: the approach over empty land is walked once per tile, not
//! once per pixel.
//!
//! Why it is exact: at parameter `t` the beam's points are the convex hull of the corners'
//! points (every direction is a convex combination of the corners), so over `[ta, tb]` they
//! lie in the box around the corners' points at `ta` and `tb`, and no lower than the lowest
//! of them. A stretch whose lowest point stays above the highest sample of every cell under
//! that box (grown by far more than any rounding) is clear for every ray of the beam.

use super::counters::HitMiss;
use crate::heightfield::Terrain;

/// Relative room for directions computed in `f64`: a ray's direction may lie this far
/// (relative to the corners' largest component) outside the hull of the corners.
const DIR_ROOM: f64 = 1e-9;

/// The most footprints one march tests (it needs a few dozen; this only bounds a march
/// that cannot settle, such as one along a face of the box).
const MAX_STEPS: u32 = 200;

/// How far a beam's rays travel clear of the surface: up to `t`, where the last footprint
/// the march tested (one that may touch the surface) was made of level-`level` blocks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clearance {
    /// No ray of the beam touches the surface before this `t`.
    pub t: f64,
    /// The mipmap level of the blocks of the last footprint tested.
    pub level: u32,
}

/// Rays `origin + t * dir`, each `dir` a convex combination of the four corners (within
/// `DIR_ROOM`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beam {
    /// The rays' shared origin (the camera's eye).
    pub origin: [f64; 3],
    /// The directions of the four corner rays.
    pub corners: [[f64; 3]; 4],
}

impl Beam {
    /// How far no ray of the beam touches the surface (`t` 0 when the beam cannot be cleared
    /// at all, infinity when it never comes near), and the footprint tests it took (hit: a
    /// footprint that may touch the surface).
    ///
    /// The march doubles its step past clear stretches and halves it where the footprint may
    /// touch the surface, and ends where a smaller step would not make the footprint much
    /// smaller: its own advance is below a quarter of the beam's width (or of a cell).
    pub fn clear_until(&self, terrain: &Terrain) -> (Clearance, HitMiss) {
        let mut tests = HitMiss::default();
        let field = terrain.field();
        let (w, h) = (field.width() as f64 - 1.0, field.height() as f64 - 1.0);
        let (z_lo, z_hi) = terrain.z_range();
        let c = &self.corners;
        let largest = c.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let (mut t, mut level) = (0.0, terrain.mipmap().top());
        if !(largest > 0.0 && largest.is_finite()) {
            return (Clearance { t, level }, tests);
        }
        let speed = c
            .iter()
            .fold(0.0f64, |m, d| m.max(d[0].abs().max(d[1].abs())));
        let climb = c.iter().fold(0.0f64, |m, d| m.max(d[2].abs()));
        let spread = (0..2).fold(0.0f64, |m, k| {
            let (lo, hi) = min_max(c.iter().map(|d| d[k]));
            m.max(hi - lo)
        });
        let relief = (z_hi - z_lo).max(1e-9 * z_hi.abs().max(1.0));
        let o = self.origin;
        let o_size = o.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // What a point of the beam at `t` may be off by: its direction's room, and far more
        // than the rounding of `o + t * corner`.
        let room = |t: f64| (DIR_ROOM + 1e-12) * (o_size + t * largest) + DIR_ROOM * t * largest;
        // About a cell to begin with.
        let mut step = 1.0 / speed.max(climb);
        for _ in 0..MAX_STEPS {
            let tb = t + step;
            let g = room(tb);
            // The box around the corners' points at both ends, and the lowest of them.
            let (mut xs, mut ys, mut lowest) = (
                (f64::INFINITY, f64::NEG_INFINITY),
                (f64::INFINITY, f64::NEG_INFINITY),
                f64::INFINITY,
            );
            for d in c {
                for s in [t, tb] {
                    let [x, y, z] = [0, 1, 2].map(|k| o[k] + s * d[k]);
                    (xs, ys) = ((xs.0.min(x), xs.1.max(x)), (ys.0.min(y), ys.1.max(y)));
                    lowest = lowest.min(z - g);
                }
            }
            let clear = match highest_under(terrain, [xs.0 - g, xs.1 + g], [ys.0 - g, ys.1 + g]) {
                None => true,
                Some((highest, k)) => {
                    level = k;
                    !tests.record(lowest <= highest + 1e-12 * highest.abs())
                }
            };
            if clear {
                t = tb;
                if self.gone(t, room(t), (w, h), z_hi) {
                    let t = f64::INFINITY;
                    return (Clearance { t, level }, tests);
                }
                step *= 2.0;
            } else if step * speed <= 0.25 * (1.0 + spread * t) && step * climb <= 0.01 * relief {
                return (Clearance { t, level }, tests);
            } else {
                step /= 2.0;
            }
        }
        (Clearance { t, level }, tests)
    }

    /// Whether the whole beam has left the terrain's box at `t` for good: every corner is
    /// beyond one face of it by more than `room` and moving away (then so is every convex
    /// combination).
    fn gone(&self, t: f64, room: f64, (w, h): (f64, f64), z_hi: f64) -> bool {
        let o = self.origin;
        let at = |d: &[f64; 3], k: usize| o[k] + t * d[k];
        let beyond = |k: usize, face: f64, outwards: f64| {
            self.corners
                .iter()
                .all(|d| (at(d, k) - face) * outwards > room && d[k] * outwards >= 0.0)
        };
        beyond(0, 0.0, -1.0)
            || beyond(0, w, 1.0)
            || beyond(1, 0.0, -1.0)
            || beyond(1, h, 1.0)
            || beyond(2, z_hi, 1.0)
    }
}

/// The highest height under the cells meeting the box `[x0, x1] x [y0, y1]`, from at most
/// four blocks of one mipmap level, and that level; `None` if the box misses the grid.
pub fn highest_under(
    terrain: &Terrain,
    [x0, x1]: [f64; 2],
    [y0, y1]: [f64; 2],
) -> Option<(f64, u32)> {
    let field = terrain.field();
    let (w, h) = (field.width() as f64 - 1.0, field.height() as f64 - 1.0);
    if x1 < 0.0 || y1 < 0.0 || x0 > w || y0 > h {
        return None;
    }
    // Cells whose closed square meets the box (a point on a shared edge lies in both cells;
    // either holds the surface there).
    let cell = |x: f64, n: f64| x.floor().clamp(0.0, n - 1.0) as usize;
    let (i0, i1, j0, j1) = (cell(x0, w), cell(x1, w), cell(y0, h), cell(y1, h));
    // The finest level at which the cells span at most two blocks each way.
    let mut k = 0;
    while (i1 >> k).saturating_sub(i0 >> k) > 1 || (j1 >> k).saturating_sub(j0 >> k) > 1 {
        k += 1;
    }
    let mut highest = 0;
    for bj in (j0 >> k)..=(j1 >> k) {
        for bi in (i0 >> k)..=(i1 >> k) {
            highest = highest.max(terrain.block_max_sample(k, bi, bj));
        }
    }
    Some((field.height_of(highest), k))
}

fn min_max(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    })
}
