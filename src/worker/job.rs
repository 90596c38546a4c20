//! One computation on a thread of its own with a cancel flag: the worker's batches, maps
//! and exports all run this way, so cancelling and waiting are written once.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
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
