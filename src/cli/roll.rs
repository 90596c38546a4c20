//! `dicesim roll`: one roll from the initial condition.

use super::args::SetupArgs;
use super::error::CliError;
use crate::tables;
use clap::Args;
use dicesim_experiment::one_roll::OneRoll;
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
    let rolled = OneRoll::run(&preset)?;
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", rolled.json(&preset, !args.setup.set.is_empty()))?;
    } else {
        tables::one_roll(&mut out, (&params, &preset.initial), &rolled)?;
    }
    Ok(())
}
