//! A batch as a command rolls it: its rolls (drawn from the seed, or given), a shard's slice
//! of them, the provenance its files carry, and the records file the rolls stream to as
//! they complete, so memory stays flat in the number of rolls.

use crate::batch::{BatchRun, Rolls, RunOptions, stream_batch};
use crate::columns::{RecordColumn, Stage};
use crate::data_file::{self, Column};
use crate::hashing::{Hashing, Written};
use crate::ics::{SpinColumns, records_columns, write_cell, write_record_line};
use crate::parquet::RecordsWriter;
use crate::record::RollRecord;
use crate::shard::{Part, Shard, Sweep};
use crate::versus::{VersusRun, stream_versus};
use crate::{Error, provenance};
use dicesim_physics::{InitialCondition, Params};
use dicesim_setup::output::Output;
use dicesim_setup::preset::Preset;
use serde_json::{Value, json};
use std::io::Write;
use std::ops::Range;
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// One batch: the rolls of `preset` (drawn with `seed`, or `given`), the ids this run
/// rolls of them, and what its outputs say about it.
pub struct BatchSweep<'a> {
    preset: &'a Preset,
    given: Option<&'a [(u64, InitialCondition)]>,
    /// The seed of the draws (unused by given starts).
    seed: u64,
    /// Rolls of the whole sweep.
    pub total: u64,
    /// The ids this run rolls: all of them, or a shard's.
    pub range: Range<u64>,
    /// The fingerprint of the setup and of the given starts.
    fingerprint: String,
    /// The spin columns of its records: those its starts were given.
    pub spin: SpinColumns,
    /// What every file of the batch records of it (see [`provenance::batch`]).
    pub provenance: Value,
}

impl<'a> BatchSweep<'a> {
    /// `rolls` rolls drawn from `preset`'s random ranges with `seed`, or the `given` starts
    /// (then `rolls` is unused); with `shard`, only that shard's ids.
    pub fn new(
        preset: &'a Preset,
        seed: u64,
        given: Option<&'a [(u64, InitialCondition)]>,
        rolls: u64,
        shard: Option<Shard>,
    ) -> Self {
        let total = given.map_or(rolls, |ics| ics.len() as u64);
        let fingerprint = provenance::batch_fingerprint(preset, given);
        let provenance = provenance::batch(
            preset,
            given.is_none().then_some(seed),
            total,
            given.is_some().then_some(fingerprint.as_str()),
        );
        BatchSweep {
            preset,
            given,
            seed,
            total,
            range: shard.map_or(0..total, |s| s.range(total)),
            fingerprint,
            // Random draws give an angular velocity; given starts what they hold (the whole
            // sweep's, so every shard's file has the same columns).
            spin: SpinColumns::of_starts(given.unwrap_or_default().iter().map(|(_, ic)| ic)),
            provenance,
        }
    }

    /// The same throws rolled against setup B, A with `versus` (`KEY=VALUE` each) changed:
    /// the provenance names them.
    pub fn against(mut self, versus: &[String]) -> Self {
        self.provenance["versus"] = json!(versus);
        self
    }

    /// The seed as the outputs name it: none for given starts.
    pub fn seed(&self) -> Option<u64> {
        self.given.is_none().then_some(self.seed)
    }

