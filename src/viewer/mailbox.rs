//! "Newest wins": a one-slot mailbox between the window and a background thread. Posting
//! replaces whatever waits and bumps a generation, which work in flight checks to see that it
//! has been superseded. The render worker and the loader both use it.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Condvar, Mutex, MutexGuard, PoisonError};
use std::time::Instant;

pub struct Mailbox<T> {
    /// The newest generation posted (or bumped by closing).
    generation: AtomicU64,
    closed: AtomicBool,
    waiting: Mutex<Option<(u64, T)>>,
    wake: Condvar,
}

impl<T> Mailbox<T> {
    pub fn new() -> Self {
        Mailbox {
            generation: AtomicU64::new(0),
            closed: AtomicBool::new(false),
            waiting: Mutex::new(None),
            wake: Condvar::new(),
        }
    }

    fn lock(&self) -> MutexGuard<'_, Option<(u64, T)>> {
        self.waiting.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Replaces what waits with `item`; returns its generation.
    pub fn post(&self, item: T) -> u64 {
        let mut waiting = self.lock();
        let generation = self.generation.fetch_add(1, Ordering::SeqCst) + 1;
        *waiting = Some((generation, item));
        self.wake.notify_one();
        generation
    }

    /// Waits for the next item; `None` once the mailbox is closed.
    pub fn take(&self) -> Option<(u64, T)> {
        let mut waiting = self.lock();
        loop {
            if self.is_closed() {
                return None;
            }
            if let Some(item) = waiting.take() {
                return Some(item);
            }
            waiting = self
                .wake
                .wait(waiting)
                .unwrap_or_else(PoisonError::into_inner);
        }
    }

    /// Waits until `done()`, an item waits, the mailbox closes, or `deadline` passes.
    pub fn wait_until(&self, deadline: Instant, done: impl Fn() -> bool) {
        let mut waiting = self.lock();
        while !done() && waiting.is_none() && !self.is_closed() {
            let now = Instant::now();
            if now >= deadline {
                return;
            }
            waiting = self
                .wake
                .wait_timeout(waiting, deadline - now)
                .unwrap_or_else(PoisonError::into_inner)
                .0;
        }
    }

    /// Wakes the thread waiting in [`Mailbox::wait_until`] to look at its condition again.
    pub fn nudge(&self) {
        let _waiting = self.lock();
        self.wake.notify_one();
    }

    /// The newest generation: work of any other one has been superseded.
    pub fn newest(&self) -> u64 {
        self.generation.load(Ordering::SeqCst)
    }

    /// Whether an item waits to be taken.
    pub fn has_waiting(&self) -> bool {
        self.lock().is_some()
    }

    /// Drops what waits and supersedes the work in flight, leaving the mailbox open.
    pub fn cancel(&self) {
        let mut waiting = self.lock();
        self.generation.fetch_add(1, Ordering::SeqCst);
        *waiting = None;
    }

    /// Closes the mailbox: `take` returns `None`, and work in flight is superseded.
    pub fn close(&self) {
        self.closed.store(true, Ordering::SeqCst);
        self.generation.fetch_add(1, Ordering::SeqCst);
        self.nudge();
    }

    pub fn is_closed(&self) -> bool {
        self.closed.load(Ordering::SeqCst)
    }
}
