//! How every long command runs: its progress bar, the signals that stop it, and its
//! results written the one way such a command writes them.

use super::error::CliError;
use dicesim_experiment as experiment;
use dicesim_setup::output::Output;
use signal_hook::consts::{SIGHUP, SIGINT, SIGQUIT, SIGTERM};
use std::io::Write as _;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
use std::time::Duration;

/// The progress bar of a long command: drawn on stderr while it is a terminal, hidden
/// otherwise (a pipe or a log file gets no bar codes), in `template`'s words.
pub(crate) fn progress_bar(total: u64, template: &str) -> indicatif::ProgressBar {
    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
    use std::io::IsTerminal;
    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new(total)
    } else {
        ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden())
    };
    bar.set_style(ProgressStyle::with_template(template).expect("the progress template is valid"));
    bar
}

/// The first stop signal a command caught (0 before any): the exit status of a command it
/// stopped is 128 + its number, as a shell reports a process that signal ended (130 for
/// Ctrl-C, 143 for SIGTERM, 129 for SIGHUP, 131 for SIGQUIT), whether the command kept its
/// completed work first or not.
static FIRST_SIGNAL: AtomicI32 = AtomicI32::new(0);

/// The exit status of a command a stop signal interrupted: 128 + the signal (Ctrl-C's when
/// the interruption came from elsewhere).
pub fn interrupted_status() -> u8 {
    match FIRST_SIGNAL.load(Ordering::SeqCst) {
        0 => 128 + SIGINT as u8,
        signal => (128 + signal) as u8,
    }
}

/// How long a command may take, after the first stop signal, to keep its completed work
/// (finish the rolls running, write the kept files and the summary): then it stops as at a
/// second signal, so any stop signal ends any command within 2 s, whatever it was doing
/// (drawing a big map's image, a write the disk holds up, a reader that stopped reading).
const GRACE: Duration = Duration::from_millis(1500);

/// The signals that ask a command to stop: Ctrl-C, `kill`, a closed terminal, Ctrl-\\ (and
/// Slurm's time limit, which sends SIGTERM).
const STOP_SIGNALS: [i32; 4] = [SIGINT, SIGTERM, SIGHUP, SIGQUIT];

/// Runs a long experiment as every such command does: a progress bar over its `total` rolls
/// (`template` in indicatif's words), Ctrl-C asking it to stop, its error worded like the
/// others'. `run` gets the stop flag and reports how many rolls are done.
pub(crate) fn run_with_progress<T>(
    total: u64,
    template: &str,
    run: impl FnOnce(&AtomicBool, &mut dyn FnMut(u64)) -> Result<T, experiment::Error>,
) -> Result<T, CliError> {
    let bar = progress_bar(total, template);
    let stop = cancel_on_ctrl_c()?;
    let result = run(&stop, &mut |done| bar.set_position(done)).map_err(CliError::experiment(""))?;
    bar.finish_and_clear();
    Ok(result)
}

/// A long experiment's result, written the one way every such command writes it.
pub(crate) struct Results<'a, T: serde::Serialize> {
    pub(crate) value: &'a T,
    /// What defines the experiment: the CSV's sidecar's, the JSON's and the PNG's
    /// `provenance`.
    pub(crate) provenance: &'a serde_json::Value,
    /// The CSV's columns, for its sidecar.
    pub(crate) columns: &'a [experiment::data_file::Column],
    /// The CSV, its header first.
    pub(crate) csv: &'a dyn Fn(&mut (dyn std::io::Write + Send)) -> std::io::Result<()>,
    pub(crate) png: &'a dyn Fn() -> Result<Vec<u8>, CliError>,
    /// The table printed when `--json` is not given.
    pub(crate) table: &'a dyn Fn(&mut dyn std::io::Write) -> std::io::Result<()>,
}