    /// The rolls of this run, as the engine takes them.
    pub fn rolls(&self) -> Rolls<'_> {
        match self.given {
            Some(ics) => Rolls::Given(&ics[self.range.start as usize..self.range.end as usize]),
            None => Rolls::Random {
                ranges: &self.preset.random,
                base: &self.preset.initial,
                seed: self.seed,
                first: self.range.start,
                count: self.range.end - self.range.start,
            },
        }
    }

    /// Rolls the batch with `params`, each record also to `output`'s records file (CSV,
    /// JSON or Parquet by its extension; it appears under its name only once it is whole,
    /// or an interrupted prefix) and hashed as it is written; `progress` gets each chunk's
    /// roll count. Returns the run and, with a file, its size and hash. With a file, any
    /// failure is [`Error::Output`]: the file was not written.
    pub fn roll(
        &self,
        params: &Params,
        options: &RunOptions,
        stop: &AtomicBool,
        output: Option<&Output>,
        progress: &mut dyn FnMut(u64),
    ) -> Result<(BatchRun, Option<Written>), Error> {
        let Some(output) = output else {
            let rolls = self.rolls();
            return Ok((
                stream_batch(params, &rolls, options, stop, &mut |chunk| {
                    progress(chunk.len() as u64);
                    Ok(())
                })?,
                None,
            ));
        };
        let mut done = None;
        let meta =
            (output.sidecar()).map(|_| data_file::sidecar(&self.provenance, &records_columns(self.spin)));
        output.write_table(meta.as_deref(), |w| {
            let (batch, written) =
                self.roll_into(params, options, stop, (output.extension(), w), progress)?;
            done = Some((batch, Some(written)));
            Ok(())
        })?;
        Ok(done.expect("the batch ran"))
    }

    /// Rolls the batch with `params`, writing the records file of `extension` (`csv`,
    /// `json` or `parquet`: the bytes [`BatchSweep::roll`] puts in a file of that name)
    /// into `w` as the rolls complete, hashed as written. Also how a caller keeps the
    /// records in memory (the Python module's tables are this Parquet).
    pub fn roll_into(
        &self,
        params: &Params,
        options: &RunOptions,
        stop: &AtomicBool,
        (extension, w): (&str, &mut (dyn Write + Send)),
        progress: &mut dyn FnMut(u64),
    ) -> std::io::Result<(BatchRun, Written)> {
        let rolls = self.rolls();
        let mut roll = |sink: &mut dyn FnMut(&[RollRecord]) -> Result<(), String>| {
            stream_batch(params, &rolls, options, stop, &mut |chunk| {
                progress(chunk.len() as u64);
                sink(chunk)
            })
        };
        let mut hashing = Hashing::new(w);
        let mut file = RecordsFile::start(
            &mut hashing,
            extension,
            (&self.provenance, self.spin),
            self.seed(),
            rolls.len(),
        )?;
        let batch = keeping_io_errors(&mut roll, &mut |chunk| file.write(chunk))?;
        file.finish(&batch)?;
        let written = hashing.seal();
        Ok((batch, written))
    }

    /// What `batch --json` prints of `batch`, a run of this sweep: its provenance, size,
    /// how it ran and its statistics.
    pub fn report(&self, batch: &BatchRun) -> Value {
        json!({
            "provenance": self.provenance,
            "preset": self.preset.name,
            "seed": self.seed(),
            "requested": batch.requested,
            "completed": batch.completed,
            "interrupted": batch.cancelled,
            "jobs": batch.jobs,
            "engine": batch.engine,
            "summary": batch.summary,
            "past_stability_limit": batch.past_stability_limit,
        })
    }

    /// What `batch --versus --json` prints of `run`, a run of this sweep against setup B (and
    /// its .json file holds): its size, how it ran, the table of A's ending against B's, and
    /// the provenance, which names the throws and both setups.
    pub fn versus_report(&self, run: &VersusRun) -> Value {
        let mut v = json!({
            "preset": self.preset.name,
            "versus": self.provenance["versus"],
            "seed": self.seed(),
            "requested": run.requested,
            "completed": run.completed,
            "interrupted": run.cancelled,
            "jobs": run.jobs,
            "engine": run.engine,
        });
        let summary = json!(run.table.summary());
        for (key, value) in summary.as_object().expect("a struct") {
            v[key] = value.clone();
        }
        v["provenance"] = self.provenance.clone();
        v
    }

    /// Rolls every throw in setup `a` and in `b`; with `csv`, each throw's two endings go to
    /// that file as they complete (see [`versus_csv_header`]). `progress` gets each chunk's
    /// throw count. With a file, any failure is [`Error::Output`].
    pub fn roll_versus(
        &self,
        (a, b): (&Params, &Params),
        options: &RunOptions,
        stop: &AtomicBool,
        csv: Option<&Output>,
        progress: &mut dyn FnMut(u64),
    ) -> Result<VersusRun, Error> {
        let rolls = self.rolls();
        let mut roll = |sink: &mut dyn FnMut(&[RollRecord]) -> Result<(), String>| {
            stream_versus(a, b, &rolls, options, stop, &mut |chunk| {
                progress(chunk.len() as u64 / 2);
                sink(chunk)
            })
        };
        let Some(output) = csv else {
            return roll(&mut |_| Ok(()));
        };
        let mut done = None;
        let columns = versus_columns(self.spin);
        let meta = data_file::sidecar(&self.provenance, &columns);
        output.write_table(Some(&meta), |w| {
            writeln!(w, "{}", data_file::header(&columns))?;
            let mut line = Vec::with_capacity(256);
            let run = keeping_io_errors(&mut roll, &mut |chunk| {
                for pair in chunk.chunks_exact(2) {
                    line.clear();
                    write_versus_line(&mut line, (&pair[0], &pair[1]), self.spin);
                    line.push(b'\n');
                    w.write_all(&line)?;
                }
                Ok(())
            })?;
            done = Some(run);
            Ok(())
        })?;
        Ok(done.expect("the throws were rolled"))
    }

    /// The part summary of `shard` of this sweep, which rolled `batch` and wrote `records`
    /// (the file and what was written into it) if any, for the part file at `part_path`.
    pub fn part(
        &self,
        shard: Shard,
        part_path: &Path,
        records: Option<(&Path, Written)>,
        batch: &BatchRun,
    ) -> Part {
        let sweep = Sweep::Batch {
            preset: self.preset.name.clone(),
            fingerprint: self.fingerprint.clone(),
            seed: self.seed(),
            rolls: self.total,
        };
        // The setup as rolled, so a merge draws every start again from it.
        let mut setup = self.preset.clone();
        setup.random.seed = self.seed;
        Part::of_batch(
            sweep,
            (shard, self.range.clone()),
            part_path,
            records,
            &setup,
            batch,
        )
    }
}

