//! Sweeps split across machines: shards, the summary each shard leaves, and the checks a
//! merge makes before it puts the parts together.
//!
//! A roll's initial condition depends on (seed, roll id) alone and a map cell on its node
//! alone, so rolling ids `[⌊K·R/N⌋, ⌊(K+1)·R/N⌋)` in shard `K` of `N` and putting the parts
//! back in shard order gives exactly the rolls of one run. What a merge must make sure of
//! is that the parts really are the shards of one sweep: [`check_parts`].

use crate::basin::{BasinMap, Layer};
use crate::batch::BatchRun;
use crate::hashing::Written;
use crate::provenance;
use crate::stats::FaceTally;
use crate::tally::Tally;
use dicesim_setup::output::{Output, OutputError};
use dicesim_setup::preset::{Preset, read_regular_file};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// The part-summary format this program writes and reads; others are refused (format 1
/// had no setup and no content hash of its records, so its records could not be checked;
/// format 2 no commit, and CSV records with their provenance on their first line).
pub const PART_FORMAT: u32 = 3;

/// The extension of a part summary, replacing the records file's.
pub const PART_EXTENSION: &str = "part.json";

/// s, the longest time a part may say its shard took (32 years): sums of any number of
/// parts then stay finite.
const MAX_ELAPSED_S: f64 = 1e9;

/// Shard `index` of `count` (0-based): an equal slice of a sweep's rolls or map rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shard {
    pub index: u64,
    pub count: u64,
}

impl Shard {
    /// A shard from `K/N` with `0 ≤ K < N`, e.g. `3/8` (the fourth of eight).
    pub fn parse(s: &str) -> Result<Shard, String> {
        let bad = |why: &str| format!("`{s}`: {why}");
        let (k, n) = s
            .split_once('/')
            .ok_or_else(|| bad("expected K/N, e.g. 0/8 for the first of 8 shards"))?;
        let whole = |t: &str| {
            t.trim()
                .parse::<u64>()
                .map_err(|_| bad(&format!("`{t}` is not a whole number")))
        };
        let (index, count) = (whole(k)?, whole(n)?);
        if count == 0 {
            return Err(bad("N must be at least 1"));
        }
        if index >= count {
            return Err(bad(&format!("K counts from 0, so it must be below N = {count}")));
        }
        Ok(Shard { index, count })
    }

    /// The ids (or rows) `[⌊K·total/N⌋, ⌊(K+1)·total/N⌋)` of this shard; the shards of one
    /// `count` cover `0..total` without gaps or overlaps, in order.
    pub fn range(&self, total: u64) -> Range<u64> {
        let at = |k: u64| (k as u128 * total as u128 / self.count as u128) as u64;
        at(self.index)..at(self.index + 1)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// What a sweep is; every shard of one sweep carries the same.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum Sweep {
    /// A batch of rolls; shards split the roll ids.
    Batch {
        /// The preset's name (shown, not compared: the fingerprint covers its values).
        preset: String,
        fingerprint: String,
        /// `None` for given initial conditions (an `--ics` file).
        seed: Option<u64>,
        /// Rolls of the whole sweep.
        rolls: u64,
    },
    /// A basin map; shards split the rows.
    Map {
        preset: String,
        fingerprint: String,
        /// `KEY:MIN:MAX` of each axis.
        x: String,
        y: String,
        width: usize,
        height: usize,
        /// `face` or `settle-time`, for the image a merge draws.
        layer: String,
    },
}

impl Sweep {
    /// The sweep of a map of `setup` over the axes `x` and `y` (`KEY:MIN:MAX`, as given) on
    /// a `width`×`height` grid, to be drawn as `layer`.
    pub fn map(setup: &Preset, (x, y): (&str, &str), (width, height): (usize, usize), layer: Layer) -> Sweep {
        Sweep::Map {
            preset: setup.name.clone(),
            fingerprint: provenance::map_fingerprint(setup),
            x: x.to_string(),
            y: y.to_string(),
            width,
            height,
            layer: layer.name().to_string(),
        }
    }

