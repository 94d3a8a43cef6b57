//! What effect rays are cast against: the terrain, how it is traced, the lighting, which rays
//! to leave out and the bounds kept for the terrain ahead; the occlusion ray shadows, soft
//! shadows and sky light share, and the colours of the sky and the fog.

use super::effects::SunDisc;
use super::gamma;
use super::normals;
use super::scene::{Lighting, Normals};
use super::sky_gradient::{horizon, night_sky_colour, sky_colour, NIGHT_HORIZON};
use crate::arith::Scalar;
use crate::geometry::{Base, Face, Ray};
use crate::heightfield::{NearStart, SkyBounds, StripBounds, Terrain};
use crate::traverse::{Counters, Departure, Found, Method, Occlusion, Start, Tracer};
use glam::DVec3;
use std::borrow::Cow;
use std::sync::Arc;

/// Which shadow rays to leave out where they cannot change the pixel (all on by default;
/// switching one off must not change the image, only the work).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Culling {
    /// Leave out shadow rays of surfaces facing away from the sun ([`ShadowSkip::FacingAway`](crate::render::ShadowSkip::FacingAway)).
    pub facing_away: bool,
    /// Leave out every shadow ray when the sun climbs steeper than any slope
    /// ([`ShadowSkip::NoShadowPossible`](crate::render::ShadowSkip::NoShadowPossible)).
    pub no_shadow_possible: bool,
    /// Leave out shadow rays that start above the terrain and rise
    /// ([`ShadowSkip::AboveTerrain`](crate::render::ShadowSkip::AboveTerrain)).
    pub above_terrain: bool,
    /// Leave out soft-shadow and sky-light rays that climb more steeply than the terrain can
    /// rise around their start ([`ShadowSkip::HorizonClear`](crate::render::ShadowSkip::HorizonClear), [`SkyRays::cast`](crate::render::SkyRays::cast)).
    pub horizon_clear: bool,
    /// Leave out the soft-shadow rays of a cone provably blocked whole
    /// ([`SoftShadow::blocked`](crate::render::effects::SoftShadow::blocked)).
    pub cone_blocked: bool,
    /// Walk only the first cells of a shadow or sky-light ray that bounds kept for the terrain
    /// ahead prove clear beyond them (the sun's [`StripBounds`], the sky's [`SkyBounds`]).
    pub far_bounds: bool,
    /// Settle the sky-light rays the kept bounds leave unsettled as blocked where a probe
    /// finds them under the surface ([`SkyRays::probed`](crate::render::SkyRays::probed)).
    pub probes: bool,
    /// Settle the first cells of shadow, soft-shadow and sky-light rays that start on their
    /// own flat triangle and climb faster than the surface can rise near it ([`NearStart`]).
    pub near_slopes: bool,
    /// Start each camera ray's walk where its wedge's profile proves it clear of the surface,
    /// and settle the rays above their wedge's whole profile with no walk ([`Wedges`](crate::traverse::Wedges)).
    pub camera_clearance: bool,
    /// Walk the first cells of camera rays from their clearance one by one, not down the
    /// mipmap ([`Tracer::walking_near`]).
    pub near_walk: bool,
}

impl Default for Culling {
    fn default() -> Self {
        Culling {
            facing_away: true,
            no_shadow_possible: true,
            above_terrain: true,
            horizon_clear: true,
            cone_blocked: true,
            far_bounds: true,
            probes: true,
            near_slopes: true,
            camera_clearance: true,
            near_walk: true,
        }
    }
}

/// The context an effect casts its rays in (see [`crate::render::effects`]).
#[derive(Clone)]
pub struct Context<'a> {
    /// The terrain traced.
    pub terrain: &'a Terrain,
    /// Sun, shading and effects.
    pub lighting: Lighting,
    /// The traversal method of primary and shadow rays.
    pub method: Method,
    /// Which shadow rays to leave out.
    pub culling: Culling,
    /// The strip bounds of the sun's direction in the grid, where the scene has hard shadows
    /// and they can help (see [`Context::new`]).
    pub(super) strips: Option<Arc<StripBounds>>,
    /// The sky's bounds around each block, where the scene has sky light (see
    /// [`Context::new`]).
    pub(super) sky: Option<Arc<SkyBounds>>,
    /// The base under the terrain its rays meet, as the lighting's style makes it.
    pub base: Option<Base>,
    /// The sun's disc, where the scene has soft shadows (see [`Context::sun_disc`]).
    pub(super) disc: Option<SunDisc>,
}

