//! `--shard K/N` of `batch` and `basin`: the option, the part summary a shard leaves for
//! `dicesim merge`, and the setup fingerprints that tell sweeps apart.

use super::CliError;
use clap::Args;
use dicesim_experiment::shard::{PART_FORMAT, Part, Shard, Sweep, fingerprint};
use dicesim_experiment::{Axis, BasinMap, BatchRun};
use dicesim_physics::InitialCondition;
use dicesim_setup::output::Output;
use dicesim_setup::preset::Preset;
use std::hash::Hasher;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use twox_hash::XxHash64;

/// The extension of a part summary, replacing the records file's.
pub(crate) const PART_EXTENSION: &str = "part.json";

#[derive(Debug, Clone, Default, Args)]
pub(crate) struct ShardArgs {
    /// Roll only shard K of N (K from 0): ids ⌊K·R/N⌋ up to ⌊(K+1)·R/N⌋ of the same R rolls
    /// (rows of a map); `dicesim merge` puts the N parts back into the one-machine result.
    #[arg(long, value_name = "K/N", value_parser = Shard::parse)]
    pub(crate) shard: Option<Shard>,
    /// Where the shard's summary for `dicesim merge` goes (default: --out with the extension
    /// `.part.json`). Without --out the shard keeps only this summary: its counts.
    #[arg(long, value_name = "FILE.part.json", requires = "shard")]
    pub(crate) part: Option<PathBuf>,
}

impl ShardArgs {
    /// The shard to roll and where its summary goes (checked like any output: an existing
    /// summary is replaced only with `force`), or `None` for a whole run.
    pub(crate) fn resolve(
        &self,
        out: Option<&Path>,
        force: bool,
    ) -> Result<Option<(Shard, Output)>, CliError> {
        let Some(shard) = self.shard else {
            return Ok(None);
        };
        let part = match (&self.part, out) {
            (Some(part), _) => part.clone(),
            (None, Some(out)) => out.with_extension(PART_EXTENSION),
            (None, None) => {
                return Err(CliError::Usage(
                    "--shard needs --out (the shard's records) or --part (only its summary)".to_string(),
                ));
            }
        };
        if out == Some(part.as_path()) {
            return Err(CliError::Usage(format!(
                "--part {} would overwrite the records of --out",
                part.display()
            )));
        }
        let part = Output::check(&part, &["json"], force).map_err(CliError::output("--part "))?;
        Ok(Some((shard, part)))
    }
}

/// A writer that passes bytes on and keeps their count and XXH64 hash: a shard's records
/// are hashed as they are written, without reading the file again.
pub(crate) struct Hashing<W> {
    inner: W,
    bytes: u64,
    hash: XxHash64,
}

impl<W: Write> Hashing<W> {
    pub(crate) fn new(inner: W) -> Self {
        Hashing {
            inner,
            bytes: 0,
            hash: XxHash64::with_seed(0),
        }
    }

    /// The bytes written and their hash, as a part records them.
    pub(crate) fn seal(&self) -> Written {
        Written {
            bytes: self.bytes,
            hash: format!("{:016x}", self.hash.finish()),
        }
    }
}

impl<W: Write> Write for Hashing<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hash.write(&buf[..n]);
        self.bytes += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// A records file's size and content hash.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Written {
    pub(crate) bytes: u64,
    pub(crate) hash: String,
}

/// The size and hash of a records file, read in bounded pieces; only a regular file is
/// opened (a FIFO or device named as records would block or never end) and at most
/// `expected_bytes + 1` bytes are read.
pub(crate) fn hash_file(path: &Path, expected_bytes: u64) -> Result<Written, String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".to_string());
    }
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut h = Hashing::new(std::io::sink());
    std::io::copy(&mut file.take(expected_bytes.saturating_add(1)), &mut h).map_err(|e| e.to_string())?;
    Ok(h.seal())
}

/// The part's fields every shard fills the same way.
pub(crate) fn new_part(
    sweep: Sweep,
    shard: Shard,
    range: std::ops::Range<u64>,
    part_path: &Path,
    records: Option<(&Path, Written)>,
    setup: &Preset,
) -> Part {
    Part {
        part_format: PART_FORMAT,
        version: env!("CARGO_PKG_VERSION").to_string(),
        sweep,
        shard,
        range: [range.start, range.end],
        complete: false,
        records_bytes: records.as_ref().map(|(_, w)| w.bytes),
        records_hash: records.as_ref().map(|(_, w)| w.hash.clone()),
        records: records.map(|(r, _)| records_reference(part_path, r)),
        setup: setup.to_toml(),
        tally: None,
        map_faces: None,
        elapsed_s: 0.0,
        jobs: 0,
    }
}

/// How a part names its records file: by file name when both sit in one folder (so a
/// folder of parts can be moved or copied as a whole), else by absolute path.
fn records_reference(part: &Path, records: &Path) -> String {
    let folder = |p: &Path| p.parent().map(Path::to_path_buf).unwrap_or_default();
    match records.file_name() {
        Some(name) if folder(part) == folder(records) => name.to_string_lossy().into_owned(),
        _ => std::path::absolute(records)
            .unwrap_or_else(|_| records.to_path_buf())
            .to_string_lossy()
            .into_owned(),
    }
}

