//! The contract every effect keeps: given a hit and the context its rays are cast in (the
//! terrain, how it is traced, the lighting), it casts what rays it needs and returns what it
//! found (its light, what became of its rays, their queries). The shader composes them.

use crate::arith::Scalar;
use crate::geometry::Ray;
use crate::render::context::{Context, OcclusionStart};
use crate::traverse::Found;
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
