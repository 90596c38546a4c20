//! Basin maps for the explorer: `experiment::run_map` on a thread of its own, its partial
//! maps sent straight to the UI as they come, coarse first.
//!
//! Every map is tagged with the generation the UI gave its request. A new request or a
//! cancel sets the old map's cancel flag and lets its thread wind down on its own (it stops
//! at the end of its refinement level), so the worker never waits for it; whatever that
//! thread still sends carries the old generation and the UI drops it.

use crate::experiment::{Axis, BasinMap, Error, MapSpec, Method, ScanKey, run_map};
use crate::physics::{InitialCondition, Params};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;

/// One axis of a requested map: a numeric setup value, its range and grid nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapAxis {
    pub key: &'static ScanKey,
    /// In the value's unit.
    pub min: f64,
    /// In the value's unit.
    pub max: f64,
    pub cells: usize,
}

impl MapAxis {
    /// The experiment's axis, checked against the value's allowed range.
    pub fn axis(&self) -> Result<Axis, Error> {
        Axis::new(self.key.clone(), self.min, self.max, self.cells)
    }
}

/// A map to compute around the worker's current setup.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapRequest {
    /// Chosen by the UI; results of older generations are stale.
    pub generation: u64,
    pub x: MapAxis,
    pub y: MapAxis,
}

/// A request with the setup it maps around, as the worker had it when the request came.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MapJob {
    pub(crate) request: MapRequest,
    pub(crate) params: Params,
    pub(crate) initial: InitialCondition,
}

/// What the worker's engine asks its map thread to do next.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum MapOrder {
    Start(Box<MapJob>),
    Cancel,
}

/// A map, partial or complete, or why it could not be computed.
#[derive(Debug, Clone, PartialEq)]
pub struct MapUpdate {
    pub generation: u64,
    /// The setup every cell starts from, but for its two axis values (see `node_setup`).
    pub params: Params,
    pub initial: InitialCondition,
    pub map: Result<BasinMap, String>,
}

/// Computes `job` on this thread (one roll thread per core), handing every partial map and
/// the complete one to `send`; stops early when `cancel` is set or `send` returns false.
pub(crate) fn compute(job: &MapJob, cancel: &AtomicBool, send: &mut dyn FnMut(MapUpdate) -> bool) {
    let update = |map| MapUpdate {
        generation: job.request.generation,
        params: job.params,
        initial: job.initial,
        map,
    };
    let spec = match (job.request.x.axis(), job.request.y.axis()) {
        (Ok(x), Ok(y)) => MapSpec {
            x,
            y,
            method: Method::Adaptive,
        },
        (Err(e), _) | (_, Err(e)) => {
            send(update(Err(e.to_string())));
            return;
        }
    };
    let result = run_map(&job.params, &job.initial, &spec, 0, cancel, &mut |partial| {
        if !cancel.load(Ordering::Relaxed) && !send(update(Ok(partial.clone()))) {
            // Nobody listens any more: stop at the end of this level.
            cancel.store(true, Ordering::Relaxed);
        }
    });
    if let Err(e) = result {
        send(update(Err(e.to_string())));
    }
}

/// Where map threads send their updates; false once the UI has gone.
pub(super) type MapSink = Arc<dyn Fn(MapUpdate) -> bool + Send + Sync>;

struct MapRun {
    cancel: Arc<AtomicBool>,
    thread: JoinHandle<()>,
}

/// The map threads of one worker: at most one current, cancelled ones winding down.
pub(super) struct MapRunner {
    sink: MapSink,
    current: Option<MapRun>,
    retired: Vec<MapRun>,
}

impl MapRunner {
    pub(crate) fn new(sink: MapSink) -> MapRunner {
        MapRunner {
            sink,
            current: None,
            retired: Vec::new(),
        }
    }

    /// Follows the engine's newest order, and forgets threads that have ended.
    pub(crate) fn sync(&mut self, order: Option<MapOrder>) {
        if let Some(order) = order {
            if let Some(run) = self.current.take() {
                run.cancel.store(true, Ordering::Relaxed);
                self.retired.push(run);
            }
            if let MapOrder::Start(job) = order {
                self.start(*job);
            }
        }
        let (ended, running): (Vec<MapRun>, Vec<MapRun>) =
            self.retired.drain(..).partition(|r| r.thread.is_finished());
        self.retired = running;
        for run in ended {
            let _ = run.thread.join();
        }
    }

    fn start(&mut self, job: MapJob) {
        let cancel = Arc::new(AtomicBool::new(false));
        let (flag, sink) = (cancel.clone(), self.sink.clone());
        let thread = std::thread::Builder::new()
            .name("dicesim-map".to_string())
            .spawn(move || compute(&job, &flag, &mut |u| sink(u)));
        match thread {
            Ok(thread) => self.current = Some(MapRun { cancel, thread }),
            Err(e) => {
                (self.sink)(MapUpdate {
                    generation: job.request.generation,
                    params: job.params,
                    initial: job.initial,
                    map: Err(format!("cannot start the map thread: {e}")),
                });
            }
        }
    }
}

impl Drop for MapRunner {
    /// Cancels every map and waits for each to reach the end of its level.
    fn drop(&mut self) {
        let runs: Vec<MapRun> = self
            .current
            .take()
            .into_iter()
            .chain(self.retired.drain(..))
            .collect();
        for run in &runs {
            run.cancel.store(true, Ordering::Relaxed);
        }
        for run in runs {
            let _ = run.thread.join();
        }
    }
}
