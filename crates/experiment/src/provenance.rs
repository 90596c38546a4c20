//! What every output says about where it came from, and the fingerprints that tell setups
//! apart.
//!
//! A provenance names this program's version and build (the commit) and everything that defines an experiment's
//! result (the preset's values, the seed, the sizes), never the engine, threads, shard or
//! time: a file is the same bytes however and wherever it was rolled, and `merge` rebuilds
//! the provenance of a sweep from its parts to check each part's files against it.

use crate::basin::{Axis, BasinMap};
use crate::compare::{CompareSpec, CountsSpec};
use crate::compare_budden::{BuddenSpec, hand_throw};
use crate::compare_joint::{GridKey, JointSpec, MEASURED_CUT};
use crate::compare_shaved::{ShavedSpec, drop_throw};
use crate::predict::PredictSpec;
use dicesim_physics::InitialCondition;
use dicesim_setup::preset::Preset;
use serde::Serialize;
use serde_json::{Value, json};

/// The program and its version, as every output records it.
pub const PROGRAM: &str = concat!("dicesim ", env!("CARGO_PKG_VERSION"));

/// The commit this program was built from (12 hexadecimal digits), followed by ` modified`
/// when its tracked files differed from it, or `unknown` for a build outside a git checkout
/// (see the crate's `build.rs`): with [`PROGRAM`], what tells two builds apart.
pub const COMMIT: &str = env!("DICESIM_COMMIT");

/// The version and the build as `dicesim --version` prints them after the name:
/// `0.7.0 (commit 1a2b3c4d5e6f)`, `0.7.0 (commit 1a2b3c4d5e6f, modified)`, `0.7.0 (unknown commit)`.
pub const VERSION_LINE: &str = concat!(env!("CARGO_PKG_VERSION"), " (", env!("DICESIM_BUILD"), ")");

/// The program, its version and its build in one line, for a picture's `Software` text.
pub const BUILD: &str = concat!(
    "dicesim ",
    env!("CARGO_PKG_VERSION"),
    " (",
    env!("DICESIM_BUILD"),
    ")"
);

/// A short, stable fingerprint of a setup: FNV-1a (64 bit) of its JSON form, whose floats
/// are written in shortest round-trip form, so equal setups give equal fingerprints on any
/// machine and any run.
pub fn fingerprint(setup: &impl Serialize) -> String {
    let json = serde_json::to_vec(setup).expect("a setup always serialises to JSON");
    let hash = json.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    format!("{hash:016x}")
}

/// The fingerprint of a batch's setup: every value of the preset but its name, description
/// and seed (a merge names a different seed as such), and the given initial conditions.
pub fn batch_fingerprint(preset: &Preset, given: Option<&[(u64, InitialCondition)]>) -> String {
    // As the part's setup writes it, so a merge can recompute it from there.
    let mut values = preset.as_written();
    values.name.clear();
    values.description.clear();
    values.random.seed = 0;
    fingerprint(&(values, given))
}

/// The fingerprint of a map's setup: the preset's values (the axes are compared apart).
pub fn map_fingerprint(preset: &Preset) -> String {
    batch_fingerprint(preset, None)
}

/// A batch's provenance: the preset's values with the seed rolled (`None` for given
/// initial conditions, which `given_fingerprint` then names), and the roll count.
pub fn batch(preset: &Preset, seed: Option<u64>, rolls: u64, given_fingerprint: Option<&str>) -> Value {
    json!({
        "program": PROGRAM,
        "commit": COMMIT,
        "preset": setup(preset, seed),
        "seed": seed,
        "rolls": rolls,
        "initial_conditions": match given_fingerprint {
            Some(f) => format!("given (--ics), fingerprint {f}"),
            None => "drawn from the preset's [random] ranges with the seed".to_string(),
        },
    })
}

/// A map's provenance: the preset's values (the start every cell varies two values of),
/// each axis as `KEY:MIN:MAX` with its node count, and how the cells were found (every node
/// rolled, or the adaptive method).
pub fn map(preset: &Preset, map: &BasinMap) -> Value {
    let axis = |a: &Axis| {
        json!({
            "axis": format!("{}:{}:{}", a.key.key, a.min, a.max),
            "nodes": a.cells,
        })
    };
    json!({
        "program": PROGRAM,
        "commit": COMMIT,
        "preset": setup(preset, None),
        "x": axis(&map.x),
        "y": axis(&map.y),
        "method": map.method.name(),
    })
}

/// A predictability experiment's provenance; `vary` is the `KEY=V1,V2,…` it was given.
pub fn prediction(preset: &Preset, spec: &PredictSpec, vary: Option<&str>) -> Value {
    json!({
        "program": PROGRAM,
        "commit": COMMIT,
        "preset": setup(preset, Some(spec.seed)),
        "seed": spec.seed,
        "rolls": spec.count,
        "epsilons": spec.epsilons,
        "vary": vary,
    })
}

