//! Strip bounds: for one direction of travel (the sun's), an upper bound on how high the
//! terrain ahead rises against a ray climbing at the direction's slope, so that most rays
//! towards it are known clear beyond a few cells without a walk (the exact, conservative
//! form of the line-sweep horizons of Timonen & Westerholm 2010). Built for the sun's disc,
//! they serve every direction within it: soft shadows look up the same bounds.
//!
//! In the direction's frame, `u` runs along its dominant horizontal axis (towards it) and `v`
//! along the other; a ray's path keeps `w = v - m*u` fixed (`m` the slope across) and climbs
//! `kappa` samples per unit of `u`. Strips of [`STRIP`] cells in `w` are cut into blocks of
//! [`BLOCK`] columns of `u`; each block holds `C(c)`, an upper bound on `s - kappa*(u - u_c)`
//! over every triangle vertex `(u, v, s)` (`s` in samples) of the cells the strip's paths
//! cross from the block's first column line `u_c` on:
//!
//! `C(c) = max(the block's own vertices, C(c+1) - BLOCK*kappa)`, one pass per strip.
//!
//! Why a look-up is exact: over a triangle `s - kappa*u` is linear, so its largest value lies
//! at a vertex; every point of the surface under a path of the strip beyond `u_c` is thus at
//! most `C(c) + kappa*(u - u_c)` high, and a ray whose height at `u_c` exceeds `C(c)` stays
//! above it all the way. Strips are grown by [`PAD`] across, bounds are rounded up to whole
//! samples, and the caller's room covers the rounding of the ray's own start.
//!
//! A disc of directions around the axis: the bounds are built along the axis's `m` with the
//! lowest `kappa` of any direction in the disc, so they bound the terrain against every such
//! ray's climb too. A ray of slope `m'` drifts across strips, `w` changing by `(m' - m)` per
//! unit of `u`; it need only be followed until it rises above the highest sample, so its look-up
//! takes the largest bound over the strips its `w` passes through up to there.

use super::near_rise::{ConeRises, NearStart};
use super::Heightfield;

/// Strip width across the direction, in cells.
pub const STRIP: usize = 2;

/// Columns of `u` per stored bound.
pub const BLOCK: usize = 3;

/// How many column lines ahead a look-up asks before it leaves the ray to a full walk: a
/// clear verdict further on leaves more to walk than the walk down the mipmap skips.
const FARTHEST_COLUMNS: usize = 48;

/// How far each strip is grown on either side (cells): far more than a path's `w` can be off
/// by rounding, or by a start that lies a little off the computed one.
const PAD: f64 = 1e-4;

/// Upper bounds on the terrain ahead of rays in one direction (see the module docs).
#[derive(Clone, Debug)]
pub struct StripBounds {
    dir: [f64; 3],
    /// The disc's half-angle around `dir` (radians; 0 for one direction).
    half: f64,
    frame: DirFrame,
    /// `m`: change of `v` per unit of `u` along a path.
    slope: f64,
    /// `kappa`: samples a path climbs per unit of `u`.
    climb: f64,
    /// The lowest `w` of any sample, where strip 0 starts.
    w_min: f64,
    /// Per strip: its first block and where its bounds start in `bounds`.
    strips: Vec<StripRange>,
    /// `C(c)` rounded up to whole samples, strip after strip.
    bounds: Vec<u16>,
    /// The height of sample 0, and samples per unit of height.
    base: f64,
    per_step: f64,
    /// How far a path climbs across the whole map (samples), for the rounding of `climb`.
    climb_across: f64,
    /// `t` per unit of `u` along `dir`.
    per_du: f64,
    /// The highest sample: a ray above it is above all the terrain.
    top: f64,
    /// The slopes `m` of the disc's outermost azimuths, lowest first (the axis's twice for
    /// one direction); `None` where they do not both run towards higher `u`.
    disc_slopes: Option<(f64, f64)>,
    /// How fast the surface rises along the disc's azimuths near each block, for the part a
    /// look-up leaves to walk (see [`StripBounds::clear_before`]); `None` where the disc
    /// spans nearly half a turn of azimuths.
    rises: Option<ConeRises>,
}

