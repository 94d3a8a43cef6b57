//! Traversals of a ray across the grid (runs, cell DDA), the arithmetics they are generic
//! over, and their query counters.

mod counters;
mod dda;
mod degenerate;
mod dyadic;
mod exact;
mod frame;
mod interval;
mod mipmap;
mod rational;
mod runs;
pub mod scalar;
mod search;

pub use counters::{Counters, HitMiss};
pub use exact::Exact;
pub use interval::{settled, Interval};
pub use rational::{with_bound, Rational, RationalEvents, DEFAULT_BOUND};
pub use scalar::Scalar;

use crate::geometry::{clip_to_box, gradient, Ray, RaySpace};
use crate::heightfield::Terrain;
use dyadic::Dyadic;
use frame::{Frame, Span};
use num_rational::BigRational;
pub use search::Found;
use search::{span_cells, Search};
use std::fmt;
use std::ops::ControlFlow;
use std::str::FromStr;
use std::time::Duration;

/// How the grid is walked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Row by row, run lengths from the intercept recurrence (Henning & Stephenson).
    Runs,
    /// Cell by cell (Amanatides & Woo).
    Dda,
    /// Block by block down a max-mipmap (Tevs et al.), runs at the bottom.
    Mipmap,
}

impl Method {
    /// Every method, the default (fastest) first.
    pub const ALL: [Method; 3] = [Method::Mipmap, Method::Runs, Method::Dda];
}

/// The arithmetic a traversal computes in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arith {
    F32,
    F64,
    /// Fractions with denominators at most `bound` (num-rational `Ratio<i64>` sized).
    Rational {
        bound: u32,
    },
    /// No rounding at all: the DESIGN 2 answer for the given `f64` inputs.
    Exact,
}

/// What a ray asks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Query {
    /// The least `t >= 0` at which the ray touches the surface.
    FirstHit,
    /// Whether the ray touches the surface at some `t > 0` (the start point does not count).
    Shadow,
}

/// How to walk, whatever the arithmetic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WalkOptions {
    pub method: Method,
    pub query: Query,
    /// List the cells the walk covered, in order.
    pub record_cells: bool,
    /// A triangle `(cell, k)` the ray starts on and leaves at once (it touches it only at
    /// `t = 0`), not to be tested: a shadow ray's own triangle.
    pub start_triangle: Option<((usize, usize), u8)>,
}

impl WalkOptions {
    /// A query of the given kind without cell recording.
    pub fn new(method: Method, query: Query) -> Self {
        WalkOptions {
            method,
            query,
            record_cells: false,
            start_triangle: None,
        }
    }
}

/// How to trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TraceOptions {
    pub method: Method,
    pub arith: Arith,
    pub query: Query,
    /// List the cells the walk covered, in order.
    pub record_cells: bool,
}

impl TraceOptions {
    /// The walk part of the options.
    pub fn walk(&self) -> WalkOptions {
        WalkOptions {
            method: self.method,
            query: self.query,
            record_cells: self.record_cells,
            start_triangle: None,
        }
    }

