//! `heightray bench ...`: tables on stdout.

use super::{SpeedArgs, TextbookArgs};
use heightray::bench::{
    hard_cases_versus_exact, sized_scene, throughput, versus_textbook, ThroughputRow, ROUNDS, SEED,
};
use heightray::render::{Scene, SceneFile};
use heightray::traverse::prepare;
use heightray::traverse::{Arith, HitMiss};
use heightray::Terrain;
use indicatif::ProgressBar;
use indicatif::ProgressStyle;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

pub fn speed(args: &SpeedArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        args.threads.iter().all(|&t| t > 0),
        "--threads counts must be at least 1"
    );
    let configs = args.methods.len() * args.ariths.len() * args.threads.len() * ROUNDS;
    let mut measured = Vec::new();
    if args.sizes.is_empty() {
        let scenes = scenes_or_builtins(&args.scenes)?;
        let size = args.size.unwrap_or(256);
        let bar = progress_bar(configs * scenes.len());
        for source in &scenes {
            let name = source.path.display().to_string();
            bar.set_message(name.clone());
            let scene = scene_at_size(source, size)?;
            let terrain = Terrain::new(scene.field.clone());
            let rows = measure(args, &scene, &terrain, &bar)?;
            measured.push((name, terrain, rows));
        }
        bar.finish_and_clear();
    } else {
        let size = args.size.unwrap_or(512);
        let bar = progress_bar(configs * args.sizes.len());
        for &samples in &args.sizes {
            bar.set_message(format!("generating {samples}x{samples}"));
            let scene = sized_scene(samples, size)?;
            let terrain = fastest_build(&scene);
            bar.set_message(format!("{samples}x{samples}"));
            let rows = measure(args, &scene, &terrain, &bar)?;
            let label = format!("valley landscape (seed {SEED}) at {samples}x{samples}");
            measured.push((label, terrain, rows));
        }
        bar.finish_and_clear();
    }
    for (label, terrain, rows) in &measured {
        print_table(label, terrain, rows);
    }
    if measured.len() > 1 && !args.sizes.is_empty() {
        print_growth(&measured);
    }
    Ok(ExitCode::SUCCESS)
}

