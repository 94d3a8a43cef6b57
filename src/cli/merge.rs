//! `heightray merge PARTS... -o poster.png`: tiles rendered by `render --tile` or `--tiles`
//! joined into the whole picture, each placed where its PNG says it lies. Refused unless the
//! parts are of one picture and cover it exactly once.

use super::MergeArgs;
use heightray::batch::{TilePlace, TILE_KEYWORD};
use heightray::output_file;
use std::fs::File;
use std::io::BufReader;
use std::path::Path;
use std::process::ExitCode;

/// The picture being joined: its size, its pixels (0x00RRGGBB) and which are covered.
struct Canvas {
    size: (u32, u32),
    pixels: Vec<u32>,
    covered: Vec<bool>,
}

pub fn run(args: &MergeArgs) -> anyhow::Result<ExitCode> {
    output_file::check_image(&args.output).map_err(anyhow::Error::msg)?;
    let mut whole: Option<Canvas> = None;
    for part in &args.parts {
        let place = place_of(part)?;
        let image = image::open(part)
            .map_err(|e| anyhow::anyhow!("cannot read tile {}: {e}", part.display()))?
            .to_rgb8();
        let window = place.window;
        anyhow::ensure!(
            image.dimensions() == (window.width, window.height),
            "tile {} is {}x{}, but says it is {}x{}",
            part.display(),
            image.width(),
            image.height(),
            window.width,
            window.height
        );
        let Canvas {
            size,
            pixels,
            covered,
        } = whole.get_or_insert_with(|| {
            let n = place.whole.0 as usize * place.whole.1 as usize;
            Canvas {
                size: place.whole,
                pixels: vec![0; n],
                covered: vec![false; n],
            }
        });
        anyhow::ensure!(
            *size == place.whole,
            "tile {} is part of a {}x{} picture, the tiles before it of a {}x{} one",
            part.display(),
            place.whole.0,
            place.whole.1,
            size.0,
            size.1
        );
        for (x, y, rgb) in image.enumerate_pixels() {
            let at = (y + window.y) as usize * size.0 as usize + (x + window.x) as usize;
            anyhow::ensure!(
                !covered[at],
                "tile {} overlaps another at pixel ({}, {}): give each tile once",
                part.display(),
                x + window.x,
                y + window.y
            );
            covered[at] = true;
            let [r, g, b] = rgb.0;
            pixels[at] = u32::from(r) << 16 | u32::from(g) << 8 | u32::from(b);
        }
    }
    let Some(Canvas {
        size,
        pixels,
        covered,
    }) = whole
    else {
        anyhow::bail!("no tiles given to merge");
    };
    let missing = covered.iter().filter(|&&c| !c).count();
    anyhow::ensure!(
        missing == 0,
        "the tiles leave {missing} of the picture's {} pixels uncovered: a tile is missing",
        covered.len()
    );
    output_file::save_rgb(&args.output, &pixels, size).map_err(anyhow::Error::msg)?;
    eprintln!(
        "{} tiles merged into {} ({}x{})",
        args.parts.len(),
        args.output.display(),
        size.0,
        size.1
    );
    Ok(ExitCode::SUCCESS)
}

/// Where the tile in `path` lies, from its PNG text chunk.
fn place_of(path: &Path) -> anyhow::Result<TilePlace> {
    let cannot =
        |e: &dyn std::fmt::Display| anyhow::anyhow!("cannot read tile {}: {e}", path.display());
    let file = File::open(path).map_err(|e| cannot(&e))?;
    let reader = png::Decoder::new(BufReader::new(file))
        .read_info()
        .map_err(|e| cannot(&e))?;
    reader
        .info()
        .uncompressed_latin1_text
        .iter()
        .find(|chunk| chunk.keyword == TILE_KEYWORD)
        .and_then(|chunk| TilePlace::from_text(&chunk.text))
        .ok_or_else(|| {
            anyhow::anyhow!(
                "{} is not a tile: it does not say where it lies (tiles are made by \
                 `heightray render --tile` or `--tiles`)",
                path.display()
            )
        })
}