/// Writes every `--out` file by its extension (CSV with its sidecar, JSON with the
/// provenance, else PNG), all of them or none, then prints the table and the files
/// written, or the JSON alone with `--json` (its provenance in it, as in a file).
pub(crate) fn write_results<T: serde::Serialize>(
    outputs: &[Output],
    json: bool,
    r: Results<'_, T>,
) -> Result<(), CliError> {
    let with_provenance = || -> Result<serde_json::Value, std::io::Error> {
        let mut v = serde_json::to_value(r.value)?;
        v["provenance"] = r.provenance.clone();
        Ok(v)
    };
    let mut staged = Vec::with_capacity(outputs.len());
    for output in outputs {
        let meta = (output.sidecar()).map(|_| experiment::data_file::sidecar(r.provenance, r.columns));
        let mut file = output.stage(meta.as_deref()).map_err(CliError::output(""))?;
        match output.extension() {
            "csv" => (r.csv)(&mut file),
            "json" => with_provenance().and_then(|v| {
                serde_json::to_writer_pretty(&mut file, &v)?;
                writeln!(file)
            }),
            _ => file.write_all(&(r.png)()?),
        }
        .map_err(|e| CliError::output("")(output.failed(&e)))?;
        staged.push(file);
    }
    dicesim_setup::output::commit(staged).map_err(CliError::output(""))?;
    let mut out = std::io::stdout().lock();
    if json {
        serde_json::to_writer_pretty(&mut out, &with_provenance()?).map_err(std::io::Error::from)?;
        writeln!(out)?;
    } else {
        (r.table)(&mut out)?;
        for output in outputs {
            writeln!(out, "wrote {}", output.path().display())?;
        }
    }
    out.flush()?;
    Ok(())
}

/// A flag the first stop signal sets (the running rolls notice it within a few thousand
/// steps and the command keeps what is complete); a second signal stops at once, after
/// removing the temporary file being written and saying so.
pub(crate) fn cancel_on_ctrl_c() -> Result<Arc<AtomicBool>, CliError> {
    let stop = Arc::new(AtomicBool::new(false));
    on_stop_signals(Some(stop.clone()))?;
    Ok(stop)
}

/// For a command that has no use for a partial result (`merge`): any stop signal removes the
/// temporary file being written, says that nothing was written and exits.
pub(crate) fn stop_at_once_on_signals() -> Result<(), CliError> {
    on_stop_signals(None)
}

fn on_stop_signals(graceful: Option<Arc<AtomicBool>>) -> Result<(), CliError> {
    let mut signals = signal_hook::iterator::Signals::new(STOP_SIGNALS)
        .map_err(|e| CliError::Io(std::io::Error::other(format!("cannot catch signals: {e}"))))?;
    std::thread::spawn(move || {
        for signal in signals.forever() {
            let _ = FIRST_SIGNAL.compare_exchange(0, signal, Ordering::SeqCst, Ordering::SeqCst);
            if let Some(stop) = &graceful
                && !stop.swap(true, Ordering::SeqCst)
            {
                std::thread::spawn(move || {
                    std::thread::sleep(GRACE);
                    let stopped = dicesim_setup::output::stop_writing();
                    let what = if stopped.removed > 0 {
                        "the file being written was removed; files completed before it are kept"
                    } else {
                        "files completed before now are kept"
                    };
                    let _ = writeln!(
                        std::io::stderr(),
                        "dicesim: still not done keeping the completed work 1.5 s after signal {signal}, \
                         so stopped: {what}"
                    );
                    std::process::exit(i32::from(interrupted_status()));
                });
                continue;
            }
            stop_now(
                signal,
                if graceful.is_some() {
                    "stopped again by signal"
                } else {
                    "stopped by signal"
                },
            );
        }
    });
    Ok(())
}

/// Removes the temporary file being written, says so (`why` names the signal) and exits with
/// the status of the first signal.
fn stop_now(signal: i32, why: &str) -> ! {
    let stopped = dicesim_setup::output::stop_writing();
    let placed: Vec<String> = stopped.placed.iter().map(|p| p.display().to_string()).collect();
    let placed = placed.join(", ");
    let what = match (stopped.removed > 0, placed.is_empty()) {
        (false, true) => "nothing was written".to_string(),
        (true, true) => "the file being written was removed, nothing was written".to_string(),
        (false, false) => format!("{placed} had been written before it"),
        (true, false) => format!("{placed} had been written before it; the file being written was removed"),
    };
    let _ = writeln!(std::io::stderr(), "dicesim: {why} {signal}: {what}");
    std::process::exit(i32::from(interrupted_status()));
}
