//! A sweep as a Slurm job array: one array task per shard, and a merge job that runs once
//! every shard has succeeded. [`JobArray::write`] checks every path and value the scripts
//! name, makes the sweep's folders and writes both scripts.

use crate::shard::PART_EXTENSION;
use dicesim_setup::output::{Output, OutputError};
use std::path::{Path, PathBuf};

/// Why the job scripts were not written.
#[derive(Debug, thiserror::Error)]
pub enum SlurmError {
    /// A value or path the scripts cannot hold, or a folder already in use: bad input.
    #[error("{0}")]
    Refused(String),
    /// The sweep's folders could not be made.
    #[error("{0}")]
    Failed(String),
    /// A script refused (it exists) or not written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// The folder could not be looked into.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

/// What each shard keeps, and so what the merge writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// The records as CSV: the merge writes the one-machine CSV (and a map's PNG).
    Csv,
    /// The records as Parquet (batches only): the merge writes the one-machine .parquet.
    Parquet,
    /// Only the counts: the merge prints the sweep's summary.
    Summary,
}

impl Keep {
    /// Refuses what a sweep of `kind` cannot keep: a map's cells are no roll records.
    pub fn check(self, kind: SweepKind) -> Result<(), String> {
        if kind == SweepKind::Map && self == Keep::Parquet {
            return Err("--format parquet holds roll records: a map's shards write .csv".to_string());
        }
        Ok(())
    }
}

/// The sweep's kind, as it decides file names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SweepKind {
    Batch,
    Map,
}

/// The values both jobs carry in `#SBATCH` lines, in Slurm's notation.
#[derive(Debug, Clone, Default)]
pub struct Directives {
    /// Wall-clock limit per job, e.g. `30`, `2:00:00`, `1-00:00:00`.
    pub time: Option<String>,
    /// Memory per job, e.g. `500M`.
    pub mem: Option<String>,
    pub partition: Option<String>,
    pub account: Option<String>,
}

impl Directives {
    /// Checks every value written into an `#SBATCH` line: sbatch reads these lines without
    /// a shell and without quoting, so whitespace would start another option (`--time
    /// '1:00:00 --wrap=x'`) and a line break another line of the script. Each value must
    /// also be in Slurm's own notation for it. The error names the option and the notation.
    pub fn check(&self) -> Result<(), String> {
        let time_ok = |v: &str| v.chars().all(|c| c.is_ascii_digit() || c == ':' || c == '-');
        let mem_ok = |v: &str| {
            let digits = v.trim_end_matches(['K', 'M', 'G', 'T', 'k', 'm', 'g', 't']);
            !digits.is_empty() && digits.len() + 1 >= v.len() && digits.chars().all(|c| c.is_ascii_digit())
        };
        let name_ok = |v: &str| v.chars().all(|c| c.is_ascii_alphanumeric() || "_-.,".contains(c));
        type Check<'a> = &'a dyn Fn(&str) -> bool;
        let names = "letters, digits, _ - . and , only";
        let values: [(&str, &Option<String>, Check<'_>, &str); 4] = [
            (
                "--time",
                &self.time,
                &time_ok,
                "minutes, or [D-]H:M:S, e.g. 30 or 2:00:00",
            ),
            (
                "--mem",
                &self.mem,
                &mem_ok,
                "a number and a unit K, M, G or T, e.g. 500M",
            ),
            ("--partition", &self.partition, &name_ok, names),
            ("--account", &self.account, &name_ok, names),
        ];
        for (flag, value, ok, expected) in values {
            let Some(v) = value else { continue };
            if v.is_empty() || !directive_safe(v) || !ok(v) {
                return Err(format!(
                    "{flag} `{}`: not a value for an #SBATCH line ({expected}; no spaces or control characters)",
                    v.escape_debug()
                ));
            }
        }
        Ok(())
    }
}

/// A sweep split into a job array.
#[derive(Debug, Clone)]
pub struct JobArray {
    /// The sweep's command line, a `batch` or `basin` one without the shard's own options.
    pub command: Vec<String>,
    pub kind: SweepKind,
    /// Shards, one per array task.
    pub shards: u64,
    /// CPUs per array task; each shard runs that many threads.
    pub cpus_per_task: u64,
    /// At most this many shards at once (`--array=…%M`).
    pub max_running: Option<u64>,
    pub keep: Keep,
    pub directives: Directives,
    /// The dicesim program the jobs run.
    pub dicesim: PathBuf,
    /// The sweep's folder (absolute): the scripts, `parts/`, `logs/` and the merged result.
    pub dir: PathBuf,
    /// The folder the jobs run in (absolute): where the command line's paths start.
    pub workdir: PathBuf,
}

/// The two job scripts and where the merged result lands.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Scripts {
    /// The array job's script, `shards.sbatch`.
    pub shards: String,
    /// The merge job's script, `merge.sbatch`.
    pub merge: String,
    pub result: PathBuf,
}

