//! Command-line arguments and the subcommands (README, 'The command line').

mod accuracy;
mod bench;
mod bench_compare;
mod bench_effects;
mod bench_out_of_core;
mod flight_args;
mod generate;
mod knobs;
mod loading;
mod merge;
mod ortho_args;
mod prepare;
mod render;
mod render_frames;
mod render_ortho;
mod render_progress;
mod render_tiles;
mod speed_report;
mod submit;
mod trace;
mod video;

use clap::{Parser, Subcommand};
pub use flight_args::{MergeArgs, SlurmArgs, SubmitCommand, VideoArgs};
use heightray::batch::{FrameSpec, Share, TileGrid};
use heightray::compact::Compact;
use heightray::heightfield::{ColourEncoding, NoDataValue};
use heightray::render::MAX_PIXELS;
use heightray::{Arith, Method};
use knobs::ValueError;
use std::path::PathBuf;
use std::process::ExitCode;

/// Exact, fast ray tracing of terrain height fields on the CPU.
///
/// Without a subcommand, opens the viewer (on the built-in terrain, or FILE_OR_SCENE).
#[derive(Parser, Debug)]
#[command(
    name = "heightray",
    version,
    about,
    args_conflicts_with_subcommands = true
)]
pub struct Args {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Memory the pages of an open tile store (.hrt) may hold, e.g. 4G or 512M (default: half
    /// the machine's memory).
    #[arg(long, global = true, value_parser = knobs::bytes, value_name = "BYTES")]
    pub memory: Option<u64>,
    #[command(flatten)]
    pub view: ViewArgs,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Open the interactive viewer (the default without a subcommand).
    View(ViewArgs),
    /// Render a scene file to a PNG, with statistics.
    Render(RenderArgs),
    /// Trace rays against a height field and print one JSON object per ray.
    Trace(TraceArgs),
    /// Benchmarks: `speed` (rays per second of whole frames), `accuracy` (time against error),
    /// `textbook` (the mipmap walk against the textbook walk without its guarantees),
    /// `effects` (what each effect costs), `compare` (two binaries' `speed` in turn).
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Write a generated landscape of the built-in generator: a 16-bit grayscale PNG, or a
    /// GeoTIFF of the whole map or of one window of it (a tile of a map of any size).
    Generate(generate::GenerateArgs),
    /// Join tiles made by `render --tile` or `--tiles` into the whole picture.
    Merge(MergeArgs),
    /// Encode a folder of frames (`frame-00000.png`...) as an H.264 MP4 with ffmpeg.
    Video(VideoArgs),
    /// Hand frames or tiles to a cluster's scheduler as a job array.
    #[command(subcommand)]
    Submit(SubmitCommand),
    /// Prepare a tile store (.hrt) once from a map larger than memory or a mosaic of tiles;
    /// `view` and `render` then open it directly, reading only what the rays touch.
    Prepare(prepare::PrepareArgs),
}

#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// Height map (PNG, PGM, TIFF, .hgt or .asc, see `trace --help`) or scene file (.toml), or
    /// several georeferenced tiles to join into one map; default: the built-in terrain.
    #[arg(value_name = "FILE_OR_SCENE")]
    pub sources: Vec<PathBuf>,
    /// Height of the largest sample value (default: a built-in's or scene's own; a quarter
    /// of the larger side for an image).
    #[arg(long)]
    pub z_scale: Option<f64>,
    #[command(flatten)]
    pub loading: MapArgs,
    /// Window size in logical pixels, WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, default_value = "1280x720")]
    pub size: (u32, u32),
    /// Rays per physical pixel along each axis (default: one per logical pixel).
    #[arg(long)]
    pub render_scale: Option<f32>,
    /// Quit after this many fully refined frames have been shown (for scripts and tests).
    #[arg(long)]
    pub exit_after_frames: Option<u64>,
    /// With --exit-after-frames: save the window's last frame (panels included) there.
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Folder that S exports rendered images to (default: the current directory).
    #[arg(long, value_name = "DIR")]
    pub export_dir: Option<PathBuf>,
    /// Size S exports at, WIDTHxHEIGHT, rendered anew (default: the view's render size).
    #[arg(long, value_parser = parse_size, value_name = "WIDTHxHEIGHT")]
    pub export_size: Option<(u32, u32)>,
    /// Write the window's state as JSON to this file after every frame (for tests).
    #[arg(long)]
    pub report_state: Option<PathBuf>,
}

