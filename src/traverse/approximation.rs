//! The `f64` ray near an exact one, and the room an `f64` walk along it leaves: what it skips,
//! the exact ray does not touch.

use super::counters::{Counters, HitMiss};
use super::frame::Frame;
use super::frame::Levels;
use super::near_ray::F64Ray;
use super::options::Query;
use super::search::moves_away;
use crate::arith::scalar::F64_TOLERANCE;
use crate::heightfield::Terrain;

/// An `f64` ray near an exact one, for an `f64` walk to clear the way for it.
pub struct Approximation {
    /// Its frame, covering the exact ray's segment.
    pub frame: Frame<f64>,
    pub oz: f64,
    pub dz: f64,
    /// How far the exact origin may be from this ray's, per axis (the direction is the same).
    pub radius: [f64; 3],
    /// The level to start at where it is known better than the default (a clearance's).
    pub level: Option<u32>,
}

impl Approximation {
    /// The `f64` ray `near` over `frame` (its segment, clipped), from the clearance start and
    /// level `start` if the exact walk has them.
    pub(super) fn along(frame: Frame<f64>, near: F64Ray, start: Option<(f64, u32)>) -> Self {
        let (origin, radius, dir) = near;
        Approximation {
            frame,
            oz: origin[2],
            dz: dir[2],
            radius,
            level: start.map(|(_, level)| level),
        }
    }

    /// The level its walk starts at, for a query of the given kind: a shadow ray starts on
    /// the surface, where every block around it fails its test.
    pub(super) fn first_level(&self, query: Query, top: u32) -> u32 {
        if query == Query::Shadow {
            0
        } else {
            Levels {
                top,
                start: self.level,
            }
            .first()
        }
    }
}

/// The farthest the exact path may be from an `f64` walk's, per axis, for the walk's bounds
/// to hold: a walk that tests a cell's neighbours for the exact path needs it within the
/// neighbours, less than a cell away.
pub(super) const MAX_POS: f64 = 0.25;

/// How far the exact ray may be from the points an `f64` walk along its [`Approximation`]
/// computes, worked out once per ray.
///
/// The exact ray is `o + t*d` with `d` an `f64` and `o` within `radius` (per axis) of the
/// `f64` origin. The walk skips blocks only where the ray stays above them with room for that
/// and for every rounding it made: the positions (within `pos` of the exact path), the `t` of
/// block faces (within `dt`) and the heights along the ray (within `z_err`). The surface rises
/// at most `max_slope` per unit of horizontal distance, so within `pos` of a block on each
/// axis (`pos` times the square root of two away) it is at most that much higher.
pub(super) struct Bounds {
    oz: f64,
    dz: f64,
    /// What the ray must clear a block's highest sample by.
    room: f64,
    /// How far, per axis, the exact path at a `t` may be from the point the walk computed for
    /// that `t`.
    pub pos: f64,
    /// How far a `t` the walk computed may be from the exact one.
    pub dt: f64,
    /// The `t` that moves the exact path off a face it may lie on as far as intervals tell.
    pub off_faces: f64,
    /// The exact ray was found under the surface (see [`Bounds::may_hit`]).
    under: bool,
}

impl Bounds {
    /// The bounds for a ray whose path crosses blocks (neither frame component is zero);
    /// `None` where they do not hold: the exact path may be more than [`MAX_POS`] from the
    /// walk's (an origin so far off, or known so roughly, that its rounding spans cells).
    pub fn new(ray: &Approximation, terrain: &Terrain) -> Option<Self> {
        let (f, oz, dz, radius) = (&ray.frame, ray.oz, ray.dz, ray.radius);
        let eps = f64::EPSILON;
        let t_max = f.t1.abs().max(f.t0.abs());
        let d_xy = f.du.abs().max(f.dv.abs());
        // Face crossings `(k - o) * (1/d)` carry three roundings; clip ends as many.
        let dt = 4.0 * eps * t_max + f64::MIN_POSITIVE;
        let coords = f.ou.abs().max(f.ov.abs()) + d_xy * t_max;
        // Two axes, each off by its own rounding and by the face crossing's `dt`; the tested
        // span lengthened by `dt` at both ends moves as far again. An exit within the `f64`
        // tolerance of a corner is snapped onto it (`exit_point`): as far off as that
        // tolerance. The exact origin is off by its radius.
        let snap = F64_TOLERANCE * t_max.max(1.0) * d_xy;
        let off = radius[0].max(radius[1]);
        let pos = 2.0 * (4.0 * eps * coords + d_xy * dt) + 2.0 * d_xy * dt + 2.0 * snap + off;
        // (`pos` bounds each axis: the exact path is up to `pos * SQRT_2` away.)
        let rise = terrain.max_slope() * (1.0 + 1e-9) * pos * std::f64::consts::SQRT_2;
        let z_err = 4.0 * eps * (oz.abs() + dz.abs() * t_max) + dz.abs() * dt + radius[2];
        // The block test's own operands, the ray's height and the block's, are rounded too:
        // bounded once here for the whole segment (a `t` the walk computed may lie a rounding
        // past its end) rather than at every test, where the sum would sit on the walk's
        // critical path.
        let (z_lo, z_hi) = terrain.z_range();
        let operands =
            4.0 * eps * ((oz.abs() + dz.abs() * t_max) * 1.01 + z_lo.abs().max(z_hi.abs()));
        // (NaN does not hold either.)
        if pos.partial_cmp(&MAX_POS).is_none_or(|o| o.is_gt()) {
            return None;
        }
        Some(Bounds {
            oz,
            dz,
            room: (z_err + rise + operands) * (1.0 + 1e-6),
            pos,
            dt,
            off_faces: 4.0 * (off + 4.0 * eps * coords) / f.du.abs().min(f.dv.abs()),
            under: false,
        })
    }

