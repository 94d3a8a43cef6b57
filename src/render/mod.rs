mod camera;
pub mod effects;
pub mod framing;
mod gamma;
mod normals;
mod passes;
mod ramp;
mod scene;
mod shade;
mod stats;
pub mod sun_position;
mod tally;
pub mod timing;
mod versus_exact;

pub use camera::{Camera, CameraError};
pub use passes::{Frame, Renderer, PASS_BLOCKS};
pub use ramp::{HeightSpan, Ramp};
pub use scene::{
    CameraSection, EffectsSection, HeightmapSection, Lighting, NoDataKey, Normals, Orbit, Scene,
    SceneError, SceneFile, ShadingSection, SunSection, DEFAULT_SIZE,
};
pub use shade::{Culling, Sample, Shader, Shadow, ShadowSkip};
pub use stats::{FrameStats, PixelStats};
pub use tally::{Counting, Tally};
pub use versus_exact::{differing_pixels, view_pixel_differences, PixelRow, View};
