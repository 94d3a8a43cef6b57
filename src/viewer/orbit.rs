//! The viewer's camera: an orbit around a target point, moved by drags, the wheel, keys and
//! double-clicks, and turned into a [`Camera`] for each render size.

use crate::render::framing::{self, Fit};
use crate::render::{self, Camera, CameraError};
use crate::Terrain;
use glam::DVec3;

/// Pitch stays this far from straight up or down: there the orbit's up vector would be
/// parallel to the view and the camera undefined.
pub const PITCH_LIMIT_DEG: f64 = 89.0;
/// The lowest pitch: a little below the horizon, to look up at a peak from a valley, never so
/// far that the eye ends under the ground it looks at.
pub const MIN_PITCH_DEG: f64 = -5.0;
/// Degrees of yaw and pitch per pixel of drag.
const DEG_PER_PIXEL: f64 = 0.3;
/// Closest and farthest zoom, as fractions and multiples of the orbit's scale.
const ZOOM_RANGE: (f64, f64) = (2e-3, 50.0);
/// How much one wheel step zooms (the factor is `exp(-ZOOM_PER_STEP)`).
const ZOOM_PER_STEP: f64 = 0.15;

/// A camera orbiting `target`: `yaw` from +x towards +y, `pitch` above the horizon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// The point looked at and turned around.
    pub target: [f64; 3],
    /// Degrees from +x towards +y.
    pub yaw_deg: f64,
    /// Degrees above the horizon.
    pub pitch_deg: f64,
    /// From the target to the eye.
    pub distance: f64,
    /// Vertical field of view in degrees.
    pub fov_y_deg: f64,
    /// A length for the terrain's size (about its framing distance), which bounds zooming.
    pub scale: f64,
}

impl Orbit {
    /// The whole terrain from the south-west, the sun behind the viewer's shoulder, in a
    /// 16:9 view (the viewer frames it again for its view's own shape).
    pub fn framing(terrain: &Terrain) -> Orbit {
        Orbit::fit(
            terrain,
            framing::DEFAULT_YAW_DEG,
            framing::DEFAULT_PITCH_DEG,
            framing::DEFAULT_FOV_Y_DEG,
            16.0 / 9.0,
        )
    }

    /// The orbit from `yaw_deg` and `pitch_deg` that shows the whole map in a view of `aspect`
    /// (width over height), as near as it can.
    pub fn fit(
        terrain: &Terrain,
        yaw_deg: f64,
        pitch_deg: f64,
        fov_y_deg: f64,
        aspect: f64,
    ) -> Orbit {
        let Fit { target, distance } = framing::fit(terrain, yaw_deg, pitch_deg, fov_y_deg, aspect);
        Orbit {
            target,
            yaw_deg,
            pitch_deg,
            distance,
            fov_y_deg,
            scale: framing::scale(terrain),
        }
    }

    /// The orbit whose eye and target are the given points (a scene file's `eye`/`target`).
    pub fn from_eye(eye: [f64; 3], target: [f64; 3], fov_y_deg: f64, scale: f64) -> Orbit {
        let offset = DVec3::from(eye) - DVec3::from(target);
        let distance = offset.length().max(f64::MIN_POSITIVE);
        let pitch = (offset.z / distance).clamp(-1.0, 1.0).asin().to_degrees();
        Orbit {
            target,
            yaw_deg: offset.y.atan2(offset.x).to_degrees(),
            pitch_deg: pitch.clamp(MIN_PITCH_DEG, PITCH_LIMIT_DEG),
            distance,
            fov_y_deg,
            scale,
        }
    }

    /// The eye position.
    pub fn eye(&self) -> DVec3 {
        DVec3::from(self.target) + self.offset_direction() * self.distance
    }

    /// The camera for an image of `size` pixels.
    pub fn camera(&self, size: (u32, u32)) -> Result<Camera, CameraError> {
        Camera::orbit(
            self.target,
            self.yaw_deg,
            self.pitch_deg,
            self.distance,
            self.fov_y_deg,
            size,
        )
    }