/// The blocks of one strip that meet the map, `first..first + len`, stored from `at` on.
#[derive(Clone, Copy, Debug, Default)]
struct StripRange {
    first: u32,
    len: u32,
    at: u32,
}

/// How grid `(x, y)` maps to the direction's `(u, v)`: `u` along the dominant axis, counted
/// from the far side when the direction points towards lower coordinates.
#[derive(Clone, Copy, Debug)]
struct DirFrame {
    /// `u` runs along y (not x).
    along_y: bool,
    /// `u` grows as the grid coordinate falls.
    reversed: bool,
    /// Samples along `u` and along `v`.
    nu: usize,
    nv: usize,
}

impl DirFrame {
    /// `(u, v)` of the grid point `(x, y)`.
    fn uv(&self, x: f64, y: f64) -> (f64, f64) {
        let (a, b) = if self.along_y { (y, x) } else { (x, y) };
        let u = if self.reversed {
            (self.nu - 1) as f64 - a
        } else {
            a
        };
        (u, b)
    }

    /// How far `dir` (grid coordinates) runs along `u` (positive towards higher `u`) and `v`.
    #[inline]
    fn along(&self, [dx, dy, _]: [f64; 3]) -> (f64, f64) {
        let (a, b) = if self.along_y { (dy, dx) } else { (dx, dy) };
        (if self.reversed { -a } else { a }, b)
    }

    /// The index in the field's samples of the vertex `(u, v)`.
    fn index(&self, u: usize, v: usize, width: usize) -> usize {
        let a = if self.reversed { self.nu - 1 - u } else { u };
        let (x, y) = if self.along_y { (v, a) } else { (a, v) };
        y * width + x
    }
}

impl StripBounds {
    /// The bounds for rays travelling in `dir` (grid coordinates), or in any direction within
    /// `half` (radians) of it, over `field`; `None` where they cannot help: a disc that does
    /// not climb all round, holds a vertical or not finite direction or half a turn of
    /// azimuths, or a flat field.
    pub fn build(field: &Heightfield, dir: [f64; 3], half: f64) -> Option<StripBounds> {
        let [dx, dy, dz] = dir;
        if !(dir.iter().all(|c| c.is_finite()) && dz > 0.0 && field.step() > 0.0) {
            return None;
        }
        if !(half.is_finite() && half >= 0.0) {
            return None;
        }
        let along_y = dy.abs() > dx.abs();
        let (du, dv) = if along_y { (dy, dx) } else { (dx, dy) };
        if du == 0.0 {
            return None;
        }
        let (nu, nv) = match along_y {
            true => (field.height(), field.width()),
            false => (field.width(), field.height()),
        };
        let frame = DirFrame {
            along_y,
            reversed: du < 0.0,
            nu,
            nv,
        };
        let slope = dv / du.abs();
        let climb = lowest_climb(du.abs(), dv.abs(), dz, half)? / field.step();
        if !(slope.is_finite() && climb.is_finite() && climb > 0.0) {
            return None;
        }
        // `w` over the map: `v` from 0 to `nv - 1` less `m*u` from 0 to `m*(nu - 1)`.
        let far = (nu - 1) as f64 * slope;
        let (w_min, w_max) = (-far.max(0.0), (nv - 1) as f64 - far.min(0.0));
        let count = ((w_max - w_min) / STRIP as f64).floor() as usize + 1;
        let blocks = (nu - 1).div_ceil(BLOCK).max(1);
        let samples = field.samples();
        let top = samples.iter().copied().max().map_or(0.0, f64::from);
        let azimuths = disc_azimuths(dir, half);
        let mut bounds = StripBounds {
            dir,
            half,
            frame,
            slope,
            climb,
            w_min,
            strips: Vec::with_capacity(count),
            bounds: Vec::new(),
            base: field.height_of(0),
            per_step: 1.0 / field.step(),
            climb_across: climb * nu as f64,
            per_du: 1.0 / du.abs(),
            top,
            disc_slopes: azimuths.and_then(|ends| disc_slopes(&frame, ends)),
            rises: azimuths.map(|cone| ConeRises::build(field, cone, NEAR)),
        };
        let mut column = Vec::with_capacity(blocks);
        for j in 0..count {
            column.clear();
            let mut next = f64::NEG_INFINITY;
            let mut last = None;
            for c in (0..blocks).rev() {
                let own = bounds.block_local(j, c, samples, field.width());
                if own.is_none() && last.is_some() {
                    // The strip leaves the map towards lower `u` (it met it only further on).
                    break;
                }
                let Some(own) = own else { continue };
                last.get_or_insert(c);
                next = own.max(next - (BLOCK as f64) * climb);
                column.push(next.ceil().clamp(0.0, f64::from(u16::MAX)) as u16);
            }
            let Some(last) = last else {
                bounds.strips.push(StripRange::default());
                continue;
            };
            let len = column.len();
            bounds.strips.push(StripRange {
                first: (last + 1 - len) as u32,
                len: len as u32,
                at: bounds.bounds.len() as u32,
            });
            bounds.bounds.extend(column.iter().rev());
        }
        Some(bounds)
    }

