//! `dicesim merge`: the shards of a sweep put back together, byte for byte the one-machine
//! result, after checking that they are all the shards of one sweep.

use super::CliError;
use super::basin::print_map_summary;
use super::batch::print_counts;
use super::shard::{
    PART_EXTENSION, batch_fingerprint, batch_provenance, csv_provenance_line, hash_file, map_provenance,
    read_part, records_path,
};
use clap::Args;
use dicesim_experiment::basin::node_setup;
use dicesim_experiment::ics::{parse_record_csv_row, record_csv_line, records_csv_header};
use dicesim_experiment::merge::{MergeError, bounded_line, copy_rows, parse_map_row, without_bom};
use dicesim_experiment::parquet::{RecordsWriter, read_records};
use dicesim_experiment::record::{check_record, same_record};
use dicesim_experiment::shard::{Part, Sweep, check_parts};
use dicesim_experiment::tally::Tally;
use dicesim_experiment::{Axis, BasinMap, Cell, FaceTally, Layer, Method};
use dicesim_experiment::{RollRecord, roll_record};
use dicesim_figures::plot::write_image;
use dicesim_physics::{InitialCondition, Outcome, Params};
use dicesim_setup::output::Output;
use dicesim_setup::preset::Preset;
use dicesim_setup::random::RandomDraws;
use parquet::errors::ParquetError;
use serde_json::json;
use std::io::{BufReader, Write};
use std::path::{Path, PathBuf};
use std::time::Duration;

#[derive(Debug, Args)]
pub(crate) struct MergeArgs {
    /// The part summaries (`*.part.json`) that `batch --shard` or `basin --shard` wrote, or
    /// folders holding them; in any order.
    #[arg(required = true, value_name = "PARTS")]
    pub(crate) parts: Vec<PathBuf>,
    /// Write the merged result: a batch's .csv or .parquet; a map's .csv, .png or .svg
    /// (repeatable).
    /// Without it, only the summary is printed.
    #[arg(long, value_name = "FILE")]
    pub(crate) out: Vec<PathBuf>,
    /// Replace existing --out files.
    #[arg(long, requires = "out")]
    pub(crate) force: bool,
    /// Print the summary as one JSON object instead of text.
    #[arg(long)]
    pub(crate) json: bool,
    /// Roll N records chosen at random again and refuse the merge unless each ends bit for
    /// bit as recorded (the other checks catch damage and mix-ups; only rolling again
    /// catches records that are consistent but not what the setup rolls).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub(crate) verify: u64,
}

pub(crate) fn run(args: &MergeArgs) -> Result<(), CliError> {
    // A merge keeps nothing partial: a signal removes the file being written and exits.
    super::stop_at_once_on_signals()?;
    // Existing files are refused before any work, unless replacing them was asked for.
    let outputs = super::checked_outputs(&args.out, &["csv", "parquet", "png", "svg"], args.force)?;
    let paths = part_files(&args.parts)?;
    let parts: Vec<(String, Part)> = paths
        .iter()
        .map(|p| Ok((p.display().to_string(), read_part(p)?)))
        .collect::<Result<_, CliError>>()?;
    let mut inputs: Vec<(PathBuf, String)> = Vec::new();
    for (path, (_, part)) in paths.iter().zip(&parts) {
        inputs.push((path.clone(), "a part summary".to_string()));
        if let Some(records) = records_path(path, part) {
            inputs.push((records, format!("the records of {}", path.display())));
        }
    }
    dicesim_setup::output::check_apart(&outputs, &inputs).map_err(CliError::output("--out "))?;
    let order = check_parts(&parts).map_err(CliError::Parts)?;
    let ordered: Vec<(&Path, &Part)> = order.iter().map(|&i| (paths[i].as_path(), &parts[i].1)).collect();
    let first = ordered[0].1;
    if !args.out.is_empty() && first.records.is_none() {
        return Err(CliError::Parts(format!(
            "the parts hold only summaries (their shards ran without --out): nothing to write to {}",
            args.out[0].display()
        )));
    }
    match &first.sweep {
        Sweep::Batch { .. } => merge_batch(args, &outputs, &ordered),
        Sweep::Map { .. } => merge_map(args, &outputs, &ordered),
    }
}

