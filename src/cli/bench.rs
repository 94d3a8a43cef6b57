//! `heightray bench ...`: tables on stdout.

use super::SpeedArgs;
use anyhow::Context;
use heightray::bench::throughput;
use heightray::heightfield::BUILTINS;
use heightray::render::{Scene, SceneFile};
use heightray::traverse::Arith;
use heightray::Terrain;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub fn speed(args: &SpeedArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        args.threads.iter().all(|&t| t > 0),
        "--threads counts must be at least 1"
    );
    let scenes = scenes_or_builtins(&args.scenes);
    let configs = args.methods.len() * args.ariths.len() * args.threads.len();
    let bar = progress_bar(configs * scenes.len());
    let mut tables = Vec::new();
    for path in &scenes {
        let scene = scene_at_size(path, args.size)?;
        let terrain = Terrain::new(scene.field.clone());
        bar.set_message(path.display().to_string());
        let rows = throughput(
            &scene,
            &terrain,
            &args.methods,
            &args.ariths,
            &args.threads,
            &mut || bar.inc(1),
        )?;
        tables.push((path.display().to_string(), terrain, rows));
    }
    bar.finish_and_clear();
    for (label, terrain, rows) in tables {
        let field = terrain.field();
        println!(
            "\n{label}: {}x{} samples, {}x{} pixels, build {:.1} ms",
            field.width(),
            field.height(),
            args.size,
            args.size,
            terrain.build_time().as_secs_f64() * 1e3
        );
        println!("| method | arith | threads | primary Mrays/s | shadow Mrays/s | primary x f64 | 2 threads x 1 |");
        println!("|---|---|---:|---:|---:|---:|---:|");
        for row in &rows {
            let same = |arith, threads| {
                rows.iter()
                    .find(|r| r.method == row.method && r.arith == arith && r.threads == threads)
            };
            let versus_f64 = same(Arith::F64, row.threads)
                .map(|r| row.primary_per_second() / r.primary_per_second());
            let versus_one = same(row.arith, 1)
                .filter(|_| row.threads > 1)
                .map(|r| row.primary_per_second() / r.primary_per_second());
            println!(
                "| {} | {} | {} | {:.3} | {:.3} | {} | {} |",
                row.method,
                row.arith,
                row.threads,
                row.primary_per_second() / 1e6,
                row.shadow_per_second() / 1e6,
                versus_f64.map_or("-".into(), |r| format!("{r:.2}")),
                versus_one.map_or("-".into(), |r| format!("{r:.2}")),
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// The given scene files, or the built-in scenes.
pub(super) fn scenes_or_builtins(scenes: &[PathBuf]) -> Vec<PathBuf> {
    if scenes.is_empty() {
        let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
        BUILTINS
            .iter()
            .map(|b| assets.join(format!("{}.toml", b.name)))
            .collect()
    } else {
        scenes.to_vec()
    }
}

/// A progress bar counting configurations.
pub(super) fn progress_bar(len: usize) -> ProgressBar {
    ProgressBar::new(len as u64).with_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    )
}

/// A scene file with its image size replaced.
pub(super) fn scene_at_size(path: &Path, size: u32) -> anyhow::Result<Scene> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let mut file: SceneFile =
        toml::from_str(&text).with_context(|| format!("scene {}", path.display()))?;
    file.camera.width = size;
    file.camera.height = size;
    Ok(Scene::from_file(
        &file,
        path.parent().unwrap_or(Path::new(".")),
        path,
    )?)
}