    /// A first-hit query without cell recording.
    pub fn new(method: Method, arith: Arith) -> Self {
        TraceOptions {
            method,
            arith,
            query: Query::FirstHit,
            record_cells: false,
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
    /// The cell `(i, j)` and triangle (0: `P00 P10 P11`, 1: `P00 P11 P01`) hit. Where the
    /// hit point is shared, the first in visiting order, `T0` before `T1`.
    pub cell: [usize; 2],
    pub triangle: u8,
}

/// The answer for one ray.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    pub hit: Option<Hit>,
    pub counters: Counters,
    /// Cells covered, in order (when asked for).
    pub cells: Vec<[usize; 2]>,
}

/// Traces one ray.
pub fn trace(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    match options.arith {
        Arith::F32 => trace_in::<f32>(terrain, ray, options),
        Arith::F64 => trace_in::<f64>(terrain, ray, options),
        Arith::Exact => trace_exact(terrain, ray, options),
        Arith::Rational { bound } => {
            let (mut trace, events) =
                with_bound(bound, || trace_in::<Rational>(terrain, ray, options));
            trace.counters.rational_rounded = events.rounded;
            trace.counters.rational_saturated = events.saturated;
            trace
        }
    }
}

/// Every cell the walk of `method` covers for the whole clipped ray, in order, with no culling
/// and no stop at a hit: in exact arithmetic, exactly the cells the projected segment touches.
pub fn covered_cells(
    terrain: &Terrain,
    ray: &Ray,
    method: Method,
    arith: Arith,
) -> Vec<[usize; 2]> {
    fn cover<S: Scalar>(terrain: &Terrain, ray: &Ray, method: Method) -> Vec<[usize; 2]> {
        let (o, d) = (ray.origin().map(S::from_f64), ray.dir().map(S::from_f64));
        let Some(frame) = clip(terrain, &o, &d, ray.dir()) else {
            return Vec::new();
        };
        let mut cells = Vec::new();
        walk(&frame, method, &mut |span: Span<S>| {
            cells.extend(span_cells(&frame, &span).map(|(i, j)| [i, j]));
            ControlFlow::Continue(())
        });
        cells
    }
    match arith {
        Arith::F32 => cover::<f32>(terrain, ray, method),
        Arith::F64 => cover::<f64>(terrain, ray, method),
        Arith::Exact => match settled(|| cover::<Interval>(terrain, ray, method)) {
            (cells, true) => cells,
            (_, false) => cover::<Exact>(terrain, ray, method),
        },
        Arith::Rational { bound } => {
            with_bound(bound, || cover::<Rational>(terrain, ray, method)).0
        }
    }
}

/// Builds what `method` needs beyond the terrain's shared data (the run walk's row and column
/// maxima are built on first use otherwise); returns the time the method's data took in all,
/// the terrain's shared part included, and its bytes beyond the samples.
pub fn prepare(terrain: &Terrain, method: Method) -> (Duration, usize) {
    match method {
        Method::Mipmap => (terrain.build_time(), terrain.accel_bytes()),
        Method::Runs => {
            let lines = terrain.lines();
            (terrain.build_time() + lines.build_time(), lines.bytes())
        }
        // The cell test reads the four corner samples: nothing to build.
        Method::Dda => (terrain.build_time(), 0),
    }
}

/// The ray clipped to the terrain's box, in the octant frame.
fn clip<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
) -> Option<Frame<S>> {
    let field = terrain.field();
    let (w, h) = (field.width(), field.height());
    let (z_lo, z_hi) = terrain.z_range();
    let lo = [S::zero(), S::zero(), S::from_f64(z_lo)];
    let hi = [
        S::from_i64(w as i64 - 1),
        S::from_i64(h as i64 - 1),
        S::from_f64(z_hi),
    ];
    let mut clipped = clip_to_box(o, d, &lo, &hi)?;
    // Floats lengthen the segment by their own rounding, so that the last cells before a box
    // face (flat ground at the lowest height) are not cut off.
    clipped.t1 = clipped.t1.past_rounding();
    Some(Frame::new(o, d, dir_f64, clipped, (w, h)))
}

fn walk<S: Scalar>(
    frame: &Frame<S>,
    method: Method,
    visit: &mut impl FnMut(Span<S>) -> ControlFlow<()>,
) {
    // Either walk ends by itself or because `visit` broke; both are fine here.
    let _ = match method {
        // Without culling the hierarchy has nothing to skip: its cells are the run walk's.
        Method::Runs | Method::Mipmap => runs::walk(frame, visit),
        Method::Dda => dda::walk(frame, visit),
    };
}

