//! Turning rays into pixels: cameras (and, to come, scenes, shading and passes).

mod camera;

pub use camera::{Camera, CameraError};
