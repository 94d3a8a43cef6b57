//! `heightray bench ...`: tables on stdout.

use super::{SpeedArgs, TextbookArgs};
use heightray::bench::{
    hard_cases_versus_exact, render_as, sized_scene, throughput, versus_textbook, view,
    HardCaseRow, Reference, ThroughputRow, Tracer, ROUNDS, SEED,
};
use heightray::render::Frame;
use heightray::render::{Scene, SceneFile};
use heightray::traverse::prepare;
use heightray::traverse::{Arith, HitMiss, Method};
use heightray::Terrain;
use indicatif::ProgressBar;
use indicatif::ProgressStyle;
use std::io::{self, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

pub fn speed(args: &SpeedArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        args.threads.iter().all(|&t| t > 0),
        "--threads counts must be at least 1"
    );
    let tracers = args.methods.len() * args.ariths.len() + usize::from(args.embree);
    let configs = tracers * args.threads.len() * ROUNDS;
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
            let (rows, references) = measure(args, &scene, &terrain, &bar)?;
            measured.push((name, terrain, rows, references));
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
            let (rows, references) = measure(args, &scene, &terrain, &bar)?;
            let label = format!("valley landscape (seed {SEED}) at {samples}x{samples}");
            measured.push((label, terrain, rows, references));
        }
        bar.finish_and_clear();
    }
    let out = &mut std::io::stdout().lock();
    for (label, terrain, rows, references) in &measured {
        print_table(out, label, terrain, rows, references)?;
    }
    if measured.len() > 1 && !args.sizes.is_empty() {
        print_growth(out, &measured)?;
    }
    Ok(ExitCode::SUCCESS)
}

