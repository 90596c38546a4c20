//! A batch's parts merged: every record checked against the setup and the part's counts,
//! the merged records written as the one-machine CSV or Parquet file.

use super::parts::{MergeError, Parts, checked_records_path, chosen_at_random, out_kind, outcome_words};
use super::rows::{bounded_line, without_bom};
use crate::ics::{parse_record_csv_row, record_csv_line, records_csv_header};
use crate::parquet::{RecordsWriter, read_records};
use crate::provenance;
use crate::record::{RollRecord, check_record, roll_record, same_record};
use crate::shard::{Part, Sweep};
use crate::summary::BatchSummary;
use crate::tally::Tally;
use dicesim_physics::{InitialCondition, Params};
use dicesim_setup::output::Output;
use dicesim_setup::preset::Preset;
use dicesim_setup::random::RandomDraws;
use parquet::errors::ParquetError;
use rayon::prelude::*;
use std::io::BufReader;
use std::path::Path;
use std::time::Duration;

/// A merged batch: what `merge` prints of it.
#[derive(Debug, Clone)]
pub struct BatchMerge {
    /// The sweep's provenance, as its every file carries it.
    pub provenance: serde_json::Value,
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
}

impl Parts {
    /// Merges a batch's parts into `outputs` (.csv or .parquet), after checking every part's
    /// counts and every record ([`check_record`]); `verify` records chosen at random are
    /// rolled again and must end bit for bit as recorded.
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
        let tally = self.tally(params.max_steps())?;
        let with_records = self.first().records.is_some();
        if verify > 0 && !with_records {
            return Err(MergeError::Parts(
                "--verify rolls records again: these parts hold only summaries".to_string(),
            ));
        }
        let expect = BatchExpect {
            provenance: provenance::batch(
                &preset,
                *seed,
                *rolls,
                seed.is_none().then_some(fingerprint.as_str()),
            ),
            params,
            preset,
            seed: *seed,
        };
        let chosen = chosen_at_random(*rolls as usize, verify);
        let mut picked: Vec<RollRecord> = Vec::with_capacity(chosen.len());
        // Every part is read and checked once with or without outputs; each output reads again.
        if with_records {
            self.for_each_record(&expect, &mut |r| {
                if chosen.binary_search(&(r.id as usize)).is_ok() {
                    picked.push(*r);
                }
                Ok(())
            })?;
        }
        verify_records(&expect.params, &picked)?;
        for output in outputs {
            self.write_records(output, &expect)?;
        }
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
        })
    }

    /// The counts of every part added up, each checked first: consistent in itself and
    /// with its shard's size and the setup's `max_steps` per roll.
    fn tally(&self, max_steps: u64) -> Result<Tally, MergeError> {
        let mut tally = Tally::default();
        for (path, p) in self.iter() {
            let t = p.tally.as_ref().ok_or_else(|| {
                MergeError::Parts(format!(
                    "{}: a batch part without its counts (`tally`)",
                    path.display()
                ))
            })?;
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

    /// Calls `each` with every record of every part in order, each part checked by
    /// [`for_each_record`].
    fn for_each_record(
        &self,
        expect: &BatchExpect,
        each: &mut dyn FnMut(&RollRecord) -> Result<(), MergeError>,
    ) -> Result<(), MergeError> {
        for (path, p) in self.iter() {
            for_each_record(path, p, expect, each)?;
        }
        Ok(())
    }

    /// Writes the merged records to `output`, its kind by its extension as given.
    fn write_records(&self, output: &Output, expect: &BatchExpect) -> Result<(), MergeError> {
        let kind = out_kind(output.path(), &["csv", "parquet"])?;
        let failed = |e: std::io::Error| MergeError::unwritten(output.failed(&e));
        output.write_with(
            |w| match kind {
                "csv" => {
                    writeln!(w, "{}", provenance::csv_line(&expect.provenance)).map_err(failed)?;
                    writeln!(w, "{}", records_csv_header().join(",")).map_err(failed)?;
                    // The cells are numbers and status names, which CSV never quotes: the
                    // line is what the csv writer of a one-machine batch writes.
                    self.for_each_record(expect, &mut |r| {
                        writeln!(w, "{}", record_csv_line(r)).map_err(failed)
                    })?;
                    w.flush().map_err(failed)
                }
                _ => {
                    let failed = |e: ParquetError| failed(std::io::Error::other(e));
                    let mut parquet =
                        RecordsWriter::new(&mut *w, &expect.provenance.to_string()).map_err(failed)?;
                    self.for_each_record(expect, &mut |r| parquet.write(r).map_err(failed))?;
                    parquet.finish().map_err(failed)?;
                    Ok(())
                }
            },
            MergeError::unwritten,
        )
    }
}

/// What a batch's records must be: the setup's parameters, the start each id draws (for
/// a seeded sweep), and the provenance every file of the sweep carries.
struct BatchExpect {
    params: Params,
    preset: Preset,
    seed: Option<u64>,
    provenance: serde_json::Value,
}

impl BatchExpect {
    fn check(&self, r: &RollRecord) -> Result<(), String> {
        let drawn: Option<InitialCondition> = self
            .seed
            .map(|seed| self.preset.random.draw(&self.preset.initial, seed, r.id));
        check_record(r, &self.params, drawn.as_ref())
    }
}

/// The records of one part as they are read: each must be the next id of the part's range
/// and pass [`BatchExpect::check`], and they are counted for the part's summary.
struct Reading<'a> {
    part: &'a Part,
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

    fn take(
        &mut self,
        r: RollRecord,
        row: u64,
        each: &mut dyn FnMut(&RollRecord) -> Result<(), MergeError>,
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
        self.expect.check(&r).map_err(|e| self.at(row, e))?;
        self.tally.add(&r);
        self.next += 1;
        each(&r)
    }

    /// Reads a CSV records file: the sweep's provenance line, the header, then the rows.
    fn csv(
        &mut self,
        file: std::fs::File,
        each: &mut dyn FnMut(&RollRecord) -> Result<(), MergeError>,
    ) -> Result<(), MergeError> {
        let mut reader = BufReader::with_capacity(1 << 20, file);
        let mut buf = Vec::new();
        let expected = [
            provenance::csv_line(&self.expect.provenance),
            records_csv_header().join(","),
        ];
        for (line, want) in expected.iter().enumerate() {
            let at = line as u64 + 1;
            let got = bounded_line(&mut reader, &mut buf).map_err(|e| self.at(at, e))?;
            match got.map(|g| if line == 0 { without_bom(g) } else { g }) {
                Some(got) if got == *want => {}
                Some(got) => {
                    let what = if line == 0 { "provenance" } else { "header" };
                    return Err(self.at(at, format!("{what} `{}`, expected `{want}`", got.escape_debug())));
                }
                None => return Err(self.at(at, "the file ends before its rows".to_string())),
            }
        }
        let mut line = 3;
        while let Some(row) = bounded_line(&mut reader, &mut buf).map_err(|e| self.at(line, e))? {
            let r = parse_record_csv_row(&row).map_err(|e| self.at(line, e))?;
            self.take(r, line, each)?;
            line += 1;
        }
        Ok(())
    }

    /// Reads a Parquet records file, whose metadata must hold the sweep's provenance.
    fn parquet(
        &mut self,
        file: std::fs::File,
        each: &mut dyn FnMut(&RollRecord) -> Result<(), MergeError>,
    ) -> Result<(), MergeError> {
        let provenance = self.expect.provenance.to_string();
        let mut row = 0;
        let mut failed = None;
        read_records(file, Some(&provenance), &mut |r| {
            row += 1;
            self.take(r, row, each).map_err(|e| {
                let words = e.to_string();
                failed = Some(e);
                words
            })
        })
        .map_err(|e| {
            failed
                .take()
                .unwrap_or_else(|| MergeError::Parts(format!("{}: {e}", self.path.display())))
        })
    }
}

