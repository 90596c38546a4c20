//! One roll of an experiment: its initial condition and how it ended.

use dicesim_physics::lanes;
use dicesim_physics::{InitialCondition, Outcome, Params};
use dicesim_setup::number::StepClock;
use serde::Serialize;
use std::sync::atomic::{AtomicBool, Ordering};

/// A finished roll as batches, basin maps and the outcome table record it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RollRecord {
    /// Roll index within its batch (or cell index within a map).
    pub id: u64,
    pub initial: InitialCondition,
    /// The ending, its time as files print it ([`reported`]).
    pub outcome: Outcome,
    /// The face most nearly up at t = 0.
    pub start_face: u8,
}

#[cfg(test)]
impl RollRecord {
    /// A roll of one step that ended with `status` on `face`: what the tallies' tests need,
    /// for they read only how a roll ended.
    pub(crate) fn ended(id: u64, status: dicesim_physics::Status, face: Option<u8>) -> RollRecord {
        RollRecord {
            id,
            initial: InitialCondition::default(),
            outcome: Outcome {
                status,
                face,
                steps: 1,
                time_s: 0.001,
                impacts: 0,
                first_impact: None,
            },
            start_face: 4,
        }
    }
}

/// `outcome` as every experiment reports it: its times (the end's, the first impact's) the steps × Δt of `params`, rounded to
/// Δt's decimals ([`StepClock`]), not the clock's sum of Δt (`0.684`, not
/// `0.6840000000000005`); the step count, exact, is beside it.
pub fn reported(mut outcome: Outcome, params: &Params) -> Outcome {
    let clock = StepClock::new(params.integrator.dt);
    outcome.time_s = clock.time_s(outcome.steps);
    if let Some(first) = &mut outcome.first_impact {
        first.time_s = clock.time_s(first.step);
    }
    outcome
}

/// Rolls `initial` to its end. The parameters must be valid (an out-of-range initial
/// condition still ends in a status, never a panic).
pub fn roll_record(params: &Params, initial: &InitialCondition, id: u64) -> RollRecord {
    roll_record_or_cancel(params, initial, id, &AtomicBool::new(false)).expect("never cancelled")
}

/// [`roll_record`], or `None` once `cancel` is set (looked at before the first step and
/// then every [`STEPS_BETWEEN_STOP_CHECKS`](dicesim_physics::sim::STEPS_BETWEEN_STOP_CHECKS)
/// steps, so a cancel answers at once even when one roll is millions of steps long).
pub(crate) fn roll_record_or_cancel(
    params: &Params,
    initial: &InitialCondition,
    id: u64,
    cancel: &AtomicBool,
) -> Option<RollRecord> {
    let cancelled = || cancel.load(Ordering::Relaxed);
    if cancelled() {
        return None;
    }
    // The box or a polyhedral die, as a batch rolls it: what `merge --verify` and the
    // single rolls of a sweep hold records to.
    let (outcome, start_face) = lanes::roll_one(params, initial, &cancelled)?;
    Some(RollRecord {
        id,
        initial: *initial,
        outcome: reported(outcome, params),
        start_face,
    })
}
