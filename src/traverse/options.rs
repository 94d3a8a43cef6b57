//! What a caller asks of a traversal: the method, the query, the options of a walk and of a
//! trace, and the answer they get back.

use super::{Clearance, Counters, PlanePoint};
use crate::arith::Arith;
use crate::geometry::{Base, Face};
use num_rational::BigRational;
use std::fmt;
use std::str::FromStr;

/// How the grid is walked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Row by row, run lengths from the intercept recurrence (Henning & Stephenson).
    Runs,
    /// Cell by cell (Amanatides & Woo).
    Dda,
    /// Block by block down a max-mipmap (Tevs et al.), runs at the bottom.
    Mipmap,
    /// Run by run at every level of the mipmap: a run of coarse blocks is a run of runs,
    /// skipped whole or walked again a level down.
    HierarchicalRuns,
}

impl Method {
    /// Every method, the default (fastest) first.
    pub const ALL: [Method; 4] = [
        Method::Mipmap,
        Method::HierarchicalRuns,
        Method::Runs,
        Method::Dda,
    ];

    /// Whether the method walks the mipmap's levels (and so starts from a clearance, see
    /// [`Tracer::trace`](super::Tracer::trace)).
    pub fn is_hierarchical(self) -> bool {
        matches!(self, Method::Mipmap | Method::HierarchicalRuns)
    }
}

/// What a ray asks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Query {
    /// The least `t >= 0` at which the ray touches the surface.
    FirstHit,
    /// Whether the ray touches the surface at some `t > 0` (the start point does not count).
    Shadow,
}

/// How to walk, whatever the arithmetic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct WalkOptions {
    /// How the grid is walked.
    pub method: Method,
    /// What the ray asks.
    pub query: Query,
    /// List the cells the walk reaches (see [`TraceOptions::record_cells`]).
    pub record_cells: bool,
    /// A triangle `(cell, k)` the ray starts on and leaves at once (it touches it only at
    /// `t = 0`), not to be tested: a shadow ray's own triangle.
    pub start_triangle: Option<((usize, usize), u8)>,
    /// The ray touches nothing before this clearance's `t` (a camera ray's, from its
    /// [`Wedges`](super::Wedges)): the hierarchical walk starts there, at its level.
    pub clearance: Option<Clearance>,
    /// For a shadow ray in intervals: its start, exactly (the hit point it starts at). A
    /// triangle test the intervals cannot settle is then decided exactly on its own.
    pub exact_start: Option<PlanePoint>,
    /// The walk ends at this `t` (an occlusion ray asking only so far, see
    /// [`Tracer::within`](super::Tracer::within)).
    pub reach: Option<f64>,
    /// Walk the first cells one by one from a clearance (see
    /// [`near_walk`](super::mipmap::near::near_walk)); the answers are the same either way.
    pub near: bool,
    /// The base under the terrain, part of the surface where given.
    pub base: Option<Base>,
}

impl WalkOptions {
    /// A query of the given kind without cell recording.
    pub(crate) fn new(method: Method, query: Query) -> Self {
        WalkOptions {
            method,
            query,
            record_cells: false,
            start_triangle: None,
            clearance: None,
            exact_start: None,
            reach: None,
            near: true,
            base: None,
        }
    }
}

/// How to trace ([`trace`](super::trace), [`occluded`](super::occluded)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TraceOptions {
    /// How the grid is walked.
    pub method: Method,
    /// The arithmetic traced in.
    pub arith: Arith,
    /// List the cells the walk reaches at the cell level, in order ([`Trace::cells`]): the
    /// walk, its answer and its counters are the same either way.
    pub record_cells: bool,
    /// Walk rays in packets where they can ([`trace_packets`](super::trace_packets)): the
    /// answers are the same, the work is shared.
    pub packets: bool,
    /// The base under the terrain (a floor, and walls if it has them), part of the surface
    /// where given; none by default.
    pub base: Option<Base>,
}

impl TraceOptions {
    /// Options without cell recording, one ray at a time.
    pub fn new(method: Method, arith: Arith) -> Self {
        TraceOptions {
            method,
            arith,
            record_cells: false,
            packets: false,
            base: None,
        }
    }
}

/// Where a ray hit.
#[derive(Clone, Debug, PartialEq)]
pub struct Hit {
    /// The ray parameter (nearest `f64` of the exact value in exact mode).
    pub t: f64,
    /// The exact parameter, in exact mode.
    pub t_exact: Option<BigRational>,
    /// `o + t*d`.
    pub point: [f64; 3],
    /// The cell `(i, j)` hit. Where the hit point is shared, the first in visiting order.
    pub cell: [usize; 2],
    /// The triangle hit (0: `P00 P10 P11`, 1: `P00 P11 P01`); `T0` where both share the
    /// hit point, and on the base.
    pub triangle: u8,
    /// What was hit: the terrain, or a wall or the floor of the base (then `cell` is the cell
    /// the point lies over, or beside on a wall).
    pub face: Face,
}

/// The answer for one ray.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    /// The first hit (or, for a shadow query, a hit after the start), if any.
    pub hit: Option<Hit>,
    /// The queries the ray made.
    pub counters: Counters,
    /// The cells the walk reached at the cell level, in order (when asked for): along the
    /// path, skipping the blocks a hierarchy skips; where an `f64` walk certifies an exact
    /// answer, the cells along its own path and the neighbours it tested for the exact path,
    /// each within rounding of the path.
    pub cells: Vec<[usize; 2]>,
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Method::Runs => "runs",
            Method::Dda => "dda",
            Method::Mipmap => "mipmap",
            Method::HierarchicalRuns => "hruns",
        })
    }
}

/// A name that is not a traversal method's.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown method '{0}': use mipmap, hruns, runs, dda or auto")]
pub struct UnknownMethod(pub String);

impl FromStr for Method {
    type Err = UnknownMethod;
    fn from_str(s: &str) -> Result<Self, UnknownMethod> {
        match s {
            "runs" => Ok(Method::Runs),
            "dda" => Ok(Method::Dda),
            "mipmap" | "auto" => Ok(Method::Mipmap),
            "hruns" => Ok(Method::HierarchicalRuns),
            _ => Err(UnknownMethod(s.to_owned())),
        }
    }
}
