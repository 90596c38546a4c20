//! The export of one roll from the explorer: its trace (CSV) and its energy plot (PNG),
//! written side by side.

use crate::energy_plot::energy_plot_png;
use dicesim_experiment::Error;
use dicesim_experiment::trace::{TraceWriter, header, record_len, row};
use dicesim_physics::{Energy, InitialCondition, Params, Simulation};
use dicesim_setup::number::human_bytes;
use dicesim_setup::output::Output;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

/// The largest trace the explorer writes, bytes: beyond it a roll is better thinned with
/// `dicesim trace --every K` than written step by step.
pub(crate) const EXPORT_LIMIT_BYTES: u64 = 256 * 1024 * 1024;

/// Most points of the exported energy plot (each term's peak is kept over a stride).
const PLOT_SAMPLES: u64 = 20_000;

/// Steps between looks at the cancel flag and progress reports.
const REPORT_EVERY: u64 = 4096;

/// What [`export_roll`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Exported {
    pub trace: PathBuf,
    pub(crate) plot: PathBuf,
    /// Rows of the trace, header excluded.
    pub rows: u64,
    pub bytes: u64,
}

/// How far an export has got: first rolling to learn its length, then writing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExportProgress {
    /// False while the roll is measured, true once rows are written.
    pub writing: bool,
    pub steps_done: u64,
    /// The roll's steps, once measured (the cap `integrator.max_time / dt` before).
    pub steps_total: u64,
    /// The trace's size, bytes: estimated while measuring, exact from the row lengths after.
    pub bytes: u64,
}

/// Where an export goes: the trace (CSV) and the energy plot (PNG), the plot on a
/// logarithmic energy axis when `log_scale` (as the screen showed it).
#[derive(Debug, Clone)]
pub struct ExportFiles {
    pub trace: Output,
    pub plot: Output,
    pub log_scale: bool,
}

/// Rolls `initial` again from t = 0 to its end, writing every step's row to `files.trace`
/// and the energy against time to `files.plot` (a PNG).
///
/// The roll is first run without writing, to learn its length and the trace's size: a trace
/// above [`EXPORT_LIMIT_BYTES`] is refused, naming the `dicesim trace --every K` that fits.
/// `cancel` is looked at every few thousand steps; `progress` hears about it as often.
pub fn export_roll(
    params: &Params,
    initial: &InitialCondition,
    title: &str,
    files: &ExportFiles,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(ExportProgress),
) -> Result<Exported, Error> {
    let ExportFiles {
        trace,
        plot,
        log_scale,
    } = files;
    let cancelled = || cancel.load(Ordering::Relaxed);
    let mut sim = Simulation::new_unchecked(params, initial);
    let mut status = ExportProgress {
        writing: false,
        steps_done: 0,
        steps_total: params.max_steps(),
        bytes: 0,
    };
    // Measure: the steps, and the row length sampled along the roll.
    let (mut sampled_len, mut samples_taken) = (record_len(&row(&sim)), 1u64);
    while sim.outcome().is_none() {
        sim.advance();
        let step = sim.state().step;
        if step.is_multiple_of(REPORT_EVERY) {
            if cancelled() {
                return Err(Error::Cancelled);
            }
            sampled_len += record_len(&row(&sim));
            samples_taken += 1;
            status.steps_done = step;
            status.bytes = sampled_len / samples_taken * (status.steps_total + 1);
            progress(status);
        }
    }
    let rows = sim.state().step + 1;
    let estimate = record_len(&header()) + sampled_len / samples_taken * rows;
    if estimate > EXPORT_LIMIT_BYTES {
        let every = estimate.div_ceil(EXPORT_LIMIT_BYTES);
        // Short enough for the explorer's status line, with the way out in it.
        return Err(Error::Export(format!(
            "{} ({rows} rows) is over the {} limit: `dicesim trace --every {every}` thins it",
            human_bytes(estimate),
            human_bytes(EXPORT_LIMIT_BYTES)
        )));
    }
    status = ExportProgress {
        writing: true,
        steps_done: 0,
        steps_total: rows - 1,
        bytes: estimate,
    };
    progress(status);
    let stride = rows.div_ceil(PLOT_SAMPLES).max(1);
    let mut samples: Vec<(f64, Energy)> = Vec::with_capacity((rows / stride + 2) as usize);
    let mut peak: Option<(f64, Energy)> = None;
    let mut written = 0u64;
    let mut sim = Simulation::new_unchecked(params, initial);
    trace
        .write(|out| {
            let mut csv = TraceWriter::new(out)?;
            written += record_len(&header());
            loop {
                written += csv.write(&sim)?;
                let (t, e) = (sim.state().time_s, sim.energy());
                peak = Some(match peak {
                    None => (t, e),
                    Some((_, p)) => (t, e.max_each(&p)),
                });
                let step = sim.state().step;
                let ended = sim.outcome().is_some();
                if step.is_multiple_of(stride) || ended {
                    samples.extend(peak.take());
                }
                if ended {
                    return csv.flush();
                }
                if step.is_multiple_of(REPORT_EVERY) && step > 0 {
                    if cancelled() {
                        return Err(std::io::Error::other(CANCELLED));
                    }
                    status.steps_done = step;
                    progress(status);
                }
                sim.advance();
            }
        })
        .map_err(|e| match e {
            dicesim_setup::output::OutputError::Write { message, .. } if message == CANCELLED => {
                Error::Cancelled
            }
            e => Error::Export(e.to_string()),
        })?;
    // The title starts with the preset's name ("paper · preset roll — …").
    let name = title.split(" · ").next().unwrap_or(title);
    let record = crate::plot::Record::of_setup(title, name, params, initial);
    let png = energy_plot_png(&samples, sim.stop_threshold(), *log_scale, &record)
        .map_err(|e| Error::Export(format!("{}: {e}", plot.path().display())))?;
    plot.write_bytes(&png).map_err(|e| Error::Export(e.to_string()))?;
    Ok(Exported {
        trace: trace.path().to_path_buf(),
        plot: plot.path().to_path_buf(),
        rows,
        bytes: written,
    })
}

/// The reason a cancelled export's write stops with (it never reaches a person).
const CANCELLED: &str = "export cancelled";