/// Runs `roll` with `sink`, which writes a file: the sink's own I/O error comes back whole
/// (the engine carries only its words), so a closed pipe stays a closed pipe.
fn keeping_io_errors<T>(
    roll: impl FnOnce(&mut dyn FnMut(&[RollRecord]) -> Result<(), String>) -> Result<T, Error>,
    sink: &mut dyn FnMut(&[RollRecord]) -> std::io::Result<()>,
) -> std::io::Result<T> {
    let mut kept = None;
    let done = roll(&mut |chunk| {
        sink(chunk).map_err(|e| {
            let words = e.to_string();
            kept = Some(e);
            words
        })
    });
    done.map_err(|e| {
        kept.take()
            .unwrap_or_else(|| std::io::Error::other(e.to_string()))
    })
}

/// The per-roll file as the records arrive: CSV, JSON or Parquet by extension. JSON puts
/// the rolls first and what is known only at the end (interrupted, summary) after them.
enum RecordsFile<'w> {
    Csv {
        w: &'w mut (dyn Write + Send),
        spin: SpinColumns,
        line: Vec<u8>,
    },
    Json {
        w: &'w mut (dyn Write + Send),
        first: bool,
    },
    Parquet(RecordsWriter<&'w mut (dyn Write + Send)>),
}

