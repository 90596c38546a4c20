//! `dicesim roll`: one roll from the initial condition.

use super::args::SetupArgs;
use super::error::CliError;
use clap::Args;
use dicesim_experiment::one_roll::OneRoll;
use dicesim_physics::why_it_cannot_settle;
use dicesim_physics::{InitialCondition, Outcome, Params, Simulation, Stability, Status, UnstableReason};
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
    let OneRoll { sim, outcome, reason } = OneRoll::run(&preset)?;
    let mut out = std::io::stdout().lock();
    if args.json {
        let rolled = OneRoll { sim, outcome, reason };
        writeln!(out, "{}", rolled.json(&preset, !args.setup.set.is_empty()))?;
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
