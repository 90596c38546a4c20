//! The simulation thread: commands in, snapshots out.
//!
//! The worker owns the physics. It paces simulated time against wall time at the requested
//! playback speed, runs batches between commands, and blocks on its command channel while
//! nothing moves, so a paused explorer costs no CPU. It never touches the terminal.
//!
//! Its parts build on each other in one direction: the messages (`protocol`), the twin die
//! and the live roll over them, the [`Simulator`] (the state machine the commands drive)
//! over those, and this file, which runs the simulator on its thread with its jobs.

pub(crate) mod curve;
mod export_jobs;
mod job;
mod live;
pub(crate) mod map_jobs;
mod pacer;
#[cfg(test)]
mod param_twin_tests;
mod play_on;
mod protocol;
mod simulator;
mod timeline;
mod twin_die;

pub use curve::{CURVE_STARTS, CurveSetup, CurveState, CurveUpdate};
pub use dicesim_setup::preset::Speed;
pub use map_jobs::{MapAxis, MapRequest, MapUpdate};
pub(crate) use protocol::{
    BatchProgress, DieState, EnergySample, ExportStatus, MapExport, OutcomeTable, RollKind, SeparationSample,
    TimelineSnapshot, TwinSnapshot,
};
pub use protocol::{Command, Notice, Phase, RollEvent, Snapshot};
pub use simulator::Simulator;

use dicesim_experiment::{RollRecord, Rolls, run_batch};
use job::{Post, Report, Runner};
use map_jobs::MapSink;
use pacer::{Clock, TICK, WallClock};
use simulator::BatchRequest;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, channel};
use std::thread::JoinHandle;

/// The running worker thread; dropping it stops the thread.
pub struct Worker {
    commands: Sender<Command>,
    thread: Option<JoinHandle<()>>,
}

impl Worker {
    /// Starts the thread. Every snapshot goes to `out` (converted, so the UI can merge it
    /// with its input events in one channel); the first is sent at once.
    pub fn spawn<T: From<Snapshot> + Send + 'static>(simulator: Simulator, out: Sender<T>) -> Worker {
        Worker::spawn_with_maps(simulator, out, |_: MapUpdate| true)
    }

    /// Like [`Worker::spawn`], with basin maps (partial, then complete) sent to `maps`.
    pub fn spawn_with_maps<T, F>(simulator: Simulator, out: Sender<T>, maps: F) -> Worker
    where
        T: From<Snapshot> + Send + 'static,
        F: Fn(MapUpdate) -> bool + Send + Sync + 'static,
    {
        let (commands, rx) = channel();
        let maps: MapSink = Arc::new(maps);
        let thread = std::thread::Builder::new()
            .name("dicesim-worker".to_string())
            .spawn(move || run(simulator, rx, out, maps, WallClock))
            .expect("the OS can start a thread");
        Worker {
            commands,
            thread: Some(thread),
        }
    }

    /// Queues a command; false once the worker has stopped.
    pub fn send(&self, command: Command) -> bool {
        self.commands.send(command).is_ok()
    }

    /// Asks the worker to stop and waits for it.
    pub fn shutdown(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        let _ = self.commands.send(Command::Quit);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        self.stop();
    }
}

fn run<T: From<Snapshot>>(
    mut simulator: Simulator,
    rx: Receiver<Command>,
    out: Sender<T>,
    maps: MapSink,
    clock: impl Clock,
) {
    let mut jobs = Jobs::new(maps);
    if out.send(report(&mut simulator, &mut jobs.curves).into()).is_err() {
        return;
    }
    crate::fault::inject("worker");
    let mut pacer = None;
    let mut next_tick = clock.now();
    loop {
        // Block while idle; while busy, wait for a command at most until the next tick.
        let first = if simulator.busy() || jobs.running() {
            match rx.recv_timeout(next_tick.saturating_duration_since(clock.now())) {
                Ok(c) => Some(c),
                Err(RecvTimeoutError::Timeout) => None,
                Err(RecvTimeoutError::Disconnected) => break,
            }
        } else {
            match rx.recv() {
                Ok(c) => Some(c),
                Err(_) => break,
            }
        };
        let mut handled = false;
        for command in first.into_iter().chain(std::iter::from_fn(|| rx.try_recv().ok())) {
            handled = true;
            if !simulator.handle(command) {
                jobs.stop();
                return;
            }
        }
        let now = clock.now();
        if !handled && now < next_tick {
            continue;
        }
        pacer::play_tick(&mut simulator, &mut pacer, now);
        jobs.sync(&mut simulator);
        if out.send(report(&mut simulator, &mut jobs.curves).into()).is_err() {
            break;
        }
        next_tick = now + TICK;
    }
    jobs.stop();
}

/// The simulator's snapshot, with whatever the curve thread has to report.
fn report(simulator: &mut Simulator, curves: &mut curve::CurveRunner) -> Snapshot {
    let curve = curves.sync(simulator.curve_setup());
    Snapshot {
        curve,
        ..simulator.snapshot()
    }
}