    /// The direction the bounds were built for.
    pub fn dir(&self) -> [f64; 3] {
        self.dir
    }

    /// The half-angle (radians) of the disc around [`StripBounds::dir`] they serve.
    pub fn half(&self) -> f64 {
        self.half
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.bounds.len() * 2
            + self.strips.len() * std::mem::size_of::<StripRange>()
            + self.rises.as_ref().map_or(0, ConeRises::bytes)
    }

    /// Whether a ray from `start` towards `dir` that [`StripBounds::clear_beyond`] calls clear
    /// from `t` on is clear before `t` too: it starts well inside its own flat triangle
    /// (`near`) and outclimbs the surface around it all the way to `t`.
    pub fn clear_before(&self, start: [f64; 3], dir: [f64; 3], t: f64, near: NearStart) -> bool {
        // (Not `hypot`: a direction cannot overflow.)
        let across = (dir[0] * dir[0] + dir[1] * dir[1]).sqrt();
        self.outclimbed(start, dir[2] / across, t * across, near)
    }

    /// Whether every ray of the disc from `start` (which climbs at least `climb` per cell
    /// horizontally) outclimbs the surface over its first `distance` cells, as `near` has it.
    pub fn outclimbed(&self, start: [f64; 3], climb: f64, distance: f64, near: NearStart) -> bool {
        self.rises
            .as_ref()
            .is_some_and(|rises| rises.outclimbed(start, climb, distance, near))
    }

    /// The highest `s - climb*(u - u_c)` over the vertices of the cells that the strip `j`'s
    /// paths cross in block `c` (`u_c` its first column line); `None` where those paths lie
    /// outside the map there.
    fn block_local(&self, j: usize, c: usize, samples: &[u16], width: usize) -> Option<f64> {
        let DirFrame { nu, nv, .. } = self.frame;
        let u0 = c * BLOCK;
        let u1 = (u0 + BLOCK).min(nu - 1);
        let w_lo = self.w_min + (j * STRIP) as f64 - PAD;
        let w_hi = self.w_min + ((j + 1) * STRIP) as f64 + PAD;
        let (a, b) = (self.slope * u0 as f64, self.slope * u1 as f64);
        let (v_lo, v_hi) = (w_lo + a.min(b), w_hi + a.max(b));
        if v_hi < 0.0 || v_lo > (nv - 1) as f64 {
            return None;
        }
        let r0 = v_lo.floor().max(0.0) as usize;
        let r1 = ((v_hi.floor() as usize) + 1).min(nv - 1);
        let mut best = f64::NEG_INFINITY;
        for u in u0..=u1 {
            let highest = (r0..=r1)
                .map(|v| samples[self.frame.index(u, v, width)])
                .max()
                .unwrap_or(0);
            best = best.max(f64::from(highest) - self.climb * (u - u0) as f64);
        }
        Some(best)
    }

