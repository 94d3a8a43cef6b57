//! The contracts every effect keeps: given a hit and the context its rays are cast in (the
//! terrain, how it is traced, the lighting), it casts what rays it needs and returns what it
//! found ([`Effect`]); it says what it counts over a frame and how that is reported
//! ([`Counted`]); and it says where in a sample the shader asks it and how its outcome
//! changes the colour ([`BeforeHit`], [`AtHit`]). The list in [`super`] registers it.

use super::settings::Effects;
use crate::arith::Scalar;
use crate::geometry::Ray;
use crate::render::context::{Context, OcclusionStart};
use crate::traverse::{Counters, Found};
use glam::DVec3;
use std::cell::OnceCell;

/// An effect at a hit on the surface.
pub trait Effect {
    /// What the effect found at a hit.
    type Outcome;
    /// Casts the effect's rays from the hit `at` in the context `cx`, in arithmetic `S`.
    fn cast<S: Scalar>(&self, cx: &Context<'_>, at: &At<'_, S>) -> Self::Outcome;
}

/// A hit on the surface an effect starts from: the primary ray's hit `found`, the ray, and
/// the point shaded (in `f64`); and where its occlusion rays start, worked out when an effect
/// first asks and shared by the others.
pub struct At<'h, S> {
    /// The primary ray's hit.
    pub found: &'h Found<S>,
    /// The primary ray.
    pub ray: &'h Ray,
    /// The point shaded.
    pub p: DVec3,
    start: OnceCell<OcclusionStart<'h, S>>,
}

impl<'h, S: Scalar> At<'h, S> {
    /// The hit `found` of `ray`, shaded at `p`.
    pub fn new(found: &'h Found<S>, ray: &'h Ray, p: DVec3) -> Self {
        At {
            found,
            ray,
            p,
            start: OnceCell::new(),
        }
    }

    /// Where the hit's occlusion rays start, in the context `cx` (the same for every context
    /// of one frame: the terrain, its base and the shading decide it).
    pub(super) fn start(&self, cx: &Context<'_>) -> &OcclusionStart<'h, S> {
        self.start
            .get_or_init(|| cx.occlusion_start(self.found, self.ray, self.p))
    }
}

/// The light at a hit as the effects leave it: the share of the sun seen (its shadow's, then
/// any effect's that dims it) and the ambient light (the scene's constant term, or what an
/// effect such as sky light puts in its place).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// The share of the sun's light that reaches the point, 0 to 1.
    pub sun: f64,
    /// The light from everywhere but the sun, per channel.
    pub ambient: DVec3,
}

/// What an effect counts over a frame and how the frame reports it: every registered effect
/// (see [`super`]) keeps this.
pub trait Counted {
    /// Its key in the statistics: in `--stats` JSON under `effects` and `thread_time_ms`.
    const NAME: &'static str;
    /// What the viewer's Effects panel calls it.
    const LABEL: &'static str;
    /// Its word in `bench effects`' columns and keys (`<word> rays/px`, `<word>_culled`).
    const WORD: &'static str;
    /// What it did at one sample (its default: nothing asked).
    type Outcome: Copy + std::fmt::Debug + Default + PartialEq;
    /// Its counters over a frame: summed field by field (`derive(AddAssign)`) and reported
    /// by their names (`derive(Serialize)`), so a new counter is one field.
    type Stats: Copy
        + std::fmt::Debug
        + Default
        + PartialEq
        + Eq
        + std::ops::AddAssign
        + serde::Serialize;
    /// Counts one sample's `outcome` into `stats`.
    fn count(outcome: &Self::Outcome, stats: &mut Self::Stats);
    /// The rays it cast in a frame (each kind's share of the rays).
    fn rays(stats: &Self::Stats) -> u64;
    /// The share of the rays it could have cast that it left out, where it asked any; the
    /// frame's other counts in `frame`.
    fn culled(stats: &Self::Stats, frame: &Around<'_>) -> Option<f64>;
}

/// What a frame counted besides an effect's own counters, for its shares.
pub struct Around<'a> {
    /// The effects the frame was rendered with.
    pub asked: &'a Effects,
    /// Shadow rays cast towards the sun's point (hard shadows).
    pub shadow_rays: u64,
    /// Points whose shadow the sun's rules settled whole, with no ray (every reason but
    /// facing away).
    pub settled: u64,
}

/// An effect the shader asks at each sample, beyond what it counts: whether the scene asks
/// for it. [`BeforeHit`] or [`AtHit`] says where it acts.
pub trait Sampled: Counted {
    /// Whether the scene of `cx` asks for it.
    fn asked(cx: &Context<'_>) -> bool;
}

/// An effect a camera ray may meet before the terrain, in the terrain's stead (water). It
/// leaves no hit to cast a shadow ray from, so its rays' queries take the shadow rays' place:
/// the sample's secondary queries, counted with the shadow rays' in the frame's totals.
pub trait BeforeHit: Sampled {
    /// What the effect shows along `ray` before the primary ray's hit `found` (if any), where
    /// it shows; traced in `S`.
    fn before_hit<S: Scalar>(
        cx: &Context<'_>,
        ray: &Ray,
        found: Option<&Found<S>>,
    ) -> Option<Shown<Self::Outcome>>;
}

/// What an effect before the hit shows of a sample.
pub struct Shown<O> {
    /// The sample's linear colour, through the fog.
    pub colour: DVec3,
    /// What the effect did.
    pub outcome: O,
    /// Its rays' queries.
    pub queries: Counters,
    /// Exact mode decided one of its tests again exactly.
    pub redone: bool,
}

/// An effect that changes the light at a hit on the surface (sky light). Its outcome keeps
/// its rays' queries, which only its own counters sum.
pub trait AtHit: Sampled {
    /// Casts its rays from `at` in `cx`, in `S`, and changes `light` as they say.
    fn at_hit<S: Scalar>(cx: &Context<'_>, at: &At<'_, S>, light: &mut Light) -> Self::Outcome;
    /// Its rays' queries at a sample (for heat maps).
    fn queries(outcome: &Self::Outcome) -> Counters;
    /// Exact mode decided one of its tests again exactly (see
    /// [`Sample::redone`](crate::render::Sample::redone)).
    fn redone(outcome: &Self::Outcome) -> bool;
}

/// One effect of the list as a frame counted it (see [`Counted`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// [`Counted::NAME`].
    pub name: &'static str,
    /// [`Counted::LABEL`].
    pub label: &'static str,
    /// [`Counted::WORD`].
    pub word: &'static str,
    /// [`Counted::rays`].
    pub rays: u64,
    /// [`Counted::culled`].
    pub culled: Option<f64>,
    /// Its counters by name, as `--stats` reports them.
    pub counters: serde_json::Value,
}