pub fn textbook(args: &TextbookArgs) -> anyhow::Result<ExitCode> {
    let scenes = scenes_or_builtins(&args.scenes)?;
    let bar = progress_bar(scenes.len() + 1);
    let mut rows = Vec::new();
    for source in &scenes {
        let name = source.path.display().to_string();
        bar.set_message(name.clone());
        let scene = scene_at_size(source, args.size)?;
        let terrain = Terrain::new(scene.field.clone());
        rows.push((name, versus_textbook(&scene, &terrain)));
        bar.inc(1);
    }
    bar.set_message("hard cases");
    let hard = hard_cases_versus_exact(args.per_set)?;
    bar.finish_and_clear();
    println!("camera rays, one thread, f64; heightray's mipmap walk without the renderer's beams");
    println!("| scene | rays | hits | queries per ray: heightray / textbook | heightray Mrays/s | textbook Mrays/s | heightray time x textbook | answers that differ |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for (name, row) in rows {
        let rate = |time: Duration| row.rays as f64 / time.as_secs_f64() / 1e6;
        println!(
            "| {name} | {} | {} | {:.2} / {:.2} | {:.3} | {:.3} | {:.2} | {} |",
            row.rays,
            row.hits,
            row.heightray_queries,
            row.textbook_queries,
            rate(row.heightray_time),
            rate(row.textbook_time),
            row.heightray_time.as_secs_f64() / row.textbook_time.as_secs_f64(),
            row.differing,
        );
    }
    println!("\nthe hard-case sets of `bench accuracy`: answers in f64 that differ from heightray's exact answers (a hit against a miss, or t off by more than a relative 1e-9)");
    println!("| set | rays | heightray mipmap f64 | textbook walk |");
    println!("|---|---:|---:|---:|");
    for row in hard {
        println!(
            "| {} | {} | {} | {} |",
            row.set, row.rays, row.heightray_differing, row.textbook_differing
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// The scene's terrain, built as many times as fit in a second (at least three): the one
/// whose build was fastest, as every frame time is the fastest of many (a 2 ms build is
/// half page faults on a fresh allocation on one run, and not on the next).
fn fastest_build(scene: &Scene) -> Terrain {
    let start = Instant::now();
    let mut fastest = Terrain::new(scene.field.clone());
    for built in 1.. {
        if built >= 3 && start.elapsed() > Duration::from_secs(1) {
            break;
        }
        let terrain = Terrain::new(scene.field.clone());
        if terrain.build_time() < fastest.build_time() {
            fastest = terrain;
        }
    }
    fastest
}

fn measure(
    args: &SpeedArgs,
    scene: &Scene,
    terrain: &Terrain,
    bar: &ProgressBar,
) -> anyhow::Result<Vec<ThroughputRow>> {
    throughput(
        scene,
        terrain,
        &args.methods,
        &args.ariths,
        &args.threads,
        &mut || bar.inc(1),
    )
}

fn print_table(label: &str, terrain: &Terrain, rows: &[ThroughputRow]) {
    let field = terrain.field();
    let samples = (field.width() * field.height()) as f64;
    println!("\n{label}: {}x{} samples", field.width(), field.height());
    println!("| method | arith | threads | build ms | bytes/sample | primary Mrays/s | shadow Mrays/s | frame with shadows ms | time x f64 | 2 threads x 1 |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for row in rows {
        let same = |arith, threads| {
            rows.iter()
                .find(|r| r.method == row.method && r.arith == arith && r.threads == threads)
        };
        let versus_f64 = same(Arith::F64, row.threads)
            .map(|r| r.primary_per_second() / row.primary_per_second());
        let versus_one = same(row.arith, 1)
            .filter(|_| row.threads > 1)
            .map(|r| row.primary_per_second() / r.primary_per_second());
        let (build, bytes) = prepare(terrain, row.method);
        println!(
            "| {} | {} | {} | {:.1} | {:.2} | {:.3} | {} | {:.1} | {} | {} |",
            row.method,
            row.arith,
            row.threads,
            build.as_secs_f64() * 1e3,
            bytes as f64 / samples,
            row.primary_per_second() / 1e6,
            row.shadow_per_second()
                .map_or("-".into(), |r| format!("{:.3}", r / 1e6)),
            row.total_time.as_secs_f64() * 1e3,
            versus_f64.map_or("-".into(), |r| format!("{r:.2}")),
            versus_one.map_or("-".into(), |r| format!("{r:.2}")),
        );
    }
    if rows.iter().any(|r| r.shadow_per_second().is_none()) {
        println!("(shadow Mrays/s \"-\": no shadow rays, or the frame with shadows was not slower than the one without: shadows were lost in the noise of the two times)");
    }
}

/// How each method's time per primary ray grows with the terrain size (first arithmetic, one
/// thread) beside the growth of log N, and the queries per primary ray it grows with.
fn print_growth(measured: &[(String, Terrain, Vec<ThroughputRow>)]) {
    let first = &measured[0];
    let side = |t: &Terrain| t.field().width() as f64;
    let mut header = "| method | arith |".to_string();
    for (_, terrain, _) in measured {
        header += &format!(" {0}x{0} |", side(terrain));
    }
    header += &format!("\n|---|---|{}", "---:|".repeat(measured.len()));
    // One line per method: `cell` of its row at each size.
    let lines = |cell: &dyn Fn(&ThroughputRow, &ThroughputRow) -> String| {
        for base in first.2.iter().filter(|r| r.threads == 1) {
            let mut line = format!("| {} | {} |", base.method, base.arith);
            for (_, _, rows) in measured {
                let row = rows.iter().find(|r| {
                    r.method == base.method && r.arith == base.arith && r.threads == base.threads
                });
                line += &row.map_or(" - |".into(), |r| format!(" {} |", cell(base, r)));
            }
            println!("{line}");
        }
    };

    println!("\ngrowth of time per primary ray with the terrain size (x the smallest)\n{header}");
    lines(&|base, r| format!("{:.2}", base.primary_per_second() / r.primary_per_second()));
    let mut line = "| log2 N | - |".to_string();
    for (_, terrain, _) in measured {
        line += &format!(" {:.2} |", side(terrain).log2() / side(&first.1).log2());
    }
    println!("{line}");

    // What the time grows with: the finer terrain has more near misses per ray.
    println!("\nqueries per primary ray: block / run / cell / triangle / beam (once per tile of rays)\n{header}");
    lines(&|_, r| {
        let per_ray = |queries: HitMiss| queries.total() as f64 / r.primary_rays as f64;
        let q = &r.primary_queries;
        format!(
            "{:.1} / {:.1} / {:.1} / {:.1} / {:.2}",
            per_ray(q.block),
            per_ray(q.run),
            per_ray(q.cell),
            per_ray(q.triangle),
            per_ray(q.beam)
        )
    });
}

/// A scene to measure on, as written: `path` names it (a built-in scene by its name).
pub(super) struct SceneSource {
    pub path: PathBuf,
    file: SceneFile,
}

/// The given scene files, or the built-in scenes (embedded, with their maps).
pub(super) fn scenes_or_builtins(scenes: &[PathBuf]) -> anyhow::Result<Vec<SceneSource>> {
    if scenes.is_empty() {
        let builtins = SceneFile::builtins()?.into_iter();
        let source = |(name, file)| SceneSource {
            path: PathBuf::from(name),
            file,
        };
        Ok(builtins.map(source).collect())
    } else {
        let read = |path: &PathBuf| -> anyhow::Result<SceneSource> {
            let file = SceneFile::read(path)?;
            Ok(SceneSource {
                path: path.clone(),
                file,
            })
        };
        scenes.iter().map(read).collect()
    }
}

/// A progress bar counting configurations.
pub(super) fn progress_bar(len: usize) -> ProgressBar {
    ProgressBar::new(len as u64).with_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    )
}

/// A scene with its image size replaced.
pub(super) fn scene_at_size(source: &SceneSource, size: u32) -> anyhow::Result<Scene> {
    let mut file = source.file.clone();
    file.camera.width = size;
    file.camera.height = size;
    let path = &source.path;
    Ok(Scene::from_file(&file, Scene::base(path), path)?)
}
