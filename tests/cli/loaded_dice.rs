//! Loaded dice (docs/model.md, "Loaded dice") as batches roll them: a die loaded evenly is
//! fair, a heavy corner biases it, and the binary writes the loaded records of before again.
//! The mass model itself is tested in the physics crate (crates/physics/tests/physics/).

use crate::common;

use dicesim_experiment::{RandomRanges, Rolls, RunOptions, stream_batch};
use dicesim_physics::{InitialCondition, Params};
use std::sync::atomic::AtomicBool;

fn loaded(extra: [f64; 8]) -> Params {
    let mut p = Params::default();
    p.die.extra_corner_mass = extra;
    p
}

/// A die with every corner loaded alike is a fair die, only heavier (its flight is the
/// physics crate's loaded_dice test): no face comes up more than chance allows.
#[test]
fn all_extras_equal_is_fair() {
    let summary = batch(&loaded([0.5; 8]), 900);
    assert_eq!(summary.status.settled, 900);
    assert!(summary.p_value.unwrap() > 0.001, "{:?}", summary.faces);
}

fn batch(p: &Params, count: u64) -> dicesim_experiment::BatchSummary {
    let ranges = RandomRanges {
        random_orientation: true,
        ..RandomRanges::default()
    };
    let base = InitialCondition::default();
    let rolls = Rolls::Random {
        ranges: &ranges,
        base: &base,
        seed: 15,
        first: 0,
        count,
    };
    let run = stream_batch(
        p,
        &rolls,
        &RunOptions::default(),
        &AtomicBool::new(false),
        &mut |_| Ok(()),
    )
    .unwrap();
    run.summary
}

#[test]
fn a_heavy_corner_keeps_its_three_faces_down() {
    // Corner 8 meets faces 4, 5 and 6; weighted, it ends down more often, so those faces come
    // up less often and their opposites 3, 2 and 1 more.
    let mut extra = [0.0; 8];
    extra[7] = 2.0;
    let summary = batch(&loaded(extra), 1500);
    let n = summary.faces.total() as f64;
    let counts = summary.faces.counts();
    let heavy = (counts[3] + counts[4] + counts[5]) as f64 / n;
    // The batch's own 95 % interval on that share lies below the fair die's 1/2.
    let se = (heavy * (1.0 - heavy) / n).sqrt();
    assert!(
        heavy + 1.96 * se < 0.5,
        "faces 4–6 came up in {heavy} of {n}: {counts:?}"
    );
    assert!(summary.p_value.unwrap() < 0.01, "{counts:?}");
    // The fair die's batch from the same starts shows no such deficit.
    let fair = batch(&Params::default(), 1500).faces.counts();
    let fair_heavy = (fair[3] + fair[4] + fair[5]) as f64 / fair.iter().sum::<u64>() as f64;
    assert!(fair_heavy > heavy + 2.0 * se, "{fair:?} against {counts:?}");
}

/// The records files of loaded rolls, byte for byte against
/// `crates/physics/tests/data/loaded/` (whose starts the physics crate replays).
///
/// Those files were written by the program as it stood before the step became one kernel
/// for both engines, when a loaded die could only roll on the scalar engine (commit bab7ddc,
/// `dicesim batch … --engine scalar --jobs 1 --out FILE.csv` with the arguments below): the
/// reference data cover the fair die only, so this is what pins a loaded die's trajectory.
/// Both engines must write them again.
#[test]
fn loaded_rolls_match_the_records_written_before_the_lanes_had_loaded_dice() {
    let golden: [(&str, &[&str]); 2] = [
        (
            "loaded-corner.csv",
            &["--preset", "loaded-corner", "--rolls", "200", "--seed", "19"],
        ),
        (
            "loaded-two.csv",
            &[
                "--preset",
                "loaded-corner",
                "--set",
                "die.extra_corner_mass=[0,1.5,0,0,0,0.5,0,0]",
                "--set",
                "ground.friction_law=whole-die-norm",
                "--set",
                "integrator.stop_energy=point-masses",
                "--rolls",
                "100",
                "--seed",
                "23",
            ],
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (file, args) in golden {
        let expected = std::fs::read(format!(
            "{}/crates/physics/tests/data/loaded/{file}",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        for engine in ["scalar", "lanes"] {
            let out = dir.path().join(format!("{engine}-{file}"));
            let mut all = vec![
                "batch",
                "--engine",
                engine,
                "--jobs",
                "2",
                "--out",
                out.to_str().unwrap(),
            ];
            all.extend_from_slice(args);
            let run = common::dicesim_in(dir.path(), &all);
            assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
            // The records after the provenance line (which the older program did not write)
            // must be the older program's bytes.
            let written = std::fs::read(&out).unwrap();
            assert!(written.starts_with(b"# {"), "{file}: no provenance line");
            let records_start = written.iter().position(|&b| b == b'\n').unwrap() + 1;
            let written = &written[records_start..];
            assert!(
                written == expected.as_slice(),
                "{file} with the {engine} engine differs from the records written before"
            );
        }
    }
}
