//! `heightray bench ...`: tables on stdout.

use super::{AccuracyArgs, SpeedArgs};
use anyhow::Context;
use heightray::bench::{accuracy as measure, throughput};
use heightray::heightfield::{self, Builtin, BUILTINS};
use heightray::render::Camera;
use heightray::render::{Scene, SceneFile};
use heightray::traverse::Arith;
use heightray::Terrain;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub fn accuracy(args: &AccuracyArgs) -> anyhow::Result<ExitCode> {
    let (field, label) = match (&args.map, args.z_scale) {
        (Some(path), Some(z)) => (heightfield::load(path, z)?, path.display().to_string()),
        _ => {
            let builtin = Builtin::named(&args.builtin).with_context(|| {
                let names: Vec<_> = BUILTINS.iter().map(|b| b.name).collect();
                format!(
                    "no built-in terrain '{}'; there are {}",
                    args.builtin,
                    names.join(", ")
                )
            })?;
            (builtin.load()?, builtin.name.to_owned())
        }
    };
    let terrain = Terrain::new(field);
    let camera = default_view(&terrain, args.size)?;
    let (w, h) = (terrain.field().width(), terrain.field().height());
    println!(
        "terrain {label} ({w}x{h}), acceleration data built in {:.2} ms, {:.1} bytes/sample; \
         {size}x{size} primary rays of an oblique view, 1 thread",
        terrain.build_time().as_secs_f64() * 1e3,
        terrain.accel_bytes() as f64 / (w * h) as f64,
        size = args.size
    );
    let rows = measure(&terrain, &camera, &args.methods, &args.ariths);
    println!();
    println!("| method | arith | ns/ray | x f64 | hits | run q/ray | cell q/ray | triangle q/ray | cell E/N | vs exact: hit/miss | cell/tri | t err > 1e-9 | worst t err |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for row in &rows {
        let f64_ns = rows
            .iter()
            .find(|r| r.method == row.method && r.arith == Arith::F64)
            .map(|r| r.ns_per_ray());
        let c = &row.counters;
        println!(
            "| {} | {} | {:.0} | {} | {} | {:.2} | {:.2} | {:.2} | 1:{:.1} | {} |",
            row.method,
            row.arith,
            row.ns_per_ray(),
            f64_ns.map_or("-".into(), |f| format!("{:.2}", row.ns_per_ray() / f)),
            row.hits,
            row.per_ray(c.run.total()),
            row.per_ray(c.cell.total()),
            row.per_ray(c.triangle.total()),
            c.cell.miss as f64 / c.cell.hit.max(1) as f64,
            row.versus_exact.map_or("- | - | - | -".into(), |d| format!(
                "{} | {} | {} | {:.1e}",
                d.hit_or_miss, d.cell_or_triangle, d.t_error, d.worst_t_error
            )),
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// An oblique view from the south-west corner over the whole terrain.
fn default_view(terrain: &Terrain, size: u32) -> anyhow::Result<Camera> {
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let (_, z_hi) = terrain.z_range();
    let eye = [-0.08 * w, -0.12 * h, 1.5 * z_hi.max(1.0) + 0.2 * w];
    let target = [0.5 * w, 0.5 * h, 0.33 * z_hi];
    Ok(Camera::look_at(
        eye,
        target,
        [0.0, 0.0, 1.0],
        45.0,
        (size, size),
    )?)
}

pub fn speed(args: &SpeedArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        args.threads.iter().all(|&t| t > 0),
        "--threads counts must be at least 1"
    );
    let scenes = if args.scenes.is_empty() {
        let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
        BUILTINS
            .iter()
            .map(|b| assets.join(format!("{}.toml", b.name)))
            .collect()
    } else {
        args.scenes.clone()
    };
    let configs = args.methods.len() * args.ariths.len() * args.threads.len();
    let bar = ProgressBar::new((configs * scenes.len()) as u64).with_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} configurations, {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
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

/// A scene file with its image size replaced.
fn scene_at_size(path: &PathBuf, size: u32) -> anyhow::Result<Scene> {
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
