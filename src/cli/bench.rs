//! `heightray bench ...`: tables on stdout.

use super::speed_report::{
    print_growth, print_table, Machine, ReferenceBuild, SpeedReport, StripsReport, TerrainReport,
    LEVELS_APART,
};
use super::{SpeedArgs, TextbookArgs};
use heightray::arith::Arith;
use heightray::bench::{
    hard_cases_versus_exact, render_as, sized_scene, throughput, versus_textbook, view,
    HardCaseRow, Reference, ThroughputRow, Tracer, ROUNDS, SEED,
};
use heightray::heightfield::StripBounds;
use heightray::output_file;
use heightray::render::timing::timed;
use heightray::render::Frame;
use heightray::render::{Scene, SceneFile};
use heightray::traverse::Method;
use heightray::traverse::{SimdPath, SIMD_VARIABLE};
use heightray::Terrain;
use indicatif::ProgressBar;
use indicatif::ProgressStyle;
use std::io::{self, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// Embree's tracers in `bench speed --embree`: its triangles by single rays and two packet
/// widths, and its grid.
const EMBREE_TRACERS: usize = 4;

pub fn speed(args: &SpeedArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        args.frames.threads.iter().all(|&t| t > 0),
        "--threads counts must be at least 1"
    );
    let tracers = args.frames.methods.len() * args.frames.ariths.len()
        + EMBREE_TRACERS * usize::from(args.embree);
    let configs = tracers * args.frames.threads.len() * ROUNDS;
    let (mut measured, mut notes) = (Vec::new(), Vec::new());
    if args.frames.sizes.is_empty() {
        let scenes = scenes_or_builtins(&args.frames.scenes)?;
        let size = args.frames.size.unwrap_or(256);
        let bar = progress_bar(configs * scenes.len());
        for source in &scenes {
            let name = source.path.display().to_string();
            bar.set_message(name.clone());
            let scene = scene_at_size(source, size)?;
            let terrain = Terrain::new(scene.field.clone());
            let (rows, references) = measure(args, &scene, &terrain, &bar, &mut notes)?;
            let strips = sun_strips(&scene, &terrain);
            measured.push(TerrainReport::new(
                name,
                &terrain,
                &rows,
                &references,
                strips,
            ));
        }
        bar.finish_and_clear();
    } else {
        let size = args.frames.size.unwrap_or(512);
        let bar = progress_bar(configs * args.frames.sizes.len());
        for &samples in &args.frames.sizes {
            bar.set_message(format!("generating {samples}x{samples}"));
            let scene = sized_scene(samples, size)?;
            let terrain = fastest_build(&scene);
            bar.set_message(format!("{samples}x{samples}"));
            let (rows, references) = measure(args, &scene, &terrain, &bar, &mut notes)?;
            let label = format!("valley landscape (seed {SEED}) at {samples}x{samples}");
            let strips = sun_strips(&scene, &terrain);
            measured.push(TerrainReport::new(
                label,
                &terrain,
                &rows,
                &references,
                strips,
            ));
            if args.out_of_core {
                let stored =
                    super::bench_out_of_core::from_store(args, &scene, &rows, &bar, &mut notes)?;
                measured.push(stored);
            }
        }
        bar.finish_and_clear();
    }
    let report = SpeedReport {
        command: std::env::args().collect::<Vec<_>>().join(" "),
        machine: Machine::this(),
        terrains: measured,
        notes,
    };
    let out = &mut std::io::stdout().lock();
    for terrain in &report.terrains {
        print_table(out, terrain)?;
    }
    for note in &report.notes {
        writeln!(out, "{note}")?;
    }
    if let Err(message) = SimdPath::requested() {
        eprintln!("heightray: {message}");
    }
    writeln!(
        out,
        "SIMD path of the packet walk (`render --packets on`): {} (forced with {SIMD_VARIABLE}=scalar|avx2|avx512)",
        SimdPath::active()
    )?;
    if report.terrains.len() > 1 && !args.frames.sizes.is_empty() && !args.out_of_core {
        print_growth(out, &report.terrains)?;
    }
    if let Some(path) = &args.out {
        let json = serde_json::to_string_pretty(&report)?;
        output_file::write_bytes(path, (json + "\n").as_bytes()).map_err(anyhow::Error::msg)?;
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
        "camera rays, one thread, f64; heightray's mipmap walk without the renderer's wedge clearances"
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
pub(super) const WITHOUT_EMBREE: &str =
    "this heightray was built without Embree: install libembree-dev \
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

/// What the sun's strip bounds of the scene's view take to build (the fastest of at least
/// three builds, or as many as fit in half a second) and hold; `None` where the view has none.
fn sun_strips(scene: &Scene, terrain: &Terrain) -> Option<StripsReport> {
    let renderer = view(
        scene,
        terrain,
        Tracer::Heightray(Method::Mipmap, Arith::F64),
        true,
    );
    let strips = renderer.shader.strip_bounds()?;
    let (dir, half) = (strips.dir(), strips.half());
    let start = Instant::now();
    let mut fastest = (Duration::MAX, 0);
    for built in 0.. {
        if built >= 3 && start.elapsed() > Duration::from_millis(500) {
            break;
        }
        let ((), time) = timed(|| {
            let bounds = StripBounds::build(terrain.field(), dir, half);
            fastest.1 = bounds.map_or(0, |b| b.bytes());
        });
        fastest.0 = fastest.0.min(time);
    }
    let samples = (terrain.field().width() * terrain.field().height()) as f64;
    Some(StripsReport {
        build_ms: fastest.0.as_secs_f64() * 1e3,
        bytes_per_sample: fastest.1 as f64 / samples,
    })
}

/// A reference tracer built for one terrain, with what its build took and holds.
struct Built {
    tracer: Box<dyn Reference>,
    build: Duration,
    bytes: usize,
}

/// Embree's scenes of the terrain when asked for: its triangles traced by single rays and by
/// packets of 8 and 16 where this build and processor trace them natively (`notes` says
/// where not), and its grid by single rays.
#[cfg(feature = "embree")]
fn references(
    args: &SpeedArgs,
    terrain: &Terrain,
    notes: &mut Vec<String>,
) -> anyhow::Result<Vec<Built>> {
    use heightray::bench::embree::{Api, EmbreeScene, EmbreeTracer, Geometry};
    use std::sync::Arc;
    let mut built = Vec::new();
    if !args.embree {
        return Ok(built);
    }
    for geometry in [Geometry::Triangles, Geometry::Grid] {
        let scene = Arc::new(EmbreeScene::build(terrain, geometry)?);
        let note = format!("Embree {}", scene.version());
        if !notes.contains(&note) {
            notes.push(note);
        }
        let apis = match geometry {
            Geometry::Triangles => [Api::Single, Api::Packets8, Api::Packets16].as_slice(),
            Geometry::Grid => &[Api::Single],
        };
        for &api in apis {
            if api != Api::Single && !scene.native_packets(api.width()) {
                let note = format!(
                    "Embree's {}-wide packets: not native in this build of Embree on this processor (rtcGetDeviceProperty), not measured",
                    api.width()
                );
                if !notes.contains(&note) {
                    notes.push(note);
                }
                continue;
            }
            built.push(Built {
                build: scene.build_time(),
                bytes: scene.bytes(),
                tracer: Box::new(EmbreeTracer {
                    scene: scene.clone(),
                    api,
                }),
            });
        }
    }
    Ok(built)
}

#[cfg(not(feature = "embree"))]
fn references(
    args: &SpeedArgs,
    _terrain: &Terrain,
    _notes: &mut Vec<String>,
) -> anyhow::Result<Vec<Built>> {
    anyhow::ensure!(!args.embree, WITHOUT_EMBREE);
    Ok(Vec::new())
}

/// The configurations' rows, and the reference tracers' figures if they were asked for
/// (their scenes are dropped here: at 8193² Embree's take gigabytes).
pub(super) fn measure(
    args: &SpeedArgs,
    scene: &Scene,
    terrain: &Terrain,
    bar: &ProgressBar,
    notes: &mut Vec<String>,
) -> anyhow::Result<(Vec<ThroughputRow>, Vec<ReferenceBuild>)> {
    let built = references(args, terrain, notes)?;
    // The bar counted every Embree tracer; a packet width this processor lacks is not run.
    let left_out = (EMBREE_TRACERS * usize::from(args.embree)).saturating_sub(built.len());
    if let Some(len) = bar.length() {
        let configs = left_out * args.frames.threads.len() * ROUNDS;
        bar.set_length(len.saturating_sub(configs as u64));
    }
    let tracers: Vec<&dyn Reference> = built.iter().map(|b| &*b.tracer).collect();
    let rows = throughput(
        scene,
        terrain,
        &args.frames.methods,
        &args.frames.ariths,
        &args.frames.threads,
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
        ReferenceBuild {
            name: built.tracer.name(),
            build: built.build,
            bytes: built.bytes,
            differing: pairs.filter(|(&a, &b)| apart(a, b)).count(),
            hits: (ours.totals.primary_hits, theirs.totals.primary_hits),
        }
    });
    Ok((rows, figures.collect()))
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
    file.size = Some((size, size));
    let path = &source.path;
    Ok(Scene::from_file(&file, Scene::base(path), path)?)
}
