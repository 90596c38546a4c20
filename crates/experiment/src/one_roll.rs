//! One roll from a preset's initial condition, as `dicesim roll` reports it: its ending,
//! why it ended so, its stopping rule and stability, its final state and the setup. Any
//! die: the box (its `Roll` steps its `Simulation`, so it reports as it always has) or a
//! polyhedral die, its face the number a player reads.

use crate::provenance;
use crate::record::reported;
use dicesim_physics::stability::Limit;
use dicesim_physics::{
    Outcome, ParamError, Params, Roll, Stability, Status, UnstableReason, why_it_cannot_settle,
};
use dicesim_setup::preset::Preset;
use serde_json::{Value, json};

/// A roll run to its end.
pub struct OneRoll {
    /// The roll at its end.
    pub roll: Roll,
    /// Its ending, its time the steps × Δt that every output prints.
    pub outcome: Outcome,
    /// Which limit an unstable roll passed; `None` for any other ending.
    pub reason: Option<UnstableReason>,
}

/// The stability reading a single roll reports: the physics' verdict of its setup
/// (`Stability::predict`, read on the die's own body: docs/model.md, "Stability").
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    pub limit: Limit,
    pub value: f64,
    pub allowed: f64,
    /// The reading in words.
    pub words: String,
}

impl Verdict {
    /// The verdict on `params` rolled from `initial`.
    pub fn of(params: &Params, initial: &dicesim_physics::InitialCondition) -> Verdict {
        let r = Stability::predict(params, initial).verdict();
        Verdict {
            limit: r.limit,
            value: r.value,
            allowed: r.allowed,
            words: r.to_string(),
        }
    }

    /// `value / allowed`: below 1 the roll is predicted to step stably.
    pub fn load(&self) -> f64 {
        self.value / self.allowed
    }

    pub fn exceeded(&self) -> bool {
        let load = self.load();
        load > 1.0 || load.is_nan()
    }
}

/// Why `roll`'s table cannot hold its die on a face, if it cannot: the physics' words for
/// the box; for a polyhedral die, that its stopping rule has no threshold on this table.
pub fn why_it_cannot_settle_roll(roll: &Roll) -> Option<String> {
    let params = roll.params();
    if !roll.is_polyhedral() {
        return why_it_cannot_settle(params);
    }
    (!roll.stop_rule().can_settle()).then(|| {
        format!(
            "this table cannot hold the {} on a face (no energy tells a settled die from a rocking one)",
            params.die.kind.name()
        )
    })
}

impl OneRoll {
    /// Rolls `preset`'s initial condition on its setup to the end.
    pub fn run(preset: &Preset) -> Result<OneRoll, ParamError> {
        let params = preset.params();
        let mut roll = Roll::new(&params, &preset.initial)?;
        // Its time as every output prints it: the steps × Δt, not the clock's sum.
        let outcome = reported(roll.run_to_end(), &params);
        let reason =
            (outcome.status == Status::Unstable).then(|| UnstableReason::new(&params, &preset.initial));
        Ok(OneRoll {
            roll,
            outcome,
            reason,
        })
    }

    /// The roll as one JSON object (`dicesim roll --json`) of `preset`, which rolled it;
    /// `changed`: the preset was changed from its file (`--set`), as its provenance says.
    /// The final state's points are the box's `corner_offsets`, a die's `point_offsets`.
    pub fn json(&self, preset: &Preset, changed: bool) -> Value {
        let (roll, outcome) = (&self.roll, &self.outcome);
        let params = preset.params();
        // The rule this roll applied at its end: a loaded die's depends on the face down.
        let rule = roll.stop_rule_now();
        let stability = Verdict::of(&params, &preset.initial);
        let finite = |x: f64| x.is_finite().then_some(x);
        let unstable_reason = match (&self.reason, outcome.status) {
            (Some(r), _) => Some(json!({
                "limit": r.0.limit,
                "value": r.0.value,
                "allowed": r.0.allowed,
                "exceeded": r.0.exceeded(),
                "message": r.to_string(),
            })),
            (None, Status::Unstable) => Some(json!({
                "limit": stability.limit,
                "value": stability.value,
                "allowed": stability.allowed,
                "exceeded": stability.exceeded(),
                "message": format!("the energy ran away; {}", stability.words),
            })),
            _ => None,
        };
        let points = if roll.is_polyhedral() {
            "point_offsets"
        } else {
            "corner_offsets"
        };
        let mut last = json!({
            "position": roll.position().as_slice(),
            "velocity": roll.velocity().as_slice(),
            "angular_momentum": roll.angular_momentum().as_slice(),
            "angular_velocity": roll.angular_velocity().as_slice(),
            "energy": roll.energy(),
        });
        last[points] = json!(
            roll.point_offsets()
                .iter()
                .map(|r| [r.x, r.y, r.z])
                .collect::<Vec<_>>()
        );
        json!({
            "preset": preset.name,
            "face": outcome.face,
            "status": outcome.status,
            "steps": outcome.steps,
            "time_s": outcome.time_s,
            "unstable_reason": unstable_reason,
            "cannot_settle": why_it_cannot_settle_roll(roll),
            "energy_threshold": finite(rule.energy_threshold),
            "kinetic_threshold": finite(rule.kinetic_threshold),
            "stop_energy": roll.stop_energy(),
            "stop_kinetic_energy": roll.stop_kinetic_energy(),
            "stability_number": params.stability_number(),
            "stability": {
                "stable": !stability.exceeded(),
                "limit": stability.limit,
                "value": stability.value,
                "allowed": stability.allowed,
                "load": stability.load(),
            },
            "final": last,
            "params": params,
            "initial": preset.initial,
            "provenance": provenance::roll(preset, "the preset's roll", changed),
        })
    }
}
