//! `dicesim roll`: one roll from the initial condition.

use super::{CliError, SetupArgs};
use clap::Args;
use dicesim_physics::why_it_cannot_settle;
use dicesim_physics::{Simulation, Stability, Status, UnstableReason};
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
    let params = preset.params();
    let mut sim = Simulation::new(&params, &preset.initial)?;
    let outcome = sim.run_to_end();
    let s = sim.state();
    let energy = sim.energy();
    // The rule this roll applied at its end: a loaded die's depends on the face down.
    let rule = sim.stop_rule_now();
    let stability = Stability::predict(&params, &preset.initial).verdict();
    let reason = (outcome.status == Status::Unstable).then(|| UnstableReason::new(&params, &preset.initial));
    let cannot_settle = why_it_cannot_settle(&params);
    let finite = |x: f64| x.is_finite().then_some(x);
    let mut out = std::io::stdout().lock();
    if args.json {
        let v = json!({
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
            "cannot_settle": cannot_settle,
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
                "energy": energy,
                "corner_offsets": s.corner_offsets.iter().map(|r| [r.x, r.y, r.z]).collect::<Vec<_>>(),
            },
            "params": params,
            "initial": preset.initial,
        });
        writeln!(out, "{v}")?;
    } else {
        let verdict = match (outcome.status, outcome.face) {
            (Status::Settled, Some(f)) => format!("face {f} (settled)"),
            (Status::Settled, None) => "settled, but the 4 highest corners form no face".to_string(),
            (Status::Timeout, _) => match &cannot_settle {
                Some(why) => format!("did not settle within {} s: {why}", params.integrator.max_time),
                None => format!("did not settle within {} s", params.integrator.max_time),
            },
            (Status::Unstable, _) => format!("unstable: {}", reason.expect("an unstable roll has a reason")),
        };
        let v3 = |v: &nalgebra::Vector3<f64>| format!("({:.6}, {:.6}, {:.6})", v.x, v.y, v.z);
        writeln!(out, "{verdict}")?;
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
    }
    Ok(())
}
