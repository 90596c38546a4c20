//! The export of one roll from the explorer: its trace (CSV) and its energy plot (PNG),
//! written side by side.

use crate::energy_plot::energy_plot_png;
use dicesim_experiment::Error;
use dicesim_experiment::data_file;
use dicesim_experiment::trace::{TraceWriter, columns_for, header_for, record_len, row};
use dicesim_physics::{Energy, InitialCondition, Params, Roll};
use dicesim_setup::number::{StepClock, human_bytes};
use dicesim_setup::output::{Output, commit};
use std::io::Write as _;
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
/// logarithmic energy axis when `log_scale` (as the screen showed it); both carry
/// `provenance`, the roll's (the trace in its sidecar, the plot in its text).
#[derive(Debug, Clone)]
pub struct ExportFiles {
    pub trace: Output,
    pub plot: Output,
    pub log_scale: bool,
    pub provenance: serde_json::Value,
}

/// Rolls `initial` again from t = 0 to its end, writing every step's row to `files.trace`
/// and the energy against time to `files.plot` (a PNG): both files or neither.
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
        provenance,
    } = files;
    let clock = StepClock::new(params.integrator.dt);
    let cancelled = || cancel.load(Ordering::Relaxed);
    let mut sim = Roll::new_unchecked(params, initial);
    let mut status = ExportProgress {
        writing: false,
        steps_done: 0,
        steps_total: params.max_steps(),
        bytes: 0,
    };
    // Measure: the steps, and the row length sampled along the roll.
    let (mut sampled_len, mut samples_taken) = (record_len(&row(&sim, &clock)), 1u64);
    while sim.outcome().is_none() {
        sim.advance();
        let step = sim.steps();
        if step.is_multiple_of(REPORT_EVERY) {
            if cancelled() {
                return Err(Error::Cancelled);
            }
            sampled_len += record_len(&row(&sim, &clock));
            samples_taken += 1;
            status.steps_done = step;
            status.bytes = sampled_len / samples_taken * (status.steps_total + 1);
            progress(status);
        }
    }
    let rows = sim.steps() + 1;
    let estimate = record_len(&header_for(params)) + sampled_len / samples_taken * rows;
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
    let mut sim = Roll::new_unchecked(params, initial);
    let failed = |e: dicesim_setup::output::OutputError| Error::Export(e.to_string());
    let meta = data_file::sidecar(provenance, &columns_for(params));
    let mut staged = trace.stage(Some(&meta)).map_err(failed)?;
    let mut csv =
        TraceWriter::of(&mut staged, params).map_err(|e| Error::Export(trace.failed(&e).to_string()))?;
    written += record_len(&header_for(params));
    loop {
        written += csv
            .write(&sim)
            .map_err(|e| Error::Export(trace.failed(&e).to_string()))?;
        let (t, e) = (sim.time_s(), sim.energy());
        peak = Some(match peak {
            None => (t, e),
            Some((_, p)) => (t, e.max_each(&p)),
        });
        let step = sim.steps();
        let ended = sim.outcome().is_some();
        if step.is_multiple_of(stride) || ended {
            samples.extend(peak.take());
        }
        if ended {
            break;
        }
        if step.is_multiple_of(REPORT_EVERY) && step > 0 {
            if cancelled() {
                // The staged trace is dropped: nothing is left.
                return Err(Error::Cancelled);
            }
            status.steps_done = step;
            progress(status);
        }
        sim.advance();
    }
    // The title starts with the preset's name ("paper · preset roll — …").
    let name = title.split(" · ").next().unwrap_or(title);
    let record = crate::plot::Record::of_setup(title, name, params, initial).with_provenance(provenance);
    let png = energy_plot_png(&samples, sim.stop_threshold(), *log_scale, &record)
        .map_err(|e| Error::Export(format!("{}: {e}", plot.path().display())))?;
    let mut picture = plot.stage(None).map_err(failed)?;
    picture
        .write_all(&png)
        .map_err(|e| Error::Export(plot.failed(&e).to_string()))?;
    commit(vec![staged, picture]).map_err(failed)?;
    Ok(Exported {
        trace: trace.path().to_path_buf(),
        plot: plot.path().to_path_buf(),
        rows,
        bytes: written,
    })
}
