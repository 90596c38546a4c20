//! The engine's chaos twin: a second simulation from the ε-perturbed start, stepped in
//! lock-step with the die, and the separation samples the plot shows.

use super::{DieState, Phase, SeparationSample, TwinSnapshot};
use crate::experiment::twin::{EPSILON, perturbed, separation};
use crate::physics::{InitialCondition, ParamError, Params, Simulation, face_most_nearly_up};

pub(crate) struct Twin {
    pub(crate) epsilon: f64,
    pub(crate) sim: Simulation,
    start_face: u8,
    /// Samples since the last snapshot.
    history: Vec<SeparationSample>,
    /// Steps since the last sample.
    unsampled: u64,
}

impl Twin {
    /// A twin of the roll from `initial`, at t = 0; ε outside its range is refused.
    pub(crate) fn new(params: &Params, initial: &InitialCondition, epsilon: f64) -> Result<Twin, ParamError> {
        EPSILON.check(epsilon)?;
        let sim = Simulation::new_unchecked(params, &perturbed(initial, epsilon));
        let start_face = face_most_nearly_up(&sim.state().corner_offsets);
        Ok(Twin {
            epsilon,
            sim,
            start_face,
            history: Vec::new(),
            unsampled: 0,
        })
    }

    /// One step, unless its roll is over (it plays on past its stopping rule as the die does).
    pub(crate) fn step(&mut self) {
        if !self.ended() {
            self.sim.advance();
        }
    }

    pub(crate) fn ended(&self) -> bool {
        super::live::played_out(&self.sim)
    }

    /// After a step: records the separation every `stride` steps, and at the end.
    pub(crate) fn stepped(&mut self, die: &Simulation, stride: u64, last: bool) {
        self.unsampled += 1;
        if self.unsampled >= stride || last {
            self.sample(die);
        }
    }

    /// Records the separation from `die` now.
    pub(crate) fn sample(&mut self, die: &Simulation) {
        self.unsampled = 0;
        let time_s = die.state().time_s.max(self.sim.state().time_s);
        self.history.push(SeparationSample {
            time_s,
            separation: separation(die, &self.sim),
        });
    }

    pub(crate) fn snapshot(&mut self, die: &Simulation) -> TwinSnapshot {
        TwinSnapshot {
            epsilon: self.epsilon,
            die: DieState::of(&self.sim, self.start_face),
            phase: match self.sim.outcome() {
                Some(o) => Phase::Ended(o),
                None => Phase::Rolling,
            },
            separation: separation(die, &self.sim),
            history: std::mem::take(&mut self.history),
        }
    }
}
