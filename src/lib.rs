//! heightray: exact, fast ray tracing of terrain height fields on the CPU.
//!
//! Data flows one way: a file becomes a [`Heightfield`], acceleration data makes it a
//! [`Terrain`], and [`traverse::trace`] (the first hit) and [`traverse::occluded`] (any hit
//! after the start) answer rays against it.

#![warn(missing_docs)]

/// Numbers: the scalar trait, intervals, bounded and exact rationals, the `Arith` a user picks
/// and the one way from it to generic code.
pub mod arith;
/// Work split into numbered pieces for independent workers: a flythrough's frames, a
/// poster's tiles, and the share `I/N` each worker takes.
pub mod batch;
/// Benchmarks: methods, arithmetics and thread counts measured side by side in one run.
pub mod bench;
/// Numbers echoed in messages, written compactly (`1e300`, not 301 digits).
pub mod compact;
/// Rays, box clipping, the watertight two-triangle cell test, and the surface contract.
pub mod geometry;
/// Height fields: samples, loading, and the maxima the walks skip empty space with.
pub mod heightfield;
/// Writing a file a user names: checked first, then written whole or not at all.
pub mod output_file;
/// Map products made straight down: shaded relief, sky-view factor and hours of sunlight, as
/// GeoTIFFs on the map's own grid.
pub mod products;
mod regular_file;
/// Turning rays into pixels: cameras, scene files, shading, progressive passes, statistics.
pub mod render;
/// Answering rays (first hit, occlusion) by walking the grid: the methods, exact mode's
/// strategy, query counters.
pub mod traverse;
/// The interactive viewer: winit, softbuffer and egui, drawn on the CPU (feature `viewer`).
#[cfg(feature = "viewer")]
pub mod viewer;

pub use arith::Arith;
pub use geometry::{Base, Face, Ray, RayError, Side};
pub use heightfield::{Heightfield, HeightfieldError, LoadError, Terrain};
pub use traverse::{occluded, trace, Counters, Hit, Method, Trace, TraceOptions};

// The README's Rust example runs as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
