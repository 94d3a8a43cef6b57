mod accumulate;
pub mod animation;
pub mod annotate;
mod camera;
mod context;
mod contours;
mod deep;
pub mod effects;
mod frame;
pub mod framing;
mod gamma;
pub mod local_time;
mod normals;
mod passes;
mod ramp;
mod sample;
mod scene;
mod shade;
mod sky_gradient;
mod stats;
pub mod sun_position;
mod surface;
mod tally;
pub mod timing;
mod versus_exact;

pub use accumulate::{reach, Accumulation};
pub use camera::{Camera, CameraError, Window, MAX_PIXELS};
pub use context::{Context, Culling};
pub use contours::Contours;
pub use effects::{Reflection, Shadow, ShadowSkip, SkyRays, SoftShadow};
pub use frame::Frame;
pub use passes::{Renderer, PASS_BLOCKS};
pub use ramp::{HeightSpan, Ramp};
pub use sample::Sample;
pub use scene::{
    bytes_from_hex, bytes_from_linear, level_in_map_units, level_z, linear_from_bytes,
};
pub use scene::{
    BaseDepthError, BaseStyle, CameraSection, ContoursError, EffectsError, EffectsSection,
    HeightmapSection, Lighting, NoDataKey, Normals, Orbit, OverlaySection, PlaceSunError, Scene,
    SceneError, SceneFile, SectionError, ShadingSection, SunSection, WaterError, WaterSection,
    DEFAULT_SIZE, DEFAULT_WATER_COLOUR,
};
pub use shade::Shader;
pub use stats::{FrameStats, PixelStats};
pub use tally::{Counting, Tally};
pub use versus_exact::{
    differing_pixels, largest_difference, view_pixel_differences, PixelRow, View,
};