    /// Whether the exact ray may touch block `(bi, bj)` of level `k` (a cell at level 0) on
    /// the walk's path while the walk's `t` runs over `[t_lo, t_hi]`; counted as a cell or
    /// block query.
    ///
    /// As in the search's walk, an exact ray below a cell on the path is under the surface
    /// (the exact path is within `pos` of the cell, and the surface there no lower than its
    /// lowest sample by more than the room's `rise`), and from then on the block tests ask
    /// for the blocks' lowest samples. Either test is exact for any ray.
    #[inline(always)]
    pub fn may_hit(
        &mut self,
        terrain: &Terrain,
        k: u32,
        (bi, bj): (usize, usize),
        window: (f64, f64),
        counters: &mut Counters,
    ) -> bool {
        if k == 0 {
            let (below, may_hit) = self.cell_test(terrain, (bi, bj), window);
            self.under |= below;
            return counters.cell.record(may_hit);
        }
        let (field, mipmap) = (terrain.field(), terrain.mipmap());
        let may_hit = if self.under {
            self.goes_up_to(field.height_of(mipmap.lowest(k, bi, bj)), window)
        } else {
            self.comes_down_to(field.height_of(mipmap.highest(k, bi, bj)), window)
        };
        if counters.block.record(may_hit) {
            terrain.fetch_below(k, bi, bj);
        }
        may_hit
    }

    /// Whether the exact ray may touch cell `(i, j)`, off the walk's path but within reach of
    /// it, over the walk's `t` in `window`; counted as a cell query. (Off the path, a ray
    /// below the cell's samples need not be under the surface where it is.)
    pub fn cell_may_hit(
        &self,
        terrain: &Terrain,
        cell: (usize, usize),
        window: (f64, f64),
        counters: &mut Counters,
    ) -> bool {
        counters
            .cell
            .record(self.cell_test(terrain, cell, window).1)
    }

    /// A cell's test by both its samples: whether the exact ray stays below its lowest, and
    /// whether it may touch it (the surface within `pos` of the cell is nowhere lower than
    /// the lowest by more than the room's `rise`, nor higher than the highest).
    #[inline(always)]
    fn cell_test(
        &self,
        terrain: &Terrain,
        (i, j): (usize, usize),
        window: (f64, f64),
    ) -> (bool, bool) {
        let field = terrain.field();
        let (lowest, highest) = terrain.cell_sample_range(i, j);
        let below = !self.goes_up_to(field.height_of(lowest), window);
        (
            below,
            !below && self.comes_down_to(field.height_of(highest), window),
        )
    }

    /// Whether the exact ray may come down to `highest` while the walk's `t` runs over
    /// `[t_lo, t_hi]` and its path over cells whose highest height that is; counted in
    /// `counter`.
    #[inline(always)]
    pub fn may_reach(&self, highest: f64, window: (f64, f64), counter: &mut HitMiss) -> bool {
        counter.record(self.comes_down_to(highest, window))
    }

    /// Whether the exact ray may come down to `highest` while the walk's `t` runs over
    /// `[t_lo, t_hi]`.
    #[inline(always)]
    fn comes_down_to(&self, highest: f64, (t_lo, t_hi): (f64, f64)) -> bool {
        let t = if self.dz < 0.0 { t_hi } else { t_lo };
        let lowest = self.oz + self.dz * t;
        lowest - self.room <= highest
    }

    /// Whether the exact ray may go up to `lowest` while the walk's `t` runs over
    /// `[t_lo, t_hi]`.
    #[inline(always)]
    fn goes_up_to(&self, lowest: f64, (t_lo, t_hi): (f64, f64)) -> bool {
        let t = if self.dz < 0.0 { t_lo } else { t_hi };
        let highest = self.oz + self.dz * t;
        highest + self.room >= lowest
    }

    /// Whether the ray moves away from the samples its block test compares it with (see
    /// [`Follower::moves_away`](super::mipmap)).
    pub fn moves_away(&self) -> bool {
        moves_away(&self.dz, self.under)
    }
}
