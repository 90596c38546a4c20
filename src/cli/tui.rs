//! `dicesim tui` (and `dicesim` alone): the terminal explorer.

use super::{CliError, SetupArgs};
use crate::tui::Theme;
use clap::Args;
use std::io::IsTerminal;

#[derive(Debug, Clone, Default, Args)]
pub(crate) struct TuiArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
}

/// Opens the explorer; `no_color` is the global `--no-color` (or NO_COLOR).
pub(crate) fn run(args: &TuiArgs, no_color: bool) -> Result<(), CliError> {
    let preset = args.setup.resolve()?;
    if !std::io::stdout().is_terminal() || !std::io::stdin().is_terminal() {
        return Err(CliError::Usage(
            "the explorer needs a terminal; for output to a pipe or file use `dicesim roll`, `trace` or `batch` \
             (`dicesim --help` lists them)"
                .to_string(),
        ));
    }
    let theme = if no_color {
        Theme::monochrome()
    } else {
        Theme::from_env()
    };
    crate::tui::run(&preset, theme).map_err(CliError::Explorer)
}
