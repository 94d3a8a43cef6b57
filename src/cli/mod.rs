//! Command-line arguments and the subcommands (DESIGN 4).

mod accuracy;
mod bench;
mod generate;
mod render;
mod trace;

use clap::{Parser, Subcommand};
use heightray::{Arith, Method};
use std::path::PathBuf;
use std::process::ExitCode;

/// Exact, fast ray tracing of terrain height fields on the CPU.
#[derive(Parser, Debug)]
#[command(name = "heightray", version, about)]
pub struct Args {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a scene file to a PNG, with statistics.
    Render(RenderArgs),
    /// Trace rays against a height field and print one JSON object per ray.
    Trace(TraceArgs),
    /// Benchmarks: `speed` (rays per second of whole frames), `accuracy` (time against error).
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Write a generated landscape (16-bit grayscale PNG) of the built-in generator.
    Generate(GenerateArgs),
}

#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Primary and shadow rays per second on the built-in scenes, per method, arithmetic and
    /// thread count, as ratios.
    Speed(SpeedArgs),
    /// Time per primary ray, queries per ray and answers that differ from exact arithmetic,
    /// per method and arithmetic, one thread.
    Accuracy(AccuracyArgs),
}

#[derive(clap::Args, Debug)]
pub struct SpeedArgs {
    /// Scene files (default: the built-in scenes).
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<PathBuf>,
    /// Image width and height (overrides the scenes').
    #[arg(long, default_value_t = 256)]
    pub size: u32,
    /// Methods, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "runs,dda")]
    pub methods: Vec<Method>,
    /// Arithmetics, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "f32,f64,rational:65536")]
    pub ariths: Vec<Arith>,
    /// Thread counts, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,2")]
    pub threads: Vec<usize>,
}

#[derive(clap::Args, Debug)]
pub struct AccuracyArgs {
    /// Scene files (default: the built-in scenes).
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<PathBuf>,
    /// Image width and height for the scenes' rays and renders (exact arithmetic is slow).
    #[arg(long, default_value_t = 48)]
    pub size: u32,
    /// Rays per generated hard-case set.
    #[arg(long, default_value_t = 64)]
    pub per_set: usize,
    /// Methods, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "runs,dda")]
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
pub struct GenerateArgs {
    /// Samples per side.
    #[arg(long, default_value_t = 513)]
    pub size: usize,
    /// Noise seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output PNG.
    #[arg(short, long)]
    pub output: PathBuf,
}

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// Scene file (TOML).
    pub scene: PathBuf,
    /// Output PNG.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Traversal, overriding the scene's.
    #[arg(long)]
    pub method: Option<Method>,
    /// Arithmetic, overriding the scene's.
    #[arg(long)]
    pub arith: Option<Arith>,
    /// Write the frame's statistics as JSON.
    #[arg(long)]
    pub stats: Option<PathBuf>,
}

#[derive(clap::Args, Debug)]
pub struct TraceArgs {
    /// Height map: 8- or 16-bit grayscale PNG, or PGM (P2/P5).
    pub map: PathBuf,
    /// Height of the largest sample value (maxval).
    #[arg(long, allow_hyphen_values = true)]
    pub z_scale: f64,
    /// Ray origin X,Y,Z.
    #[arg(long, value_parser = parse_triple, allow_hyphen_values = true, requires = "dir", conflicts_with = "rays")]
    pub origin: Option<[f64; 3]>,
    /// Ray direction DX,DY,DZ (not normalised).
    #[arg(long, value_parser = parse_triple, allow_hyphen_values = true, requires = "origin")]
    pub dir: Option<[f64; 3]>,
    /// A file of rays, one per line: `ox oy oz dx dy dz` (`#` starts a comment).
    #[arg(long, required_unless_present = "origin")]
    pub rays: Option<PathBuf>,
    /// Traversal: runs, dda, or auto.
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
        Command::Trace(args) => trace::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Generate(args) => generate::run(&args),
        Command::Bench(BenchCommand::Speed(args)) => bench::speed(&args),
        Command::Bench(BenchCommand::Accuracy(args)) => accuracy::run(&args),
    }
}

fn parse_triple(s: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [x, y, z] = parts[..] else {
        return Err(format!("expected three comma-separated numbers, got '{s}'"));
    };
    let number = |p: &str| {
        p.parse::<f64>()
            .map_err(|_| format!("'{p}' is not a number"))
    };
    Ok([number(x)?, number(y)?, number(z)?])
}
