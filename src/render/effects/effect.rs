//! The contract every effect keeps: given a hit and the context its rays are cast in (the
//! terrain, how it is traced, the lighting), it casts what rays it needs and returns what it
//! found (its light, what became of its rays, their queries). The shader composes them.

use crate::arith::Scalar;
use crate::geometry::Ray;
use crate::render::context::Context;
use crate::traverse::Found;
use glam::DVec3;

/// An effect at a hit on the surface.
pub trait Effect {
    /// What the effect found at a hit.
    type Outcome;
    /// Casts the effect's rays from the hit `at` in the context `cx`, in arithmetic `S`.
    fn cast<S: Scalar>(&self, cx: &Context<'_>, at: &At<'_, S>) -> Self::Outcome;
}

/// A hit on the surface an effect starts from: the primary ray's hit `found`, the ray, and
/// the point shaded (in `f64`).
#[derive(Clone, Copy)]
pub struct At<'h, S> {
    /// The primary ray's hit.
    pub found: &'h Found<S>,
    /// The primary ray.
    pub ray: &'h Ray,
    /// The point shaded.
    pub p: DVec3,
}
