//! `dicesim trace`: a roll's trajectory and energies as CSV.

use super::args::SetupArgs;
use super::error::CliError;
use clap::Args;
use dicesim_experiment::limits::TRACE_STEPS;
use dicesim_experiment::trace::{TraceWriter, columns_for, follow};
use dicesim_experiment::{data_file, provenance};
use dicesim_physics::Roll;
use std::io::Write;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub(crate) struct TraceArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// Run exactly N steps, even past the end of the roll (default: until the roll ends; at
    /// most 12000000 steps).
    #[arg(long, value_name = "N")]
    pub(crate) steps: Option<u64>,
    /// Print one row every K steps (the last step is always printed).
    #[arg(long, value_name = "K", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) every: u64,
    /// Write the trace to a .csv file instead of standard output, with its sidecar
    /// FILE.csv.meta.json naming the setup rolled and the program that rolled it.
    #[arg(long, value_name = "FILE.csv")]
    pub(crate) out: Option<PathBuf>,
    /// Replace an existing --out file (and its sidecar).
    #[arg(long, requires = "out")]
    pub(crate) force: bool,
}

pub(crate) fn run(args: &TraceArgs) -> Result<(), CliError> {
    if let Some(steps) = args.steps {
        TRACE_STEPS.check(steps).map_err(CliError::experiment(""))?;
    }
    let preset = args.setup.resolve()?;
    dicesim_setup::preset::refuse_unapplied(&args.setup.set, |key| {
        dicesim_setup::random::unapplied_when_fixed(key, "trace")
    })?;
    let params = preset.params();
    let roll = Roll::new(&params, &preset.initial)?;
    let Some(path) = &args.out else {
        return Ok(trace(args, roll, std::io::stdout().lock())?);
    };
    let output = super::args::checked_outputs(std::slice::from_ref(path), &["csv"], args.force)?.remove(0);
    // Half a trace is of no use: a stop signal removes the file being written and its sidecar.
    super::running::stop_at_once_on_signals()?;
    let rolled = provenance::roll(&preset, "the preset's roll", !args.setup.set.is_empty());
    let meta = data_file::sidecar(&rolled, &columns_for(&params));
    output
        .write_table(Some(&meta), |w| trace(args, roll, w))
        .map_err(CliError::output(""))
}

/// Writes the trace of `roll`, as `args` asks, to `out`.
fn trace(args: &TraceArgs, mut roll: Roll, out: impl Write) -> std::io::Result<()> {
    let mut out = TraceWriter::of(out, roll.params())?;
    follow(&mut roll, args.steps, args.every, &mut |roll| {
        out.write(roll).map(drop)
    })?;
    out.flush()
}