/// The records file a part names, as a path (relative names are relative to the part).
pub(crate) fn records_path(part_path: &Path, part: &Part) -> Option<PathBuf> {
    let name = Path::new(part.records.as_deref()?);
    Some(if name.is_absolute() {
        name.to_path_buf()
    } else {
        part_path.parent().unwrap_or(Path::new("")).join(name)
    })
}

/// The fingerprint of a batch's setup: every value of the preset but its name, description
/// and seed (a merge names a different seed as such), and the given initial conditions.
pub(crate) fn batch_fingerprint(preset: &Preset, given: Option<&[(u64, InitialCondition)]>) -> String {
    // As the part's setup writes it, so a merge can recompute it from there.
    let mut values = preset.as_written();
    values.name.clear();
    values.description.clear();
    values.random.seed = 0;
    fingerprint(&(values, given))
}

/// What every batch output says about where it came from: this program's version and
/// the setup that defines the rolls (the preset's values, the seed, the roll count, or the
/// fingerprint of given initial conditions). Never the engine, threads, shard or time, so
/// a file is the same bytes however it was rolled. `merge` rebuilds it from a part.
pub(crate) fn batch_provenance(
    preset: &Preset,
    seed: Option<u64>,
    rolls: u64,
    given_fingerprint: Option<&str>,
) -> serde_json::Value {
    let mut values = preset.as_written();
    if let Some(seed) = seed {
        values.random.seed = seed;
    }
    serde_json::json!({
        "program": dicesim_experiment::PROGRAM,
        "preset": values,
        "seed": seed,
        "rolls": rolls,
        "initial_conditions": match given_fingerprint {
            Some(f) => format!("given (--ics), fingerprint {f}"),
            None => "drawn from the preset's [random] ranges with the seed".to_string(),
        },
    })
}

/// The provenance as a CSV file's first line: a `#` comment, which `--ics` skips and
/// `merge` requires to be the sweep's own.
pub(crate) fn csv_provenance_line(provenance: &serde_json::Value) -> String {
    format!("# {provenance}")
}

/// What every map output says about where it came from: this program's version, the
/// preset's values (the start every cell varies two values of), each axis as `KEY:MIN:MAX`
/// with its node count, and how the cells were found (every node rolled, or the adaptive
/// method). Never the engine, threads, shard or time: a merged map is the same bytes as the
/// map rolled on one machine. `merge` rebuilds it from the parts.
pub(crate) fn map_provenance(preset: &Preset, map: &BasinMap) -> serde_json::Value {
    let axis = |a: &Axis| {
        serde_json::json!({
            "axis": format!("{}:{}:{}", a.key.key, a.min, a.max),
            "nodes": a.cells,
        })
    };
    serde_json::json!({
        "program": dicesim_experiment::PROGRAM,
        "preset": preset.as_written(),
        "x": axis(&map.x),
        "y": axis(&map.y),
        "method": map.method.name(),
    })
}

/// The fingerprint of a map's setup: the preset's values (the axes are compared apart).
pub(crate) fn map_fingerprint(preset: &Preset) -> String {
    batch_fingerprint(preset, None)
}

/// Writes `part` as JSON, atomically.
pub(crate) fn write_part(output: &Output, part: &Part) -> Result<(), CliError> {
    output
        .write(|w| {
            serde_json::to_writer_pretty(&mut *w, part)?;
            writeln!(w)
        })
        .map_err(CliError::output(""))
}

/// The largest part summary read, bytes (a part is a few kB; its setup the largest part).
const MAX_PART_BYTES: u64 = 1 << 20;

/// Reads a part summary, naming the file and the JSON problem when it is not one. Only a
/// regular file of at most [`MAX_PART_BYTES`] is read: a FIFO named `*.part.json` is
/// refused rather than waited on.
pub(crate) fn read_part(path: &Path) -> Result<Part, CliError> {
    let text = dicesim_setup::preset::read_regular_file(path, MAX_PART_BYTES)
        .map_err(|e| CliError::Parts(format!("{}: {e}", path.display())))?;
    let de = &mut serde_json::Deserializer::from_str(&text);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let at = e.path().to_string();
        let inner = e.into_inner();
        CliError::Parts(format!(
            "{}: not a dicesim part summary: {}{inner}",
            path.display(),
            if at == "." {
                String::new()
            } else {
                format!("at `{at}`: ")
            }
        ))
    })
}

/// Writes the part summary of a batch shard that rolled `batch` (ids `range` of `sweep`),
/// its records in `records` if any.
pub(crate) fn write_batch_part(
    output: &Output,
    sweep: Sweep,
    shard: Shard,
    range: std::ops::Range<u64>,
    records: Option<(&Path, Written)>,
    setup: &Preset,
    batch: &BatchRun,
) -> Result<(), CliError> {
    let mut part = new_part(sweep, shard, range, output.path(), records, setup);
    part.complete = !batch.cancelled;
    part.tally = Some(batch.tally.clone());
    part.elapsed_s = batch.summary.elapsed_s;
    part.jobs = batch.jobs;
    write_part(output, &part)
}
