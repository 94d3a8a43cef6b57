//! The base under a terrain: a floor below its lowest sample and, optionally, four walls from
//! the map's edge down to it.
//!
//! - The *floor* is the closed rectangle `z = f` over the footprint `[0, W-1] x [0, H-1]`.
//! - A *wall* stands on each edge line of the footprint: over each edge segment `[k, k+1]`
//!   whose edge cell has triangles, the closed trapezoid between `z = f` and the segment of
//!   the terrain's boundary edge (so a wall never rises above the terrain it meets).
//!
//! Both are tested once per ray, beside the walk, in the walk's arithmetic: a crossing of the
//! face's plane checked against the face's half-planes, or, for a ray lying in the plane, the
//! half-planes clipping the ray (where it first touches the face). Every value is a sum of
//! products of the ray's components, sample heights and grid coordinates, so rationals are
//! exact and intervals flag what they cannot settle.

use super::base_screen::Screen;
use crate::arith::Scalar;
use crate::heightfield::Terrain;

/// The side of the footprint a wall stands on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// On `x = 0`.
    West,
    /// On `x = W-1`.
    East,
    /// On `y = 0`.
    South,
    /// On `y = H-1`.
    North,
}

impl Side {
    /// Every side, in the order ties between walls go.
    pub const ALL: [Side; 4] = [Side::West, Side::East, Side::South, Side::North];

    /// The axis the wall faces along (0: x, 1: y).
    fn axis(self) -> usize {
        match self {
            Side::West | Side::East => 0,
            Side::South | Side::North => 1,
        }
    }

    /// The unit normal facing out of the footprint.
    pub fn normal(self) -> [f64; 3] {
        match self {
            Side::West => [-1.0, 0.0, 0.0],
            Side::East => [1.0, 0.0, 0.0],
            Side::South => [0.0, -1.0, 0.0],
            Side::North => [0.0, 1.0, 0.0],
        }
    }

    /// The name a user reads.
    pub fn name(self) -> &'static str {
        match self {
            Side::West => "west",
            Side::East => "east",
            Side::South => "south",
            Side::North => "north",
        }
    }
}

/// What a ray hit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Face {
    /// A terrain triangle.
    #[default]
    Terrain,
    /// A wall of the base.
    Wall(Side),
    /// The floor of the base.
    Floor,
}

impl Face {
    /// The name a user reads.
    pub fn name(self) -> &'static str {
        match self {
            Face::Terrain => "terrain",
            Face::Wall(_) => "wall",
            Face::Floor => "floor",
        }
    }
}

/// A floor at a height below the lowest sample, with or without walls.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Base {
    floor: f64,
    walls: bool,
    /// The highest sample on each side's edge line, in [`Side::ALL`]'s order: no wall rises
    /// above it.
    tops: [f64; 4],
}

// (The floor is finite: `Base::under` checks it.)
impl Eq for Base {}

impl Base {
    /// How far below the lowest sample the floor lies by default: 5% of the relief, at least
    /// one height unit.
    pub fn default_depth(terrain: &Terrain) -> f64 {
        let (lo, hi) = terrain.z_range();
        (0.05 * (hi - lo)).max(1.0)
    }

    /// A base `depth` below the lowest sample of `terrain`, with walls if `walls`; `None`
    /// unless the depth is finite and the floor lies strictly below every sample.
    pub fn under(terrain: &Terrain, depth: f64, walls: bool) -> Option<Base> {
        let (lo, _) = terrain.z_range();
        let floor = lo - depth;
        let field = terrain.field();
        let tops = Side::ALL.map(|side| {
            let (at, length) = wall_line(terrain, side);
            let z = |k| match side.axis() {
                0 => field.z(at, k),
                _ => field.z(k, at),
            };
            (0..=length).map(z).fold(f64::NEG_INFINITY, f64::max)
        });
        (depth.is_finite() && floor.is_finite() && floor < lo).then_some(Base {
            floor,
            walls,
            tops,
        })
    }

    /// The floor's height.
    pub fn floor(&self) -> f64 {
        self.floor
    }

    /// Whether the base has walls.
    pub fn walls(&self) -> bool {
        self.walls
    }
}

/// Where a ray first touches the base.
#[derive(Clone, Debug, PartialEq)]
pub struct BaseHit<S> {
    /// The ray parameter (for a ray lying in a face's plane from its start, the start's).
    pub t: S,
    /// The face touched.
    pub face: Face,
}

/// A closed half-space `a . p + b >= 0` of points `p`.
struct HalfSpace<S> {
    a: [S; 3],
    b: S,
}

