//! A batch's parts merged: every record checked against the setup and the part's counts,
//! the merged records written as the one-machine CSV or Parquet files, in one pass over the
//! parts for all outputs together: every record is read, checked and written once.
//!
//! What is fixed for the sweep (the body's placement, the clock, the ranges' limits) is
//! worked out once ([`RecordCheck`]). A CSV row of a seeded sweep is checked by writing the
//! row its id's drawn start and its own ending give and comparing the two lines: the one
//! formatting of the record, no real parsed, every cell's spelling checked. The rows of a
//! piece of a part are checked in parallel, then taken in order.

use super::parts::{MergeError, Parts, checked_records_path, chosen_at_random};
use super::rows::{MAX_LINE_BYTES, without_bom};
use crate::columns::{COLUMNS, RecordCheck};
use crate::data_file;
use crate::ics::{
    SpinColumns, parse_record_line, read_drawn_row, records_columns, records_csv_header, write_cell,
    write_record_line,
};
use crate::parquet::{RecordsWriter, read_records};
use crate::provenance;
use crate::record::{RollRecord, roll_record};
use crate::shard::{Part, Sweep};
use crate::summary::BatchSummary;
use crate::tally::Tally;
use dicesim_physics::{InitialCondition, Params, StabilityCheck};
use dicesim_setup::output::{Output, OutputError, Staged, commit, sidecar_path};
use dicesim_setup::preset::{Preset, read_regular_file};
use dicesim_setup::random::RandomDraws;
use rayon::prelude::*;
use serde_json::Value;
use std::hash::Hasher;
use std::io::{Read, Write};
use std::path::Path;
use std::time::Duration;
use twox_hash::XxHash64;

/// A merged batch: what `merge` prints of it.
#[derive(Debug, Clone)]
pub struct BatchMerge {
    /// The sweep's provenance, as the merged files carry it.
    pub provenance: Value,
    /// The preset's name.
    pub preset: String,
    /// The seed of the draws; `None` for given initial conditions.
    pub seed: Option<u64>,
    /// Rolls of the whole sweep.
    pub rolls: u64,
    /// The statistics of every roll, its speed per second of all shards' time added up.
    pub summary: BatchSummary,
    pub shards: usize,
    /// s of wall-clock time of all shards added up, and of the longest.
    pub shard_s: f64,
    pub longest_s: f64,
    /// Records rolled again by `--verify`.
    pub verified: usize,
    /// Rolls that started past the stability limit, counted as the one-machine batch counts
    /// them: from the records, or from the seed's draws for parts that hold only summaries;
    /// `None` where neither is known (summaries of given starts).
    pub past_stability_limit: Option<u64>,
}

impl BatchMerge {
    /// What `merge --json` prints of it: what `batch --json` prints of a one-machine run,
    /// with the shards' own figures.
    pub fn report(&self) -> Value {
        serde_json::json!({
            "provenance": self.provenance,
            "preset": self.preset,
            "seed": self.seed,
            "requested": self.rolls,
            "completed": self.summary.rolls,
            "interrupted": false,
            "shards": self.shards,
            "longest_shard_s": self.longest_s,
            "verified": self.verified,
            "past_stability_limit": self.past_stability_limit,
            "summary": self.summary,
        })
    }
}

/// What takes each record read, in order, with its CSV row where it has one.
type Taker<'a> = dyn FnMut(&RollRecord, Option<&[u8]>) -> Result<(), MergeError> + 'a;

/// A record read, and the outcome of its checks.
type Checked = (RollRecord, Result<(), String>);

/// Bytes of a CSV part read and checked at a time (its rows checked in parallel).
const PIECE_BYTES: u64 = 4 << 20;

/// The largest sidecar read, bytes (one is a few kB).
const MAX_SIDECAR_BYTES: u64 = 1 << 20;

