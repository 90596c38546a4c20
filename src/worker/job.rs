//! One computation on a thread of its own with a cancel flag: the worker's batches, maps,
//! curves and exports all run this way, so cancelling and waiting are written once; those
//! that report progress to the worker's ticks share one runner shape too ([`Tracked`]).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

pub(super) struct Job<T> {
    cancel: Arc<AtomicBool>,
    thread: JoinHandle<T>,
}

impl<T: Send + 'static> Job<T> {
    /// Starts `work` on a thread named `name`; `work` gets the flag [`Job::stop`] sets.
    pub fn spawn(
        name: &str,
        work: impl FnOnce(&AtomicBool) -> T + Send + 'static,
    ) -> std::io::Result<Job<T>> {
        let cancel = Arc::new(AtomicBool::new(false));
        let flag = cancel.clone();
        let thread = std::thread::Builder::new()
            .name(name.to_string())
            .spawn(move || work(&flag))?;
        Ok(Job { cancel, thread })
    }

    pub fn is_finished(&self) -> bool {
        self.thread.is_finished()
    }

    /// Its result; `None` if it panicked.
    pub fn join(self) -> Option<T> {
        self.thread.join().ok()
    }

    /// Cancels it and waits for its thread to end. Every computation looks at the flag
    /// within a few thousand steps, so this takes milliseconds, not a roll.
    pub fn stop(self) {
        self.cancel.store(true, Ordering::Relaxed);
        let _ = self.thread.join();
    }
}

/// Where a job's thread leaves its progress for the worker's next tick.
pub(super) struct Post<P>(Arc<Mutex<P>>);

impl<P> Post<P> {
    /// Changes what waits for the worker (appends rolls, replaces the newest curve…).
    pub fn post(&self, change: impl FnOnce(&mut P)) {
        change(&mut self.0.lock().unwrap_or_else(|e| e.into_inner()));
    }
}

/// The one shape of the worker's jobs (batch, export, curve): started under the id the
/// engine gave it, its progress taken on every tick, stopped or joined once. Only the
/// kind of progress (`P`) and of result (`T`) differ.
pub(super) struct Tracked<P, T> {
    pub id: u64,
    progress: Arc<Mutex<P>>,
    job: Job<T>,
}

impl<P: Default + Send + 'static, T: Send + 'static> Tracked<P, T> {
    /// Starts `work` on a thread named `name`; it gets the cancel flag and where to post.
    pub fn start(
        name: &str,
        id: u64,
        work: impl FnOnce(&AtomicBool, &Post<P>) -> T + Send + 'static,
    ) -> std::io::Result<Tracked<P, T>> {
        let progress = Arc::new(Mutex::new(P::default()));
        let post = Post(progress.clone());
        let job = Job::spawn(name, move |cancel| work(cancel, &post))?;
        Ok(Tracked { id, progress, job })
    }

    /// What was posted since the last call.
    pub fn progress(&self) -> P {
        std::mem::take(&mut *self.progress.lock().unwrap_or_else(|e| e.into_inner()))
    }

    pub fn is_finished(&self) -> bool {
        self.job.is_finished()
    }

    /// Waits for its end: what was posted last, and its result (`None` if it panicked).
    pub fn finish(self) -> (P, Option<T>) {
        let result = self.job.join();
        let rest = std::mem::take(&mut *self.progress.lock().unwrap_or_else(|e| e.into_inner()));
        (rest, result)
    }

    /// Cancels it and waits for its thread (see [`Job::stop`]).
    pub fn stop(self) {
        self.job.stop();
    }
}