impl<S: Scalar> HalfSpace<S> {
    /// `sign * p[axis] + b >= 0`.
    fn on_axis(axis: usize, sign: i64, b: S) -> Self {
        let mut a = [S::zero(), S::zero(), S::zero()];
        a[axis] = S::from_i64(sign);
        HalfSpace { a, b }
    }

    /// `a . v`.
    fn linear(&self, v: &[S; 3]) -> S {
        let [a0, a1, a2] = &self.a;
        a0.clone() * v[0].clone() + a1.clone() * v[1].clone() + a2.clone() * v[2].clone()
    }

    /// `a . p + b`.
    fn value(&self, p: &[S; 3]) -> S {
        self.linear(p) + self.b.clone()
    }
}

/// A convex face in its plane: the four half-spaces bounding it there.
struct Piece<S> {
    bounds: [HalfSpace<S>; 4],
}

impl<S: Scalar> Piece<S> {
    /// Whether point `p`, in the face's plane, lies on the face.
    fn contains(&self, p: &[S; 3]) -> bool {
        self.bounds.iter().all(|h| !h.value(p).is_negative())
    }
}

/// What a test of the base asks.
#[derive(Clone, Debug)]
pub struct BaseQuery<S> {
    /// Count only touches at `t > 0` (a shadow ray's start does not count).
    pub after_start: bool,
    /// Only a touch strictly before this `t` can be the answer (the terrain's hit, which
    /// wins a tie).
    pub before: Option<S>,
}

/// The first touch of the ray `o + t*d` (`t >= 0`, or `t > 0` as `query` says) with the
/// base of `terrain`: walls before the floor on ties, walls in [`Side::ALL`]'s order.
pub fn base_hit<S: Scalar>(
    terrain: &Terrain,
    base: &Base,
    o: &[S; 3],
    d: &[S; 3],
    query: &BaseQuery<S>,
) -> Option<BaseHit<S>> {
    let mut best: Option<BaseHit<S>> = None;
    let consider = |t: Option<S>, face: Face, best: &mut Option<BaseHit<S>>| {
        let Some(t) = t else { return };
        if best.as_ref().is_none_or(|b| t < b.t) {
            *best = Some(BaseHit { t, face });
        }
    };
    // (In the arithmetics without rounding, a look in `f64` first: most rays miss most faces
    // by far.)
    let screen = Screen::new(o, d, query.before.as_ref());
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let may_touch = |axis: usize, at: f64, lo: [f64; 3], hi: [f64; 3]| {
        screen.as_ref().is_none_or(|s| !s.misses(axis, at, lo, hi))
    };
    if base.walls {
        for (side, top) in Side::ALL.into_iter().zip(base.tops) {
            let (at, _) = wall_line(terrain, side);
            let (lo, hi) = ([0.0, 0.0, base.floor], [w, h, top]);
            if may_touch(side.axis(), at as f64, lo, hi) {
                let t = wall_touch(terrain, base, side, o, d, query);
                consider(t, Face::Wall(side), &mut best);
            }
        }
    }
    if may_touch(2, base.floor, [0.0; 3], [w, h, 0.0]) {
        let t = floor_touch(terrain, base, o, d, query);
        consider(t, Face::Floor, &mut best);
    }
    best
}

/// The grid coordinate of a wall's plane and the length of its edge line.
fn wall_line(terrain: &Terrain, side: Side) -> (usize, usize) {
    let field = terrain.field();
    let (w, h) = (field.width() - 1, field.height() - 1);
    match side {
        Side::West => (0, h),
        Side::East => (w, h),
        Side::South => (0, w),
        Side::North => (h, w),
    }
}

/// Wall piece `k` of `side`: `None` where its edge cell is a hole.
fn wall_piece<S: Scalar>(terrain: &Terrain, base: &Base, side: Side, k: usize) -> Option<Piece<S>> {
    let field = terrain.field();
    let (at, _) = wall_line(terrain, side);
    let axis = side.axis();
    // The cell along the edge, and the two samples bounding the segment.
    let cell_at = match side {
        Side::West | Side::South => at,
        Side::East | Side::North => at - 1,
    };
    let ((ci, cj), (i0, j0), (i1, j1)) = match axis {
        0 => ((cell_at, k), (at, k), (at, k + 1)),
        _ => ((k, cell_at), (k, at), (k + 1, at)),
    };
    if field.is_hole_cell(ci, cj) {
        return None;
    }
    let (z0, z1) = (S::from_f64(field.z(i0, j0)), S::from_f64(field.z(i1, j1)));
    let along = 1 - axis;
    let k_lo = S::from_i64(k as i64);
    let k_hi = S::from_i64(k as i64 + 1);
    // Under the segment: z0 * (k+1 - u) + z1 * (u - k) - z >= 0.
    let mut a = [S::zero(), S::zero(), -S::one()];
    a[along] = z1.clone() - z0.clone();
    let b = z0 * k_hi.clone() - z1 * k_lo.clone();
    Some(Piece {
        bounds: [
            HalfSpace::on_axis(along, 1, -k_lo),
            HalfSpace::on_axis(along, -1, k_hi),
            HalfSpace::on_axis(2, 1, -S::from_f64(base.floor)),
            HalfSpace { a, b },
        ],
    })
}

