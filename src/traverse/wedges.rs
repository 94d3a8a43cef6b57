//! Camera wedge profiles: how far each ray from one eye travels before it may touch the
//! surface, from a bound per azimuth wedge around the eye (vertical ray coherence, Lee & Shin
//! 1997: the rays in one vertical plane through the eye meet the terrain in order of their
//! elevation).
//!
//! Around the eye's ground point, [`FEWEST_WEDGES`] or twice as many wedges of azimuth are
//! cut into rings of distance `B[k]..B[k+1]` (growing by a constant ratio, so each piece keeps
//! its shape: [`RING_DEPTH`] times as deep as it is wide). Each piece of a wedge gets an upper
//! bound `σ` of `(height - eye height) / distance` over the cells under it, and each wedge
//! keeps the running maximum of its pieces' bounds outwards (its profile).
//!
//! Why it is exact: every point of a ray `eye + t*d` lies in the vertical plane of its
//! azimuth, at distance `ρ = t * |d_xy|` and height `eye_z + s * ρ` (`s = d_z / |d_xy|`, its
//! slope). If `s` is above the profile up to ring `k`, then at every point `p` of the wedge
//! nearer than `B[k+1]` the ray passes above `σ * ρ(p) >= height(p) - eye_z`: it touches
//! nothing before `t = B[k+1] / |d_xy|`. A ray above its wedge's whole profile passes above
//! every point of the map it crosses: a certain miss. The pieces' boxes are grown by far more
//! than the rounding of the ray's azimuth and of the corners, and heights raised by far more
//! than the rounding of the arithmetic the ray is walked in, so the answer holds for the ray
//! as walked (a ray in `f32` is the `f64` ray rounded).

use super::counters::HitMiss;
use crate::arith::Arith;
use crate::heightfield::Terrain;
use std::sync::{Arc, OnceLock};

/// Wedges of azimuth around the eye (a multiple of 4, so that no wedge holds an axis
/// direction inside it and a piece's box is the box of its four corners), and as many again
/// where wider pieces than [`WIDEST_FAR_PIECE`] would reach the map's farthest point: far
/// pieces as wide as that leave rays a long walk from their clearance, while over a smaller
/// extent twice the pieces cost more to build than they save.
const FEWEST_WEDGES: usize = 1024;

/// The widest (cells) the pieces of [`FEWEST_WEDGES`] may be at the map's farthest point
/// before the wedges are doubled.
const WIDEST_FAR_PIECE: f64 = 8.0;

/// The first ring boundary beyond 0, in cells: the piece around the eye's ground point.
const FIRST_RING: f64 = 1.0;

/// How much deeper than wide a piece of a wedge is (its rings grow by `1 + RING_DEPTH * 2π /
/// wedges`): shallower pieces bound the rays closer to where they may first touch.
const RING_DEPTH: f64 = 0.5;

/// The most blocks each way a piece's highest sample is read from (finer blocks where the
/// piece is small).
const BLOCKS_ACROSS: usize = 4;

/// How far a ray travels clear of the surface: up to `t`, after which its walk starts at
/// mipmap level `level` (a wedge's clearance ends next to where the ray may touch: level 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clearance {
    /// The ray touches the surface at no `t` below this (infinity: nowhere).
    pub t: f64,
    /// The mipmap level the walk from `t` starts at.
    pub level: u32,
}

/// The profiles of the wedges around one eye over one terrain, each made the first time a ray
/// in it asks (a frame's rays see only the wedges in view).
#[derive(Clone)]
pub struct Wedges<'a> {
    terrain: &'a Terrain,
    profiles: Arc<Profiles>,
}

/// What [`Wedges`] keep, apart from the terrain: kept across the passes of a view.
pub struct Profiles {
    eye: [f64; 3],
    arith: Arith,
    /// Wedges of azimuth.
    count: usize,
    /// Ring boundaries `B[0] = 0 < B[1] < ...`, the last beyond every point of the map.
    rings: Vec<f64>,
    /// What heights are raised by and boxes grown by, for rounding.
    room: f64,
    /// No point of the map lies this near the eye's ground point (a ring within it holds
    /// none, however large its pieces' boxes).
    nearest: f64,
    /// Per wedge, the running maximum of its pieces' bounds, ring by ring.
    profiles: Vec<OnceLock<Box<[f64]>>>,
}

impl Profiles {
    /// Whether these are the profiles around `eye` for rays walked in `arith`.
    pub fn are_for(&self, eye: [f64; 3], arith: Arith) -> bool {
        self.eye == eye && self.arith == arith
    }
}

