//! One roll of an experiment: its initial condition and how it ended.

use dicesim_physics::{
    InitialCondition, Outcome, Params, Placement, Simulation, Status, face_most_nearly_up,
};
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
        outcome: reported(outcome, params),
        start_face,
    })
}

/// The checks of records read back from a file, for one setup: what is fixed for the setup
/// (its body's placement, its clock, its step limit) is worked out once, not per record.
pub struct RecordCheck {
    params: Params,
    placement: Placement,
    clock: StepClock,
    max_steps: u64,
}

impl RecordCheck {
    /// The checks of records of `params` (valid parameters).
    pub fn new(params: &Params) -> RecordCheck {
        RecordCheck {
            params: *params,
            placement: Placement::new(params),
            clock: StepClock::new(params.integrator.dt),
            max_steps: params.max_steps(),
        }
    }

    /// The clock that prints the records' times.
    pub fn clock(&self) -> &StepClock {
        &self.clock
    }

    /// The face most nearly up at t = 0 of a roll from `initial`, placed exactly as
    /// [`roll_record`] places it (a loaded die's corners about its centre of mass included).
    pub fn start_face(&self, initial: &InitialCondition) -> u8 {
        face_most_nearly_up(&self.placement.start_offsets(initial))
    }

    /// Checks every field of a record read back from a file against what a roll of the
    /// setup can produce: a start inside the allowed ranges and clear of the table, the
    /// start face that start gives, a face only for a settled roll, a step count within
    /// `integrator.max_time` and the time those steps print. `drawn` is the start the
    /// sweep's seed gives this id (random sweeps), which the record must carry bit for bit.
    /// What cannot be checked without rolling again is the outcome itself (`merge --verify`).
    pub fn check(&self, r: &RollRecord, drawn: Option<&InitialCondition>) -> Result<(), String> {
        let ic = &r.initial;
        match drawn {
            Some(d) if !same_start(ic, d) => {
                return Err(format!(
                    "roll {}: its start is not the one the sweep's seed draws for it (a record of another sweep, or an edited one)",
                    r.id
                ));
            }
            // A draw lies in the sweep's ranges, which were checked clear of the table once.
            Some(_) => {}
            None => ic
                .validate()
                .and_then(|()| self.placement.check_clear_of_table(ic))
                .map_err(|e| format!("roll {}: {e}", r.id))?,
        }
        self.check_ending(r)
    }

    /// The checks of [`RecordCheck::check`] that do not look at the start's values: its
    /// start face, and the ending ([`RecordCheck::check_outcome`]).
    pub fn check_ending(&self, r: &RollRecord) -> Result<(), String> {
        let face = self.start_face(&r.initial);
        if r.start_face != face {
            return Err(format!(
                "roll {}: start_face {} is not the face its start puts up ({face})",
                r.id, r.start_face
            ));
        }
        self.check_outcome(&r.outcome)
            .map_err(|e| format!("roll {}: {e}", r.id))
    }

    /// Checks an outcome read back from a file: a face only for a settled roll, a step count
    /// within `integrator.max_time` (a timeout exactly at it), and the time those steps
    /// print, bit for bit.
    pub fn check_outcome(&self, o: &Outcome) -> Result<(), String> {
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
        let max_steps = self.max_steps;
        if o.steps > max_steps || (o.status == Status::Timeout && o.steps != max_steps) {
            return Err(format!(
                "{} steps with status `{}`, but a roll times out at exactly {max_steps} steps",
                o.steps,
                o.status.name()
            ));
        }
        let expected = self.clock.time_s(o.steps);
        if o.time_s.to_bits() != expected.to_bits() {
            return Err(format!(
                "time_s {:?} is not {} steps of {} s ({expected:?})",
                o.time_s, o.steps, self.params.integrator.dt
            ));
        }
        self.check_impacts(o)
    }

