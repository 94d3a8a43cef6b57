//! Framing the whole map: the orbit, from given angles, whose view holds every corner of the
//! map's bounding box, whatever the view's aspect; the viewer's R and F, and the view of a
//! scene without a `[camera]`. Also the ground under a point of the world, which a framed
//! target stays on.
//!
//! Points are in world coordinates (see
//! [`Terrain::world_from_grid`](crate::Terrain::world_from_grid)).

use super::camera::{Camera, CameraError};
use crate::Terrain;
use glam::DVec3;

/// The corners stay within this share of the view's half width and half height.
const MARGIN: f64 = 0.92;
/// The default view's yaw: from the south-west, the sun behind the viewer's shoulder.
pub const DEFAULT_YAW_DEG: f64 = -130.0;
/// The default view's pitch above the horizon.
pub const DEFAULT_PITCH_DEG: f64 = 35.0;
/// The default view's vertical field of view.
pub const DEFAULT_FOV_Y_DEG: f64 = 45.0;

/// The eight corners of the map's bounding box, in the world.
pub fn box_corners(terrain: &Terrain) -> [DVec3; 8] {
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let (lo, hi) = terrain.z_range();
    std::array::from_fn(|k| {
        DVec3::from(terrain.world_point([
            if k & 1 == 0 { 0.0 } else { w },
            if k & 2 == 0 { 0.0 } else { h },
            if k & 4 == 0 { lo } else { hi },
        ]))
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
                    points.extend(zs.map(|z| DVec3::from(terrain.world_point([x, y, z]))));
                }
            }
        }
    }
    points
}

/// How far above the surface a camera's eye stays, as a fraction of the map's [`scale`]: the
/// viewer's moves and a flythrough's path keep it there.
pub const EYE_CLEARANCE: f64 = 5e-4;

/// A length for the map's size that does not depend on the view: about the distance that
/// frames it. Zooming is bounded in multiples of it.
pub fn scale(terrain: &Terrain) -> f64 {
    let corners = box_corners(terrain);
    let radius = 0.5 * (corners[7] - corners[0]).length();
    (0.8 * radius / (DEFAULT_FOV_Y_DEG.to_radians() / 2.0).tan()).max(1.0)
}

/// A framed orbit's target and distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The point looked at.
    pub target: [f64; 3],
    /// From the target to the eye.
    pub distance: f64,
}

/// The camera that frames the whole map from the default angles, as the viewer first shows
/// it, for an image of `size` pixels.
pub fn framed_camera(terrain: &Terrain, size: (u32, u32)) -> Result<Camera, CameraError> {
    let aspect = f64::from(size.0) / f64::from(size.1.max(1));
    let Fit { target, distance } = fit(
        terrain,
        DEFAULT_YAW_DEG,
        DEFAULT_PITCH_DEG,
        DEFAULT_FOV_Y_DEG,
        aspect,
    );
    Camera::orbit(
        target,
        DEFAULT_YAW_DEG,
        DEFAULT_PITCH_DEG,
        distance,
        DEFAULT_FOV_Y_DEG,
        size,
    )
}

/// Unit vector from an orbit's target towards its eye, `yaw_deg` from +x towards +y and
/// `pitch_deg` above the horizon.
pub fn eye_direction(yaw_deg: f64, pitch_deg: f64) -> DVec3 {
    let (yaw, pitch) = (yaw_deg.to_radians(), pitch_deg.to_radians());
    DVec3::new(
        yaw.cos() * pitch.cos(),
        yaw.sin() * pitch.cos(),
        pitch.sin(),
    )
}

/// An orbit camera's unit axes: forward (eye to target), right and up, as [`Camera`] has them.
pub fn axes(yaw_deg: f64, pitch_deg: f64) -> (DVec3, DVec3, DVec3) {
    let forward = -eye_direction(yaw_deg, pitch_deg);
    let right = forward.cross(DVec3::Z).normalize_or(DVec3::X);
    (forward, right, right.cross(forward))
}

/// The orbit from `yaw_deg` and `pitch_deg` that shows the whole map in a view of `aspect`
/// (width over height), as near as it can.
///
/// For a target `T`, eye direction `o` and distance `d`, a point at `q = c - T` from the
/// target lies at depth `d + q.f` (`f = -o`) and at `q.r`, `q.u` across: it is inside the view
/// when `|q.r| <= m h a (d + q.f)` and `|q.u| <= m h (d + q.f)`, with `h = tan(fov/2)`. So the
/// smallest `d` is a maximum over the corners of the mipmap's blocks (`block_corners`). The
/// target then moves to centre the points' extent on screen, and the distance is found again
/// for the new target.
pub fn fit(terrain: &Terrain, yaw_deg: f64, pitch_deg: f64, fov_y_deg: f64, aspect: f64) -> Fit {
    let corners = box_corners(terrain);
    let points = block_corners(terrain);
    let centre = 0.5 * (corners[0] + corners[7]);
    let mut orbit = Fit {
        target: on_map(centre.into(), terrain),
        distance: 1.0,
    };
    let aspect = if aspect.is_finite() && aspect > 0.0 {
        aspect
    } else {
        16.0 / 9.0
    };
    let half_height = (fov_y_deg.to_radians() / 2.0).tan();
    let (forward, right, up) = axes(yaw_deg, pitch_deg);
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

/// The surface height at `(x, y)`: the plane of the cell's triangle that holds the point, as
/// the renderer meshes it (cell `(i, j)` split along the diagonal from `P00` to `P11`). Off the
/// map it is the map's lowest height, so the eye cannot pass under the map's edge either.
pub fn surface_z(terrain: &Terrain, x: f64, y: f64) -> f64 {
    // The camera moves in the world, whose x may be stretched from the grid's.
    let [x, y, _] = terrain.grid_point([x, y, 0.0]);
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    if !(x >= 0.0 && y >= 0.0 && x <= w && y <= h) {
        return terrain.z_range().0;
    }
    // The last row and column of samples belong to the cells before them.
    let i = (x.floor() as usize).min(field.width() - 2);
    let j = (y.floor() as usize).min(field.height() - 2);
    field.surface_z((i, j), (x - i as f64, y - j as f64))
}

/// The nearest point to `point` in the map's box and not below its surface: a target in the
/// air above the highest peak leaves the view looking at nothing.
pub fn on_map([x, y, z]: [f64; 3], terrain: &Terrain) -> [f64; 3] {
    let field = terrain.field();
    let size = [(field.width() - 1) as f64, (field.height() - 1) as f64, 0.0];
    let [w, h, _] = terrain.world_point(size);
    let (x, y) = (x.clamp(0.0, w), y.clamp(0.0, h));
    [
        x,
        y,
        z.min(terrain.z_range().1).max(surface_z(terrain, x, y)),
    ]
}