impl Parts {
    /// Merges a batch's parts into `outputs` (.csv or .parquet, all written or none), after
    /// checking every part's counts and every record ([`RecordCheck`]); `verify` records
    /// chosen at random are rolled again and must end bit for bit as recorded.
    pub fn merge_batch(&self, outputs: &[Output], verify: u64) -> Result<BatchMerge, MergeError> {
        let Sweep::Batch {
            preset: name,
            fingerprint,
            seed,
            rolls,
        } = &self.first().sweep
        else {
            unreachable!("merge_batch is called for batches")
        };
        let preset = self.setup()?;
        let params = preset.params();
        params.validate()?;
        let tally = self.tally(&params)?;
        let with_records = self.first().records.is_some();
        if verify > 0 && !with_records {
            return Err(MergeError::Parts(
                "--verify rolls records again: these parts hold only summaries".to_string(),
            ));
        }
        if seed.is_some() {
            // Every start is a draw from the ranges: those are checked once for all of them,
            // as the batch checked them before its first roll.
            (preset.random.validate())
                .and_then(|()| preset.random.check_clear_of_table(&params, &preset.initial))
                .map_err(|e| MergeError::Parts(format!("{}: its setup: {e}", self.parts[0].0.display())))?;
        }
        let sweep = provenance::batch(
            &preset,
            *seed,
            *rolls,
            seed.is_none().then_some(fingerprint.as_str()),
        );
        let spin = if with_records {
            self.spin_columns(seed.is_some())?
        } else {
            SpinColumns::AngularVelocity
        };
        let expect = BatchExpect {
            check: RecordCheck::new(&params),
            params,
            preset,
            seed: *seed,
            spin,
            header: records_csv_header(spin),
            provenance: provenance::built_by(sweep.clone(), &self.builds()),
            sweep,
        };
        let chosen = chosen_at_random(*rolls as usize, verify);
        let stability = StabilityCheck::new(&expect.params);
        let mut past_stability_limit = 0;
        let mut picked: Vec<RollRecord> = Vec::with_capacity(chosen.len());
        let mut staged = outputs
            .iter()
            .map(|o| {
                let meta =
                    (o.sidecar()).map(|_| data_file::sidecar(&expect.provenance, &records_columns(spin)));
                o.stage(meta.as_deref()).map_err(MergeError::unwritten)
            })
            .collect::<Result<Vec<Staged>, MergeError>>()?;
        if with_records {
            let mut sinks = (staged.iter_mut().zip(outputs))
                .map(|(w, o)| Sink::start(w, o, &expect))
                .collect::<Result<Vec<Sink<'_>>, MergeError>>()?;
            let mut each = |r: &RollRecord, line: Option<&[u8]>| -> Result<(), MergeError> {
                if chosen.binary_search(&(r.id as usize)).is_ok() {
                    picked.push(*r);
                }
                past_stability_limit += u64::from(!stability.predict(&r.initial).is_stable());
                sinks.iter_mut().try_for_each(|sink| sink.write(r, line))
            };
            for (path, p) in self.iter() {
                for_each_record(path, p, &expect, &mut each)?;
            }
            for sink in sinks {
                sink.finish()?;
            }
        }
        let past_stability_limit = match (with_records, *seed) {
            (true, _) => Some(past_stability_limit),
            (false, Some(seed)) => Some(
                (0..*rolls)
                    .filter(|&id| !stability.predict(&expect.draw(seed, id)).is_stable())
                    .count() as u64,
            ),
            (false, None) => None,
        };
        verify_records(&expect.params, &picked).map_err(|e| {
            let part = self
                .iter()
                .find(|(_, p)| (p.range[0]..p.range[1]).contains(&e.id));
            let file = part.and_then(|(path, p)| p.records_path(path));
            MergeError::Parts(match file {
                Some(file) => format!("{}: {e}", file.display()),
                None => e.to_string(),
            })
        })?;
        commit(staged).map_err(MergeError::unwritten)?;
        let (shard_s, longest_s) = self.shard_times();
        Ok(BatchMerge {
            provenance: expect.provenance,
            preset: name.clone(),
            seed: *seed,
            rolls: *rolls,
            summary: tally.summary(Duration::from_secs_f64(shard_s)),
            shards: self.parts.len(),
            shard_s,
            longest_s,
            verified: picked.len(),
            past_stability_limit,
        })
    }

