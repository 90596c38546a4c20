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
    // Exactly N steps (`--steps 0`: the start alone), or until the roll ends.
    let done = |sim: &Simulation| match args.steps {
        Some(n) => sim.state().step >= n,
        None => sim.outcome().is_some(),
    };
    while !done(&sim) {
        sim.advance();
        if sim.state().step % args.every == 0 || done(&sim) {
            out.write(&sim)?;
        }
    }
    out.flush()?;
    Ok(())
}
