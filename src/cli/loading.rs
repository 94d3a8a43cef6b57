//! Loading on the command line: progress on stderr while a big map decodes and builds
//! (nothing is drawn when stderr is not a terminal), then one summary line.

use super::MapArgs;
use heightray::heightfield::store::residency;
use heightray::heightfield::{load_with, LoadOptions};
use heightray::Terrain;
use indicatif::{ProgressBar, ProgressStyle};
use std::ops::ControlFlow;
use std::path::Path;
use std::time::{Duration, Instant};

/// Decodes a height map with a progress bar and builds its acceleration data.
pub fn map(path: &Path, z_scale: f64, args: &MapArgs) -> anyhow::Result<Terrain> {
    let options = LoadOptions {
        z_scale,
        colour: args.rgb,
        nodata: args.nodata,
        height_unit: None,
    };
    let bar = ProgressBar::new(1000).with_style(
        ProgressStyle::with_template("decoding {msg} {bar:40} {percent}% {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(path.display().to_string());
    let start = Instant::now();
    let field = load_with(path, &options, &|fraction| {
        bar.set_position((fraction * 1000.0) as u64);
        ControlFlow::Continue(())
    });
    bar.finish_and_clear();
    let field = field?;
    let decode_time = start.elapsed();
    let terrain = stage("building acceleration data", || Terrain::new(field));
    summary(path, &terrain, decode_time);
    Ok(terrain)
}

/// Runs `work` with a spinner that names it and counts the seconds.
pub fn stage<T>(label: &str, work: impl FnOnce() -> T) -> T {
    let spinner = ProgressBar::new_spinner().with_message(label.to_owned());
    spinner.set_style(
        ProgressStyle::with_template("{spinner} {msg} {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    spinner.enable_steady_tick(Duration::from_millis(200));
    let result = work();
    spinner.finish_and_clear();
    result
}

/// The summary line: what was loaded and how long reading and building took.
pub fn summary(label: &Path, terrain: &Terrain, read_time: Duration) {
    eprintln!(
        "{}: {}; read in {:.2} s, built in {:.2} s",
        label.display(),
        terrain.summary(),
        read_time.as_secs_f64(),
        terrain.build_time().as_secs_f64()
    );
}

/// After work on a map from a tile store: its size, the process's resident memory now and at
/// most, the budget its pages were held to, and where its page faults were served from (the
/// page cache's hit rate).
pub fn store_memory(terrain: &Terrain) {
    let field = terrain.field();
    let Some(bytes) = field.store_bytes() else {
        return;
    };
    let memory = residency::process_memory();
    let store = residency::residency();
    let hits = memory
        .hit_rate()
        .map_or("no page faults".to_owned(), |rate| {
            format!("{:.2}% served from memory", rate * 100.0)
        });
    eprintln!(
        "tile store: {}x{} samples, {:.2} GB; resident memory {:.0} MB, peak {:.0} MB (the \
         store's pages held to {:.0} MB, {:.0} MB let go of); page faults {hits} ({} from \
         memory, {} read from disk)",
        field.width(),
        field.height(),
        bytes as f64 / 1e9,
        memory.resident as f64 / 1e6,
        memory.peak_resident as f64 / 1e6,
        residency::budget() as f64 / 1e6,
        store.released as f64 / 1e6,
        memory.minor_faults,
        memory.major_faults
    );
}
