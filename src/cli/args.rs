//! The arguments several commands share: the setup (`--preset`, `--set`), and the options
//! of a long experiment (`--jobs`, `--out`, `--force`, `--json`, `--shard`, `--part`,
//! `--engine`), declared once and worded by each command for what it writes.

use super::error::CliError;
use clap::builder::EnumValueParser;
use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches, ValueEnum, value_parser};
use dicesim_experiment::shard::{PART_EXTENSION, Shard};
use dicesim_experiment::{Engine, RunOptions};
use dicesim_setup::output::{Output, check_apart};
use dicesim_setup::preset::{Preset, Store};
use std::marker::PhantomData;
use std::path::{Path, PathBuf};

/// The setup every simulating command starts from.
#[derive(Debug, Clone, Default, Args)]
pub(crate) struct SetupArgs {
    /// Start from this preset: a name (the user's folder, then the shipped set) or a path
    /// to a `.toml` file. Without it, the shipped `paper` preset.
    #[arg(long, value_name = "NAME|PATH")]
    pub(crate) preset: Option<String>,
    /// Override one preset value, e.g. `ground.stiffness=600000`,
    /// `initial.angular_velocity=[10,0,3]` or `initial.velocity.y=25` (repeatable, applied
    /// in order).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub(crate) set: Vec<String>,
}

impl SetupArgs {
    /// The preset with every override applied and validated.
    pub(crate) fn resolve(&self) -> Result<Preset, CliError> {
        let (preset, _) = Store::from_env().load_or_default(self.preset.as_deref())?;
        with_overrides(&preset, "--set", &self.set)
    }
}

/// `preset` with `overrides` applied, each note of what they did beyond setting a key (the
/// keys a law switch dropped) said on standard error after the option they came from.
pub(crate) fn with_overrides(
    preset: &Preset,
    option: &str,
    overrides: &[String],
) -> Result<Preset, CliError> {
    let (preset, notes) = preset.with_overrides_noted(overrides)?;
    for note in notes {
        eprintln!("dicesim: note: {option} {note}");
    }
    Ok(preset)
}

/// `--engine`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum EngineArg {
    /// The lane engine where the CPU has AVX2, else the scalar one.
    Auto,
    /// One roll after another.
    Scalar,
    /// Four rolls per AVX2 vector (the scalar engine on CPUs without AVX2).
    Lanes,
}

impl EngineArg {
    fn engine(self) -> Engine {
        match self {
            EngineArg::Auto => Engine::Auto,
            EngineArg::Scalar => Engine::Scalar,
            EngineArg::Lanes => Engine::Lanes,
        }
    }
}

/// `--shard K/N` and `--part` of a sweep (`batch`, `basin`).
#[derive(Debug, Clone, Default, Args)]
pub(crate) struct ShardArgs {
    /// Roll only shard K of N (K from 0): ids ⌊K·R/N⌋ up to ⌊(K+1)·R/N⌋ of the same R rolls
    /// (rows of a map); `dicesim merge` puts the N parts back into the one-machine result.
    #[arg(long, value_name = "K/N", value_parser = Shard::parse)]
    pub(crate) shard: Option<Shard>,
    /// Where the shard's summary for `dicesim merge` goes (default: --out with the extension
    /// `.part.json`). Without --out the shard keeps only this summary: its counts.
    #[arg(long, value_name = "FILE.part.json", requires = "shard")]
    pub(crate) part: Option<PathBuf>,
}

/// How a command words the options of [`RunArgs`] in its help, and which it has: what does
/// not depend on the threads or the engine, and what its files hold. Each text is that
/// option's help as a doc comment gives it (clap drops a one-paragraph comment's period).
pub(crate) struct Wording {
    pub(crate) jobs: &'static str,
    pub(crate) out: &'static str,
    pub(crate) out_value: &'static str,
    /// Whether `--out` may be given once per file (else once).
    pub(crate) repeatable: bool,
    pub(crate) force: &'static str,
    /// `None`: the command prints text only, and has no `--json`.
    pub(crate) json: Option<&'static str>,
    /// Whether the command is a sweep that `--shard` splits ([`ShardArgs`]).
    pub(crate) sharded: bool,
    pub(crate) engine: &'static str,
}

/// A command's [`Wording`] of its [`RunArgs`].
pub(crate) trait Worded {
    const WORDING: Wording;
}

/// The options of a long experiment, in the order its help lists them: threads, outputs,
/// `--json`, the shard of a sweep, the engine.
#[derive(Debug)]
pub(crate) struct RunArgs<W> {
    pub(crate) jobs: Option<u64>,
    pub(crate) out: Vec<PathBuf>,
    pub(crate) force: bool,
    /// Always false where the command has no `--json`.
    pub(crate) json: bool,
    /// Never set where the command is not a sweep.
    pub(crate) shard: ShardArgs,
    pub(crate) engine: EngineArg,
    wording: PhantomData<W>,
}

