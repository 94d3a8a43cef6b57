//! What `bench speed` measured, as one value: printed as Markdown tables on stdout and written
//! as JSON with `--out`, so the tables and the file always hold the same figures.

use heightray::arith::Arith;
use heightray::bench::{ThroughputRow, Tracer};
use heightray::traverse::{prepare, HitMiss};
use heightray::Terrain;
use serde::Serialize;
use std::io::{self, Write};
use std::time::Duration;

/// A whole run of `bench speed`.
#[derive(Serialize)]
pub struct SpeedReport {
    /// The command line that made the report.
    pub command: String,
    pub machine: Machine,
    pub terrains: Vec<TerrainReport>,
    /// What the run says of itself beside the tables: Embree's version, and which of its
    /// packet widths were not measured and why.
    pub notes: Vec<String>,
}

/// The machine the figures were measured on.
#[derive(Serialize)]
pub struct Machine {
    /// The processor's model name (`/proc/cpuinfo`), or "unknown".
    pub cpu: String,
    /// Hardware threads the operating system offers.
    pub threads: usize,
}

impl Machine {
    pub fn this() -> Machine {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|info| {
                info.lines()
                    .find(|line| line.starts_with("model name"))
                    .and_then(|line| line.split_once(':'))
                    .map(|(_, name)| name.trim().to_string())
            })
            .unwrap_or_else(|| "unknown".into());
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        Machine { cpu, threads }
    }
}

/// One terrain's configurations.
#[derive(Serialize)]
pub struct TerrainReport {
    pub label: String,
    /// Samples per side: width, height.
    pub samples: [usize; 2],
    pub rows: Vec<RowReport>,
    /// Figures of the reference tracers that are not frame times.
    pub references: Vec<ReferenceReport>,
    /// Each of heightray's rows against each reference tracer's at the same thread count.
    pub versus_references: Vec<Versus>,
    /// The sun's strip bounds, where the view has them: built once per direction of the sun
    /// and kept while it stays, so the frames above hold them already (steady state).
    pub sun_strips: Option<StripsReport>,
}

/// What the sun's strip bounds cost to build and hold.
#[derive(Serialize, Clone, Copy)]
pub struct StripsReport {
    /// The fastest of several builds, on one thread.
    pub build_ms: f64,
    pub bytes_per_sample: f64,
}

/// A row of heightray's against a reference tracer's row at the same thread count.
#[derive(Serialize)]
pub struct Versus {
    pub method: String,
    pub arith: String,
    pub threads: usize,
    pub reference: String,
    /// heightray's primary (camera) rays per second over the reference's: above 1, heightray
    /// is faster.
    pub camera_x: f64,
    /// heightray's shadow rays per second over the reference's, where both were measured.
    pub shadow_x: Option<f64>,
    /// heightray's time for the frame with shadows over the reference's: below 1, heightray
    /// is faster.
    pub frame_time_x: f64,
    /// The same with the sun moving: the strip bounds' build added to heightray's frame.
    pub sun_moving_frame_time_x: f64,
}

/// One configuration: a tracer at a thread count.
#[derive(Serialize)]
pub struct RowReport {
    pub method: String,
    pub arith: String,
    pub threads: usize,
    pub build_ms: f64,
    /// Bytes of acceleration data per sample (heightray: beyond its 2-byte samples; a
    /// reference tracer: everything it holds).
    pub bytes_per_sample: f64,
    pub primary_rays: u64,
    pub shadow_rays: u64,
    pub primary_mrays_per_s: f64,
    /// `None` where there were no shadow rays or their time was lost in the noise.
    pub shadow_mrays_per_s: Option<f64>,
    pub frame_ms: f64,
    pub frame_with_shadows_ms: f64,
    /// The frame with shadows' time against the same method's in `f64` at the same thread
    /// count.
    pub frame_x_f64: Option<f64>,
    /// Primary rays per second against the same tracer on one thread.
    pub threads_x_one: Option<f64>,
    /// Queries per primary ray (heightray's tracers only).
    pub queries_per_primary_ray: Option<Queries>,
}

/// Queries per primary ray, by kind.
#[derive(Serialize, Clone, Copy)]
pub struct Queries {
    pub block: f64,
    pub run: f64,
    pub cell: f64,
    pub triangle: f64,
    /// Wedge look-ups: one per camera ray, for its clearance.
    pub wedge: f64,
}

/// What was measured of a reference tracer besides its frames.
#[derive(Serialize)]
pub struct ReferenceReport {
    pub name: String,
    pub build_ms: f64,
    pub bytes_per_sample: f64,
    /// Pixels of its frame with shadows whose colour differs from heightray's (mipmap, `f64`)
    /// by more than [`LEVELS_APART`] in a channel.
    pub differing_pixels: usize,
    pub pixels: u64,
    /// Primary hits: heightray's (mipmap, `f64`), the reference's.
    pub primary_hits: [u64; 2],
}

