//! Progressive, multi-threaded rendering: passes from one ray per 8x8 block down to one per
//! pixel, each pixel traced exactly once over all passes, in bands of 8 rows on rayon's
//! threads. A caller-supplied check lets a newer camera cancel the work between bands.

use super::camera::Camera;
use super::deep::{self, Painted, Sampled};
use super::effects::nanos_since;
use super::effects::pixel::FIRST_BATCH;
use super::frame::Frame;
use super::shade::Shader;
use super::stats::{FrameStats, PixelStats};
use super::tally::Counting;
use crate::arith::{with_numbers, Arith, Numbers, WithNumbers};
use crate::geometry::Ray;
use crate::traverse::{clear_packet, Clearance, Wedges, LANES};
use rayon::prelude::*;
use std::ops::Range;
use std::time::Instant;

/// Block size of each pass: pass `k` traces the pixels on the `PASS_BLOCKS[k]` lattice that no
/// coarser pass traced, and paints each as a block of that size.
pub const PASS_BLOCKS: [u32; 4] = [8, 4, 2, 1];

/// Rows per unit of parallel work (a multiple of the coarsest block, so blocks never straddle).
const BAND: u32 = 8;

/// Columns per tile: a band is traced tile by tile.
const TILE: u32 = 16;

/// The columns of a pass's pixels whose rays are walked in packets, row by row.
const PACKET_COLUMNS: usize = 4;

impl Frame {
    /// Whether every pass has been rendered.
    pub fn complete(&self) -> bool {
        self.passes_done == PASS_BLOCKS.len()
    }
}

/// Renders a camera's view with a shader in one arithmetic.
pub struct Renderer<'a> {
    /// The terrain, lighting and method a pixel is traced and shaded with.
    pub shader: Shader<'a>,
    /// The camera whose rays the pixels are.
    pub camera: Camera,
    /// The arithmetic the rays are traced in.
    pub arith: Arith,
}

