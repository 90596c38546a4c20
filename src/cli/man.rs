//! `dicesim man`: the manual pages, one for the program and one for each command (with its
//! options and examples), rendered from the same clap definitions as `--help`.

use super::error::CliError;
use clap::{Args, Command};
use dicesim_setup::output::Output;
use std::io::Write;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub(crate) struct ManArgs {
    /// The command whose page to print, e.g. `batch` or `presets save` (none: the program's
    /// own page, which lists the commands).
    #[arg(value_name = "COMMAND", conflicts_with = "out_dir")]
    pub(crate) command: Vec<String>,
    /// Write every page into this existing folder instead: `dicesim.1`, `dicesim-batch.1`,
    /// `dicesim-presets-save.1`, …
    #[arg(long, value_name = "DIR")]
    pub(crate) out_dir: Option<PathBuf>,
    /// Replace pages that are already in the folder.
    #[arg(long, requires = "out_dir")]
    pub(crate) force: bool,
}

/// A page: its file name (`dicesim-batch.1`) and its roff text.
struct Page {
    file_name: String,
    roff: Vec<u8>,
}

/// The page of `command`; every page names the program and its version as its source
/// (clap_mangen would name the subcommand, without a version).
fn render(command: Command, source: &str) -> Result<Page, CliError> {
    let man = clap_mangen::Man::new(command).source(source);
    let mut roff = Vec::new();
    man.render(&mut roff)?;
    Ok(Page {
        file_name: man.get_filename(),
        roff,
    })
}

/// `command` as the pages show it: built, so each subcommand is named with its parents
/// (`dicesim-presets-save`), and without clap's `help` subcommand (every page has `--help`).
fn built(command: Command) -> Command {
    let mut command = command.disable_help_subcommand(true);
    command.build();
    command
}

/// The page of `command` and of every command under it, parents first.
fn every_page(command: &Command, source: &str, pages: &mut Vec<Page>) -> Result<(), CliError> {
    pages.push(render(command.clone(), source)?);
    for sub in command.get_subcommands().filter(|s| !s.is_hide_set()) {
        every_page(sub, source, pages)?;
    }
    Ok(())
}

/// Prints the page `args` names, or writes every page into `--out-dir`; `program` is the
/// whole command line's definition.
pub(crate) fn run(args: &ManArgs, program: Command) -> Result<(), CliError> {
    let program = built(program);
    let source = format!(
        "{} {}",
        program.get_name(),
        program.get_version().unwrap_or_default()
    );
    let Some(dir) = &args.out_dir else {
        let mut command = &program;
        for name in &args.command {
            command = command
                .get_subcommands()
                .filter(|s| !s.is_hide_set())
                .find(|s| s.get_name() == name)
                .ok_or_else(|| no_such_command(command, name))?;
        }
        let page = render(command.clone(), &source)?;
        // A failed write (a full disk, /dev/full) is a failure, not a success: flushed here.
        let mut out = std::io::stdout().lock();
        out.write_all(&page.roff)?;
        out.flush()?;
        return Ok(());
    };
    let mut pages = Vec::new();
    every_page(&program, &source, &mut pages)?;
    // Every path is checked before the first page is written: all pages or none.
    let outputs = pages
        .iter()
        .map(|page| Output::check(&dir.join(&page.file_name), &["1"], args.force))
        .collect::<Result<Vec<_>, _>>()
        .map_err(CliError::output("--out-dir "))?;
    for (page, output) in pages.iter().zip(&outputs) {
        output
            .write_bytes(&page.roff)
            .map_err(CliError::output("--out-dir "))?;
    }
    writeln!(
        std::io::stdout().lock(),
        "wrote {} manual pages into {} (`man dicesim`, `man dicesim-batch`, … once it is on MANPATH)",
        pages.len(),
        dir.display()
    )?;
    std::io::stdout().flush()?;
    Ok(())
}

fn no_such_command(parent: &Command, name: &str) -> CliError {
    let names: Vec<&str> = parent
        .get_subcommands()
        .filter(|s| !s.is_hide_set())
        .map(Command::get_name)
        .collect();
    let path = parent
        .get_display_name()
        .unwrap_or(parent.get_name())
        .replace('-', " ");
    if names.is_empty() {
        CliError::Usage(format!(
            "`{path}` has no commands under it, so no page for `{name}`"
        ))
    } else {
        CliError::Usage(format!(
            "`{path}` has no command `{name}`; its commands are {}",
            names.join(", ")
        ))
    }
}