#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Primary and shadow rays per second on the built-in scenes, per method, arithmetic and
    /// thread count, as ratios.
    Speed(SpeedArgs),
    /// Time per primary ray, queries per ray and answers that differ from exact arithmetic,
    /// per method and arithmetic, one thread.
    Accuracy(AccuracyArgs),
    /// Time per camera ray of the mipmap walk in f64 against the textbook max-mipmap walk,
    /// which makes the same queries without the rounding slack, lattice points and
    /// watertight triangle test that make heightray exact: what those cost (one thread), and
    /// what they buy (answers on the hard-case sets that differ from exact).
    Textbook(TextbookArgs),
    /// What soft shadows, sky light and samples per pixel cost on the built-in scenes, each
    /// alone and all together in one run, as ratios to the plain frame; and how samples per
    /// pixel converge to a supersampled reference.
    Effects(EffectsArgs),
    /// Two heightray binaries measure the same `bench speed` frames in turn, round after
    /// round: each row's rays per second and frame time, new over old, with their spread.
    Compare(CompareArgs),
}

#[derive(clap::Args, Debug)]
pub struct EffectsArgs {
    /// Scene files (default: the built-in scenes).
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<PathBuf>,
    /// Image width and height.
    #[arg(long, default_value_t = 256, value_parser = knobs::bench_image_size)]
    pub size: u32,
    /// Samples per pixel of the sampled frames.
    #[arg(long, default_value_t = 16)]
    pub samples: u32,
    /// The sun's angular diameter of the soft-shadow frames, in degrees.
    #[arg(long, default_value_t = 0.53)]
    pub sun_angle_deg: f64,
    /// Also cast every ray of the one-sample frames (the sun's shadow ray, soft-shadow and
    /// sky rays) with Embree 3 from its own hits, none culled, and set the frames side by side
    /// (needs a build with `--features embree`).
    #[arg(long)]
    pub embree: bool,
    /// Worker threads (default: all cores; at most 4 a core are used).
    #[arg(long, value_parser = knobs::threads)]
    pub threads: Option<usize>,
    /// Also write every figure as JSON here.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

#[derive(clap::Args, Debug)]
pub struct SpeedArgs {
    #[command(flatten)]
    pub frames: SpeedFrames,
    /// Also measure Embree 3 on the terrain's triangles (single rays, and packets of 8 and 16
    /// where native) and on its grid, same view, same run (needs a build with `--features
    /// embree`, which links libembree3).
    #[arg(long)]
    pub embree: bool,
    /// With --sizes: also trace each map from a tile store whose pages are held to a quarter
    /// of its size, and write its frame times over those in memory.
    #[arg(long)]
    pub out_of_core: bool,
    /// Also write every figure as JSON here (the tables on stdout are made from the same data).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// The frames `bench speed` measures: which terrains and view, traced how.
#[derive(clap::Args, Debug)]
pub struct SpeedFrames {
    /// Scene files (default: the built-in scenes).
    #[arg(long, value_delimiter = ',', conflicts_with = "sizes")]
    pub scenes: Vec<PathBuf>,
    /// Instead of scenes: the built-in valley's landscape generated at these sizes (samples
    /// per side, e.g. 513,2049,4097,8193) under the same view, with build time, memory per
    /// sample and the growth of time per ray.
    #[arg(long, value_delimiter = ',', value_parser = knobs::landscape_size)]
    pub sizes: Vec<usize>,
    /// Image width and height (overrides the scenes'; 512 with --sizes if not given).
    #[arg(long, value_parser = knobs::bench_image_size)]
    pub size: Option<u32>,
    /// Methods, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "mipmap,hruns,runs,dda")]
    pub methods: Vec<Method>,
    /// Arithmetics, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "f32,f64,rational:65536")]
    pub ariths: Vec<Arith>,
    /// Thread counts, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,2", value_parser = knobs::threads)]
    pub threads: Vec<usize>,
}

#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// The heightray binary to compare against (an older build, say).
    #[arg(long, value_name = "BIN")]
    pub baseline: PathBuf,
    /// The heightray binary compared with it (default: this one).
    #[arg(long, value_name = "BIN")]
    pub candidate: Option<PathBuf>,
    /// Runs of `bench speed` by each binary, alternating: baseline, candidate, baseline...
    #[arg(long, default_value_t = 5, value_parser = knobs::rounds)]
    pub rounds: usize,
    /// The configuration both binaries measure, as `bench speed` takes it (its flags must be
    /// ones the baseline knows).
    #[command(flatten)]
    pub frames: SpeedFrames,
    /// Also write every figure as JSON here.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

#[derive(clap::Args, Debug)]
pub struct TextbookArgs {
    /// Scene files (default: the built-in scenes).
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<PathBuf>,
    /// Image width and height (overrides the scenes').
    #[arg(long, default_value_t = 512, value_parser = knobs::bench_image_size)]
    pub size: u32,
    /// Rays per hard-case set (answered exactly too, for reference).
    #[arg(long, default_value_t = 1024, value_parser = knobs::per_set)]
    pub per_set: usize,
    /// Also answer the hard cases with Embree 3 and with heightray in `f32` (needs a build
    /// with `--features embree`).
    #[arg(long)]
    pub embree: bool,
}

#[derive(clap::Args, Debug)]
pub struct AccuracyArgs {
    /// Scene files (default: the built-in scenes).
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<PathBuf>,
    /// Image width and height for the scenes' rays and renders (exact arithmetic is slow).
    #[arg(long, default_value_t = 48, value_parser = knobs::bench_image_size)]
    pub size: u32,
    /// Rays per generated hard-case set.
    #[arg(long, default_value_t = 64, value_parser = knobs::per_set)]
    pub per_set: usize,
    /// Methods, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "mipmap,hruns,runs,dda")]
    pub methods: Vec<Method>,
    /// Arithmetics, comma-separated (exact is always measured: it is the reference).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "f32,f64,rational:16,rational:256,rational:4096,rational:65536,rational:16777216,exact"
    )]
    pub ariths: Vec<Arith>,
    /// Also write the report (Markdown) here.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Plot time per ray against error rate (PNG or SVG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// Scene file (TOML), or a height map to render whole, framed as the viewer frames it.
    pub scene: PathBuf,
    /// Image size, replacing the scene's (default for a map alone: 1280x720).
    #[arg(long, value_parser = parse_size, value_name = "WIDTHxHEIGHT")]
    pub size: Option<(u32, u32)>,
    /// Output image (PNG; .tif writes a TIFF, see --depth and --dpi).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Worker threads (default: all cores; at most 4 a core are used).
    #[arg(long, value_parser = knobs::threads)]
    pub threads: Option<usize>,
    /// Traversal (mipmap, hruns, runs, dda or auto), overriding the scene's.
    #[arg(long)]
    pub method: Option<Method>,
    /// Arithmetic (f32, f64, rational, rational:BOUND or exact), overriding the scene's.
    #[arg(long)]
    pub arith: Option<Arith>,
    /// Write the frame's statistics as JSON.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Camera rays per pixel (1 to 1024), overriding the scene's `[render] samples`.
    #[arg(long)]
    pub samples: Option<u32>,
    /// Let each pixel stop taking samples once they agree, as `[render] adaptive = true`.
    #[arg(long)]
    pub adaptive: bool,
    /// Walk neighbouring camera rays in packets (on) or each alone (off): the same image.
    #[arg(long, default_value = "off", value_parser = ["on", "off"])]
    pub packets: String,
    /// Render the scene's [animation] frames into the folder -o: N, A..B (B not included),
    /// A..=B, A..B/STEP or all. Frames already written are skipped.
    #[arg(long, conflicts_with_all = ["stats", "tile", "tiles"])]
    pub frames: Option<FrameSpec>,
    /// With --frames: render only share I of N (every N-th frame from the I-th, I from 0).
    #[arg(long, requires = "frames", value_name = "I/N")]
    pub frame_of: Option<Share>,
    /// Render frames or tiles again even where their files exist.
    #[arg(long)]
    pub force: bool,
    /// Render one tile into -o: band I of N horizontal bands (I/N), or tile I of --tiles.
    #[arg(long, value_name = "I/N or I", conflicts_with = "stats")]
    pub tile: Option<render_tiles::TileArg>,
    /// Cut the picture into COLUMNSxROWS tiles (numbered row by row from the top left);
    /// without --tile, every tile (or --tile-of's share) goes into the folder -o.
    #[arg(long, conflicts_with = "stats")]
    pub tiles: Option<TileGrid>,
    /// With --tiles: render only share I of N of the tiles into the folder -o.
    #[arg(long, requires = "tiles", conflicts_with = "tile", value_name = "I/N")]
    pub tile_of: Option<Share>,
    #[command(flatten)]
    pub ortho: ortho_args::OrthoArgs,
}

