//! The render thread: it takes the newest job, renders it pass by pass on rayon's threads and
//! publishes each pass, so the window always has something to show and never waits.
//!
//! A job carries a generation number; submitting a new job bumps the shared counter, which the
//! running pass sees through `render_pass`'s `cancelled` check within one row. Only
//! the refining passes are cancelled: the first, coarse one is always shown (or, for a map
//! read from a tile store, the preview of it the first pass refines).

use super::mailbox::Mailbox;
use super::orbit::Orbit;
use super::store_view::{preview_renderer, store_pool};
use crate::render::Accumulation;
use crate::render::{Camera, Contours, Culling, Frame, Lighting, Renderer, Shader, PASS_BLOCKS};
use crate::{Arith, Method, Terrain};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// What to render.
#[derive(Clone)]
pub struct RenderJob {
    pub terrain: Arc<Terrain>,
    /// The orbit the camera was made from (for renders of the same view at other sizes).
    pub orbit: Orbit,
    pub camera: Camera,
    pub lighting: Lighting,
    pub method: Method,
    pub arith: Arith,
    /// Contour lines on the terrain, not yet seen by the camera.
    pub contours: Option<Contours>,
    /// Jobs of one view (the same camera, terrain and settings at any resolution) share it.
    pub view_id: u64,
}

impl RenderJob {
    /// A renderer of this job's view in arithmetic `arith`.
    pub fn renderer(&self, arith: Arith) -> Renderer<'_> {
        let camera = self.camera.in_grid(self.terrain.world_from_grid());
        let (lighting, method) = (self.lighting, self.method);
        Renderer {
            shader: Shader::new(&self.terrain, lighting, method, Culling::default())
                .with_contours(self.contours, &camera),
            camera,
            arith,
        }
    }
}

/// A frame after some passes, as published to the window.
pub struct RenderedFrame {
    pub frame: Frame,
    /// The mipmap level of the map's preview the frame shows where no pass has traced a
    /// pixel yet (see [`Preview`](crate::heightfield::Preview)), if it shows one.
    pub preview: Option<u32>,
    pub generation: u64,
    /// The job it belongs to (the camera maps window pixels to the rays that were traced).
    pub job: RenderJob,
    /// Time from the job's start to the end of each pass done so far.
    pub pass_times: Vec<Duration>,
    /// Samples per pixel added after the passes, and asked (0 of 0 with one sample).
    pub samples: (u32, u32),
    /// Pixels still taking samples (adaptive pixels stop early).
    pub sampling: usize,
}

impl RenderedFrame {
    /// Time from the job's start to its latest pass.
    pub fn elapsed(&self) -> Duration {
        self.pass_times.last().copied().unwrap_or_default()
    }

    /// Whether nothing more will be rendered for this job: every pass, and every round of
    /// samples per pixel.
    pub fn finished(&self) -> bool {
        self.preview.is_none()
            && self.frame.complete()
            && (self.samples.0 >= self.samples.1 || self.sampling == 0)
    }
}

struct Shared {
    /// The newest job; a pass of any other generation stops.
    jobs: Mailbox<RenderJob>,
    /// The terrain (by address) whose view's first pass was last traced, and the seconds it
    /// took a pixel: a map read from a tile store is shown from its preview only while first
    /// passes are slow (its pages on the disk).
    first_pass: Mutex<Option<(usize, f64)>>,
    latest: Mutex<Option<Arc<RenderedFrame>>>,
    rendering: AtomicBool,
    /// The newest generation the window has put on screen.
    presented: AtomicU64,
}

/// Owns the render thread; dropping it stops the thread.
pub struct RenderWorker {
    shared: Arc<Shared>,
    thread: Option<JoinHandle<()>>,
}

impl RenderWorker {
    /// Starts the thread; `notify` is called (from the thread) after each published pass.
    pub fn start(notify: impl Fn() + Send + Sync + 'static) -> std::io::Result<RenderWorker> {
        let shared = Arc::new(Shared {
            jobs: Mailbox::new(),
            first_pass: Mutex::new(None),
            latest: Mutex::new(None),
            rendering: AtomicBool::new(false),
            presented: AtomicU64::new(0),
        });
        let thread_shared = Arc::clone(&shared);
        let thread = std::thread::Builder::new()
            .name("heightray-render".into())
            .spawn(move || render_loop(&thread_shared, &notify))?;
        Ok(RenderWorker {
            shared,
            thread: Some(thread),
        })
    }

    /// Replaces whatever is being rendered with `job`; returns its generation.
    pub fn submit(&self, job: RenderJob) -> u64 {
        self.shared.jobs.post(job)
    }