impl JobArray {
    /// Writes `shards.sbatch` and `merge.sbatch` into the sweep's folder (replacing earlier
    /// ones only with `force`), after checking, before anything is written, that the scripts
    /// can name every path as it is and that the folder holds no parts of another sweep; the
    /// folder, `parts/` and `logs/` are made if missing. Returns the scripts and their paths.
    pub fn write(&self, force: bool) -> Result<(Scripts, [PathBuf; 2]), SlurmError> {
        let refuse = |m: String| Err(SlurmError::Refused(m));
        self.keep.check(self.kind).map_err(SlurmError::Refused)?;
        if let Some(c) = self.dicesim.to_string_lossy().chars().find(|c| c.is_control()) {
            return refuse(format!(
                "--dicesim {}: a control character ({}) in a path a script runs",
                self.dicesim.display(),
                c.escape_unicode()
            ));
        }
        for (what, path) in [("--dir", &self.dir), ("the current folder", &self.workdir)] {
            if !directive_safe(&path.to_string_lossy()) {
                return refuse(format!(
                    "{what} {}: a path in an #SBATCH line may not hold spaces, control characters, quotes, backslashes or %",
                    path.display().to_string().escape_debug()
                ));
            }
        }
        if self.dir.exists() && !self.dir.is_dir() {
            return refuse(format!("--dir {}: not a folder", self.dir.display()));
        }
        let (parts, logs) = (self.dir.join("parts"), self.dir.join("logs"));
        let suffix = format!(".{PART_EXTENSION}");
        let stale = parts.is_dir()
            && std::fs::read_dir(&parts)?
                .filter_map(|e| e.ok())
                .any(|e| e.file_name().to_string_lossy().ends_with(&suffix));
        if stale {
            return refuse(format!(
                "{} already holds the parts of a sweep: choose another --dir, or remove them first",
                parts.display()
            ));
        }
        // What this call makes, so that a failure (a full disk) takes it away again: a sweep
        // folder left with empty parts/ and logs/ would look like a sweep set up.
        let mut made: Vec<&Path> = Vec::new();
        let paths = [self.dir.join("shards.sbatch"), self.dir.join("merge.sbatch")];
        let written = (|| {
            for d in [&self.dir, &parts, &logs] {
                if !d.exists() {
                    std::fs::create_dir_all(d)
                        .map_err(|e| SlurmError::Failed(format!("{}: {e}", d.display())))?;
                    made.push(d);
                }
            }
            let scripts = self.scripts();
            let [shards_out, merge_out] = paths
                .each_ref()
                .map(|path| Output::check(path, &["sbatch"], force));
            let (shards_out, merge_out) = (shards_out?, merge_out?);
            let new_shards = !paths[0].exists();
            shards_out.write_bytes(scripts.shards.as_bytes())?;
            if let Err(e) = merge_out.write_bytes(scripts.merge.as_bytes()) {
                if new_shards {
                    let _ = std::fs::remove_file(&paths[0]);
                }
                return Err(e.into());
            }
            Ok(scripts)
        })();
        match written {
            Ok(scripts) => Ok((scripts, paths)),
            Err(e) => {
                // Innermost first; a folder something else has filled meanwhile stays.
                for d in made.iter().rev() {
                    let _ = std::fs::remove_dir(d);
                }
                Err(e)
            }
        }
    }

