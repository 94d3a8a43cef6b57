//! The sun's shadow at a hit: which shadow rays can change the pixel, the rules that settle
//! the others without a walk, and the occlusion ray shadows, soft shadows and sky light share.

use super::effects::SoftShadow;
use super::normals;
use super::scene::Normals;
use super::shade::Shader;
use crate::arith::Scalar;
use crate::geometry::Face;
use crate::geometry::Ray;
use crate::traverse::{Counters, Found, Occlusion, Start};
use glam::DVec3;

/// Why a shadow ray was not cast although the scene has shadows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowSkip {
    /// The surface faces away from the sun: it is dark whatever a shadow ray says.
    FacingAway,
    /// The sun stands higher than the steepest slope anywhere: nothing can cast a shadow.
    NoShadowPossible,
    /// The shadow ray starts above the highest terrain and rises.
    AboveTerrain,
    /// Soft shadows: every direction towards the sun's disc climbs more steeply than the
    /// terrain can rise around the point (see [`crate::render::effects`]).
    HorizonClear,
}

/// What became of a pixel's shadow.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shadow {
    /// No primary hit, or the scene has no shadows: nothing to decide.
    #[default]
    NotAsked,
    /// Left out where it cannot change the pixel, for this reason.
    Skipped(ShadowSkip),
    /// Cast towards the sun.
    Cast {
        /// The shadow ray found the surface: the pixel is in shadow.
        shadowed: bool,
    },
    /// Soft shadows: directions towards the sun's disc, some cast, the others provably clear.
    Soft(SoftShadow),
}

/// A pixel's shadow as cast: what became of it, the shadow ray's queries, and whether a
/// decision on it was made exactly after intervals left it unsettled (see
/// [`Sample::redone`](super::Sample::redone)).
pub(super) type Cast = (Shadow, Counters, bool);

impl Shader<'_> {
    /// Decides whether a shadow ray of the hit `found`, shaded at `p`, can change the pixel,
    /// and casts it if so (in a scene with shadows).
    pub(super) fn shadow<S: Scalar>(
        &self,
        found: &Found<S>,
        ray: &Ray,
        p: DVec3,
        facing: f64,
    ) -> Cast {
        let skip = |why| (Shadow::Skipped(why), Counters::default(), false);
        if self.culling.facing_away && facing <= 0.0 {
            return skip(ShadowSkip::FacingAway);
        }
        if self.lighting.effects.sun_angle_deg > 0.0 {
            return self.soft_shadow(found, ray, p);
        }
        let sun = self.grid_sun();
        // The sun climbs strictly steeper than any triangle (with room for the rounding of
        // max_slope), compared squared: no square root per shadow ray.
        let steepest = self.terrain.max_slope() * (1.0 + 1e-9);
        let climbs_steeper = sun[2] > 0.0
            && sun[2] * sun[2] > steepest * steepest * (sun[0] * sun[0] + sun[1] * sun[1]);
        if self.culling.no_shadow_possible && climbs_steeper {
            return skip(ShadowSkip::NoShadowPossible);
        }
        let start = self.occlusion_start(found, p);
        let occlusion = self.occluded_beyond(found, ray, p, start, (sun, sun));
        match occlusion.occluded {
            Some(shadowed) => (
                Shadow::Cast { shadowed },
                occlusion.counters,
                occlusion.exactly,
            ),
            None => (
                Shadow::Skipped(ShadowSkip::AboveTerrain),
                Counters::default(),
                occlusion.exactly,
            ),
        }
    }

    /// The occlusion ray of the hit `found` (shaded at `p`, its rays starting from `start`)
    /// towards `dir`, a direction of the sun's disc around `axis` (the sun in the grid):
    /// walked only as far as the sun's strip bounds
    /// ([`StripBounds`](crate::heightfield::StripBounds)) leave it unsettled, with the look-up
    /// counted.
    #[inline(always)]
    pub(super) fn occluded_beyond<S: Scalar>(
        &self,
        found: &Found<S>,
        ray: &Ray,
        p: DVec3,
        start: DVec3,
        (axis, dir): ([f64; 3], [f64; 3]),
    ) -> Occlusion {
        let strips = self.strips.as_ref().filter(|s| s.dir() == axis);
        let Some(strips) = strips.filter(|_| self.culling.far_bounds) else {
            return self.occluded(found, ray, p, dir, None);
        };
        let room = self.start_room::<S>(ray, start);
        let near = strips.clear_beyond(start.to_array(), dir, room);
        let mut occlusion = self.occluded(found, ray, p, dir, near);
        occlusion.counters.bound.record(near.is_none());
        occlusion
    }

    /// How far (in height) the true start of an occlusion ray from the hit of `ray` may lie
    /// below `start`, as computed in `f64`, in arithmetic `S`: the roundings that made it (the
    /// hit's `t` along the primary ray, then the point), with far more room than they need.
    pub(super) fn start_room<S: Scalar>(&self, ray: &Ray, start: DVec3) -> f64 {
        let o = ray.origin();
        let largest = (0..3).fold(0.0f64, |m, k| m.max(o[k].abs() + start[k].abs()));
        1024.0 * S::rounding_error(largest) * (1.0 + self.terrain.max_slope())
    }

    /// Whether a ray from the hit `found` of `ray` (shaded at `p`) towards `dir` touches the
    /// surface: the occlusion ray of shadows, soft shadows and sky light (not traced where it
    /// starts above the terrain and rises, and that rule is on), asking only up to `t_max`
    /// along the ray if given (see [`Tracer::within`]).
    pub(super) fn occluded<S: Scalar>(
        &self,
        found: &Found<S>,
        ray: &Ray,
        p: DVec3,
        dir: [f64; 3],
        t_max: Option<f64>,
    ) -> Occlusion {
        let tracer = self.tracer();
        let tracer = match t_max {
            Some(t) => tracer.within(t),
            None => tracer,
        };
        let skip_above = self.culling.above_terrain;
        match self.lighting.normals {
            // Smooth shading: from the curved surface the shading describes, which its own flat
            // triangle may cross (see `normals`), skipping that triangle; the base is flat.
            Normals::Smooth if found.face == Face::Terrain => {
                let start = normals::shadow_origin(self.terrain, found.cell, found.triangle, p);
                let from = Start::Near {
                    ray,
                    hit: found,
                    point: start.to_array(),
                };
                tracer.occluded(&from, dir, skip_above)
            }
            _ => tracer.occluded(&Start::Hit { ray, hit: found }, dir, skip_above),
        }
    }

    /// Where [`Shader::occluded`] starts its rays from the hit `found` shaded at `p`, in
    /// `f64`, before raising.
    pub(super) fn occlusion_start<S>(&self, found: &Found<S>, p: DVec3) -> DVec3 {
        match (self.lighting.normals, found.face) {
            (Normals::Smooth, Face::Terrain) => {
                normals::shadow_origin(self.terrain, found.cell, found.triangle, p)
            }
            _ => p,
        }
    }
}
