//! A view along a camera path.

use glam::DVec3;

/// A view along a path: where the eye is, what it looks at, how wide.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The eye.
    pub eye: DVec3,
    /// The point looked at.
    pub target: DVec3,
    /// Vertical field of view in degrees.
    pub fov_y_deg: f64,
}
