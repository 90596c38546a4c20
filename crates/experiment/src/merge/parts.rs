//! The part summaries of one sweep read and checked against each other, and what both
//! kinds of merge share: the records files checked before they are read, the refusals, the
//! records `--verify` chooses.

use super::rows::RowError;
use crate::shard::{PART_EXTENSION, Part, Sweep, check_parts};
use dicesim_physics::{Outcome, ParamError};
use dicesim_setup::output::{Output, OutputError, check_apart};
use dicesim_setup::preset::Preset;
use std::path::{Path, PathBuf};

/// Why the parts of a sweep were not merged.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// The parts are not the shards of one sweep, or one of them is not what its shard
    /// wrote (the message names the file and the problem): bad input.
    #[error("{0}")]
    Parts(String),
    /// A part's records could not be read while merging.
    #[error("{0}")]
    Failed(String),
    /// The parts' setup holds a value outside its range.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// An output refused before any work, prefixed with the option it came from, or a
    /// merged file not written.
    #[error("{context}{source}")]
    Output {
        context: &'static str,
        #[source]
        source: OutputError,
    },
    /// A stream the merge writes failed.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

impl MergeError {
    /// A merged file that was not written.
    pub(super) fn unwritten(source: OutputError) -> MergeError {
        MergeError::Output { context: "", source }
    }
}

/// The part summaries of one sweep, every shard once, in shard order, each with its path.
pub struct Parts {
    pub(super) parts: Vec<(PathBuf, Part)>,
}

impl Parts {
    /// Reads the part summaries `given` (files, or folders of `*.part.json` files, in any
    /// order) and checks, before any work: that none of `outputs` (nor a CSV's sidecar) is
    /// one of them, of their records or of their records' sidecars, that they are every
    /// shard of one sweep rolled by one build ([`check_parts`]; by several builds of this
    /// version where `accept_mixed_builds`), and that they hold records if `outputs` asks
    /// for a merged file.
    pub fn read(
        given: &[PathBuf],
        outputs: &[Output],
        accept_mixed_builds: bool,
    ) -> Result<Parts, MergeError> {
        let paths = part_files(given)?;
        let parts: Vec<(String, Part)> = paths
            .iter()
            .map(|p| Ok((p.display().to_string(), Part::read(p).map_err(MergeError::Parts)?)))
            .collect::<Result<_, MergeError>>()?;
        let mut inputs: Vec<(PathBuf, String)> = Vec::new();
        for (path, (_, part)) in paths.iter().zip(&parts) {
            inputs.push((path.clone(), "a part summary".to_string()));
            if let Some(records) = part.records_path(path) {
                let sidecar = dicesim_setup::output::sidecar_path(&records);
                inputs.push((records, format!("the records of {}", path.display())));
                inputs.push((sidecar, format!("the records' sidecar of {}", path.display())));
            }
        }
        check_apart(outputs, &inputs).map_err(|source| MergeError::Output {
            context: "--out ",
            source,
        })?;
        let order = check_parts(&parts, accept_mixed_builds).map_err(MergeError::Parts)?;
        let mut parts: Vec<Option<Part>> = parts.into_iter().map(|(_, p)| Some(p)).collect();
        let parts: Vec<(PathBuf, Part)> = order
            .iter()
            .map(|&i| (paths[i].clone(), parts[i].take().expect("each shard once")))
            .collect();
        if let Some(first) = outputs.first()
            && parts[0].1.records.is_none()
        {
            return Err(MergeError::Parts(format!(
                "the parts hold only summaries (their shards ran without --out): nothing to write to {}",
                first.path().display()
            )));
        }
        Ok(Parts { parts })
    }

    /// Whether the sweep is a basin map's (else a batch's).
    pub fn is_map(&self) -> bool {
        matches!(self.parts[0].1.sweep, Sweep::Map { .. })
    }

    pub(super) fn first(&self) -> &Part {
        &self.parts[0].1
    }

