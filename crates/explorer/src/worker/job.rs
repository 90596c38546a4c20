//! One computation on a thread of its own with a cancel flag: the worker's batches, maps,
//! curves and exports all run this way, so cancelling and waiting are written once. Each
//! kind of job has one [`Runner`] (at most one job of that kind at a time, its progress
//! taken on every tick), and the simulator keeps what it asked for in an [`Order`]: the
//! runner stops any job whose id the order no longer waits for.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

pub(super) struct Job<T> {
    cancel: Arc<AtomicBool>,
    thread: JoinHandle<T>,
}

impl<T: Send + 'static> Job<T> {
    /// Starts `work` on a thread named `name`; `work` gets the flag [`Job::stop`] sets.
    pub(crate) fn spawn(
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
}

impl<T> Job<T> {
    pub(crate) fn is_finished(&self) -> bool {
        self.thread.is_finished()
    }

    /// Its result; `None` if it panicked.
    pub(crate) fn join(self) -> Option<T> {
        self.thread.join().ok()
    }

    /// Cancels it and waits for its thread to end. Every computation looks at the flag
    /// within a few thousand steps, so this takes milliseconds, not a roll.
    pub(crate) fn stop(self) {
        self.cancel.store(true, Ordering::Relaxed);
        let _ = self.thread.join();
    }
}

/// Where a job's thread leaves its progress for the worker's next tick.
pub(super) struct Post<P>(Arc<Mutex<P>>);

impl<P> Post<P> {
    /// Changes what waits for the worker (appends rolls, replaces the newest curve…).
    pub(crate) fn post(&self, change: impl FnOnce(&mut P)) {
        change(&mut self.0.lock().unwrap_or_else(|e| e.into_inner()));
    }
}

/// The one shape of the worker's jobs (batch, export, map, curve): started under the id
/// the simulator gave it, its progress taken on every tick, stopped or joined once. Only the
/// kind of progress (`P`) and of result (`T`) differ.
pub(super) struct Tracked<P, T> {
    pub(crate) id: u64,
    progress: Arc<Mutex<P>>,
    job: Job<T>,
}

impl<P: Default + Send + 'static, T: Send + 'static> Tracked<P, T> {
    /// Starts `work` on a thread named `name`; it gets the cancel flag and where to post.
    pub(crate) fn start(
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
    pub(crate) fn progress(&self) -> P {
        std::mem::take(&mut *self.progress.lock().unwrap_or_else(|e| e.into_inner()))
    }

    pub(crate) fn is_finished(&self) -> bool {
        self.job.is_finished()
    }

    /// Waits for its end: what was posted last, and its result (`None` if it panicked).
    pub(crate) fn finish(self) -> (P, Option<T>) {
        let result = self.job.join();
        let rest = std::mem::take(&mut *self.progress.lock().unwrap_or_else(|e| e.into_inner()));
        (rest, result)
    }
}

impl<P, T> Tracked<P, T> {
    /// Cancels it and waits for its thread (see [`Job::stop`]).
    pub(crate) fn stop(self) {
        self.job.stop();
    }
}

/// What a runner's job did since the last tick.
pub(super) enum Report<P, T> {
    /// Still running: what it posted since.
    Progress(u64, P),
    /// Ended: what it posted last, and its result (`None` if it panicked).
    Finished(u64, P, Option<T>),
}

/// The thread of one kind of job: at most one at a time.
pub(super) struct Runner<P, T> {
    /// The thread's name.
    name: &'static str,
    run: Option<Tracked<P, T>>,
}

impl<P: Default + Send + 'static, T: Send + 'static> Runner<P, T> {
    pub(crate) fn new(name: &'static str) -> Runner<P, T> {
        Runner { name, run: None }
    }

    pub(crate) fn running(&self) -> bool {
        self.run.is_some()
    }

    /// Stops the job unless it is the one `wanted` (the simulator's order moved on, or was
    /// cancelled).
    pub(crate) fn keep_only(&mut self, wanted: Option<u64>) {
        if self.run.as_ref().is_some_and(|r| Some(r.id) != wanted) {
            self.stop();
        }
    }

    /// Starts `work` under `id`, after stopping the job running, if any.
    pub(crate) fn start(
        &mut self,
        id: u64,
        work: impl FnOnce(&AtomicBool, &Post<P>) -> T + Send + 'static,
    ) -> std::io::Result<()> {
        self.stop();
        self.run = Some(Tracked::start(self.name, id, work)?);
        Ok(())
    }