    /// Tells the worker the window has shown a frame of `generation`.
    pub fn presented(&self, generation: u64) {
        self.shared
            .presented
            .fetch_max(generation, Ordering::SeqCst);
        self.shared.jobs.nudge();
    }

    /// Tells the worker the window has taken the newest frame and let go of older ones.
    pub fn taken(&self) {
        self.shared.jobs.nudge();
    }

    /// The newest published frame.
    pub fn latest(&self) -> Option<Arc<RenderedFrame>> {
        self.shared
            .latest
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone()
    }

    /// Whether a job is being rendered or waits to be.
    pub fn busy(&self) -> bool {
        self.shared.rendering.load(Ordering::SeqCst) || self.shared.jobs.has_waiting()
    }
}

impl Drop for RenderWorker {
    fn drop(&mut self) {
        // Closing also supersedes the pass in flight.
        self.shared.jobs.close();
        if let Some(thread) = self.thread.take() {
            // A panicked render thread has nothing more to say at exit.
            let _ = thread.join();
        }
    }
}

fn render_loop(shared: &Shared, notify: &(dyn Fn() + Sync)) {
    while let Some((generation, job)) = shared.jobs.take() {
        shared.rendering.store(true, Ordering::SeqCst);
        match store_pool(&job.terrain) {
            Some(pool) => pool.install(|| render_job(shared, notify, generation, job)),
            None => render_job(shared, notify, generation, job),
        }
        shared.rendering.store(false, Ordering::SeqCst);
    }
}

/// Whether `job`'s first pass, at the pace of the last one traced over its terrain (per
/// pixel: views while moving are smaller), takes so little that a preview would show the map
/// no sooner.
fn quick_first_pass(shared: &Shared, job: &RenderJob) -> bool {
    /// A first pass quicker than this many seconds shows the map sooner than a preview does.
    const PREVIEW_WORTH: f64 = 0.25;
    let terrain = Arc::as_ptr(&job.terrain) as usize;
    let last = *shared
        .first_pass
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    let pixels = first_pass_pixels(job.camera.size());
    last.is_some_and(|(of, pace)| of == terrain && pace * pixels < PREVIEW_WORTH)
}

/// The pixels the first pass of a `width x height` frame traces.
fn first_pass_pixels((width, height): (u32, u32)) -> f64 {
    let block = PASS_BLOCKS[0];
    f64::from(width.div_ceil(block)) * f64::from(height.div_ceil(block))
}

/// Waits (briefly) until the window has shown `generation`, or a newer job has come.
fn wait_until_presented(shared: &Shared, generation: u64) {
    const PATIENCE: Duration = Duration::from_millis(40);
    shared.jobs.wait_until(Instant::now() + PATIENCE, || {
        shared.presented.load(Ordering::SeqCst) >= generation
    });
}

