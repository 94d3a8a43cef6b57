//! From a ray to a colour: the primary ray, the shadow ray only where it can change the pixel,
//! Lambert shading with an elevation ramp, sky and fog.

use super::contours::Contours;
use super::effects::{nanos_since, EffectTime, Reflection, SkyRays};
use super::gamma;
use super::scene::Lighting;
use super::shadow::Shadow;
use super::sky_gradient::{horizon, night_sky_colour, sky_colour, NIGHT_HORIZON};
use super::tally::{Counting, Tally};
use crate::arith::Scalar;
use crate::arith::{with_numbers, Arith, Generic, Numbers, WithNumbers};
use crate::geometry::Ray;
use crate::geometry::{Base, Face};
use crate::heightfield::{SkyBounds, StripBounds, Terrain};
use crate::traverse::{Clearance, Counters, Hit, Method, Profiles, Tracer, Wedges};
use glam::DVec3;
use std::cell::{Cell, RefCell};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

/// One traced sample, recorded on its own (see [`Tally`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    /// 0x00RRGGBB.
    pub rgb: u32,
    /// What the primary ray hit: the terrain or the base, if anything.
    pub hit: Option<Face>,
    /// What became of the shadow ray.
    pub shadow: Shadow,
    /// The primary ray's queries.
    pub primary: Counters,
    /// The shadow rays' queries (towards the sun, or its disc), or the reflected ray's.
    pub secondary: Counters,
    /// The sky-light rays.
    pub sky: SkyRays,
    /// What became of the reflection of water the pixel shows.
    pub reflection: Reflection,
    /// Intervals left a decision unsettled, and exact mode made it again exactly: it traced
    /// the pixel again in rationals, or cast only its shadow ray again, or decided one of the
    /// shadow ray's triangle tests on its own.
    pub redone: bool,
    /// The time its effects took.
    pub time: EffectTime,
}

/// Which shadow rays to leave out where they cannot change the pixel (all on by default;
/// switching one off must not change the image, only the work).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Culling {
    /// Leave out shadow rays of surfaces facing away from the sun ([`ShadowSkip::FacingAway`]).
    pub facing_away: bool,
    /// Leave out every shadow ray when the sun climbs steeper than any slope
    /// ([`ShadowSkip::NoShadowPossible`]).
    pub no_shadow_possible: bool,
    /// Leave out shadow rays that start above the terrain and rise
    /// ([`ShadowSkip::AboveTerrain`]).
    pub above_terrain: bool,
    /// Leave out soft-shadow and sky-light rays that climb more steeply than the terrain can
    /// rise around their start ([`ShadowSkip::HorizonClear`], [`SkyRays::cast`]).
    pub horizon_clear: bool,
    /// Leave out the soft-shadow rays of a cone provably blocked whole
    /// ([`SoftShadow::blocked`]).
    pub cone_blocked: bool,
    /// Walk only the first cells of a shadow or sky-light ray that bounds kept for the terrain
    /// ahead prove clear beyond them (the sun's [`StripBounds`], the sky's [`SkyBounds`]).
    pub far_bounds: bool,
    /// Start each camera ray's walk where its wedge's profile proves it clear of the surface,
    /// and settle the rays above their wedge's whole profile with no walk ([`Wedges`]).
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
            camera_clearance: true,
            near_walk: true,
        }
    }
}

/// Everything a pixel needs besides its ray.
#[derive(Clone)]
pub struct Shader<'a> {
    /// The terrain traced.
    pub terrain: &'a Terrain,
    /// Sun, shading and effects.
    pub lighting: Lighting,
    /// The traversal method of primary and shadow rays.
    pub method: Method,
    /// Which shadow rays to leave out.
    pub culling: Culling,
    /// The strip bounds of the sun's direction in the grid, where the scene has hard shadows
    /// and they can help (see [`Shader::new`]).
    pub(super) strips: Option<Arc<StripBounds>>,
    /// The sky's bounds around each block, where the scene has sky light (see
    /// [`Shader::new`]).
    pub(super) sky: Option<Arc<SkyBounds>>,
    /// The camera wedges' profiles made last, kept across a view's passes (clones share
    /// them).
    pub(super) wedges: Arc<Mutex<Option<Arc<Profiles>>>>,
    /// The base under the terrain its rays meet, as the lighting's style makes it.
    pub base: Option<Base>,
    /// Contour lines drawn on the terrain, as the camera sees them (none from [`Shader::new`]).
    pub contours: Option<Contours>,
}