    /// What the job did since the last call; `None` while none runs.
    pub(crate) fn poll(&mut self) -> Option<Report<P, T>> {
        let run = self.run.as_ref()?;
        if !run.is_finished() {
            return Some(Report::Progress(run.id, run.progress()));
        }
        let run = self.run.take().expect("checked above");
        let id = run.id;
        let (rest, result) = run.finish();
        Some(Report::Finished(id, rest, result))
    }
}

impl<P, T> Runner<P, T> {
    /// Cancels the job running, if any, and waits for its thread (see [`Job::stop`]).
    pub(crate) fn stop(&mut self) {
        if let Some(run) = self.run.take() {
            run.stop();
        }
    }
}

impl<P, T> Drop for Runner<P, T> {
    fn drop(&mut self) {
        self.stop();
    }
}

/// What the simulator has asked a runner for: the job it waits for (with what it shows of
/// it, `S`), and the request not yet taken. Ids are never reused, so a report of an older
/// job is recognised and dropped.
#[derive(Debug)]
pub(super) struct Order<S, R> {
    current: Option<(u64, S)>,
    request: Option<R>,
    started: u64,
}

impl<S, R> Default for Order<S, R> {
    fn default() -> Self {
        Order {
            current: None,
            request: None,
            started: 0,
        }
    }
}

impl<S, R> Order<S, R> {
    /// Orders a new job (replacing any other), shown as `state`; `request` gets its id.
    pub(crate) fn place(&mut self, state: S, request: impl FnOnce(u64) -> R) {
        let id = self.started;
        self.started += 1;
        self.current = Some((id, state));
        self.request = Some(request(id));
    }

    /// Nothing is waited for any more; what was shown of the job, if one was ordered.
    pub(crate) fn cancel(&mut self) -> Option<S> {
        self.request = None;
        self.current.take().map(|(_, s)| s)
    }

    /// The request, once, for the runner.
    pub(crate) fn take_request(&mut self) -> Option<R> {
        self.request.take()
    }

    /// The job waited for.
    pub(crate) fn id(&self) -> Option<u64> {
        self.current.as_ref().map(|(id, _)| *id)
    }

    pub(crate) fn state(&self) -> Option<&S> {
        self.current.as_ref().map(|(_, s)| s)
    }

    /// What is shown of job `id`, if it is the one waited for.
    pub(crate) fn state_of(&mut self, id: u64) -> Option<&mut S> {
        self.current.as_mut().filter(|(i, _)| *i == id).map(|(_, s)| s)
    }

    /// Job `id` has ended: what was shown of it, if it was the one waited for.
    pub(crate) fn finish(&mut self, id: u64) -> Option<S> {
        if self.id() == Some(id) {
            self.current.take().map(|(_, s)| s)
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn an_order_waits_for_its_newest_job_only() {
        let mut o: Order<u32, &str> = Order::default();
        o.place(1, |id| {
            assert_eq!(id, 0);
            "first"
        });
        o.place(2, |id| {
            assert_eq!(id, 1);
            "second"
        });
        assert_eq!(
            o.take_request(),
            Some("second"),
            "the newest request replaces the other"
        );
        assert_eq!(o.take_request(), None, "a request is taken once");
        assert!(o.state_of(0).is_none(), "reports of the replaced job are dropped");
        assert_eq!(o.finish(0), None);
        assert_eq!(o.state_of(1).copied(), Some(2));
        assert_eq!(o.finish(1), Some(2));
        assert_eq!(o.id(), None, "nothing is waited for after the end");
        o.place(3, |id| {
            assert_eq!(id, 2, "ids are never reused");
            "third"
        });
        assert_eq!(o.cancel(), Some(3));
        assert_eq!(o.take_request(), None, "a cancelled order starts nothing");
        assert_eq!(o.finish(2), None, "a cancelled job's end is not reported");
    }

    /// Polls until the job ends; what it posted, in order, and its result.
    fn run_out(r: &mut Runner<Vec<u32>, u32>) -> (u64, Vec<u32>, Option<u32>) {
        let mut seen = Vec::new();
        loop {
            match r.poll() {
                Some(Report::Progress(_, mut p)) => seen.append(&mut p),
                Some(Report::Finished(id, mut rest, result)) => {
                    seen.append(&mut rest);
                    return (id, seen, result);
                }
                None => panic!("no job runs"),
            }
            std::thread::sleep(Duration::from_millis(1));
        }
    }

    #[test]
    fn a_runner_stops_the_job_no_longer_wanted_and_reports_the_next_whole() {
        let mut r: Runner<Vec<u32>, u32> = Runner::new("dicesim-test-job");
        let ran_to_cancel = Arc::new(AtomicBool::new(false));
        let flag = ran_to_cancel.clone();
        r.start(7, move |cancel, post| {
            post.post(|p| p.push(1));
            while !cancel.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_millis(1));
            }
            flag.store(true, Ordering::Relaxed);
            0
        })
        .expect("a thread");
        r.keep_only(Some(7));
        assert!(r.running(), "the job waited for keeps running");
        r.keep_only(Some(8));
        assert!(!r.running() && r.poll().is_none(), "another order stops it");
        assert!(
            ran_to_cancel.load(Ordering::Relaxed),
            "stopping waited for its thread"
        );
        r.start(9, |_, post| {
            post.post(|p| p.push(2));
            post.post(|p| p.push(3));
            5
        })
        .expect("a thread");
        assert_eq!(run_out(&mut r), (9, vec![2, 3], Some(5)));
        assert!(!r.running());
        r.start(10, |_, _| panic!("a job that panics")).expect("a thread");
        assert_eq!(
            run_out(&mut r),
            (10, vec![], None),
            "a panic is an end without a result"
        );
    }
}
