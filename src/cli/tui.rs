//! `dicesim tui` (and `dicesim` alone): the terminal explorer.

use super::args::SetupArgs;
use super::error::CliError;
use clap::{Args, ValueEnum};
use dicesim_explorer::lesson::Lesson;
use dicesim_explorer::tui::Theme;
use dicesim_setup::preset::{Preset, Store, ThemeName};
use std::io::IsTerminal;

#[derive(Debug, Clone, Default, Args)]
pub(crate) struct TuiArgs {
    #[command(flatten)]
    pub(crate) setup: SetupArgs,
    /// The theme to open in, over the preset's own (`t` still cycles them): projector is
    /// bold, high-contrast black on white for a room.
    #[arg(long, value_enum)]
    pub(crate) theme: Option<ThemeArg>,
    /// Walk a lesson: its first step opens at once, PageDown goes on (docs/lesson.md).
    /// Without FILE, the shipped lesson (the README's "In the classroom").
    #[arg(long, value_name = "FILE", num_args = 0..=1)]
    pub(crate) lesson: Option<Option<std::path::PathBuf>>,
}

/// The explorer's themes, as `--theme` names them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum ThemeArg {
    Dark,
    Light,
    Projector,
}

impl From<ThemeArg> for ThemeName {
    fn from(t: ThemeArg) -> ThemeName {
        match t {
            ThemeArg::Dark => ThemeName::Dark,
            ThemeArg::Light => ThemeName::Light,
            ThemeArg::Projector => ThemeName::Projector,
        }
    }
}

/// The setup the explorer opens: the preset with `--set` applied, in the `--theme` asked.
fn opening(args: &TuiArgs) -> Result<Preset, CliError> {
    let mut preset = args.setup.resolve()?;
    if let Some(theme) = args.theme {
        preset.view.theme = Some(theme.into());
    }
    Ok(preset)
}

/// The lesson the step keys walk: `--lesson FILE`'s, else the shipped one; a file that
/// does not read is a usage error naming its line.
fn lesson(args: &TuiArgs) -> Result<Lesson, CliError> {
    let store = Store::from_env();
    match &args.lesson {
        Some(Some(path)) => Lesson::from_file(path, &store),
        _ => Lesson::shipped(&store),
    }
    .map_err(|e| CliError::Usage(format!("the lesson cannot be walked: {e}")))
}

/// Opens the explorer; `no_color` is the global `--no-color` (or NO_COLOR).
pub(crate) fn run(args: &TuiArgs, no_color: bool) -> Result<(), CliError> {
    let lesson = lesson(args)?;
    let walk = args.lesson.is_some();
    let preset = opening(args)?;
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
    dicesim_explorer::tui::run(&preset, theme, lesson, walk).map_err(CliError::from)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::command::{Cli, CliCommand};
    use clap::Parser;

    fn tui_args(argv: &[&str]) -> Result<TuiArgs, clap::Error> {
        let cli = Cli::try_parse_from(argv)?;
        match cli.command {
            Some(CliCommand::Tui(args)) => Ok(args),
            other => panic!("not the explorer: {other:?}"),
        }
    }

    #[test]
    fn theme_opens_the_explorer_in_that_theme_over_the_presets() {
        let args = tui_args(&["dicesim", "tui", "--preset", "paper", "--theme", "projector"]).unwrap();
        assert_eq!(opening(&args).unwrap().view.theme, Some(ThemeName::Projector));
        // slow-motion-classroom has a view of its own; --theme wins, the rest of it stays.
        let own =
            opening(&tui_args(&["dicesim", "tui", "--preset", "slow-motion-classroom"]).unwrap()).unwrap();
        let args = tui_args(&[
            "dicesim",
            "tui",
            "--preset",
            "slow-motion-classroom",
            "--theme",
            "light",
        ])
        .unwrap();
        let over = opening(&args).unwrap();
        assert_eq!(over.view.theme, Some(ThemeName::Light));
        assert_eq!(
            (over.view.speed, over.view.arrows),
            (own.view.speed, own.view.arrows)
        );
        let e = tui_args(&["dicesim", "tui", "--theme", "purple"])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("dark") && e.contains("light") && e.contains("projector"),
            "{e}"
        );
    }
}