pub fn textbook(args: &TextbookArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(!args.embree || cfg!(feature = "embree"), WITHOUT_EMBREE);
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
    let out = &mut std::io::stdout().lock();
    writeln!(
        out,
        "camera rays, one thread, f64; heightray's mipmap walk without the renderer's beams"
    )?;
    writeln!(out, "| scene | rays | hits | queries per ray: heightray / textbook | heightray Mrays/s | textbook Mrays/s | heightray time x textbook | answers that differ |")?;
    writeln!(out, "|---|---:|---:|---:|---:|---:|---:|---:|")?;
    for (name, row) in rows {
        let rate = |time: Duration| row.rays as f64 / time.as_secs_f64() / 1e6;
        writeln!(
            out,
            "| {name} | {} | {} | {:.2} / {:.2} | {:.3} | {:.3} | {:.2} | {} |",
            row.rays,
            row.hits,
            row.heightray_queries,
            row.textbook_queries,
            rate(row.heightray_time),
            rate(row.textbook_time),
            row.heightray_time.as_secs_f64() / row.textbook_time.as_secs_f64(),
            row.differing,
        )?;
    }
    print_hard_cases(
        out,
        "the hard-case sets of `bench accuracy`: answers in f64 that differ from heightray's exact answers (a hit against a miss, or t off by more than a relative 1e-9)",
        ["heightray mipmap f64", "textbook walk"],
        &hard,
    )?;
    // (A build without Embree refused `--embree` above.)
    #[cfg(feature = "embree")]
    if args.embree {
        print_embree_hard_cases(out, args.per_set)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// Why `--embree` cannot be measured by this build.
const WITHOUT_EMBREE: &str = "this heightray was built without Embree: install libembree-dev \
     (Debian, Ubuntu) and run it with `cargo run --release --features embree -- ...`";

/// The hard cases in `f32`: heightray's mipmap walk and Embree against exact.
#[cfg(feature = "embree")]
fn print_embree_hard_cases(out: &mut impl Write, per_set: usize) -> anyhow::Result<()> {
    use heightray::bench::embree::{hard_cases_in_f32, F32_TOLERANCE};
    print_hard_cases(
        out,
        &format!("the same sets in f32: answers that differ from heightray's exact answers (a hit against a miss, or t off by more than a relative {F32_TOLERANCE:e})"),
        ["heightray mipmap f32", "Embree 3"],
        &hard_cases_in_f32(per_set)?,
    )?;
    Ok(())
}

/// A table of the hard-case sets: how many answers of each of two tracers differ from exact.
fn print_hard_cases(
    out: &mut impl Write,
    heading: &str,
    [first, second]: [&str; 2],
    rows: &[HardCaseRow],
) -> io::Result<()> {
    writeln!(out, "\n{heading}")?;
    writeln!(out, "| set | rays | {first} | {second} |")?;
    writeln!(out, "|---|---:|---:|---:|")?;
    for row in rows {
        let [a, b] = row.differing;
        writeln!(out, "| {} | {} | {a} | {b} |", row.set, row.rays)?;
    }
    Ok(())
}

/// The scene's terrain, built as many times as fit in a second (at least three): the one
/// whose build was fastest, as every frame time is the fastest of many (a short build may
/// spend half its time in page faults on a fresh allocation, or none).
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

/// One scene measured: its label, terrain, rows and the reference tracers' figures.
type Measured = (String, Terrain, Vec<ThroughputRow>, Vec<ReferenceFigures>);

/// A reference tracer built for one terrain, with what its build took and holds.
struct Built {
    tracer: Box<dyn Reference>,
    build: Duration,
    bytes: usize,
}

/// What was measured of a reference tracer besides its frames.
struct ReferenceFigures {
    name: String,
    build: Duration,
    bytes: usize,
    /// Pixels of the frame with shadows whose colour differs from heightray's (mipmap, `f64`)
    /// by more than [`LEVELS_APART`] in a channel.
    differing: usize,
    /// Primary hits: heightray's, the reference's.
    hits: (u64, u64),
}

/// Colours this many levels apart or fewer count as the same pixel: a hit point in `f32`
/// shades a level or two off the one in `f64`.
const LEVELS_APART: u32 = 2;

/// Embree's scenes of the terrain, its triangles and its grid, when asked for.
#[cfg(feature = "embree")]
fn references(args: &SpeedArgs, terrain: &Terrain) -> anyhow::Result<Vec<Built>> {
    use heightray::bench::embree::{EmbreeScene, Geometry};
    let geometries = if args.embree {
        [Geometry::Triangles, Geometry::Grid].as_slice()
    } else {
        &[]
    };
    let build = |&geometry| -> anyhow::Result<Built> {
        let scene = EmbreeScene::build(terrain, geometry)?;
        Ok(Built {
            build: scene.build_time(),
            bytes: scene.bytes(),
            tracer: Box::new(scene),
        })
    };
    geometries.iter().map(build).collect()
}

#[cfg(not(feature = "embree"))]
fn references(args: &SpeedArgs, _terrain: &Terrain) -> anyhow::Result<Vec<Built>> {
    anyhow::ensure!(!args.embree, WITHOUT_EMBREE);
    Ok(Vec::new())
}

/// The configurations' rows, and the reference tracers' figures if they were asked for
/// (their scenes are dropped here: at 8193² Embree's take gigabytes).
fn measure(
    args: &SpeedArgs,
    scene: &Scene,
    terrain: &Terrain,
    bar: &ProgressBar,
) -> anyhow::Result<(Vec<ThroughputRow>, Vec<ReferenceFigures>)> {
    let built = references(args, terrain)?;
    let tracers: Vec<&dyn Reference> = built.iter().map(|b| &*b.tracer).collect();
    let rows = throughput(
        scene,
        terrain,
        &args.methods,
        &args.ariths,
        &args.threads,
        &tracers,
        &mut || bar.inc(1),
    )?;
    let render = |tracer| {
        let renderer = view(scene, terrain, tracer, true);
        let (w, h) = renderer.camera.size();
        let mut frame = Frame::new(w, h);
        render_as(tracer, &renderer, &tracers, &mut frame);
        frame
    };
    if built.is_empty() {
        return Ok((rows, Vec::new()));
    }
    let ours = render(Tracer::Heightray(Method::Mipmap, Arith::F64));
    let apart = |a: u32, b: u32| {
        (0..3).any(|k| ((a >> (8 * k)) & 255).abs_diff((b >> (8 * k)) & 255) > LEVELS_APART)
    };
    let figures = built.iter().enumerate().map(|(k, built)| {
        let theirs = render(Tracer::Reference(k));
        let pairs = ours.pixels.iter().zip(&theirs.pixels);
        ReferenceFigures {
            name: built.tracer.name(),
            build: built.build,
            bytes: built.bytes,
            differing: pairs.filter(|(&a, &b)| apart(a, b)).count(),
            hits: (ours.totals.primary_hits, theirs.totals.primary_hits),
        }
    });
    Ok((rows, figures.collect()))
}

fn print_table(
    out: &mut impl Write,
    label: &str,
    terrain: &Terrain,
    rows: &[ThroughputRow],
    references: &[ReferenceFigures],
) -> io::Result<()> {
    let field = terrain.field();
    let samples = (field.width() * field.height()) as f64;
    writeln!(
        out,
        "\n{label}: {}x{} samples",
        field.width(),
        field.height()
    )?;
    writeln!(out, "| method | arith | threads | build ms | bytes/sample | primary Mrays/s | shadow Mrays/s | frame with shadows ms | time x f64 | 2 threads x 1 |")?;
    writeln!(out, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")?;
    for row in rows {
        let same = |tracer, threads| {
            rows.iter()
                .find(|r| r.tracer == tracer && r.threads == threads)
        };
        let versus_f64 = match row.tracer {
            Tracer::Heightray(method, _) => {
                same(Tracer::Heightray(method, Arith::F64), row.threads)
                    .map(|r| r.primary_per_second() / row.primary_per_second())
            }
            Tracer::Reference(_) => None,
        };
        let versus_one = same(row.tracer, 1)
            .filter(|_| row.threads > 1)
            .map(|r| row.primary_per_second() / r.primary_per_second());
        let (method, arith) = names(row.tracer, references);
        let (build, bytes) = match row.tracer {
            Tracer::Heightray(method, _) => prepare(terrain, method),
            Tracer::Reference(k) => (references[k].build, references[k].bytes),
        };
        writeln!(
            out,
            "| {method} | {arith} | {} | {:.1} | {:.2} | {:.3} | {} | {:.1} | {} | {} |",
            row.threads,
            build.as_secs_f64() * 1e3,
            bytes as f64 / samples,
            row.primary_per_second() / 1e6,
            row.shadow_per_second()
                .map_or("-".into(), |r| format!("{:.3}", r / 1e6)),
            row.total_time.as_secs_f64() * 1e3,
            versus_f64.map_or("-".into(), |r| format!("{r:.2}")),
            versus_one.map_or("-".into(), |r| format!("{r:.2}")),
        )?;
    }
    if rows.iter().any(|r| r.shadow_per_second().is_none()) {
        writeln!(out, "(shadow Mrays/s \"-\": no shadow rays, or the frame with shadows was not slower than the one without: shadows were lost in the noise of the two times)")?;
    }
    if !references.is_empty() {
        writeln!(out, "(embree: Embree 3 on the terrain's triangles, or on its grid, in f32, built on one thread; its bytes/sample are all it holds, vertices included, where heightray's are what it holds beyond the 2-byte samples)")?;
    }
    let pixels = rows.first().map_or(0, |r| r.primary_rays);
    for figures in references {
        writeln!(out, "({}: its frame with shadows differs from the mipmap's in f64 in {} of {pixels} pixels by more than {LEVELS_APART} levels in a channel; primary hits: mipmap {}, {} {})",
            figures.name, figures.differing, figures.hits.0, figures.name, figures.hits.1)?;
    }
    Ok(())
}

/// A tracer's method and arithmetic columns.
fn names(tracer: Tracer, references: &[ReferenceFigures]) -> (String, String) {
    match tracer {
        Tracer::Heightray(method, arith) => (method.to_string(), arith.to_string()),
        Tracer::Reference(k) => (references[k].name.clone(), "f32".into()),
    }
}

/// How each method's time per primary ray grows with the terrain size (first arithmetic, one
/// thread) beside the growth of log N, and the queries per primary ray it grows with.
fn print_growth<W: Write>(out: &mut W, measured: &[Measured]) -> io::Result<()> {
    let first = &measured[0];
    let side = |t: &Terrain| t.field().width() as f64;
    let mut header = "| method | arith |".to_string();
    for (_, terrain, _, _) in measured {
        header += &format!(" {0}x{0} |", side(terrain));
    }
    header += &format!("\n|---|---|{}", "---:|".repeat(measured.len()));
    // One line per method: `cell` of its row at each size.
    let lines =
        |out: &mut W, cell: &dyn Fn(&ThroughputRow, &ThroughputRow) -> String, ours_only: bool| {
            let ours = |r: &&ThroughputRow| !ours_only || matches!(r.tracer, Tracer::Heightray(..));
            for base in first.2.iter().filter(|r| r.threads == 1).filter(ours) {
                let (method, arith) = names(base.tracer, &first.3);
                let mut line = format!("| {method} | {arith} |");
                for (_, _, rows, _) in measured {
                    let row = rows
                        .iter()
                        .find(|r| r.tracer == base.tracer && r.threads == base.threads);
                    line += &row.map_or(" - |".into(), |r| format!(" {} |", cell(base, r)));
                }
                writeln!(out, "{line}")?;
            }
            Ok(())
        };

    writeln!(
        out,
        "\ngrowth of time per primary ray with the terrain size (x the smallest)\n{header}"
    )?;
    let growth = |base: &ThroughputRow, r: &ThroughputRow| {
        format!("{:.2}", base.primary_per_second() / r.primary_per_second())
    };
    lines(out, &growth, false)?;
    let mut line = "| log2 N | - |".to_string();
    for (_, terrain, _, _) in measured {
        line += &format!(" {:.2} |", side(terrain).log2() / side(&first.1).log2());
    }
    writeln!(out, "{line}")?;

    // What the time grows with: the finer terrain has more near misses per ray.
    writeln!(out, "\nqueries per primary ray: block / run / cell / triangle / beam (once per tile of rays)\n{header}")?;
    let queries = |_: &ThroughputRow, r: &ThroughputRow| {
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
    };
    lines(out, &queries, true)
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
