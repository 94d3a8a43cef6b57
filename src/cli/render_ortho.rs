//! `heightray render MAP --ortho`: a map product made straight down ([`heightray::products`]),
//! written as a GeoTIFF on the map's own grid or as a PNG picture; and TIFF output of pictures
//! (`--depth 16`, `--dpi`).

use super::render::Setup;
use super::{ortho_args::OrthoArgs, RenderArgs};
use heightray::heightfield::place;
use heightray::output_file;
use heightray::products::tiff_out::{self, Depth, GeoTags, TiffTags};
use heightray::products::{
    Horizon, Maker, MapContours, OrthoGrid, Raster, Rgba16, SkyView, SunPath, Sunlight,
};
use heightray::render::{level_z, local_time, Contours, Culling, Frame, Shader};
use heightray::TraceOptions;
use image::{DynamicImage, GrayAlphaImage, ImageFormat, LumaA, Rgba, RgbaImage};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// Whether `path` names a TIFF.
pub fn is_tiff(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("tif") || e.eq_ignore_ascii_case("tiff"))
}

/// The TIFF depth asked for.
fn depth(args: &OrthoArgs) -> Depth {
    match args.depth.as_str() {
        "16" => Depth::Sixteen,
        _ => Depth::Eight,
    }
}

/// The resolution asked for, checked.
fn dpi(args: &OrthoArgs) -> anyhow::Result<Option<f64>> {
    match args.dpi {
        Some(dpi) if !(dpi.is_finite() && (1.0..=100_000.0).contains(&dpi)) => {
            anyhow::bail!("--dpi must be from 1 to 100000, got {dpi}")
        }
        dpi => Ok(dpi),
    }
}

/// Checks that `--depth` and `--dpi` go with a TIFF output (not frames, tiles or a PNG).
pub fn check_tiff_options(args: &RenderArgs) -> anyhow::Result<()> {
    let asked = args.ortho.depth != "8" || args.ortho.dpi.is_some();
    let batch = args.frames.is_some() || args.tile.is_some() || args.tiles.is_some();
    anyhow::ensure!(
        !(asked && batch),
        "--depth and --dpi are written into one picture's TIFF: frames and tiles are 8-bit PNGs"
    );
    anyhow::ensure!(
        !asked || is_tiff(&args.output),
        "--depth and --dpi are written into TIFFs: name the output .tif (got {})",
        args.output.display()
    );
    dpi(&args.ortho).map(|_| ())
}

/// Whether the output is a 16-bit TIFF: its picture is then rendered with 16-bit words
/// ([`Frame::with_words`]).
pub fn sixteen_bits(args: &RenderArgs) -> bool {
    is_tiff(&args.output) && depth(&args.ortho) == Depth::Sixteen
}

