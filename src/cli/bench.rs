//! `heightray bench ...`: tables on stdout.

use super::SpeedArgs;
use anyhow::Context;
use heightray::bench::measure;
use heightray::heightfield::{self, Builtin, BUILTINS};
use heightray::render::Camera;
use heightray::traverse::Arith;
use heightray::Terrain;
use std::process::ExitCode;

pub fn speed(args: &SpeedArgs) -> anyhow::Result<ExitCode> {
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