impl<'w> RecordsFile<'w> {
    /// Starts the file: a CSV with its header (its provenance is its sidecar's), a JSON
    /// with its provenance as a field, a Parquet file with it as key-value metadata.
    fn start(
        w: &'w mut (dyn Write + Send),
        extension: &str,
        (provenance, spin): (&Value, SpinColumns),
        seed: Option<u64>,
        requested: u64,
    ) -> std::io::Result<Self> {
        Ok(match extension {
            "csv" => {
                writeln!(w, "{}", crate::ics::records_csv_header(spin))?;
                RecordsFile::Csv {
                    w,
                    spin,
                    line: Vec::with_capacity(256),
                }
            }
            "json" => {
                write!(
                    w,
                    "{{\"provenance\":{provenance},\"seed\":{},\"requested\":{requested},\"rolls\":[",
                    json!(seed)
                )?;
                RecordsFile::Json { w, first: true }
            }
            _ => RecordsFile::Parquet(
                RecordsWriter::new(w, spin, &provenance.to_string()).map_err(std::io::Error::other)?,
            ),
        })
    }

    fn write(&mut self, records: &[RollRecord]) -> std::io::Result<()> {
        match self {
            RecordsFile::Csv { w, spin, line } => {
                for r in records {
                    line.clear();
                    write_record_line(line, r, *spin);
                    line.push(b'\n');
                    w.write_all(line)?;
                }
            }
            RecordsFile::Json { w, first } => {
                for r in records {
                    if !std::mem::take(first) {
                        w.write_all(b",")?;
                    }
                    serde_json::to_writer(&mut **w, r)?;
                }
            }
            RecordsFile::Parquet(parquet) => {
                for r in records {
                    parquet.write(r).map_err(std::io::Error::other)?;
                }
            }
        }
        Ok(())
    }

    fn finish(self, batch: &BatchRun) -> std::io::Result<()> {
        match self {
            RecordsFile::Csv { w, .. } => w.flush(),
            RecordsFile::Json { w, .. } => writeln!(
                w,
                "],\"interrupted\":{},\"summary\":{}}}",
                batch.cancelled,
                json!(batch.summary)
            ),
            RecordsFile::Parquet(parquet) => parquet.finish().map(drop).map_err(std::io::Error::other),
        }
    }
}

/// The columns of a roll's record that are its ending ([`Stage::Ending`]): face, status, steps,
/// time and the impacts.
fn ending(spin: SpinColumns) -> impl Iterator<Item = &'static RecordColumn> {
    spin.columns()
        .iter()
        .copied()
        .filter(|c| c.stage == Stage::Ending)
}

/// The columns of the per-throw CSV of a versus batch: the throw (id, initial condition,
/// start face) and each setup's ending, A's columns `a_…`, B's `b_…`.
pub fn versus_columns(spin: SpinColumns) -> Vec<Column> {
    let column = |c: &RecordColumn, side: &str| Column {
        name: format!("{side}{}", c.name()),
        kind: c.ty.kind(),
    };
    let mut all: Vec<Column> = (spin.columns().iter())
        .filter(|c| c.stage == Stage::Throw)
        .map(|c| column(c, ""))
        .collect();
    for side in ["a_", "b_"] {
        all.extend(ending(spin).map(|c| column(c, side)));
    }
    all
}