    pub(super) fn iter(&self) -> impl Iterator<Item = (&Path, &Part)> {
        self.parts.iter().map(|(path, part)| (path.as_path(), part))
    }

    /// The setup every part records, which must be one text in all of them and, read as a
    /// preset, give the sweep's fingerprint (a seeded sweep's: given starts are in theirs).
    pub(super) fn setup(&self) -> Result<Preset, MergeError> {
        let (first_path, first) = (&self.parts[0].0, self.first());
        for (path, p) in self.iter() {
            if p.setup != first.setup {
                return Err(MergeError::Parts(format!(
                    "{} records another setup than {}: parts of one sweep record one",
                    path.display(),
                    first_path.display()
                )));
            }
        }
        let preset = Preset::from_toml_str(&first.setup, "setup").map_err(|e| {
            MergeError::Parts(format!(
                "{}: its `setup` is not a valid preset: {e}",
                first_path.display()
            ))
        })?;
        if let Sweep::Batch {
            fingerprint,
            seed: Some(_),
            ..
        }
        | Sweep::Map { fingerprint, .. } = &first.sweep
        {
            let found = crate::provenance::batch_fingerprint(&preset, None);
            if found != *fingerprint {
                return Err(MergeError::Parts(format!(
                    "{}: its `setup` has fingerprint {found}, but its sweep says {fingerprint}",
                    first_path.display()
                )));
            }
        }
        Ok(preset)
    }

    /// The build the parts were rolled by, as a merged file's provenance names it: their one
    /// commit, or each of them in shard order when several were accepted.
    pub(super) fn builds(&self) -> String {
        let mut commits: Vec<&str> = Vec::new();
        for (_, p) in self.iter() {
            if !commits.contains(&p.commit.as_str()) {
                commits.push(&p.commit);
            }
        }
        match commits.as_slice() {
            [one] => one.to_string(),
            several => format!("mixed builds: {}", several.join(", ")),
        }
    }

    /// The s of wall-clock time of all shards added up, and of the longest.
    pub(super) fn shard_times(&self) -> (f64, f64) {
        let times = self.parts.iter().map(|(_, p)| p.elapsed_s);
        (times.clone().sum(), times.fold(0.0, f64::max))
    }
}

