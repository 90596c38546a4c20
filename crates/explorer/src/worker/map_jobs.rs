//! Basin maps for the explorer: `experiment::run_map` as a job of the worker's map runner,
//! its partial maps passed straight on to the UI on every tick, coarse first.
//!
//! Every map is tagged with the generation the UI gave its request. A new request or a
//! cancel stops the old map and waits for its thread, which takes milliseconds since every
//! roll looks at the cancel flag every few thousand steps: at most one map computes at a
//! time. Whatever the old map sent last carries the old generation and the UI drops it.

use dicesim_experiment::{Axis, BasinMap, Error, MapSpec, Method, ScanKey, run_map};
use dicesim_physics::{InitialCondition, Params};
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
    /// The simulator's id of the job (the UI knows it by `request.generation`).
    pub(crate) id: u64,
    pub(crate) request: MapRequest,
    pub(crate) params: Params,
    pub(crate) initial: InitialCondition,
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

/// Where the map runner sends the maps; false once the UI has gone.
pub(super) type MapSink = Arc<dyn Fn(MapUpdate) -> bool + Send + Sync>;

impl MapJob {
    /// What the UI is told when the job could not even start.
    pub(crate) fn failed(&self, why: String) -> MapUpdate {
        MapUpdate {
            generation: self.request.generation,
            params: self.params,
            initial: self.initial,
            map: Err(why),
        }
    }
}