    /// Whether a ray from `start` (grid coordinates) towards `dir` (a direction of the disc
    /// the bounds serve) certainly touches no triangle beyond a few cells ahead: `Some(t)`
    /// where it is clear from `start + t * dir` on, so that only `[0, t]` is left to walk.
    /// `room` is how far (in height) the ray's true start may lie below `start` or across.
    #[inline(always)]
    pub fn clear_beyond(&self, start: [f64; 3], dir: [f64; 3], room: f64) -> Option<f64> {
        let (du, dv) = self.frame.along(dir);
        if du.is_nan() || du <= 0.0 {
            return None;
        }
        let (slope, per_du) = if dir == self.dir {
            (self.slope, self.per_du)
        } else {
            let per_du = 1.0 / du;
            // The bounds hold against climbs of at least their own.
            if dir[2] * per_du * self.per_step < self.climb {
                return None;
            }
            (dv * per_du, per_du)
        };
        let ahead = self.clear_ahead(start, (slope, slope), room)?;
        Some(ahead * per_du)
    }

    /// Whether every ray of the disc from `start` certainly touches no triangle beyond a few
    /// cells ahead: `Some(r)` where each is clear from `r` cells away (horizontally) on. The
    /// disc's rays climb at least as the bounds were built for; their slopes lie between its
    /// outermost azimuths'.
    pub fn disc_clear_beyond(&self, start: [f64; 3], room: f64) -> Option<f64> {
        let (lo, hi) = self.disc_slopes?;
        let ahead = self.clear_ahead(start, (lo, hi), room)?;
        // (A path of slope `m` runs `sqrt(1 + m^2)` cells for each of `u`.)
        let longest = (1.0 + lo * lo).max(1.0 + hi * hi).sqrt();
        Some(ahead * longest * (1.0 + 1e-9))
    }

    /// How far along `u` past `start` (plus a little) the rays from `start` with slopes in
    /// `[lo, hi]` across, climbing at least the bounds' own, are certainly clear; `None` where
    /// no column line within reach proves it.
    #[inline(always)]
    fn clear_ahead(&self, start: [f64; 3], (lo, hi): (f64, f64), room: f64) -> Option<f64> {
        let (u, v) = self.frame.uv(start[0], start[1]);
        // (Non-negative here, so truncation is the floor: no call to `floor`.)
        if !(u >= 0.0 && u < self.frame.nu as f64) {
            return None;
        }
        let w = v - self.slope * u;
        // The next column line more than one cell ahead: the start's own cells are walked.
        let first = ((u + 1.0) * (1.0 / BLOCK as f64)) as usize + 1;
        let z = (start[2] - self.base) * self.per_step;
        let own = self.strip_of(w).filter(|&j| j < self.strips.len())?;
        // Far more than the rounding of the ray's height and of the climb (with `1e-9` of
        // the climb to the column added at each).
        let error = 1e-9 * (z.abs() + self.climb_across + f64::from(u16::MAX))
            + room * self.per_step * (1.0 + self.climb);
        // Where a ray off the axis's slope leaves the map or rises above every sample: how
        // far its drift across the strips is followed.
        let u_end = (lo != self.slope || hi != self.slope).then(|| {
            let above = (self.top - z + error + 1e-9 * self.climb_across).max(0.0) / self.climb;
            (u + above).min(self.frame.nu as f64)
        });
        // The first column line from which the rays stay above its bound; a ray unsettled at
        // one column may be settled at a later one, leaving more (but not all) to walk.
        (first..first + FARTHEST_COLUMNS).find_map(|c| {
            let u_c = (c * BLOCK) as f64;
            let rise = self.climb * (u_c - u);
            let bound = match u_end {
                None => self.bound_at(own, c),
                // How far across the rays drift from the column until they leave the map or
                // rise above every sample.
                Some(u_end) => {
                    let (near, far) = (u_c - u, u_end.max(u_c) - u);
                    let drift = [(lo, near), (lo, far), (hi, near), (hi, far)]
                        .map(|(m, gap)| w + (m - self.slope) * gap);
                    let low = drift.iter().fold(f64::INFINITY, |a, &b| a.min(b));
                    let high = drift.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b));
                    let first = self.strip_of(low - PAD).unwrap_or(0);
                    let last = self.strip_of(high + PAD).unwrap_or(self.strips.len());
                    (first..=last.min(self.strips.len() - 1))
                        .map(|j| self.bound_at(j, c))
                        .fold(f64::NEG_INFINITY, f64::max)
                }
            };
            (z + rise - (error + 1e-9 * rise) > bound).then_some(u_c - u + 1e-3)
        })
    }

    /// The strip holding paths with `w`; `None` below the first one.
    fn strip_of(&self, w: f64) -> Option<usize> {
        let strip = (w - self.w_min) * (1.0 / STRIP as f64);
        // (Non-negative here, so truncation is the floor.)
        (strip >= 0.0).then_some(strip as usize)
    }

    /// The bound of strip `j` from block `c` on (`-inf` where no terrain lies ahead).
    fn bound_at(&self, j: usize, c: usize) -> f64 {
        let Some(range) = self.strips.get(j) else {
            return f64::NEG_INFINITY;
        };
        let (first, len) = (range.first as usize, range.len as usize);
        if len == 0 || c >= first + len {
            // No terrain ahead: the strip has left the map (or never meets it).
            f64::NEG_INFINITY
        } else if c < first {
            // The strip meets the map only further on.
            let gap = ((first - c) * BLOCK) as f64;
            f64::from(self.bounds[range.at as usize]) - gap * self.climb
        } else {
            f64::from(self.bounds[range.at as usize + c - first])
        }
    }
}

