//! Statistics of a frame: the query counters ([`crate::traverse::Counters`]) summed, per
//! primary ray and as hit/miss ratios, and a compact per-pixel record for heat maps.

use super::effects::{EffectStats, EffectTime};
use super::sample::Sample;
use crate::traverse::{Counters, HitMiss};
use derive_more::AddAssign;
use serde_json::{json, Value};

/// Queries one pixel's rays (primary and shadow) made, for heat maps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PixelStats {
    /// Block queries.
    pub blocks: u32,
    /// Run queries.
    pub runs: u32,
    /// Cell queries.
    pub cells: u32,
    /// Triangle tests.
    pub triangles: u32,
    /// Camera rays (samples) the pixel took.
    pub samples: u32,
}

impl PixelStats {
    /// The queries of a traced sample's rays, saturating at `u32::MAX`.
    pub fn of(sample: &Sample) -> PixelStats {
        let mut stats = PixelStats {
            samples: 1,
            ..PixelStats::default()
        };
        stats.add_queries(&sample.primary);
        stats.add_queries(&sample.secondary);
        for queries in sample.effects.queries_at_hit() {
            stats.add_queries(&queries);
        }
        stats
    }

    /// Adds a ray's queries, saturating at `u32::MAX`.
    #[inline(always)]
    pub fn add_queries(&mut self, counters: &Counters) {
        let add = |to: &mut u32, queries: HitMiss| {
            *to = to.saturating_add(queries.total().min(u64::from(u32::MAX)) as u32);
        };
        add(&mut self.blocks, counters.block);
        add(&mut self.runs, counters.run);
        add(&mut self.cells, counters.cell);
        add(&mut self.triangles, counters.triangle);
    }
}

// (By hand: a heat map's counts saturate rather than wrap.)
impl std::ops::AddAssign for PixelStats {
    fn add_assign(&mut self, rhs: PixelStats) {
        self.blocks = self.blocks.saturating_add(rhs.blocks);
        self.runs = self.runs.saturating_add(rhs.runs);
        self.cells = self.cells.saturating_add(rhs.cells);
        self.triangles = self.triangles.saturating_add(rhs.triangles);
        self.samples = self.samples.saturating_add(rhs.samples);
    }
}

/// Shadow rays not cast, by reason.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign)]
pub struct Skipped {
    /// The surface faced away from the sun.
    pub facing_away: u64,
    /// The sun climbed steeper than any slope.
    pub no_shadow_possible: u64,
    /// The shadow ray started above the terrain and rose.
    pub above_terrain: u64,
    /// Soft shadows: the whole cone towards the sun climbed above the terrain's bound.
    pub horizon_clear: u64,
}

impl Skipped {
    /// Points whose shadow the sun's rules settled whole, with no ray: every reason but
    /// facing away.
    pub fn settled(&self) -> u64 {
        self.horizon_clear + self.no_shadow_possible + self.above_terrain
    }
}

/// Totals of a frame (or of any set of pixels). Two frames' totals are equal when they
/// counted the same rays, however long those took.
#[derive(Clone, Copy, Debug, Default, AddAssign)]
pub struct FrameStats {
    /// Primary rays traced (one per pixel).
    pub primary_rays: u64,
    /// Primary rays that hit the surface.
    pub primary_hits: u64,
    /// Of those, the rays that hit the base (its walls or its floor).
    pub base_hits: u64,
    /// Shadow rays cast.
    pub shadow_rays: u64,
    /// Shadow rays that found the surface.
    pub shadowed: u64,
    /// Shadow rays left out, by reason.
    pub skipped: Skipped,
    /// The primary rays' queries.
    pub primary: Counters,
    /// The shadow rays' queries.
    pub shadow: Counters,
    /// Each effect's counters, and samples per pixel.
    pub effects: EffectStats,
    /// Pixels with a decision exact mode made again exactly after intervals left it unsettled
    /// (see [`Sample::redone`]).
    pub redone: u64,
    /// The thread time the frame and its effects took (measured, so not compared).
    pub time: EffectTime,
}

impl PartialEq for FrameStats {
    fn eq(&self, b: &FrameStats) -> bool {
        // (Destructured, so that a field added later is compared or left out on purpose.)
        let FrameStats {
            primary_rays,
            primary_hits,
            base_hits,
            shadow_rays,
            shadowed,
            skipped,
            primary,
            shadow,
            effects,
            redone,
            time: _,
        } = *self;
        (
            primary_rays,
            primary_hits,
            base_hits,
            shadow_rays,
            shadowed,
            redone,
        ) == (
            b.primary_rays,
            b.primary_hits,
            b.base_hits,
            b.shadow_rays,
            b.shadowed,
            b.redone,
        ) && (skipped, primary, shadow, effects) == (b.skipped, b.primary, b.shadow, b.effects)
    }
}

