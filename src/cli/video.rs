//! `heightray video DIR -o fly.mp4`: a folder of frames (`frame-00000.png`...) encoded by the
//! `ffmpeg` command as H.264 in yuv420p, which every player opens. The frames must run without
//! a gap; the video is written beside its name and renamed into place once whole.

use super::VideoArgs;
use anyhow::Context;
use heightray::output_file;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

pub fn run(args: &VideoArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        args.fps.is_finite() && args.fps > 0.0 && args.fps <= 1000.0,
        "--fps must be above 0 and at most 1000, got {}",
        args.fps
    );
    anyhow::ensure!(
        args.crf <= 51,
        "--crf must be from 0 (lossless) to 51 (smallest), got {}",
        args.crf
    );
    output_file::check(&args.output, "fly.mp4").map_err(anyhow::Error::msg)?;
    let (first, count) = frame_run(&args.folder)?;
    let partial = partial_path(&args.output);
    let status = Command::new("ffmpeg")
        .args(["-hide_banner", "-loglevel", "error", "-nostdin", "-y"])
        .args(["-framerate", &args.fps.to_string()])
        .args(["-start_number", &first.to_string()])
        .arg("-i")
        .arg(args.folder.join("frame-%05d.png"))
        .args(["-frames:v", &count.to_string()])
        // yuv420p halves the chroma: an odd width or height is padded by a pixel.
        .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"])
        .args(["-c:v", "libx264", "-pix_fmt", "yuv420p"])
        .args(["-crf", &args.crf.to_string()])
        .args(["-movflags", "+faststart", "-f", "mp4"])
        .arg(&partial)
        .status();
    let status = match status {
        Err(e) if e.kind() == ErrorKind::NotFound => anyhow::bail!(
            "the ffmpeg command is not installed; install it (Debian and Ubuntu: sudo apt-get \
             install ffmpeg) and run this again"
        ),
        other => other.context("cannot run ffmpeg")?,
    };
    if !status.success() {
        let _ = std::fs::remove_file(&partial);
        anyhow::bail!(
            "ffmpeg failed ({status}) encoding {}",
            args.folder.display()
        );
    }
    std::fs::rename(&partial, &args.output)
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    eprintln!(
        "{}: frames {first} to {} ({count} frames) at {} fps",
        args.output.display(),
        first + count - 1,
        args.fps
    );
    Ok(ExitCode::SUCCESS)
}

/// The first frame number in `folder` and how many follow it without a gap; an error names
/// the first missing frame, or says there are none.
fn frame_run(folder: &Path) -> anyhow::Result<(u64, u64)> {
    let entries = std::fs::read_dir(folder)
        .with_context(|| format!("cannot read the folder of frames {}", folder.display()))?;
    let mut numbers: Vec<u64> = entries
        .filter_map(|entry| {
            let name = entry.ok()?.file_name().into_string().ok()?;
            let digits = name.strip_prefix("frame-")?.strip_suffix(".png")?;
            (digits.len() >= 5 && digits.bytes().all(|b| b.is_ascii_digit()))
                .then(|| digits.parse().ok())
                .flatten()
        })
        .collect();
    numbers.sort_unstable();
    let Some(&first) = numbers.first() else {
        anyhow::bail!(
            "{} holds no frames (frame-00000.png...): render them first with heightray \
             render SCENE --frames A..B -o {0}",
            folder.display()
        );
    };
    if let Some(gap) = numbers.iter().zip(first..).find(|(&n, k)| n != *k) {
        anyhow::bail!(
            "frame {} is missing from {} (frames run from {first}); render it, e.g. heightray \
             render SCENE --frames {}..{} -o {1}",
            gap.1,
            folder.display(),
            gap.1,
            gap.0
        );
    }
    Ok((first, numbers.len() as u64))
}

/// A hidden file beside `path` for the video while it is encoded.
fn partial_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or("video".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.{}.partial", std::process::id()))
}
