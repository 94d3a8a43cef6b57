//! `heightray render SCENE --tile I/N -o part.png` (band I of N), `--tiles CxR --tile I -o
//! part.png` (tile I of a grid), or `--tiles CxR [--tile-of K/N] -o DIR/` (every tile, or a
//! worker's share, as `DIR/tile-007.png`): parts of one picture that `heightray merge` joins
//! into exactly the whole. Each tile is rendered with a margin as wide as adaptive sampling's
//! decisions reach ([`reach`]), so its pixels are the whole picture's; the PNG keeps the tile's
//! place in a text chunk.

use super::render::Setup;
use super::render_frames::{is_whole_image, output_folder};
use super::render_progress::Progress;
use super::RenderArgs;
use heightray::batch::{BatchError, Share, TileGrid, TilePlace, TILE_KEYWORD};
use heightray::output_file;
use heightray::render::reach;
use heightray::render::Frame;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::str::FromStr;

/// `--tile I` or `--tile I/N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileArg {
    index: u64,
    /// Bands, for `I/N`.
    bands: Option<u32>,
}

/// Why a `--tile` value is refused.
#[derive(Debug, thiserror::Error)]
pub enum TileArgError {
    /// Not `I/N`.
    #[error(transparent)]
    Share(#[from] BatchError),
    /// Too many bands.
    #[error("--tile {0}: at most 65536 bands")]
    Bands(String),
}

impl FromStr for TileArg {
    type Err = TileArgError;
    fn from_str(s: &str) -> Result<TileArg, TileArgError> {
        if let Ok(index) = s.trim().parse::<u64>() {
            return Ok(TileArg { index, bands: None });
        }
        let share: Share = s.parse()?;
        let bands = u32::try_from(share.count)
            .ok()
            .filter(|&n| n <= 65536)
            .ok_or_else(|| TileArgError::Bands(s.to_owned()))?;
        Ok(TileArg {
            index: share.index,
            bands: Some(bands),
        })
    }
}

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    let grid = match (args.tiles, args.tile) {
        (Some(grid), Some(TileArg { bands: Some(_), .. })) => anyhow::bail!(
            "--tiles {}x{} numbers its tiles itself: give --tile I (0 to {}), not I/N",
            grid.columns,
            grid.rows,
            grid.count() - 1
        ),
        (Some(grid), _) => grid,
        (
            None,
            Some(TileArg {
                bands: Some(bands), ..
            }),
        ) => TileGrid::bands(bands),
        (None, _) => {
            anyhow::bail!("--tile I needs --tiles COLUMNSxROWS; or give --tile I/N for band I of N")
        }
    };
    // One tile to a file, or tiles into a folder.
    let (indices, folder): (Vec<u64>, Option<&Path>) = match args.tile {
        Some(tile) => {
            output_file::check_image(&args.output).map_err(anyhow::Error::msg)?;
            (vec![tile.index], None)
        }
        None => {
            output_folder(&args.output)?;
            let all: Vec<u64> = (0..grid.count()).collect();
            (
                args.tile_of.unwrap_or(Share::ALL).of(&all),
                Some(&args.output),
            )
        }
    };
    let setup = Setup::new(args)?;
    let size = setup.camera.size();
    let margin = reach(&setup.lighting.effects);
    let places = indices
        .iter()
        .map(|&i| grid.tile(i, size).map(|place| (i, place)))
        .collect::<Result<Vec<_>, BatchError>>()?;
    let path_of = |index: u64| match folder {
        Some(folder) => tile_file(folder, index),
        None => args.output.clone(),
    };
    let to_do: Vec<(u64, TilePlace)> = places
        .into_iter()
        .filter(|&(index, place)| {
            let tile_size = (place.window.width, place.window.height);
            folder.is_none() || args.force || !is_whole_image(&path_of(index), tile_size)
        })
        .collect();
    let pixels: u64 = to_do
        .iter()
        .map(|(_, p)| {
            let grown = p.grown(margin);
            u64::from(grown.width) * u64::from(grown.height)
        })
        .sum();
    let progress = Progress::new(pixels);
    for (index, place) in to_do {
        let grown = place.grown(margin);
        let camera = setup
            .camera
            .window(grown)
            .ok_or_else(|| anyhow::anyhow!("tile {index} lies outside the image"))?;
        let renderer = setup.renderer(camera);
        let mut frame = Frame::new(grown.width, grown.height);
        setup
            .pool
            .install(|| progress.render(&renderer, &mut frame));
        // The whole picture's annotations, this tile's part of them.
        setup.annotate(setup.camera, &mut frame.pixels, grown)?;
        let pixels = crop(
            &frame,
            place.window.x - grown.x,
            place.window.y - grown.y,
            place,
        );
        let path = path_of(index);
        save_tile(&path, &pixels, place)?;
        progress.finished(&path.display().to_string());
    }
    progress.done();
    Ok(ExitCode::SUCCESS)
}

/// The file tile `index` goes to in `folder`: `tile-007.png`.
pub fn tile_file(folder: &Path, index: u64) -> PathBuf {
    folder.join(format!("tile-{index:03}.png"))
}

/// The tile's pixels out of a frame rendered with a margin, from `(dx, dy)` in it.
fn crop(frame: &Frame, dx: u32, dy: u32, place: TilePlace) -> Vec<u32> {
    let (w, h) = (place.window.width as usize, place.window.height as usize);
    let stride = frame.width as usize;
    (0..h)
        .flat_map(|y| {
            let start = (y + dy as usize) * stride + dx as usize;
            frame.pixels[start..start + w].iter().copied()
        })
        .collect()
}

/// Writes a tile as an 8-bit RGB PNG whose text chunk gives its place, atomically.
fn save_tile(path: &Path, pixels: &[u32], place: TilePlace) -> anyhow::Result<()> {
    let bytes: Vec<u8> = pixels
        .iter()
        .flat_map(|&rgb| [(rgb >> 16) as u8, (rgb >> 8) as u8, rgb as u8])
        .collect();
    let cannot = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
    output_file::write(path, |out| {
        let mut encoder = png::Encoder::new(out, place.window.width, place.window.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder
            .add_text_chunk(TILE_KEYWORD.into(), place.to_text())
            .map_err(|e| cannot(&e))?;
        let mut writer = encoder.write_header().map_err(|e| cannot(&e))?;
        writer.write_image_data(&bytes).map_err(|e| cannot(&e))?;
        writer.finish().map_err(|e| cannot(&e))
    })
    .map_err(anyhow::Error::msg)
}
