//! An orbit around a target: a `[camera]`'s or an `[[animation.key]]`'s view. On its own so
//! that camera paths can use it without the scene's errors.

use super::triple::three;
use serde::{Deserialize, Serialize};

/// A camera given as an orbit around a target (see [`Camera::orbit`](crate::render::Camera::orbit)).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Orbit {
    /// The point looked at.
    #[serde(deserialize_with = "three")]
    pub target: [f64; 3],
    /// Degrees from +x towards +y.
    pub yaw_deg: f64,
    /// Degrees above the horizon.
    pub pitch_deg: f64,
    /// From the target to the eye.
    pub distance: f64,
}
