//! Shaded relief seen straight down: each pixel the mean, in linear light, of vertical rays
//! spread over its area, each shaded as a picture is ([`Shader`]: the scene's ramp, sun and
//! effects, exact cast shadows in exact mode). Rays that find no terrain (holes, beyond the
//! map's edge) leave their share of the pixel transparent. For 16 bits a channel each ray
//! brings its own linear colour; for 8, the colour of its display bytes, as pictures were
//! always made.

use super::grid::OrthoGrid;
use super::tiff_out::Depth;
use crate::render::{linear_from_bytes, Shader};
use crate::{Arith, Face, Ray};

/// Rays per pixel along each axis.
pub const RAYS_PER_AXIS: u32 = 4;

/// A colour pixel: red, green, blue (display-encoded, as pictures are) and coverage, each
/// 0 to 65535.
pub type Rgba16 = [u16; 4];

/// The pixel `(column, row)` of `grid` in shaded relief, for a picture of `depth`.
pub fn pixel(
    shader: &Shader<'_>,
    (arith, depth): (Arith, Depth),
    grid: &OrthoGrid,
    column: u32,
    row: u32,
) -> Rgba16 {
    let top = shader.terrain.z_range().1 + 1.0;
    let n = RAYS_PER_AXIS;
    let mut sum = [0.0f64; 3];
    let mut hits = 0u32;
    for a in 0..n {
        for b in 0..n {
            // Offsets a quarter of a stratum apart along x and y: on a pixel a cell wide, no
            // ray falls on a cell's diagonal, where the triangle first in order would take
            // every tie.
            let u = (f64::from(a) + 0.25) / f64::from(n);
            let v = (f64::from(b) + 0.75) / f64::from(n);
            let [x, y] = grid.point(column, row, (u, v));
            let Ok(ray) = Ray::new([x, y, top], [0.0, 0.0, -1.0]) else {
                continue;
            };
            let (sample, hit, colour) = shader.traced_linear(&ray, arith, None);
            if hit.is_some_and(|h| h.face == Face::Terrain) {
                let [_, r, g, b] = sample.rgb.to_be_bytes();
                let linear = match depth {
                    Depth::Eight => linear_from_bytes([r, g, b]),
                    Depth::Sixteen => colour.to_array(),
                };
                for k in 0..3 {
                    sum[k] += linear[k];
                }
                hits += 1;
            }
        }
    }
    if hits == 0 {
        return [0; 4];
    }
    let encode = |linear: f64| (linear.clamp(0.0, 1.0).powf(1.0 / 2.2) * 65535.0).round() as u16;
    let coverage = (f64::from(hits) / f64::from(n * n) * 65535.0).round() as u16;
    let [r, g, b] = sum.map(|s| encode(s / f64::from(hits)));
    [r, g, b, coverage]
}
