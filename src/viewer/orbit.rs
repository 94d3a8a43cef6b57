//! The viewer's camera: an orbit around a target point, moved by drags, the wheel and
//! double-clicks, and turned into a [`Camera`] for each render size.

use crate::render::{Camera, CameraError};
use crate::Terrain;
use glam::DVec3;

/// Pitch stays this far from straight up or down: there the orbit's up vector would be
/// parallel to the view and the camera undefined.
const PITCH_LIMIT_DEG: f64 = 89.0;
/// Degrees of yaw and pitch per pixel of drag.
const DEG_PER_PIXEL: f64 = 0.3;
/// Closest and farthest zoom, as fractions and multiples of the framing distance.
const ZOOM_RANGE: (f64, f64) = (1e-3, 50.0);

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
    /// The framing distance of the current terrain, which bounds zooming.
    pub scale: f64,
}

impl Orbit {
    /// Looks at the whole terrain from the south-west, the sun behind the viewer's shoulder.
    pub fn framing(terrain: &Terrain) -> Orbit {
        let field = terrain.field();
        let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
        let (lo, hi) = terrain.z_range();
        let fov_y_deg: f64 = 45.0;
        // Nearly the bounding sphere of the terrain's box in the vertical field of view: the
        // view is wider than high and the box's corners rarely all face the camera.
        let radius = 0.5 * DVec3::new(w, h, hi - lo).length();
        let distance = (0.8 * radius / (fov_y_deg.to_radians() / 2.0).tan()).max(1.0);
        Orbit {
            target: [w / 2.0, h / 2.0, (lo + hi) / 2.0],
            yaw_deg: -130.0,
            pitch_deg: 35.0,
            distance,
            fov_y_deg,
            scale: distance,
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
            pitch_deg: pitch.clamp(-PITCH_LIMIT_DEG, PITCH_LIMIT_DEG),
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
            (self.pitch_deg + dy * DEG_PER_PIXEL).clamp(-PITCH_LIMIT_DEG, PITCH_LIMIT_DEG);
    }

    /// Moves the target (and the eye with it) so the terrain follows a drag of `(dx, dy)`
    /// pixels in a view `view_height` pixels high.
    pub fn pan(&mut self, dx: f64, dy: f64, view_height: f64) {
        let forward = -self.offset_direction();
        let right = forward.cross(DVec3::Z).normalize_or(DVec3::X);
        let up = right.cross(forward);
        // One pixel covers this much of the plane through the target.
        let per_pixel =
            2.0 * self.distance * (self.fov_y_deg.to_radians() / 2.0).tan() / view_height.max(1.0);
        let moved = DVec3::from(self.target) - right * dx * per_pixel + up * dy * per_pixel;
        self.target = moved.into();
    }

    /// Moves the eye towards the target (`steps > 0`) or away, by a factor per step.
    pub fn zoom(&mut self, steps: f64) {
        let (near, far) = (ZOOM_RANGE.0 * self.scale, ZOOM_RANGE.1 * self.scale);
        self.distance = (self.distance * (-steps * 0.06).exp()).clamp(near, far);
    }

    /// Orbits around `point` from where the eye is now (the view turns to face it).
    pub fn retarget(&mut self, point: [f64; 3]) {
        let retargeted = Orbit::from_eye(self.eye().into(), point, self.fov_y_deg, self.scale);
        // An eye on the point itself has no direction: keep the old angles then.
        if retargeted.distance > 1e-9 * self.scale {
            *self = retargeted;
        }
    }

    /// Unit vector from the target towards the eye.
    fn offset_direction(&self) -> DVec3 {
        let (yaw, pitch) = (self.yaw_deg.to_radians(), self.pitch_deg.to_radians());
        DVec3::new(
            yaw.cos() * pitch.cos(),
            yaw.sin() * pitch.cos(),
            pitch.sin(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::Builtin;

    fn terrain() -> Terrain {
        let field = Builtin::named("small49")
            .and_then(|b| b.load().ok())
            .expect("the built-in terrain decodes");
        Terrain::new(field)
    }

    #[test]
    fn framing_centres_the_terrain_and_builds_a_camera() {
        let orbit = Orbit::framing(&terrain());
        assert_eq!(orbit.target[0], 24.0);
        assert_eq!(orbit.target[1], 24.0);
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
        assert!(orbit.distance >= ZOOM_RANGE.0 * orbit.scale);
        assert!(orbit.camera((10, 10)).is_ok());
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
}