/// Writes a rendered picture as a TIFF at the depth and resolution asked for: from its words
/// where it has them, else from its bytes.
pub fn save_tiff(args: &RenderArgs, frame: &Frame) -> anyhow::Result<()> {
    let wide: Vec<[u16; 4]> = match frame.words.is_empty() {
        true => frame
            .pixels
            .iter()
            .map(|&rgb| {
                // Bytes widened exactly: byte b is 257 b of 65535.
                let [_, r, g, b] = rgb.to_be_bytes();
                [r, g, b, 255].map(|c| u16::from(c) * 257)
            })
            .collect(),
        false => frame
            .words
            .iter()
            .map(|&[r, g, b]| [r, g, b, u16::MAX])
            .collect(),
    };
    let size = (frame.width, frame.height);
    let tags = TiffTags {
        geo: None,
        dpi: dpi(&args.ortho)?,
    };
    output_file::write(&args.output, |out| {
        tiff_out::write_colour(out, size, &wide, depth(&args.ortho), &tags)
    })
    .map_err(anyhow::Error::msg)
}

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    let ortho = &args.ortho;
    let tiff = is_tiff(&args.output);
    if tiff {
        output_file::check(&args.output, "relief.tif").map_err(anyhow::Error::msg)?;
    } else {
        anyhow::ensure!(
            ImageFormat::from_path(&args.output).ok() == Some(ImageFormat::Png),
            "--ortho writes a GeoTIFF (.tif) or a PNG picture (.png), not {}",
            args.output.display()
        );
        output_file::check(&args.output, "relief.png").map_err(anyhow::Error::msg)?;
    }
    let sky_view =
        SkyView::new(ortho.svf_directions, ortho.svf_radius).map_err(anyhow::Error::msg)?;
    anyhow::ensure!(
        ortho.product == "sunlight-hours" || ortho.date.is_none(),
        "--date is for --product sunlight-hours"
    );
    let setup = Setup::new(args)?;
    let terrain = &setup.terrain;
    let grid = OrthoGrid::over(terrain.field(), ortho.cell).map_err(anyhow::Error::msg)?;
    let contours = contours(args, &setup)?;
    let options = TraceOptions::new(setup.method, setup.arith);
    let mut lighting = setup.lighting;
    // Seen straight down from just above the terrain: no haze, and no base under holes,
    // which stay transparent.
    lighting.fog = 0.0;
    let maker = match ortho.product.as_str() {
        "sky-view" => Maker::SkyView(sky_view, Horizon::new(terrain)),
        "sunlight-hours" => {
            let path = sun_path(args, terrain.field())?;
            eprintln!(
                "the sun is up {:.2} h of {} steps of {} minutes ({})",
                path.daylight_hours(),
                path.steps,
                ortho.sun_step,
                path.zone
            );
            let bounds = ortho.strip_bounds == "on";
            Maker::Sunlight(Sunlight::with_bounds(terrain, &path, options, bounds))
        }
        _ => {
            let mut shader = Shader::new(terrain, lighting, setup.method, Culling::default());
            shader.base = None;
            // A PNG picture is 8-bit.
            let depth = if tiff { depth(ortho) } else { Depth::Eight };
            Maker::Shaded(Box::new(shader), setup.arith, depth)
        }
    };
    if let Some(exaggeration) = heightray::heightfield::relief::exaggeration(terrain.field()) {
        if ortho.product != "shaded" && (exaggeration - 1.0).abs() > 1e-9 {
            eprintln!(
                "note: heights are exaggerated x{exaggeration:.2}: angles are not the ground's"
            );
        }
    }
    let bar = ProgressBar::new(u64::from(grid.height)).with_style(
        ProgressStyle::with_template("{msg} {bar:40} {pos}/{len} rows {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(ortho.product.clone());
    let start = Instant::now();
    let raster = setup.pool.install(|| maker.raster(&grid, &|| bar.inc(1)));
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    let size = (grid.width, grid.height);
    let range = match &raster {
        Raster::Values(values) => value_range(values),
        Raster::Colour(_) => None,
    };
    let raster = match contours {
        Some(lines) => {
            let mut pixels = match raster {
                Raster::Colour(pixels) => pixels,
                Raster::Values(values) => grey(&values, stretch(&values)),
            };
            let labels = lines
                .draw(terrain.field(), &grid, &mut pixels)
                .map_err(anyhow::Error::msg)?;
            eprintln!("contour lines drawn, {} index labels", labels.len());
            Raster::Colour(pixels)
        }
        None => raster,
    };
    if tiff {
        let geo = grid
            .geotransform()
            .zip(grid.georef())
            .map(|(transform, georef)| GeoTags::new(&transform, georef));
        if geo.is_none() {
            eprintln!(
                "note: the map has no georeferencing: {} is a plain TIFF",
                args.output.display()
            );
        }
        let tags = TiffTags {
            geo,
            dpi: dpi(ortho)?,
        };
        output_file::write(&args.output, |out| match &raster {
            Raster::Colour(pixels) => {
                tiff_out::write_colour(out, size, pixels, depth(ortho), &tags)
            }
            Raster::Values(values) => tiff_out::write_values(out, size, values, &tags),
        })
        .map_err(anyhow::Error::msg)?;
    } else {
        let shown = match &raster {
            Raster::Values(values) => stretch(values),
            Raster::Colour(_) => None,
        };
        save_png(&args.output, size, &raster, shown)?;
    }
    let transform = grid
        .geotransform()
        .map(|t| format!(", geotransform {t:?}"))
        .unwrap_or_default();
    let values = range
        .map(|(lo, hi)| format!(", values {lo:.4} to {hi:.4}"))
        .unwrap_or_default();
    println!(
        "{}: {} {}x{} in {seconds:.2} s ({} threads){transform}{values}",
        args.output.display(),
        ortho.product,
        grid.width,
        grid.height,
        setup.pool.current_num_threads()
    );
    Ok(ExitCode::SUCCESS)
}

/// The contour lines drawn over the product: `--contours` (with `--index-every`) or the
/// scene's; none over a product's values, which a line would falsify.
fn contours(args: &RenderArgs, setup: &Setup) -> anyhow::Result<Option<MapContours>> {
    let ortho = &args.ortho;
    let field = setup.terrain.field();
    let scene_index = setup.contours.map(|c| c.index_every());
    let asked = match ortho.contours {
        Some(interval) => {
            let index = ortho.index_every.or(scene_index).unwrap_or(5);
            let lines = Contours::new(level_z(field, interval), index);
            anyhow::ensure!(
                lines.is_some(),
                "--contours must be a finite height interval > 0, got {interval}"
            );
            lines
        }
        None => {
            anyhow::ensure!(
                ortho.index_every.is_none() || setup.contours.is_some(),
                "--index-every goes with --contours (or a scene's [overlay] contours)"
            );
            let index = ortho.index_every.or(scene_index).unwrap_or(5);
            setup
                .contours
                .and_then(|c| Contours::new(c.interval_z(), index))
        }
    };
    let Some(lines) = asked else {
        return Ok(None);
    };
    if ortho.product != "shaded" && is_tiff(&args.output) {
        anyhow::ensure!(
            ortho.contours.is_none(),
            "--contours draws on pictures: --product {} writes values into {}; write a .png \
             picture, or use --product shaded",
            ortho.product,
            args.output.display()
        );
        eprintln!("note: the scene's contour lines are not drawn into the product's values");
        return Ok(None);
    }
    Ok(Some(MapContours::new(&lines, field)))
}

/// Values as a grey picture: the least of `range` black, the greatest white; no value
/// transparent.
fn grey(values: &[f32], range: Option<(f32, f32)>) -> Vec<Rgba16> {
    let (lo, hi) = range.unwrap_or((0.0, 1.0));
    values
        .iter()
        .map(|&v| {
            if v.is_nan() {
                return [0; 4];
            }
            let share = if hi > lo {
                ((v - lo) / (hi - lo)).clamp(0.0, 1.0)
            } else {
                1.0
            };
            let level = (share * 255.0).round() as u16 * 257;
            [level, level, level, u16::MAX]
        })
        .collect()
}

/// The sun over `--date` at the map's centre, on its local clocks (UTC where no zone is
/// known).
fn sun_path(args: &RenderArgs, field: &heightray::Heightfield) -> anyhow::Result<SunPath> {
    let Some(date) = args.ortho.date else {
        anyhow::bail!("--product sunlight-hours needs --date YYYY-MM-DD");
    };
    let Some((latitude, longitude)) = place::centre_degrees(field) else {
        anyhow::bail!(
            "sunlight hours need the map's place on the Earth: {} is not georeferenced by \
             longitude and latitude or an EPSG code",
            args.scene.display()
        );
    };
    let zone = local_time::zone_at(latitude, longitude).unwrap_or(chrono_tz::UTC);
    Ok(SunPath::over_day(
        date,
        (latitude, longitude),
        zone,
        args.ortho.sun_step,
    )?)
}

/// The least and greatest value that is not NaN.
fn value_range(values: &[f32]) -> Option<(f32, f32)> {
    values
        .iter()
        .filter(|v| !v.is_nan())
        .fold(None, |range, &v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// The 2nd and 98th percentiles of the values that are not NaN: a picture's grey scale,
/// which a few extreme pixels (a pit, a peak) would otherwise flatten.
fn stretch(values: &[f32]) -> Option<(f32, f32)> {
    let mut finite: Vec<f32> = values.iter().copied().filter(|v| !v.is_nan()).collect();
    finite.sort_unstable_by(f32::total_cmp);
    let at = |share: f64| finite[((finite.len() - 1) as f64 * share).round() as usize];
    (!finite.is_empty()).then(|| (at(0.02), at(0.98)))
}

/// A product as a picture: colour as it is, a quantity in grey from the least (black) to the
/// greatest value of `range` (white); no surface transparent.
fn save_png(
    path: &Path,
    (width, height): (u32, u32),
    raster: &Raster,
    range: Option<(f32, f32)>,
) -> anyhow::Result<()> {
    let at = |x: u32, y: u32| y as usize * width as usize + x as usize;
    let image = match raster {
        Raster::Colour(pixels) => {
            DynamicImage::ImageRgba8(RgbaImage::from_fn(width, height, |x, y| {
                Rgba(pixels[at(x, y)].map(|c| ((u32::from(c) + 128) / 257) as u8))
            }))
        }
        // (Grey and alpha: a quarter of the bytes of colour, and as many shades.)
        Raster::Values(values) => {
            // Byte `b` widened is `257 b`: its high byte is `b` again.
            let pixels = grey(values, range);
            DynamicImage::ImageLumaA8(GrayAlphaImage::from_fn(width, height, |x, y| {
                let [level, _, _, alpha] = pixels[at(x, y)];
                LumaA([(level >> 8) as u8, (alpha >> 8) as u8])
            }))
        }
    };
    output_file::write(path, |out| {
        image
            .write_to(out, ImageFormat::Png)
            .map_err(|e| format!("cannot write {}: {e}", path.display()))
    })
    .map_err(anyhow::Error::msg)
}
