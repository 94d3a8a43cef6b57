//! `heightray generate`: the built-in terrain generator as a PNG file, or as a GeoTIFF of the
//! whole map or of one window of it, so that a map larger than memory is made tile by tile.

use super::knobs;
use heightray::heightfield::{landscape, landscape_window, Georef, MapUnits};
use heightray::output_file;
use heightray::products::tiff_out::{write_gray16, GeoTags, TiffTags};
use image::{ImageBuffer, ImageFormat, Luma};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct GenerateArgs {
    /// Samples per side of the map (at most 16385 for a PNG, which holds the whole map).
    #[arg(long, default_value_t = 513, value_parser = knobs::generated_map_size)]
    pub size: usize,
    /// Noise seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output: a PNG (the whole map, normalised over its own range), or a GeoTIFF (.tif) of
    /// the window, normalised over a range the seed fixes, so that windows join seamlessly.
    #[arg(short, long)]
    pub output: PathBuf,
    /// The window to write, X,Y,WIDTH,HEIGHT in samples from the map's north-west corner
    /// (GeoTIFF only; default: the whole map).
    #[arg(long, value_parser = knobs::window, value_name = "X,Y,W,H")]
    pub window: Option<[usize; 4]>,
    /// Metres from one sample to the next in a GeoTIFF (default: the heights' full range,
    /// 65535 m, is a quarter of the map's width, the relief a PNG's is viewed with).
    #[arg(long)]
    pub spacing: Option<f64>,
}

pub fn run(args: &GenerateArgs) -> anyhow::Result<ExitCode> {
    let format = output_file::check_image(&args.output).map_err(anyhow::Error::msg)?;
    if format == ImageFormat::Tiff {
        return tile(args);
    }
    anyhow::ensure!(
        args.window.is_none() && args.spacing.is_none(),
        "--window and --spacing write a GeoTIFF: name the output .tif"
    );
    anyhow::ensure!(
        args.size <= 16385,
        "a PNG holds the whole map, at most 16385 samples a side; write a larger map window \
         by window as GeoTIFF tiles (--window X,Y,W,H -o tile.tif)"
    );
    let field = landscape(args.size, args.seed, 1.0)?;
    let (w, h) = (field.width(), field.height());
    // Image row 0 is the northern edge (y = H-1).
    let image = ImageBuffer::from_fn(w as u32, h as u32, |x, r| {
        Luma([field.sample(x as usize, h - 1 - r as usize)])
    });
    output_file::write(&args.output, |out| {
        image
            .write_to(out, format)
            .map_err(|e| format!("cannot write {}: {e}", args.output.display()))
    })
    .map_err(anyhow::Error::msg)?;
    Ok(ExitCode::SUCCESS)
}

/// Writes the window as a 16-bit GeoTIFF in metres on a projected grid whose north-west
/// corner lies at (0, size x spacing), so that every window of the map lies on one grid.
fn tile(args: &GenerateArgs) -> anyhow::Result<ExitCode> {
    let size = args.size;
    let window = args.window.unwrap_or([0, 0, size, size]);
    let spacing = args.spacing.unwrap_or(65535.0 / ((size - 1) as f64 / 4.0));
    anyhow::ensure!(
        spacing.is_finite() && spacing > 0.0 && spacing * size as f64 <= 1e9,
        "--spacing must be above 0 and the map at most 10^9 m wide, got {spacing}"
    );
    let samples = landscape_window(size, args.seed, window)?;
    let [x0, y0, w, h] = window;
    let corner = [x0 as f64 * spacing, (size - y0) as f64 * spacing];
    let transform = [corner[0], spacing, 0.0, corner[1], 0.0, -spacing];
    let georef = Georef::new(corner, [spacing; 2], MapUnits::Linear { metres: 1.0 })?;
    let tags = TiffTags {
        geo: Some(GeoTags::new(&transform, &georef)),
        dpi: None,
    };
    let dims = (u32::try_from(w)?, u32::try_from(h)?);
    output_file::write(&args.output, |out| {
        write_gray16(out, dims, &samples, &tags)
            .map_err(|e| format!("cannot write {}: {e}", args.output.display()))
    })
    .map_err(anyhow::Error::msg)?;
    Ok(ExitCode::SUCCESS)
}
