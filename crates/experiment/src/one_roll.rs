//! One roll from a preset's initial condition, as `dicesim roll` reports it: its ending,
//! why it ended so, its stopping rule and stability, its final state and the setup.

use crate::provenance;
use crate::record::reported;
use dicesim_physics::{
    Outcome, ParamError, Simulation, Stability, Status, UnstableReason, why_it_cannot_settle,
};
use dicesim_setup::preset::Preset;
use serde_json::{Value, json};

/// A roll run to its end.
pub struct OneRoll {
    /// The simulation at the roll's end.
    pub sim: Simulation,
    /// Its ending, its time the steps × Δt that every output prints.
    pub outcome: Outcome,
    /// Which limit an unstable roll passed; `None` for any other ending.
    pub reason: Option<UnstableReason>,
}

impl OneRoll {
    /// Rolls `preset`'s initial condition on its setup to the end.
    pub fn run(preset: &Preset) -> Result<OneRoll, ParamError> {
        let params = preset.params();
        let mut sim = Simulation::new(&params, &preset.initial)?;
        // Its time as every output prints it: the steps × Δt, not the clock's sum.
        let outcome = reported(sim.run_to_end(), &params);
        let reason =
            (outcome.status == Status::Unstable).then(|| UnstableReason::new(&params, &preset.initial));
        Ok(OneRoll { sim, outcome, reason })
    }

    /// The roll as one JSON object (`dicesim roll --json`) of `preset`, which rolled it;
    /// `changed`: the preset was changed from its file (`--set`), as its provenance says.
    pub fn json(&self, preset: &Preset, changed: bool) -> Value {
        let (sim, outcome) = (&self.sim, &self.outcome);
        let params = preset.params();
        let s = sim.state();
        // The rule this roll applied at its end: a loaded die's depends on the face down.
        let rule = sim.stop_rule_now();
        let stability = Stability::predict(&params, &preset.initial).verdict();
        let finite = |x: f64| x.is_finite().then_some(x);
        json!({
            "preset": preset.name,
            "face": outcome.face,
            "status": outcome.status,
            "steps": outcome.steps,
            "time_s": outcome.time_s,
            "unstable_reason": self.reason.as_ref().map(|r| json!({
                "limit": r.0.limit,
                "value": r.0.value,
                "allowed": r.0.allowed,
                "exceeded": r.0.exceeded(),
                "message": r.to_string(),
            })),
            "cannot_settle": why_it_cannot_settle(&params),
            "energy_threshold": finite(rule.energy_threshold),
            "kinetic_threshold": finite(rule.kinetic_threshold),
            "stop_energy": sim.stop_energy(),
            "stop_kinetic_energy": sim.stop_kinetic_energy(),
            "stability_number": params.stability_number(),
            "stability": {
                "stable": !stability.exceeded(),
                "limit": stability.limit,
                "value": stability.value,
                "allowed": stability.allowed,
                "load": stability.load(),
            },
            "final": {
                "position": s.position.as_slice(),
                "velocity": s.velocity.as_slice(),
                "angular_momentum": s.angular_momentum.as_slice(),
                "angular_velocity": sim.angular_velocity().as_slice(),
                "energy": sim.energy(),
                "corner_offsets": s.corner_offsets.iter().map(|r| [r.x, r.y, r.z]).collect::<Vec<_>>(),
            },
            "params": params,
            "initial": preset.initial,
            "provenance": provenance::roll(preset, "the preset's roll", changed),
        })
    }
}