impl Renderer<'_> {
    /// Renders all remaining passes (on the current rayon pool). Nobody sees the frame between
    /// passes, so each band runs all of them in one job: no thread waits at the end of a pass
    /// for the other's last band. Each pixel is painted alone: a coarse pass's blocks would not
    /// be seen, and painting them would cost a share of every frame.
    pub fn render(&self, frame: &mut Frame) {
        if self.adaptive() {
            return self.render_in_rounds(frame);
        }
        let remaining = frame.passes_done..PASS_BLOCKS.len();
        self.passes(frame, remaining, &|| false, Paint::Pixels, Walking::Singly);
    }

    /// [`Renderer::render`] with neighbouring camera rays walked down the mipmap in packets
    /// ([`clear_packet`]) where the method is hierarchical and the arithmetic is `f64`: the same
    /// image. (Not the default: on the built-in views the packets' node tests cost more than
    /// the walks they shorten save.)
    pub fn render_in_packets(&self, frame: &mut Frame) {
        if self.adaptive() {
            return self.render_in_rounds(frame);
        }
        let remaining = frame.passes_done..PASS_BLOCKS.len();
        self.passes(frame, remaining, &|| false, Paint::Pixels, Walking::Packets);
    }

    /// [`Renderer::render`], calling `tick` before each tile of each pass (each row of each
    /// batch with adaptive samples; [`Renderer::ticks`] of them in all, or fewer where adaptive
    /// pixels stop early): for progress shown while a long frame renders. The same image.
    pub fn render_watched(&self, frame: &mut Frame, tick: &(dyn Fn() + Sync)) {
        let ticked = || {
            tick();
            false
        };
        if self.adaptive() {
            self.render_cancellable(frame, &ticked);
            return;
        }
        let remaining = frame.passes_done..PASS_BLOCKS.len();
        self.passes(frame, remaining, &ticked, Paint::Pixels, Walking::Singly);
    }

    /// How many times [`Renderer::render_watched`] ticks for `frame` at most.
    pub fn ticks(&self, frame: &Frame) -> u64 {
        let (w, h) = (u64::from(frame.width), u64::from(frame.height));
        if self.adaptive() {
            let batches = self.shader.lighting.effects.samples.div_ceil(FIRST_BATCH);
            return h * u64::from(batches);
        }
        let remaining = (PASS_BLOCKS.len() - frame.passes_done) as u64;
        h.div_ceil(u64::from(BAND)) * w.div_ceil(u64::from(TILE)) * remaining
    }

    /// Whether pixels take adaptive samples: they are then traced in rounds over the whole
    /// frame, each settled by its neighbours' estimates.
    fn adaptive(&self) -> bool {
        let effects = &self.shader.lighting.effects;
        effects.adaptive && effects.samples > 1
    }

    /// Renders the next pass, painting each traced pixel's block of the pass, so the frame can
    /// be shown as it is. Returns false when `cancelled` turned true (asked before each tile):
    /// the pass is then partly painted, and the frame is to be dropped.
    pub fn render_pass(&self, frame: &mut Frame, cancelled: &(dyn Fn() -> bool + Sync)) -> bool {
        let next = frame.passes_done..(frame.passes_done + 1).min(PASS_BLOCKS.len());
        self.passes(frame, next, cancelled, Paint::Blocks, Walking::Singly)
    }

    /// [`Renderer::render_pass`] painting only the pixels it traces: what the frame shows at
    /// the others (a preview of the view) stays until their own pass traces them.
    pub fn refine_pass(&self, frame: &mut Frame, cancelled: &(dyn Fn() -> bool + Sync)) -> bool {
        let next = frame.passes_done..(frame.passes_done + 1).min(PASS_BLOCKS.len());
        self.passes(frame, next, cancelled, Paint::Pixels, Walking::Singly)
    }

    /// Renders the passes `passes`, band by band; see [`Renderer::render_pass`]. The camera
    /// rays start from their clearance in the camera's [`Wedges`] (made for these passes, each
    /// wedge when a ray first asks).
    fn passes(
        &self,
        frame: &mut Frame,
        passes: Range<usize>,
        cancelled: &(dyn Fn() -> bool + Sync),
        paint: Paint,
        walking: Walking,
    ) -> bool {
        let width = frame.width as usize;
        let rows = BAND as usize * width;
        let per_sample = self.shader.per_sample();
        let wedges = self.wedges();
        let words = deep::chunks(&mut frame.words, rows, frame.pixels.len());
        let bands: Vec<Option<FrameStats>> = frame
            .pixels
            .par_chunks_mut(rows)
            .zip(frame.stats.par_chunks_mut(rows))
            .zip(words)
            .enumerate()
            // Every band a job of its own that an idle thread can take: rayon's adaptive
            // split leaves runs of bands to one thread, and where the costly rays gather in
            // a few bands (the horizon, seen with the run walk over a large map) the other
            // thread then waits for seconds.
            .with_max_len(1)
            .map(|(band, ((pixels, stats), words))| {
                let mut out = BandOut {
                    pixels,
                    words,
                    stats,
                    y0: band as u32 * BAND,
                    width: frame.width,
                    height: frame.height,
                    paint,
                    walking,
                };
                let band = Band {
                    renderer: self,
                    wedges: wedges.as_ref(),
                    shader: &per_sample,
                    out: &mut out,
                    passes: passes.clone(),
                    cancelled,
                };
                let start = Instant::now();
                let totals = with_numbers(self.arith, band).0;
                totals.map(|mut totals| {
                    totals.time.traced += nanos_since(start);
                    totals
                })
            })
            .collect();
        if bands.iter().any(Option::is_none) {
            return false;
        }
        for totals in bands.into_iter().flatten() {
            frame.totals += totals;
        }
        frame.passes_done = passes.end;
        true
    }

    /// The wedges of the camera's rays (see [`Shader::wedges`]).
    fn wedges(&self) -> Option<Wedges<'_>> {
        self.shader.wedges(self.camera.eye(), self.arith)
    }

    /// Traces the pixels of the passes `passes` in one band and paints them; `None` if
    /// cancelled. The band is traced tile by tile, each tile's passes one after another: the
    /// terrain its rays cross is still in the caches for the next pass. Each camera ray starts
    /// where its wedge's profile clears it ([`Wedges::clearance`]).
    fn band<P: Sampled>(
        &self,
        wedges: Option<&Wedges<'_>>,
        out: &mut BandOut<'_>,
        passes: Range<usize>,
        sample: impl Fn(&Ray, Option<Clearance>, &mut Counting<'_>) -> P,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> Option<FrameStats> {
        let y_end = (out.y0 + BAND).min(out.height);
        // Each pass with its block size and the band's rows it traces.
        let passes: Vec<(usize, u32, Vec<u32>)> = PASS_BLOCKS
            .iter()
            .enumerate()
            .take(passes.end)
            .skip(passes.start)
            .map(|(pass, &block)| {
                let rows = (out.y0..y_end).filter(|y| y % block == 0).collect();
                (pass, block, rows)
            })
            .collect();
        let mut tiles = Tiles {
            renderer: self,
            wedges,
            out,
            sample,
            totals: FrameStats::default(),
        };
        for x0 in (0..tiles.out.width).step_by(TILE as usize) {
            let x_end = (x0 + TILE).min(tiles.out.width);
            for (pass, block, rows) in &passes {
                // Asked for every tile: a tile of slow rays (small rational bounds) takes long
                // enough.
                if cancelled() {
                    return None;
                }
                let columns: Vec<u32> = (x0..x_end).step_by(*block as usize).collect();
                tiles.trace(*pass, *block, &columns, rows);
            }
        }
        Some(tiles.totals)
    }
}

