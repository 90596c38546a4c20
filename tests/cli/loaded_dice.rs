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
    let counts = summary.faces.counts.clone();
    let heavy = (counts[3] + counts[4] + counts[5]) as f64 / n;
    // The batch's own 95 % interval on that share lies below the fair die's 1/2.
    let se = (heavy * (1.0 - heavy) / n).sqrt();
    assert!(
        heavy + 1.96 * se < 0.5,
        "faces 4–6 came up in {heavy} of {n}: {counts:?}"
    );
    assert!(summary.p_value.unwrap() < 0.01, "{counts:?}");
    // The fair die's batch from the same starts shows no such deficit.
    let fair = batch(&Params::default(), 1500).faces.counts.clone();
    let fair_heavy = (fair[3] + fair[4] + fair[5]) as f64 / fair.iter().sum::<u64>() as f64;
    assert!(fair_heavy > heavy + 2.0 * se, "{fair:?} against {counts:?}");
}

/// The records files of loaded rolls, value for value and bit for bit against
/// `crates/physics/tests/data/loaded/` (whose starts the physics crate replays).
///
/// Those files were written by the program as it stood before the step became one kernel
/// for both engines, when a loaded die could only roll on the scalar engine (commit bab7ddc,
/// `dicesim batch … --engine scalar --jobs 1 --out FILE.csv` with the arguments below): the
/// reference data cover the fair die only, so this is what pins a loaded die's trajectory.
/// Their endings were rolled again (the starts kept) when a loaded die began to turn by the
/// splitting about its principal axes (docs/model.md, "Rotation of an anisotropic body").
/// Both engines must write them again: every cell the same double, the same integer or the
/// same word, under the names with units of today's files (the angular momentum, unset in
/// every row, now has no columns), and each time the decimal steps × Δt where the file has
/// the clock's sum of Δt, which differs from it only in the last bits.
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
            let written = std::fs::read_to_string(&out).unwrap();
            let before = String::from_utf8(expected.clone()).unwrap();
            same_values(&before, &written, &format!("{file} with the {engine} engine"));
        }
    }
}

/// Checks that a records file of today (`written`) holds the values of one written before
/// the columns had units (`before`), row for row and bit for bit (its impact columns, which
/// that file had not, aside).
fn same_values(before: &str, written: &str, what: &str) {
    let table = |text: &str| -> (Vec<String>, Vec<Vec<String>>) {
        let mut lines = text.lines();
        let header = lines.next().unwrap().split(',').map(String::from).collect();
        (
            header,
            lines.map(|l| l.split(',').map(String::from).collect()).collect(),
        )
    };
    let ((old_header, old_rows), (new_header, new_rows)) = (table(before), table(written));
    assert_eq!(old_rows.len(), new_rows.len(), "{what}: rows");
    let unit_of = |name: &str| {
        ["_cm_per_s", "_rad_per_s", "_g_cm2_per_s", "_cm", "_deg"]
            .into_iter()
            .find(|u| name.ends_with(u) && name != "time_s")
            .map_or(name.to_string(), |u| name.trim_end_matches(u).to_string())
    };
    for (n, name) in new_header.iter().enumerate() {
        // The impact columns came after these files: every other column was in them.
        let Some(o) = old_header.iter().position(|c| *c == unit_of(name)) else {
            assert!(
                [
                    "impacts",
                    "first_impact_steps",
                    "first_impact_time_s",
                    "first_impact_face_down"
                ]
                .contains(&name.as_str()),
                "{what}: no column for {name}"
            );
            continue;
        };
        for (r, (old, new)) in old_rows.iter().zip(&new_rows).enumerate() {
            let (a, b) = (&old[o], &new[n]);
            match (a.parse::<u64>(), a.parse::<f64>()) {
                _ if a.is_empty() || a.parse::<f64>().is_err() => assert_eq!(a, b, "{what}: row {r} {name}"),
                (Ok(i), _) if !b.contains(['.', 'e']) => {
                    assert_eq!(b.parse::<u64>().ok(), Some(i), "{what}: row {r} {name}")
                }
                (_, Ok(x)) if name == "time_s" => {
                    let steps: f64 = new[new_header.iter().position(|c| c == "steps").unwrap()]
                        .parse()
                        .unwrap();
                    let y: f64 = b.parse().unwrap();
                    // The decimal steps × 0.001, and the clock's sum within a few ulps of it.
                    assert_eq!(
                        y,
                        format!("{}e-3", steps as u64).parse::<f64>().unwrap(),
                        "{what}: row {r}"
                    );
                    assert!((x - y).abs() <= 1e-12 * y, "{what}: row {r}: {a} against {b}");
                }
                (_, Ok(x)) => assert_eq!(
                    b.parse::<f64>().map(f64::to_bits),
                    Ok(x.to_bits()),
                    "{what}: row {r} {name}: {a} against {b}"
                ),
                _ => unreachable!(),
            }
        }
    }
    // Nothing of the file before is lost: each column not written now is empty in every row.
    for (o, name) in old_header.iter().enumerate() {
        if !new_header.iter().any(|n| unit_of(n) == *name) {
            assert!(
                old_rows.iter().all(|r| r[o].is_empty()),
                "{what}: {name} was not empty"
            );
        }
    }
}
