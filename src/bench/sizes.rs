//! The same landscape at several sizes, seen from the same oblique view: how build time,
//! memory and time per ray grow with the terrain.

use crate::arith::Arith;
use crate::heightfield::{landscape, HeightfieldError};
use crate::render::{
    Camera, CameraError, EffectsSection, Lighting, Scene, ShadingSection, SunSection,
};
use crate::traverse::Method;
use thiserror::Error;

/// The seed of every generated size (the built-in valley's).
pub const SEED: u64 = 1;

/// Why a sized scene could not be made.
#[derive(Debug, Error)]
pub enum SizedSceneError {
    /// The generated height field was refused.
    #[error(transparent)]
    Field(#[from] HeightfieldError),
    /// The scaled view's camera was refused.
    #[error(transparent)]
    Camera(#[from] CameraError),
}

/// The built-in valley's landscape and view at `samples x samples`: heights, camera and sun
/// scale with the grid, so every size shows the same picture in more detail.
pub fn sized_scene(samples: usize, image: u32) -> Result<Scene, SizedSceneError> {
    let scale = (samples.max(2) - 1) as f64 / 512.0;
    let field = landscape(samples, SEED, 120.0 * scale)?;
    let at = |p: [f64; 3]| p.map(|c| c * scale);
    let camera = Camera::look_at(
        at([-40.0, -60.0, 180.0]),
        at([256.0, 256.0, 40.0]),
        [0.0, 0.0, 1.0],
        45.0,
        (image, image),
    )?;
    // The valley's sun and shading are the defaults; shadows on, no fog.
    let effects = EffectsSection {
        shadows: true,
        fog: 0.0,
        ..EffectsSection::default()
    };
    Ok(Scene {
        field,
        camera,
        lighting: Lighting::from_sections(
            &SunSection::default(),
            &effects,
            &ShadingSection::default(),
        ),
        method: Method::Mipmap,
        arith: Arith::F64,
        animation: None,
        annotations: Default::default(),
        contours: None,
    })
}
