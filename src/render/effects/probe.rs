//! Probes under the surface: an occlusion ray that leaves its own flat triangle upwards and
//! is found, somewhere within its reach, clearly below the surface has crossed the surface in
//! between (a map without holes: through a hole a ray gets under the surface without
//! crossing it), so it is blocked, with no walk. A line meets its own triangle's plane only at its
//! start, so the crossing is another triangle's, at a `t` the walk asks about: the walk
//! answers the same. The rays the bounds leave unsettled pass near the terrain's horizon, and
//! most that are blocked dip under a ridge for a stretch a few probes find.

use crate::heightfield::Terrain;
use glam::DVec3;

/// Horizontal distances (cells) from the start at which a ray is probed, nearest first.
const PROBES: [f64; 10] = [1.5, 3.0, 5.0, 8.0, 12.0, 17.0, 24.0, 33.0, 45.0, 60.0];

/// Whether the ray from `start` (grid coordinates, on its flat triangle up to `room` in any
/// coordinate, leaving it upwards) in direction `dir` certainly lies below the surface at some
/// probe within `t_max` along it: then it touches the surface before. Never on a map with
/// holes.
pub(super) fn blocked_under_surface(
    terrain: &Terrain,
    start: DVec3,
    room: f64,
    dir: DVec3,
    t_max: f64,
) -> bool {
    let across = (dir.x * dir.x + dir.y * dir.y).sqrt();
    let field = terrain.field();
    let holes = field.nodata_count() > 0;
    if holes || !(across > 0.0 && t_max.is_finite() && start.is_finite() && field.step() > 0.0) {
        return false;
    }
    let (samples, width) = (field.samples(), field.width());
    let (w, h) = ((width - 1) as f64, (field.height() - 1) as f64);
    let (lo, hi) = terrain.z_range();
    // Heights in sample steps, so that a probe compares the samples themselves.
    let (base, per_step) = (field.height_of(0), 1.0 / field.step());
    // The true start may lie `room` away in each coordinate, which moves the surface under a
    // probe by the steepest slope times that; the rest covers rounding the probe itself.
    let slack = room * (1.0 + 2.0 * terrain.max_slope()) + 1e-9 * (1.0 + lo.abs() + hi.abs());
    for r in PROBES {
        let t = r / across;
        let q = start + t * dir;
        if t > t_max || q.z > hi || !(q.x >= 0.0 && q.y >= 0.0 && q.x < w && q.y < h) {
            return false;
        }
        let (i, j) = (q.x as usize, q.y as usize);
        let k = j * width + i;
        let corners = [k, k + 1, k + width, k + width + 1].map(|k| f64::from(samples[k]));
        let [s00, s10, s01, s11] = corners;
        let (fx, fy) = (q.x - i as f64, q.y - j as f64);
        // The cell's triangles as `Heightfield::surface_z` splits them, in sample steps.
        let surface = if fx >= fy {
            s00 + fx * (s10 - s00) + fy * (s11 - s10)
        } else {
            s00 + fy * (s01 - s00) + fx * (s11 - s01)
        };
        let below = surface - (q.z - base) * per_step;
        if below > slack * (1.0 + t) * per_step {
            return true;
        }
    }
    false
}
