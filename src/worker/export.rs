//! The roll export as a job: the engine asks for it (setup, folder, name), the export
//! runner runs it on a thread of its own, and only here does it meet the file system: free
//! names chosen, checked (see `output::Output`) and written by `experiment::trace`.

use crate::experiment::trace::{ExportFiles, ExportProgress, Exported, export_roll};
use crate::output::{Output, free_stem};
use crate::physics::{InitialCondition, Params};
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

/// An export to run off the worker's thread: the roll's setup, the folder and the name
/// it asks for. The engine never looks at the file system: the job chooses and checks
/// the files where it runs, on the export runner's thread.
#[derive(Debug, Clone)]
pub(crate) struct ExportJob {
    pub(crate) id: u64,
    pub(crate) params: Params,
    pub(crate) initial: InitialCondition,
    pub(crate) title: String,
    pub(crate) dir: PathBuf,
    /// The file name without a number or extension (`dicesim-paper-preset-roll`).
    pub(crate) stem: String,
    pub(crate) log_scale: bool,
}

impl ExportJob {
    /// Chooses two free names in the folder, checks them (see [`Output::check`]) and runs
    /// the export on this thread (see [`export_roll`]): nothing is written if a check fails.
    pub(crate) fn run(
        &self,
        cancel: &AtomicBool,
        progress: &mut dyn FnMut(ExportProgress),
    ) -> Result<Exported, crate::experiment::Error> {
        let dir = std::fs::canonicalize(&self.dir).unwrap_or_else(|_| self.dir.clone());
        let stem = free_stem(&dir, &self.stem, &["csv", "png"]);
        let check = |ext: &str| {
            Output::check(&dir.join(format!("{stem}.{ext}")), &[ext], false)
                .map_err(|e| crate::experiment::Error::Export(e.to_string()))
        };
        let files = ExportFiles {
            trace: check("csv")?,
            plot: check("png")?,
            log_scale: self.log_scale,
        };
        export_roll(&self.params, &self.initial, &self.title, &files, cancel, progress)
    }
}
