//! Framing the whole map: the orbit, from given angles, whose view holds every corner of the
//! map's bounding box, whatever the view's aspect.

use super::ground::on_map;
use super::orbit::Orbit;
use crate::Terrain;
use glam::DVec3;

/// The corners stay within this share of the view's half width and half height.
const MARGIN: f64 = 0.92;
/// The default view: from the south-west, the sun behind the viewer's shoulder.
pub const DEFAULT_YAW_DEG: f64 = -130.0;
pub const DEFAULT_PITCH_DEG: f64 = 35.0;
pub const DEFAULT_FOV_Y_DEG: f64 = 45.0;

/// The eight corners of the map's bounding box.
pub fn box_corners(terrain: &Terrain) -> [DVec3; 8] {
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let (lo, hi) = terrain.z_range();
    std::array::from_fn(|k| {
        DVec3::new(
            if k & 1 == 0 { 0.0 } else { w },
            if k & 2 == 0 { 0.0 } else { h },
            if k & 4 == 0 { lo } else { hi },
        )
    })
}

/// Points whose hull holds the whole surface, and not much more: the corners of the boxes of
/// the mipmap's blocks on a level of at most 16 x 16 blocks (each block's box spans its lowest
/// and highest sample). The map's own bounding box would leave the air over its low corners
/// in the view, and show the map small.
fn block_corners(terrain: &Terrain) -> Vec<DVec3> {
    let (field, mipmap) = (terrain.field(), terrain.mipmap());
    let level = mipmap.top().saturating_sub(4).max(2).min(mipmap.top());
    let side = 1usize << level;
    let (cells_x, cells_y) = (field.width() - 1, field.height() - 1);
    let mut points = Vec::new();
    for bj in 0..cells_y.div_ceil(side) {
        for bi in 0..cells_x.div_ceil(side) {
            let xs = [bi * side, ((bi + 1) * side).min(cells_x)].map(|x| x as f64);
            let ys = [bj * side, ((bj + 1) * side).min(cells_y)].map(|y| y as f64);
            let zs = [mipmap.lowest(level, bi, bj), mipmap.highest(level, bi, bj)]
                .map(|sample| field.height_of(sample));
            for x in xs {
                for y in ys {
                    points.extend(zs.map(|z| DVec3::new(x, y, z)));
                }
            }
        }
    }
    points
}

/// A length for the map's size that does not depend on the view: about the distance that
/// frames it. Zooming is bounded in multiples of it.
pub fn scale(terrain: &Terrain) -> f64 {
    let corners = box_corners(terrain);
    let radius = 0.5 * (corners[7] - corners[0]).length();
    (0.8 * radius / (DEFAULT_FOV_Y_DEG.to_radians() / 2.0).tan()).max(1.0)
}

/// The orbit from `yaw_deg` and `pitch_deg` that shows the whole map in a view of `aspect`
/// (width over height), as near as it can.
///
/// For a target `T`, eye direction `o` and distance `d`, a point at `q = c - T` from the
/// target lies at depth `d + q.f` (`f = -o`) and at `q.r`, `q.u` across: it is inside the view
/// when `|q.r| <= m h a (d + q.f)` and `|q.u| <= m h (d + q.f)`, with `h = tan(fov/2)`. So the
/// smallest `d` is a maximum over the points of [`block_corners`]. The target then moves to
/// centre the points' extent on screen, and the distance is found again for the new target.
pub fn fit(terrain: &Terrain, yaw_deg: f64, pitch_deg: f64, fov_y_deg: f64, aspect: f64) -> Orbit {
    let corners = box_corners(terrain);
    let points = block_corners(terrain);
    let centre = 0.5 * (corners[0] + corners[7]);
    let mut orbit = Orbit {
        target: on_map(centre.into(), terrain),
        yaw_deg,
        pitch_deg,
        distance: 1.0,
        fov_y_deg,
        scale: scale(terrain),
    };
    let aspect = if aspect.is_finite() && aspect > 0.0 {
        aspect
    } else {
        16.0 / 9.0
    };
    let half_height = (fov_y_deg.to_radians() / 2.0).tan();
    let (forward, right, up) = orbit.axes();
    for round in 0..3 {
        let target = DVec3::from(orbit.target);
        let mut distance = f64::MIN_POSITIVE;
        for &c in &points {
            let q = c - target;
            let across = (q.dot(right).abs() / aspect).max(q.dot(up).abs());
            distance = distance.max(across / (MARGIN * half_height) - q.dot(forward));
        }
        orbit.distance = distance;
        if round == 2 {
            break;
        }
        // Where the corners' extent is centred on screen, in the plane through the target.
        let (mut x, mut y) = ((f64::MAX, f64::MIN), (f64::MAX, f64::MIN));
        for &c in &points {
            let q = c - target;
            let depth = distance + q.dot(forward);
            let (sx, sy) = (q.dot(right) / depth, q.dot(up) / depth);
            (x, y) = ((x.0.min(sx), x.1.max(sx)), (y.0.min(sy), y.1.max(sy)));
        }
        let shift = right * (0.5 * (x.0 + x.1) * distance) + up * (0.5 * (y.0 + y.1) * distance);
        // (The target stays where every camera move leaves it, or the framing would not last.)
        orbit.target = on_map((target + shift).into(), terrain);
    }
    orbit
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::Builtin;
    use crate::viewer::ground::keep_above;

    /// Every sample of the map lands inside the image of the orbit's camera.
    fn map_inside(terrain: &Terrain, orbit: &Orbit, size: (u32, u32)) -> bool {
        let (forward, right, up) = orbit.axes();
        let eye = orbit.eye();
        let h = (orbit.fov_y_deg.to_radians() / 2.0).tan();
        let aspect = f64::from(size.0) / f64::from(size.1);
        let field = terrain.field();
        (0..field.height()).all(|j| {
            (0..field.width()).all(|i| {
                let q = DVec3::new(i as f64, j as f64, field.z(i, j)) - eye;
                let depth = q.dot(forward);
                let (sx, sy) = (q.dot(right) / depth / (h * aspect), q.dot(up) / depth / h);
                depth > 0.0 && sx.abs() < 1.0 && sy.abs() < 1.0
            })
        })
    }

    #[test]
    fn the_whole_map_fits_any_aspect_and_fills_it() {
        let field = Builtin::named("small49").and_then(|b| b.load().ok());
        let terrain = Terrain::new(field.expect("the built-in terrain decodes"));
        for (size, yaw, pitch) in [
            ((1280, 720), DEFAULT_YAW_DEG, DEFAULT_PITCH_DEG),
            ((800, 500), DEFAULT_YAW_DEG, DEFAULT_PITCH_DEG),
            ((300, 900), 20.0, 60.0),
            ((2000, 300), 100.0, 10.0),
        ] {
            let aspect = f64::from(size.0) / f64::from(size.1);
            let orbit = fit(&terrain, yaw, pitch, DEFAULT_FOV_Y_DEG, aspect);
            assert!(map_inside(&terrain, &orbit, size), "{size:?}");
            // Already where the ground rule would put it: the framing lasts.
            let mut kept = orbit;
            keep_above(&mut kept, &terrain);
            assert_eq!(kept, orbit, "{size:?}");
            // Tight: a fifth closer and some corner leaves the view.
            let closer = Orbit {
                distance: 0.8 * orbit.distance,
                ..orbit
            };
            assert!(!map_inside(&terrain, &closer, size), "{size:?}");
        }
    }
}
