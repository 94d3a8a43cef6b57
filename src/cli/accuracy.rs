//! `heightray bench accuracy`: what accuracy costs in time, as a Markdown report and a plot.

use super::bench::{progress_bar, scene_at_size, scenes_or_builtins};
use super::AccuracyArgs;
use heightray::arith::Arith;
use heightray::bench::{accuracy, hard_cases, pixel_differences, plot, scene_sets, AccuracyRow};
use heightray::output_file;
use heightray::render::{PixelRow, Scene};
use heightray::traverse::Method;
use heightray::Terrain;
use std::fmt::Write as _;
use std::io::{self, Write as _};
use std::process::ExitCode;

pub fn run(args: &AccuracyArgs) -> anyhow::Result<ExitCode> {
    let mut ariths = args.ariths.clone();
    if !ariths.contains(&Arith::Exact) {
        ariths.push(Arith::Exact);
    }
    let scenes = scenes_or_builtins(&args.scenes)?;
    let mut sets = Vec::new();
    let mut loaded = Vec::new();
    for source in &scenes {
        let scene = scene_at_size(source, args.size)?;
        let name = source
            .path
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        sets.extend(scene_sets(&name, &scene)?);
        loaded.push((name, scene));
    }
    sets.extend(hard_cases(args.per_set)?);

    let configs = args.methods.len() * ariths.len();
    // Each scene's renders with every method, and with effects in the first method.
    let renders = loaded.len() * (args.methods.len() + 1) * (ariths.len() + 1);
    let bar = progress_bar(configs * sets.len() + renders);
    let mut rows: Vec<AccuracyRow> = Vec::new();
    for set in &sets {
        bar.set_message(set.name.clone());
        rows.extend(accuracy(set, &args.methods, &ariths, &mut || bar.inc(1)));
    }
    let mut pixels: Vec<(String, Vec<PixelRow>)> = Vec::new();
    for (name, scene) in &loaded {
        bar.set_message(format!("{name}: renders"));
        let terrain = Terrain::new(scene.field.clone());
        pixels.push((
            name.clone(),
            pixel_differences(scene, &terrain, &args.methods, &ariths, &mut || bar.inc(1)),
        ));
        // Effect rays walk as shadow rays do, in every method: the first stands for all.
        let lit = with_soft_shadows_and_sky(scene);
        let first = &args.methods[..1.min(args.methods.len())];
        pixels.push((
            format!("{name} with soft shadows and sky light"),
            pixel_differences(&lit, &terrain, first, &ariths, &mut || bar.inc(1)),
        ));
    }
    bar.finish_and_clear();

    let report = report(args, &rows, &pixels);
    if let Some(path) = &args.out {
        output_file::write_bytes(path, report.as_bytes()).map_err(anyhow::Error::msg)?;
    }
    if let Some(path) = &args.plot {
        plot::time_against_error(&summary(&rows, &args.methods, &ariths), path)?;
    }
    // (Last: a reader of the report that stops early loses none of the files.)
    io::stdout().lock().write_all(report.as_bytes())?;
    Ok(ExitCode::SUCCESS)
}

/// Per method and arithmetic over all sets: (label, ns per ray, fraction of answers differing
/// from exact).
fn summary(rows: &[AccuracyRow], methods: &[Method], ariths: &[Arith]) -> Vec<plot::Point> {
    let mut points = Vec::new();
    for &method in methods {
        for &arith in ariths {
            let mine = rows
                .iter()
                .filter(|r| r.method == method && r.arith == arith);
            let (mut ns, mut rays, mut wrong) = (0.0, 0u64, 0u64);
            for row in mine {
                ns += row.time.as_secs_f64() * 1e9;
                rays += row.rays;
                wrong += row.versus_exact.map_or(0, |d| d.total());
            }
            points.push(plot::Point {
                label: format!("{method} {arith}"),
                method: method.to_string(),
                ns_per_ray: ns / rays.max(1) as f64,
                error_rate: wrong as f64 / rays.max(1) as f64,
            });
        }
    }
    points
}

fn report(args: &AccuracyArgs, rows: &[AccuracyRow], pixels: &[(String, Vec<PixelRow>)]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Answers compared with exact arithmetic on the same rays (same method): hit/miss, another \
         cell or triangle, or t off by a relative 1e-9; cells the exact walk covers that the walk \
         skipped. One thread; scenes at {0}x{0}, {1} rays per hard-case set.\n",
        args.size, args.per_set
    );
    let _ = writeln!(out, "### All sets\n\n| method | arith | ns/ray | x f64 | answers differing |\n|---|---|---:|---:|---:|");
    let points = summary(rows, &args.methods, &distinct_ariths(rows));
    for p in &points {
        let f64_ns = points
            .iter()
            .find(|q| q.method == p.method && q.label.ends_with(" f64"))
            .map(|q| q.ns_per_ray);
        let _ = writeln!(
            out,
            "| {} | {:.0} | {} | {:.3}% |",
            p.label.replacen(' ', " | ", 1),
            p.ns_per_ray,
            f64_ns.map_or("-".into(), |f| format!("{:.2}", p.ns_per_ray / f)),
            100.0 * p.error_rate
        );
    }
    let mut set_names: Vec<&str> = rows.iter().map(|r| r.set.as_str()).collect();
    set_names.dedup();
    for name in set_names {
        let _ = writeln!(out, "\n### {name}\n\n| method | arith | rays | ns/ray | x f64 | hit/miss | cell/tri | t err > 1e-9 | worst t err | cells skipped |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|");
        for row in rows.iter().filter(|r| r.set == name) {
            let f64_ns = rows
                .iter()
                .find(|r| r.set == name && r.method == row.method && r.arith == Arith::F64)
                .map(AccuracyRow::ns_per_ray);
            let d = row.versus_exact.unwrap_or_default();
            let _ = writeln!(
                out,
                "| {} | {} | {} | {:.0} | {} | {} | {} | {} | {:.1e} | {} |",
                row.method,
                row.arith,
                row.rays,
                row.ns_per_ray(),
                f64_ns.map_or("-".into(), |f| format!("{:.2}", row.ns_per_ray() / f)),
                d.hit_or_miss,
                d.cell_or_triangle,
                d.t_error,
                d.worst_t_error,
                row.skipped_cells.unwrap_or(0)
            );
        }
    }
    for (name, rows) in pixels {
        let _ = writeln!(out, "\n### {name}: pixels that differ from the exact render\n\n| method | arith | pixels differing | largest difference (display bytes) | frame ms (all threads) |\n|---|---|---:|---:|---:|");
        for row in rows {
            let _ = writeln!(
                out,
                "| {} | {} | {} of {} | {} | {:.1} |",
                row.method,
                row.arith,
                row.differing,
                row.pixels,
                row.largest_difference,
                row.time.as_secs_f64() * 1e3
            );
        }
    }
    out
}

fn distinct_ariths(rows: &[AccuracyRow]) -> Vec<Arith> {
    let mut ariths: Vec<Arith> = Vec::new();
    for row in rows {
        if !ariths.contains(&row.arith) {
            ariths.push(row.arith);
        }
    }
    ariths
}

/// `scene` with a real sun's disc (0.53 degrees) and sky light, at the default rays: the
/// effects whose rays start on the surface.
fn with_soft_shadows_and_sky(scene: &Scene) -> Scene {
    let mut lit = scene.clone();
    lit.lighting.effects.sun_angle_deg = 0.53;
    lit.lighting.effects.sky_light = true;
    lit
}