/// The part files named: files as given, folders as the `*.part.json` files inside.
fn part_files(given: &[PathBuf]) -> Result<Vec<PathBuf>, CliError> {
    let mut files = Vec::new();
    for path in given {
        if path.is_dir() {
            let suffix = format!(".{PART_EXTENSION}");
            let mut inside: Vec<PathBuf> = std::fs::read_dir(path)
                .map_err(|e| CliError::Parts(format!("{}: {e}", path.display())))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.to_string_lossy().ends_with(&suffix))
                .collect();
            if inside.is_empty() {
                return Err(CliError::Parts(format!(
                    "{}: no *{suffix} files in this folder",
                    path.display()
                )));
            }
            inside.sort();
            files.extend(inside);
        } else {
            files.push(path.clone());
        }
    }
    Ok(files)
}

/// The kind of an output file, from its extension, checked against what this sweep writes.
fn out_kind<'a>(path: &Path, allowed: &[&'a str]) -> Result<&'a str, CliError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or_default();
    allowed.iter().find(|&&a| a == ext).copied().ok_or_else(|| {
        CliError::Parts(format!(
            "--out {}: expected a {} file",
            path.display(),
            allowed
                .iter()
                .map(|a| format!(".{a}"))
                .collect::<Vec<_>>()
                .join(", ")
        ))
    })
}

/// The records file a part names, checked before it is read: a regular file (never a FIFO
/// or device, which would block or never end) with exactly the size and content hash the
/// shard recorded when it wrote it.
fn checked_records_path(part_path: &Path, part: &Part) -> Result<PathBuf, CliError> {
    let path = records_path(part_path, part).expect("checked: every part has records");
    let named = |e: String| {
        CliError::Parts(format!(
            "{} (records of {}): {e}",
            path.display(),
            part_path.display()
        ))
    };
    let (bytes, hash) = (
        part.records_bytes.expect("checked with records"),
        part.records_hash.as_deref().expect("checked with records"),
    );
    let found = hash_file(&path, bytes).map_err(named)?;
    if found.bytes != bytes {
        return Err(named(format!(
            "{}{} bytes, but the shard wrote {bytes}: the file was cut, extended or replaced",
            if found.bytes > bytes { "more than " } else { "" },
            found.bytes.min(bytes)
        )));
    }
    if found.hash != hash {
        return Err(named(format!(
            "its content hash is {}, but the shard wrote {hash}: the file was changed after it was written",
            found.hash
        )));
    }
    Ok(path)
}

/// The format of a part's records, from its file name.
fn records_kind(part_path: &Path, part: &Part) -> Result<&'static str, CliError> {
    let path = records_path(part_path, part).expect("checked: every part has records");
    match path.extension().and_then(|e| e.to_str()) {
        Some("csv") => Ok("csv"),
        Some("parquet") => Ok("parquet"),
        _ => Err(CliError::Parts(format!(
            "{}: records in {}, neither .csv nor .parquet",
            part_path.display(),
            path.display()
        ))),
    }
}

/// Names the records file whose rows failed.
fn row_error(path: &Path, e: MergeError) -> CliError {
    match e {
        MergeError::Io(e) => CliError::Sweep(format!("{}: {e}", path.display())),
        e => CliError::Parts(format!("{}: {e}", path.display())),
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
        let drawn = self
            .seed
            .map(|seed| self.preset.random.draw(&self.preset.initial, seed, r.id));
        check_record(r, &self.params, drawn.as_ref())
    }
}

