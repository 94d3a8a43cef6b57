//! A packet's rays in lanes, and the node test made for all of them at once.

use crate::arith::{larger, smaller};
use crate::geometry::Ray;
use crate::heightfield::Terrain;
use crate::traverse::frame::{clip, Frame};
use crate::traverse::mipmap::has_blocks;

/// The most rays a packet holds (one AVX-512 register of `f64`).
pub const LANES: usize = 8;

/// Room, relative to the largest coordinate involved, left around every block face and every
/// height: far more than the few roundings of `f64` each computation makes.
pub(super) const ROOM: f64 = 1e-9;

/// The rays of a packet in the octant frame, one lane each. A lane without a ray has an empty
/// segment (`t_lo` infinite, `t_hi` minus infinite), so it touches no block.
#[derive(Clone, Debug)]
pub(super) struct Lanes {
    pub ou: [f64; LANES],
    pub ov: [f64; LANES],
    pub inv_du: [f64; LANES],
    pub inv_dv: [f64; LANES],
    pub oz: [f64; LANES],
    pub dz: [f64; LANES],
    /// The part of the ray left to walk: its clipped segment from where its clearance ends.
    pub t_lo: [f64; LANES],
    pub t_hi: [f64; LANES],
}

/// Rays of one octant frame walked together.
pub(super) struct Packet<'a> {
    pub terrain: &'a Terrain,
    /// The first ray's frame: the octant, and the valid frame cells, the same for every lane.
    pub frame: Frame<f64>,
    pub lanes: Lanes,
    /// The lanes that hold a ray, one bit each.
    pub members: u32,
    /// How far block faces are moved out (see [`ROOM`]).
    pub room: f64,
}

/// One node test for every lane: the lanes whose path crosses the block, those of them that
/// may touch it, and where each enters it.
pub(super) struct NodeTest {
    pub touch: u32,
    pub may: u32,
    pub enter: [f64; LANES],
}

impl<'a> Packet<'a> {
    /// The rays that can walk blocks in the octant frame of the first that can, their
    /// segments from `from_t` on; `None` if no ray can.
    pub fn new(terrain: &'a Terrain, rays: &[Ray], from_t: f64) -> Option<Self> {
        let mut lanes = Lanes {
            t_lo: [f64::INFINITY; LANES],
            t_hi: [f64::NEG_INFINITY; LANES],
            ..Lanes::zero()
        };
        let (mut frame, mut members, mut size) = (None::<Frame<f64>>, 0, 0.0f64);
        for (l, ray) in rays.iter().enumerate() {
            let (o, d) = (ray.origin(), ray.dir());
            // (A direction so near a grid axis that its reciprocal overflows is left alone.)
            let walkable = |f: &Frame<f64>| has_blocks(f) && f.inv_dv.is_finite();
            let Some(f) = clip(terrain, &o, &d, d).filter(walkable) else {
                continue;
            };
            let octant = |f: &Frame<f64>| (f.swap, f.flip_u, f.flip_v);
            if frame
                .as_ref()
                .is_some_and(|first| octant(first) != octant(&f))
            {
                continue;
            }
            lanes.ou[l] = f.ou;
            lanes.ov[l] = f.ov;
            lanes.inv_du[l] = f.inv_du;
            lanes.inv_dv[l] = f.inv_dv;
            lanes.oz[l] = o[2];
            lanes.dz[l] = d[2];
            // (The clipped start is rounded: moved down by far more.)
            lanes.t_lo[l] = (f.t0 - ROOM * f.t0.abs()).max(from_t);
            lanes.t_hi[l] = f.t1;
            members |= 1 << l;
            size = o.iter().fold(size, |m, x| m.max(x.abs()));
            frame.get_or_insert(f);
        }
        let field = terrain.field();
        let (z_lo, z_hi) = terrain.z_range();
        let extent = (field.width() + field.height()) as f64 + z_lo.abs() + z_hi.abs();
        Some(Packet {
            terrain,
            frame: frame?,
            lanes,
            members,
            room: ROOM * (size + extent + 1.0),
        })
    }
}

impl Lanes {
    fn zero() -> Self {
        let zero = [0.0; LANES];
        Lanes {
            ou: zero,
            ov: zero,
            inv_du: zero,
            inv_dv: zero,
            oz: zero,
            dz: zero,
            t_lo: zero,
            t_hi: zero,
        }
    }

    /// The node test of the block `[u0, u1] x [v0, v1]` (frame coordinates) whose highest
    /// height is `highest`, its faces moved out by `room`. Every lane takes the same
    /// branch-free steps, which the compiler makes SIMD over the lanes; the explicit SIMD
    /// kernels ([`super::x86`]) take them in the same order.
    #[inline(always)]
    pub fn test(&self, room: f64, [u0, u1, v0, v1]: [f64; 4], highest: f64) -> NodeTest {
        let (mut touch, mut may, mut enter) = ([false; LANES], [false; LANES], [0.0; LANES]);
        for l in 0..LANES {
            let (t_enter, t_exit) = self.crossing(l, room, [u0, u1, v0, v1]);
            // The ray's lowest height over the block: where it enters if it climbs, where it
            // leaves if it descends; lowered by far more than its rounding.
            let t = if self.dz[l] < 0.0 { t_exit } else { t_enter };
            let (oz, dz_t) = (self.oz[l], self.dz[l] * t);
            let lowest = oz + dz_t - ROOM * (oz.abs() + dz_t.abs());
            touch[l] = t_enter <= t_exit;
            may[l] = touch[l] & (lowest <= highest);
            enter[l] = t_enter;
        }
        NodeTest {
            touch: bits(&touch),
            may: bits(&may),
            enter,
        }
    }

    /// Where lane `l` enters and leaves the block `[u0, u1] x [v0, v1]` grown by `room` on
    /// every side, within its segment (the exit before the entry where it misses).
    #[inline(always)]
    fn crossing(&self, l: usize, room: f64, [u0, u1, v0, v1]: [f64; 4]) -> (f64, f64) {
        let (ou, ov, iu, iv) = (self.ou[l], self.ov[l], self.inv_du[l], self.inv_dv[l]);
        let (tu0, tu1) = ((u0 - room - ou) * iu, (u1 + room - ou) * iu);
        let (tv0, tv1) = ((v0 - room - ov) * iv, (v1 + room - ov) * iv);
        let t_enter = larger(larger(tu0, tv0), self.t_lo[l]);
        let t_exit = smaller(smaller(tu1, tv1), self.t_hi[l]);
        (t_enter, t_exit)
    }
}

/// One bit per lane.
#[inline(always)]
fn bits(lanes: &[bool; LANES]) -> u32 {
    lanes
        .iter()
        .enumerate()
        .fold(0, |m, (l, &b)| m | (u32::from(b) << l))
}

/// A node test for all lanes at once ([`Lanes::test`], in some instruction set).
pub(super) trait Kernel {
    fn test(lanes: &Lanes, room: f64, faces: [f64; 4], highest: f64) -> NodeTest;
}