type ExportResult = Result<export_jobs::WrittenExport, dicesim_experiment::Error>;

/// The worker's jobs, each kind on a runner of its own: they follow what the simulator has
/// ordered (a job it no longer waits for is stopped), and their progress goes back to the
/// simulator, or for maps straight on to the UI, on every tick.
struct Jobs {
    /// Rolls finished since the last tick, and how the batch ended.
    batch: Runner<Vec<RollRecord>, Result<(), String>>,
    /// The newest progress, and what was written.
    export: Runner<Option<ExportStatus>, ExportResult>,
    /// Maps since the last tick (partial, coarse first, then the complete one).
    map: Runner<Vec<MapUpdate>, ()>,
    maps: MapSink,
    /// The twin's predictability curve follows the simulator's setup, not an order.
    curves: curve::CurveRunner,
}

impl Jobs {
    fn new(maps: MapSink) -> Jobs {
        Jobs {
            batch: Runner::new("dicesim-batch"),
            export: Runner::new("dicesim-export"),
            map: Runner::new("dicesim-map"),
            maps,
            curves: curve::CurveRunner::default(),
        }
    }

    fn running(&self) -> bool {
        self.batch.running() || self.export.running() || self.map.running() || self.curves.running()
    }

    /// Starts, stops and collects so every runner follows the simulator's orders.
    fn sync(&mut self, simulator: &mut Simulator) {
        self.batch.keep_only(simulator.batch_id());
        if let Some(request) = simulator.take_batch_request() {
            let id = request.id;
            if let Err(e) = self
                .batch
                .start(id, move |cancel, post| batch_work(&request, cancel, post))
            {
                simulator.finish_batch(id, Err(e.to_string()));
            }
        }
        match self.batch.poll() {
            Some(Report::Progress(id, fresh)) => simulator.add_batch_records(id, &fresh),
            Some(Report::Finished(id, rest, result)) => {
                simulator.add_batch_records(id, &rest);
                simulator.finish_batch(id, result.unwrap_or_else(|| Err("a roll panicked".to_string())));
            }
            None => {}
        }

        self.export.keep_only(simulator.export_id());
        if let Some(job) = simulator.take_export_request() {
            let id = job.id;
            let started = self.export.start(id, move |cancel, post| {
                job.run(cancel, &mut |p| post.post(|newest| *newest = Some(p)))
            });
            if let Err(e) = started {
                simulator.finish_export(id, Err(dicesim_experiment::Error::Export(e.to_string())));
            }
        }
        match self.export.poll() {
            Some(Report::Progress(id, Some(p))) => simulator.export_progress(id, p),
            Some(Report::Finished(id, _, result)) => simulator.finish_export(
                id,
                result.unwrap_or_else(|| {
                    Err(dicesim_experiment::Error::Export(
                        "the export panicked".to_string(),
                    ))
                }),
            ),
            _ => {}
        }

        self.map.keep_only(simulator.map_id());
        if let Some(job) = simulator.take_map_request() {
            let started = self.map.start(job.id, move |cancel, post| {
                map_jobs::compute(&job, cancel, &mut |u| {
                    post.post(|fresh| fresh.push(u));
                    true
                })
            });
            if let Err(e) = started {
                (self.maps)(job.failed(format!("cannot start the map thread: {e}")));
                simulator.finish_map(job.id);
            }
        }
        let (maps, ended) = match self.map.poll() {
            Some(Report::Progress(_, maps)) => (maps, None),
            Some(Report::Finished(id, rest, _)) => (rest, Some(id)),
            None => (Vec::new(), None),
        };
        for u in maps {
            (self.maps)(u);
        }
        if let Some(id) = ended {
            simulator.finish_map(id);
        }
    }

    /// Cancels every job and waits for its thread (milliseconds: rolls look at the flag
    /// every few thousand steps).
    fn stop(&mut self) {
        self.batch.stop();
        self.export.stop();
        self.map.stop();
        self.curves.stop();
    }
}

/// A batch's rolls, posted as they finish.
fn batch_work(
    request: &BatchRequest,
    cancel: &AtomicBool,
    post: &Post<Vec<RollRecord>>,
) -> Result<(), String> {
    let rolls = Rolls::Given(&request.rolls);
    if let Some(b) = &request.versus {
        // The parameter twin's throws, each in A and in B: pairs of records, in order.
        let options = dicesim_experiment::RunOptions::default();
        return dicesim_experiment::versus::stream_versus(
            &request.params,
            b,
            &rolls,
            &options,
            cancel,
            &mut |chunk| {
                post.post(|fresh: &mut Vec<RollRecord>| fresh.extend_from_slice(chunk));
                Ok(())
            },
        )
        .map(|_| ())
        .map_err(|e| e.to_string());
    }
    let mut seen = 0;
    run_batch(&request.params, &rolls, 0, cancel, &mut |records| {
        post.post(|fresh: &mut Vec<RollRecord>| fresh.extend_from_slice(&records[seen..]));
        seen = records.len();
    })
    .map(|_| ())
    .map_err(|e| e.to_string())
}
