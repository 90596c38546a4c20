//! Basin maps for the explorer: `experiment::run_map` on a thread of its own, its partial
//! maps sent straight to the UI as they come, coarse first.
//!
//! Every map is tagged with the generation the UI gave its request. A new request or a
//! cancel stops the old map and waits for its thread, which takes milliseconds since every
//! roll looks at the cancel flag every few thousand steps: at most one map computes at a
//! time. Whatever the old map sent last carries the old generation and the UI drops it.

use super::job::Job;
use crate::experiment::{Axis, BasinMap, Error, MapSpec, Method, ScanKey, run_map};
use crate::physics::{InitialCondition, Params};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

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
    crate::fault::inject("map");
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
            // Nobody listens any more: stop.
            cancel.store(true, Ordering::Relaxed);
        }
    });
    if let Err(e) = result {
        send(update(Err(e.to_string())));
    }
}

/// Where map threads send their updates; false once the UI has gone.
pub(super) type MapSink = Arc<dyn Fn(MapUpdate) -> bool + Send + Sync>;

/// The map thread of one worker: at most one at a time.
pub(super) struct MapRunner {
    sink: MapSink,
    current: Option<Job<()>>,
}

impl MapRunner {
    pub(crate) fn new(sink: MapSink) -> MapRunner {
        MapRunner { sink, current: None }
    }

    /// Follows the engine's newest order, and forgets a map that has ended.
    pub(crate) fn sync(&mut self, order: Option<MapOrder>) {
        if let Some(order) = order {
            self.stop();
            if let MapOrder::Start(job) = order {
                self.start(*job);
            }
        }
        if self.current.as_ref().is_some_and(Job::is_finished) {
            self.stop();
        }
    }

    /// Whether a map is computing.
    pub(crate) fn running(&self) -> bool {
        self.current.is_some()
    }

    fn start(&mut self, job: MapJob) {
        let sink = self.sink.clone();
        match Job::spawn("dicesim-map", move |cancel| {
            compute(&job, cancel, &mut |u| sink(u))
        }) {
            Ok(run) => self.current = Some(run),
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

    fn stop(&mut self) {
        if let Some(run) = self.current.take() {
            run.stop();
        }
    }
}

impl Drop for MapRunner {
    fn drop(&mut self) {
        self.stop();
    }
}
