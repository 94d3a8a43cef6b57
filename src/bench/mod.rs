//! Benchmarks: methods, arithmetics and thread counts measured side by side in one run, as
//! ratios.

mod accuracy;
mod speed;

pub use accuracy::{accuracy, AccuracyRow, Disagreement};
pub use speed::{throughput, ThroughputRow};
