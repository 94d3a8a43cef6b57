//! Rays, box clipping, and the watertight two-triangle cell test.

mod certain_miss;
mod clip;
mod ray;
#[cfg(test)]
pub mod strategies;
mod triangle;

pub use certain_miss::{CellImages, Certain, CertainMiss};
pub use clip::{clip_to_box, Clipped};
pub use ray::{times_power_of_two, Ray, RayError};
pub use triangle::{
    gradient, plane_crossing, plane_height, ray_space_axes, triangle_corners, CellTriangles,
    RaySpace, TriangleHit,
};