/// Calls `each` with every record of a batch part in order, after checking the file is
/// the one the shard wrote and each record field by field ([`check_record`]); the records'
/// own counts must be the part's summary. Errors name the file and the row.
fn for_each_record(
    part_path: &Path,
    part: &Part,
    expect: &BatchExpect,
    each: &mut dyn FnMut(&RollRecord) -> Result<(), MergeError>,
) -> Result<(), MergeError> {
    let path = checked_records_path(part_path, part)?;
    let whole = |e: String| MergeError::Parts(format!("{}: {e}", path.display()));
    let mut reading = Reading {
        part,
        expect,
        path: &path,
        next: part.range[0],
        tally: Tally::default(),
    };
    let file = std::fs::File::open(&path).map_err(|e| whole(e.to_string()))?;
    match path.extension().and_then(|e| e.to_str()) {
        Some("csv") => reading.csv(file, each)?,
        Some("parquet") => reading.parquet(file, each)?,
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
    let claimed = part.tally.as_ref().expect("checked: a batch part has its counts");
    if reading.tally != *claimed {
        return Err(MergeError::Parts(format!(
            "{}: its counts are not those of its records in {} ({})",
            part_path.display(),
            path.display(),
            tally_difference(claimed, &reading.tally)
        )));
    }
    Ok(())
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
fn verify_records(params: &Params, records: &[RollRecord]) -> Result<(), MergeError> {
    let differing = records
        .par_iter()
        .find_first(|r| !same_record(&roll_record(params, &r.initial, r.id), r));
    match differing {
        None => Ok(()),
        Some(r) => {
            let again = roll_record(params, &r.initial, r.id);
            Err(MergeError::Parts(format!(
                "--verify: roll {} rolled again ends {} after {} steps, but its record says {} after {}: the records are not what this setup rolls",
                r.id,
                outcome_words(&again.outcome),
                again.outcome.steps,
                outcome_words(&r.outcome),
                r.outcome.steps
            )))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::summary::{StartFaceCounts, StatusCounts};

    #[test]
    fn a_recount_names_the_first_count_that_differs() {
        let claimed = Tally {
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
            ..Default::default()
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
        assert!(
            e.starts_with(&format!(
                "--verify: roll 3 rolled again ends {} after {} steps, but its record says",
                outcome_words(&honest.outcome),
                honest.outcome.steps
            )),
            "{e}"
        );
        assert!(e.ends_with(&format!(
            "after {}: the records are not what this setup rolls",
            forged.outcome.steps
        )));
    }
}