    /// The spin columns of the sweep's records: a seeded sweep's draws give an angular
    /// velocity; given starts what the first part's file has (every shard's must be the same).
    fn spin_columns(&self, seeded: bool) -> Result<SpinColumns, MergeError> {
        if seeded {
            return Ok(SpinColumns::AngularVelocity);
        }
        let (part_path, part) = (&self.parts[0].0, self.first());
        let path = checked_records_path(part_path, part)?;
        let bad = |e: String| MergeError::Parts(format!("{}: {e}", path.display()));
        let file = std::fs::File::open(&path).map_err(|e| bad(e.to_string()))?;
        if path.extension().is_some_and(|e| e == "parquet") {
            return crate::parquet::records_spin(file).map_err(bad);
        }
        let mut first = Vec::new();
        file.take(MAX_LINE_BYTES)
            .read_to_end(&mut first)
            .map_err(|e| bad(e.to_string()))?;
        let header = String::from_utf8_lossy(&first);
        let header = without_bom(header.lines().next().unwrap_or_default().to_string());
        SpinColumns::of_header(&header).ok_or_else(|| {
            bad(format!(
                "line 1: header `{}` is not the header of a records file",
                header.escape_debug()
            ))
        })
    }

    /// The counts of every part added up, each checked first: one per number the setup's
    /// die shows, consistent in itself and with its shard's size and the setup's
    /// `max_steps` per roll.
    fn tally(&self, params: &Params) -> Result<Tally, MergeError> {
        let numbers = params.die.face_numbers();
        let max_steps = params.max_steps();
        let mut tally = Tally::new(numbers);
        for (path, p) in self.iter() {
            let t = &part_tally(path, p, numbers)?;
            if t.rolls != p.len() {
                return Err(MergeError::Parts(format!(
                    "{}: counts {} rolls, but its shard has {}",
                    path.display(),
                    t.rolls,
                    p.len()
                )));
            }
            t.check(max_steps)
                .map_err(|e| MergeError::Parts(format!("{}: {e}", path.display())))?;
            tally.merge(t);
        }
        Ok(tally)
    }
}

/// The counts batch part `p` (from the file at `path`) claims, as those of a die that shows
/// `numbers`.
fn part_tally(path: &Path, p: &Part, numbers: &'static [u8]) -> Result<Tally, MergeError> {
    let refused = |e: String| MergeError::Parts(format!("{}: {e}", path.display()));
    let t = p
        .tally
        .clone()
        .ok_or_else(|| refused("a batch part without its counts (`tally`)".to_string()))?;
    t.of_die(numbers).map_err(|e| refused(format!("`tally`: {e}")))
}

/// What a batch's records must be: the setup's checks and draws, the columns, and the
/// provenance of the sweep.
struct BatchExpect {
    check: RecordCheck,
    params: Params,
    preset: Preset,
    seed: Option<u64>,
    spin: SpinColumns,
    header: String,
    /// The sweep's provenance, as this program's build would write it.
    sweep: Value,
    /// The merged files' provenance: the sweep's, as the parts' build (or builds) wrote it.
    provenance: Value,
}

impl BatchExpect {
    /// The start the sweep's seed draws for roll `id`.
    fn draw(&self, seed: u64, id: u64) -> InitialCondition {
        self.preset.random.draw(&self.preset.initial, seed, id)
    }

    /// What a part's records file says of where it came from: the sweep's provenance with
    /// the part's build.
    fn provenance_of(&self, part: &Part) -> Value {
        provenance::built_by(self.sweep.clone(), &part.commit)
    }