/// One band's passes, traced with the numbers of the renderer's arithmetic.
struct Band<'r, 'o, 'b, 'c> {
    renderer: &'r Renderer<'r>,
    wedges: Option<&'r Wedges<'r>>,
    /// The shader of each sample (see [`pixel::per_sample`]).
    shader: &'r Shader<'r>,
    out: &'o mut BandOut<'b>,
    passes: Range<usize>,
    cancelled: &'c (dyn Fn() -> bool + Sync),
}

impl WithNumbers for Band<'_, '_, '_, '_> {
    type Output = Option<FrameStats>;
    fn with<N: Numbers>(self) -> Self::Output {
        let shader = self.shader;
        let (renderer, wedges, passes) = (self.renderer, self.wedges, self.passes);
        if self.out.words.is_some() {
            // Linear colours, which give the words as well as the bytes.
            let sample =
                |r: &Ray, c, counting: &mut Counting<'_>| shader.linear_sample::<N>(r, c, counting);
            return renderer.band(wedges, self.out, passes, sample, self.cancelled);
        }
        let sample = |r: &Ray, c, counting: &mut Counting<'_>| shader.sample::<N>(r, c, counting);
        renderer.band(wedges, self.out, passes, sample, self.cancelled)
    }
}

/// Traces the pixels of a band tile by tile.
struct Tiles<'r, 'o, 'b, F> {
    renderer: &'r Renderer<'r>,
    wedges: Option<&'r Wedges<'r>>,
    out: &'o mut BandOut<'b>,
    sample: F,
    totals: FrameStats,
}

