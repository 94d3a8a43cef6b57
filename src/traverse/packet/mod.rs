//! Packets: up to [`LANES`] rays of one octant (a few neighbouring camera rays) walked down the
//! min-max mipmap together, each node tested for all of them at once in SIMD lanes, until each
//! ray reaches the first cell it may touch; its own walk starts there (see
//! [`Clearance`]), as it starts from its wedge's clearance ([`Wedges`](super::Wedges)).
//!
//! The walk is depth first, children front to back: in the octant frame every ray goes
//! towards +u and +v, so of a block's four children the near one comes first and the far one
//! last for every ray, and the two others are both touched only where a ray passes through
//! their shared corner. A ray leaves the packet at a cell that may be hit; when at most
//! [`HANDOFF`] of several remain, they leave it too, as the shared tests no longer pay.
//!
//! Why it is exact: a ray's part over a block lies in the block's `t` range, computed with the
//! block's faces moved out by [`Packet::room`], far more than the rounding of the range and of
//! the heights along it (and the ray's height is lowered by as much). A ray that clears the
//! block's highest sample there touches nothing in the block. A ray's start is the least `t`
//! of its parts not yet proven clear: the cell it may hit, and the blocks still waiting on the
//! walk's stack that it may touch (a ray passing near a corner is in more blocks than its
//! path crosses, whose order cannot be trusted). Before that `t` it touches nothing, so its own
//! walk from there finds the answer the walk from its start finds, cell, triangle and `t`.

mod dispatch;
mod lanes;
mod walk;
#[cfg(target_arch = "x86_64")]
mod x86;

pub use crate::arith::{SimdPath, SIMD_VARIABLE};

use super::counters::HitMiss;
use super::Clearance;
use crate::geometry::Ray;
use crate::heightfield::Terrain;
use lanes::Packet;
pub use lanes::LANES;

/// Rays left in a packet when all of them leave it for their own walks.
const HANDOFF: u32 = 1;

/// Where each ray of a packet starts its own walk, and the packet's node tests.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PacketClearance {
    /// Per ray, in the order given: nothing touches it before this `t`, and its walk starts
    /// at this level. A ray the packet could not take keeps the clearance it came with.
    pub lanes: [Option<Clearance>; LANES],
    /// The packet's node tests (hit: some ray may touch the block).
    pub tests: HitMiss,
}

/// Walks `rays` (at most [`LANES`]; more are left out) together down the mipmap, from where
/// `from` (a clearance true of them all) ends. Rays in another octant frame than the
/// first ray that can walk blocks, and rays with nothing to walk, keep `from`.
pub fn clear_packet(terrain: &Terrain, rays: &[Ray], from: Option<Clearance>) -> PacketClearance {
    clear_packet_on(SimdPath::active(), terrain, rays, from)
}

/// [`clear_packet`] on the SIMD path `path` (or the best below it the processor has): the
/// same answers on every path.
pub fn clear_packet_on(
    path: SimdPath,
    terrain: &Terrain,
    rays: &[Ray],
    from: Option<Clearance>,
) -> PacketClearance {
    let mut out = PacketClearance {
        lanes: [from; LANES],
        tests: HitMiss::default(),
    };
    let from_t = from.map_or(0.0, |c| c.t);
    // (A clearance of the whole way leaves nothing to walk.)
    if from_t.is_nan() || from_t == f64::INFINITY {
        return out;
    }
    let rays = &rays[..rays.len().min(LANES)];
    if let Some(packet) = Packet::new(terrain, rays, from_t) {
        dispatch::walk(path.min(SimdPath::detected()), &packet, &mut out);
    }
    out
}