    /// The impacts of an outcome: a first impact exactly when there was one, within the
    /// roll (after its start, by its end), its time its steps' own, its face down a face; and
    /// no more impacts than half the steps (each begins after a state clear of the table).
    fn check_impacts(&self, o: &Outcome) -> Result<(), String> {
        if 2 * o.impacts > o.steps + 1 {
            return Err(format!(
                "{} impacts in {} steps: each needs a step clear of the table",
                o.impacts, o.steps
            ));
        }
        let Some(first) = &o.first_impact else {
            return match o.impacts {
                0 => Ok(()),
                n => Err(format!("{n} impacts but no first impact")),
            };
        };
        if o.impacts == 0 {
            return Err("a first impact with 0 impacts".to_string());
        }
        if first.step == 0 || first.step > o.steps {
            return Err(format!(
                "first impact at step {}, outside the roll's steps 1 to {}",
                first.step, o.steps
            ));
        }
        let expected = self.clock.time_s(first.step);
        if first.time_s.to_bits() != expected.to_bits() {
            return Err(format!(
                "first_impact_time_s {:?} is not {} steps of {} s ({expected:?})",
                first.time_s, first.step, self.params.integrator.dt
            ));
        }
        if !face_ok(first.face_down) {
            return Err(format!(
                "first_impact_face_down {} is not a face of a die",
                first.face_down
            ));
        }
        Ok(())
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_reports_its_time_as_steps_of_dt_and_its_checks_hold_it_to_that() {
        let params = Params::default();
        let r = roll_record(&params, &InitialCondition::default(), 0);
        let dt = params.integrator.dt;
        // The decimal steps × Δt (Δt = 0.001 s: the steps in thousandths), which the
        // clock's sum of Δt misses in its last bits.
        assert_eq!(dt, 0.001);
        let steps = r.outcome.steps;
        let decimal = format!("{}.{:03}", steps / 1000, steps % 1000);
        assert_eq!(r.outcome.time_s, decimal.parse::<f64>().unwrap());
        let check = RecordCheck::new(&params);
        assert_eq!(check.check(&r, None), Ok(()));
        assert_eq!(check.check(&r, Some(&r.initial)), Ok(()));
        assert_eq!(check.start_face(&r.initial), r.start_face);
        let mut summed = r;
        summed.outcome.time_s = (0..r.outcome.steps).fold(0.0, |t, _| t + dt);
        if summed.outcome.time_s != r.outcome.time_s {
            assert!(
                check
                    .check(&summed, None)
                    .unwrap_err()
                    .contains("steps of 0.001 s")
            );
        }
        let mut turned = r;
        turned.start_face = 7 - r.start_face;
        assert!(
            check
                .check(&turned, None)
                .unwrap_err()
                .starts_with("roll 0: start_face")
        );
        let mut other = r.initial;
        other.height += 1.0;
        assert!(
            check
                .check(&r, Some(&other))
                .unwrap_err()
                .contains("not the one the sweep's seed draws")
        );
    }

    #[test]
    fn a_records_impacts_are_checked_as_read_back() {
        let params = Params::default();
        let r = roll_record(&params, &InitialCondition::default(), 0);
        let check = RecordCheck::new(&params);
        // The paper's throw falls 14 cm before it first touches: it has impacts, the first
        // a whole number of steps into the roll and printed as those steps of Δt.
        let first = r.outcome.first_impact.expect("the paper's throw lands");
        assert!(r.outcome.impacts >= 1 && first.step < r.outcome.steps);
        assert_eq!(
            first.time_s,
            StepClock::new(params.integrator.dt).time_s(first.step)
        );
        let refused = |edit: &dyn Fn(&mut Outcome), words: &str| {
            let mut bad = r;
            edit(&mut bad.outcome);
            let e = check.check(&bad, None).unwrap_err();
            assert!(e.contains(words), "{e}");
        };
        refused(&|o| o.first_impact = None, "impacts but no first impact");
        refused(&|o| o.impacts = 0, "a first impact with 0 impacts");
        refused(
            &|o| o.first_impact.as_mut().unwrap().step = o.steps + 1,
            "outside the roll's steps",
        );
        refused(&|o| o.first_impact.as_mut().unwrap().time_s += 1e-9, "is not");
        refused(
            &|o| o.first_impact.as_mut().unwrap().face_down = 7,
            "not a face of a die",
        );
        refused(&|o| o.impacts = o.steps, "each needs a step clear of the table");
    }
}
