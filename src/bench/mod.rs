mod accuracy;
#[cfg(feature = "embree")]
pub mod embree;
mod fastest;
pub mod plot;
mod ray_sets;
mod sizes;
mod speed;
mod textbook;

pub use accuracy::{
    accuracy, differing_pixels, pixel_differences, view_pixel_differences, AccuracyRow,
    Disagreement, PixelRow, View,
};
pub use ray_sets::{hard_cases, scene_sets, RaySet};
pub use sizes::{sized_scene, SizedSceneError, SEED};
pub use speed::{render_as, throughput, view, Reference, ThroughputRow, Tracer, ROUNDS};
pub use textbook::{hard_cases_versus_exact, versus_textbook, HardCaseRow, Textbook, TextbookRow};
