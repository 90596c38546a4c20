//! `dicesim presets`: list, show and save presets, and tell where the user's folder is.

use super::args::SetupArgs;
use super::error::CliError;
use clap::{Args, Subcommand};
use dicesim_setup::preset::{PresetError, Store, check_name};
use std::io::Write;

#[derive(Debug, Args)]
pub(crate) struct PresetsArgs {
    #[command(subcommand)]
    pub(crate) command: PresetsCommand,
}

#[derive(Debug, Subcommand)]
pub(crate) enum PresetsCommand {
    /// List every preset loadable by name: name, where it lives (user/shipped), description.
    List,
    /// Print a preset as a whole TOML file (every key, with units), after any `--set`.
    Show {
        /// A preset name or a path to a `.toml` file.
        #[arg(value_name = "NAME|PATH")]
        name: String,
        /// Override one value before showing it (repeatable, applied in order).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
    },
    /// Save a setup into the user's preset folder as NAME.toml.
    Save {
        /// Letters, digits, `-` and `_` only.
        name: String,
        #[command(flatten)]
        setup: SetupArgs,
        /// What the preset shows (default: which preset it is based on, and the overrides).
        #[arg(long, value_name = "TEXT")]
        description: Option<String>,
        /// Replace an existing preset of that name.
        #[arg(long)]
        force: bool,
    },
    /// Print the user's preset folder (set `DICESIM_PRESETS` to use another).
    Path,
}

pub(crate) fn run(args: &PresetsArgs) -> Result<(), CliError> {
    let store = Store::from_env();
    let mut out = std::io::stdout().lock();
    match &args.command {
        PresetsCommand::List => {
            let entries = store.list();
            let width = entries.iter().map(|e| e.name.len()).max().unwrap_or(0);
            for e in entries {
                let about = match &e.preset {
                    Ok(p) => p.description.split_whitespace().collect::<Vec<_>>().join(" "),
                    Err(err) => format!("does not load: {err}"),
                };
                writeln!(
                    out,
                    "{:<width$}  {:<7}  {}",
                    dicesim_setup::output::printable(&e.name),
                    e.source.kind(),
                    dicesim_setup::output::printable(&about)
                )?;
            }
        }
        PresetsCommand::Show { name, set } => {
            let setup = SetupArgs {
                preset: Some(name.clone()),
                set: set.clone(),
            };
            // A description may hold anything a file can; the terminal gets it escaped.
            write!(
                out,
                "{}",
                dicesim_setup::output::printable(&setup.resolve()?.to_toml())
            )?;
        }
        PresetsCommand::Save {
            name,
            setup,
            description,
            force,
        } => {
            check_name(name)?;
            let mut preset = setup.resolve()?;
            // The base's description describes the base; a saved variant says what it is.
            preset.description = match description {
                Some(text) => text.clone(),
                None if setup.set.is_empty() => format!("A copy of the `{}` preset.", preset.name),
                None => format!("The `{}` preset with {}.", preset.name, setup.set.join(", ")),
            };
            preset.name = name.clone();
            let path = store.save(&preset, *force).map_err(|e| match e {
                PresetError::Exists { .. } => CliError::Exists(e),
                e => CliError::from(e),
            })?;
            writeln!(out, "saved {}", path.display())?;
        }
        PresetsCommand::Path => {
            writeln!(out, "{}", store.user_dir()?.display())?;
        }
    }
    Ok(())
}
