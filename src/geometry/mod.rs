// (The summary line of this module's docs is its `pub mod` line in lib.rs; the empty line
// below starts the rest as a paragraph of its own.)
//!
//! # The surface contract
//!
//! What every method and arithmetic answers (the README's section "The surface" says it at
//! length):
//!
//! - Sample `(i, j)` lies at `x = i`, `y = j` (y grows north), at the height its field maps it
//!   to ([`crate::Heightfield`]), computed in `f64`: those heights are the exact inputs of
//!   exact mode.
//! - Cell `(i, j)` is the closed square `[i, i+1] x [j, j+1]`, split along the diagonal from
//!   `P00` to `P11` into two closed triangles: `T0 = (P00, P10, P11)`, where
//!   `0 <= y-j <= x-i <= 1`, and `T1 = (P00, P11, P01)`, where `0 <= x-i <= y-j <= 1`. A cell
//!   with a no-data corner is a hole: it has no triangles, and rays pass through it.
//! - The first hit is the least `t >= 0` at which the ray `o + t*d` touches a triangle; a ray
//!   lying in a triangle's plane hits where it first touches the triangle.
//! - Ties: a hit point shared by several triangles is reported in the first cell in visiting
//!   order (the cells the projected path touches, in order of first contact), `T0` before
//!   `T1`.

mod base;
mod base_screen;
mod cell_lanes;
mod certain_miss;
mod clip;
mod ray;
#[cfg(test)]
pub mod strategies;
mod triangle;

pub use base::{base_hit, Base, BaseHit, BaseQuery, Face, Side};
pub use certain_miss::{CellImages, Certain, CertainMiss};
pub use clip::{clip_to_box, Clipped};
pub use ray::{times_power_of_two, Ray, RayError};
pub use triangle::{
    gradient, plane_crossing, plane_height, ray_space_axes, triangle_corners, CellTriangles,
    RaySpace, TriangleHit,
};