    /// The checks of a record read from a Parquet file (or a CSV row that is not as the
    /// fast path expects): every field, its start against the draw of a seeded sweep.
    fn check_record(&self, r: &RollRecord) -> Result<(), String> {
        let drawn = self.seed.map(|seed| self.draw(seed, r.id));
        self.check.check(r, drawn.as_ref())
    }

    /// One CSV row read: the record, or the reason it is not a row this program writes;
    /// with it, the outcome of its checks. `line` is a scratch buffer.
    fn read_row(&self, row: &[u8], line: &mut Vec<u8>) -> Result<Checked, String> {
        if let Some(seed) = self.seed
            && let Some(r) = self.row_as_drawn(row, seed, line)
        {
            // The start is the draw bit for bit and every cell is spelt as written.
            return Ok((r, self.check.check_ending(&r)));
        }
        let r = parse_record_line(text(row)?, self.spin)?;
        Ok((r, self.check_record(&r)))
    }

    /// The record of `row` if it is exactly the row its id's draw and its own ending give,
    /// else `None`: the row is then read cell by cell, which names what differs.
    fn row_as_drawn(&self, row: &[u8], seed: u64, line: &mut Vec<u8>) -> Option<RollRecord> {
        read_drawn_row(row, self.spin, &|id| self.draw(seed, id), line)
    }
}

/// Where merged records go: a CSV (each checked row as it was read) or a Parquet file.
enum Sink<'a> {
    Csv(&'a mut Staged, SpinColumns),
    Parquet {
        // Boxed: a Parquet writer holds a row group of records.
        writer: Box<RecordsWriter<&'a mut Staged>>,
        path: &'a Path,
    },
}

impl<'a> Sink<'a> {
    /// Starts output `o`, staged in `w`: a CSV's header, a Parquet file's schema and
    /// provenance. An output of another kind is refused.
    fn start(w: &'a mut Staged, o: &'a Output, expect: &BatchExpect) -> Result<Sink<'a>, MergeError> {
        match super::parts::out_kind(o.path(), &["csv", "parquet"])? {
            "csv" => {
                writeln!(w, "{}", expect.header).map_err(|e| MergeError::unwritten(w.failed(&e)))?;
                Ok(Sink::Csv(w, expect.spin))
            }
            _ => {
                let writer = RecordsWriter::new(w, expect.spin, &expect.provenance.to_string())
                    .map_err(|e| unwritten(o.path(), e))?;
                Ok(Sink::Parquet {
                    writer: Box::new(writer),
                    path: o.path(),
                })
            }
        }
    }

    /// Writes one record: `line`, its CSV row as read and checked, where there is one.
    fn write(&mut self, r: &RollRecord, line: Option<&[u8]>) -> Result<(), MergeError> {
        match self {
            Sink::Csv(w, spin) => {
                let mut own = Vec::new();
                let line = line.unwrap_or_else(|| {
                    // Only a Parquet part gives no line: its record is written here once.
                    write_record_line(&mut own, r, *spin);
                    &own
                });
                (w.write_all(line).and_then(|()| w.write_all(b"\n")))
                    .map_err(|e| MergeError::unwritten(w.failed(&e)))
            }
            Sink::Parquet { writer, path } => writer.write(r).map_err(|e| unwritten(path, e)),
        }
    }

    fn finish(self) -> Result<(), MergeError> {
        match self {
            Sink::Csv(w, _) => w.flush().map_err(|e| MergeError::unwritten(w.failed(&e))),
            Sink::Parquet { writer, path } => writer.finish().map(drop).map_err(|e| unwritten(path, e)),
        }
    }
}