/// A comparison's provenance; `fit` is the `KEY:LO:HI` it was given, fitted over
/// `candidates` values.
pub fn comparison(preset: &Preset, spec: &CompareSpec, fit: Option<&str>, candidates: usize) -> Value {
    json!({
        "program": PROGRAM,
        "commit": COMMIT,
        "preset": setup(preset, Some(spec.seed)),
        "dataset": spec.dataset.name(),
        "seed": spec.seed,
        "throws": spec.throws,
        "fit": fit,
        "candidates": fit.map(|_| candidates),
    })
}

/// The provenance of a player's counts against the simulated die: the counts themselves
/// (their origin, die and numbers: a file is read once, so its counts travel with the result).
pub fn counts(preset: &Preset, spec: &CountsSpec, fit: Option<&str>, candidates: usize) -> Value {
    json!({
        "program": PROGRAM,
        "commit": COMMIT,
        "preset": setup(preset, Some(spec.seed)),
        "dataset": "counts",
        "counts": {
            "origin": spec.counts.origin,
            "die": spec.counts.die,
            "numbers": spec.counts.numbers,
            "counts": spec.counts.counts,
            "notes": spec.counts.notes,
        },
        "seed": spec.seed,
        "throws": spec.throws,
        "fit": fit,
        "candidates": fit.map(|_| candidates),
    })
}

/// The provenance of a comparison with Budden's cuboids, its random ranges as the throws
/// were drawn: from a uniformly random orientation.
pub fn budden(preset: &Preset, spec: &BuddenSpec, fit: Option<&str>) -> Value {
    let mut thrown = preset.clone();
    thrown.random = hand_throw(&preset.random);
    json!({
        "program": PROGRAM,
        "commit": COMMIT,
        "preset": setup(&thrown, Some(spec.seeds[0])),
        "dataset": "budden",
        "seeds": spec.seeds,
        "throws": spec.throws,
        "fit": fit,
        "candidates": spec.fit.as_ref().map(|f| f.candidates),
        "calibrate_on": spec.calibrate_on,
    })
}

/// The provenance of a comparison with the shaved die: the preset as it was thrown (its
/// random ranges the protocol's drop), the cuts and the throws.
pub fn shaved_die(preset: &Preset, spec: &ShavedSpec) -> Value {
    let mut thrown = preset.clone();
    thrown.random = drop_throw(spec.seed);
    json!({
        "program": PROGRAM,
        "commit": COMMIT,
        "preset": setup(&thrown, None),
        "dataset": "shaved-die",
        "seed": spec.seed,
        "throws": spec.throws,
        "cuts": spec.cuts,
    })
}

/// The provenance of a joint fit: the preset (its own ranges; Budden's throws draw from them
/// from any orientation, the shaved die's are the protocol's drop), the grid, the seed and
/// the throws.
pub fn joint(preset: &Preset, spec: &JointSpec) -> Value {
    json!({
        "program": PROGRAM,
        "commit": COMMIT,
        "preset": setup(preset, Some(spec.seed)),
        "dataset": "joint",
        "seed": spec.seed,
        "fit": spec.keys.iter().map(GridKey::text).collect::<Vec<_>>(),
        "shaved_throws": spec.shaved_throws,
        "cut": MEASURED_CUT,
        "calibrate_on": spec.calibrate_on,
    })
}

/// The provenance of one roll (`dicesim trace`, the explorer's exports): the setup as it
/// was rolled (`rolled`: its values, whatever preset they came from), which roll of it
/// (`roll`, e.g. "the preset's roll", "random roll 3 of seed 1"), and whether the values
/// were changed from the named preset's (`--set`, or edited in the explorer).
pub fn roll(rolled: &Preset, roll: &str, changed_from_preset: bool) -> Value {
    json!({
        "program": PROGRAM,
        "commit": COMMIT,
        "preset": setup(rolled, None),
        "roll": roll,
        "changed_from_preset": changed_from_preset,
    })
}

/// The setup as a provenance states it: the preset file `presets show` writes for it (every
/// key its contact law reads, nothing else), as JSON, with `seed` as its `random.seed` where
/// the seed rolled is not the preset's. A preset written from it is the setup rolled.
pub fn setup(preset: &Preset, seed: Option<u64>) -> Value {
    let mut rolled = preset.clone();
    if let Some(seed) = seed {
        rolled.random.seed = seed;
    }
    rolled.to_json()
}