/// Exact arithmetic: intervals first; only a ray with a decision they cannot settle is traced
/// again in rationals. Settled decisions are the exact ones, so only the hit's `t` remains to
/// be computed exactly, on the one triangle hit.
fn trace_exact(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    let (mut fast, is_settled) = settled(|| trace_in::<Interval>(terrain, ray, options));
    if !is_settled {
        return trace_in::<Exact>(terrain, ray, options);
    }
    let Some(hit) = fast.hit.take() else {
        return fast;
    };
    match exact_t(terrain, ray, hit.cell, hit.triangle) {
        Some((above, closing)) => {
            // The point `o + d * above/closing`, each coordinate one exact fraction.
            let point = [0, 1, 2].map(|k| {
                let (o, d) = (ray.origin()[k], ray.dir()[k]);
                let numerator =
                    Dyadic::from_f64(o) * closing.clone() + Dyadic::from_f64(d) * above.clone();
                numerator.over_to_f64(&closing)
            });
            let t = above.over(&closing);
            fast.hit = Some(Hit {
                t: num_traits::ToPrimitive::to_f64(&t).unwrap_or(f64::NAN),
                point,
                t_exact: Some(t),
                ..hit
            });
            fast
        }
        // The ray lies in the triangle's plane (or, impossibly, misses it): rationals decide.
        None => trace_in::<Exact>(terrain, ray, options),
    }
}

/// Where the ray meets the plane of triangle `k` of `cell`, exactly, as `t = above / closing`;
/// `None` if it runs parallel.
fn exact_t(terrain: &Terrain, ray: &Ray, [i, j]: [usize; 2], k: u8) -> Option<(Dyadic, Dyadic)> {
    let heights = terrain.corner_heights(i, j).map(Dyadic::from_f64);
    let z00 = heights[0].clone();
    let (gx, gy) = gradient(k, heights);
    let [ox, oy, oz] = ray.origin().map(Dyadic::from_f64);
    let [dx, dy, dz] = ray.dir().map(Dyadic::from_f64);
    let (x0, y0) = (Dyadic::from_i64(i as i64), Dyadic::from_i64(j as i64));
    // oz + t*dz = z00 + gx*(ox + t*dx - i) + gy*(oy + t*dy - j), solved for t.
    let above = oz - z00 - gx.clone() * (ox - x0) - gy.clone() * (oy - y0);
    let closing = gx * dx + gy * dy - dz;
    (!closing.is_zero()).then_some((above, closing))
}

fn trace_in<S: Scalar>(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Trace {
    let (o, d) = (ray.origin().map(S::from_f64), ray.dir().map(S::from_f64));
    let answer = trace_scalar(terrain, &o, &d, ray.dir(), options.walk());
    let hit = answer.hit.map(|found| {
        let point = found.point(&o, &d).map(|c| c.to_f64());
        Hit {
            t: found.t.to_f64(),
            t_exact: found.t.to_exact(),
            point,
            cell: [found.cell.0, found.cell.1],
            triangle: found.triangle,
        }
    });
    Trace {
        hit,
        counters: answer.counters,
        cells: answer.cells,
    }
}

/// The answer for one ray, in the arithmetic it was traced in.
#[derive(Clone, Debug)]
pub struct ScalarTrace<S> {
    pub hit: Option<Found<S>>,
    pub counters: Counters,
    pub cells: Vec<[usize; 2]>,
}

/// Traces a ray given in the traversal's own arithmetic (for rays that start where another
/// ray hit: exact mode keeps the exact point). `dir_f64` is the direction as given, which
/// picks the octant and axes identically in every arithmetic. For [`Rational`] the caller
/// sets the bound, see [`with_bound`].
pub fn trace_scalar<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    let mut counters = Counters::default();
    let frame = clip(terrain, o, d, dir_f64);
    let Some(frame) = frame else {
        counters.bbox.record(false);
        return ScalarTrace {
            hit: None,
            counters,
            cells: Vec::new(),
        };
    };
    counters.bbox.record(true);
    // (A walk asked to list its cells walks them all.) A shadow ray starts on the surface.
    let on_surface = walk_options.query == Query::Shadow;
    let (frame, near_terrain) = match walk_options.method {
        Method::Mipmap if !walk_options.record_cells => {
            match cleared(terrain, o, d, dir_f64, frame, &mut counters) {
                Some((frame, cleared)) => (frame, cleared || on_surface),
                None => {
                    return ScalarTrace {
                        hit: None,
                        counters,
                        cells: Vec::new(),
                    }
                }
            }
        }
        _ => (frame, on_surface),
    };
    let mut search = Search {
        terrain,
        frame: &frame,
        ray: RaySpace::new(o.clone(), d.clone(), dir_f64),
        oz: o[2].clone(),
        dz: d[2].clone(),
        query: walk_options.query,
        run_test: walk_options.method == Method::Runs,
        counters,
        found: None,
        cells: walk_options.record_cells.then(Vec::new),
        start_triangle: walk_options.start_triangle,
        slack: search::slack(&o[2], &d[2], &frame.t1),
    };
    if walk_options.method == Method::Mipmap {
        // Ends by itself or at the answer; both are fine here.
        let _ = mipmap::walk(&frame, &mut search, near_terrain);
    } else {
        walk(&frame, walk_options.method, &mut |span| search.span(span));
    }
    ScalarTrace {
        hit: search.found,
        counters: search.counters,
        cells: search.cells.unwrap_or_default(),
    }
}