/// How far (horizontally, in cells) the part a look-up leaves to walk can run: to the next
/// column line more than a cell ahead, at most `BLOCK + 1` columns of `u`, along a direction
/// at most `sqrt(2)` times longer than its `u`.
const NEAR: f64 = (BLOCK + 1) as f64 * std::f64::consts::SQRT_2 + 1e-2;

/// The azimuths of the directions within `half` (radians) of `dir`, as the unit vectors at
/// either end, widened for rounding; `None` where they span nearly half a turn or more.
fn disc_azimuths(dir: [f64; 3], half: f64) -> Option<([f64; 2], [f64; 2])> {
    let length = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    let horizontal = dir[0].hypot(dir[1]) / length;
    // The widest azimuth off the axis of a circular cone: asin(sin(half) / cos(elevation)).
    // (NaN, from a vertical direction, spans every azimuth.)
    let across = Some(half.sin() / horizontal).filter(|&a| a < 0.9)?;
    let spread = across.asin() * (1.0 + 1e-6) + 1e-7;
    let mid = dir[1].atan2(dir[0]);
    let unit = |angle: f64| [angle.cos(), angle.sin()];
    Some((unit(mid - spread), unit(mid + spread)))
}

/// The slopes across of the disc's outermost azimuths `(lo, hi)` (see [`disc_azimuths`]) in
/// `frame`, lowest first.
fn disc_slopes(frame: &DirFrame, (lo, hi): ([f64; 2], [f64; 2])) -> Option<(f64, f64)> {
    let slope = |[x, y]: [f64; 2]| {
        let (du, dv) = frame.along([x, y, 0.0]);
        (du > 0.0).then(|| dv / du)
    };
    let (a, b) = (slope(lo)?, slope(hi)?);
    Some((a.min(b), a.max(b)))
}

/// The lowest climb `dz / |du|` of any direction within `half` of `(du, dv, dz)` (`du` the
/// dominant horizontal part, all three non-negative), rounded down; `None` where the disc
/// does not climb all round or spans too wide a turn of azimuths for `du` to keep its sign.
fn lowest_climb(du: f64, dv: f64, dz: f64, half: f64) -> Option<f64> {
    if half == 0.0 {
        return Some(dz / du);
    }
    let across = du.hypot(dv);
    let elevation = dz.atan2(across) - half * (1.0 + 1e-6);
    // How far the disc's azimuths turn from the axis's, as the soft shadow's sector does.
    let turn = half.sin() * dz.hypot(across) / across;
    if !(elevation > 0.0 && turn < 0.9) {
        return None;
    }
    let turn = turn.asin() * (1.0 + 1e-6) + 1e-9;
    let nearest = ((dv / du).atan() - turn).max(0.0);
    if dv.atan2(du) + turn >= 1.5 {
        return None;
    }
    Some(elevation.tan() / nearest.cos() * (1.0 - 1e-9))
}
