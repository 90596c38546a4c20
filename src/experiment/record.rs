//! One roll of an experiment: its initial condition and how it ended.

use crate::physics::{InitialCondition, Outcome, Params, Simulation, face_most_nearly_up};
use serde::Serialize;

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
    let mut sim = Simulation::new_unchecked(params, initial);
    let start_face = face_most_nearly_up(&sim.state().corner_offsets);
    let outcome = sim.run_to_end();
    RollRecord {
        id,
        initial: *initial,
        outcome,
        start_face,
    }
}
