//! `dicesim merge`: the shards of a sweep put back together, byte for byte the one-machine
//! result, after checking that they are all the shards of one sweep.

use super::CliError;
use super::basin::print_map_summary;
use super::batch::print_counts;
use super::shard::{PART_EXTENSION, read_part, records_path};
use crate::experiment::RollRecord;
use crate::experiment::ics::{record_csv_row, records_csv_header};
use crate::experiment::merge::{MergeError, check_roll_id, copy_rows, parse_map_row};
use crate::experiment::parquet::{RecordsWriter, read_records};
use crate::experiment::plot::write_image;
use crate::experiment::shard::{Part, Sweep, check_parts};
use crate::experiment::tally::Tally;
use crate::experiment::{Axis, BasinMap, FaceTally, Layer, Method};
use crate::output::Output;
use clap::Args;
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
}

pub(crate) fn run(args: &MergeArgs) -> Result<(), CliError> {
    // Existing files are refused before any work, unless replacing them was asked for.
    let outputs: Vec<Output> = args
        .out
        .iter()
        .map(|o| Output::check(o, &["csv", "parquet", "png", "svg"], args.force))
        .collect::<Result<_, _>>()
        .map_err(CliError::output("--out "))?;
    let paths = part_files(&args.parts)?;
    let parts: Vec<(String, Part)> = paths
        .iter()
        .map(|p| Ok((p.display().to_string(), read_part(p)?)))
        .collect::<Result<_, CliError>>()?;
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

/// Opens a part's records file, naming both files if it cannot.
fn open_records_file(part_path: &Path, part: &Part) -> Result<(PathBuf, std::fs::File), CliError> {
    let path = records_path(part_path, part).expect("checked: every part has records");
    let file = std::fs::File::open(&path).map_err(|e| {
        CliError::Parts(format!(
            "{} (records of {}): {e}",
            path.display(),
            part_path.display()
        ))
    })?;
    Ok((path, file))
}

/// Opens a part's records file for buffered reading.
fn open_records(part_path: &Path, part: &Part) -> Result<(PathBuf, BufReader<std::fs::File>), CliError> {
    let (path, file) = open_records_file(part_path, part)?;
    Ok((path, BufReader::with_capacity(1 << 20, file)))
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

/// Calls `each` with every record of a Parquet part, checking they are its ids in order.
fn for_each_record(
    part_path: &Path,
    part: &Part,
    each: &mut dyn FnMut(RollRecord) -> Result<(), String>,
) -> Result<(), CliError> {
    let (path, file) = open_records_file(part_path, part)?;
    let mut next = part.range[0];
    read_records(file, &mut |r| {
        if r.id != next {
            return Err(format!(
                "row {}: roll id {}, expected {next}",
                next - part.range[0],
                r.id
            ));
        }
        next += 1;
        each(r)
    })
    .map_err(|e| CliError::Parts(format!("{}: {e}", path.display())))?;
    if next != part.range[1] {
        return Err(CliError::Parts(format!(
            "{}: holds {} of the {} rolls the part summary counts",
            path.display(),
            next - part.range[0],
            part.len()
        )));
    }
    Ok(())
}

/// Names the part file whose rows failed.
fn row_error(path: &Path, e: MergeError) -> CliError {
    match e {
        MergeError::Io(e) => CliError::Sweep(format!("{}: {e}", path.display())),
        e => CliError::Parts(format!("{}: {e}", path.display())),
    }
}

/// The s of wall-clock time of all shards added up, and of the longest.
fn shard_times(parts: &[(&Path, &Part)]) -> (f64, f64) {
    let times = parts.iter().map(|(_, p)| p.elapsed_s);
    (times.clone().sum(), times.fold(0.0, f64::max))
}

fn merge_batch(args: &MergeArgs, outputs: &[Output], parts: &[(&Path, &Part)]) -> Result<(), CliError> {
    let Sweep::Batch {
        preset, seed, rolls, ..
    } = &parts[0].1.sweep
    else {
        unreachable!("merge_batch is called for batches")
    };
    let mut tally = Tally::default();
    for (path, p) in parts {
        let t = p.tally.as_ref().ok_or_else(|| {
            CliError::Parts(format!(
                "{}: a batch part without its counts (`tally`)",
                path.display()
            ))
        })?;
        if t.rolls != p.len() {
            return Err(CliError::Parts(format!(
                "{}: counts {} rolls, but its shard has {}",
                path.display(),
                t.rolls,
                p.len()
            )));
        }
        tally.merge(t);
    }
    for output in outputs {
        let out = output.path();
        let kind = out_kind(out, &["csv", "parquet"])?;
        let failed = |e: std::io::Error| CliError::output("")(output.failed(&e));
        output.write_with(|w| match kind {
            "csv" => {
                // Part files are copied line by line: no cell of a record needs quoting.
                let header = records_csv_header().join(",");
                writeln!(w, "{header}").map_err(failed)?;
                for (path, p) in parts {
                    if records_kind(path, p)? == "parquet" {
                        let mut csv = csv::Writer::from_writer(&mut *w);
                        for_each_record(path, p, &mut |r| {
                            csv.write_record(record_csv_row(&r)).map_err(|e| e.to_string())
                        })?;
                        csv.flush().map_err(failed)?;
                        continue;
                    }
                    let (records, reader) = open_records(path, p)?;
                    let first = p.range[0];
                    copy_rows(reader, &mut *w, &header, p.len(), &mut |n, row| {
                        check_roll_id(row, first + n)
                    })
                    .map_err(|e| row_error(&records, e))?;
                }
                Ok(())
            }
            _ => {
                let failed = |e: ParquetError| failed(std::io::Error::other(e));
                let mut parquet = RecordsWriter::new(&mut *w).map_err(failed)?;
                for (path, p) in parts {
                    if records_kind(path, p)? != "parquet" {
                        return Err(CliError::Parts(format!(
                            "{}: its records are CSV; a merged .parquet needs .parquet parts (or merge to .csv)",
                            path.display()
                        )));
                    }
                    for_each_record(path, p, &mut |r| parquet.write(&r).map_err(|e| e.to_string()))?;
                }
                parquet.finish().map_err(failed)?;
                Ok(())
            }
        }, |e| CliError::output("")(e))?;
    }
    let (shard_s, longest_s) = shard_times(parts);
    let summary = tally.summary(Duration::from_secs_f64(shard_s));
    let mut stdout = std::io::stdout().lock();
    if args.json {
        let v = json!({
            "preset": preset,
            "seed": seed,
            "requested": rolls,
            "completed": tally.rolls,
            "interrupted": false,
            "shards": parts.len(),
            "longest_shard_s": longest_s,
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
        for out in &args.out {
            writeln!(stdout, "wrote                  {}", out.display())?;
        }
    }
    Ok(())
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
    if !args.out.is_empty() {
        // One pass over the parts: the merged CSV as it is read, and every cell for images.
        let mut header = Vec::new();
        map.write_csv(&mut header)?;
        let header = String::from_utf8(header).expect("the CSV header is UTF-8");
        let header = header.trim_end();
        let csv_out = outputs
            .iter()
            .zip(&kinds)
            .find(|(_, k)| **k == "csv")
            .map(|(o, _)| o);
        let w = *width;
        let cells = &mut map.cells;
        let mut read_parts = |sink: &mut (dyn Write + Send)| -> Result<(), CliError> {
            let failed = |e: std::io::Error| match csv_out {
                Some(o) => CliError::output("")(o.failed(&e)),
                None => CliError::Io(e),
            };
            writeln!(sink, "{header}").map_err(failed)?;
            for (path, p) in parts {
                let (records, reader) = open_records(path, p)?;
                let first_cell = p.range[0] as usize * w;
                copy_rows(reader, &mut *sink, header, p.len() * w as u64, &mut |n, row| {
                    let index = first_cell + n as usize;
                    cells[index] = Some(parse_map_row(row, index % w, index / w)?);
                    Ok(())
                })
                .map_err(|e| row_error(&records, e))?;
            }
            Ok(())
        };
        match csv_out {
            Some(o) => o.write_with(&mut read_parts, |e| CliError::output("")(e))?,
            None => read_parts(&mut std::io::sink())?,
        }
        map.sampled = map.cells.iter().flatten().filter(|c| c.sampled).count();
        for (output, _) in outputs.iter().zip(&kinds).filter(|(_, k)| **k != "csv") {
            write_image(&map, layer, output).map_err(|e| match e {
                crate::experiment::Error::Output(e) => CliError::output("")(e),
                e => CliError::experiment(&format!("{}: ", output.path().display()))(e),
            })?;
        }
    }
    let (shard_s, longest_s) = shard_times(parts);
    let mut stdout = std::io::stdout().lock();
    print_map_summary(&mut stdout, &map, layer, &faces)?;
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