    /// The two scripts' text.
    pub fn scripts(&self) -> Scripts {
        let q = |p: &Path| shell_word(&p.to_string_lossy());
        let name = self
            .dir
            .file_name()
            .map_or("sweep".into(), |s| s.to_string_lossy().into_owned());
        let name: String = name
            .chars()
            .map(|c| if directive_safe(&c.to_string()) { c } else { '_' })
            .collect();
        let job_name = format!("dicesim-{name}");
        let common = self.common_directives();
        let parts = self.dir.join("parts");
        let logs = self.dir.join("logs");
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
            last = self.shards - 1,
            throttle = self.max_running.map(|m| format!("%{m}")).unwrap_or_default(),
            cpus = self.cpus_per_task,
            logs = logs.display(),
            dicesim = q(&self.dicesim),
            sweep = self
                .command
                .iter()
                .map(|a| shell_word(a))
                .collect::<Vec<_>>()
                .join(" "),
            n = self.shards,
            keep = self.shard_keeps(&format!("{}/part-\"$k\"", q(&parts))),
        );
        let (result, outs) = self.merged();
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
            logs = logs.display(),
            dicesim = q(&self.dicesim),
            parts = q(&parts),
            summary = q(&self.dir.join("summary.txt")),
        );
        Scripts {
            shards,
            merge,
            result,
        }
    }

    /// The `#SBATCH` lines both jobs share. sbatch reads them itself, without a shell:
    /// their values stay unquoted (checked by [`Directives::check`]).
    fn common_directives(&self) -> String {
        let d = &self.directives;
        let mut common = format!("#SBATCH --chdir={}\n", self.workdir.display());
        for (option, value) in [
            ("time", &d.time),
            ("mem", &d.mem),
            ("partition", &d.partition),
            ("account", &d.account),
        ] {
            if let Some(v) = value {
                common.push_str(&format!("#SBATCH --{option}={v}\n"));
            }
        }
        common
    }

    /// The options by which a shard keeps its result, its files named from `part_stem`.
    fn shard_keeps(&self, part_stem: &str) -> String {
        match self.keep {
            Keep::Csv => format!("--out {part_stem}.csv"),
            Keep::Parquet => format!("--out {part_stem}.parquet"),
            Keep::Summary => format!("--part {part_stem}.{PART_EXTENSION}"),
        }
    }

    /// Where the merged result lands, and the merge's `--out` options that write it.
    fn merged(&self) -> (PathBuf, String) {
        let q = |p: &Path| shell_word(&p.to_string_lossy());
        let dir = &self.dir;
        match (self.kind, self.keep) {
            (_, Keep::Summary) => (dir.join("summary.txt"), String::new()),
            (SweepKind::Batch, Keep::Csv) => {
                let csv = dir.join("batch.csv");
                let outs = format!(" --out {}", q(&csv));
                (csv, outs)
            }
            (SweepKind::Batch, Keep::Parquet) => {
                let file = dir.join("batch.parquet");
                let outs = format!(" --out {}", q(&file));
                (file, outs)
            }
            (SweepKind::Map, _) => {
                let csv = dir.join("map.csv");
                let outs = format!(" --out {} --out {}", q(&csv), q(&dir.join("map.png")));
                (csv, outs)
            }
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
pub fn shell_word(s: &str) -> String {
    let safe = |c: char| c.is_ascii_alphanumeric() || "_-+=./:,@%^".contains(c);
    if !s.is_empty() && s.chars().all(safe) {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}

/// Submits `script` with `sbatch --parsable` and returns the job id.
pub fn sbatch(options: &[String], script: &Path) -> Result<String, String> {
    let output = std::process::Command::new("sbatch")
        .arg("--parsable")
        .args(options)
        .arg(script)
        .output()
        .map_err(|e| format!("cannot run sbatch (is Slurm installed here?): {e}"))?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    if !output.status.success() {
        return Err(format!(
            "sbatch {} failed: {}",
            script.display(),
            String::from_utf8_lossy(&output.stderr).trim()
        ));
    }
    // `--parsable` prints `id` or `id;cluster`.
    let id = stdout.trim().split(';').next().unwrap_or_default();
    if id.is_empty() || !id.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!("sbatch printed `{}`, not a job id", stdout.trim()));
    }
    Ok(id.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn array(command: &[&str], kind: SweepKind, keep: Keep) -> JobArray {
        JobArray {
            command: command.iter().map(|s| s.to_string()).collect(),
            kind,
            shards: 8,
            cpus_per_task: 1,
            max_running: None,
            keep,
            directives: Directives {
                time: Some("10:00".into()),
                ..Directives::default()
            },
            dicesim: PathBuf::from("/opt/my dicesim"),
            dir: PathBuf::from("/d/s"),
            workdir: PathBuf::from("/home/u"),
        }
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
        let a = array(
            &["batch", "--rolls", "40000", "--set", "ground.friction=0.3"],
            SweepKind::Batch,
            Keep::Csv,
        );
        let s = a.scripts();
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
    fn a_maps_merge_draws_it_and_a_summary_keeps_only_counts() {
        let map = array(&["basin"], SweepKind::Map, Keep::Csv).scripts();
        assert!(
            map.merge
                .contains(" merge /d/s/parts --out /d/s/map.csv --out /d/s/map.png > ")
        );
        let counts = array(&["basin"], SweepKind::Map, Keep::Summary).scripts();
        assert!(
            counts
                .shards
                .contains(" --part /d/s/parts/part-\"$k\".part.json\n")
        );
        assert_eq!(counts.result, Path::new("/d/s/summary.txt"));
        assert!(counts.merge.contains(" merge /d/s/parts > /d/s/summary.txt\n"));
    }

    #[test]
    fn directives_that_would_change_the_script_are_refused() {
        let with = |time: &str, mem: &str| Directives {
            time: Some(time.into()),
            mem: Some(mem.into()),
            ..Directives::default()
        };
        assert_eq!(with("1-00:00:00", "500M").check(), Ok(()));
        assert_eq!(
            with("1:00:00 --wrap=x", "1G").check().unwrap_err(),
            "--time `1:00:00 --wrap=x`: not a value for an #SBATCH line (minutes, or [D-]H:M:S, e.g. 30 or 2:00:00; no spaces or control characters)"
        );
        assert!(with("30", "5MB").check().unwrap_err().starts_with("--mem `5MB`"));
        assert!(with("30", "\n").check().unwrap_err().starts_with("--mem `\\n`"));
    }

    #[test]
    fn nothing_is_written_for_a_folder_that_holds_another_sweep() {
        let tmp = tempfile::tempdir().unwrap();
        let mut a = array(&["batch", "--rolls", "8"], SweepKind::Batch, Keep::Csv);
        a.dicesim = PathBuf::from("/opt/dicesim");
        (a.dir, a.workdir) = (tmp.path().join("sweep"), tmp.path().to_path_buf());
        let (_, [shards, merge]) = a.write(false).unwrap();
        assert!(shards.is_file() && merge.is_file() && a.dir.join("logs").is_dir());
        std::fs::write(a.dir.join("parts/part-0.part.json"), "{}").unwrap();
        let e = a.write(true).unwrap_err().to_string();
        assert!(e.ends_with(
            "/parts already holds the parts of a sweep: choose another --dir, or remove them first"
        ));
        a.keep = Keep::Parquet;
        a.kind = SweepKind::Map;
        assert_eq!(
            a.write(true).unwrap_err().to_string(),
            "--format parquet holds roll records: a map's shards write .csv"
        );
    }
}