/// A merged file at `path` that was not written.
fn unwritten(path: &Path, e: impl std::fmt::Display) -> MergeError {
    MergeError::unwritten(OutputError::Write {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

/// The records of one part as they are read: each must be the next id of the part's range
/// and pass its checks, and they are counted for the part's summary.
struct Reading<'a> {
    part: &'a Part,
    /// The part summary's file, which names this records file.
    part_path: &'a Path,
    expect: &'a BatchExpect,
    path: &'a Path,
    next: u64,
    tally: Tally,
}

impl Reading<'_> {
    /// A problem at `row` (1-based) of the records file.
    fn at(&self, row: u64, e: String) -> MergeError {
        MergeError::Parts(format!("{}: row {row}: {e}", self.path.display()))
    }

    /// Takes the next record, `checked` the outcome of its checks, `line` its CSV row.
    fn take(
        &mut self,
        (r, checked): Checked,
        row: u64,
        line: Option<&[u8]>,
        each: &mut Taker<'_>,
    ) -> Result<(), MergeError> {
        if r.id != self.next {
            return Err(self.at(row, format!("roll id {}, expected {}", r.id, self.next)));
        }
        if self.next == self.part.range[1] {
            return Err(self.at(
                row,
                format!("more rolls than the {} the part summary counts", self.part.len()),
            ));
        }
        checked.map_err(|e| self.at(row, e))?;
        self.tally.add(&r);
        self.next += 1;
        each(&r, line)
    }

    /// Reads a CSV records file of `bytes` bytes (as its part says), hashing it as it is
    /// read: its header, then its rows, a piece at a time. A file whose size or hash is not
    /// the part's is refused for that before anything it holds.
    fn csv(
        &mut self,
        file: std::fs::File,
        (bytes, hash): (u64, &str),
        each: &mut Taker<'_>,
    ) -> Result<(), MergeError> {
        let mut reader = HashingReader {
            inner: file.take(bytes.saturating_add(1)),
            hash: XxHash64::with_seed(0),
            bytes: 0,
        };
        let read = self.csv_rows(&mut reader, each);
        // The rest of the file, for its hash, even after a bad row: a changed file is
        // refused as one.
        let _ = std::io::copy(&mut reader, &mut std::io::sink());
        let found = format!("{:016x}", reader.hash.finish());
        if reader.bytes != bytes || found != hash {
            return Err(MergeError::Parts(format!(
                "{} (records of {}): its content hash is {found}, but the shard wrote {hash}: the file was changed after it was written",
                self.path.display(),
                self.part_path.display()
            )));
        }
        read
    }

    fn csv_rows(&mut self, reader: &mut HashingReader, each: &mut Taker<'_>) -> Result<(), MergeError> {
        let mut buf: Vec<u8> = Vec::with_capacity(PIECE_BYTES as usize + MAX_LINE_BYTES as usize);
        let mut line_number = 1u64;
        let mut header_seen = false;
        loop {
            let before = buf.len();
            let n = (&mut *reader)
                .take(PIECE_BYTES)
                .read_to_end(&mut buf)
                .map_err(|e| MergeError::Failed(format!("{}: {e}", self.path.display())))?;
            let end_of_file = n == 0 || (n as u64) < PIECE_BYTES;
            let complete = match buf.iter().rposition(|&b| b == b'\n') {
                Some(last) => last + 1,
                None => 0,
            };
            if !end_of_file && complete == 0 && buf.len() > before && buf.len() as u64 > MAX_LINE_BYTES {
                return Err(self.at(line_number, format!("a line longer than {MAX_LINE_BYTES} bytes")));
            }
            let piece = &buf[..complete];
            let lines: Vec<&[u8]> = if piece.is_empty() {
                Vec::new()
            } else {
                piece[..piece.len() - 1].split(|&b| b == b'\n').collect()
            };
            let mut lines = lines.as_slice();
            if !header_seen && let Some((first, rest)) = lines.split_first() {
                let header = text(first).map_err(|e| self.at(1, e))?;
                let header = without_bom(header.to_string());
                if header != self.expect.header {
                    return Err(self.at(
                        1,
                        format!(
                            "header `{}`, expected `{}`",
                            header.escape_debug(),
                            self.expect.header
                        ),
                    ));
                }
                header_seen = true;
                line_number += 1;
                lines = rest;
            }
            self.take_piece(lines, line_number, each)?;
            line_number += lines.len() as u64;
            buf.drain(..complete);
            if end_of_file {
                break;
            }
        }
        if !buf.is_empty() {
            let long = buf.len() as u64 > MAX_LINE_BYTES;
            return Err(self.at(
                line_number,
                if long {
                    format!("a line longer than {MAX_LINE_BYTES} bytes")
                } else {
                    "the last line is cut short (no line end)".to_string()
                },
            ));
        }
        if !header_seen {
            return Err(self.at(1, "the file ends before its rows".to_string()));
        }
        Ok(())
    }

    /// Checks the rows `lines` (the first at file line `first`) in parallel, then takes
    /// them in order: the first problem by line is the one reported.
    fn take_piece(&mut self, lines: &[&[u8]], first: u64, each: &mut Taker<'_>) -> Result<(), MergeError> {
        let expect = self.expect;
        let read: Vec<Result<Checked, String>> = lines
            .par_iter()
            .map_init(
                || Vec::with_capacity(256),
                |scratch, line| {
                    if line.len() as u64 > MAX_LINE_BYTES {
                        return Err(format!("a line longer than {MAX_LINE_BYTES} bytes"));
                    }
                    expect.read_row(line, scratch)
                },
            )
            .collect();
        for (k, (result, line)) in read.into_iter().zip(lines).enumerate() {
            let row = first + k as u64;
            let record = result.map_err(|e| self.at(row, e))?;
            self.take(record, row, Some(line), each)?;
        }
        Ok(())
    }

    /// Reads a Parquet records file, whose metadata must hold the sweep's provenance.
    fn parquet(&mut self, file: std::fs::File, each: &mut Taker<'_>) -> Result<(), MergeError> {
        let provenance = self.expect.provenance_of(self.part).to_string();
        let mut row = 0;
        let mut failed = None;
        let spin = Some(self.expect.spin);
        read_records(file, Some(&provenance), spin, &mut |r| {
            row += 1;
            let checked = self.expect.check_record(&r);
            self.take((r, checked), row, None, each).map_err(|e| {
                let words = e.to_string();
                failed = Some(e);
                words
            })
        })
        .map(drop)
        .map_err(|e| {
            failed
                .take()
                .unwrap_or_else(|| MergeError::Parts(format!("{}: {e}", self.path.display())))
        })
    }
}

/// A line of a records file as text.
fn text(line: &[u8]) -> Result<&str, String> {
    std::str::from_utf8(line).map_err(|_| "a line that is not UTF-8 text".to_string())
}

/// A reader that keeps the count and XXH64 hash of the bytes read through it.
struct HashingReader {
    inner: std::io::Take<std::fs::File>,
    hash: XxHash64,
    bytes: u64,
}

impl Read for HashingReader {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.hash.write(&buf[..n]);
        self.bytes += n as u64;
        Ok(n)
    }
}