/// The part files named: files as given, folders as the `*.part.json` files inside.
fn part_files(given: &[PathBuf]) -> Result<Vec<PathBuf>, MergeError> {
    let mut files = Vec::new();
    for path in given {
        if path.is_dir() {
            let suffix = format!(".{PART_EXTENSION}");
            let mut inside: Vec<PathBuf> = std::fs::read_dir(path)
                .map_err(|e| MergeError::Parts(format!("{}: {e}", path.display())))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.to_string_lossy().ends_with(&suffix))
                .collect();
            if inside.is_empty() {
                return Err(MergeError::Parts(format!(
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

/// The kind of an output file, from its extension as given, checked against what this
/// sweep writes.
pub(super) fn out_kind<'a>(path: &Path, allowed: &[&'a str]) -> Result<&'a str, MergeError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or_default();
    allowed.iter().find(|&&a| a == ext).copied().ok_or_else(|| {
        MergeError::Parts(format!(
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

/// The size and content hash a part says its records file `path` has, once the file is
/// found to be a regular file (never a FIFO or device, which would block or never end) of
/// that size: its hash is then checked as it is read.
pub(super) fn records_size_checked<'a>(
    part_path: &Path,
    part: &'a Part,
    path: &Path,
) -> Result<(u64, &'a str), MergeError> {
    let named = |e: String| {
        MergeError::Parts(format!(
            "{} (records of {}): {e}",
            path.display(),
            part_path.display()
        ))
    };
    let (bytes, hash) = (
        part.records_bytes.expect("checked with records"),
        part.records_hash.as_deref().expect("checked with records"),
    );
    let meta = std::fs::metadata(path).map_err(|e| named(e.to_string()))?;
    if !meta.is_file() {
        return Err(named("not a regular file".to_string()));
    }
    if meta.len() != bytes {
        return Err(named(size_words(meta.len(), bytes)));
    }
    Ok((bytes, hash))
}

/// How a records file of `found` bytes differs from the `bytes` its shard wrote.
fn size_words(found: u64, bytes: u64) -> String {
    format!(
        "{}{} bytes, but the shard wrote {bytes}: the file was cut, extended or replaced",
        if found > bytes { "more than " } else { "" },
        found.min(bytes)
    )
}

/// The records file a part names, checked before it is read: a regular file (never a FIFO
/// or device, which would block or never end) with exactly the size and content hash the
/// shard recorded when it wrote it.
pub(super) fn checked_records_path(part_path: &Path, part: &Part) -> Result<PathBuf, MergeError> {
    let path = part
        .records_path(part_path)
        .expect("checked: every part has records");
    let named = |e: String| {
        MergeError::Parts(format!(
            "{} (records of {}): {e}",
            path.display(),
            part_path.display()
        ))
    };
    let (bytes, hash) = (
        part.records_bytes.expect("checked with records"),
        part.records_hash.as_deref().expect("checked with records"),
    );
    let found = crate::hashing::hash_file(&path, bytes).map_err(named)?;
    if found.bytes != bytes {
        return Err(named(size_words(found.bytes, bytes)));
    }
    if found.hash != hash {
        return Err(named(format!(
            "its content hash is {}, but the shard wrote {hash}: the file was changed after it was written",
            found.hash
        )));
    }
    Ok(path)
}

/// Names the records file whose rows failed.
pub(super) fn row_error(path: &Path, e: RowError) -> MergeError {
    match e {
        RowError::Io(e) => MergeError::Failed(format!("{}: {e}", path.display())),
        e => MergeError::Parts(format!("{}: {e}", path.display())),
    }
}

/// `n` of the `total` records or cells (indices, increasing) for `--verify` to roll again,
/// chosen at random where a forger cannot foresee them.
pub(super) fn chosen_at_random(total: usize, n: u64) -> Vec<usize> {
    if n == 0 {
        return Vec::new();
    }
    let n = (n as usize).min(total);
    let mut chosen = rand::seq::index::sample(&mut rand::rng(), total, n).into_vec();
    chosen.sort_unstable();
    chosen
}

/// How an ending reads in a refusal: `settled on face 3`, `timeout`.
pub(super) fn outcome_words(o: &Outcome) -> String {
    match o.face {
        Some(f) => format!("{} on face {f}", o.status.name()),
        None => o.status.name().to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verify_chooses_distinct_records_within_the_sweep() {
        assert!(chosen_at_random(10, 0).is_empty());
        let some = chosen_at_random(1000, 50);
        assert_eq!(some.len(), 50);
        assert!(some.windows(2).all(|w| w[0] < w[1]) && some[49] < 1000);
        // Asking for more than there are rolls every one of them again.
        assert_eq!(chosen_at_random(5, 9), [0, 1, 2, 3, 4]);
    }

    #[test]
    fn an_output_must_be_of_a_kind_the_sweep_writes() {
        assert_eq!(out_kind(Path::new("m.csv"), &["csv", "parquet"]).unwrap(), "csv");
        assert_eq!(
            out_kind(Path::new("m.png"), &["csv", "parquet"])
                .unwrap_err()
                .to_string(),
            "--out m.png: expected a .csv, .parquet file"
        );
    }

    #[test]
    fn a_folder_gives_its_part_summaries_in_name_order() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["b.part.json", "a.part.json", "a.csv"] {
            std::fs::write(dir.path().join(name), "").unwrap();
        }
        let files = part_files(&[dir.path().to_path_buf()]).unwrap();
        let names: Vec<_> = files.iter().map(|p| p.file_name().unwrap().to_owned()).collect();
        assert_eq!(names, ["a.part.json", "b.part.json"]);
        let empty = tempfile::tempdir().unwrap();
        assert!(
            part_files(&[empty.path().to_path_buf()])
                .unwrap_err()
                .to_string()
                .ends_with(": no *.part.json files in this folder")
        );
    }
}
