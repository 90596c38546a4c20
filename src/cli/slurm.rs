//! `dicesim slurm`: a sweep as a Slurm job array (one task per shard) and a merge job that
//! runs once every shard has succeeded.

use super::shard::PART_EXTENSION;
use super::{Cli, CliError, Command};
use clap::{Args, Parser, ValueEnum};
use dicesim_experiment::shard::Shard;
use dicesim_setup::output::Output;
use std::io::Write;
use std::path::{Path, PathBuf};

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

/// The sweep's kind, as it decides file names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Batch,
    Map,
}

pub(crate) fn run(args: &SlurmArgs) -> Result<(), CliError> {
    // Everything is checked before anything is written: a refusal leaves no folder or file.
    check_directives(args)?;
    let kind = check_command(&args.command, args.shards)?;
    if kind == Kind::Map && args.format == PartFormat::Parquet {
        return Err(CliError::Usage(
            "--format parquet holds roll records: a map's shards write .csv".to_string(),
        ));
    }
    let dicesim = match &args.dicesim {
        Some(p) => std::path::absolute(p)?,
        None => std::env::current_exe()
            .map_err(|e| CliError::Sweep(format!("cannot find this program's path (give --dicesim): {e}")))?,
    };
    if let Some(c) = dicesim.to_string_lossy().chars().find(|c| c.is_control()) {
        return Err(CliError::Usage(format!(
            "--dicesim {}: a control character ({}) in a path a script runs",
            dicesim.display(),
            c.escape_unicode()
        )));
    }
    let dir = std::path::absolute(&args.dir)?;
    let workdir = std::env::current_dir()?;
    for (what, path) in [("--dir", &dir), ("the current folder", &workdir)] {
        if !directive_safe(&path.to_string_lossy()) {
            return Err(CliError::Usage(format!(
                "{what} {}: a path in an #SBATCH line may not hold spaces, control characters, quotes, backslashes or %",
                path.display().to_string().escape_debug()
            )));
        }
    }
    if dir.exists() && !dir.is_dir() {
        return Err(CliError::Usage(format!("--dir {}: not a folder", dir.display())));
    }
    let parts = dir.join("parts");
    let logs = dir.join("logs");
    let suffix = format!(".{PART_EXTENSION}");
    let stale = parts.is_dir()
        && std::fs::read_dir(&parts)?
            .filter_map(|e| e.ok())
            .any(|e| e.file_name().to_string_lossy().ends_with(&suffix));
    if stale {
        return Err(CliError::Usage(format!(
            "{} already holds the parts of a sweep: choose another --dir, or remove them first",
            parts.display()
        )));
    }
    for d in [&dir, &parts, &logs] {
        std::fs::create_dir_all(d).map_err(|e| CliError::Sweep(format!("{}: {e}", d.display())))?;
    }
    let scripts = Scripts::new(args, kind, &dicesim, &dir, &workdir);
    let shards_path = dir.join("shards.sbatch");
    let merge_path = dir.join("merge.sbatch");
    let outputs = [&shards_path, &merge_path]
        .map(|path| Output::check(path, &["sbatch"], args.force).map_err(CliError::output("")));
    let [shards_out, merge_out] = outputs;
    let (shards_out, merge_out) = (shards_out?, merge_out?);
    for (output, text) in [(&shards_out, &scripts.shards), (&merge_out, &scripts.merge)] {
        output
            .write_bytes(text.as_bytes())
            .map_err(CliError::output(""))?;
    }
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
        let array = sbatch(&[], &shards_path)?;
        let merge = sbatch(&[format!("--dependency=afterok:{array}")], &merge_path)?;
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

/// Checks every value written into an `#SBATCH` line: sbatch reads these lines without a
/// shell and without quoting, so whitespace would start another option (`--time '1:00:00
/// --wrap=x'`) and a line break another line of the script. Each value must also be in
/// Slurm's own notation for it.
fn check_directives(args: &SlurmArgs) -> Result<(), CliError> {
    let time_ok = |v: &str| v.chars().all(|c| c.is_ascii_digit() || c == ':' || c == '-');
    let mem_ok = |v: &str| {
        let digits = v.trim_end_matches(['K', 'M', 'G', 'T', 'k', 'm', 'g', 't']);
        !digits.is_empty() && digits.len() + 1 >= v.len() && digits.chars().all(|c| c.is_ascii_digit())
    };
    let name_ok = |v: &str| v.chars().all(|c| c.is_ascii_alphanumeric() || "_-.,".contains(c));
    type Check<'a> = &'a dyn Fn(&str) -> bool;
    let values: [(&str, &Option<String>, Check<'_>, &str); 4] = [
        (
            "--time",
            &args.time,
            &time_ok,
            "minutes, or [D-]H:M:S, e.g. 30 or 2:00:00",
        ),
        (
            "--mem",
            &args.mem,
            &mem_ok,
            "a number and a unit K, M, G or T, e.g. 500M",
        ),
        (
            "--partition",
            &args.partition,
            &name_ok,
            "letters, digits, _ - . and , only",
        ),
        (
            "--account",
            &args.account,
            &name_ok,
            "letters, digits, _ - . and , only",
        ),
    ];
    for (flag, value, ok, expected) in values {
        let Some(v) = value else { continue };
        if v.is_empty() || !directive_safe(v) || !ok(v) {
            return Err(CliError::Usage(format!(
                "{flag} `{}`: not a value for an #SBATCH line ({expected}; no spaces or control characters)",
                v.escape_debug()
            )));
        }
    }
    Ok(())
}

/// Checks the sweep's command line as dicesim would parse it, and that it leaves the shard's
/// own options to the script.
fn check_command(command: &[String], shards: u64) -> Result<Kind, CliError> {
    if let Some(a) = command.iter().find(|a| a.chars().any(char::is_control)) {
        return Err(CliError::Usage(format!(
            "the sweep's command line: `{}` holds a control character",
            a.escape_debug()
        )));
    }
    let cli = Cli::try_parse_from(std::iter::once("dicesim").chain(command.iter().map(String::as_str)))
        .map_err(|e| {
            CliError::Usage(format!(
                "the sweep's command line: {}",
                e.render().to_string().trim_end()
            ))
        })?;
    let (kind, owned) = match &cli.command {
        Some(Command::Batch(b)) => (
            Kind::Batch,
            b.out.is_some() || b.jobs.is_some() || b.shard.shard.is_some() || b.shard.part.is_some(),
        ),
        Some(Command::Basin(b)) => (
            Kind::Map,
            b.out.is_some() || b.jobs.is_some() || b.shard.shard.is_some() || b.shard.part.is_some(),
        ),
        _ => {
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
    match &cli.command {
        Some(Command::Batch(b)) => {
            super::batch::check_sweep(
                b,
                Some(Shard {
                    index: 0,
                    count: shards,
                }),
            )
            .map_err(in_task)?;
        }
        Some(Command::Basin(b)) => {
            super::basin::check_sweep(b, true).map_err(in_task)?;
        }
        _ => unreachable!("the kind was matched above"),
    }
    Ok(kind)
}

/// Submits `script` with `sbatch --parsable` and returns the job id.
fn sbatch(options: &[String], script: &Path) -> Result<String, CliError> {
    let output = std::process::Command::new("sbatch")
        .arg("--parsable")
        .args(options)
        .arg(script)
        .output()
        .map_err(|e| CliError::Sweep(format!("cannot run sbatch (is Slurm installed here?): {e}")))?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    if !output.status.success() {
        return Err(CliError::Sweep(format!(
            "sbatch {} failed: {}",
            script.display(),
            String::from_utf8_lossy(&output.stderr).trim()
        )));
    }
    // `--parsable` prints `id` or `id;cluster`.
    let id = stdout.trim().split(';').next().unwrap_or_default();
    if id.is_empty() || !id.bytes().all(|b| b.is_ascii_digit()) {
        return Err(CliError::Sweep(format!(
            "sbatch printed `{}`, not a job id",
            stdout.trim()
        )));
    }
    Ok(id.to_string())
}

/// The two job scripts and where the merged result lands.
struct Scripts {
    shards: String,
    merge: String,
    result: PathBuf,
}

impl Scripts {
    fn new(args: &SlurmArgs, kind: Kind, dicesim: &Path, dir: &Path, workdir: &Path) -> Scripts {
        let q = |p: &Path| shell_word(&p.to_string_lossy());
        let n = args.shards;
        let name = dir
            .file_name()
            .map_or("sweep".into(), |s| s.to_string_lossy().into_owned());
        let name: String = name
            .chars()
            .map(|c| if directive_safe(&c.to_string()) { c } else { '_' })
            .collect();
        let job_name = format!("dicesim-{name}");
        // sbatch reads #SBATCH lines itself, without a shell: their values stay unquoted.
        let mut common = String::new();
        common.push_str(&format!("#SBATCH --chdir={}\n", workdir.display()));
        for (option, value) in [
            ("time", &args.time),
            ("mem", &args.mem),
            ("partition", &args.partition),
            ("account", &args.account),
        ] {
            if let Some(v) = value {
                common.push_str(&format!("#SBATCH --{option}={v}\n"));
            }
        }
        let sweep: Vec<String> = args.command.iter().map(|a| shell_word(a)).collect();
        let sweep = sweep.join(" ");
        let parts = dir.join("parts");
        let part_stem = format!("{}/part-\"$k\"", q(&parts));
        let keep = match args.format {
            PartFormat::Csv => format!("--out {part_stem}.csv"),
            PartFormat::Parquet => format!("--out {part_stem}.parquet"),
            PartFormat::Summary => format!("--part {part_stem}.{PART_EXTENSION}"),
        };
        let throttle = args.max_running.map(|m| format!("%{m}")).unwrap_or_default();
        let shards = format!(
            "#!/bin/bash\n\
             # One shard of a dicesim sweep per array task; written by `dicesim slurm`.\n\
             #SBATCH --job-name={job_name}\n\
             #SBATCH --array=0-{last}{throttle}\n\
             #SBATCH --ntasks=1\n\
             #SBATCH --cpus-per-task={cpus}\n\
             #SBATCH --output={logs}/shard-%A_%a.out\n\
             {common}\
             set -euo pipefail\n\
             k=\"$SLURM_ARRAY_TASK_ID\"\n\
             exec {dicesim} {sweep} --jobs \"${{SLURM_CPUS_PER_TASK:-{cpus}}}\" --shard \"$k/{n}\" {keep}\n",
            last = n - 1,
            cpus = args.cpus_per_task,
            logs = dir.join("logs").display(),
            dicesim = q(dicesim),
        );
        let (result, outs) = match (kind, args.format) {
            (_, PartFormat::Summary) => (dir.join("summary.txt"), String::new()),
            (Kind::Batch, PartFormat::Csv) => {
                let csv = dir.join("batch.csv");
                (csv.clone(), format!(" --out {}", q(&csv)))
            }
            (Kind::Batch, PartFormat::Parquet) => {
                let file = dir.join("batch.parquet");
                (file.clone(), format!(" --out {}", q(&file)))
            }
            (Kind::Map, _) => {
                let csv = dir.join("map.csv");
                (
                    csv.clone(),
                    format!(" --out {} --out {}", q(&csv), q(&dir.join("map.png"))),
                )
            }
        };
        let merge = format!(
            "#!/bin/bash\n\
             # Merges the shards of a dicesim sweep once all have succeeded; written by `dicesim slurm`.\n\
             #SBATCH --job-name={job_name}-merge\n\
             #SBATCH --ntasks=1\n\
             #SBATCH --cpus-per-task=1\n\
             #SBATCH --output={logs}/merge-%j.out\n\
             {common}\
             set -euo pipefail\n\
             {dicesim} merge {parts}{outs} > {summary}\n\
             cat {summary}\n",
            logs = dir.join("logs").display(),
            dicesim = q(dicesim),
            parts = q(&parts),
            summary = q(&dir.join("summary.txt")),
        );
        Scripts {
            shards,
            merge,
            result,
        }
    }
}

/// Whether sbatch reads `s` in an #SBATCH line as it is (no quoting there; `%` is a
/// file-name pattern).
fn directive_safe(s: &str) -> bool {
    !s.chars()
        .any(|c| c.is_whitespace() || c.is_control() || "'\"\\%".contains(c))
}

/// `s` as one word of a shell command: as it is when only safe characters, else in single
/// quotes.
fn shell_word(s: &str) -> String {
    let safe = |c: char| c.is_ascii_alphanumeric() || "_-+=./:,@%^".contains(c);
    if !s.is_empty() && s.chars().all(safe) {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(command: &[&str]) -> SlurmArgs {
        let mut argv = vec!["slurm", "--shards", "8", "--dir", "/d/s", "--time", "10:00", "--"];
        argv.extend(command);
        #[derive(Parser)]
        struct Wrap {
            #[command(flatten)]
            a: SlurmArgs,
        }
        Wrap::parse_from(argv).a
    }

    #[test]
    fn shell_words_survive_the_shell() {
        assert_eq!(shell_word("--rolls"), "--rolls");
        assert_eq!(
            shell_word("initial.angular_velocity.x:-60:60"),
            "initial.angular_velocity.x:-60:60"
        );
        assert_eq!(shell_word("a b"), "'a b'");
        assert_eq!(shell_word("it's"), r"'it'\''s'");
        assert_eq!(shell_word(""), "''");
        assert_eq!(shell_word("$HOME"), "'$HOME'");
    }

    #[test]
    fn array_script_runs_one_shard_per_task() {
        let a = args(&["batch", "--rolls", "40000", "--set", "ground.friction=0.3"]);
        let s = Scripts::new(
            &a,
            Kind::Batch,
            Path::new("/opt/my dicesim"),
            Path::new("/d/s"),
            Path::new("/home/u"),
        );
        assert_eq!(
            s.shards,
            "#!/bin/bash\n\
             # One shard of a dicesim sweep per array task; written by `dicesim slurm`.\n\
             #SBATCH --job-name=dicesim-s\n\
             #SBATCH --array=0-7\n\
             #SBATCH --ntasks=1\n\
             #SBATCH --cpus-per-task=1\n\
             #SBATCH --output=/d/s/logs/shard-%A_%a.out\n\
             #SBATCH --chdir=/home/u\n\
             #SBATCH --time=10:00\n\
             set -euo pipefail\n\
             k=\"$SLURM_ARRAY_TASK_ID\"\n\
             exec '/opt/my dicesim' batch --rolls 40000 --set ground.friction=0.3 --jobs \"${SLURM_CPUS_PER_TASK:-1}\" --shard \"$k/8\" --out /d/s/parts/part-\"$k\".csv\n"
        );
        assert!(
            s.merge
                .contains("\n'/opt/my dicesim' merge /d/s/parts --out /d/s/batch.csv > /d/s/summary.txt\n")
        );
        assert!(s.merge.contains("\n#SBATCH --output=/d/s/logs/merge-%j.out\n"));
        assert_eq!(s.result, Path::new("/d/s/batch.csv"));
        assert!(directive_safe("/scratch/u/run-1"));
        assert!(!directive_safe("/scratch/my run") && !directive_safe("/a%b") && !directive_safe("/a'b"));
    }

    #[test]
    fn sweeps_leave_the_shard_options_to_the_script() {
        let e = |c: &[&str]| {
            check_command(&c.iter().map(|s| s.to_string()).collect::<Vec<_>>(), 8)
                .unwrap_err()
                .to_string()
        };
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
        let ok = |c: &[&str]| check_command(&c.iter().map(|s| s.to_string()).collect::<Vec<_>>(), 8).unwrap();
        assert_eq!(ok(&["batch", "--rolls", "5"]), Kind::Batch);
        assert_eq!(
            ok(&[
                "basin",
                "--x",
                "initial.height:5:20",
                "--y",
                "ground.friction:0.2:0.8"
            ]),
            Kind::Map
        );
    }
}
