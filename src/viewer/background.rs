//! A thread for long work the window asks for on demand (measuring every arithmetic, the
//! exact render to compare with): it runs the newest job on a rayon pool of its own, so the
//! view's render passes on the global pool never queue behind it, and it publishes progress
//! and partial results as it goes. Posting a job or cancelling supersedes the job in flight,
//! which sees it through [`Step::cancelled`].

use super::mailbox::Mailbox;
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;

/// What a job has to say so far.
pub struct Report<R> {
    /// The job's generation (as [`Background::submit`] returned it).
    pub generation: u64,
    /// Share of the work done, 0 to 1.
    pub fraction: f32,
    /// What it is doing now, for people.
    pub status: String,
    /// The result so far (a job may publish partial results).
    pub result: Option<R>,
    pub finished: bool,
}

struct Shared<J, R> {
    jobs: Mailbox<J>,
    latest: Mutex<Option<Arc<Report<R>>>>,
    notify: Box<dyn Fn() + Send + Sync>,
}

/// What a running job sees: whether it has been superseded, and where to report.
pub struct Step<'a, J, R> {
    shared: &'a Shared<J, R>,
    generation: u64,
}

impl<J: Send, R: Send + Sync> Step<'_, J, R> {
    /// Whether a newer job, a cancel or the window's exit has superseded this one.
    pub fn cancelled(&self) -> bool {
        self.shared.jobs.newest() != self.generation
    }

    /// Publishes progress (and the result so far) and wakes the window.
    pub fn report(&self, fraction: f32, status: String, result: Option<R>, finished: bool) {
        // A superseded job's news would only overwrite its successor's.
        if self.cancelled() {
            return;
        }
        let report = Report {
            generation: self.generation,
            fraction,
            status,
            result,
            finished,
        };
        *self
            .shared
            .latest
            .lock()
            .unwrap_or_else(PoisonError::into_inner) = Some(Arc::new(report));
        (self.shared.notify)();
    }
}

/// Owns the thread; dropping it cancels the job in flight and stops the thread.
pub struct Background<J, R> {
    shared: Arc<Shared<J, R>>,
    thread: Option<JoinHandle<()>>,
}

impl<J: Send + 'static, R: Send + Sync + 'static> Background<J, R> {
    /// Starts a thread named `name` that runs jobs with `run` on `threads` threads; `notify`
    /// is called (from the thread) after each report.
    pub fn start(
        name: &str,
        threads: usize,
        run: fn(J, &Step<'_, J, R>),
        notify: impl Fn() + Send + Sync + 'static,
    ) -> std::io::Result<Self> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.max(1))
            .thread_name({
                let name = name.to_owned();
                move |k| format!("{name}-{k}")
            })
            .build()
            .map_err(std::io::Error::other)?;
        let shared = Arc::new(Shared {
            jobs: Mailbox::new(),
            latest: Mutex::new(None),
            notify: Box::new(notify),
        });
        let thread_shared = Arc::clone(&shared);
        let thread = std::thread::Builder::new()
            .name(name.to_owned())
            .spawn(move || {
                while let Some((generation, job)) = thread_shared.jobs.take() {
                    let step = Step {
                        shared: &thread_shared,
                        generation,
                    };
                    pool.install(|| run(job, &step));
                }
            })?;
        Ok(Background {
            shared,
            thread: Some(thread),
        })
    }

    /// Replaces whatever runs or waits with `job`; returns its generation.
    pub fn submit(&self, job: J) -> u64 {
        self.shared.jobs.post(job)
    }

    /// Stops the job in flight (within one band of rows) and drops any waiting one.
    pub fn cancel(&self) {
        self.shared.jobs.cancel();
    }

    /// The newest report of job `generation`, if it has made one.
    pub fn report(&self, generation: u64) -> Option<Arc<Report<R>>> {
        self.shared
            .latest
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone()
            .filter(|r| r.generation == generation)
    }
}

impl<J, R> Drop for Background<J, R> {
    fn drop(&mut self) {
        self.shared.jobs.close();
        if let Some(thread) = self.thread.take() {
            // A panicked job has nothing more to say at exit.
            let _ = thread.join();
        }
    }
}