/// In an arithmetic without rounding, an `f64` walk first clears the way for the mipmap (see
/// [`mipmap::clear_way`]) where the ray is exactly an `f64` ray: the frame from just before
/// the first cell that may be hit, and whether the walk ran (then that cell is next to the
/// frame's start), or `None` when nothing can be hit at all.
fn cleared<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    frame: Frame<S>,
    counters: &mut Counters,
) -> Option<(Frame<S>, bool)> {
    let exactly = |v: &[S; 3]| -> Option<[f64; 3]> {
        Some([v[0].exact_f64()?, v[1].exact_f64()?, v[2].exact_f64()?])
    };
    let (Some(of), Some(df)) = (exactly(o), exactly(d)) else {
        return Some((frame, false));
    };
    let Some(fast) = clip(terrain, &of, &df, dir_f64) else {
        return Some((frame, false));
    };
    match mipmap::clear_way(&fast, terrain, (of[2], df[2]), counters) {
        mipmap::Cleared::All => None,
        mipmap::Cleared::Until(t) => {
            // Start a little before that cell, inside the cleared block: on the face the
            // `f64` walk found, intervals could not tell the two sides apart. (The exact
            // segment starts within rounding of the `f64` one's start.)
            let margin = 1e-9 * (t.abs() + 1.0);
            let start = t - margin;
            if start > fast.t0 + margin {
                Some((frame.starting_at(S::from_f64(start)), true))
            } else {
                Some((frame, true))
            }
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Method::Runs => "runs",
            Method::Dda => "dda",
            Method::Mipmap => "mipmap",
        })
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "runs" => Ok(Method::Runs),
            "dda" => Ok(Method::Dda),
            "mipmap" | "auto" => Ok(Method::Mipmap),
            _ => Err(format!(
                "unknown method '{s}': use mipmap, runs, dda or auto"
            )),
        }
    }
}

impl fmt::Display for Arith {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Arith::F32 => f.write_str("f32"),
            Arith::F64 => f.write_str("f64"),
            Arith::Rational { bound } => write!(f, "rational:{bound}"),
            Arith::Exact => f.write_str("exact"),
        }
    }
}

impl FromStr for Arith {
    type Err = String;
    /// `f32`, `f64`, `exact`, `rational` (bound 2^16) or `rational:BOUND`.
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "f32" => Ok(Arith::F32),
            "f64" => Ok(Arith::F64),
            "exact" => Ok(Arith::Exact),
            "rational" => Ok(Arith::Rational {
                bound: DEFAULT_BOUND,
            }),
            _ => {
                let bound = s
                    .strip_prefix("rational:")
                    .and_then(|b| b.parse::<u32>().ok())
                    .filter(|&b| (1..=1 << 30).contains(&b));
                bound.map(|bound| Arith::Rational { bound }).ok_or(format!(
                    "unknown arithmetic '{s}': use f32, f64, rational, rational:BOUND (1..=2^30) or exact"
                ))
            }
        }
    }
}
