//! Long runs from Python: the GIL released while the cores roll, Ctrl-C answered.
//!
//! Python runs its signal handlers only on its main thread, and only when it holds the GIL,
//! so the caller's thread waits for the work on another thread and asks Python for pending
//! signals every few milliseconds. A `KeyboardInterrupt` sets the run's stop flag, which
//! every worker reads between rolls, and the call returns only once the work has stopped:
//! nothing keeps rolling behind the notebook's back.

use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// How often the waiting thread asks Python for signals: well under the second a Ctrl-C
/// may take to come back.
const POLL: Duration = Duration::from_millis(20);

/// Runs `work` with a stop flag on a thread of its own, the GIL released; a signal handler's
/// exception (Ctrl-C's `KeyboardInterrupt`) stops the work, waits for it and is returned.
pub(crate) fn run_interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&AtomicBool) -> T + Send,
) -> PyResult<T> {
    let stop = AtomicBool::new(false);
    std::thread::scope(|scope| {
        let worker = scope.spawn(|| work(&stop));
        loop {
            py.detach(|| {
                let waited = std::time::Instant::now();
                while !worker.is_finished() && waited.elapsed() < POLL {
                    std::thread::sleep(Duration::from_millis(2));
                }
            });
            if worker.is_finished() {
                return Ok(join(worker));
            }
            if let Err(interrupted) = py.check_signals() {
                stop.store(true, Ordering::Relaxed);
                py.detach(|| drop(join(worker)));
                return Err(interrupted);
            }
        }
    })
}

/// The worker's result; a panic in it is the caller's panic (pyo3 raises it as
/// `PanicException`).
fn join<T>(worker: std::thread::ScopedJoinHandle<'_, T>) -> T {
    worker
        .join()
        .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
}
