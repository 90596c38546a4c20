//! `dicesim roll`: one roll from the initial condition.

use super::args::SetupArgs;
use super::error::CliError;
use clap::Args;
use dicesim_physics::why_it_cannot_settle;
use dicesim_physics::{InitialCondition, Outcome, Params, Simulation, Stability, Status, UnstableReason};
use dicesim_setup::preset::Preset;
use serde_json::json;
use std::io::Write;

#[derive(Debug, Args)]
pub(crate) struct RollArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub(crate) json: bool,
}

pub(crate) fn run(args: &RollArgs) -> Result<(), CliError> {
    let preset = args.setup.resolve()?;
    dicesim_setup::preset::refuse_unapplied(&args.setup.set, |key| {
        dicesim_setup::random::unapplied_when_fixed(key, "roll")
    })?;
    let params = preset.params();
    let mut sim = Simulation::new(&params, &preset.initial)?;
    // Its time as every output prints it: the steps × Δt, not the clock's sum.
    let outcome = dicesim_experiment::record::reported(sim.run_to_end(), &params);
    let reason = (outcome.status == Status::Unstable).then(|| UnstableReason::new(&params, &preset.initial));
    let mut out = std::io::stdout().lock();
    if args.json {
        let mut v = roll_json(&preset, &sim, &outcome, reason.as_ref());
        let changed = !args.setup.set.is_empty();
        v["provenance"] = dicesim_experiment::provenance::roll(&preset, "the preset's roll", changed);
        writeln!(out, "{v}")?;
    } else {
        print_roll(
            &mut out,
            (&params, &preset.initial),
            &sim,
            &outcome,
            reason.as_ref(),
        )?;
    }
    Ok(())
}

/// The roll as one JSON object: its ending, why it ended so, its stopping rule and
/// stability, its final state, and the setup.
fn roll_json(
    preset: &Preset,
    sim: &Simulation,
    outcome: &Outcome,
    reason: Option<&UnstableReason>,
) -> serde_json::Value {
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
        "unstable_reason": reason.map(|r| json!({
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
    })
}

/// The roll as text: its ending in words, then its steps, time, stopping energy and final
/// state.
fn print_roll(
    out: &mut impl Write,
    (params, initial): (&Params, &InitialCondition),
    sim: &Simulation,
    outcome: &Outcome,
    reason: Option<&UnstableReason>,
) -> std::io::Result<()> {
    let s = sim.state();
    let rule = sim.stop_rule_now();
    let verdict = match (outcome.status, outcome.face) {
        (Status::Settled, Some(f)) => format!("face {f} (settled)"),
        (Status::Settled, None) => "settled, but the 4 highest corners form no face".to_string(),
        (Status::Timeout, _) => match why_it_cannot_settle(params) {
            Some(why) => format!("did not settle within {} s: {why}", params.integrator.max_time),
            None => format!("did not settle within {} s", params.integrator.max_time),
        },
        (Status::Unstable, _) => format!("unstable: {}", reason.expect("an unstable roll has a reason")),
    };
    let v3 = |v: &nalgebra::Vector3<f64>| format!("({:.6}, {:.6}, {:.6})", v.x, v.y, v.z);
    writeln!(out, "{verdict}")?;
    // An unstable roll's verdict names the limit already; any other ending past one is not
    // what the model gives, however plain it looks.
    let stability = Stability::predict(params, initial).verdict();
    if stability.exceeded() && reason.is_none() {
        writeln!(
            out,
            "stability         past its limit, so this ending is the step's, not the model's: {stability}"
        )?;
    }
    writeln!(out, "steps             {}", outcome.steps)?;
    writeln!(out, "simulated time    {:.3} s", outcome.time_s)?;
    if rule.can_settle() {
        writeln!(
            out,
            "stop energy       {:.1} erg (threshold {:.1} erg, {}); kinetic {:.1} erg (threshold {:.1} erg)",
            sim.stop_energy(),
            rule.energy_threshold,
            params.integrator.stop_energy.name(),
            sim.stop_kinetic_energy(),
            rule.kinetic_threshold
        )?;
    } else {
        writeln!(
            out,
            "stop energy       {:.1} erg ({}; no threshold: this table cannot hold a face)",
            sim.stop_energy(),
            params.integrator.stop_energy.name()
        )?;
    }
    writeln!(out, "position          {} cm", v3(&s.position))?;
    writeln!(out, "velocity          {} cm/s", v3(&s.velocity))?;
    writeln!(out, "angular momentum  {} g·cm²/s", v3(&s.angular_momentum))?;
    Ok(())
}
