//! Hours of direct sun over a day: the sun's place over the map's centre every few minutes
//! (NREL's SPA, [`SunPosition`]), and at each step whether it is above the horizon and the
//! terrain leaves a point in its light. A point is lit when the ray from it towards the sun
//! touches the surface nowhere after it starts: within two cells that is decided along the
//! surface's own profile ([`Horizon::rise`], which also darkens a slope facing away), beyond
//! them by an occlusion query from where a vertical ray meets the surface ([`Tracer::occluded`]), in the traversal's
//! arithmetic (exactly in exact mode). Each step's sun has its strip bounds ([`StripBounds`]),
//! as a picture's sun has: a ray they prove clear beyond its first cells walks only those.

use super::horizon::Horizon;
use crate::arith::Scalar;
use crate::arith::{run, Generic};
use crate::heightfield::StripBounds;
use crate::render::local_time;
use crate::render::sun_position::SunPosition;
use crate::traverse::{Start, Tracer};
use crate::{Ray, Terrain, TraceOptions};
use chrono::{Duration, NaiveDate, NaiveTime};
use chrono_tz::Tz;
use rayon::prelude::*;

/// The sun over one day, step by step.
#[derive(Clone, Debug, PartialEq)]
pub struct SunPath {
    /// Directions towards the sun (world, x east, y north, z up) at the steps it is up.
    pub sun_up: Vec<[f64; 3]>,
    /// Steps in the day (23, 24 or 25 hours on the local clocks).
    pub steps: usize,
    /// Hours each step stands for.
    pub step_hours: f64,
    /// The time zone of the day's clocks.
    pub zone: Tz,
}

/// Why a day's sun path cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SunPathError {
    /// A step that does not divide an hour.
    #[error(
        "the sun's step must divide an hour (1, 2, 3, 4, 5, 6, 10, 12, 15, 20, 30 or 60 \
         minutes), got {0}"
    )]
    Step(u32),
    /// The last date the calendar knows has no next day.
    #[error("the date is the last one known")]
    LastDate,
    /// A midnight the zone's clocks skip.
    #[error(transparent)]
    Time(#[from] crate::render::local_time::TimeError),
    /// The sun's position at a step.
    #[error(transparent)]
    Sun(#[from] crate::render::sun_position::SunError),
}

impl SunPath {
    /// The sun seen from `latitude`, `longitude` (degrees) at the middle of each step of
    /// `step_minutes` (a divisor of 60) of `date`, from midnight to midnight in `zone`.
    pub fn over_day(
        date: NaiveDate,
        (latitude, longitude): (f64, f64),
        zone: Tz,
        step_minutes: u32,
    ) -> Result<SunPath, SunPathError> {
        if step_minutes == 0 || 60 % step_minutes != 0 {
            return Err(SunPathError::Step(step_minutes));
        }
        let midnight =
            |day: NaiveDate| local_time::utc_of_local(day.and_time(NaiveTime::MIN), zone);
        let next_day = date.succ_opt().ok_or(SunPathError::LastDate)?;
        let (start, end) = (midnight(date)?, midnight(next_day)?);
        let step = Duration::minutes(i64::from(step_minutes));
        let steps = ((end - start).num_minutes() / i64::from(step_minutes)) as usize;
        let mut sun_up = Vec::new();
        for k in 0..steps {
            let instant = start + step * k as i32 + step / 2;
            let sun = SunPosition::at_utc(instant, latitude, longitude)?;
            if sun.is_up() {
                sun_up.push(sun.direction());
            }
        }
        Ok(SunPath {
            sun_up,
            steps,
            step_hours: f64::from(step_minutes) / 60.0,
            zone,
        })
    }

    /// Hours the sun is above the horizon (what flat open ground receives).
    pub fn daylight_hours(&self) -> f64 {
        self.sun_up.len() as f64 * self.step_hours
    }
}

/// Hours of direct sun at points of one terrain.
pub struct Sunlight<'a> {
    terrain: &'a Terrain,
    horizon: Horizon<'a>,
    /// Per step with the sun up: its compass direction, the tangent of its elevation, and its
    /// direction in grid coordinates.
    suns: Vec<([f64; 2], f64, [f64; 3])>,
    /// Per step with the sun up: the strip bounds of its direction, where they can help and
    /// are asked for.
    strips: Vec<Option<StripBounds>>,
    step_hours: f64,
    options: TraceOptions,
    /// How far along the surface's profile a ray's start is decided (world units).
    near: f64,
}