impl<'a> Context<'a> {
    /// The context of `terrain` with the bounds its shadow and sky-light rays look up, from
    /// the terrain's own: the sun's strip bounds (built once per direction of the sun and
    /// kept while it stays) and the sky's (kept for the terrain's lifetime).
    pub fn new(terrain: &'a Terrain, lighting: Lighting, method: Method, culling: Culling) -> Self {
        let mut cx = Context {
            terrain,
            lighting,
            method,
            culling,
            strips: None,
            sky: None,
            base: lighting.base.for_terrain(terrain),
            disc: None,
        };
        let angle = lighting.effects.sun_angle_deg;
        if lighting.shadows && angle > 0.0 {
            cx.disc = Some(SunDisc::new(
                lighting.sun,
                angle,
                cx.grid_dir(lighting.sun.into()),
            ));
        }
        if lighting.shadows && lighting.sun_up() && culling.far_bounds {
            cx.strips = terrain.strip_bounds(cx.grid_sun(), cx.sun_half());
        }
        if lighting.effects.sky_light && culling.far_bounds {
            cx.sky = terrain.sky_bounds(cx.sky_reach());
        }
        cx
    }

    /// The strip bounds the sun's shadow rays look up, if the scene has shadows and the
    /// bounds can help (see [`StripBounds::build`]).
    pub fn strip_bounds(&self) -> Option<&StripBounds> {
        self.strips.as_deref()
    }

