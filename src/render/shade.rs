//! From a ray to a colour: the primary ray, the shadow ray only where it can change the pixel,
//! Lambert shading with an elevation ramp, sky and fog; the effects of the list in
//! [`effects`] asked in their stages (before the hit, at it), each changing the light.

use super::camera::Camera;
use super::context::{Context, Culling};
use super::contours::Contours;
use super::effects::pixel::per_sample;
use super::effects::{
    self, nanos_since, At, Cast, Effect, EffectTime, Light, Shadow, ShadowSkip, SoftShadows,
    SunShadow,
};
use super::gamma;
use super::sample::Sample;
use super::scene::Lighting;
use super::tally::{Counting, Tally};
use crate::arith::{with_numbers, Arith, Generic, Numbers, Scalar, WithNumbers};
use crate::geometry::{Face, Ray};
use crate::heightfield::Terrain;
use crate::traverse::{Clearance, Counters, Hit, Method, Profiles, Wedges};
use glam::DVec3;
use std::cell::{Cell, RefCell};
use std::ops::{Deref, DerefMut};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

/// Everything a pixel needs besides its ray: the context its rays are cast in, the camera
/// wedges and the contour lines; composes the effects a scene asks for into a colour.
#[derive(Clone)]
pub struct Shader<'a> {
    /// The terrain, how it is traced, the lighting and the bounds kept for it.
    pub cx: Context<'a>,
    /// The camera wedges' profiles made last, kept across a view's passes (clones share
    /// them).
    wedges: Arc<Mutex<Option<Arc<Profiles>>>>,
    /// Contour lines drawn on the terrain, as the camera sees them (none from [`Shader::new`]).
    pub contours: Option<Contours>,
}

impl<'a> Deref for Shader<'a> {
    type Target = Context<'a>;
    fn deref(&self) -> &Context<'a> {
        &self.cx
    }
}

impl DerefMut for Shader<'_> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.cx
    }
}

impl<'a> Shader<'a> {
    /// A shader of `terrain` in the context [`Context::new`] makes.
    pub fn new(terrain: &'a Terrain, lighting: Lighting, method: Method, culling: Culling) -> Self {
        Shader {
            cx: Context::new(terrain, lighting, method, culling),
            wedges: Arc::default(),
            contours: None,
        }
    }

    /// This shader with `contours` drawn as `camera` (in grid coordinates) sees them.
    pub fn with_contours(mut self, contours: Option<Contours>, camera: &Camera) -> Self {
        self.contours = contours.map(|c| c.seen_by(camera));
        self
    }

