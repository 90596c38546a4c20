//! `dicesim trace`: a roll's trajectory and energies as CSV.

use super::args::SetupArgs;
use super::error::CliError;
use clap::Args;
use dicesim_experiment::trace::TraceWriter;
use dicesim_physics::Simulation;

#[derive(Debug, Args)]
pub(crate) struct TraceArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Run exactly N steps, even past the end of the roll (default: until the roll ends).
    #[arg(long, value_name = "N")]
    pub(crate) steps: Option<u64>,
    /// Print one row every K steps (the last step is always printed).
    #[arg(long, value_name = "K", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) every: u64,
}

pub(crate) fn run(args: &TraceArgs) -> Result<(), CliError> {
    let preset = args.setup.resolve()?;
    let mut sim = Simulation::new(&preset.params(), &preset.initial)?;
    let mut out = TraceWriter::new(std::io::stdout().lock())?;
    out.write(&sim)?;
    loop {
        let ended = sim.advance().is_some();
        let step = sim.state().step;
        let last = match args.steps {
            Some(n) => step >= n,
            None => ended,
        };
        if step % args.every == 0 || last {
            out.write(&sim)?;
        }
        if last || (args.steps.is_none() && sim.outcome().is_some()) {
            break;
        }
    }
    out.flush()?;
    Ok(())
}
