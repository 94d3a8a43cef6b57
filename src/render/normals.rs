//! Smooth normals from the samples, and where a shadow ray starts on a smoothly shaded
//! surface.
//!
//! Smooth shading lights a point by a normal interpolated from its triangle's corners, while
//! the geometry stays the flat triangles. Near the terminator the two disagree: a triangle can
//! turn away from the sun while the interpolated normal still faces it, and a shadow ray
//! started on that flat triangle runs into the surface at once. The shading is lit, the
//! shadow dark, and the whole triangle shows as a hard-edged dark patch across the slope.
//! [`shadow_origin`] starts the ray on the curved surface the normals describe instead
//! (Hanika, "Hacking the shadow terminator", Ray Tracing Gems II, 2021).

use crate::heightfield::Terrain;
use glam::DVec3;

/// The corners of triangle `triangle` of cell `(i, j)` with their barycentric weights at
/// `p` (whose x and y are clamped to the cell).
pub fn corner_weights(
    (i, j): (usize, usize),
    triangle: u8,
    p: DVec3,
) -> [((usize, usize), f64); 3] {
    let (u, w) = (
        (p.x - i as f64).clamp(0.0, 1.0),
        (p.y - j as f64).clamp(0.0, 1.0),
    );
    if triangle == 0 {
        [((i, j), 1.0 - u), ((i + 1, j), u - w), ((i + 1, j + 1), w)]
    } else {
        [((i, j), 1.0 - w), ((i + 1, j + 1), u), ((i, j + 1), w - u)]
    }
}

/// The vertex normals of triangle `triangle` of `cell`, interpolated at `p`, normalised.
#[inline(always)]
pub fn smooth_normal(terrain: &Terrain, cell: (usize, usize), triangle: u8, p: DVec3) -> DVec3 {
    let [a, b, c] = corner_weights(cell, triangle, p);
    let n = |((x, y), weight): ((usize, usize), f64)| vertex_normal(terrain, x, y) * weight;
    (n(a) + n(b) + n(c)).normalize_or(DVec3::Z)
}

/// Central-difference normal at sample `(i, j)`, one-sided at the border and next to a
/// no-data sample (whose stand-in height is not terrain); flat where both sides are.
pub fn vertex_normal(terrain: &Terrain, i: usize, j: usize) -> DVec3 {
    let field = terrain.field();
    let (w, h) = (field.width() - 1, field.height() - 1);
    let (i0, i1, j0, j1) = (
        Some(i.saturating_sub(1))
            .filter(|&x| !field.is_nodata(x, j))
            .unwrap_or(i),
        Some((i + 1).min(w))
            .filter(|&x| !field.is_nodata(x, j))
            .unwrap_or(i),
        Some(j.saturating_sub(1))
            .filter(|&y| !field.is_nodata(i, y))
            .unwrap_or(j),
        Some((j + 1).min(h))
            .filter(|&y| !field.is_nodata(i, y))
            .unwrap_or(j),
    );
    let slope = |z1: f64, z0: f64, run: usize| {
        if run == 0 {
            0.0
        } else {
            (z1 - z0) / run as f64
        }
    };
    let dzdx = slope(field.z(i1, j), field.z(i0, j), i1 - i0);
    let dzdy = slope(field.z(i, j1), field.z(i, j0), j1 - j0);
    DVec3::new(-dzdx, -dzdy, 1.0).normalize_or(DVec3::Z)
}

/// Where the shadow ray of `p`, on triangle `triangle` of `cell`, starts under smooth
/// shading: `p` moved out to the curved surface the vertex normals describe. For each corner,
/// `p` is projected onto the corner's tangent plane where it lies below it (only outwards:
/// where the surface curves in, the flat triangle is already outside), and the projections
/// are blended by `p`'s barycentric weights. On flat ground every tangent plane is the
/// triangle's and `p` stays where it is; the lift is largest mid-triangle where the surface
/// bends most, and vanishes at the corners.
pub fn shadow_origin(terrain: &Terrain, cell: (usize, usize), triangle: u8, p: DVec3) -> DVec3 {
    let field = terrain.field();
    corner_weights(cell, triangle, p)
        .into_iter()
        .fold(p, |origin, ((x, y), weight)| {
            let corner = DVec3::new(x as f64, y as f64, field.z(x, y));
            let n = vertex_normal(terrain, x, y);
            let below = (corner - p).dot(n).max(0.0);
            origin + n * (weight * below)
        })
}