/// Appends one throw's row of the versus CSV: the throw, `a`'s ending, then `b`'s.
fn write_versus_line(line: &mut Vec<u8>, (a, b): (&RollRecord, &RollRecord), spin: SpinColumns) {
    let throw = spin.columns().iter().filter(|c| c.stage == Stage::Throw);
    for (k, c) in throw.enumerate() {
        if k > 0 {
            line.push(b',');
        }
        write_cell(line, (c.get)(a));
    }
    for r in [a, b] {
        for c in ending(spin) {
            line.push(b',');
            write_cell(line, (c.get)(r));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::batch::run_batch;
    use crate::tally::Tally;

    #[test]
    fn a_shard_rolls_its_slice_of_the_sweeps_ids() {
        let paper = Preset::default();
        let whole = BatchSweep::new(&paper, 7, None, 10, None);
        let shard = BatchSweep::new(&paper, 7, None, 10, Some(Shard { index: 1, count: 3 }));
        assert_eq!((shard.total, shard.range.clone()), (10, 3..6));
        // Every file of a sweep records the same provenance, shard or not.
        assert_eq!(shard.provenance, whole.provenance);
        let (Rolls::Random { first, count, .. }, Rolls::Random { count: all, .. }) =
            (shard.rolls(), whole.rolls())
        else {
            panic!("drawn rolls")
        };
        assert_eq!((first, count, all), (3, 3, 10));
        let given = [(4, paper.initial), (9, paper.initial)];
        let g = BatchSweep::new(&paper, 7, Some(&given), 0, None);
        assert_eq!((g.total, g.seed()), (2, None));
        assert!(matches!(g.rolls(), Rolls::Given(ics) if ics.len() == 2));
    }

    #[test]
    fn records_stream_to_a_file_whose_hash_the_part_keeps() {
        let paper = Preset::default();
        let sweep = BatchSweep::new(&paper, 7, None, 6, Some(Shard { index: 0, count: 2 }));
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p0.csv");
        let output = Output::check(&path, &["csv"], false).unwrap();
        let (params, never) = (paper.params(), AtomicBool::new(false));
        let mut counted = 0;
        let (batch, written) = sweep
            .roll(&params, &RunOptions::default(), &never, Some(&output), &mut |n| {
                counted += n
            })
            .unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let written = written.unwrap();
        assert_eq!(written, crate::hashing::hash_file(&path, written.bytes).unwrap());
        // The header, and one row per roll of the shard, in id order; the provenance in
        // the sidecar beside it.
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines[0],
            crate::ics::records_csv_header(SpinColumns::AngularVelocity)
        );
        assert_eq!((lines.len(), counted, batch.completed), (4, 3, 3));
        let meta: Value =
            serde_json::from_slice(&std::fs::read(dir.path().join("p0.csv.meta.json")).unwrap()).unwrap();
        assert_eq!(meta["provenance"], sweep.provenance);
        assert_eq!(meta["columns"][1]["name"], "height_cm");
        let ids: Vec<&str> = lines[1..].iter().map(|l| l.split(',').next().unwrap()).collect();
        assert_eq!(ids, ["0", "1", "2"]);
        let part = sweep.part(
            Shard { index: 0, count: 2 },
            &dir.path().join("p0.part.json"),
            Some((&path, written)),
            &batch,
        );
        assert_eq!((part.range, part.records.as_deref()), ([0, 3], Some("p0.csv")));
        // The part's counts are those of the rolls: the same as a batch that keeps them all.
        let kept = run_batch(&params, &sweep.rolls(), 0, &never, &mut |_| {}).unwrap();
        assert_eq!(part.tally, Some(Tally::of_records(kept.numbers, &kept.records)));
    }

    #[test]
    fn a_versus_row_is_the_throw_and_both_endings() {
        let spin = SpinColumns::AngularVelocity;
        let header: Vec<String> = versus_columns(spin).into_iter().map(|c| c.name).collect();
        let n = ending(spin).count();
        assert_eq!(header.len(), records_columns(spin).len() + n);
        assert_eq!(
            &header[header.len() - 2 * n..header.len() - 2 * n + 2],
            ["a_face", "a_status"]
        );
        assert_eq!(
            &header[header.len() - n..header.len() - n + 2],
            ["b_face", "b_status"]
        );
        assert_eq!(
            header.last().map(String::as_str),
            Some("b_first_impact_face_down")
        );
        let paper = Preset::default();
        let a = crate::roll_record(&paper.params(), &paper.initial, 4);
        let mut b = a;
        b.outcome.face = None;
        b.outcome.status = dicesim_physics::Status::Timeout;
        let mut line = Vec::new();
        write_versus_line(&mut line, (&a, &b), spin);
        let line = String::from_utf8(line).unwrap();
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), header.len());
        let a_line = crate::ics::record_csv_line(&a, spin);
        assert!(line.starts_with(&a_line), "{line}");
        assert_eq!(cells[cells.len() - n..cells.len() - n + 2], ["", "timeout"]);
    }
}
