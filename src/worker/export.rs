//! The explorer's exports as jobs: the engine orders one (what, the folder, the name it
//! asks for), the export runner runs it on a thread of its own, and only there does it
//! meet the file system: free names chosen and checked together (see
//! `output::free_outputs`), each file written whole or not at all. The roll gives its
//! trace (CSV) and energy plot (PNG, written by `experiment::trace`); a basin map its
//! cells (CSV) and its picture (PNG).

use crate::experiment::plot::{ImageFormat, image_bytes, map_record};
use crate::experiment::trace::{ExportFiles, ExportProgress, Exported, export_roll};
use crate::experiment::{BasinMap, Error, Layer};
use crate::output::free_outputs;
use crate::physics::{InitialCondition, Params};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

/// What an export writes.
#[derive(Debug, Clone)]
pub(crate) enum Exporting {
    /// The roll from t = 0: its trace, and its energy plot (`log_scale`: on a
    /// logarithmic energy axis, as the screen showed it).
    Roll {
        params: Params,
        initial: InitialCondition,
        title: String,
        log_scale: bool,
    },
    /// A basin map as the screen shows it: its cells, and its picture in `layer` at
    /// `size` pixels, recording the setup every cell starts from.
    Map {
        map: Box<BasinMap>,
        params: Params,
        initial: InitialCondition,
        /// The preset's name, for the picture's record.
        preset: String,
        layer: Layer,
        size: (u32, u32),
    },
}

/// An export to run off the worker's thread: what, the folder and the name it asks for.
#[derive(Debug, Clone)]
pub(crate) struct ExportJob {
    pub(crate) id: u64,
    pub(crate) dir: PathBuf,
    /// The file name without a number or extension (`dicesim-paper-preset-roll`).
    pub(crate) stem: String,
    pub(crate) what: Exporting,
}

/// What an export wrote.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Written {
    Roll(Exported),
    Map {
        csv: PathBuf,
        png: PathBuf,
        size: (u32, u32),
        cells: (usize, usize),
        complete: bool,
    },
}

impl ExportJob {
    /// Chooses free names in the folder, checks them and writes the files on this
    /// thread; nothing is written if a check fails, and a cancel before the last file
    /// leaves none.
    pub(crate) fn run(
        &self,
        cancel: &AtomicBool,
        progress: &mut dyn FnMut(ExportProgress),
    ) -> Result<Written, Error> {
        let dir = std::fs::canonicalize(&self.dir).unwrap_or_else(|_| self.dir.clone());
        let outputs = free_outputs(&dir, &self.stem, ["csv", "png"]);
        match &self.what {
            Exporting::Roll {
                params,
                initial,
                title,
                log_scale,
            } => {
                let [csv, png] = outputs.map_err(|e| Error::Export(e.to_string()))?;
                let files = ExportFiles {
                    trace: csv,
                    plot: png,
                    log_scale: *log_scale,
                };
                export_roll(params, initial, title, &files, cancel, progress).map(Written::Roll)
            }
            Exporting::Map {
                map,
                params,
                initial,
                preset,
                layer,
                size,
            } => {
                let [csv, png] = outputs?;
                // The caption and the PNG's text chunks say which setup every cell started from.
                let record = map_record(map, *layer, Some((preset, params, initial)));
                let picture = image_bytes(map, *layer, &record, *size, ImageFormat::Png)?;
                if cancel.load(Ordering::Relaxed) {
                    return Err(Error::Cancelled);
                }
                csv.write(|w| map.write_csv(w))?;
                if let Err(e) = png.write_bytes(&picture) {
                    // Both files or neither.
                    let _ = std::fs::remove_file(csv.path());
                    return Err(e.into());
                }
                Ok(Written::Map {
                    csv: csv.path().to_path_buf(),
                    png: png.path().to_path_buf(),
                    size: *size,
                    cells: (map.width(), map.height()),
                    complete: map.complete,
                })
            }
        }
    }
}