/// Colours this many levels apart or fewer count as the same pixel: a hit point in `f32`
/// shades a level or two off the one in `f64`.
pub const LEVELS_APART: u32 = 2;

/// A reference tracer's build and what it holds, before its rows are reported.
pub struct ReferenceBuild {
    pub name: String,
    pub build: Duration,
    pub bytes: usize,
    pub differing: usize,
    pub hits: (u64, u64),
}

impl TerrainReport {
    /// The report of one terrain's rows, with each row's ratios worked out.
    pub fn new(
        label: String,
        terrain: &Terrain,
        rows: &[ThroughputRow],
        references: &[ReferenceBuild],
        sun_strips: Option<StripsReport>,
    ) -> TerrainReport {
        let field = terrain.field();
        let samples = (field.width() * field.height()) as f64;
        let same = |tracer, threads| {
            rows.iter()
                .find(|r: &&ThroughputRow| r.tracer == tracer && r.threads == threads)
        };
        let row_report = |row: &ThroughputRow| {
            let (method, arith, build, bytes) = match row.tracer {
                Tracer::Heightray(method, arith) => {
                    let (build, bytes) = prepare(terrain, method);
                    (method.to_string(), arith.to_string(), build, bytes)
                }
                Tracer::Reference(k) => {
                    let r = &references[k];
                    (r.name.clone(), "f32".into(), r.build, r.bytes)
                }
            };
            let frame_x_f64 = match row.tracer {
                Tracer::Heightray(method, _) => {
                    same(Tracer::Heightray(method, Arith::F64), row.threads)
                        .map(|r| row.total_time.as_secs_f64() / r.total_time.as_secs_f64())
                }
                Tracer::Reference(_) => None,
            };
            let threads_x_one = same(row.tracer, 1)
                .filter(|_| row.threads > 1)
                .map(|r| row.primary_per_second() / r.primary_per_second());
            let queries = matches!(row.tracer, Tracer::Heightray(..)).then(|| {
                let per_ray = |q: HitMiss| q.total() as f64 / row.primary_rays as f64;
                let q = &row.primary_queries;
                Queries {
                    block: per_ray(q.block),
                    run: per_ray(q.run),
                    cell: per_ray(q.cell),
                    triangle: per_ray(q.triangle),
                    wedge: per_ray(q.wedge),
                }
            });
            RowReport {
                method,
                arith,
                threads: row.threads,
                build_ms: build.as_secs_f64() * 1e3,
                bytes_per_sample: bytes as f64 / samples,
                primary_rays: row.primary_rays,
                shadow_rays: row.shadow_rays,
                primary_mrays_per_s: row.primary_per_second() / 1e6,
                shadow_mrays_per_s: row.shadow_per_second().map(|r| r / 1e6),
                frame_ms: row.primary_time.as_secs_f64() * 1e3,
                frame_with_shadows_ms: row.total_time.as_secs_f64() * 1e3,
                frame_x_f64,
                threads_x_one,
                queries_per_primary_ray: queries,
            }
        };
        let pixels = rows.first().map_or(0, |r| r.primary_rays);
        let reference_report = |r: &ReferenceBuild| ReferenceReport {
            name: r.name.clone(),
            build_ms: r.build.as_secs_f64() * 1e3,
            bytes_per_sample: r.bytes as f64 / samples,
            differing_pixels: r.differing,
            pixels,
            primary_hits: [r.hits.0, r.hits.1],
        };
        let rows: Vec<RowReport> = rows.iter().map(row_report).collect();
        let build_ms = sun_strips.map_or(0.0, |s| s.build_ms);
        let versus_references = versus(&rows, references, build_ms);
        TerrainReport {
            label,
            samples: [field.width(), field.height()],
            rows,
            references: references.iter().map(reference_report).collect(),
            versus_references,
            sun_strips,
        }
    }
}

/// Every heightray row (named by a method) against every reference row (named by one of
/// `references`) at the same thread count; `strips_ms` is what the sun's strip bounds take to
/// build, charged to each frame where the sun moves.
fn versus(rows: &[RowReport], references: &[ReferenceBuild], strips_ms: f64) -> Vec<Versus> {
    let is_reference = |row: &RowReport| references.iter().any(|r| r.name == row.method);
    let (theirs, ours): (Vec<&RowReport>, Vec<&RowReport>) =
        rows.iter().partition(|r| is_reference(r));
    let mut pairs = Vec::new();
    for row in ours {
        for other in theirs.iter().filter(|o| o.threads == row.threads) {
            let shadow = row.shadow_mrays_per_s.zip(other.shadow_mrays_per_s);
            pairs.push(Versus {
                method: row.method.clone(),
                arith: row.arith.clone(),
                threads: row.threads,
                reference: other.method.clone(),
                camera_x: row.primary_mrays_per_s / other.primary_mrays_per_s,
                shadow_x: shadow.map(|(ours, theirs)| ours / theirs),
                frame_time_x: row.frame_with_shadows_ms / other.frame_with_shadows_ms,
                sun_moving_frame_time_x: (row.frame_with_shadows_ms + strips_ms)
                    / other.frame_with_shadows_ms,
            });
        }
    }
    pairs
}