/// `provenance` as the build `commit` wrote it: what a merge expects of files that shards
/// of another build of this version rolled.
pub fn built_by(mut provenance: Value, commit: &str) -> Value {
    provenance["commit"] = json!(commit);
    provenance
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fingerprints_are_stable_and_tell_setups_apart() {
        // FNV-1a of the JSON `[1.5,"x"]`, computed by hand from the published constants.
        let by_hand = "[1.5,\"x\"]".bytes().fold(0xcbf29ce484222325u64, |h, b| {
            (h ^ b as u64).wrapping_mul(0x100000001b3)
        });
        assert_eq!(fingerprint(&(1.5, "x")), format!("{by_hand:016x}"));
        assert_ne!(fingerprint(&(1.5, "x")), fingerprint(&(1.5000000000000002, "x")));
    }

    #[test]
    fn the_build_is_a_commit_or_stated_unknown() {
        let (hash, modified) = COMMIT.split_once(' ').unwrap_or((COMMIT, ""));
        if hash == "unknown" {
            assert!(VERSION_LINE.ends_with("(unknown commit)"), "{VERSION_LINE}");
        } else {
            assert!(
                hash.len() >= 7 && hash.bytes().all(|b| b.is_ascii_hexdigit()),
                "{COMMIT}"
            );
            assert!(modified.is_empty() || modified == "modified", "{COMMIT}");
            assert!(
                VERSION_LINE.contains(&format!("(commit {hash}")),
                "{VERSION_LINE}"
            );
            assert_eq!(VERSION_LINE.ends_with(", modified)"), !modified.is_empty());
        }
        assert_eq!(BUILD, format!("dicesim {VERSION_LINE}"));
    }

    /// Every file under `path` (itself, for a file) with its modification time.
    fn modified(path: &std::path::Path, into: &mut Vec<(std::path::PathBuf, std::time::SystemTime)>) {
        let Ok(meta) = std::fs::metadata(path) else {
            return;
        };
        into.push((path.to_path_buf(), meta.modified().unwrap()));
        if meta.is_dir() {
            for entry in std::fs::read_dir(path).unwrap() {
                modified(&entry.unwrap().path(), into);
            }
        }
    }

    /// A `git status` rebuilds nothing: it rewrites git's index whenever a file's times
    /// changed (here a licence's, touched to now), and the build script that stamps the
    /// commit watches nothing that `git status` writes.
    #[test]
    fn git_status_changes_nothing_the_commit_stamp_watches() {
        if COMMIT == "unknown" {
            return; // built outside a checkout: nothing of git is watched
        }
        let output = std::path::Path::new(env!("OUT_DIR")).with_file_name("output");
        let script = std::fs::read_to_string(output).unwrap();
        let watched: Vec<&str> = (script.lines())
            .filter_map(|l| l.strip_prefix("cargo:rerun-if-changed="))
            .collect();
        assert!(watched.iter().any(|w| w.ends_with("HEAD")), "{script}");
        let stamps = || {
            let mut all = Vec::new();
            for w in &watched {
                modified(std::path::Path::new(w), &mut all);
            }
            all
        };
        let before = stamps();
        let git = |args: &[&str]| {
            let out = (std::process::Command::new("git").args(args))
                .current_dir(env!("CARGO_MANIFEST_DIR"))
                .output()
                .unwrap();
            assert!(out.status.success(), "git {args:?}");
            String::from_utf8(out.stdout).unwrap()
        };
        // A file git tracks that no build reads.
        let top = std::path::PathBuf::from(git(&["rev-parse", "--show-toplevel"]).trim());
        let licence = std::fs::File::options()
            .append(true)
            .open(top.join("LICENSE-MIT"))
            .unwrap();
        licence.set_modified(std::time::SystemTime::now()).unwrap();
        git(&["status"]);
        let after = stamps();
        let changed: Vec<_> = (after.iter().filter(|a| !before.contains(a)))
            .map(|(path, _)| path)
            .collect();
        assert!(
            changed.is_empty() && after.len() == before.len(),
            "`git status` changed {changed:?}"
        );
    }

    #[test]
    fn a_sweeps_fingerprint_follows_its_values_not_its_names() {
        let paper = Preset::default();
        let mut renamed = paper.clone();
        renamed.name = "mine".into();
        renamed.description = "another text".into();
        renamed.random.seed += 1;
        // Names and the seed are compared apart (a different seed is named as such).
        assert_eq!(batch_fingerprint(&renamed, None), batch_fingerprint(&paper, None));
        let mut slippery = paper.clone();
        slippery.ground.friction = 0.3;
        assert_ne!(
            batch_fingerprint(&slippery, None),
            batch_fingerprint(&paper, None)
        );
        // Given starts are part of a batch's setup: other starts, another sweep.
        let one = [(0, paper.initial)];
        let mut higher = paper.initial;
        higher.height += 1.0;
        assert_ne!(
            batch_fingerprint(&paper, Some(&one)),
            batch_fingerprint(&paper, Some(&[(0, higher)]))
        );
        assert_ne!(
            batch_fingerprint(&paper, Some(&one)),
            batch_fingerprint(&paper, None)
        );
    }

    #[test]
    fn a_batchs_provenance_names_its_seed_or_its_given_starts() {
        let paper = Preset::default();
        let drawn = batch(&paper, Some(7), 100, None);
        assert_eq!(drawn["seed"], 7);
        assert_eq!(drawn["preset"]["random"]["seed"], 7);
        assert_eq!(drawn["rolls"], 100);
        assert_eq!(drawn["program"], PROGRAM);
        let given = batch(&paper, None, 3, Some("00ff"));
        assert_eq!(given["seed"], Value::Null);
        assert_eq!(given["initial_conditions"], "given (--ics), fingerprint 00ff");
        assert_eq!(drawn["commit"], COMMIT);
        assert_eq!(built_by(drawn, "abc")["commit"], "abc");
    }
}