/// Calls `each` with every record of a batch part in order (and its CSV row, for a CSV
/// part), after checking the file is the one the shard wrote (its size and content hash,
/// and a CSV's sidecar its provenance) and each record field by field; the records' own
/// counts must be the part's summary. Errors name the file and the row.
fn for_each_record(
    part_path: &Path,
    part: &Part,
    expect: &BatchExpect,
    each: &mut Taker<'_>,
) -> Result<(), MergeError> {
    let path = part
        .records_path(part_path)
        .expect("checked: every part has records");
    let whole = |e: String| MergeError::Parts(format!("{}: {e}", path.display()));
    let mut reading = Reading {
        part,
        part_path,
        expect,
        path: &path,
        next: part.range[0],
        tally: Tally::new(expect.check.numbers()),
    };
    match path.extension().and_then(|e| e.to_str()) {
        Some("csv") => {
            let (bytes, hash) = super::parts::records_size_checked(part_path, part, &path)?;
            check_sidecar(&path, expect, part)?;
            let file = std::fs::File::open(&path).map_err(|e| whole(e.to_string()))?;
            reading.csv(file, (bytes, hash), each)?;
        }
        Some("parquet") => {
            let path = checked_records_path(part_path, part)?;
            let file = std::fs::File::open(&path).map_err(|e| whole(e.to_string()))?;
            reading.parquet(file, each)?;
        }
        _ => {
            return Err(MergeError::Parts(format!(
                "{}: records in {}, neither .csv nor .parquet",
                part_path.display(),
                path.display()
            )));
        }
    }
    if reading.next != part.range[1] {
        return Err(whole(format!(
            "holds {} of the {} rolls the part summary counts",
            reading.next - part.range[0],
            part.len()
        )));
    }
    let claimed = part_tally(part_path, part, expect.check.numbers())?;
    if reading.tally != claimed {
        return Err(MergeError::Parts(format!(
            "{}: its counts are not those of its records in {} ({})",
            part_path.display(),
            path.display(),
            tally_difference(&claimed, &reading.tally)
        )));
    }
    Ok(())
}

