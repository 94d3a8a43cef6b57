//! heightray: exact, fast ray tracing of terrain height fields on the CPU.
//!
//! Data flows one way: a file becomes a [`Heightfield`], acceleration data makes it a
//! [`Terrain`], and [`traverse::trace`] answers rays against it.

pub mod bench;
pub mod geometry;
pub mod heightfield;
mod regular_file;
pub mod render;
pub mod traverse;
pub mod viewer;

pub use geometry::{Ray, RayError};
pub use heightfield::{Heightfield, HeightfieldError, LoadError, Terrain};
pub use traverse::{trace, Arith, Counters, Hit, Method, Query, Trace, TraceOptions};
