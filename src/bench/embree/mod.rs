//! Embree 3, a general-purpose CPU ray tracer and the usual yardstick of CPU ray tracing
//! speed, on the same terrain and view as heightray, so `bench speed --embree` measures both
//! in one run on one machine (built with the `embree` feature, which links Debian's
//! `libembree3`).
//!
//! The terrain goes to Embree as what it is, two triangles per cell with heightray's diagonal
//! (the surface contract, [`crate::geometry`]), its corners the samples in `f32`
//! (`scene`). A frame does what heightray's does: a ray per pixel through
//! [`Camera::ray`](crate::render::Camera::ray), the hit shaded by heightray's
//! [`Shader`](crate::render::Shader) from the hit's cell and triangle, and a shadow ray
//! where the surface faces the sun (`pixel`). Embree traces the rays one at a time
//! (`rtcIntersect1`, `rtcOccluded1`: `single`) or in packets of 8 or 16 (`packets`). So
//! the images can be compared pixel by pixel, and the times differ only in the tracing.

mod effects;
mod ffi;
mod hard_cases;
mod packets;
mod pixel;
mod scene;
mod single;
#[cfg(test)]
mod tests;

pub use hard_cases::{hard_cases_in_f32, F32_TOLERANCE};
pub use scene::EmbreeScene;

use crate::render::{Frame, Renderer};
use glam::DVec3;
use std::sync::Arc;
use thiserror::Error;

/// Why Embree's scene could not be made.
#[derive(Debug, Error)]
pub enum EmbreeError {
    /// An Embree call failed.
    #[error("Embree failed to {what} (RTCError {code})")]
    Call {
        /// What the call was to do.
        what: &'static str,
        /// Embree's `RTCError` code.
        code: u32,
    },
    /// The terrain (width and height in samples) is too large for the geometry: more triangles
    /// than a 32-bit primitive id counts, or a side longer than a grid primitive's.
    #[error("a {0}x{1} terrain is too large for Embree's {2}")]
    TooLarge(usize, usize, Geometry),
    /// A grid primitive has no holes, and the terrain has no-data cells.
    #[error("Embree's grid covers every cell; this terrain has cells over no data")]
    Holes,
}

/// How the terrain goes to Embree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Geometry {
    /// Two triangles per cell, as the surface contract ([`crate::geometry`]) defines them,
    /// each with a primitive id.
    Triangles,
    /// Embree's grid primitive over the samples: vertices only, cells split into triangles as
    /// Embree splits them.
    Grid,
}

impl std::fmt::Display for Geometry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Geometry::Triangles => "triangles",
            Geometry::Grid => "grid",
        })
    }
}

/// Where a ray first hits the terrain, as Embree found it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmbreeHit {
    /// The cell `(i, j)` hit.
    pub cell: (usize, usize),
    /// `T0` or `T1` of the cell: 0 or 1 (the surface contract, [`crate::geometry`]).
    pub triangle: u8,
    /// The ray parameter of the hit, as Embree reports it.
    pub t: f64,
    /// The triangle's unit normal, pointing up.
    pub up: DVec3,
}

/// Which of Embree's calls trace a frame's rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Api {
    /// `rtcIntersect1` and `rtcOccluded1`, a ray at a time.
    Single,
    /// `rtcIntersect8` and `rtcOccluded8`: camera rays by tiles of 4x2 pixels.
    Packets8,
    /// `rtcIntersect16` and `rtcOccluded16`: camera rays by tiles of 4x4 pixels.
    Packets16,
}

impl Api {
    /// Rays per call.
    pub fn width(self) -> usize {
        match self {
            Api::Single => 1,
            Api::Packets8 => 8,
            Api::Packets16 => 16,
        }
    }
}

/// A scene traced through one of Embree's APIs: a tracer of `bench speed`'s frames.
pub struct EmbreeTracer {
    /// The scene, shared by the tracers of its APIs.
    pub scene: Arc<EmbreeScene>,
    /// The calls that trace its rays.
    pub api: Api,
}

impl super::Reference for EmbreeTracer {
    /// `embree triangles` for single rays (as before packets were measured), `embree
    /// triangles 8-wide` for packets.
    fn name(&self) -> String {
        match self.api {
            Api::Single => format!("embree {}", self.scene.geometry),
            api => format!("embree {} {}-wide", self.scene.geometry, api.width()),
        }
    }
    fn render(&self, renderer: &Renderer<'_>, frame: &mut Frame) {
        match self.api {
            Api::Single => self.scene.render(renderer, frame),
            Api::Packets8 => self.scene.render_packets::<8>(renderer, frame),
            Api::Packets16 => self.scene.render_packets::<16>(renderer, frame),
        }
    }
}