impl<'a> Wedges<'a> {
    /// The wedges around `eye` over `terrain` for rays walked in `arith`; `None` where they
    /// cannot be certified (bounded rationals round by a step of their own, not relative to
    /// the value; an eye too far away for the bounds to mean anything).
    pub fn new(terrain: &'a Terrain, eye: [f64; 3], arith: Arith) -> Option<Wedges<'a>> {
        // Far more than the rounding of the walk's arithmetic (for `f32`, the rounding of the
        // ray and of the heights), relative to the size of every coordinate in play.
        let relative = match arith {
            Arith::F32 => 1e-5,
            Arith::F64 | Arith::Exact => 1e-9,
            Arith::Rational { .. } => return None,
        };
        let field = terrain.field();
        let (w, h) = (field.width() as f64 - 1.0, field.height() as f64 - 1.0);
        let (z_lo, z_hi) = terrain.z_range();
        let [ex, ey, ez] = eye;
        let size = ex.abs() + ey.abs() + ez.abs() + w + h + z_lo.abs() + z_hi.abs() + 1.0;
        let room = relative * size;
        if !room.is_finite() {
            return None;
        }
        // The map's nearest and farthest points from the eye's ground point.
        let near_x = (0.0 - ex).max(ex - w).max(0.0);
        let near_y = (0.0 - ey).max(ey - h).max(0.0);
        let nearest = near_x.hypot(near_y) - room;
        let far_x = ex.abs().max((ex - w).abs());
        let far_y = ey.abs().max((ey - h).abs());
        let farthest = far_x.hypot(far_y) + room;
        let wide = farthest * std::f64::consts::TAU / FEWEST_WEDGES as f64 > WIDEST_FAR_PIECE;
        let count = FEWEST_WEDGES << usize::from(wide);
        let ratio = 1.0 + RING_DEPTH * std::f64::consts::TAU / count as f64;
        let mut rings = vec![0.0, FIRST_RING.max(nearest)];
        while rings[rings.len() - 1] < farthest {
            let last = rings[rings.len() - 1];
            rings.push(last * ratio);
        }
        let profiles = Profiles {
            eye,
            arith,
            count,
            rings,
            room,
            nearest,
            profiles: (0..count).map(|_| OnceLock::new()).collect(),
        };
        Some(Wedges::kept(terrain, Arc::new(profiles)))
    }

    /// The wedges of `profiles` (made over `terrain`).
    pub fn kept(terrain: &'a Terrain, profiles: Arc<Profiles>) -> Wedges<'a> {
        Wedges { terrain, profiles }
    }

    /// What these wedges keep apart from the terrain.
    pub fn profiles(&self) -> &Arc<Profiles> {
        &self.profiles
    }

    /// How far the ray `origin + t * dir` travels clear of the surface, and the look-up as a
    /// query (miss: a certain miss, nothing to walk); `None` where the wedges cannot tell (a
    /// ray from elsewhere than the eye, a vertical ray, a ray that may touch the surface at
    /// once).
    pub fn clearance(&self, origin: [f64; 3], dir: [f64; 3]) -> (Option<Clearance>, HitMiss) {
        let mut asked = HitMiss::default();
        if origin != self.profiles.eye {
            return (None, asked);
        }
        let [dx, dy, dz] = dir;
        let across = (dx * dx + dy * dy).sqrt();
        let slope = dz / across;
        // Below the rounding of the slope's division and of `across` (a few ulps).
        let slope = slope - slope.abs() * 1e-12;
        // (A nearly vertical ray's squares may lose their precision below the normal range.)
        if !(slope.is_finite() && across > 1e-100 && across.is_finite()) {
            return (None, asked);
        }
        let profile = self.profile(wedge_of(dx, dy, self.profiles.count));
        let clear = profile.partition_point(|&bound| bound < slope);
        if !asked.record(clear < profile.len()) {
            let t = f64::INFINITY;
            return (Some(Clearance { t, level: 0 }), asked);
        }
        if clear == 0 {
            return (None, asked);
        }
        let t = self.profiles.rings[clear] / across * (1.0 - 1e-12);
        (Some(Clearance { t, level: 0 }), asked)
    }

    /// Wedge `w`'s profile, made the first time it is asked for.
    fn profile(&self, w: usize) -> &[f64] {
        self.profiles.profiles[w].get_or_init(|| self.build(w))
    }

    /// Wedge `w`'s profile: per ring, the largest bound of its pieces up to that ring.
    fn build(&self, w: usize) -> Box<[f64]> {
        let (a0, a1) = (
            4.0 * w as f64 / self.profiles.count as f64,
            4.0 * (w + 1) as f64 / self.profiles.count as f64,
        );
        let (u0, u1) = (ground_direction(a0), ground_direction(a1));
        let [ex, ey, ez] = self.profiles.eye;
        let mut running = f64::NEG_INFINITY;
        self.profiles
            .rings
            .windows(2)
            .map(|ring| {
                let (r0, r1) = (ring[0], ring[1]);
                if r1 <= self.profiles.nearest {
                    return running;
                }
                let grow = self.profiles.room + 1e-12 * r1;
                let corners = [(r0, u0), (r0, u1), (r1, u0), (r1, u1)];
                let (xs, ys) = corners.iter().fold(
                    (
                        (f64::INFINITY, f64::NEG_INFINITY),
                        (f64::INFINITY, f64::NEG_INFINITY),
                    ),
                    |(xs, ys), &(r, [ux, uy])| {
                        let (x, y) = (ex + r * ux, ey + r * uy);
                        ((xs.0.min(x), xs.1.max(x)), (ys.0.min(y), ys.1.max(y)))
                    },
                );
                let highest = highest_within(
                    self.terrain,
                    [xs.0 - grow, xs.1 + grow],
                    [ys.0 - grow, ys.1 + grow],
                    BLOCKS_ACROSS,
                );
                if let Some((highest, _)) = highest {
                    running = running.max(slope_bound(highest + self.profiles.room - ez, r0, r1));
                }
                running
            })
            .collect()
    }
}

/// An upper bound of `rise / ρ` over `ρ` in `[r0, r1]`, rounded up.
fn slope_bound(rise: f64, r0: f64, r1: f64) -> f64 {
    let bound = match rise >= 0.0 {
        true if r0 == 0.0 => return f64::INFINITY,
        true => rise / r0,
        false => rise / r1,
    };
    // (A division rounds by half an ulp at most.)
    bound + bound.abs() * 1e-15
}

/// The wedge of ground direction `(dx, dy)` (not both zero) among `count`, by its
/// pseudo-angle.
fn wedge_of(dx: f64, dy: f64, count: usize) -> usize {
    let w = (pseudo_angle(dx, dy) * (count as f64 / 4.0)) as usize;
    // (An angle just below 4 may round up to it: that wedge borders angle 0.)
    w.min(count - 1)
}

/// A monotone stand-in for the angle of `(x, y)` from the `x` axis, in `[0, 4]`: `y / (|x| +
/// |y|)` turned around the quadrants (0 along `+x`, 1 along `+y`, 2 along `-x`, 3 along `-y`).
fn pseudo_angle(x: f64, y: f64) -> f64 {
    let p = y / (x.abs() + y.abs());
    match (x >= 0.0, y >= 0.0) {
        (true, true) => p,
        (false, _) => 2.0 - p,
        (true, false) => 4.0 + p,
    }
}

/// The unit ground direction of pseudo-angle `a` (see [`pseudo_angle`]).
fn ground_direction(a: f64) -> [f64; 2] {
    let [x, y] = match a {
        a if a <= 1.0 => [1.0 - a, a],
        a if a <= 2.0 => [1.0 - a, 2.0 - a],
        a if a <= 3.0 => [a - 3.0, 2.0 - a],
        a => [a - 3.0, a - 4.0],
    };
    let length = x.hypot(y);
    [x / length, y / length]
}

/// The highest height under the cells meeting the box `[x0, x1] x [y0, y1]`, from at most
/// four blocks of one mipmap level, and that level; `None` if the box misses the grid.
pub fn highest_under(terrain: &Terrain, xs: [f64; 2], ys: [f64; 2]) -> Option<(f64, u32)> {
    highest_within(terrain, xs, ys, 2)
}

/// [`highest_under`] from at most `across` blocks each way.
fn highest_within(
    terrain: &Terrain,
    [x0, x1]: [f64; 2],
    [y0, y1]: [f64; 2],
    across: usize,
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
    // The finest level at which the cells span at most `across` blocks each way.
    let mut k = 0;
    let spans = |k: u32, lo: usize, hi: usize| (hi >> k) - (lo >> k) >= across;
    while spans(k, i0, i1) || spans(k, j0, j1) {
        k += 1;
    }
    let mut highest = 0;
    if k == 0 {
        // The cells' corners: each sample read once, not once for every cell it corners.
        let (samples, w) = (field.samples(), field.width());
        for y in j0..=j1 + 1 {
            let row = &samples[y * w + i0..=y * w + i1 + 1];
            highest = row.iter().fold(highest, |a, &b| a.max(b));
        }
        return Some((field.height_of(highest), 0));
    }
    for bj in (j0 >> k)..=(j1 >> k) {
        for bi in (i0 >> k)..=(i1 >> k) {
            highest = highest.max(terrain.block_max_sample(k, bi, bj));
        }
    }
    Some((field.height_of(highest), k))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pseudo_angles_turn_with_the_angle_and_invert() {
        let mut last = -1.0;
        for step in 0..720 {
            let angle = (step as f64 * 0.5).to_radians();
            let a = pseudo_angle(angle.cos(), angle.sin());
            assert!(a > last, "not monotone at {step}");
            last = a;
            let [x, y] = ground_direction(a);
            assert!((x - angle.cos()).abs() < 1e-12 && (y - angle.sin()).abs() < 1e-12);
        }
        for n in [FEWEST_WEDGES, 2 * FEWEST_WEDGES] {
            assert_eq!(wedge_of(1.0, -1e-300, n), n - 1);
            assert_eq!(wedge_of(1.0, 0.0, n), 0);
            assert_eq!(wedge_of(0.0, 1.0, n), n / 4);
        }
    }

    #[test]
    fn a_bound_is_above_every_slope_of_its_ring() {
        // Rising 2 over distances 4..8: at most 2/4; falling 2: at most -2/8.
        assert!(slope_bound(2.0, 4.0, 8.0) >= 0.5);
        assert!(slope_bound(-2.0, 4.0, 8.0) >= -0.25);
        assert_eq!(slope_bound(0.0, 0.0, 1.0), f64::INFINITY);
    }
}
