//! The hovered pixel's ray, traced again on demand with `heightray::trace` (one primary ray
//! and, if it hits, one shadow query towards the sun) so every query it made can be shown.

use crate::geometry::plane_height;
use crate::traverse::Scalar;
use crate::{trace, Arith, Hit, Query, Ray, Terrain, Trace, TraceOptions};
use std::time::{Duration, Instant};

/// One pixel's ray and what it asked.
#[derive(Clone, Debug)]
pub struct Probe {
    /// The pixel in the rendered frame.
    pub pixel: (u32, u32),
    /// The frame generation the pixel belonged to.
    pub generation: u64,
    pub primary: Trace,
    /// The shadow query from the hit point towards the sun (when the primary ray hit).
    pub shadow: Option<Trace>,
    /// Time both traces took.
    pub elapsed: Duration,
}

/// What the probe needs to know of the view.
pub struct ProbeSetup<'a> {
    pub terrain: &'a Terrain,
    pub options: TraceOptions,
    pub sun: [f64; 3],
}

impl Probe {
    /// Traces `ray` (pixel `pixel` of frame `generation`) and its shadow query.
    pub fn trace(setup: &ProbeSetup<'_>, ray: Ray, pixel: (u32, u32), generation: u64) -> Probe {
        let start = Instant::now();
        let primary = trace(setup.terrain, &ray, &setup.options);
        let shadow = primary.hit.as_ref().and_then(|hit| {
            let origin = shadow_origin(setup, &ray, hit);
            let ray = Ray::new(origin, setup.sun).ok()?;
            let options = TraceOptions {
                query: Query::Shadow,
                ..setup.options
            };
            Some(trace(setup.terrain, &ray, &options))
        });
        Probe {
            pixel,
            generation,
            primary,
            shadow,
            elapsed: start.elapsed(),
        }
    }

    /// Whether the hit point is in shadow (None without a hit).
    pub fn shadowed(&self) -> Option<bool> {
        self.shadow.as_ref().map(|s| s.hit.is_some())
    }
}

/// Where the shadow query starts, as the renderer does it: on the hit triangle's plane (exact
/// on flat ground) and raised by what rounding may have moved it below the surface. `trace`
/// reports the point in `f64` even in exact mode, so exact mode is lifted by one `f64`
/// rounding too (the renderer keeps its exact point: a grazing shadow may then differ).
fn shadow_origin(setup: &ProbeSetup<'_>, ray: &Ray, hit: &Hit) -> [f64; 3] {
    let largest = ray
        .origin()
        .iter()
        .chain(&ray.dir())
        .fold(0.0f64, |m, c| m.max(c.abs()));
    let magnitude = largest * (1.0 + hit.t.abs());
    let rounding = match setup.options.arith {
        Arith::F32 => <f32 as Scalar>::rounding_error(magnitude),
        Arith::F64 | Arith::Exact => <f64 as Scalar>::rounding_error(magnitude),
        Arith::Rational { bound } => {
            <f64 as Scalar>::rounding_error(magnitude).max(1.0 / f64::from(bound.max(1)))
        }
    };
    let lift = 64.0 * rounding * (1.0 + setup.terrain.max_slope());
    let [x, y, _] = hit.point;
    let cell = (hit.cell[0], hit.cell[1]);
    let heights = setup.terrain.corner_heights(cell.0, cell.1);
    [x, y, plane_height(hit.triangle, cell, heights, x, y) + lift]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::Builtin;
    use crate::Method;

    #[test]
    fn a_ray_down_onto_the_terrain_hits_and_asks_a_shadow_query() {
        let field = Builtin::named("small49")
            .and_then(|b| b.load().ok())
            .expect("decodes");
        let terrain = Terrain::new(field);
        let setup = ProbeSetup {
            terrain: &terrain,
            options: TraceOptions::new(Method::Runs, Arith::F64),
            sun: [0.0, 0.0, 1.0],
        };
        let ray = Ray::new([20.5, 20.25, 100.0], [0.0, 0.0, -1.0]).expect("valid ray");
        let probe = Probe::trace(&setup, ray, (3, 4), 7);
        let hit = probe.primary.hit.as_ref().expect("hits the terrain");
        assert_eq!(hit.cell, [20, 20]);
        // Straight up from a height field nothing is in the way.
        assert_eq!(probe.shadowed(), Some(false));
        assert!(probe.primary.counters.triangle.total() > 0);
    }
}
