//! The integration tests, in one crate, so that the crate's generic traversal is instantiated
//! and a test binary linked once, not once per file. (`tests/huge_header.rs` and
//! `tests/bounded_reading.rs` stay apart: their recording allocator is the whole binary's;
//! `tests/viewer` drives a window under Xvfb.)

#[path = "../common/mod.rs"]
mod common;

mod annotations;
mod bad_input;
mod base;
mod big_inputs;
mod cell_lanes;
mod cli_bench;
mod cli_compare;
mod cli_paths;
mod cli_render;
mod cli_trace;
mod crs_scale;
mod deep_tiffs;
mod disc_bounds;
mod drapes;
mod exact_paths;
mod exact_reach;
mod exact_reference;
mod far_bounds;
mod far_rays;
mod flight;
mod float_modes;
mod formats;
mod generated_tiles;
mod georeferencing;
mod hard_cases;
mod holes;
mod hostile_input;
mod loader_fuzz;
mod mosaics;
mod near_slopes;
mod near_walk;
mod ortho_contours;
mod orthophotos;
mod packets;
mod place_labels;
mod poster;
mod products;
mod products_cli;
mod ramps;
mod recorded_cells;
mod render;
mod snapshots;
mod sun_bearing;
mod sun_time;
mod sunlight_bounds;
mod terminator;
mod tile_stores;
mod true_scale;
mod water;
mod wedges;