/// Calls `each` with every record of a batch part in order, after checking the file is
/// the one the shard wrote and each record field by field ([`check_record`]); the records'
/// own counts must be the part's summary. Errors name the file and the row.
fn for_each_record(
    part_path: &Path,
    part: &Part,
    expect: &BatchExpect,
    each: &mut dyn FnMut(&RollRecord) -> Result<(), CliError>,
) -> Result<(), CliError> {
    let path = checked_records_path(part_path, part)?;
    let at = |row: u64, e: String| CliError::Parts(format!("{}: row {row}: {e}", path.display()));
    let mut next = part.range[0];
    let mut tally = Tally::default();
    let mut take = |r: RollRecord, row: u64| -> Result<(), CliError> {
        if r.id != next {
            return Err(at(row, format!("roll id {}, expected {next}", r.id)));
        }
        if next == part.range[1] {
            return Err(at(
                row,
                format!("more rolls than the {} the part summary counts", part.len()),
            ));
        }
        expect.check(&r).map_err(|e| at(row, e))?;
        tally.add(&r);
        next += 1;
        each(&r)
    };
    let file = std::fs::File::open(&path).map_err(|e| CliError::Parts(format!("{}: {e}", path.display())))?;
    let whole = |e: String| CliError::Parts(format!("{}: {e}", path.display()));
    match records_kind(part_path, part)? {
        "csv" => {
            let mut reader = BufReader::with_capacity(1 << 20, file);
            let mut buf = Vec::new();
            let expected = [
                csv_provenance_line(&expect.provenance),
                records_csv_header().join(","),
            ];
            for (line, want) in expected.iter().enumerate() {
                let got = bounded_line(&mut reader, &mut buf).map_err(|e| at(line as u64 + 1, e))?;
                match got.map(|g| if line == 0 { without_bom(g) } else { g }) {
                    Some(got) if got == *want => {}
                    Some(got) => {
                        let what = if line == 0 { "provenance" } else { "header" };
                        return Err(at(
                            line as u64 + 1,
                            format!("{what} `{}`, expected `{want}`", got.escape_debug()),
                        ));
                    }
                    None => return Err(at(line as u64 + 1, "the file ends before its rows".to_string())),
                }
            }
            let mut line = 3;
            while let Some(row) = bounded_line(&mut reader, &mut buf).map_err(|e| at(line, e))? {
                let r = parse_record_csv_row(&row).map_err(|e| at(line, e))?;
                take(r, line)?;
                line += 1;
            }
        }
        _ => {
            let provenance = expect.provenance.to_string();
            let mut row = 0;
            let mut failed = None;
            read_records(file, Some(&provenance), &mut |r| {
                row += 1;
                take(r, row).map_err(|e| {
                    let words = e.to_string();
                    failed = Some(e);
                    words
                })
            })
            .map_err(|e| failed.take().unwrap_or_else(|| whole(e)))?;
        }
    }
    if next != part.range[1] {
        return Err(whole(format!(
            "holds {} of the {} rolls the part summary counts",
            next - part.range[0],
            part.len()
        )));
    }
    let claimed = part.tally.as_ref().expect("checked: a batch part has its counts");
    if tally != *claimed {
        return Err(CliError::Parts(format!(
            "{}: its counts are not those of its records in {} ({})",
            part_path.display(),
            path.display(),
            tally_difference(claimed, &tally)
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

/// The setup every part records, which must be one text in all of them and, read as a
/// preset, give the sweep's fingerprint (a seeded sweep's: given starts are in theirs).
fn part_setup(parts: &[(&Path, &Part)]) -> Result<Preset, CliError> {
    let (first_path, first) = parts[0];
    for (path, p) in parts {
        if p.setup != first.setup {
            return Err(CliError::Parts(format!(
                "{} records another setup than {}: parts of one sweep record one",
                path.display(),
                first_path.display()
            )));
        }
    }
    let bad = |e: String| {
        CliError::Parts(format!(
            "{}: its `setup` is not a valid preset: {e}",
            first_path.display()
        ))
    };
    let preset = Preset::from_toml_str(&first.setup, "setup").map_err(|e| bad(e.to_string()))?;
    if let Sweep::Batch {
        fingerprint,
        seed: Some(_),
        ..
    }
    | Sweep::Map { fingerprint, .. } = &first.sweep
    {
        let found = batch_fingerprint(&preset, None);
        if found != *fingerprint {
            return Err(CliError::Parts(format!(
                "{}: its `setup` has fingerprint {found}, but its sweep says {fingerprint}",
                first_path.display()
            )));
        }
    }
    Ok(preset)
}

/// Checks the counts every part summary claims, consistent in themselves and with its
/// shard's size.
fn check_counts(path: &Path, t: &Tally, p: &Part, max_steps: u64) -> Result<(), CliError> {
    if t.rolls != p.len() {
        return Err(CliError::Parts(format!(
            "{}: counts {} rolls, but its shard has {}",
            path.display(),
            t.rolls,
            p.len()
        )));
    }
    t.check(max_steps)
        .map_err(|e| CliError::Parts(format!("{}: {e}", path.display())))
}

/// The s of wall-clock time of all shards added up, and of the longest.
fn shard_times(parts: &[(&Path, &Part)]) -> (f64, f64) {
    let times = parts.iter().map(|(_, p)| p.elapsed_s);
    (times.clone().sum(), times.fold(0.0, f64::max))
}

fn merge_batch(args: &MergeArgs, outputs: &[Output], parts: &[(&Path, &Part)]) -> Result<(), CliError> {
    let Sweep::Batch {
        preset: name,
        fingerprint,
        seed,
        rolls,
    } = &parts[0].1.sweep
    else {
        unreachable!("merge_batch is called for batches")
    };
    let preset = part_setup(parts)?;
    let params = preset.params();
    params.validate()?;
    let max_steps = params.max_steps();
    let mut tally = Tally::default();
    for (path, p) in parts {
        let t = p.tally.as_ref().ok_or_else(|| {
            CliError::Parts(format!(
                "{}: a batch part without its counts (`tally`)",
                path.display()
            ))
        })?;
        check_counts(path, t, p, max_steps)?;
        tally.merge(t);
    }
    let with_records = parts[0].1.records.is_some();
    if args.verify > 0 && !with_records {
        return Err(CliError::Parts(
            "--verify rolls records again: these parts hold only summaries".to_string(),
        ));
    }
    let expect = BatchExpect {
        provenance: batch_provenance(
            &preset,
            *seed,
            *rolls,
            seed.is_none().then_some(fingerprint.as_str()),
        ),
        params,
        preset,
        seed: *seed,
    };
    // The records --verify rolls again, chosen at random where a forger cannot foresee them.
    let chosen: std::collections::BTreeSet<u64> = if args.verify > 0 {
        let n = args.verify.min(*rolls);
        rand::seq::index::sample(&mut rand::rng(), *rolls as usize, n as usize)
            .into_iter()
            .map(|i| i as u64)
            .collect()
    } else {
        Default::default()
    };
    let mut picked: Vec<RollRecord> = Vec::with_capacity(chosen.len());
    // Every part is read and checked once with or without outputs; each output reads again.
    let read_all = |each: &mut dyn FnMut(&RollRecord) -> Result<(), CliError>| -> Result<(), CliError> {
        for (path, p) in parts {
            for_each_record(path, p, &expect, each)?;
        }
        Ok(())
    };
    if with_records {
        read_all(&mut |r| {
            if chosen.contains(&r.id) {
                picked.push(*r);
            }
            Ok(())
        })?;
    }
    verify(&expect.params, &picked)?;
    for output in outputs {
        let out = output.path();
        let kind = out_kind(out, &["csv", "parquet"])?;
        let failed = |e: std::io::Error| CliError::output("")(output.failed(&e));
        output.write_with(
            |w| match kind {
                "csv" => {
                    writeln!(w, "{}", csv_provenance_line(&expect.provenance)).map_err(failed)?;
                    writeln!(w, "{}", records_csv_header().join(",")).map_err(failed)?;
                    // The cells are numbers and status names, which CSV never quotes: the
                    // line is what the csv writer of a one-machine batch writes.
                    read_all(&mut |r| writeln!(w, "{}", record_csv_line(r)).map_err(failed))?;
                    w.flush().map_err(failed)
                }
                _ => {
                    let failed = |e: ParquetError| failed(std::io::Error::other(e));
                    let mut parquet =
                        RecordsWriter::new(&mut *w, &expect.provenance.to_string()).map_err(failed)?;
                    read_all(&mut |r| parquet.write(r).map_err(failed))?;
                    parquet.finish().map_err(failed)?;
                    Ok(())
                }
            },
            |e| CliError::output("")(e),
        )?;
    }
    let (shard_s, longest_s) = shard_times(parts);
    let summary = tally.summary(Duration::from_secs_f64(shard_s));
    let mut stdout = std::io::stdout().lock();
    if args.json {
        let v = json!({
            "provenance": expect.provenance,
            "preset": name,
            "seed": seed,
            "requested": rolls,
            "completed": tally.rolls,
            "interrupted": false,
            "shards": parts.len(),
            "longest_shard_s": longest_s,
            "verified": picked.len(),
            "summary": summary,
        });
        writeln!(stdout, "{v}")?;
    } else {
        writeln!(stdout, "{} rolls in {} shards", summary.rolls, parts.len())?;
        print_counts(&mut stdout, &summary)?;
        writeln!(
            stdout,
            "speed                  {:.0} rolls per shard-second ({} steps; the shards took {shard_s:.2} s together, the longest {longest_s:.2} s)",
            summary.rolls_per_s, summary.steps
        )?;
        if !picked.is_empty() {
            writeln!(
                stdout,
                "verified               {} records chosen at random, rolled again: identical bit for bit",
                picked.len()
            )?;
        }
        for out in &args.out {
            writeln!(stdout, "wrote                  {}", out.display())?;
        }
    }
    Ok(())
}

/// Rolls `records` again from their starts and refuses the merge if any ends differently
/// in any bit: the one check a consistent forgery cannot pass.
fn verify(params: &Params, records: &[RollRecord]) -> Result<(), CliError> {
    use rayon::prelude::*;
    let differing = records
        .par_iter()
        .find_first(|r| !same_record(&roll_record(params, &r.initial, r.id), r));
    match differing {
        None => Ok(()),
        Some(r) => {
            let again = roll_record(params, &r.initial, r.id);
            Err(CliError::Parts(format!(
                "--verify: roll {} rolled again ends {} after {} steps, but its record says {} after {}: the records are not what this setup rolls",
                r.id,
                outcome_words(&again),
                again.outcome.steps,
                outcome_words(r),
                r.outcome.steps
            )))
        }
    }
}

/// Refuses a map part whose face counts are not those of its own cells.
fn check_map_faces(parts: &[(&Path, &Part)], cells: &[Option<Cell>], w: usize) -> Result<(), CliError> {
    for (path, p) in parts {
        let rows = p.range[0] as usize * w..p.range[1] as usize * w;
        let found: FaceTally = cells[rows]
            .iter()
            .flatten()
            .filter_map(|c| c.outcome.face)
            .collect();
        if Some(found) != p.map_faces {
            return Err(CliError::Parts(format!(
                "{}: its face counts {:?} are not those of its cells {:?}",
                path.display(),
                p.map_faces.map(|f| f.counts),
                found.counts
            )));
        }
    }
    Ok(())
}

/// Rolls the cells `chosen` (indices in row order) of a map with axes `(x, y)` again from
/// their nodes' starts (`base` with the two axis values set, as the shard rolled them) and
/// refuses the merge if any ends differently in any bit, its start face included.
fn verify_cells(
    params: &Params,
    base: &InitialCondition,
    (x, y): (&Axis, &Axis),
    cells: &[Option<Cell>],
    chosen: &[usize],
) -> Result<(), CliError> {
    use rayon::prelude::*;
    let w = x.cells;
    let again = |index: usize| {
        let (p, ic) = node_setup(params, base, x, y, index % w, index / w);
        roll_record(&p, &ic, index as u64)
    };
    let differs = |index: usize| {
        let r = again(index);
        match &cells[index] {
            Some(c) => {
                let (a, b) = (&c.outcome, &r.outcome);
                c.start_face != r.start_face
                    || (a.status, a.face, a.steps) != (b.status, b.face, b.steps)
                    || a.time_s.to_bits() != b.time_s.to_bits()
            }
            None => true,
        }
    };
    let Some(index) = chosen.par_iter().copied().find_first(|&k| differs(k)) else {
        return Ok(());
    };
    let r = again(index);
    let (i, j) = (index % w, index / w);
    let recorded = match &cells[index] {
        Some(c) => format!(
            "{} after {} steps (start face {})",
            cell_outcome_words(&c.outcome),
            c.outcome.steps,
            c.start_face
        ),
        None => "nothing".to_string(),
    };
    Err(CliError::Parts(format!(
        "--verify: cell ({i}, {j}) ({} = {}, {} = {}) rolled again ends {} after {} steps (start face {}), but its row says {recorded}: the cells are not what this setup rolls",
        x.key.key,
        x.value(i),
        y.key.key,
        y.value(j),
        cell_outcome_words(&r.outcome),
        r.outcome.steps,
        r.start_face,
    )))
}

fn cell_outcome_words(o: &Outcome) -> String {
    match o.face {
        Some(f) => format!("{} on face {f}", o.status.name()),
        None => o.status.name().to_string(),
    }
}

fn outcome_words(r: &RollRecord) -> String {
    cell_outcome_words(&r.outcome)
}

fn merge_map(args: &MergeArgs, outputs: &[Output], parts: &[(&Path, &Part)]) -> Result<(), CliError> {
    let Sweep::Map {
        x,
        y,
        width,
        height,
        layer,
        ..
    } = &parts[0].1.sweep
    else {
        unreachable!("merge_map is called for maps")
    };
    if args.json {
        return Err(CliError::Parts(
            "--json: a map's summary is text (its cells are the --out .csv)".to_string(),
        ));
    }
    let preset = part_setup(parts)?;
    let params = preset.params();
    params.validate()?;
    let bad_sweep = |e: String| CliError::Parts(format!("{}: {e}", parts[0].0.display()));
    let x = Axis::parse(x, *width).map_err(|e| bad_sweep(e.to_string()))?;
    let y = Axis::parse(y, *height).map_err(|e| bad_sweep(e.to_string()))?;
    let layer = [Layer::Face, Layer::SettleTime]
        .into_iter()
        .find(|l| l.name() == layer)
        .ok_or_else(|| bad_sweep(format!("unknown layer `{layer}`")))?;
    let mut faces = FaceTally::default();
    for (path, p) in parts {
        let f = p.map_faces.as_ref().ok_or_else(|| {
            CliError::Parts(format!(
                "{}: a map part without its face counts (`map_faces`)",
                path.display()
            ))
        })?;
        for (c, n) in faces.counts.iter_mut().zip(f.counts) {
            *c += n;
        }
    }
    let mut map = BasinMap {
        x,
        y,
        method: Method::Uniform,
        cells: vec![None; width * height],
        sampled: 0,
        complete: true,
        switched_to_uniform: None,
    };
    let kinds: Vec<&str> = args
        .out
        .iter()
        .map(|o| out_kind(o, &["csv", "png", "svg"]))
        .collect::<Result<_, _>>()?;
    // The cells --verify rolls again, chosen at random where a forger cannot foresee them.
    let chosen: Vec<usize> = if args.verify > 0 {
        let cells = width * height;
        let n = (args.verify as usize).min(cells);
        let mut chosen = rand::seq::index::sample(&mut rand::rng(), cells, n).into_vec();
        chosen.sort_unstable();
        chosen
    } else {
        Vec::new()
    };
    if !args.out.is_empty() || !chosen.is_empty() {
        // One pass over the parts: the merged CSV as it is read, and every cell for images
        // and --verify.
        let mut header = Vec::new();
        map.write_csv(&mut header)?;
        let header = String::from_utf8(header).expect("the CSV header is UTF-8");
        let header = header.trim_end();
        let provenance = map_provenance(&preset, &map);
        let provenance_line = csv_provenance_line(&provenance);
        let leading = [provenance_line.as_str(), header];
        let csv_out = outputs
            .iter()
            .zip(&kinds)
            .find(|(_, k)| **k == "csv")
            .map(|(o, _)| o);
        let w = *width;
        let (x_axis, y_axis) = (map.x.clone(), map.y.clone());
        let cells = &mut map.cells;
        let mut read_parts = |sink: &mut (dyn Write + Send)| -> Result<(), CliError> {
            let failed = |e: std::io::Error| match csv_out {
                Some(o) => CliError::output("")(o.failed(&e)),
                None => CliError::Io(e),
            };
            writeln!(sink, "{provenance_line}\n{header}").map_err(failed)?;
            for (path, p) in parts {
                let records = checked_records_path(path, p)?;
                let reader = std::fs::File::open(&records)
                    .map(|f| BufReader::with_capacity(1 << 20, f))
                    .map_err(|e| CliError::Parts(format!("{}: {e}", records.display())))?;
                let first_cell = p.range[0] as usize * w;
                copy_rows(reader, &mut *sink, &leading, p.len() * w as u64, &mut |n, row| {
                    let index = first_cell + n as usize;
                    let (i, j) = (index % w, index / w);
                    let (nx, ny) = (x_axis.value(i).to_string(), y_axis.value(j).to_string());
                    cells[index] = Some(parse_map_row(row, i, j, Some((&nx, &ny, &params)))?);
                    Ok(())
                })
                .map_err(|e| row_error(&records, e))?;
            }
            // Checked before the merged CSV is kept: a refused merge writes nothing.
            check_map_faces(parts, cells, w)?;
            verify_cells(&params, &preset.initial, (&x_axis, &y_axis), cells, &chosen)
        };
        match csv_out {
            Some(o) => o.write_with(&mut read_parts, |e| CliError::output("")(e))?,
            None => read_parts(&mut std::io::sink())?,
        }
        map.sampled = map.cells.iter().flatten().filter(|c| c.sampled).count();
        for (output, _) in outputs.iter().zip(&kinds).filter(|(_, k)| **k != "csv") {
            let setup = (preset.name.as_str(), &params, &preset.initial);
            write_image(&map, layer, setup, &provenance, output).map_err(|e| match e {
                dicesim_experiment::Error::Output(e) => CliError::output("")(e),
                e => CliError::experiment(&format!("{}: ", output.path().display()))(e),
            })?;
        }
    }
    let (shard_s, longest_s) = shard_times(parts);
    let mut stdout = std::io::stdout().lock();
    print_map_summary(&mut stdout, &map, layer, &faces)?;
    if !chosen.is_empty() {
        writeln!(
            stdout,
            "verified            {} cells chosen at random, rolled again: identical bit for bit",
            chosen.len()
        )?;
    }
    writeln!(
        stdout,
        "time                {shard_s:.2} s over {} shards (the longest {longest_s:.2} s)",
        parts.len()
    )?;
    for out in &args.out {
        writeln!(stdout, "wrote               {}", out.display())?;
    }
    Ok(())
}