impl<W: Worded> Args for RunArgs<W> {
    fn augment_args(cmd: Command) -> Command {
        let w = &W::WORDING;
        let out_action = if w.repeatable {
            ArgAction::Append
        } else {
            ArgAction::Set
        };
        let mut cmd = cmd
            .arg(
                flag("jobs", w.jobs)
                    .action(ArgAction::Set)
                    .value_name("J")
                    .value_parser(value_parser!(u64).range(1..)),
            )
            .arg(
                flag("out", w.out)
                    .action(out_action)
                    .value_name(w.out_value)
                    .value_parser(value_parser!(PathBuf)),
            )
            .arg(flag("force", w.force).action(ArgAction::SetTrue));
        if let Some(json) = w.json {
            cmd = cmd.arg(flag("json", json).action(ArgAction::SetTrue));
        }
        if w.sharded {
            cmd = ShardArgs::augment_args(cmd);
        }
        cmd.arg(
            flag("engine", w.engine)
                .action(ArgAction::Set)
                .value_name("ENGINE")
                .value_parser(EnumValueParser::<EngineArg>::new())
                .default_value("auto"),
        )
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

/// The option `--{id}` with `help`.
fn flag(id: &'static str, help: &'static str) -> Arg {
    Arg::new(id).long(id).help(help)
}

impl<W: Worded> FromArgMatches for RunArgs<W> {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let w = &W::WORDING;
        Ok(RunArgs {
            jobs: m.get_one::<u64>("jobs").copied(),
            out: m
                .get_many::<PathBuf>("out")
                .into_iter()
                .flatten()
                .cloned()
                .collect(),
            force: m.get_flag("force"),
            json: w.json.is_some() && m.get_flag("json"),
            shard: if w.sharded {
                ShardArgs::from_arg_matches(m)?
            } else {
                ShardArgs::default()
            },
            engine: *m.get_one::<EngineArg>("engine").expect("--engine has a default"),
            wording: PhantomData,
        })
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl<W> RunArgs<W> {
    /// How the rolls run: `--jobs` checked against [`max_jobs`], and the engine.
    pub(crate) fn options(&self) -> Result<RunOptions, CliError> {
        Ok(RunOptions {
            jobs: checked_jobs(self.jobs)?,
            engine: self.engine.engine(),
        })
    }

    /// The `--out` path of a command that writes one file, as given.
    pub(crate) fn out_path(&self) -> Option<&Path> {
        self.out.first().map(PathBuf::as_path)
    }

    /// The one `--out` file of a command that writes one, checked before any work.
    pub(crate) fn output(&self, extensions: &[&str]) -> Result<Option<Output>, CliError> {
        self.out
            .first()
            .map(|p| Output::check(p, extensions, self.force))
            .transpose()
            .map_err(CliError::output("--out "))
    }

    /// Every `--out` file of a command that writes several.
    pub(crate) fn outputs(&self, extensions: &[&str]) -> Result<Vec<Output>, CliError> {
        checked_outputs(&self.out, extensions, self.force)
    }

    /// Whether any option a Slurm script gives each shard is set.
    pub(crate) fn sets_a_shards_options(&self) -> bool {
        !self.out.is_empty() || self.jobs.is_some() || self.shard.shard.is_some() || self.shard.part.is_some()
    }

    /// The shard to roll and where its summary goes (checked like any output: an existing
    /// summary is replaced only with `--force`), or `None` for a whole run.
    pub(crate) fn sharding(&self) -> Result<Option<(Shard, Output)>, CliError> {
        let Some(shard) = self.shard.shard else {
            return Ok(None);
        };
        let out = self.out_path();
        let part = match (&self.shard.part, out) {
            (Some(part), _) => part.clone(),
            (None, Some(out)) => out.with_extension(PART_EXTENSION),
            (None, None) => {
                return Err(CliError::Usage(
                    "--shard needs --out (the shard's records) or --part (only its summary)".to_string(),
                ));
            }
        };
        if out == Some(part.as_path()) {
            return Err(CliError::Usage(format!(
                "--part {} would overwrite the records of --out",
                part.display()
            )));
        }
        let part = Output::check(&part, &["json"], self.force).map_err(CliError::output("--part "))?;
        Ok(Some((shard, part)))
    }
}

/// `--jobs J` checked against [`max_jobs`] (more than a few threads per core only adds
/// switching); no value means one thread per core.
fn checked_jobs(jobs: Option<u64>) -> Result<usize, CliError> {
    use dicesim_experiment::batch::max_jobs;
    let cores = dicesim_experiment::batch::thread_count(0);
    match jobs {
        None => Ok(cores),
        Some(j) if j as usize <= max_jobs() && j > 0 => Ok(j as usize),
        Some(j) => Err(CliError::Usage(format!(
            "--jobs {j}: at most {} (4 × the {cores} cores here)",
            max_jobs()
        ))),
    }
}

/// The `--out` files of a command that writes several: each checked (extension, folder,
/// `--force`) and none named twice, before any work.
pub(crate) fn checked_outputs(
    paths: &[PathBuf],
    extensions: &[&str],
    force: bool,
) -> Result<Vec<Output>, CliError> {
    let outputs = paths
        .iter()
        .map(|p| Output::check(p, extensions, force))
        .collect::<Result<Vec<_>, _>>()
        .map_err(CliError::output("--out "))?;
    check_apart(&outputs, &[]).map_err(CliError::output("--out "))?;
    Ok(outputs)
}