impl<'a> Shader<'a> {
    /// A shader of `terrain` with the bounds its shadow and sky-light rays look up, from the
    /// terrain's own: the sun's strip bounds (built once per direction of the sun and kept
    /// while it stays) and the sky's (kept for the terrain's lifetime).
    pub fn new(terrain: &'a Terrain, lighting: Lighting, method: Method, culling: Culling) -> Self {
        let mut shader = Shader {
            terrain,
            lighting,
            method,
            culling,
            strips: None,
            sky: None,
            wedges: Arc::default(),
            base: lighting.base.for_terrain(terrain),
            contours: None,
        };
        if lighting.shadows && lighting.sun_up() && culling.far_bounds {
            shader.strips = terrain.strip_bounds(shader.grid_sun(), shader.sun_half());
        }
        if lighting.effects.sky_light && culling.far_bounds {
            shader.sky = terrain.sky_bounds(shader.sky_reach());
        }
        shader
    }

    /// The strip bounds the sun's shadow rays look up, if the scene has shadows and the
    /// bounds can help (see [`StripBounds::build`]).
    pub fn strip_bounds(&self) -> Option<&StripBounds> {
        self.strips.as_deref()
    }
}

impl<'a> Shader<'a> {
    /// Traces and shades one primary ray with the numbers `N` of an arithmetic (see
    /// [`with_numbers`](crate::arith::with_numbers)), from its [`Clearance`] if given (it
    /// touches nothing before); counts its rays into `counting` and returns its colour
    /// (0x00RRGGBB).
    #[inline(always)]
    pub fn sample<N: Numbers>(
        &self,
        ray: &Ray,
        clearance: Option<Clearance>,
        counting: &mut Counting<'_>,
    ) -> u32 {
        if !N::REDOES {
            return self.sample_into::<N, _>(ray, clearance, None, counting);
        }
        // Recorded apart first: a run the intervals leave unsettled counts nothing.
        let mut own = Sample::default();
        let rgb = self.sample_into::<N, _>(ray, clearance, None, &mut own);
        own.count_into(counting);
        rgb
    }

    /// [`Shader::sample`] recorded on its own: its colour, shadow and each kind of ray's
    /// queries.
    pub fn recorded<N: Numbers>(&self, ray: &Ray, clearance: Option<Clearance>) -> Sample {
        self.record::<N>(ray, clearance, None)
    }

    /// [`Shader::recorded`] in arithmetic `arith`, with the primary ray's hit (its `t` to the
    /// nearest `f64` of the traversal's, the point shaded, the cell and triangle; no exact
    /// `t`): what the viewer's probe shows of the very rays the renderer traces for a pixel.
    pub fn traced(&self, ray: &Ray, arith: Arith) -> (Sample, Option<Hit>) {
        self.traced_from(ray, arith, None)
    }

    /// [`Shader::traced`] from `clearance` (see [`Shader::sample`]).
    pub fn traced_from(
        &self,
        ray: &Ray,
        arith: Arith,
        clearance: Option<Clearance>,
    ) -> (Sample, Option<Hit>) {
        /// One sample, recorded, with the numbers of an arithmetic.
        struct Recorded<'s, 'a> {
            shader: &'s Shader<'a>,
            ray: &'s Ray,
            clearance: Option<Clearance>,
            hit: &'s Cell<Option<Hit>>,
        }
        impl WithNumbers for Recorded<'_, '_> {
            type Output = Sample;
            fn with<N: Numbers>(self) -> Sample {
                self.shader
                    .record::<N>(self.ray, self.clearance, Some(self.hit))
            }
        }
        let hit = Cell::new(None);
        let recorded = Recorded {
            shader: self,
            ray,
            clearance,
            hit: &hit,
        };
        let (sample, _) = with_numbers(arith, recorded);
        (sample, hit.take())
    }

