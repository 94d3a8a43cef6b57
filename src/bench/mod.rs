mod accuracy;
mod effects;
#[cfg(feature = "embree")]
pub mod embree;
#[cfg(feature = "bench")]
pub mod plot;
mod ray_sets;
mod sizes;
mod speed;
mod textbook;

pub use accuracy::{accuracy, pixel_differences, AccuracyRow, Disagreement};
pub use effects::{block_average, configurations, frame_with, renderer_with, rms_error, EffectRow};
pub use ray_sets::{hard_cases, scene_sets, RaySet};
pub use sizes::{sized_scene, SizedSceneError, SEED};
pub use speed::{render_as, throughput, view, Reference, ThroughputRow, Tracer, ROUNDS};
pub use textbook::{hard_cases_versus_exact, versus_textbook, HardCaseRow, Textbook, TextbookRow};
