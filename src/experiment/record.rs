//! One roll of an experiment: its initial condition and how it ended.

use crate::physics::{InitialCondition, Outcome, Params, Simulation, face_most_nearly_up};
use serde::Serialize;
use std::sync::atomic::{AtomicBool, Ordering};

/// A finished roll as batches, basin maps and the outcome table record it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RollRecord {
    /// Roll index within its batch (or cell index within a map).
    pub id: u64,
    pub initial: InitialCondition,
    pub outcome: Outcome,
    /// The face most nearly up at t = 0.
    pub start_face: u8,
}

/// Rolls `initial` to its end. The parameters must be valid (an out-of-range initial
/// condition still ends in a status, never a panic).
pub fn roll_record(params: &Params, initial: &InitialCondition, id: u64) -> RollRecord {
    roll_record_or_cancel(params, initial, id, &AtomicBool::new(false)).expect("never cancelled")
}

/// [`roll_record`], or `None` once `cancel` is set (looked at before the first step and
/// then every [`STEPS_BETWEEN_STOP_CHECKS`](crate::physics::sim::STEPS_BETWEEN_STOP_CHECKS)
/// steps, so a cancel answers at once even when one roll is millions of steps long).
pub(crate) fn roll_record_or_cancel(
    params: &Params,
    initial: &InitialCondition,
    id: u64,
    cancel: &AtomicBool,
) -> Option<RollRecord> {
    let mut sim = Simulation::for_outcome(params, initial);
    let start_face = face_most_nearly_up(&sim.state().corner_offsets);
    let cancelled = || cancel.load(Ordering::Relaxed);
    if cancelled() {
        return None;
    }
    let outcome = sim.run_until_stopped(&cancelled)?;
    Some(RollRecord {
        id,
        initial: *initial,
        outcome,
        start_face,
    })
}