    /// This shader for one sample of a pixel's: each sample's share of the pixel's effect
    /// rays (see [`per_sample`](super::effects::pixel::per_sample)).
    pub fn per_sample(&self) -> Shader<'a> {
        let mut shader = self.clone();
        shader.cx.lighting.effects = per_sample(&self.lighting.effects);
        shader
    }

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
        gamma::pack(self.linear_sample::<N>(ray, clearance, counting).to_array())
    }

    /// [`Shader::sample`]'s colour in linear light, before it is packed into bytes: what
    /// 16-bit output is made from.
    #[inline(always)]
    pub fn linear_sample<N: Numbers>(
        &self,
        ray: &Ray,
        clearance: Option<Clearance>,
        counting: &mut Counting<'_>,
    ) -> DVec3 {
        if !N::REDOES {
            return self.sample_into::<N, _>(ray, clearance, None, counting);
        }
        // Recorded apart first: a run the intervals leave unsettled counts nothing.
        let mut own = Sample::default();
        let colour = self.sample_into::<N, _>(ray, clearance, None, &mut own);
        own.count_into(counting);
        colour
    }

    /// [`Shader::sample`] recorded on its own: its colour, shadow and each kind of ray's
    /// queries.
    pub fn recorded<N: Numbers>(&self, ray: &Ray, clearance: Option<Clearance>) -> Sample {
        self.record::<N>(ray, clearance, None).0
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
        let (sample, hit, _) = self.traced_linear(ray, arith, clearance);
        (sample, hit)
    }

    /// [`Shader::traced_from`] with the sample's colour in linear light as a display shows it
    /// (each channel clamped to [0, 1]): what a pixel's samples are averaged as.
    pub fn traced_linear(
        &self,
        ray: &Ray,
        arith: Arith,
        clearance: Option<Clearance>,
    ) -> (Sample, Option<Hit>, DVec3) {
        /// One sample, recorded, with the numbers of an arithmetic.
        struct Recorded<'s, 'a> {
            shader: &'s Shader<'a>,
            ray: &'s Ray,
            clearance: Option<Clearance>,
            hit: &'s Cell<Option<Hit>>,
        }
        impl WithNumbers for Recorded<'_, '_> {
            type Output = (Sample, DVec3);
            fn with<N: Numbers>(self) -> (Sample, DVec3) {
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
        let ((sample, colour), _) = with_numbers(arith, recorded);
        (sample, hit.take(), gamma::shown(colour.to_array()).into())
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

    /// [`Shader::recorded`], its hit kept in `keep` if given, with its linear colour.
    fn record<N: Numbers>(
        &self,
        ray: &Ray,
        clearance: Option<Clearance>,
        keep: Option<&Cell<Option<Hit>>>,
    ) -> (Sample, DVec3) {
        let mut sample = Sample::default();
        let colour = self.sample_into::<N, _>(ray, clearance, keep, &mut sample);
        let rgb = gamma::pack(colour.to_array());
        (Sample { rgb, ..sample }, colour)
    }

    /// One sample's rays with the numbers `N`, counted into `tally`, its hit kept in `keep`
    /// if given; its linear colour.
    #[inline(always)]
    fn sample_into<N: Numbers, T: Tally>(
        &self,
        ray: &Ray,
        clearance: Option<Clearance>,
        keep: Option<&Cell<Option<Hit>>>,
        tally: &mut T,
    ) -> DVec3 {
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
    /// if given; its linear colour.
    #[inline(always)]
    fn traced_in<S: Scalar>(
        &self,
        ray: &Ray,
        clearance: Option<Clearance>,
        keep: Option<&Cell<Option<Hit>>>,
        tally: &mut impl Tally,
    ) -> DVec3 {
        let primary = self.tracer().trace::<S>(ray, clearance);
        tally.primary(&primary.counters, primary.hit.as_ref().map(|f| f.face));
        // Effects are timed as they run; hard shadows are not, so a plain frame reads no clock.
        let mut time = EffectTime::default();
        let shown = effects::before_hit::<S>(&self.cx, ray, primary.hit.as_ref(), tally, &mut time);
        if let Some((colour, redone)) = shown {
            if redone {
                tally.redone();
            }
            tally.time(&time);
            return colour;
        }
        let Some(found) = primary.hit else {
            return self.sky_seen(ray);
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
        let this = on_base.as_ref().unwrap_or(&self.cx);
        let at = At::new(&found, ray, p);
        let facing = this.facing(found.face, found.cell, found.triangle, p);
        let mut redone = false;
        let soft = self.lighting.effects.sun_angle_deg > 0.0;
        let shadow = if self.lighting.shadows {
            let start = soft.then(Instant::now);
            let (shadow, counters, exactly) = shadow(this, &at, facing);
            tally.shadow(shadow, &counters);
            redone |= exactly;
            time.soft_shadow = start.map_or(0, nanos_since);
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
        let mut light = Light {
            sun: shadow.sun_seen(),
            ambient: DVec3::splat(self.lighting.ambient),
        };
        redone |= effects::at_hit::<S>(this, &at, &mut light, tally, &mut time);
        let colour = self.lit_colour(ray, (found.face, p), t, facing, light);
        if redone {
            tally.redone();
        }
        if time != EffectTime::default() {
            tally.time(&time);
        }
        colour
    }

    /// The surface's colour at `p` on `face` before it is lit ([`Context::albedo`]), with
    /// the contour lines over it where asked, `p` seen `t` along `ray`.
    #[inline(always)]
    fn marked_albedo(&self, ray: &Ray, (face, p): (Face, DVec3), t: f64) -> DVec3 {
        let albedo = self.albedo(face, p);
        match self.contours.filter(|_| face == Face::Terrain) {
            Some(contours) => contours.mark(self.terrain, albedo, ray, p, t),
            None => albedo,
        }
    }

    /// The colour of the surface at `p` on `face`, `t` along `ray`, facing the sun as
    /// [`Context::facing`] says, in shadow or not as `shadow` says; packed.
    #[inline(always)]
    pub fn surface_rgb(
        &self,
        ray: &Ray,
        at: (Face, DVec3),
        t: f64,
        facing: f64,
        shadow: Shadow,
    ) -> u32 {
        let light = Light {
            sun: shadow.sun_seen(),
            ambient: DVec3::splat(self.lighting.ambient),
        };
        gamma::pack(self.lit_colour(ray, at, t, facing, light).to_array())
    }

    /// The colour of the surface at `p` on `face`, `t` along `ray`, facing the sun as
    /// [`Context::facing`] says, lit by `light` (the share of the sun its shadow and the
    /// effects leave, and the ambient light: the scene's term, or what an effect such as sky
    /// light puts in its place); in linear light.
    #[inline(always)]
    fn lit_colour(
        &self,
        ray: &Ray,
        (face, p): (Face, DVec3),
        t: f64,
        facing: f64,
        light: Light,
    ) -> DVec3 {
        let lit = facing.max(0.0) * light.sun;
        let light = light.ambient + DVec3::splat(self.lighting.intensity * lit);
        let colour = self.marked_albedo(ray, (face, p), t) * light;
        self.fogged_rgb(ray, t, colour)
    }
}

/// The shadow at `at` in `cx` where a shadow ray can change the pixel: the sun's disc's, or
/// its point's.
#[inline(always)]
fn shadow<S: Scalar>(cx: &Context<'_>, at: &At<'_, S>, facing: f64) -> Cast {
    if cx.culling.facing_away && facing <= 0.0 {
        let skip = Shadow::Skipped(ShadowSkip::FacingAway);
        return (skip, Counters::default(), false);
    }
    if cx.lighting.effects.sun_angle_deg > 0.0 {
        SoftShadows.cast(cx, at)
    } else {
        SunShadow.cast(cx, at)
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
    type Output = DVec3;
    #[inline(always)]
    fn run<S: Scalar>(&self) -> DVec3 {
        let mut tally = self.tally.borrow_mut();
        // (A run again in rationals after intervals left a decision unsettled starts afresh.)
        tally.restart();
        self.shader
            .traced_in::<S>(self.ray, self.clearance, self.keep, &mut **tally)
    }
}