/// Checks that the sidecar of a part's CSV records says they are this sweep's, as the
/// part's build wrote it: a CSV carries its provenance there.
fn check_sidecar(records: &Path, expect: &BatchExpect, part: &Part) -> Result<(), MergeError> {
    let sidecar = sidecar_path(records);
    let provenance = expect.provenance_of(part);
    let want = data_file::sidecar(&provenance, &records_columns(expect.spin));
    let refused = |e: String| MergeError::Parts(format!("{}: {e}", sidecar.display()));
    if std::fs::symlink_metadata(&sidecar).is_err() {
        return Err(MergeError::Parts(format!(
            "{}: its sidecar {} is missing: a CSV's provenance is in it, which merge checks (copy it with the records)",
            records.display(),
            sidecar.display()
        )));
    }
    let found = read_regular_file(&sidecar, MAX_SIDECAR_BYTES).map_err(refused)?;
    if found.as_bytes() == want {
        return Ok(());
    }
    let found: Value = serde_json::from_str(&found)
        .map_err(|e| refused(format!("not the sidecar of a dicesim records file: {e}")))?;
    let want: Value = serde_json::from_slice(&want).expect("written as JSON");
    if found == want {
        // The same sidecar written out again by another tool (keys in another order).
        return Ok(());
    }
    Err(refused(
        match first_difference(&found["provenance"], &want["provenance"]) {
            Some((key, f, w)) => format!(
                "its provenance is not this sweep's: `{key}` is {f}, expected {w} (records of another sweep or build)"
            ),
            None if found["columns"] != want["columns"] => {
                "its columns are not those of the sweep's records".to_string()
            }
            None => "not written as this program writes a sidecar".to_string(),
        },
    ))
}

/// The first key (dotted path) where two JSON values differ, with both values there.
fn first_difference(found: &Value, want: &Value) -> Option<(String, String, String)> {
    match (found, want) {
        (Value::Object(f), Value::Object(w)) => {
            let keys: std::collections::BTreeSet<&String> = f.keys().chain(w.keys()).collect();
            keys.into_iter().find_map(|k| {
                let (a, b) = (f.get(k).unwrap_or(&Value::Null), w.get(k).unwrap_or(&Value::Null));
                first_difference(a, b).map(|(path, x, y)| {
                    let path = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{k}.{path}")
                    };
                    (path, x, y)
                })
            })
        }
        (f, w) if f == w => None,
        (f, w) => Some((String::new(), f.to_string(), w.to_string())),
    }
}

