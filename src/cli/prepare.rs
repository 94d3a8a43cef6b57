//! `heightray prepare`: a tile store made once from a large map or a mosaic of tiles, with a
//! progress bar; run again with the same inputs, it goes on where it stopped.

use super::MapArgs;
use heightray::heightfield::store::{self, Stage};
use heightray::heightfield::LoadOptions;
use indicatif::{ProgressBar, ProgressStyle};
use std::ops::ControlFlow;
use std::os::unix::fs::MetadataExt;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct PrepareArgs {
    /// Input maps: one map, or georeferenced tiles on one grid (GeoTIFF, .hgt, .asc, PNG...)
    /// joined as a mosaic; samples no tile covers are holes, and are not stored.
    #[arg(required = true, value_name = "INPUT")]
    pub inputs: Vec<PathBuf>,
    /// The store to write (`.hrt`), which `view` and `render` open as a map.
    #[arg(short, long)]
    pub output: PathBuf,
    #[command(flatten)]
    pub loading: MapArgs,
}

/// Prepares the store and prints what it holds.
pub fn run(args: &PrepareArgs) -> anyhow::Result<ExitCode> {
    let options = LoadOptions {
        z_scale: 1.0,
        colour: args.loading.rgb,
        nodata: args.loading.nodata,
        height_unit: None,
    };
    let bar = ProgressBar::new(1000).with_style(
        ProgressStyle::with_template("{msg} {bar:40} {percent}% {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let start = Instant::now();
    let header = store::prepare(&args.inputs, &args.output, &options, &|stage, fraction| {
        bar.set_message(match stage {
            Stage::Planning => "reading the inputs",
            Stage::Writing => "writing samples",
            Stage::Building => "building the mipmap",
        });
        bar.set_position((fraction * 1000.0) as u64);
        ControlFlow::Continue(())
    });
    bar.finish_and_clear();
    let header = header?;
    let metadata = std::fs::metadata(&args.output)?;
    eprintln!(
        "{}: {}x{} samples from {} input(s), {} holes; {:.2} GB long, {:.2} GB on disk; \
         prepared in {:.1} s",
        args.output.display(),
        header.width,
        header.height,
        header.inputs.len(),
        header.holes.unwrap_or(0),
        metadata.len() as f64 / 1e9,
        (metadata.blocks() * 512) as f64 / 1e9,
        start.elapsed().as_secs_f64()
    );
    Ok(ExitCode::SUCCESS)
}
