//! The render thread: it takes the newest job, renders it pass by pass on rayon's threads and
//! publishes each pass, so the window always has something to show and never waits.
//!
//! A job carries a generation number; submitting a new job bumps the shared counter, which the
//! running pass sees through `render_pass`'s `cancelled` check within one band of rows. Only
//! the refining passes are cancelled: the first, coarse one is always shown.

use crate::render::{Camera, Culling, Frame, Lighting, Renderer, Shader};
use crate::{Arith, Method, Terrain};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// What to render.
#[derive(Clone)]
pub struct RenderJob {
    pub terrain: Arc<Terrain>,
    pub camera: Camera,
    pub lighting: Lighting,
    pub method: Method,
    pub arith: Arith,
    /// Jobs of one view (the same camera, terrain and settings at any resolution) share it.
    pub view_id: u64,
}

/// A frame after some passes, as published to the window.
pub struct RenderedFrame {
    pub frame: Frame,
    pub generation: u64,
    /// The job it belongs to (the camera maps window pixels to the rays that were traced).
    pub job: RenderJob,
    /// Time from the job's start to the end of each pass done so far.
    pub pass_times: Vec<Duration>,
}

impl RenderedFrame {
    /// Time from the job's start to its latest pass.
    pub fn elapsed(&self) -> Duration {
        self.pass_times.last().copied().unwrap_or_default()
    }
}

struct Shared {
    /// The newest generation; a pass of any other one stops.
    generation: AtomicU64,
    quit: AtomicBool,
    pending: Mutex<Option<(u64, RenderJob)>>,
    wake: Condvar,
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
    pub fn start(notify: impl Fn() + Send + 'static) -> std::io::Result<RenderWorker> {
        let shared = Arc::new(Shared {
            generation: AtomicU64::new(0),
            quit: AtomicBool::new(false),
            pending: Mutex::new(None),
            wake: Condvar::new(),
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
        let mut pending = self
            .shared
            .pending
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        let generation = self.shared.generation.fetch_add(1, Ordering::SeqCst) + 1;
        *pending = Some((generation, job));
        self.shared.wake.notify_one();
        generation
    }

    /// Tells the worker the window has shown a frame of `generation`.
    pub fn presented(&self, generation: u64) {
        self.shared
            .presented
            .fetch_max(generation, Ordering::SeqCst);
        let _pending = self.shared.pending.lock();
        self.shared.wake.notify_one();
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
        self.shared.rendering.load(Ordering::SeqCst)
            || self
                .shared
                .pending
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .is_some()
    }
}

impl Drop for RenderWorker {
    fn drop(&mut self) {
        self.shared.quit.store(true, Ordering::SeqCst);
        // Bumping the generation cancels the pass in flight.
        self.shared.generation.fetch_add(1, Ordering::SeqCst);
        {
            let _pending = self.shared.pending.lock();
            self.shared.wake.notify_one();
        }
        if let Some(thread) = self.thread.take() {
            // A panicked render thread has nothing more to say at exit.
            let _ = thread.join();
        }
    }
}

fn render_loop(shared: &Shared, notify: &dyn Fn()) {
    while let Some((generation, job)) = next_job(shared) {
        shared.rendering.store(true, Ordering::SeqCst);
        render_job(shared, notify, generation, job);
        shared.rendering.store(false, Ordering::SeqCst);
    }
}

/// Waits for a job; None when the worker is stopping.
fn next_job(shared: &Shared) -> Option<(u64, RenderJob)> {
    let mut pending = shared
        .pending
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    loop {
        if shared.quit.load(Ordering::SeqCst) {
            return None;
        }
        if let Some(job) = pending.take() {
            return Some(job);
        }
        pending = shared
            .wake
            .wait(pending)
            .unwrap_or_else(PoisonError::into_inner);
    }
}

/// Waits (briefly) until the window has shown `generation`, or a newer job has come.
fn wait_until_presented(shared: &Shared, generation: u64) {
    const PATIENCE: Duration = Duration::from_millis(40);
    let deadline = Instant::now() + PATIENCE;
    let mut pending = shared
        .pending
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    while shared.presented.load(Ordering::SeqCst) < generation
        && pending.is_none()
        && !shared.quit.load(Ordering::SeqCst)
    {
        let now = Instant::now();
        if now >= deadline {
            return;
        }
        pending = shared
            .wake
            .wait_timeout(pending, deadline - now)
            .unwrap_or_else(PoisonError::into_inner)
            .0;
    }
}

/// Renders passes until the frame is complete or a newer job cancels it.
fn render_job(shared: &Shared, notify: &dyn Fn(), generation: u64, job: RenderJob) {
    let (width, height) = job.camera.size();
    let mut frame = Frame::new(width, height);
    let renderer = Renderer {
        shader: Shader {
            terrain: &job.terrain,
            lighting: job.lighting,
            method: job.method,
            culling: Culling::default(),
        },
        camera: job.camera,
        arith: job.arith,
    };
    let quitting = || shared.quit.load(Ordering::Relaxed);
    let superseded = || shared.generation.load(Ordering::Relaxed) != generation || quitting();
    let start = Instant::now();
    let mut pass_times = Vec::new();
    loop {
        // The coarse first pass always finishes (it is short): were it cancelled too, a
        // stream of camera moves could keep every job from ever showing a frame.
        let cancelled: &(dyn Fn() -> bool + Sync) = if pass_times.is_empty() {
            &quitting
        } else {
            &superseded
        };
        if !renderer.render_pass(&mut frame, cancelled) {
            return;
        }
        pass_times.push(start.elapsed());
        // The pass is handed over as it is and shown at once; the copy to refine further is
        // made after the window has been told, off the path from input to screen.
        let rendered = Arc::new(RenderedFrame {
            frame: std::mem::replace(&mut frame, Frame::new(0, 0)),
            generation,
            job: job.clone(),
            pass_times: pass_times.clone(),
        });
        *shared.latest.lock().unwrap_or_else(PoisonError::into_inner) = Some(Arc::clone(&rendered));
        notify();
        if rendered.frame.complete() {
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
        frame = rendered.frame.clone();
    }
}