/// How to read a height map.
#[derive(clap::Args, Debug)]
pub struct MapArgs {
    /// Which value means no data: auto (a GeoTIFF's own, else -32768 for signed and float
    /// rasters), none, or a number.
    #[arg(long, default_value = "auto", allow_hyphen_values = true)]
    pub nodata: NoDataValue,
    /// How RGB images become heights: luminance, mapbox or terrarium (terrain-RGB).
    #[arg(long, default_value = "luminance")]
    pub rgb: ColourEncoding,
}

#[derive(clap::Args, Debug)]
pub struct TraceArgs {
    /// Height map: PNG (grayscale, or RGB), PGM (P2/P5), TIFF (integer or float samples; a
    /// GeoTIFF's georeferencing is not used here: rays are in grid coordinates), SRTM .hgt or
    /// ESRI ASCII .asc.
    pub map: PathBuf,
    /// Height of the largest sample value (maxval); for float and signed rasters, the factor
    /// applied to their values.
    #[arg(long, allow_hyphen_values = true)]
    pub z_scale: f64,
    #[command(flatten)]
    pub loading: MapArgs,
    /// Ray origin X,Y,Z.
    #[arg(long, value_parser = parse_triple, allow_hyphen_values = true, requires = "dir", conflicts_with = "rays")]
    pub origin: Option<[f64; 3]>,
    /// Ray direction DX,DY,DZ (not normalised).
    #[arg(long, value_parser = parse_triple, allow_hyphen_values = true, requires = "origin")]
    pub dir: Option<[f64; 3]>,
    /// A file of rays, one per line: `ox oy oz dx dy dz` (`#` starts a comment).
    #[arg(long, required_unless_present = "origin")]
    pub rays: Option<PathBuf>,
    /// Traversal: mipmap, hruns (hierarchical runs), runs, dda, or auto (the fastest: the
    /// mipmap).
    #[arg(long, default_value = "auto")]
    pub method: Method,
    /// Arithmetic: f32, f64, rational, rational:BOUND (denominator bound), or exact.
    #[arg(long, default_value = "f64")]
    pub arith: Arith,
    /// List the cells each walk covered, in order.
    #[arg(long)]
    pub cells: bool,
}

