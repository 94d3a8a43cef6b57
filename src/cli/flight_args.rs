//! The arguments of the commands that render beyond one picture and one machine: `merge`,
//! `video` and `submit`.

use super::parse_size;
use clap::Subcommand;
use heightray::batch::{FrameSpec, TileGrid};
use std::path::PathBuf;

#[derive(Subcommand, Debug)]
pub enum SubmitCommand {
    /// A Slurm job array (sbatch): task K renders share K/N, then one job encodes the video
    /// (--video) or merges the tiles into DIR/poster.png.
    Slurm(SlurmArgs),
}

#[derive(clap::Args, Debug)]
pub struct SlurmArgs {
    /// Scene file (TOML) with an [animation] for --frames.
    pub scene: PathBuf,
    /// The frames: N, A..B (B not included), A..=B, A..B/STEP or all.
    #[arg(long, conflicts_with = "tiles")]
    pub frames: Option<FrameSpec>,
    /// Or the tiles of a poster, COLUMNSxROWS.
    #[arg(long)]
    pub tiles: Option<TileGrid>,
    /// Output folder (made if missing); the scripts and logs go to its slurm/ folder.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Array tasks: task K renders every N-th frame or tile from the K-th.
    #[arg(long)]
    pub tasks: u64,
    /// With --frames: encode the frames into this MP4 once every task has succeeded.
    #[arg(long)]
    pub video: Option<PathBuf>,
    /// Image size, replacing the scene's.
    #[arg(long, value_parser = parse_size, value_name = "WIDTHxHEIGHT")]
    pub size: Option<(u32, u32)>,
    /// Slurm partition (sbatch --partition).
    #[arg(long)]
    pub partition: Option<String>,
    /// Time limit of each task, HH:MM:SS (sbatch --time).
    #[arg(long, value_parser = parse_time)]
    pub time: Option<String>,
    /// Write and print the scripts without submitting them.
    #[arg(long)]
    pub dry_run: bool,
}

#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// Tiles (PNG files made by `render --tile` or `--tiles`), in any order.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// The whole picture.
    #[arg(short, long)]
    pub output: PathBuf,
}

#[derive(clap::Args, Debug)]
pub struct VideoArgs {
    /// Folder of frames, frame-00000.png onwards without a gap.
    pub folder: PathBuf,
    /// Output video (MP4).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Frames per second.
    #[arg(long, default_value_t = 30.0)]
    pub fps: f64,
    /// Quality: 0 lossless to 51 smallest (x264's constant rate factor).
    #[arg(long, default_value_t = 18)]
    pub crf: u32,
}

fn parse_time(s: &str) -> Result<String, super::knobs::ValueError> {
    let parts: Vec<&str> = s.split(':').collect();
    let numbers = parts
        .iter()
        .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()));
    if numbers && parts.len() == 3 {
        Ok(s.to_owned())
    } else {
        Err(super::knobs::ValueError::Time(s.to_owned()))
    }
}
