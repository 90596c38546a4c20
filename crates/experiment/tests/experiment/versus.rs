//! `batch --versus` as the experiment runs it: the same throws in two setups. A twin with no
//! difference agrees on every throw; the paper's die on a slippery table (μ = 0.3) against
//! its own table (μ = 1.2) ends on the same face on fewer than half of the shared throws.

use dicesim_experiment::versus::{VersusCounts, stream_versus};
use dicesim_experiment::{Rolls, RunOptions};
use dicesim_setup::preset::{Preset, Store};
use std::sync::atomic::AtomicBool;

fn paper() -> Preset {
    Store::new(None).load("paper").expect("shipped preset").0
}

/// `count` of the paper's random throws in A (`set` applied to the paper) and in B (A with
/// `versus`).
fn versus(set: &[&str], versus: &[&str], count: u64) -> VersusCounts {
    let own = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let a = paper().with_overrides(&own(set)).unwrap();
    let b = a.with_overrides(&own(versus)).unwrap();
    let rolls = Rolls::Random {
        ranges: &a.random,
        base: &a.initial,
        seed: a.random.seed,
        first: 0,
        count,
    };
    let run = stream_versus(
        &a.params(),
        &b.params(),
        &rolls,
        &RunOptions::default(),
        &AtomicBool::new(false),
        &mut |_| Ok(()),
    )
    .unwrap();
    assert_eq!((run.completed, run.cancelled), (count, false));
    assert_eq!(run.table.throws(), count);
    run.table
}

#[test]
fn a_twin_with_no_difference_agrees_on_every_throw() {
    // B sets the paper's own friction again: the same setup.
    let t = versus(&[], &["ground.friction=1.2"], 2000);
    for (a, row) in t.counts.iter().enumerate() {
        for (b, &n) in row.iter().enumerate() {
            assert!(
                a == b || n == 0,
                "A {a} against B {b}: {n} throws off the diagonal"
            );
        }
    }
    assert_eq!(t.agreeing(), t.faced());
    assert!(
        t.faced() > 1900,
        "the paper's throws end on a face: {}",
        t.faced()
    );
    let (share, [low, high]) = t.agreement().unwrap();
    assert_eq!(share, 1.0);
    assert!((high - 1.0).abs() < 1e-12, "{high}");
    // Wilson's lower bound for n of n: n / (n + z²).
    let n = t.faced() as f64;
    let z2 = 1.959_963_984_540_054f64.powi(2);
    assert!((low - n / (n + z2)).abs() < 1e-12, "{low}");
}

/// μ = 0.3 against μ = 1.2 over 10 000 shared throws at the paper's ranges: the two agree on
/// fewer than half (measured: 1681, 16.8 %, about the 1/6 of two unrelated dice).
#[test]
fn friction_changes_the_face_of_more_than_half_the_throws() {
    let t = versus(&["ground.friction=0.3"], &["ground.friction=1.2"], 10_000);
    let (share, [low, high]) = t.agreement().unwrap();
    println!(
        "μ 0.3 vs 1.2: {} of {} agree, {share:.4} [{low:.4}, {high:.4}]; {} faceless",
        t.agreeing(),
        t.faced(),
        t.throws() - t.faced()
    );
    assert!(high < 0.5, "agreement {share} [{low}, {high}]");
    assert!(t.faced() > 9_000, "{}", t.faced());
    // Every face occurs on both sides: the table is no artefact of a stuck setup.
    for f in 0..t.no_face_row() {
        assert!(t.counts[f].iter().sum::<u64>() > 1000, "A's face {}", f + 1);
        assert!(
            t.counts.iter().map(|r| r[f]).sum::<u64>() > 1000,
            "B's face {}",
            f + 1
        );
    }
}
