//! `heightray bench effects`: what each effect costs on the built-in scenes, as ratios to
//! the plain frame in one run, and how samples per pixel converge.

use super::bench::{scene_at_size, scenes_or_builtins};
use super::EffectsArgs;
use heightray::bench::{block_average, configurations, frame_with, rms_error, EffectRow};
use heightray::output_file;
use heightray::render::effects::{Effects, Water, MOST_RAYS};
use heightray::render::WaterSection;
use heightray::Terrain;
use serde_json::json;
use std::io::Write;
use std::process::ExitCode;

/// The reference of the samples' convergence is rendered this many times larger.
const SUPERSAMPLING: u32 = 4;

pub fn run(args: &EffectsArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        (1..=MOST_RAYS).contains(&args.samples),
        "--samples must be from 1 to {MOST_RAYS}"
    );
    anyhow::ensure!(
        args.sun_angle_deg > 0.0 && args.sun_angle_deg <= 20.0,
        "--sun-angle-deg must be above 0 and at most 20"
    );
    anyhow::ensure!(
        !args.embree || cfg!(feature = "embree"),
        super::bench::WITHOUT_EMBREE
    );
    let pool = super::knobs::worker_pool(args.threads)?;
    let out = &mut std::io::stdout().lock();
    let mut report = Vec::new();
    for source in scenes_or_builtins(&args.scenes)? {
        let name = source.path.display().to_string();
        let scene = scene_at_size(&source, args.size)?;
        let terrain = Terrain::new(scene.field.clone());
        let base = scene.lighting.effects;
        let water = base.water.map_or_else(|| low_water(&scene), Ok)?;
        let rows: Vec<EffectRow> = configurations(base, args.sun_angle_deg, args.samples, water)
            .into_iter()
            .map(|(label, effects)| pool.install(|| frame_with(&scene, &terrain, effects, &label)))
            .collect();
        writeln!(
            out,
            "\n{name} at {0}x{0}, {1} threads (shadows {2}):\n",
            args.size,
            pool.current_num_threads(),
            if scene.lighting.shadows { "on" } else { "off" }
        )?;
        print_costs(out, &rows)?;
        let embree = versus_embree(out, &pool, &scene, &terrain, &rows, args.embree)?;
        let samples = convergence(out, &pool, &source, &rows, args)?;
        report.push(json!({"scene": name, "frames": rows.iter().map(row_json).collect::<Vec<_>>(), "samples": samples, "embree": embree}));
    }
    if let Some(path) = &args.out {
        let text = serde_json::to_string_pretty(&json!({
            "command": std::env::args().collect::<Vec<_>>().join(" "),
            "size": args.size, "threads": pool.current_num_threads(), "scenes": report,
        }))?;
        output_file::write_bytes(path, (text + "\n").as_bytes()).map_err(anyhow::Error::msg)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The share of the map's samples the water of a scene without any floods.
const FLOODED: f64 = 0.4;

/// The scene's water, or where it has none a lake over the lowest [`FLOODED`] of the map's
/// samples: low enough to leave the relief standing, wide enough to show in the frame.
fn low_water(scene: &heightray::render::Scene) -> anyhow::Result<Water> {
    let field = &scene.field;
    // (A map has at least 2 x 2 samples.)
    let mut heights: Vec<f64> = (0..field.height())
        .flat_map(|j| (0..field.width()).map(move |i| field.z(i, j)))
        .collect();
    heights.sort_by(f64::total_cmp);
    let level = heights[((heights.len() - 1) as f64 * FLOODED) as usize];
    let section = WaterSection {
        level,
        colour: None,
    };
    // (The level is a height `z`; the section's is in the map's units.)
    let water = section.validate(field).map_err(anyhow::Error::msg)?;
    Ok(Water { level, ..water })
}

/// The costs table: time and rays per pixel by kind, as ratios to the first (plain) row,
/// a column of rays and one of the share left out per effect of the list.
fn print_costs(out: &mut impl Write, rows: &[EffectRow]) -> anyhow::Result<()> {
    let words: Vec<&str> = rows
        .first()
        .map(|row| row.each_effect().iter().map(|e| e.word).collect())
        .unwrap_or_default();
    let columns = |what: &str| {
        words
            .iter()
            .map(|w| format!(" {w} {what} |"))
            .collect::<String>()
    };
    writeln!(
        out,
        "| frame | ms | x plain | camera rays/px | shadow rays/px |{}{}",
        columns("rays/px"),
        columns("culled")
    )?;
    writeln!(
        out,
        "|---|---:|---:|---:|---:|{}",
        "---:|".repeat(2 * words.len())
    )?;
    let plain = rows.first().map_or(1.0, |r| r.time.as_secs_f64());
    let percent = |share: Option<f64>| share.map_or("-".into(), |s| format!("{:.0}%", 100.0 * s));
    for row in rows {
        let (t, px) = (&row.totals, row.pixel_count());
        let per = |n: u64| n as f64 / px;
        let effects = row.each_effect();
        let rays: String = effects
            .iter()
            .map(|e| format!(" {:.2} |", per(e.rays)))
            .collect();
        let culled: String = effects
            .iter()
            .map(|e| format!(" {} |", percent(e.culled)))
            .collect();
        writeln!(
            out,
            "| {} | {:.0} | {:.2} | {:.2} | {:.2} |{rays}{culled}",
            row.label,
            row.time.as_secs_f64() * 1e3,
            row.time.as_secs_f64() / plain,
            per(t.primary_rays),
            per(t.shadow_rays),
        )?;
    }
    let firsts: Vec<String> = rows
        .iter()
        .map(|r| format!("{} {:.0}", r.label, r.first.as_secs_f64() * 1e3))
        .collect();
    writeln!(
        out,
        "\nms: the faster of two frames in a row; the first (which makes the sky's bounds, \
         kept for the terrain, as rays ask): {} ms",
        firsts.join(", ")
    )?;
    Ok(())
}

/// The one-sample frames without water against Embree casting all their rays, where asked:
/// a table, and its rows as JSON.
#[cfg(feature = "embree")]
fn versus_embree(
    out: &mut impl Write,
    pool: &rayon::ThreadPool,
    scene: &heightray::render::Scene,
    terrain: &Terrain,
    rows: &[EffectRow],
    asked: bool,
) -> anyhow::Result<serde_json::Value> {
    use heightray::bench::embree::{EmbreeScene, Geometry};
    use heightray::bench::renderer_with;
    use heightray::render::Frame;
    if !asked {
        return Ok(serde_json::Value::Null);
    }
    let embree = EmbreeScene::build(terrain, Geometry::Triangles)?;
    writeln!(out, "\nagainst Embree {} (its triangles, single rays) casting every ray of the same effects from its own hits, none culled:\n", embree.version())?;
    writeln!(out, "| frame | heightray ms | embree ms | embree occlusion rays/px | heightray occlusion rays/px | x embree (its time / heightray's) |")?;
    writeln!(out, "|---|---:|---:|---:|---:|---:|")?;
    let mut json_rows = Vec::new();
    for row in rows
        .iter()
        .filter(|r| r.effects.samples == 1 && r.effects.water.is_none())
    {
        let renderer = renderer_with(scene, terrain, row.effects);
        let (w, h) = scene.camera.size();
        // (The faster of two frames, as heightray's.)
        let timed = || {
            let mut frame = Frame::new(w, h);
            let start = std::time::Instant::now();
            let cast = pool.install(|| embree.render_effects(&renderer, &mut frame));
            (cast, start.elapsed().as_secs_f64())
        };
        let ((cast, first), (_, again)) = (timed(), timed());
        let time = first.min(again);
        let t = &row.totals;
        let effect_rays: u64 = row.each_effect().iter().map(|e| e.rays).sum();
        let ours = t.shadow_rays + effect_rays;
        let px = row.pixel_count();
        let ms = row.time.as_secs_f64();
        writeln!(
            out,
            "| {} | {:.0} | {:.0} | {:.2} | {:.2} | {:.2} |",
            row.label,
            ms * 1e3,
            time * 1e3,
            cast as f64 / px,
            ours as f64 / px,
            time / ms
        )?;
        json_rows.push(json!({"frame": row.label, "heightray_ms": ms * 1e3, "embree_ms": time * 1e3, "embree_rays": cast, "heightray_rays": ours}));
    }
    Ok(json!(json_rows))
}

#[cfg(not(feature = "embree"))]
fn versus_embree(
    _out: &mut impl Write,
    _pool: &rayon::ThreadPool,
    _scene: &heightray::render::Scene,
    _terrain: &Terrain,
    _rows: &[EffectRow],
    asked: bool,
) -> anyhow::Result<serde_json::Value> {
    // (`run` refused `--embree` in a build without Embree.)
    let _ = asked;
    Ok(serde_json::Value::Null)
}

fn row_json(row: &EffectRow) -> serde_json::Value {
    let mut json = json!({
        "frame": row.label, "ms": row.time.as_secs_f64() * 1e3, "first_ms": row.first.as_secs_f64() * 1e3,
        "stats": row.totals.to_json(),
    });
    for effect in row.each_effect() {
        json[format!("{}_culled", effect.word)] = json!(effect.culled);
    }
    json
}

/// Uniform and adaptive samples against the scene rendered `SUPERSAMPLING` times larger
/// with one sample per pixel and averaged over blocks: their errors and camera rays.
fn convergence(
    out: &mut impl Write,
    pool: &rayon::ThreadPool,
    source: &super::bench::SceneSource,
    rows: &[EffectRow],
    args: &EffectsArgs,
) -> anyhow::Result<serde_json::Value> {
    let large = scene_at_size(source, args.size * SUPERSAMPLING)?;
    let terrain = Terrain::new(large.field.clone());
    let plain = rows.first().map_or(Effects::default(), |row| row.effects);
    let reference = pool.install(|| frame_with(&large, &terrain, plain, "reference"));
    let reference = block_average(&reference.pixels, args.size * SUPERSAMPLING, SUPERSAMPLING);
    let scene = scene_at_size(source, args.size)?;
    let mut measured: Vec<EffectRow> = [1, 4]
        .into_iter()
        .filter(|&n| n < args.samples)
        .map(|samples| {
            let effects = Effects { samples, ..plain };
            let label = format!("{samples} samples");
            pool.install(|| frame_with(&scene, &terrain, effects, &label))
        })
        .collect();
    measured.extend(
        rows.iter()
            .filter(|r| {
                r.effects.samples > 1 && r.effects.sun_angle_deg == 0.0 && !r.effects.sky_light
            })
            .cloned(),
    );
    writeln!(out, "\nsamples against the image rendered {SUPERSAMPLING}x larger and averaged over {SUPERSAMPLING}x{SUPERSAMPLING} blocks (linear light):\n")?;
    writeln!(
        out,
        "| frame | rms error | camera rays/px | rays x uniform |"
    )?;
    writeln!(out, "|---|---:|---:|---:|")?;
    let uniform = measured
        .iter()
        .find(|r| r.effects.samples == args.samples && !r.effects.adaptive)
        .map_or(1.0, |r| r.totals.primary_rays as f64);
    let mut json_rows = Vec::new();
    for row in &measured {
        let error = rms_error(&row.pixels, &reference);
        let rays = row.totals.primary_rays as f64;
        writeln!(
            out,
            "| {} | {:.5} | {:.2} | {:.2} |",
            row.label,
            error,
            rays / row.pixel_count(),
            rays / uniform
        )?;
        json_rows.push(
            json!({"frame": row.label, "rms_error": error, "camera_rays": row.totals.primary_rays}),
        );
    }
    Ok(json!(json_rows))
}