    /// The sun's disc its soft shadows are drawn over: the one made with the context, unless
    /// the lighting has changed since.
    pub(super) fn sun_disc(&self) -> Cow<'_, SunDisc> {
        let (sun, angle) = (self.lighting.sun, self.lighting.effects.sun_angle_deg);
        match self.disc.as_ref().filter(|disc| disc.is_for(sun, angle)) {
            Some(disc) => Cow::Borrowed(disc),
            None => Cow::Owned(SunDisc::new(sun, angle, self.grid_dir(sun.into()))),
        }
    }

    /// The tracer of this shader's rays: its method, walking near the surface as the culling
    /// says.
    pub fn tracer(&self) -> Tracer<'a> {
        Tracer::new(self.terrain, self.method)
            .walking_near(self.culling.near_walk)
            .with_base(self.base)
    }

    /// How far sky-light rays look for terrain, horizontally, in grid units: a world unit
    /// horizontally spans at most this many.
    pub(in crate::render) fn sky_reach(&self) -> f64 {
        let scale = self.terrain.world_from_grid().unwrap_or([1.0; 3]);
        self.lighting.effects.sky_distance / scale[0].min(scale[1])
    }

    /// A surface's linear `colour` seen along `ray` at `t`, through the fog: still linear, so
    /// that the pixel packs it to bytes or to 16-bit words as its output asks.
    #[inline(always)]
    pub(super) fn fogged_rgb(&self, ray: &Ray, t: f64, mut colour: DVec3) -> DVec3 {
        if self.lighting.fog > 0.0 {
            let distance = t * self.world_dir(ray.dir()).length();
            let clear = (-self.lighting.fog * distance).exp();
            colour = colour * clear + self.haze() * (1.0 - clear);
        }
        colour
    }

    /// The colour of a ray that misses the terrain, packed.
    pub fn sky_rgb(&self, ray: &Ray) -> u32 {
        gamma::pack(self.sky_seen(ray).to_array())
    }

    /// The linear colour of a ray that misses the terrain.
    #[inline(always)]
    pub(super) fn sky_seen(&self, ray: &Ray) -> DVec3 {
        self.sky(self.world_dir(ray.dir()).into())
    }

    /// The direction towards the sun in grid coordinates, where shadow rays are traced.
    pub(crate) fn grid_sun(&self) -> [f64; 3] {
        self.grid_dir(DVec3::from(self.lighting.sun)).into()
    }

    /// The sun disc's half-angle (radians) in the grid, with room for rounding: every soft
    /// shadow's direction lies within it of [`Shader::grid_sun`]; 0 for hard shadows.
    pub(crate) fn sun_half(&self) -> f64 {
        let angle = self.lighting.effects.sun_angle_deg;
        match angle > 0.0 {
            true => (angle / 2.0).to_radians() * (1.0 + 1e-6),
            false => 0.0,
        }
    }

    /// A unit direction in the world as a unit direction in grid coordinates, where rays are
    /// traced (the same vector where cells are square).
    pub(crate) fn grid_dir(&self, dir: DVec3) -> DVec3 {
        match self.terrain.world_from_grid() {
            Some(scale) => (dir / DVec3::from(scale)).normalize_or(dir),
            None => dir,
        }
    }

    /// A ray direction in grid coordinates as a direction in the world.
    pub(super) fn world_dir(&self, dir: [f64; 3]) -> DVec3 {
        match self.terrain.world_from_grid() {
            Some(scale) => DVec3::from(dir) * DVec3::from(scale),
            None => DVec3::from(dir),
        }
    }

    /// Sky gradient for rays that miss: the day's, or the night's once the sun is down.
    pub(super) fn sky(&self, dir: [f64; 3]) -> DVec3 {
        if self.lighting.sun_up() {
            sky_colour(DVec3::from(dir))
        } else {
            night_sky_colour(DVec3::from(dir))
        }
    }

    /// The colour fog fades to: the sky's at the horizon.
    fn haze(&self) -> DVec3 {
        if self.lighting.sun_up() {
            horizon()
        } else {
            NIGHT_HORIZON
        }
    }

    /// The occlusion ray from `start` towards `dir`, a direction of the sun's disc around
    /// `axis` (the sun in the grid): walked only as far as the sun's strip bounds
    /// ([`StripBounds`](crate::heightfield::StripBounds)) leave it unsettled, with the look-up
    /// counted.
    #[inline(always)]
    pub(super) fn occluded_beyond<S: Scalar>(
        &self,
        start: &OcclusionStart<'_, S>,
        (axis, dir): ([f64; 3], [f64; 3]),
    ) -> Occlusion {
        let Some(strips) = self.strips_along(axis) else {
            return self.occluded(start, dir, None);
        };
        let point = start.point.to_array();
        let near = strips.clear_beyond(point, dir, start.room);
        // Clear beyond the look-up, and before it by the slopes around a start on its own
        // triangle: no walk at all (a ray that starts above the terrain and rises is left to
        // the rule that skips it).
        let (_, z_max) = self.terrain.z_range();
        let skipped = self.culling.above_terrain && dir[2] > 0.0 && point[2] > z_max;
        if let (Some(t), Some(from), false) = (near, start.near, skipped) {
            if strips.clear_before(point, dir, t, from) {
                let mut counters = Counters::default();
                counters.bound.record(false);
                return Occlusion {
                    occluded: Some(false),
                    counters,
                    cells: Vec::new(),
                    exactly: false,
                };
            }
        }
        let mut occlusion = self.occluded(start, dir, near);
        occlusion.counters.bound.record(near.is_none());
        occlusion
    }

    /// The kept strip bounds of the disc around `axis`, where the rules use them.
    #[inline(always)]
    fn strips_along(&self, axis: [f64; 3]) -> Option<&StripBounds> {
        let strips = self.strips.as_deref().filter(|s| s.dir() == axis);
        strips.filter(|_| self.culling.far_bounds)
    }

    /// Whether every ray of the sun's disc around `axis` from `start` (each climbing at least
    /// `lowest_tan` per cell horizontally) is certainly clear, with no walk: the kept strip
    /// bounds clear them all beyond their first cells, and the slopes around a start on its
    /// own triangle those cells.
    pub(super) fn disc_clear<S: Scalar>(
        &self,
        start: &OcclusionStart<'_, S>,
        axis: [f64; 3],
        lowest_tan: f64,
    ) -> bool {
        let (Some(strips), Some(near)) = (self.strips_along(axis), start.near) else {
            return false;
        };
        let point = start.point.to_array();
        strips
            .disc_clear_beyond(point, start.room)
            .is_some_and(|distance| strips.outclimbed(point, lowest_tan, distance, near))
    }

    /// Whether a ray from `start` towards `dir` touches the surface: the occlusion ray of
    /// shadows, soft shadows and sky light (not traced where it starts above the terrain and
    /// rises, and that rule is on), asking only up to `t_max` along the ray if given (see
    /// [`Tracer::within`]).
    pub(super) fn occluded<S: Scalar>(
        &self,
        start: &OcclusionStart<'_, S>,
        dir: [f64; 3],
        t_max: Option<f64>,
    ) -> Occlusion {
        self.occluded_between(start, dir, (0.0, t_max))
    }

    /// [`Context::occluded`] for a ray known (by the kept bounds) to touch no triangle but
    /// its own before `clear` (see [`Tracer::clear_before`]).
    pub(super) fn occluded_between<S: Scalar>(
        &self,
        start: &OcclusionStart<'_, S>,
        dir: [f64; 3],
        (clear, t_max): (f64, Option<f64>),
    ) -> Occlusion {
        let tracer = self.tracer().clear_before(clear);
        let tracer = match t_max {
            Some(t) => tracer.within(t),
            None => tracer,
        };
        tracer.occluded_from(&start.departure, dir, self.culling.above_terrain)
    }

    /// Where the occlusion rays of the hit `found` of `ray`, shaded at `p`, start.
    pub(super) fn occlusion_start<'h, S: Scalar>(
        &self,
        found: &'h Found<S>,
        ray: &'h Ray,
        p: DVec3,
    ) -> OcclusionStart<'h, S> {
        // Smooth shading: from the curved surface the shading describes, which its own flat
        // triangle may cross (see `normals`), skipping that triangle; the base is flat.
        let near = match (self.lighting.normals, found.face) {
            (Normals::Smooth, Face::Terrain) => Some(normals::shadow_origin(
                self.terrain,
                found.cell,
                found.triangle,
                p,
            )),
            _ => None,
        };
        let point = near.unwrap_or(p);
        // How far (in height) the true start may lie below `point`, as computed in `f64`, in
        // arithmetic `S`: the roundings that made it (the hit's `t` along the primary ray,
        // then the point), with far more room than they need.
        let o = ray.origin();
        let largest = (0..3).fold(0.0f64, |m, k| m.max(o[k].abs() + point[k].abs()));
        let room = 1024.0 * S::rounding_error(largest) * (1.0 + self.terrain.max_slope());
        let from = match near {
            Some(point) => Start::Near {
                ray,
                hit: found,
                point: point.to_array(),
            },
            None => Start::Hit { ray, hit: found },
        };
        // A start on its own flat triangle, well inside it, whose rays' first cells the
        // slopes around it may settle.
        let on_own = near.is_none() && found.face == Face::Terrain && self.culling.near_slopes;
        let own = (found.cell, found.triangle);
        OcclusionStart {
            point,
            room,
            near: on_own
                .then(|| NearStart::on_triangle(self.terrain, own, point.to_array(), room))
                .flatten(),
            departure: self.tracer().departure(&from),
        }
    }
}

/// Where the occlusion rays of one hit start: the point the bounds are asked about, and the
/// rays' [`Departure`], worked out once for the hit's rays (the sun's, the soft shadow's and
/// the sky light's).
pub(crate) struct OcclusionStart<'h, S> {
    /// Where the rays start, in `f64`, before raising.
    pub(super) point: DVec3,
    /// How far (in height) the true start may lie below `point`.
    pub(super) room: f64,
    /// Where the start lies well inside its own flat triangle.
    pub(super) near: Option<NearStart>,
    departure: Departure<'h, S>,
}
