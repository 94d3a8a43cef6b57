//! Where the camera returns to, and whether it shows the map as framed.

use crate::viewer::orbit::Orbit;

/// Where R goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Home {
    /// The whole map from the default direction, framed for the view's shape.
    WholeMap,
    /// A scene file's camera.
    Scene(Orbit),
}

/// The camera shows the whole map as framed from these angles for a view of `aspect`; while it
/// is untouched, a view of another shape, or the map with another z scale, frames it again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Framed {
    pub yaw_deg: f64,
    pub pitch_deg: f64,
    pub aspect: f64,
    pub orbit: Orbit,
    /// The terrain it framed (its address: a rescaled map is a new terrain).
    pub terrain: usize,
}