impl<P: Sampled, F: Fn(&Ray, Option<Clearance>, &mut Counting<'_>) -> P> Tiles<'_, '_, '_, F> {
    /// Whether pixels take several samples (each pixel's rays then traced together).
    fn sub_pixel(&self) -> bool {
        self.renderer.shader.lighting.effects.samples > 1
    }

    /// Traces pixel `(x, y)` with several samples (see [`pixel::shade`]) and paints it.
    fn trace_samples(&mut self, x: u32, y: u32, block: u32) {
        let (renderer, sample) = (self.renderer, &self.sample);
        let mut counting = Counting::new(&mut self.totals);
        let effects = &renderer.shader.lighting.effects;
        let taken = effects.samples;
        let wedges = self.wedges;
        let (colour, later) = P::shade(&renderer.camera, (x, y), effects, |ray| {
            let clearance = clearance(wedges, ray, counting.frame);
            sample(ray, clearance, &mut counting)
        });
        let stats = PixelStats {
            samples: taken,
            ..counting.pixel
        };
        self.totals.effects.add_pixel(taken);
        self.totals.time.later_samples += later;
        self.out.paint(x, y, block, colour, stats);
    }

    /// Traces the pixels `columns x rows` that pass `pass` (of blocks `block`) traces and no
    /// earlier pass did, and paints them: where asked (and in `f64`), in packets of neighbours.
    fn trace(&mut self, pass: usize, block: u32, columns: &[u32], rows: &[u32]) {
        let traced_before =
            |x: u32, y: u32| pass > 0 && x.is_multiple_of(2 * block) && y.is_multiple_of(2 * block);
        let packs = self.out.walking == Walking::Packets
            && self.renderer.arith == Arith::F64
            && self.renderer.shader.method.is_hierarchical()
            && !self.sub_pixel();
        if packs {
            // Packets of neighbours: the pixels of a few columns, row by row.
            for columns in columns.chunks(PACKET_COLUMNS) {
                let pixels = rows
                    .iter()
                    .flat_map(|&y| columns.iter().map(move |&x| (x, y)));
                let pixels: Vec<(u32, u32)> =
                    pixels.filter(|&(x, y)| !traced_before(x, y)).collect();
                for packet in pixels.chunks(LANES) {
                    self.trace_packet(packet, block);
                }
            }
            return;
        }
        for &y in rows {
            for &x in columns {
                if traced_before(x, y) {
                    continue;
                }
                if self.sub_pixel() {
                    self.trace_samples(x, y, block);
                    continue;
                }
                let ray = self.renderer.camera.ray(x, y);
                let clearance = clearance(self.wedges, &ray, &mut self.totals);
                self.trace_pixel((x, y), &ray, block, clearance);
            }
        }
    }

    /// Traces the pixels of one packet (at most [`LANES`]), walked together from the least of
    /// their clearances, each then from the later of its own and the packet's.
    fn trace_packet(&mut self, pixels: &[(u32, u32)], block: u32) {
        let camera = &self.renderer.camera;
        let rays: Vec<Ray> = pixels.iter().map(|&(x, y)| camera.ray(x, y)).collect();
        let own: Vec<Option<Clearance>> = rays
            .iter()
            .map(|ray| clearance(self.wedges, ray, &mut self.totals))
            .collect();
        let least = own.iter().try_fold(None, |least: Option<Clearance>, c| {
            let c = (*c)?;
            Some(Some(least.filter(|l| l.t <= c.t).unwrap_or(c)))
        });
        let cleared = clear_packet(self.renderer.shader.terrain, &rays, least.flatten());
        self.totals.primary.block += cleared.tests;
        for (l, (&pixel, ray)) in pixels.iter().zip(&rays).enumerate() {
            let later = match (own[l], cleared.lanes[l]) {
                (Some(a), Some(b)) => Some(if a.t >= b.t { a } else { b }),
                (a, b) => a.or(b),
            };
            self.trace_pixel(pixel, ray, block, later);
        }
    }

    /// Traces pixel `(x, y)`'s ray from `clearance` and paints it.
    fn trace_pixel(
        &mut self,
        (x, y): (u32, u32),
        ray: &Ray,
        block: u32,
        clearance: Option<Clearance>,
    ) {
        let mut counting = Counting::new(&mut self.totals);
        let colour = (self.sample)(ray, clearance, &mut counting);
        let stats = PixelStats {
            samples: 1,
            ..counting.pixel
        };
        self.totals.effects.add_pixel(1);
        self.out.paint(x, y, block, colour, stats);
    }
}

/// A camera ray's clearance in `wedges`, its look-up counted with the frame's primary
/// queries.
pub(super) fn clearance(
    wedges: Option<&Wedges<'_>>,
    ray: &Ray,
    totals: &mut FrameStats,
) -> Option<Clearance> {
    let (clearance, asked) = wedges?.clearance(ray.origin(), ray.dir());
    totals.primary.wedge += asked;
    clearance
}

/// What a traced pixel paints.
#[derive(Clone, Copy)]
enum Paint {
    /// Its block of the pass, for a frame shown between passes.
    Blocks,
    /// Itself only.
    Pixels,
}

/// How camera rays are walked.
#[derive(Clone, Copy, PartialEq)]
enum Walking {
    /// In packets of neighbours where they can be ([`clear_packet`]).
    Packets,
    /// Each on its own.
    Singly,
}

/// The rows of one band of the frame.
struct BandOut<'a> {
    pixels: &'a mut [u32],
    /// The pixels' 16-bit words, where the frame keeps them.
    words: Option<&'a mut [[u16; 3]]>,
    stats: &'a mut [PixelStats],
    y0: u32,
    width: u32,
    height: u32,
    paint: Paint,
    walking: Walking,
}

impl BandOut<'_> {
    /// Paints the pixel `(x, y)` traced by a pass of blocks `block`: with [`Paint::Blocks`]
    /// its whole block, clipped to the band; its words too where the band keeps them.
    #[inline(always)]
    fn paint(&mut self, x: u32, y: u32, block: u32, colour: impl Painted, stats: PixelStats) {
        let row = y - self.y0;
        let block = match self.paint {
            Paint::Blocks => block,
            Paint::Pixels => 1,
        };
        let (rgb, words) = (colour.rgb(), colour.words());
        // (One pixel, as most are painted, written directly: the loop's bounds cost more than
        // the pixel.)
        if block == 1 {
            let at = (row * self.width + x) as usize;
            (self.pixels[at], self.stats[at]) = (rgb, stats);
            if let (Some(out), Some(words)) = (self.words.as_deref_mut(), words) {
                out[at] = words;
            }
            return;
        }
        let rows = row..(row + block).min(self.pixels.len() as u32 / self.width);
        for row in rows {
            let start = (row * self.width + x) as usize;
            let end = start + (block.min(self.width - x)) as usize;
            self.pixels[start..end].fill(rgb);
            self.stats[start..end].fill(stats);
            if let (Some(out), Some(words)) = (self.words.as_deref_mut(), words) {
                out[start..end].fill(words);
            }
        }
    }
}
