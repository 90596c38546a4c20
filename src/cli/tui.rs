//! `dicesim tui` (and `dicesim` alone): the terminal explorer.

use super::{CliError, SetupArgs};
use crate::tui::Theme;
use clap::Args;
use std::io::IsTerminal;

#[derive(Debug, Clone, Default, Args)]
pub struct TuiArgs {
    #[command(flatten)]
    pub setup: SetupArgs,
    /// Draw without colour; meaning is carried by bold and reverse (also with NO_COLOR set).
    #[arg(long)]
    pub no_color: bool,
}

pub fn run(args: &TuiArgs) -> Result<(), CliError> {
    let preset = args.setup.resolve()?;
    if !std::io::stdout().is_terminal() || !std::io::stdin().is_terminal() {
        return Err(CliError::Input(
            "the explorer needs a terminal; for output to a pipe or file use `dicesim roll`, `trace` or `batch` \
             (`dicesim --help` lists them)"
                .to_string(),
        ));
    }
    let theme = if args.no_color {
        Theme::monochrome()
    } else {
        Theme::from_env()
    };
    crate::tui::run(&preset, theme).map_err(|e| CliError::Run(format!("{e:#}")))
}