    /// How many ids (rolls) or rows the shards split.
    pub(crate) fn total(&self) -> u64 {
        match self {
            Sweep::Batch { rolls, .. } => *rolls,
            Sweep::Map { height, .. } => *height as u64,
        }
    }

    fn name(&self) -> &'static str {
        match self {
            Sweep::Batch { .. } => "batch",
            Sweep::Map { .. } => "map",
        }
    }

    /// What differs between two sweeps, in words, or `None` if they are the same sweep.
    fn difference(&self, other: &Sweep) -> Option<String> {
        let field =
            |what: &str, a: &dyn fmt::Display, b: &dyn fmt::Display| Some(format!("{what} {a}, not {b}"));
        match (self, other) {
            (
                Sweep::Batch {
                    fingerprint: f,
                    seed: s,
                    rolls: r,
                    ..
                },
                Sweep::Batch {
                    fingerprint: g,
                    seed: t,
                    rolls: q,
                    ..
                },
            ) => {
                let seed = |s: &Option<u64>| {
                    s.map_or("none (given initial conditions)".to_string(), |s| s.to_string())
                };
                if f != g {
                    field("a setup with fingerprint", g, f)
                } else if s != t {
                    field("seed", &seed(t), &seed(s))
                } else if r != q {
                    field("a total of rolls", q, r)
                } else {
                    None
                }
            }
            (
                Sweep::Map {
                    fingerprint: f,
                    x,
                    y,
                    width: w,
                    height: h,
                    layer: l,
                    ..
                },
                Sweep::Map {
                    fingerprint: g,
                    x: x2,
                    y: y2,
                    width: w2,
                    height: h2,
                    layer: l2,
                    ..
                },
            ) => {
                if f != g {
                    field("a setup with fingerprint", g, f)
                } else if (x, y) != (x2, y2) {
                    Some(format!("axes --x {x2} --y {y2}, not --x {x} --y {y}"))
                } else if (w, h) != (w2, h2) {
                    Some(format!("a {w2}×{h2} grid, not {w}×{h}"))
                } else if l != l2 {
                    field("layer", l2, l)
                } else {
                    None
                }
            }
            (a, b) => Some(format!("a {}, not a {}", b.name(), a.name())),
        }
    }
}

/// What a shard tells a merge: which slice of which sweep it rolled, and its counts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Part {
    /// This file's format ([`PART_FORMAT`]).
    pub part_format: u32,
    /// The program version that rolled it: another version may roll differently.
    pub version: String,
    /// The build that rolled it ([`provenance::COMMIT`]): another build may roll
    /// differently too, so a merge of parts of several builds is refused unless accepted.
    pub commit: String,
    pub sweep: Sweep,
    pub shard: Shard,
    /// The ids (batch) or rows (map) `[first, end)` this shard covers.
    pub range: [u64; 2],
    /// False if the shard was interrupted: its counts then cover only a prefix.
    pub complete: bool,
    /// The records' file, relative to the part file's folder; `None` for a summary-only part.
    pub records: Option<String>,
    /// Bytes of the records file as the shard wrote it.
    pub records_bytes: Option<u64>,
    /// The XXH64 hash (seed 0, 16 hexadecimal digits) of the records file's bytes: a file
    /// damaged or swapped after the shard wrote it is refused before it is read.
    pub records_hash: Option<String>,
    /// The setup the shard rolled, as the preset file (TOML) that gives it, its seed the
    /// one rolled: a merge recomputes every start from it and can roll records again.
    pub setup: String,
    /// A batch's counts (`None` for a map).
    pub tally: Option<Tally>,
    /// A map's faces over its cells and how many cells were rolled (`None` for a batch).
    pub map_faces: Option<FaceTally>,
    /// s of wall-clock time the shard took.
    pub elapsed_s: f64,
    /// Threads the shard ran on.
    pub jobs: usize,
}

