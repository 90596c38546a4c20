//! `dicesim slurm`: a sweep as a Slurm job array (one task per shard) and a merge job that
//! runs once every shard has succeeded.

use super::basin::{self, BasinArgs};
use super::batch::{self, BatchArgs};
use super::error::CliError;
use clap::{Args, ValueEnum};
use dicesim_experiment::shard::Shard;
use dicesim_experiment::slurm::{Directives, JobArray, Keep, SweepKind, sbatch, shell_word};
use std::io::Write;
use std::path::PathBuf;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum PartFormat {
    /// Each shard writes its records as CSV; the merge writes the one-machine CSV (and, for
    /// a map, its PNG).
    Csv,
    /// Each shard writes its records as Parquet; the merge writes the one-machine .parquet
    /// (batches only).
    Parquet,
    /// Shards keep only their counts; the merge prints the sweep's summary.
    Summary,
}

#[derive(Debug, Args)]
pub(crate) struct SlurmArgs {
    /// How many shards (array tasks) to split the sweep into.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub(crate) shards: u64,
    /// The folder for the scripts, the parts (`parts/`), the logs (`logs/`) and the merged
    /// result; created if missing. It must be on a file system the compute nodes share.
    #[arg(long, value_name = "DIR")]
    pub(crate) dir: PathBuf,
    /// CPUs per array task; each shard runs that many threads.
    #[arg(long, value_name = "C", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=4096))]
    pub(crate) cpus_per_task: u64,
    /// Wall-clock limit per job, in Slurm's notation (e.g. `30`, `2:00:00`, `1-00:00:00`).
    #[arg(long, value_name = "TIME")]
    pub(crate) time: Option<String>,
    /// Memory per job, in Slurm's notation (e.g. `500M`).
    #[arg(long, value_name = "MEM")]
    pub(crate) mem: Option<String>,
    /// The partition to run in.
    #[arg(long, value_name = "NAME")]
    pub(crate) partition: Option<String>,
    /// The account to charge.
    #[arg(long, value_name = "NAME")]
    pub(crate) account: Option<String>,
    /// Run at most M shards at once (Slurm's `--array=…%M`).
    #[arg(long, value_name = "M", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_running: Option<u64>,
    /// What the shards keep.
    #[arg(long, value_enum, default_value_t = PartFormat::Csv)]
    pub(crate) format: PartFormat,
    /// The dicesim program the jobs run (default: this one).
    #[arg(long, value_name = "PATH")]
    pub(crate) dicesim: Option<PathBuf>,
    /// Submit both jobs with `sbatch` (the merge with `--dependency=afterok` on the array).
    #[arg(long)]
    pub(crate) submit: bool,
    /// Replace the scripts of an earlier `dicesim slurm` in --dir.
    #[arg(long)]
    pub(crate) force: bool,
    /// The sweep, after `--`: a `batch` or `basin` command line without --shard, --out,
    /// --part or --jobs, e.g. `-- batch --rolls 1000000 --seed 7`.
    #[arg(last = true, required = true, value_name = "COMMAND")]
    pub(crate) command: Vec<String>,
}

/// Writes (and with `--submit` submits) the job scripts of the sweep `sweep`, the parse of
/// `args.command`.
pub(crate) fn run(args: &SlurmArgs, sweep: Result<SweepCommand, clap::Error>) -> Result<(), CliError> {
    // Everything is checked before anything is written: a refusal leaves no folder or file.
    let directives = Directives {
        time: args.time.clone(),
        mem: args.mem.clone(),
        partition: args.partition.clone(),
        account: args.account.clone(),
    };
    directives.check().map_err(CliError::Usage)?;
    let kind = check_command(&args.command, sweep, args.shards)?;
    let keep = match args.format {
        PartFormat::Csv => Keep::Csv,
        PartFormat::Parquet => Keep::Parquet,
        PartFormat::Summary => Keep::Summary,
    };
    keep.check(kind).map_err(CliError::Usage)?;
    let dicesim = match &args.dicesim {
        Some(p) => std::path::absolute(p)?,
        None => std::env::current_exe()
            .map_err(|e| CliError::Sweep(format!("cannot find this program's path (give --dicesim): {e}")))?,
    };
    let array = JobArray {
        command: args.command.clone(),
        kind,
        shards: args.shards,
        cpus_per_task: args.cpus_per_task,
        max_running: args.max_running,
        keep,
        directives,
        dicesim,
        dir: std::path::absolute(&args.dir)?,
        workdir: std::env::current_dir()?,
    };
    let (scripts, [shards_path, merge_path]) = array.write(args.force)?;
    let mut out = std::io::stdout().lock();
    let cpus = args.cpus_per_task;
    writeln!(
        out,
        "wrote      {} ({} array task{}, {cpus} CPU{} each)",
        shards_path.display(),
        args.shards,
        if args.shards == 1 { "" } else { "s" },
        if cpus == 1 { "" } else { "s" }
    )?;
    writeln!(
        out,
        "wrote      {} (runs after every shard succeeded)",
        merge_path.display()
    )?;
    if args.submit {
        let array = sbatch(&[], &shards_path).map_err(CliError::Sweep)?;
        let merge =
            sbatch(&[format!("--dependency=afterok:{array}")], &merge_path).map_err(CliError::Sweep)?;
        writeln!(out, "submitted  array job {array}")?;
        writeln!(out, "submitted  merge job {merge}")?;
        writeln!(out, "result     {}", scripts.result.display())?;
    } else {
        writeln!(
            out,
            "submit     jid=$(sbatch --parsable {}) && sbatch --dependency=afterok:\"${{jid%%;*}}\" {}",
            shell_word(&shards_path.to_string_lossy()),
            shell_word(&merge_path.to_string_lossy())
        )?;
    }
    Ok(())
}

