//! `bench speed --out-of-core`: the frames of each landscape size traced from a tile store
//! whose pages are held to a quarter of its size, beside the same map in memory, in one run.

use super::bench::measure;
use super::loading::store_memory;
use super::speed_report::TerrainReport;
use super::SpeedArgs;
use heightray::bench::{ThroughputRow, Tracer};
use heightray::heightfield::store::{self, residency};
use heightray::heightfield::{load_with, LoadOptions};
use heightray::render::Scene;
use heightray::Terrain;
use indicatif::ProgressBar;
use std::ops::ControlFlow;

/// The reports of `scene`'s map from a tile store (written to a temporary file, its pages
/// held to a quarter of its size), after `in_memory`'s rows of the same map; writes each
/// frame's time from the store over its time in memory.
pub fn from_store(
    args: &SpeedArgs,
    scene: &Scene,
    in_memory: &[ThroughputRow],
    bar: &ProgressBar,
    notes: &mut Vec<String>,
) -> anyhow::Result<TerrainReport> {
    let path = std::env::temp_dir().join(format!("heightray-bench-{}.hrt", std::process::id()));
    store::save(&scene.field, &path)?;
    let bytes = std::fs::metadata(&path)?.len();
    residency::set_budget(bytes / 4);
    let options = LoadOptions::new(scene.field.z_scale());
    let field = load_with(&path, &options, &|_| ControlFlow::Continue(()));
    // (Gone when the map is: the mapping keeps the file's pages while it is open.)
    std::fs::remove_file(&path)?;
    let field = field?;
    let terrain = Terrain::new(field);
    let (rows, references) = measure(args, scene, &terrain, bar, notes)?;
    let (w, h) = (scene.field.width(), scene.field.height());
    for (stored, kept) in rows.iter().zip(in_memory) {
        let Tracer::Heightray(method, arith) = stored.tracer else {
            continue;
        };
        notes.push(format!(
            "{w}x{h} from a tile store of {:.0} MB held to {:.0} MB, over in memory, {method} \
             {arith} on {} thread(s): frame {:.2}x, with shadows {:.2}x",
            bytes as f64 / 1e6,
            residency::budget() as f64 / 1e6,
            stored.threads,
            stored.primary_time.as_secs_f64() / kept.primary_time.as_secs_f64(),
            stored.total_time.as_secs_f64() / kept.total_time.as_secs_f64(),
        ));
    }
    store_memory(&terrain);
    let label = format!("the same map from a tile store ({w}x{h})");
    Ok(TerrainReport::new(
        label,
        &terrain,
        &rows,
        &references,
        None,
    ))
}
