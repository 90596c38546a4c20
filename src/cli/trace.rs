//! `dicesim trace`: a roll's trajectory and energies as CSV.

use super::{CliError, SetupArgs};
use crate::physics::Simulation;
use clap::Args;
use std::fmt::Write as _;
use std::io::Write;

#[derive(Debug, Args)]
pub struct TraceArgs {
    #[command(flatten)]
    pub setup: SetupArgs,
    /// Run exactly N steps, even past the end of the roll (default: until the roll ends).
    #[arg(long, value_name = "N")]
    pub steps: Option<u64>,
    /// Print one row every K steps (the last step is always printed).
    #[arg(long, value_name = "K", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub every: u64,
}

/// The CSV header; the corner columns follow MODEL.md's corner order.
pub fn header() -> String {
    let mut h =
        String::from("step,t,x,y,z,vx,vy,vz,Lx,Ly,Lz,wx,wy,wz,e_trans,e_rot,e_grav,e_elastic,e_total");
    for k in 1..=8 {
        let _ = write!(h, ",c{k}x,c{k}y,c{k}z");
    }
    h
}

/// One CSV row for the simulation's current state.
pub fn row(sim: &Simulation) -> String {
    let s = sim.state();
    let e = sim.energy();
    let w = sim.angular_velocity();
    let mut line = format!("{},{}", s.step, s.time_s);
    let values = s
        .position
        .iter()
        .chain(s.velocity.iter())
        .chain(s.angular_momentum.iter())
        .chain(w.iter());
    for v in values.copied().chain([
        e.translational,
        e.rotational,
        e.gravitational,
        e.elastic,
        e.total(),
    ]) {
        let _ = write!(line, ",{v}");
    }
    for p in sim.corner_positions() {
        let _ = write!(line, ",{},{},{}", p.x, p.y, p.z);
    }
    line
}

pub fn run(args: &TraceArgs) -> Result<(), CliError> {
    let preset = args.setup.resolve()?;
    let mut sim =
        Simulation::new(&preset.params(), &preset.initial).map_err(|e| CliError::Input(e.to_string()))?;
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    writeln!(out, "{}", header())?;
    writeln!(out, "{}", row(&sim))?;
    loop {
        let ended = sim.advance().is_some();
        let step = sim.state().step;
        let last = match args.steps {
            Some(n) => step >= n,
            None => ended,
        };
        if step % args.every == 0 || last {
            writeln!(out, "{}", row(&sim))?;
        }
        if last || (args.steps.is_none() && sim.outcome().is_some()) {
            break;
        }
    }
    out.flush()?;
    Ok(())
}