/// Ratio columns: two decimals, `-` where there is none.
fn ratio(value: Option<f64>) -> String {
    value.map_or("-".into(), |r| format!("{r:.2}"))
}

/// One terrain's table.
pub fn print_table(out: &mut impl Write, terrain: &TerrainReport) -> io::Result<()> {
    let [w, h] = terrain.samples;
    writeln!(out, "\n{}: {w}x{h} samples", terrain.label)?;
    writeln!(out, "| method | arith | threads | build ms | bytes/sample | primary Mrays/s | shadow Mrays/s | frame with shadows ms | frame x f64 | 2 threads x 1 |")?;
    writeln!(out, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")?;
    for row in &terrain.rows {
        writeln!(
            out,
            "| {} | {} | {} | {:.1} | {:.2} | {:.3} | {} | {:.1} | {} | {} |",
            row.method,
            row.arith,
            row.threads,
            row.build_ms,
            row.bytes_per_sample,
            row.primary_mrays_per_s,
            row.shadow_mrays_per_s
                .map_or("-".into(), |r| format!("{r:.3}")),
            row.frame_with_shadows_ms,
            ratio(row.frame_x_f64),
            ratio(row.threads_x_one),
        )?;
    }
    if terrain.rows.iter().any(|r| r.shadow_mrays_per_s.is_none()) {
        writeln!(out, "(shadow Mrays/s \"-\": no shadow rays, or the frame with shadows was not slower than the one without: shadows were lost in the noise of the two times)")?;
    }
    if let Some(strips) = terrain.sun_strips {
        writeln!(out, "(the sun's strip bounds: built in {:.2} ms, {:.2} bytes/sample, once per direction of the sun and kept while it stays: the frames above are the steady state)", strips.build_ms, strips.bytes_per_sample)?;
    }
    if !terrain.references.is_empty() {
        writeln!(out, "(embree: Embree 3 on the terrain's triangles, or on its grid, in f32, built on one thread; its bytes/sample are all it holds, vertices included, where heightray's are what it holds beyond the 2-byte samples)")?;
    }
    print_versus(out, terrain)?;
    for r in &terrain.references {
        writeln!(out, "({}: its frame with shadows differs from the mipmap's in f64 in {} of {} pixels by more than {LEVELS_APART} levels in a channel; primary hits: mipmap {}, {} {})",
            r.name, r.differing_pixels, r.pixels, r.primary_hits[0], r.name, r.primary_hits[1])?;
    }
    Ok(())
}

/// heightray's rows against the reference tracers': one line per row, in each column its
/// ratio to every reference in turn.
fn print_versus(out: &mut impl Write, terrain: &TerrainReport) -> io::Result<()> {
    if terrain.versus_references.is_empty() {
        return Ok(());
    }
    let names: Vec<&str> = terrain.references.iter().map(|r| r.name.as_str()).collect();
    let names = names.join(" / ");
    writeln!(out, "\nheightray against {names}, at the same thread count: rays per second x theirs (above 1: heightray is faster), frame time x theirs (below 1: heightray is faster)")?;
    writeln!(out, "| method | arith | threads | camera rays/s x theirs | shadow rays/s x theirs | frame with shadows time x theirs | the same, sun moving |")?;
    writeln!(out, "|---|---|---:|---:|---:|---:|---:|")?;
    let mut lines = terrain
        .versus_references
        .chunk_by(|a, b| (&a.method, &a.arith, a.threads) == (&b.method, &b.arith, b.threads));
    lines.try_for_each(|line| {
        let cells = |cell: &dyn Fn(&Versus) -> Option<f64>| {
            let each = terrain.references.iter().map(|r| {
                let versus = line.iter().find(|v| v.reference == r.name);
                ratio(versus.and_then(cell))
            });
            each.collect::<Vec<_>>().join(" / ")
        };
        writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} |",
            line[0].method,
            line[0].arith,
            line[0].threads,
            cells(&|v| Some(v.camera_x)),
            cells(&|v| v.shadow_x),
            cells(&|v| Some(v.frame_time_x)),
            cells(&|v| Some(v.sun_moving_frame_time_x)),
        )
    })
}

