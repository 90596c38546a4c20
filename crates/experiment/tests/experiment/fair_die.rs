//! "Is my die fair?" (docs/real-dice.md): counts of 2 000 rolls of a d20 with a bubble at a
//! known offset, simulated with a seed of their own, are held against the simulated die and
//! the bubble's offset fitted to them: the true offset lies inside the fit's 95 % interval,
//! and counts of the same die with its bubble centred (a fair die) give an interval holding
//! "no flaw". The default run fits over 20 candidates of 400 simulated rolls each (about a
//! minute on one core); the full one (`--ignored`) over 21 of 5 000.

use dicesim_experiment::compare::{CountsSpec, FitSpec, run_counts};
use dicesim_experiment::player_counts::CountsInput;
use dicesim_experiment::{Rolls, RunOptions, run_batch};
use dicesim_setup::preset::{Preset, Store};
use std::sync::atomic::AtomicBool;

/// The docs' d20 with a bubble 6 mm across toward its 20 (examples/d20-big-bubble.toml):
/// the shipped `d20-bubble` with the bubble's radius 0.3 cm (its offset first brought to the
/// centre, where a bubble of that size fits), at `offset_cm`.
fn bubble_d20(offset_cm: f64) -> Preset {
    let (preset, _) = Store::new(None).load_or_default(Some("d20-bubble")).unwrap();
    preset
        .with_overrides(&[
            "die.bubble_offset=0".to_string(),
            "die.bubble_radius=0.3".to_string(),
            format!("die.bubble_offset={offset_cm}"),
        ])
        .unwrap()
}

/// A player's counts: `rolls` rolls of the die with its bubble at `offset_cm`, seed `seed`,
/// as `FACE=COUNT` pairs read back as a player's input.
fn counted(offset_cm: f64, rolls: u64, seed: u64) -> CountsInput {
    let preset = bubble_d20(offset_cm);
    let params = preset.params();
    let draws = Rolls::Random {
        ranges: &preset.random,
        base: &preset.initial,
        seed,
        first: 0,
        count: rolls,
    };
    let batch = run_batch(&params, &draws, 0, &AtomicBool::new(false), &mut |_| {}).unwrap();
    let numbers = params.die.face_numbers();
    let pairs: Vec<String> = numbers
        .iter()
        .map(|&n| {
            let count = batch.records.iter().filter(|r| r.outcome.face == Some(n)).count();
            format!("{n}={count}")
        })
        .collect();
    CountsInput::from_inline(&pairs.join(",")).unwrap()
}

/// The fit of the bubble's offset, 0 to 0.45 cm, to the counts of a die whose bubble is at
/// `true_cm`: its 95 % interval and whether "no flaw" (offset 0) lies inside it.
fn fit(true_cm: f64, candidates: usize, throws: u64, counts_seed: u64) -> (f64, f64, Option<bool>) {
    let counts =
        counted(true_cm, 2000, counts_seed).for_die("d20", bubble_d20(0.0).params().die.face_numbers());
    let preset = bubble_d20(0.0);
    let spec = CountsSpec {
        counts: counts.unwrap(),
        throws,
        seed: 1,
        fit: Some(FitSpec::parse("die.bubble_offset:0:0.45", candidates).unwrap()),
    };
    let options = RunOptions {
        jobs: 0,
        engine: dicesim_experiment::Engine::Auto,
    };
    let c = run_counts(
        &preset.params(),
        &preset.random,
        &preset.initial,
        &spec,
        &options,
        &AtomicBool::new(false),
        &mut |_| {},
    )
    .unwrap();
    let interval = c.fit.as_ref().expect("a fit with its candidates");
    eprintln!(
        "bubble at {true_cm} cm, {candidates} candidates of {throws} rolls: best {:.3}, 95 % interval {:.3} to {:.3}; counts against a fair die p = {:.3e}",
        interval.best, interval.low, interval.high, c.data_against_fair.p_value
    );
    (interval.low, interval.high, c.fairness.unwrap().no_flaw_inside)
}

fn recovered(candidates: usize, throws: u64) {
    let truth = 0.3;
    let (low, high, no_flaw) = fit(truth, candidates, throws, 2054);
    assert!(low <= truth && truth <= high, "{truth} outside {low} to {high}");
    let (low, high, no_flaw_fair) = fit(0.0, candidates, throws, 2055);
    assert_eq!(
        no_flaw_fair,
        Some(true),
        "a fair die's counts: 0 outside {low} to {high}"
    );
    eprintln!("the flawed die's counts: no flaw inside the interval: {no_flaw:?}");
}

#[test]
fn a_bubbles_offset_is_recovered_from_2000_rolls_and_a_fair_die_is_fair() {
    recovered(20, 400);
}

#[test]
#[ignore = "about 15 minutes on one core: cargo test -p dicesim-experiment --test experiment -- --ignored fair_die"]
fn a_bubbles_offset_is_recovered_from_2000_rolls_and_a_fair_die_is_fair_in_full() {
    recovered(21, 5000);
}