/// The first count in which a part's summary differs from its records' recount.
fn tally_difference(claimed: &Tally, found: &Tally) -> String {
    let pairs: [(&str, String, String); 5] = [
        (
            "faces",
            format!("{:?}", claimed.faces.counts),
            format!("{:?}", found.faces.counts),
        ),
        (
            "statuses",
            format!("{:?}", claimed.status),
            format!("{:?}", found.status),
        ),
        (
            "start faces",
            format!("{:?}", claimed.start_face),
            format!("{:?}", found.start_face),
        ),
        ("steps", claimed.steps.to_string(), found.steps.to_string()),
        (
            "simulated seconds",
            format!("{:?}", claimed.simulated_s),
            format!("{:?}", found.simulated_s),
        ),
    ];
    pairs
        .iter()
        .find(|(_, a, b)| a != b)
        .map_or("the rolls".to_string(), |(what, a, b)| {
            format!("{what}: the summary says {a}, the records give {b}")
        })
}

/// Rolls `records` again from their starts and refuses the merge if any ends differently
/// in any bit: the one check a consistent forgery cannot pass.
fn verify_records(params: &Params, records: &[RollRecord]) -> Result<(), Unverified> {
    // Each record is rolled once: the first column that differs is both the verdict and
    // what the refusal names.
    let differing = records.par_iter().find_map_first(|r| {
        let again = roll_record(params, &r.initial, r.id);
        let column = COLUMNS.iter().find(|c| !(c.get)(r).same((c.get)(&again)))?;
        Some((r, again, column))
    });
    let Some((r, again, column)) = differing else {
        return Ok(());
    };
    let cell = |r: &RollRecord| {
        let mut text = Vec::new();
        write_cell(&mut text, (column.get)(r));
        String::from_utf8_lossy(&text).into_owned()
    };
    Err(Unverified {
        id: r.id,
        column: column.name(),
        recorded: cell(r),
        rolled: cell(&again),
    })
}

/// A record that `--verify` rolled again and found other: the first column that differs.
#[derive(Debug)]
struct Unverified {
    id: u64,
    column: &'static str,
    recorded: String,
    rolled: String,
}

impl std::fmt::Display for Unverified {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "--verify: roll {} rolled again gives {} = {}, but its record says {}: the records are not what this setup rolls",
            self.id, self.column, self.rolled, self.recorded
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::FaceTally;
    use crate::summary::{StartFaceCounts, StatusCounts};

    #[test]
    fn a_recount_names_the_first_count_that_differs() {
        let claimed = Tally {
            faces: FaceTally::new(&[1, 2, 3, 4, 5, 6]),
            rolls: 2,
            steps: 900,
            status: StatusCounts {
                settled: 2,
                ..Default::default()
            },
            start_face: StartFaceCounts {
                same: 1,
                adjacent: 1,
                opposite: 0,
            },
            ..Tally::new(&[])
        };
        assert_eq!(tally_difference(&claimed, &claimed.clone()), "the rolls");
        let mut found = claimed.clone();
        found.steps = 901;
        assert_eq!(
            tally_difference(&claimed, &found),
            "steps: the summary says 900, the records give 901"
        );
        found.start_face.same = 2;
        assert_eq!(
            tally_difference(&claimed, &found),
            "start faces: the summary says StartFaceCounts { same: 1, adjacent: 1, opposite: 0 }, \
             the records give StartFaceCounts { same: 2, adjacent: 1, opposite: 0 }"
        );
    }

    #[test]
    fn verify_refuses_a_record_that_does_not_roll_as_written() {
        let paper = Preset::default();
        let params = paper.params();
        let honest = roll_record(&params, &paper.initial, 3);
        assert!(verify_records(&params, &[honest]).is_ok());
        let mut forged = honest;
        forged.outcome.steps += 1;
        let e = verify_records(&params, &[honest, forged])
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            format!(
                "--verify: roll 3 rolled again gives steps = {}, but its record says {}: the records are not what this setup rolls",
                honest.outcome.steps, forged.outcome.steps
            )
        );
    }
}