/// How each tracer's time per primary ray grows with the terrain size (one thread) beside
/// the growth of log N, and the queries per primary ray it grows with.
pub fn print_growth<W: Write>(out: &mut W, terrains: &[TerrainReport]) -> io::Result<()> {
    let Some(first) = terrains.first() else {
        return Ok(());
    };
    let mut header = "| method | arith |".to_string();
    for terrain in terrains {
        header += &format!(" {0}x{0} |", terrain.samples[0]);
    }
    header += &format!("\n|---|---|{}", "---:|".repeat(terrains.len()));
    // One line per tracer: `cell` of its row at each size.
    let lines = |out: &mut W, cell: &dyn Fn(&RowReport, &RowReport) -> Option<String>| {
        for base in first.rows.iter().filter(|r| r.threads == 1) {
            let mut line = format!("| {} | {} |", base.method, base.arith);
            for terrain in terrains {
                let row = terrain
                    .rows
                    .iter()
                    .find(|r| r.method == base.method && r.arith == base.arith && r.threads == 1);
                let value = row.and_then(|r| cell(base, r));
                line += &format!(" {} |", value.as_deref().unwrap_or("-"));
            }
            if cell(base, base).is_some() {
                writeln!(out, "{line}")?;
            }
        }
        Ok(())
    };

    writeln!(
        out,
        "\ngrowth of time per primary ray with the terrain size (x the smallest)\n{header}"
    )?;
    let growth = |base: &RowReport, r: &RowReport| {
        Some(format!(
            "{:.2}",
            base.primary_mrays_per_s / r.primary_mrays_per_s
        ))
    };
    lines(out, &growth)?;
    let side = |t: &TerrainReport| (t.samples[0] as f64).log2();
    let mut line = "| log2 N | - |".to_string();
    for terrain in terrains {
        line += &format!(" {:.2} |", side(terrain) / side(first));
    }
    writeln!(out, "{line}")?;

    // What the time grows with: the finer terrain has more near misses per ray.
    writeln!(out, "\nqueries per primary ray: block / run / cell / triangle / wedge (one look-up per camera ray)\n{header}")?;
    let queries = |_: &RowReport, r: &RowReport| {
        r.queries_per_primary_ray.map(|q| {
            format!(
                "{:.1} / {:.1} / {:.1} / {:.1} / {:.2}",
                q.block, q.run, q.cell, q.triangle, q.wedge
            )
        })
    };
    lines(out, &queries)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(
        method: &str,
        threads: usize,
        camera: f64,
        shadow: Option<f64>,
        frame: f64,
    ) -> RowReport {
        RowReport {
            method: method.into(),
            arith: "f64".into(),
            threads,
            build_ms: 0.0,
            bytes_per_sample: 0.0,
            primary_rays: 100,
            shadow_rays: 50,
            primary_mrays_per_s: camera,
            shadow_mrays_per_s: shadow,
            frame_ms: frame / 2.0,
            frame_with_shadows_ms: frame,
            frame_x_f64: None,
            threads_x_one: None,
            queries_per_primary_ray: None,
        }
    }

    fn reference(name: &str) -> ReferenceBuild {
        ReferenceBuild {
            name: name.into(),
            build: Duration::ZERO,
            bytes: 0,
            differing: 0,
            hits: (0, 0),
        }
    }

    /// Each of heightray's rows against each reference's row at its thread count: rays per
    /// second ours over theirs, frame time ours over theirs, no shadow ratio where either
    /// shadow rate is missing.
    #[test]
    fn heightray_is_set_against_every_reference_at_the_same_thread_count() {
        let rows = [
            row("mipmap", 1, 3.0, Some(2.0), 100.0),
            row("mipmap", 2, 6.0, None, 50.0),
            row("embree triangles", 1, 2.0, Some(4.0), 125.0),
            row("embree triangles 8-wide", 1, 4.0, Some(1.0), 80.0),
            row("embree triangles", 2, 3.0, Some(4.0), 40.0),
        ];
        let references = [
            reference("embree triangles"),
            reference("embree triangles 8-wide"),
        ];
        let pairs = versus(&rows, &references, 0.0);
        let got: Vec<_> = pairs
            .iter()
            .map(|v| {
                (
                    v.threads,
                    v.reference.as_str(),
                    v.camera_x,
                    v.shadow_x,
                    v.frame_time_x,
                )
            })
            .collect();
        assert_eq!(
            got,
            [
                (1, "embree triangles", 1.5, Some(0.5), 0.8),
                (1, "embree triangles 8-wide", 0.75, Some(2.0), 1.25),
                (2, "embree triangles", 2.0, None, 1.25),
            ]
        );
        assert!(pairs.iter().all(|v| v.method == "mipmap"));
    }
}
