//! Benchmarks: methods and arithmetics measured side by side in one run, as ratios.

mod speed;

pub use speed::{measure, Disagreement, SpeedRow};