/// The sweep's command line as dicesim parses its own (the parser is the command line's,
/// which names this command: it hands the parse in rather than being imported back).
pub(crate) enum SweepCommand {
    Batch(BatchArgs),
    Basin(BasinArgs),
    /// Any other command.
    Other,
}

/// Checks the sweep's command line, `sweep` as dicesim parsed it, and that it leaves the
/// shard's own options to the script.
fn check_command(
    command: &[String],
    sweep: Result<SweepCommand, clap::Error>,
    shards: u64,
) -> Result<SweepKind, CliError> {
    if let Some(a) = command.iter().find(|a| a.chars().any(char::is_control)) {
        return Err(CliError::Usage(format!(
            "the sweep's command line: `{}` holds a control character",
            a.escape_debug()
        )));
    }
    let sweep = sweep.map_err(|e| {
        CliError::Usage(format!(
            "the sweep's command line: {}",
            e.render().to_string().trim_end()
        ))
    })?;
    let (kind, owned) = match &sweep {
        SweepCommand::Batch(b) => (SweepKind::Batch, b.run.sets_a_shards_options()),
        SweepCommand::Basin(b) => (SweepKind::Map, b.run.sets_a_shards_options()),
        SweepCommand::Other => {
            return Err(CliError::Usage(
                "dicesim slurm runs a `batch` or a `basin` sweep: put its command line after `--`"
                    .to_string(),
            ));
        }
    };
    if owned {
        return Err(CliError::Usage(
            "the sweep's command line must leave --shard, --part, --out and --jobs to the script".to_string(),
        ));
    }
    // The whole sweep as an array task will check it, so a mistake is found now rather
    // than by every task exiting 2.
    let in_task = |e: CliError| CliError::Usage(format!("the sweep's command line: {e}"));
    match &sweep {
        SweepCommand::Batch(b) => {
            let first = Shard {
                index: 0,
                count: shards,
            };
            batch::check_sweep(b, Some(first)).map_err(in_task)?;
        }
        SweepCommand::Basin(b) => {
            let (preset, params, x, y) = basin::check_sweep(b, true).map_err(in_task)?;
            dicesim_experiment::basin::check_nodes(&params, &preset.initial, &x, &y)
                .map_err(|e| in_task(CliError::experiment("")(e)))?;
        }
        SweepCommand::Other => unreachable!("the kind was matched above"),
    }
    Ok(kind)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweeps_leave_the_shard_options_to_the_script() {
        let check = |c: &[&str]| {
            let command: Vec<String> = c.iter().map(|s| s.to_string()).collect();
            check_command(&command, crate::cli::command::parse_sweep(&command), 8)
        };
        let e = |c: &[&str]| check(c).unwrap_err().to_string();
        assert_eq!(
            e(&["batch", "--rolls", "5", "--out", "x.csv"]),
            "the sweep's command line must leave --shard, --part, --out and --jobs to the script"
        );
        assert_eq!(
            e(&["roll"]),
            "dicesim slurm runs a `batch` or a `basin` sweep: put its command line after `--`"
        );
        assert!(
            e(&["batch", "--rols", "5"])
                .starts_with("the sweep's command line: error: unexpected argument '--rols'")
        );
        let ok = |c: &[&str]| check(c).unwrap();
        assert_eq!(ok(&["batch", "--rolls", "5"]), SweepKind::Batch);
        assert_eq!(
            ok(&[
                "basin",
                "--x",
                "initial.height:5:20",
                "--y",
                "ground.friction:0.2:0.8"
            ]),
            SweepKind::Map
        );
    }
}
