//! `heightray submit slurm SCENE (--frames SPEC | --tiles CxR) -o DIR/ --tasks N`: a Slurm job
//! array whose task K runs `heightray render` on share K/N of the frames or tiles, and a job
//! after it (`--dependency=afterok`) that encodes the video or merges the poster. The scripts
//! are kept in `DIR/slurm/` with the tasks' logs. Frames already written are skipped by the
//! tasks, so submitting again after a failure redoes only what is missing.

use super::SlurmArgs;
use anyhow::Context;
use heightray::batch::TileGrid;
use heightray::output_file;
use heightray::render::Scene;
use std::fmt::Write as _;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

pub fn run(args: &SlurmArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        (1..=100_000).contains(&args.tasks),
        "--tasks must be from 1 to 100000, got {}",
        args.tasks
    );
    let binary = std::env::current_exe().context("cannot find the heightray program's path")?;
    let scene = std::fs::canonicalize(&args.scene)
        .with_context(|| format!("cannot find the scene {}", args.scene.display()))?;
    super::render_frames::output_folder(&args.output)?;
    let folder = std::fs::canonicalize(&args.output)?;
    let slurm = folder.join("slurm");
    std::fs::create_dir_all(&slurm)
        .with_context(|| format!("cannot make the folder {}", slurm.display()))?;
    let size = args
        .size
        .map(|(w, h)| format!(" --size {w}x{h}"))
        .unwrap_or_default();

    // What each task renders and what the last job makes of it.
    let (share, finish) = match (&args.frames, &args.tiles) {
        (Some(spec), None) => {
            // Loaded here (its map too) so a scene without a path fails now, not in every task.
            let loaded = Scene::load(&scene)?;
            let Some(animation) = &loaded.animation else {
                anyhow::bail!("{} has no [animation] to take frames from", scene.display());
            };
            spec.frames(animation.frames())
                .map_err(anyhow::Error::msg)?;
            let finish = match &args.video {
                Some(video) => {
                    let video = absolute(video)?;
                    output_file::check(&video, "fly.mp4").map_err(anyhow::Error::msg)?;
                    Some(format!(
                        "{} video {} -o {} --fps {}",
                        quote(&binary),
                        quote(&folder),
                        quote(&video),
                        animation.fps()
                    ))
                }
                None => None,
            };
            (format!("--frames {spec} --frame-of"), finish)
        }
        (None, Some(grid)) => {
            anyhow::ensure!(
                args.video.is_none(),
                "--video is for frames; tiles are merged into {}",
                folder.join("poster.png").display()
            );
            let TileGrid { columns, rows } = grid;
            let merge = format!(
                "{} merge {}/tile-*.png -o {}",
                quote(&binary),
                quote(&folder),
                quote(&folder.join("poster.png"))
            );
            (format!("--tiles {columns}x{rows} --tile-of"), Some(merge))
        }
        _ => anyhow::bail!("give either --frames A..B or --tiles CxR"),
    };

    let mut header = String::new();
    if let Some(partition) = &args.partition {
        writeln!(header, "#SBATCH --partition={partition}")?;
    }
    if let Some(time) = &args.time {
        writeln!(header, "#SBATCH --time={time}")?;
    }
    let tasks = args.tasks;
    let render = format!(
        "#!/bin/sh\n#SBATCH --job-name=heightray-render\n#SBATCH --array=0-{last}\n\
         #SBATCH --output={logs}/render-%A_%a.out\n{header}\
         exec {binary} render {scene}{size} {share} \"$SLURM_ARRAY_TASK_ID/{tasks}\" -o {folder}\n",
        last = tasks - 1,
        logs = slurm.display(),
        binary = quote(&binary),
        scene = quote(&scene),
        folder = quote(&folder),
    );
    let render_script = slurm.join("render.sh");
    output_file::write_bytes(&render_script, render.as_bytes()).map_err(anyhow::Error::msg)?;
    let finish_script = match &finish {
        Some(command) => {
            let text = format!(
                "#!/bin/sh\n#SBATCH --job-name=heightray-finish\n\
                 #SBATCH --output={}/finish-%j.out\n{header}exec {command}\n",
                slurm.display()
            );
            let path = slurm.join("finish.sh");
            output_file::write_bytes(&path, text.as_bytes()).map_err(anyhow::Error::msg)?;
            Some(path)
        }
        None => None,
    };

    if args.dry_run {
        println!("# {}\n{render}", render_script.display());
        if let Some(path) = &finish_script {
            println!("# {}\n{}", path.display(), std::fs::read_to_string(path)?);
        }
        println!(
            "# to submit:\nsbatch --parsable {}",
            render_script.display()
        );
        if let Some(path) = &finish_script {
            println!(
                "sbatch --parsable --dependency=afterok:ARRAY_ID {}",
                path.display()
            );
        }
        return Ok(ExitCode::SUCCESS);
    }
    let array = sbatch(&[], &render_script)?;
    println!(
        "submitted job array {array} ({tasks} tasks): {}",
        render_script.display()
    );
    let mut jobs = array.clone();
    if let Some(path) = &finish_script {
        let after = sbatch(&[format!("--dependency=afterok:{array}")], path)?;
        println!(
            "submitted job {after} to run after every task succeeds: {}",
            path.display()
        );
        jobs = format!("{array},{after}");
    }
    println!(
        "follow with: squeue -j {jobs}   (and, with accounting, sacct -j {jobs}); logs in {}",
        slurm.display()
    );
    println!("after a failure, submit the same command again: frames and tiles written are kept");
    Ok(ExitCode::SUCCESS)
}

/// Submits `script` with `sbatch --parsable`, returning the job id.
fn sbatch(options: &[String], script: &Path) -> anyhow::Result<String> {
    let output = Command::new("sbatch")
        .arg("--parsable")
        .args(options)
        .arg(script)
        .output();
    let output = match output {
        Err(e) if e.kind() == ErrorKind::NotFound => anyhow::bail!(
            "sbatch is not installed here: submit from a Slurm login node, or see the scripts \
             with --dry-run (a one-node cluster on Debian: apt-get install slurm-wlm munge)"
        ),
        other => other.context("cannot run sbatch")?,
    };
    anyhow::ensure!(
        output.status.success(),
        "sbatch refused {}: {}",
        script.display(),
        String::from_utf8_lossy(&output.stderr).trim()
    );
    // `--parsable` prints `ID` or `ID;CLUSTER`.
    let text = String::from_utf8_lossy(&output.stdout);
    let id = text.trim().split(';').next().unwrap_or_default().to_owned();
    anyhow::ensure!(
        !id.is_empty() && id.bytes().all(|b| b.is_ascii_digit()),
        "sbatch printed no job id for {}: '{}'",
        script.display(),
        text.trim()
    );
    Ok(id)
}

/// `path` made absolute against the current folder (its folder must exist).
fn absolute(path: &Path) -> anyhow::Result<PathBuf> {
    std::path::absolute(path).with_context(|| format!("cannot resolve {}", path.display()))
}

/// A path as one word of a POSIX shell command.
fn quote(path: &Path) -> String {
    format!("'{}'", path.display().to_string().replace('\'', r"'\''"))
}