/// Renders passes until the frame is complete or a newer job cancels it.
fn render_job(shared: &Shared, notify: &(dyn Fn() + Sync), generation: u64, job: RenderJob) {
    let (width, height) = job.camera.size();
    let mut frame = Frame::new(width, height);
    // The passes trace one ray per pixel; samples per pixel follow in rounds, one sample of
    // every pixel each, while the camera rests.
    let mut renderer = job.renderer(job.arith);
    let samples = job.lighting.effects.samples;
    renderer.shader.lighting.effects.samples = 1;
    let rounds = job.renderer(job.arith);
    // Running sums (88 bytes a pixel) only for samples to add: one sample keeps none.
    let mut sums = if samples > 1 {
        Accumulation::new(width, height, samples)
    } else {
        Accumulation::new(0, 0, 0)
    };
    let quitting = || shared.jobs.is_closed();
    let superseded = || shared.jobs.newest() != generation || quitting();
    let start = Instant::now();
    let mut pass_times = Vec::new();
    let mut spare: Option<Arc<RenderedFrame>> = None;
    // A map read from a tile store is first shown from its preview, made of the levels held
    // in memory: the real passes then wait on the disk behind a picture, and paint only the
    // pixels they trace over it.
    let mut coarse = job
        .terrain
        .preview()
        .filter(|_| !quick_first_pass(shared, &job));
    let mut preview = coarse.map(|coarse| coarse.level);
    loop {
        let pass_start = Instant::now();
        // The coarse first pass always finishes (it is short): were it cancelled too, a
        // stream of camera moves could keep every job from ever showing a frame.
        let cancelled: &(dyn Fn() -> bool + Sync) = if pass_times.is_empty() {
            &quitting
        } else {
            &superseded
        };
        let rendered = if let Some(coarse) = coarse.take() {
            let (lighting, method) = (job.lighting, job.method);
            preview_renderer(coarse, job.camera, lighting, method).render(&mut frame);
            // (No pass of the view itself is done, and none of its rays counted.)
            frame.passes_done = 0;
            frame.totals = Default::default();
            true
        } else if frame.complete() {
            rounds.accumulate(&mut sums, &mut frame, cancelled)
        } else if preview.is_some() {
            renderer.refine_pass(&mut frame, cancelled)
        } else {
            renderer.render_pass(&mut frame, cancelled)
        };
        if frame.complete() {
            preview = None;
        }
        if !rendered {
            return;
        }
        if frame.passes_done == 1 && pass_times.len() <= 1 {
            let terrain = Arc::as_ptr(&job.terrain) as usize;
            let pace = pass_start.elapsed().as_secs_f64() / first_pass_pixels((width, height));
            *shared
                .first_pass
                .lock()
                .unwrap_or_else(PoisonError::into_inner) = Some((terrain, pace));
        }
        pass_times.push(start.elapsed());
        // The pass is handed over as it is and shown at once; the copy to refine further is
        // made after the window has been told, off the path from input to screen.
        let taken = std::mem::replace(&mut frame, Frame::new(0, 0));
        let rendered = publish(
            shared,
            taken,
            preview,
            (generation, &job),
            &pass_times,
            &sums,
        );
        let complete = rendered.finished();
        if complete {
            // Done before the window hears of it: the window reports whether the worker is
            // busy when it shows the frame, and may draw nothing more after it (a report that
            // said busy would then stay so).
            shared.rendering.store(false, Ordering::SeqCst);
        }
        notify();
        if complete {
            return;
        }
        if pass_times.len() == 1 {
            // Leave the cores to the window until the coarse pass is on screen: refining
            // alongside would slow the very redraw that shows the input's effect.
            wait_until_presented(shared, generation);
        }
        if superseded() {
            return;
        }
        frame = copy_to_refine(shared, spare.take(), &rendered);
        spare = Some(rendered);
    }
}

/// Publishes `frame` of `job` (of `generation`) as the newest, with its passes' times and
/// its samples so far.
fn publish(
    shared: &Shared,
    frame: Frame,
    preview: Option<u32>,
    (generation, job): (u64, &RenderJob),
    pass_times: &[Duration],
    sums: &Accumulation,
) -> Arc<RenderedFrame> {
    let rendered = Arc::new(RenderedFrame {
        frame,
        preview,
        generation,
        job: job.clone(),
        pass_times: pass_times.to_vec(),
        samples: (sums.done, sums.total),
        sampling: sums.active,
    });
    *shared.latest.lock().unwrap_or_else(PoisonError::into_inner) = Some(Arc::clone(&rendered));
    rendered
}