    /// Turns the eye around the target by a drag of `(dx, dy)` pixels: dragging right turns
    /// the terrain right, dragging down lifts the eye.
    pub fn rotate(&mut self, dx: f64, dy: f64) {
        self.yaw_deg = (self.yaw_deg - dx * DEG_PER_PIXEL).rem_euclid(360.0);
        if self.yaw_deg > 180.0 {
            self.yaw_deg -= 360.0;
        }
        self.pitch_deg =
            (self.pitch_deg + dy * DEG_PER_PIXEL).clamp(MIN_PITCH_DEG, PITCH_LIMIT_DEG);
    }

    /// Turns the eye around the target by `degrees` of yaw.
    pub fn turn(&mut self, degrees: f64) {
        self.rotate(-degrees / DEG_PER_PIXEL, 0.0);
    }

    /// Lifts the eye on its orbit by `degrees` of pitch (lowers it for negative degrees).
    pub fn tilt(&mut self, degrees: f64) {
        self.rotate(0.0, degrees / DEG_PER_PIXEL);
    }

    /// Moves the target (and the eye with it) so the terrain follows a drag of `(dx, dy)`
    /// pixels in a view `view_height` pixels high.
    pub fn pan(&mut self, dx: f64, dy: f64, view_height: f64) {
        let (_, right, up) = self.axes();
        // One pixel covers this much of the plane through the target.
        let per_pixel =
            2.0 * self.distance * (self.fov_y_deg.to_radians() / 2.0).tan() / view_height.max(1.0);
        let moved = DVec3::from(self.target) - right * dx * per_pixel + up * dy * per_pixel;
        self.target = moved.into();
    }

    /// Moves the target over the ground by `(ahead, aside)` times the distance: ahead is the
    /// view's direction on the ground, aside to its right.
    pub fn walk(&mut self, ahead: f64, aside: f64) {
        let (yaw_sin, yaw_cos) = self.yaw_deg.to_radians().sin_cos();
        // The eye looks along minus its offset: (-cos yaw, -sin yaw) on the ground.
        let step = self.distance;
        self.target[0] += step * (-ahead * yaw_cos - aside * yaw_sin);
        self.target[1] += step * (-ahead * yaw_sin + aside * yaw_cos);
    }

    /// Zooms by `steps` (positive: in) towards `point`: the eye and the target move towards it
    /// by the same factor, so the point stays where it is on screen and each step covers a
    /// fixed share of the way left to it, slowing as the eye nears it. The eye's distance to
    /// the point stays within the zoom range.
    pub fn zoom_towards(&mut self, point: [f64; 3], steps: f64) {
        let point = DVec3::from(point);
        let eye = self.eye();
        let reach = (eye - point).length();
        let (near, far) = (ZOOM_RANGE.0 * self.scale, ZOOM_RANGE.1 * self.scale);
        if !(reach > 0.0 && steps.is_finite()) {
            return;
        }
        let wanted = reach * (-steps * ZOOM_PER_STEP).exp();
        // Never farther out than the range, nor in past its near end; a step from outside the
        // range only moves towards it.
        let bounded = wanted.clamp(near.min(reach), far.max(reach));
        let factor = bounded / reach;
        let target = point + (DVec3::from(self.target) - point) * factor;
        self.target = target.into();
        self.distance = (self.distance * factor).max(1e-9 * self.scale);
    }

    /// Zooms towards (or away from) the target.
    pub fn zoom(&mut self, steps: f64) {
        self.zoom_towards(self.target, steps);
    }

    /// Orbits around `point` from where the eye is now (the view turns to face it).
    pub fn retarget(&mut self, point: [f64; 3]) {
        let retargeted = Orbit::from_eye(self.eye().into(), point, self.fov_y_deg, self.scale);
        // An eye on the point itself has no direction: keep the old angles then.
        if retargeted.distance > 1e-9 * self.scale {
            *self = retargeted;
        }
    }

    /// The camera's unit axes: forward (eye to target), right and up, as [`Camera`] has them.
    pub fn axes(&self) -> (DVec3, DVec3, DVec3) {
        render::framing::axes(self.yaw_deg, self.pitch_deg)
    }