/// Runs a subcommand; per-item failures are reported by the subcommand and turn into the
/// exit code, whole-command failures into the error.
pub fn run(command: Command) -> anyhow::Result<ExitCode> {
    match command {
        Command::View(args) => view(args),
        Command::Trace(args) => trace::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Generate(args) => generate::run(&args),
        Command::Merge(args) => merge::run(&args),
        Command::Prepare(args) => prepare::run(&args),
        Command::Video(args) => video::run(&args),
        Command::Submit(SubmitCommand::Slurm(args)) => submit::run(&args),
        Command::Bench(BenchCommand::Speed(args)) => bench::speed(&args),
        Command::Bench(BenchCommand::Accuracy(args)) => accuracy::run(&args),
        Command::Bench(BenchCommand::Textbook(args)) => bench::textbook(&args),
        Command::Bench(BenchCommand::Effects(args)) => bench_effects::run(&args),
        Command::Bench(BenchCommand::Compare(args)) => bench_compare::run(&args),
    }
}

/// Opens the viewer.
pub fn view(args: ViewArgs) -> anyhow::Result<ExitCode> {
    if let Some(source) = args.sources.iter().find(|p| !p.exists()) {
        // `heightray rendr` lands here too: say what else it could have meant.
        anyhow::bail!(
            "no file '{}' to view (subcommands: view, render, trace, bench, generate, merge, \
             video, submit)",
            source.display()
        );
    }
    if let Some(scale) = args.render_scale {
        anyhow::ensure!(
            (0.05..=4.0).contains(&scale),
            "--render-scale must be between 0.05 and 4, got {}",
            Compact(scale)
        );
    }
    if let Some((w, h)) = args.export_size {
        anyhow::ensure!(
            u64::from(w) * u64::from(h) <= MAX_PIXELS,
            "--export-size {w}x{h} is more than the limit of {MAX_PIXELS} pixels (8192x4096) \
             an image may have"
        );
    }
    if let Some(folder) = &args.export_dir {
        // Refused rather than made: a mistyped folder would otherwise collect the exports
        // somewhere nobody looks.
        anyhow::ensure!(
            folder.exists(),
            "--export-dir {} does not exist; make it first (mkdir -p {0}) or choose another",
            folder.display()
        );
        anyhow::ensure!(
            folder.is_dir(),
            "--export-dir {} is not a folder; choose a folder for the exports",
            folder.display()
        );
    }
    heightray::viewer::run(heightray::viewer::ViewerOptions {
        sources: args.sources,
        z_scale: args.z_scale,
        decoding: heightray::viewer::Decoding {
            colour: args.loading.rgb,
            nodata: args.loading.nodata,
            height_unit: None,
        },
        size: args.size,
        render_scale: args.render_scale,
        exit_after_frames: args.exit_after_frames,
        screenshot: args.screenshot,
        export_dir: args.export_dir,
        export_size: args.export_size,
        report_state: args.report_state,
    })?;
    Ok(ExitCode::SUCCESS)
}

pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), ValueError> {
    let parsed = s
        .split_once(['x', 'X'])
        .and_then(|(w, h)| Some((w.trim().parse::<u32>().ok()?, h.trim().parse::<u32>().ok()?)));
    match parsed {
        Some((w, h)) if w > 0 && h > 0 && w <= 16384 && h <= 16384 => Ok((w, h)),
        _ => Err(ValueError::Size(s.to_owned())),
    }
}

fn parse_triple(s: &str) -> Result<[f64; 3], ValueError> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [x, y, z] = parts[..] else {
        return Err(ValueError::Triple(s.to_owned()));
    };
    let number = |p: &str| {
        p.parse::<f64>()
            .map_err(|_| ValueError::Number(p.to_owned()))
    };
    Ok([number(x)?, number(y)?, number(z)?])
}
