//! The twin die: a second simulation stepped in lock-step with the die, and the
//! separation samples the plot shows. What tells the two apart is its [`Difference`]: a
//! start ε away (the chaos twin) or a setup B with some values changed (the parameter twin).

use super::play_on::played_out;
use super::protocol::{DieState, EnergySample, Phase, SeparationSample, TwinSnapshot};
use dicesim_physics::{InitialCondition, Params, Roll};
use dicesim_setup::chaos::{EPSILON, perturbed, separation};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::registry::Role;

/// What the twin differs from the die by.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Difference {
    /// The chaos twin: its start's height, velocity and spin × (1 + ε), the same setup.
    Start { epsilon: f64 },
    /// The parameter twin: the same start, rolled in setup B = the die's setup with these
    /// values (the last one given for a key wins).
    Setup { values: Vec<(&'static ScanKey, f64)> },
}

impl Difference {
    /// Relative: the chaos twin's ε (0 for the parameter twin, whose start is the die's).
    pub(crate) fn epsilon(&self) -> f64 {
        match self {
            Difference::Start { epsilon } => *epsilon,
            Difference::Setup { .. } => 0.0,
        }
    }

    /// The twin's setup and start for the die's `params` and `initial`; a value out of its
    /// range, a start value (both roll the same start) or a Δt difference (the two step in
    /// lock-step, step for step) is refused in words naming the key.
    pub(crate) fn apply(
        &self,
        params: &Params,
        initial: &InitialCondition,
    ) -> Result<(Params, InitialCondition), String> {
        match self {
            Difference::Start { epsilon } => {
                EPSILON.check(*epsilon).map_err(|e| e.to_string())?;
                Ok((*params, perturbed(initial, *epsilon)))
            }
            Difference::Setup { values } => {
                let (mut b, mut start) = (*params, *initial);
                for (key, value) in values {
                    if key.spec.role == Role::Initial {
                        return Err(format!(
                            "twin B: {} is a start value; both dice roll the same start",
                            key.key
                        ));
                    }
                    key.set_checked(&mut b, &mut start, *value)
                        .map_err(|e| format!("twin B: {e}"))?;
                }
                if b.integrator.dt.to_bits() != params.integrator.dt.to_bits() {
                    return Err(format!(
                        "twin B: Δt {} s differs from A's {} s; the dice step in lock-step, so \
                         both need the same Δt",
                        b.integrator.dt, params.integrator.dt
                    ));
                }
                b.validate().map_err(|e| format!("twin B: {e}"))?;
                Ok((b, start))
            }
        }
    }
}

pub(crate) struct Twin {
    pub(crate) difference: Difference,
    pub(crate) sim: Roll,
    start_face: u8,
    /// Samples since the last snapshot.
    history: Vec<SeparationSample>,
    /// A parameter twin's own energy and quantity samples since the last snapshot, taken
    /// with the separation (the plot draws B's curve beside A's).
    samples: Vec<EnergySample>,
    /// Steps since the last sample.
    unsampled: u64,
}

impl Twin {
    /// A twin of the roll of `params` from `initial`, at t = 0; a difference
    /// [`Difference::apply`] refuses is refused.
    pub(crate) fn new(
        params: &Params,
        initial: &InitialCondition,
        difference: Difference,
    ) -> Result<Twin, String> {
        let (b, start) = difference.apply(params, initial)?;
        let sim = Roll::new_unchecked(&b, &start);
        let start_face = sim.start_face();
        Ok(Twin {
            difference,
            sim,
            start_face,
            history: Vec::new(),
            samples: Vec::new(),
            unsampled: 0,
        })
    }

    /// Setup B for the die's `params` and `initial`, if this is a parameter twin.
    pub(crate) fn setup_b(&self, params: &Params, initial: &InitialCondition) -> Option<Params> {
        match self.difference {
            Difference::Start { .. } => None,
            Difference::Setup { .. } => self.difference.apply(params, initial).ok().map(|(b, _)| b),
        }
    }

    /// The chaos twin at ε, if it is one.
    pub(crate) fn epsilon(&self) -> Option<f64> {
        match self.difference {
            Difference::Start { epsilon } => Some(epsilon),
            Difference::Setup { .. } => None,
        }
    }

    /// The die's table changed mid-roll to `params`' (the die's new setup): the twin feels
    /// it too, with B's own values kept.
    pub(crate) fn set_ground(&mut self, params: &Params, initial: &InitialCondition) {
        if let Ok((b, _)) = self.difference.apply(params, initial) {
            let _ = self.sim.set_ground(b.ground);
        }
    }

    /// One step, unless its roll is over (it plays on past its stopping rule as the die does).
    pub(crate) fn step(&mut self) {
        if !self.ended() {
            self.sim.advance();
        }
    }

    pub(crate) fn ended(&self) -> bool {
        played_out(&self.sim)
    }

    /// After a step: records the separation every `stride` steps, and at the end.
    pub(crate) fn stepped(&mut self, die: &Roll, stride: u64, last: bool) {
        self.unsampled += 1;
        if self.unsampled >= stride || last {
            self.sample(die);
        }
    }

    /// Records the separation from `die` now.
    pub(crate) fn sample(&mut self, die: &Roll) {
        self.unsampled = 0;
        let time_s = die.time_s().max(self.sim.time_s());
        self.history.push(SeparationSample {
            time_s,
            separation: separation(die, &self.sim),
        });
        if let Difference::Setup { .. } = self.difference {
            self.samples.push(EnergySample::of(&self.sim));
        }
    }

    pub(crate) fn snapshot(&mut self, die: &Roll) -> TwinSnapshot {
        TwinSnapshot {
            epsilon: self.difference.epsilon(),
            differs_by: match &self.difference {
                Difference::Start { .. } => Vec::new(),
                Difference::Setup { values } => values.clone(),
            },
            die: DieState::of(&self.sim, self.start_face),
            phase: match self.sim.outcome() {
                Some(o) => Phase::Ended(o),
                None => Phase::Rolling,
            },
            separation: separation(die, &self.sim),
            history: std::mem::take(&mut self.history),
            samples: std::mem::take(&mut self.samples),
        }
    }
}