/// The first touch of wall `side`.
fn wall_touch<S: Scalar>(
    terrain: &Terrain,
    base: &Base,
    side: Side,
    o: &[S; 3],
    d: &[S; 3],
    query: &BaseQuery<S>,
) -> Option<S> {
    let (at, length) = wall_line(terrain, side);
    let axis = side.axis();
    let plane = S::from_i64(at as i64);
    if d[axis].is_zero() {
        if o[axis] != plane {
            return None;
        }
        // In the wall's plane: the first touch of any piece.
        return (0..length)
            .filter_map(|k| wall_piece(terrain, base, side, k))
            .filter_map(|piece| in_plane_touch(&piece, o, d, query))
            .reduce(S::lesser);
    }
    let t = crossing(&plane, axis, o, d, query)?;
    let mut p = [0, 1, 2].map(|c| o[c].clone() + d[c].clone() * t.clone());
    p[axis] = plane;
    // The piece under the crossing, or either piece where it lies on their common end.
    let u = p[1 - axis].floor_i64();
    let found = (u - 1..=u)
        .filter(|&k| k >= 0 && (k as usize) < length)
        .filter_map(|k| wall_piece(terrain, base, side, k as usize))
        .any(|piece: Piece<S>| piece.contains(&p));
    found.then_some(t)
}

/// The first touch of the floor.
fn floor_touch<S: Scalar>(
    terrain: &Terrain,
    base: &Base,
    o: &[S; 3],
    d: &[S; 3],
    query: &BaseQuery<S>,
) -> Option<S> {
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as i64, (field.height() - 1) as i64);
    let at = S::from_f64(base.floor);
    let piece = Piece {
        bounds: [
            HalfSpace::on_axis(0, 1, S::zero()),
            HalfSpace::on_axis(0, -1, S::from_i64(w)),
            HalfSpace::on_axis(1, 1, S::zero()),
            HalfSpace::on_axis(1, -1, S::from_i64(h)),
        ],
    };
    if d[2].is_zero() {
        if o[2] != at {
            return None;
        }
        return in_plane_touch(&piece, o, d, query);
    }
    let t = crossing(&at, 2, o, d, query)?;
    let mut p = [0, 1, 2].map(|c| o[c].clone() + d[c].clone() * t.clone());
    p[2] = at;
    piece.contains(&p).then_some(t)
}

/// Where the ray crosses the plane `p[axis] = at` (`d[axis]` is not zero), if at a `t` the
/// query counts.
fn crossing<S: Scalar>(
    at: &S,
    axis: usize,
    o: &[S; 3],
    d: &[S; 3],
    query: &BaseQuery<S>,
) -> Option<S> {
    let t = (at.clone() - o[axis].clone()) / d[axis].clone();
    let counts = if query.after_start {
        t > S::zero()
    } else {
        !t.is_negative()
    };
    (counts && query.before.as_ref().is_none_or(|b| t < *b)).then_some(t)
}

/// The first touch of a ray lying in `piece`'s plane with it: the least `t` the piece's
/// half-spaces keep (Liang and Barsky's clipping).
fn in_plane_touch<S: Scalar>(
    piece: &Piece<S>,
    o: &[S; 3],
    d: &[S; 3],
    query: &BaseQuery<S>,
) -> Option<S> {
    let mut lo = S::zero();
    let mut hi: Option<S> = None;
    for bound in &piece.bounds {
        // The half-space along the ray: g0 + g1 * t >= 0.
        let g0 = bound.value(o);
        let g1 = bound.linear(d);
        if g1.is_zero() {
            if g0.is_negative() {
                return None;
            }
            continue;
        }
        let t = -g0 / g1.clone();
        if g1.is_negative() {
            hi = Some(match hi {
                Some(h) => h.lesser(t),
                None => t,
            });
        } else {
            lo = lo.greater(t);
        }
    }
    if let Some(hi) = &hi {
        // (A shadow ray needs a touch after its start: the kept `t` must reach past zero.)
        let reaches_past_start = !query.after_start || *hi > S::zero();
        if !reaches_past_start || lo > *hi {
            return None;
        }
    }
    query.before.as_ref().is_none_or(|b| lo < *b).then_some(lo)
}
