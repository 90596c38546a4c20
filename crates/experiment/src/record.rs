//! One roll of an experiment: its initial condition and how it ended.

use dicesim_physics::{InitialCondition, Outcome, Params, Simulation, Status, face_most_nearly_up};
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
/// then every [`STEPS_BETWEEN_STOP_CHECKS`](dicesim_physics::sim::STEPS_BETWEEN_STOP_CHECKS)
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

/// The face most nearly up at t = 0 of a roll from `initial`, placed exactly as
/// [`roll_record`] places it (a loaded die's corners about its centre of mass included).
pub(crate) fn start_face(params: &Params, initial: &InitialCondition) -> u8 {
    face_most_nearly_up(&Simulation::for_outcome(params, initial).state().corner_offsets)
}

/// Checks every field of a record read back from a file against what a roll of `params`
/// can produce: a start inside the allowed ranges and clear of the table, the start face
/// that start gives, a face only for a settled roll, and a step count and simulated time
/// that agree with each other and with `integrator.max_time`. `drawn` is the start the
/// sweep's seed gives this id (random sweeps), which the record must carry bit for bit.
/// What cannot be checked without rolling again is the outcome itself (`merge --verify`).
pub fn check_record(r: &RollRecord, params: &Params, drawn: Option<&InitialCondition>) -> Result<(), String> {
    let ic = &r.initial;
    if let Some(d) = drawn
        && !same_start(ic, d)
    {
        return Err(format!(
            "roll {}: its start is not the one the sweep's seed draws for it (a record of another sweep, or an edited one)",
            r.id
        ));
    }
    ic.validate()
        .and_then(|()| ic.check_clear_of_table(params))
        .map_err(|e| format!("roll {}: {e}", r.id))?;
    if !face_ok(r.start_face) || r.start_face != start_face(params, ic) {
        return Err(format!(
            "roll {}: start_face {} is not the face its start puts up ({})",
            r.id,
            r.start_face,
            start_face(params, ic)
        ));
    }
    check_outcome(&r.outcome, params).map_err(|e| format!("roll {}: {e}", r.id))
}

/// Checks an outcome read back from a file: a face only for a settled roll, and a step
/// count and simulated time that agree with each other and with `integrator.max_time`.
pub(crate) fn check_outcome(o: &Outcome, params: &Params) -> Result<(), String> {
    match (o.status, o.face) {
        (_, Some(f)) if !face_ok(f) => return Err(format!("face {f} is not a face of a die")),
        (Status::Timeout | Status::Unstable, Some(f)) => {
            return Err(format!(
                "face {f} with status `{}` (only a settled roll has a face)",
                o.status.name()
            ));
        }
        _ => {}
    }
    let max_steps = params.max_steps();
    if o.steps > max_steps || (o.status == Status::Timeout && o.steps != max_steps) {
        return Err(format!(
            "{} steps with status `{}`, but a roll times out at exactly {max_steps} steps",
            o.steps,
            o.status.name()
        ));
    }
    // The clock adds dt once a step: its rounding stays far below 10⁻⁸ of the time.
    let expected = o.steps as f64 * params.integrator.dt;
    if !(o.time_s.is_finite() && (o.time_s - expected).abs() <= 1e-8 * expected) {
        return Err(format!(
            "time_s {:?} is not {} steps of {} s",
            o.time_s, o.steps, params.integrator.dt
        ));
    }
    Ok(())
}

/// Whether `f` names a face of the die (1 to 6).
pub(crate) fn face_ok(f: u8) -> bool {
    (1..=6).contains(&f)
}

/// Whether two starts are the same bit for bit (`-0.0` and `0.0` differ, as in a file);
/// where the angular momentum is set it is the spin, and the angular velocity (which a
/// CSV file then leaves empty) is not compared.
pub(crate) fn same_start(a: &InitialCondition, b: &InitialCondition) -> bool {
    let bits = |ic: &InitialCondition| {
        let spin: Vec<f64> = match ic.angular_momentum {
            Some(l) => vec![1.0, l[0], l[1], l[2]],
            None => vec![
                0.0,
                ic.angular_velocity[0],
                ic.angular_velocity[1],
                ic.angular_velocity[2],
            ],
        };
        [ic.height]
            .iter()
            .chain(&ic.velocity)
            .chain(&spin)
            .chain(&ic.orientation)
            .map(|x| x.to_bits())
            .collect::<Vec<u64>>()
    };
    bits(a) == bits(b)
}

/// Whether two records are the same bit for bit.
pub fn same_record(a: &RollRecord, b: &RollRecord) -> bool {
    a.id == b.id
        && same_start(&a.initial, &b.initial)
        && a.start_face == b.start_face
        && (a.outcome.status, a.outcome.face, a.outcome.steps)
            == (b.outcome.status, b.outcome.face, b.outcome.steps)
        && a.outcome.time_s.to_bits() == b.outcome.time_s.to_bits()
}