impl Part {
    /// The part of shard `shard` of `sweep`, which rolled ids (or rows) `range` of `setup`
    /// and wrote `records` (their file and what was written) if any, as its summary at
    /// `part_path` names them: not yet complete, without counts.
    fn new(
        sweep: Sweep,
        shard: Shard,
        range: Range<u64>,
        part_path: &Path,
        records: Option<(&Path, Written)>,
        setup: &Preset,
    ) -> Part {
        Part {
            part_format: PART_FORMAT,
            version: env!("CARGO_PKG_VERSION").to_string(),
            commit: provenance::COMMIT.to_string(),
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

    /// The part a batch shard leaves: `batch` rolled ids `range` of `sweep` from `setup`
    /// (its seed the one rolled).
    pub fn of_batch(
        sweep: Sweep,
        (shard, range): (Shard, Range<u64>),
        part_path: &Path,
        records: Option<(&Path, Written)>,
        setup: &Preset,
        batch: &BatchRun,
    ) -> Part {
        Part {
            complete: !batch.cancelled,
            tally: Some(batch.tally.clone()),
            elapsed_s: batch.summary.elapsed_s,
            jobs: batch.jobs,
            ..Part::new(sweep, shard, range, part_path, records, setup)
        }
    }

    /// The part a map shard leaves: `map` holds rows `rows` of `sweep`, rolled from `setup`
    /// in `elapsed_s` s on `jobs` threads.
    pub fn of_map(
        sweep: Sweep,
        (shard, rows): (Shard, Range<u64>),
        part_path: &Path,
        records: Option<(&Path, Written)>,
        setup: &Preset,
        map: &BasinMap,
        (elapsed_s, jobs): (f64, usize),
    ) -> Part {
        Part {
            complete: map.complete,
            map_faces: Some(map.face_tally()),
            elapsed_s,
            jobs,
            ..Part::new(sweep, shard, rows, part_path, records, setup)
        }
    }

    /// How many ids or rows the part covers.
    pub fn len(&self) -> u64 {
        self.range[1] - self.range[0]
    }

    /// True for a part of no ids or rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The records file this part names, as a path (a relative name is relative to the
    /// part's folder), or `None` for a summary-only part.
    pub fn records_path(&self, part_path: &Path) -> Option<PathBuf> {
        let name = Path::new(self.records.as_deref()?);
        Some(if name.is_absolute() {
            name.to_path_buf()
        } else {
            part_path.parent().unwrap_or(Path::new("")).join(name)
        })
    }

    /// Writes the part as JSON, atomically.
    pub fn write(&self, output: &Output) -> Result<(), OutputError> {
        output.write(|w| {
            serde_json::to_writer_pretty(&mut *w, self)?;
            writeln!(w)
        })
    }

    /// Reads a part summary, naming the file and the JSON problem when it is not one. Only
    /// a regular file of at most [`MAX_PART_BYTES`] is read: a FIFO named `*.part.json` is
    /// refused rather than waited on.
    pub fn read(path: &Path) -> Result<Part, String> {
        let text = read_regular_file(path, MAX_PART_BYTES).map_err(|e| format!("{}: {e}", path.display()))?;
        let de = &mut serde_json::Deserializer::from_str(&text);
        serde_path_to_error::deserialize(de).map_err(|e| {
            let at = e.path().to_string();
            let inner = e.into_inner();
            format!(
                "{}: not a dicesim part summary: {}{inner}",
                path.display(),
                if at == "." {
                    String::new()
                } else {
                    format!("at `{at}`: ")
                }
            )
        })
    }
}

/// The largest part summary read, bytes (a part is a few kB; its setup the largest part).
const MAX_PART_BYTES: u64 = 1 << 20;

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

/// Checks that `parts` (each with a name for messages, e.g. its path) are every shard of
/// one sweep, each exactly once, all complete, all with records or all without, all rolled
/// by this version and by one build (or by several, where `accept_mixed_builds`); returns
/// their indices in shard order. The first problem found is the error, naming the parts.
pub fn check_parts(parts: &[(String, Part)], accept_mixed_builds: bool) -> Result<Vec<usize>, String> {
    let Some((first_name, first)) = parts.first() else {
        return Err("no parts given".to_string());
    };
    let this = env!("CARGO_PKG_VERSION");
    for (name, p) in parts {
        if p.part_format > PART_FORMAT {
            return Err(format!(
                "{name}: part format {} is newer than this program reads ({PART_FORMAT}); update dicesim",
                p.part_format
            ));
        }
        if p.part_format < PART_FORMAT {
            return Err(format!(
                "{name}: part format {}, which this program no longer reads (it reads {PART_FORMAT}, which records the setup, the build and a content hash); run the shard again",
                p.part_format
            ));
        }
        if p.range[0] > p.range[1] {
            return Err(format!(
                "{name}: its range {}..{} ends before it starts",
                p.range[0], p.range[1]
            ));
        }
        if !(0.0..=MAX_ELAPSED_S).contains(&p.elapsed_s) {
            return Err(format!(
                "{name}: `elapsed_s` = {} is not a shard's duration (0 to 10⁹ s)",
                p.elapsed_s
            ));
        }
        if p.records.is_some() != (p.records_bytes.is_some() && p.records_hash.is_some()) {
            return Err(format!(
                "{name}: `records`, `records_bytes` and `records_hash` go together"
            ));
        }
        if p.version != first.version {
            return Err(format!(
                "{name} was rolled by dicesim {}, {first_name} by {}: versions may roll differently, so run all shards with one",
                p.version, first.version
            ));
        }
        if p.version != this {
            return Err(format!(
                "{name} was rolled by dicesim {}, and this is {this}: merge with the version that rolled it",
                p.version
            ));
        }
        if p.commit != first.commit && !accept_mixed_builds {
            return Err(format!(
                "{name} was rolled by the build of commit {}, {first_name} by commit {}: builds may roll differently, so run all shards with one (or merge with --accept-mixed-builds, and --verify rolls records again with this build)",
                p.commit, first.commit
            ));
        }
        if let Some(why) = first.sweep.difference(&p.sweep) {
            return Err(format!(
                "{name} is not a shard of the same sweep as {first_name}: it has {why}"
            ));
        }
        if p.shard.count != first.shard.count {
            return Err(format!(
                "{name} is shard {} but {first_name} is shard {}: all parts must split the sweep into the same number of shards",
                p.shard, first.shard
            ));
        }
        if p.shard.index >= p.shard.count {
            return Err(format!(
                "{name}: there is no shard {}: K counts from 0 and stays below N",
                p.shard
            ));
        }
        let expected = p.shard.range(p.sweep.total());
        if p.range != [expected.start, expected.end] {
            return Err(format!(
                "{name}: shard {} of {} covers {}..{}, but the part says {}..{}",
                p.shard,
                p.sweep.total(),
                expected.start,
                expected.end,
                p.range[0],
                p.range[1]
            ));
        }
        if !p.complete {
            return Err(format!(
                "{name}: shard {} was interrupted before it finished; run it again",
                p.shard
            ));
        }
        if p.records.is_some() != first.records.is_some() {
            let (with, without) = if p.records.is_some() {
                (name, first_name)
            } else {
                (first_name, name)
            };
            return Err(format!(
                "{with} has records but {without} holds only a summary: merge parts of one kind"
            ));
        }
    }
    let n = first.shard.count;
    let mut by_shard: HashMap<u64, usize> = HashMap::with_capacity(parts.len());
    for (i, (name, p)) in parts.iter().enumerate() {
        if let Some(j) = by_shard.insert(p.shard.index, i) {
            return Err(format!(
                "shard {} appears twice: {} and {name}",
                p.shard, parts[j].0
            ));
        }
    }
    let missing_count = n - by_shard.len() as u64;
    if missing_count > 0 {
        // Name the first few; a sweep of many shards may miss thousands.
        let named: Vec<String> = (0..n)
            .filter(|k| !by_shard.contains_key(k))
            .take(8)
            .map(|k| format!("{k}/{n}"))
            .collect();
        let more = match missing_count - named.len() as u64 {
            0 => String::new(),
            m => format!(" and {m} more"),
        };
        let (noun, verb) = if missing_count == 1 {
            ("shard", "is")
        } else {
            ("shards", "are")
        };
        return Err(format!(
            "{noun} {}{more} {verb} missing: a merge needs all {n}",
            named.join(", ")
        ));
    }
    Ok((0..n).map(|k| by_shard[&k]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_cover_the_sweep_in_order() {
        for (total, n) in [(40_000, 8), (7, 3), (2, 5), (0, 4), (u64::MAX, 7)] {
            let mut next = 0;
            for k in 0..n {
                let r = Shard { index: k, count: n }.range(total);
                assert_eq!(r.start, next);
                next = r.end;
            }
            assert_eq!(next, total);
        }
        assert_eq!(Shard::parse("3/8").unwrap().range(40_000), 15_000..20_000);
        assert_eq!(Shard { index: 1, count: 3 }.range(7), 2..4);
    }

    #[test]
    fn bad_shards_name_the_problem() {
        assert_eq!(Shard::parse(" 2 / 4 "), Ok(Shard { index: 2, count: 4 }));
        assert_eq!(
            Shard::parse("8/8").unwrap_err(),
            "`8/8`: K counts from 0, so it must be below N = 8"
        );
        assert_eq!(Shard::parse("0/0").unwrap_err(), "`0/0`: N must be at least 1");
        assert_eq!(
            Shard::parse("3").unwrap_err(),
            "`3`: expected K/N, e.g. 0/8 for the first of 8 shards"
        );
        assert_eq!(
            Shard::parse("a/2").unwrap_err(),
            "`a/2`: `a` is not a whole number"
        );
    }

    fn part(k: u64, n: u64) -> (String, Part) {
        let sweep = Sweep::Batch {
            preset: "paper".into(),
            fingerprint: "00ff".into(),
            seed: Some(1),
            rolls: 100,
        };
        let r = Shard { index: k, count: n }.range(100);
        let p = Part {
            part_format: PART_FORMAT,
            version: env!("CARGO_PKG_VERSION").into(),
            commit: "1a2b3c4d5e6f".into(),
            sweep,
            shard: Shard { index: k, count: n },
            range: [r.start, r.end],
            complete: true,
            records: Some(format!("{k}.csv")),
            records_bytes: Some(0),
            records_hash: Some("0".into()),
            setup: String::new(),
            tally: Some(Tally::new(&[1, 2, 3, 4, 5, 6])),
            map_faces: None,
            elapsed_s: 1.0,
            jobs: 1,
        };
        (format!("{k}.part.json"), p)
    }

    #[test]
    fn parts_come_back_in_shard_order() {
        let parts = vec![part(2, 3), part(0, 3), part(1, 3)];
        assert_eq!(check_parts(&parts, false), Ok(vec![1, 2, 0]));
    }

    #[test]
    fn refusals_name_the_problem() {
        let err = |parts: Vec<(String, Part)>| check_parts(&parts, false).unwrap_err();
        assert_eq!(err(vec![]), "no parts given");
        assert_eq!(
            err(vec![part(0, 4), part(2, 4)]),
            "shards 1/4, 3/4 are missing: a merge needs all 4"
        );
        assert_eq!(
            err(vec![part(0, 2), part(0, 2)]),
            "shard 0/2 appears twice: 0.part.json and 0.part.json"
        );
        assert_eq!(
            err(vec![part(0, 2), part(1, 3)]),
            "1.part.json is shard 1/3 but 0.part.json is shard 0/2: all parts must split the sweep into the same number of shards"
        );
        let mut foreign = part(1, 2);
        if let Sweep::Batch { seed, .. } = &mut foreign.1.sweep {
            *seed = Some(2);
        }
        assert_eq!(
            err(vec![part(0, 2), foreign.clone()]),
            "1.part.json is not a shard of the same sweep as 0.part.json: it has seed 2, not 1"
        );
        if let Sweep::Batch {
            fingerprint, seed, ..
        } = &mut foreign.1.sweep
        {
            *fingerprint = "abcd".into();
            *seed = Some(1);
        }
        assert_eq!(
            err(vec![part(0, 2), foreign]),
            "1.part.json is not a shard of the same sweep as 0.part.json: it has a setup with fingerprint abcd, not 00ff"
        );
        let mut cut = part(1, 2);
        cut.1.complete = false;
        assert_eq!(
            err(vec![part(0, 2), cut]),
            "1.part.json: shard 1/2 was interrupted before it finished; run it again"
        );
        let mut bare = part(1, 2);
        bare.1.records = None;
        bare.1.records_bytes = None;
        bare.1.records_hash = None;
        assert_eq!(
            err(vec![part(0, 2), bare]),
            "0.part.json has records but 1.part.json holds only a summary: merge parts of one kind"
        );
        let mut moved = part(1, 2);
        moved.1.range = [40, 100];
        assert_eq!(
            err(vec![part(0, 2), moved]),
            "1.part.json: shard 1/2 of 100 covers 50..100, but the part says 40..100"
        );
        let mut rebuilt = part(1, 2);
        rebuilt.1.commit = "9f8e7d6c5b4a modified".into();
        let e = err(vec![part(0, 2), rebuilt.clone()]);
        assert!(
            e.starts_with(
                "1.part.json was rolled by the build of commit 9f8e7d6c5b4a modified, 0.part.json by commit 1a2b3c4d5e6f: builds may roll differently"
            ),
            "{e}"
        );
        assert!(e.contains("--accept-mixed-builds"), "{e}");
        assert_eq!(check_parts(&[part(0, 2), rebuilt], true), Ok(vec![0, 1]));
        let mut old = part(0, 1);
        old.1.version = "0.0.1".into();
        assert!(err(vec![old]).starts_with("0.part.json was rolled by dicesim 0.0.1, and this is "),);
        let many: Vec<_> = (0..1).map(|k| part(k, 1000)).collect();
        assert_eq!(
            err(many),
            "shards 1/1000, 2/1000, 3/1000, 4/1000, 5/1000, 6/1000, 7/1000, 8/1000 and 991 more are missing: a merge needs all 1000"
        );
    }

    #[test]
    fn a_part_reads_back_as_written_and_finds_its_records() {
        let dir = tempfile::tempdir().unwrap();
        let (name, mut p) = part(1, 2);
        p.setup = Preset::default().to_toml();
        let path = dir.path().join(&name);
        p.write(&Output::check(&path, &["json"], false).unwrap()).unwrap();
        // Its counts come back as counts, which name their die once a merge checks them
        // against the setup's (`Tally::of_die`).
        let read = Part::read(&path).unwrap();
        let d6 = Preset::default().params().die.face_numbers();
        let named = read.tally.clone().map(|t| t.of_die(d6).unwrap());
        assert_eq!(Part { tally: named, ..read }, p);
        // A records file beside its part is named by its file name, so the folder can move.
        assert_eq!(records_reference(&path, &dir.path().join("1.csv")), "1.csv");
        assert_eq!(p.records_path(&path), Some(dir.path().join("1.csv")));
        let elsewhere = records_reference(&path, Path::new("/data/1.csv"));
        assert_eq!(elsewhere, "/data/1.csv");
        std::fs::write(&path, "{\"part_format\": \"two\"}").unwrap();
        let e = Part::read(&path).unwrap_err();
        assert!(
            e.starts_with(&format!(
                "{}: not a dicesim part summary: at `part_format`: ",
                path.display()
            )),
            "{e}"
        );
    }
}