    /// The tracer of this shader's rays: its method, walking near the surface as the culling
    /// says.
    pub fn tracer(&self) -> Tracer<'a> {
        Tracer::new(self.terrain, self.method)
            .walking_near(self.culling.near_walk)
            .with_base(self.base)
    }

    /// The wedges of camera rays from `eye` traced in `arith`, where the culling asks for them,
    /// the method starts its walks from a clearance and the arithmetic allows them (see
    /// [`Wedges::new`]). The profiles made last are kept for the next passes from the same
    /// eye.
    pub fn wedges(&self, eye: [f64; 3], arith: Arith) -> Option<Wedges<'a>> {
        if !(self.culling.camera_clearance && self.method.is_hierarchical()) {
            return None;
        }
        let mut kept = self.wedges.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(profiles) = kept.as_ref().filter(|p| p.are_for(eye, arith)) {
            return Some(Wedges::kept(self.terrain, Arc::clone(profiles)));
        }
        let wedges = Wedges::new(self.terrain, eye, arith)?;
        *kept = Some(Arc::clone(wedges.profiles()));
        Some(wedges)
    }

    /// [`Shader::recorded`], its hit kept in `keep` if given.
    fn record<N: Numbers>(
        &self,
        ray: &Ray,
        clearance: Option<Clearance>,
        keep: Option<&Cell<Option<Hit>>>,
    ) -> Sample {
        let mut sample = Sample::default();
        let rgb = self.sample_into::<N, _>(ray, clearance, keep, &mut sample);
        Sample { rgb, ..sample }
    }

    /// One sample's rays with the numbers `N`, counted into `tally`, its hit kept in `keep`
    /// if given; its colour.
    #[inline(always)]
    fn sample_into<N: Numbers, T: Tally>(
        &self,
        ray: &Ray,
        clearance: Option<Clearance>,
        keep: Option<&Cell<Option<Hit>>>,
        tally: &mut T,
    ) -> u32 {
        let pixel = Pixel {
            shader: self,
            ray,
            clearance,
            keep,
            tally: RefCell::new(tally),
        };
        let ran = N::run(&pixel);
        if ran.redone {
            pixel.tally.borrow_mut().redone();
        }
        ran.output
    }

    /// One sample's rays in arithmetic `S` alone, counted into `tally`, its hit kept in `keep`
    /// if given; its colour.
    #[inline(always)]
    fn traced_in<S: Scalar>(
        &self,
        ray: &Ray,
        clearance: Option<Clearance>,
        keep: Option<&Cell<Option<Hit>>>,
        tally: &mut impl Tally,
    ) -> u32 {
        let primary = self.tracer().trace::<S>(ray, clearance);
        tally.primary(&primary.counters, primary.hit.as_ref().map(|f| f.face));
        if let Some(water) = &self.lighting.effects.water {
            let field = self.terrain.field();
            let terrain_t = primary.hit.as_ref().map(|found| found.t.to_f64());
            if let Some(t) = water.crossing(ray.origin(), ray.dir(), terrain_t, field) {
                let start = Instant::now();
                let water = self.water_pixel::<S>(water, ray, t);
                tally.water(water.reflection, &water.counters);
                if water.redone {
                    tally.redone();
                }
                tally.time(&EffectTime {
                    water: nanos_since(start),
                    ..EffectTime::default()
                });
                return water.rgb;
            }
        }
        let Some(found) = primary.hit else {
            return self.sky_rgb(ray);
        };
        // Shading needs the point only in `f64`. Arithmetics that round shade the point they
        // computed; for the others, `t` to the nearest `f64` is as good and much cheaper than
        // the point in intervals, which only a shadow ray needs.
        let t = found.t.to_f64();
        let p = if S::EXACT {
            DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * t
        } else {
            let (o, d) = (ray.origin().map(S::from_f64), ray.dir().map(S::from_f64));
            DVec3::from(found.point(&o, &d).map(|c| c.to_f64()))
        };
        // (A hit on the base is shaded without the verdicts that hold only on the terrain.)
        let on_base = self.on_face(found.face);
        let this = on_base.as_ref().unwrap_or(self);
        let facing = this.facing(found.face, found.cell, found.triangle, p);
        let mut redone = false;
        // Effects are timed as they run; hard shadows are not, so a plain frame reads no clock.
        let mut time = EffectTime::default();
        let soft = self.lighting.effects.sun_angle_deg > 0.0;
        let shadow = if self.lighting.shadows {
            let start = soft.then(Instant::now);
            let (shadow, counters, exactly) = this.shadow::<S>(&found, ray, p, facing);
            tally.shadow(shadow, &counters);
            redone |= exactly;
            time.soft = start.map_or(0, nanos_since);
            shadow
        } else {
            Shadow::NotAsked
        };
        if let Some(keep) = keep {
            keep.set(Some(Hit {
                t,
                t_exact: None,
                point: p.to_array(),
                cell: [found.cell.0, found.cell.1],
                triangle: found.triangle,
                face: found.face,
            }));
        }
        let rgb = if self.lighting.effects.sky_light {
            let start = Instant::now();
            let (light, sky) = this.sky_light(&found, ray, p);
            tally.sky(&sky);
            redone |= sky.redone;
            time.sky = nanos_since(start);
            self.lit_rgb(ray, (found.face, p), t, facing, shadow, light)
        } else {
            self.surface_rgb(ray, (found.face, p), t, facing, shadow)
        };
        if redone {
            tally.redone();
        }
        if time != EffectTime::default() {
            tally.time(&time);
        }
        rgb
    }

    /// The colour of the surface at `p` on `face`, `t` along `ray`, facing the sun as
    /// [`Shader::facing`] says, in shadow or not as `shadow` says.
    #[inline(always)]
    pub fn surface_rgb(
        &self,
        ray: &Ray,
        (face, p): (Face, DVec3),
        t: f64,
        facing: f64,
        shadow: Shadow,
    ) -> u32 {
        let lit = match shadow {
            Shadow::Cast { shadowed: true } => 0.0,
            _ => facing.max(0.0),
        };
        let light = self.lighting.ambient + self.lighting.intensity * lit;
        let colour = self.marked_albedo(ray, (face, p), t) * light;
        self.fogged_rgb(ray, t, colour)
    }

    /// [`Shader::surface_rgb`] with soft shadows and sky light: `ambient` (a colour) instead of
    /// the scene's constant ambient term.
    fn lit_rgb(
        &self,
        ray: &Ray,
        (face, p): (Face, DVec3),
        t: f64,
        facing: f64,
        shadow: Shadow,
        ambient: DVec3,
    ) -> u32 {
        let lit = match shadow {
            Shadow::Cast { shadowed: true } => 0.0,
            Shadow::Soft(soft) => facing.max(0.0) * soft.visible(),
            _ => facing.max(0.0),
        };
        let light = ambient + DVec3::splat(self.lighting.intensity * lit);
        let colour = self.marked_albedo(ray, (face, p), t) * light;
        self.fogged_rgb(ray, t, colour)
    }

    /// A surface's linear `colour` seen along `ray` at `t`, through the fog, packed.
    #[inline(always)]
    pub(super) fn fogged_rgb(&self, ray: &Ray, t: f64, mut colour: DVec3) -> u32 {
        if self.lighting.fog > 0.0 {
            let distance = t * self.world_dir(ray.dir()).length();
            let clear = (-self.lighting.fog * distance).exp();
            colour = colour * clear + self.haze() * (1.0 - clear);
        }
        gamma::pack(colour.to_array())
    }

    /// The colour of a ray that misses the terrain.
    pub fn sky_rgb(&self, ray: &Ray) -> u32 {
        gamma::pack(self.sky(self.world_dir(ray.dir()).into()).to_array())
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
}

/// One sample's rays, in whichever arithmetic its [`Numbers`] run, counted into a tally.
struct Pixel<'s, 'a, 'c, T> {
    shader: &'s Shader<'a>,
    ray: &'s Ray,
    clearance: Option<Clearance>,
    /// Where to keep the primary ray's hit, if anywhere.
    keep: Option<&'s Cell<Option<Hit>>>,
    tally: RefCell<&'c mut T>,
}

impl<T: Tally> Generic for Pixel<'_, '_, '_, T> {
    type Output = u32;
    #[inline(always)]
    fn run<S: Scalar>(&self) -> u32 {
        let mut tally = self.tally.borrow_mut();
        // (A run again in rationals after intervals left a decision unsettled starts afresh.)
        tally.restart();
        self.shader
            .traced_in::<S>(self.ray, self.clearance, self.keep, &mut **tally)
    }
}