    /// Unit vector from the target towards the eye.
    fn offset_direction(&self) -> DVec3 {
        render::framing::eye_direction(self.yaw_deg, self.pitch_deg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::Builtin;
    use crate::render::framing::{DEFAULT_FOV_Y_DEG, DEFAULT_PITCH_DEG, DEFAULT_YAW_DEG};
    use crate::viewer::ground::keep_above;

    fn terrain() -> Terrain {
        let field = Builtin::named("small49")
            .and_then(|b| b.load().ok())
            .expect("the built-in terrain decodes");
        Terrain::new(field)
    }

    #[test]
    fn framing_looks_at_the_terrain_and_builds_a_camera() {
        let orbit = Orbit::framing(&terrain());
        assert!((0.0..=48.0).contains(&orbit.target[0]));
        assert!((0.0..=48.0).contains(&orbit.target[1]));
        assert!(orbit.camera((640, 360)).is_ok());
        // The eye is outside the terrain's bounding sphere.
        assert!(orbit.distance > 0.5 * (48.0f64 * 48.0 * 2.0).sqrt());
    }

    #[test]
    fn eye_round_trips_through_from_eye() {
        let orbit = Orbit::framing(&terrain());
        let back = Orbit::from_eye(orbit.eye().into(), orbit.target, 45.0, orbit.scale);
        assert!((back.yaw_deg - orbit.yaw_deg).abs() < 1e-9);
        assert!((back.pitch_deg - orbit.pitch_deg).abs() < 1e-9);
        assert!((back.distance - orbit.distance).abs() < 1e-9);
    }

    #[test]
    fn pitch_is_clamped_and_zoom_is_bounded() {
        let mut orbit = Orbit::framing(&terrain());
        orbit.rotate(0.0, 1e6);
        assert_eq!(orbit.pitch_deg, PITCH_LIMIT_DEG);
        assert!(orbit.camera((10, 10)).is_ok());
        orbit.zoom(1e6);
        assert!(orbit.distance >= 0.999 * ZOOM_RANGE.0 * orbit.scale);
        assert!(orbit.camera((10, 10)).is_ok());
        orbit.zoom(-1e6);
        assert!(orbit.distance <= 1.001 * ZOOM_RANGE.1 * orbit.scale);
        orbit.zoom(f64::NAN);
        assert!(orbit.camera((10, 10)).is_ok());
    }

    #[test]
    fn zooming_towards_a_point_keeps_it_in_line_and_slows_near_it() {
        let mut orbit = Orbit::framing(&terrain());
        let point = DVec3::new(10.0, 30.0, 2.0);
        let towards = |o: &Orbit| (point - o.eye()).normalize();
        let (before, reach) = (towards(&orbit), (point - orbit.eye()).length());
        orbit.zoom_towards(point.into(), 1.0);
        assert!((towards(&orbit) - before).length() < 1e-12);
        let first = reach - (point - orbit.eye()).length();
        orbit.zoom_towards(point.into(), 1.0);
        let second = reach - first - (point - orbit.eye()).length();
        // Each step covers the same share of the way left.
        assert!((second / first - (-ZOOM_PER_STEP).exp()).abs() < 1e-9);
        assert_eq!(orbit.axes().0, Orbit::framing(&terrain()).axes().0);
    }

    #[test]
    fn retarget_keeps_the_eye() {
        let mut orbit = Orbit::framing(&terrain());
        let eye = orbit.eye();
        orbit.retarget([10.0, 30.0, 2.0]);
        assert!((orbit.eye() - eye).length() < 1e-9);
        assert_eq!(orbit.target, [10.0, 30.0, 2.0]);
    }

    #[test]
    fn pan_moves_target_in_the_view_plane() {
        let mut orbit = Orbit::framing(&terrain());
        let before = DVec3::from(orbit.target);
        let to_eye = orbit.eye() - before;
        orbit.pan(100.0, 0.0, 500.0);
        let moved = DVec3::from(orbit.target) - before;
        assert!(moved.length() > 0.0);
        assert!(moved.dot(to_eye).abs() < 1e-9 * to_eye.length() * moved.length().max(1.0));
    }

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
            let orbit = Orbit::fit(&terrain, yaw, pitch, DEFAULT_FOV_Y_DEG, aspect);
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