impl Eq for FrameStats {}

impl FrameStats {
    /// Counts one traced sample.
    pub fn add(&mut self, sample: &Sample) {
        sample.count_into(self);
    }

    /// Primary and shadow queries together.
    pub fn queries(&self) -> Counters {
        let mut all = self.primary;
        all += self.shadow;
        all
    }

    /// The frame's statistics as JSON: rays, hits, shadow rays left out, and the queries in all,
    /// of primary and of shadow rays (the caller adds size, threads, method, arith and times).
    pub fn to_json(&self) -> Value {
        let q = self.queries();
        json!({
            "primary_rays": self.primary_rays,
            "primary_hits": self.primary_hits,
            "base_hits": self.base_hits,
            "shadow_rays": self.shadow_rays,
            "shadowed": self.shadowed,
            "shadow_rays_skipped": {
                "facing_away": self.skipped.facing_away,
                "no_shadow_possible": self.skipped.no_shadow_possible,
                "above_terrain": self.skipped.above_terrain,
                "horizon_clear": self.skipped.horizon_clear,
            },
            "effects": self.effects.to_json(self.primary_rays),
            "thread_time_ms": self.time.to_json(),
            "queries": {"bbox": q.bbox, "block": q.block, "run": q.run, "cell": q.cell, "triangle": q.triangle, "wedge": q.wedge, "bound": q.bound},
            "primary_queries": self.primary,
            "shadow_queries": self.shadow,
            "exact_redone": self.redone,
        })
    }

    /// The paper's table shape: totals, queries per primary ray, hits/misses ratios.
    pub fn table(&self, label: &str, build_ms: f64, render_ms: f64) -> String {
        let q = self.queries();
        let per = |n: u64| n as f64 / self.primary_rays.max(1) as f64;
        let ratio = |h: HitMiss| format!("{}:{:.1}", 1, h.miss as f64 / h.hit.max(1) as f64);
        let mut out = String::new();
        out += "| scene | build ms | render ms | primary rays | shadow rays | bbox queries | block queries | run queries | cell queries | triangle queries |\n";
        out += "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        out += &format!(
            "| {label} | {build_ms:.1} | {render_ms:.1} | {} | {} | {} | {} | {} | {} | {} |\n",
            self.primary_rays,
            self.shadow_rays,
            q.bbox.total(),
            q.block.total(),
            q.run.total(),
            q.cell.total(),
            q.triangle.total()
        );
        out += &format!(
            "\nper primary ray: {:.2} bbox, {:.2} block, {:.2} run, {:.2} cell, {:.2} triangle queries; \
             hits:misses (E:N) bbox {}, block {}, run {}, cell {}, triangle {}\n",
            per(q.bbox.total()),
            per(q.block.total()),
            per(q.run.total()),
            per(q.cell.total()),
            per(q.triangle.total()),
            ratio(q.bbox),
            ratio(q.block),
            ratio(q.run),
            ratio(q.cell),
            ratio(q.triangle)
        );
        let misses = self.primary_rays.saturating_sub(self.primary_hits);
        out += &format!(
            "wedge look-ups (a camera ray's clearance): {} ({:.2} per primary ray), {} walked from their clearance, {} certain misses settled with no walk ({:.1}% of the misses)\n",
            q.wedge.total(),
            per(q.wedge.total()),
            q.wedge.hit,
            q.wedge.miss,
            100.0 * q.wedge.miss as f64 / misses.max(1) as f64
        );
        out += &format!(
            "shadow rays: {} cast, {} in shadow; skipped {} facing away, {} no shadow possible, {} above terrain\n",
            self.shadow_rays,
            self.shadowed,
            self.skipped.facing_away,
            self.skipped.no_shadow_possible,
            self.skipped.above_terrain
        );
        if self.base_hits > 0 {
            out += &format!(
                "base: {} primary hits on its walls or floor\n",
                self.base_hits
            );
        }
        for (label, counters) in self.effects.counted() {
            out += &format!("{label}: {}\n", counts_line(&counters));
        }
        out
    }
}

/// An effect's counters as a line, `name count` by name (the queries left out: the table's
/// queries are those of primary and shadow rays).
fn counts_line(counters: &Value) -> String {
    let Some(fields) = counters.as_object() else {
        return String::new();
    };
    let counts: Vec<String> = fields
        .iter()
        .filter(|(_, count)| count.is_number())
        .map(|(name, count)| format!("{} {count}", name.replace('_', " ")))
        .collect();
    counts.join(", ")
}