impl<'a> Sunlight<'a> {
    /// Sunlight over `terrain` along `path`, occlusion queries made with `options`, with each
    /// sun's strip bounds (built on rayon's threads).
    pub fn new(terrain: &'a Terrain, path: &SunPath, options: TraceOptions) -> Self {
        Sunlight::with_bounds(terrain, path, options, true)
    }

    /// [`Sunlight::new`], with the suns' strip bounds or without: the same hours, at another
    /// cost.
    pub fn with_bounds(
        terrain: &'a Terrain,
        path: &SunPath,
        options: TraceOptions,
        bounds: bool,
    ) -> Self {
        let scale = terrain.world_from_grid().unwrap_or([1.0, 1.0, 1.0]);
        let suns = path
            .sun_up
            .iter()
            .map(|&[x, y, z]| {
                let across = x.hypot(y);
                let toward = if across > 0.0 {
                    [x / across, y / across]
                } else {
                    [0.0, 1.0]
                };
                let grid = [x / scale[0], y / scale[1], z / scale[2]];
                let length = grid.iter().map(|c| c * c).sum::<f64>().sqrt();
                (toward, z / across, grid.map(|c| c / length))
            })
            .collect::<Vec<_>>();
        let strips = suns
            .par_iter()
            .map(|&(_, _, grid)| bounds.then(|| StripBounds::build(terrain.field(), grid, 0.0)))
            .map(Option::flatten)
            .collect();
        Sunlight {
            terrain,
            horizon: Horizon::new(terrain),
            suns,
            strips,
            step_hours: path.step_hours,
            options,
            near: 2.0 * scale[0].max(scale[1]),
        }
    }

    /// Hours of direct sun at grid point `at` of the surface; `None` off the surface.
    pub fn hours_at(&self, at: [f64; 2]) -> Option<f64> {
        let z0 = self.horizon.surface_z(at)?;
        let top = self.terrain.z_range().1 + 1.0;
        let down = Ray::new([at[0], at[1], top], [0.0, 0.0, -1.0]).ok()?;
        // The sun climbs more steeply than any triangle (with room for rounding): nothing
        // can shade the point, and no ray is cast.
        let steepest = self.terrain.max_slope() * (1.0 + 1e-9);
        let mut open = 0;
        let mut asked = Vec::with_capacity(self.suns.len());
        for ((toward, tan_elevation, grid), strips) in self.suns.iter().zip(&self.strips) {
            let near = self.horizon.rise(at, z0, *toward, self.near);
            if near.is_some_and(|rise| rise >= *tan_elevation) {
                continue;
            }
            if grid[2] > steepest * grid[0].hypot(grid[1]) {
                open += 1;
            } else {
                asked.push((*grid, strips.as_ref()));
            }
        }
        let steps = FromSurface {
            tracer: Tracer::new(self.terrain, self.options.method),
            down: &down,
            suns: &asked,
            max_slope: self.terrain.max_slope(),
        };
        let (lit, _) = run(self.options.arith, &steps);
        Some((open + lit.output) as f64 * self.step_hours)
    }
}

/// The suns a point of the surface sees: occlusion rays towards each from where a vertical
/// ray meets the surface, traced once for them all, in whichever arithmetic [`run`] picks;
/// each walked only as far as its sun's strip bounds leave it unsettled.
struct FromSurface<'s, 'a> {
    tracer: Tracer<'a>,
    down: &'s Ray,
    /// Directions towards the sun in grid coordinates, and their strip bounds.
    suns: &'s [([f64; 3], Option<&'s StripBounds>)],
    /// The terrain's steepest slope.
    max_slope: f64,
}

impl Generic for FromSurface<'_, '_> {
    type Output = usize;
    fn run<S: Scalar>(&self) -> usize {
        let Some(hit) = self.tracer.trace::<S>(self.down, None).hit else {
            return self.suns.len();
        };
        let from = Start::Hit {
            ray: self.down,
            hit: &hit,
        };
        let o = self.down.origin();
        let start = [o[0], o[1], o[2] - hit.t.to_f64()];
        // How far the true start may lie below `start`, computed in `f64`: the roundings of
        // the hit's `t` and the point, with far more room than they need (as a picture's
        // shadow rays allow).
        let largest = (0..3).fold(0.0f64, |m, k| m.max(o[k].abs() + start[k].abs()));
        let room = 1024.0 * S::rounding_error(largest) * (1.0 + self.max_slope);
        self.suns
            .iter()
            .filter(|&&(sun, strips)| {
                let near = strips.and_then(|s| s.clear_beyond(start, sun, room));
                let tracer = match near {
                    Some(t) => self.tracer.within(t),
                    None => self.tracer,
                };
                tracer.occluded(&from, sun, true).occluded != Some(true)
            })
            .count()
    }
}
