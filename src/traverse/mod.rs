// (The summary line of this module's docs is its `pub mod` line in lib.rs; the empty line
// below starts the rest as a paragraph of its own.)
//!
//! Four methods walk the grid ([`Method`](crate::traverse::Method)): the min-max mipmap's
//! blocks, the hierarchical run walk, the run walk and the cell DDA. Each is one
//! implementation, generic over the arithmetics of [`Scalar`](crate::arith::Scalar)
//! ([`Arith`](crate::arith::Arith)), and counts its queries
//! ([`Counters`](crate::traverse::Counters)).
//!
//! Two questions, one way in each: [`trace`](crate::traverse::trace) (the first hit) and
//! [`occluded`](crate::traverse::occluded) (any hit after the start; from a hit on the surface,
//! [`occluded_from_hit`](crate::traverse::occluded_from_hit)). Both pick the arithmetic once,
//! through [`run`](crate::arith::run), and answer with a
//! [`Tracer`](crate::traverse::Tracer), the same generic inside the renderer runs per pixel.

mod answer;
mod approximation;
mod ask;
mod cell_log;
mod certified;
mod counters;
mod cover;
mod dda;
mod degenerate;
mod departure;
mod engine;
mod exact_mode;
mod exact_plane;
mod exact_start;
mod far;
mod frame;
mod mipmap;
mod near_ray;
mod options;
mod packet;
mod runs;
mod search;
mod segment;
mod short_walk;
mod span_cells;
mod surface;
mod tracer;
mod walks;
mod wedges;

pub use answer::ScalarTrace;
pub use ask::{occluded, trace, trace_packets};
pub use counters::{Counters, HitMiss};
pub use cover::covered_cells;
pub use departure::{Departure, Start};
pub use exact_plane::{crosses_plane, plane_t_exact};
pub use exact_start::PlanePoint;
pub use options::{Hit, Method, Trace, TraceOptions, UnknownMethod};
pub use packet::{clear_packet, clear_packet_on, PacketClearance, SimdPath, LANES, SIMD_VARIABLE};
pub use search::Found;
pub use tracer::{occluded_from_hit, Occlusion, Tracer};
pub use wedges::{highest_under, Clearance, Profiles, Wedges};

use crate::heightfield::Terrain;
use std::time::Duration;

/// Builds what `method` needs beyond the terrain's shared data (the run walk's row and column
/// maxima are built on first use otherwise); returns the time the method's data took in all,
/// the terrain's shared part included, and its bytes beyond the samples.
pub fn prepare(terrain: &Terrain, method: Method) -> (Duration, usize) {
    match method {
        Method::Mipmap | Method::HierarchicalRuns => (terrain.build_time(), terrain.accel_bytes()),
        Method::Runs => {
            let lines = terrain.lines();
            (terrain.build_time() + lines.build_time(), lines.bytes())
        }
        // The cell test reads the four corner samples: nothing to build.
        Method::Dda => (terrain.build_time(), 0),
    }
}
