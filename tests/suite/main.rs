//! The integration tests, in one crate: each file built alone instantiated the crate's generic
//! traversal for itself, and linked a binary of its own, which made most of the release test
//! build. (`tests/huge_header.rs` stays apart: its recording allocator is the whole binary's;
//! `tests/viewer` drives a window under Xvfb.)

#[path = "../common/mod.rs"]
mod common;

mod bad_input;
mod beams;
mod cli_bench;
mod cli_trace;
mod exact_paths;
mod exact_reference;
mod float_modes;
mod formats;
mod hard_cases;
mod holes;
mod loader_fuzz;
mod ramps;
mod render;
mod terminator;