/// The copy of `rendered` that the next pass refines, made in the buffers of `before` (the
/// pass published ahead of it) once the window has let go of that, which it does as it takes
/// `rendered` (briefly waited for): then two frames are alive, not three.
fn copy_to_refine(
    shared: &Shared,
    before: Option<Arc<RenderedFrame>>,
    rendered: &RenderedFrame,
) -> Frame {
    const PATIENCE: Duration = Duration::from_millis(40);
    if let Some(before) = &before {
        shared
            .jobs
            .wait_until(Instant::now() + PATIENCE, || Arc::strong_count(before) == 1);
    }
    match before.map(Arc::try_unwrap) {
        Some(Ok(mut old)) => {
            old.frame.clone_from(&rendered.frame);
            old.frame
        }
        _ => rendered.frame.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::landscape;
    use crate::render::{EffectsSection, ShadingSection, SunSection};
    use std::sync::mpsc;

    fn small_job() -> RenderJob {
        let terrain = Arc::new(Terrain::new(landscape(33, 1, 8.0).unwrap()));
        let orbit = Orbit::framing(&terrain);
        let lighting = Lighting::from_sections(
            &SunSection::default(),
            &EffectsSection::default(),
            &ShadingSection::default(),
        );
        RenderJob {
            terrain,
            orbit,
            camera: orbit.camera((40, 24)).unwrap(),
            lighting,
            method: Method::Mipmap,
            arith: Arith::F64,
            contours: None,
            view_id: 0,
        }
    }

    /// A worker held inside `notify` after each frame it publishes until `looked` is told:
    /// the test sees every published frame (not for ever: a failed assertion drops the worker,
    /// which waits for this).
    fn held_worker() -> (RenderWorker, mpsc::Receiver<()>, mpsc::Sender<()>) {
        let (published, heard) = mpsc::channel();
        let (looked, go_on) = mpsc::channel::<()>();
        let go_on = Mutex::new(go_on);
        let worker = RenderWorker::start(move || {
            let _ = published.send(());
            let _ = go_on
                .lock()
                .map(|go_on| go_on.recv_timeout(Duration::from_secs(20)));
        })
        .unwrap();
        (worker, heard, looked)
    }

    /// Each pass is refined in the buffers of the pass before the last (nothing here holds
    /// it): the last pass shows the image and counts a render in one go makes.
    #[test]
    fn passes_refined_in_reused_buffers_end_with_the_renderers_image() {
        let (worker, heard, looked) = held_worker();
        let job = small_job();
        let mut whole = Frame::new(40, 24);
        job.renderer(job.arith).render(&mut whole);
        worker.submit(job);
        let mut passes = 0;
        let last = loop {
            heard.recv_timeout(Duration::from_secs(10)).unwrap();
            passes += 1;
            let latest = worker.latest().unwrap();
            looked.send(()).unwrap();
            if latest.finished() {
                break latest;
            }
        };
        assert_eq!(passes, crate::render::PASS_BLOCKS.len());
        assert_eq!(last.frame.pixels, whole.pixels);
        assert_eq!(last.frame.stats, whole.stats);
        assert_eq!(last.frame.totals, whole.totals);
    }

    /// A map read from a tile store is shown from its preview first; the passes then paint
    /// only the pixels they trace over it, and the last shows the image a render in one go
    /// makes of the map itself.
    #[test]
    fn a_store_is_shown_from_its_preview_then_refined_to_the_renderers_image() {
        use crate::heightfield::{load, store, Heightfield};
        let dir = std::env::temp_dir().join(format!("preview-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("wide.hrt");
        let _ = std::fs::remove_file(&path);
        let hills = |i: usize, j: usize| {
            let (x, y) = (i as f64 / 300.0, j as f64 / 7.0);
            (2000.0 + 1500.0 * (x.sin() * y.cos())) as u16
        };
        let field = Heightfield::from_fn(4100, 40, 4000, 400.0, hills).unwrap();
        store::save(&field, &path).unwrap();
        let mut job = small_job();
        job.terrain = Arc::new(Terrain::new(load(&path, 400.0).unwrap()));
        job.orbit = Orbit::framing(&job.terrain);
        job.camera = job.orbit.camera((48, 32)).unwrap();
        let level = job.terrain.preview().map(|preview| preview.level);
        assert_eq!(level, Some(2), "4,099 cells in blocks of 4 fit in 2048");
        let mut whole = Frame::new(48, 32);
        job.renderer(job.arith).render(&mut whole);
        let (worker, heard, looked) = held_worker();
        worker.submit(job);
        let mut shown = Vec::new();
        let last = loop {
            heard.recv_timeout(Duration::from_secs(20)).unwrap();
            let latest = worker.latest().unwrap();
            shown.push((latest.preview, latest.frame.passes_done));
            looked.send(()).unwrap();
            if latest.finished() {
                break latest;
            }
        };
        let passes: Vec<_> = (0..=crate::render::PASS_BLOCKS.len())
            .map(|done| (level.filter(|_| done < 4), done))
            .collect();
        assert_eq!(shown, passes);
        assert_eq!(last.frame.pixels, whole.pixels);
        assert_eq!(last.frame.stats, whole.stats);
        assert_eq!(last.frame.totals, whole.totals);
        // Its first pass was quick: the same map's next view shows no preview.
        worker.submit(last.job.clone());
        heard.recv_timeout(Duration::from_secs(20)).unwrap();
        let next = worker.latest().unwrap();
        assert_eq!((next.preview, next.frame.passes_done), (None, 1));
        // (Without a sender left, the worker waits no more inside `notify`.)
        drop(looked);
        drop(worker);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// When the window hears of the complete frame, the worker already says it is idle: the
    /// window reports `busy` as it shows that frame and may draw nothing after it.
    #[test]
    fn a_complete_frame_is_published_with_the_worker_idle() {
        let (worker, heard, checked) = held_worker();
        worker.submit(small_job());
        let mut passes = 0;
        loop {
            heard.recv().unwrap();
            passes += 1;
            let complete = worker.latest().unwrap().frame.complete();
            // Asked while the worker waits inside `notify`.
            assert_eq!(worker.busy(), !complete, "after pass {passes}");
            checked.send(()).unwrap();
            if complete {
                break;
            }
        }
        assert_eq!(passes, crate::render::PASS_BLOCKS.len());
    }
}
