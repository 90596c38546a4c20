//! One validation for a setup, on every path (issue 36, item 2): a random setup, one value
//! changed on a valid die, goes through every path that builds a setup from that value — a
//! preset file, `--set`, a map axis, `predict --vary`, `batch --versus`, a fit candidate — and
//! each must give `roll`'s verdict, and when it refuses, `roll`'s words (a path may say first
//! which node or candidate it is about).

use crate::common::dicesim_in;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::path::Path;

/// Setups in the sample: each runs about seven commands.
const CASES: u32 = 40;

/// The keys a value is changed on: the die's shape, pips, mass and loads, and the table,
/// whose allowed ranges each path takes (no path refuses them by design).
const KEYS: [(&str, f64, f64); 9] = [
    ("die.half_sizes.x", 0.1, 3.0),
    ("die.half_sizes.z", 0.1, 3.0),
    ("die.corner_radius", 0.0, 2.0),
    ("die.pip_diameter", 0.0, 1.2),
    ("die.pip_depth", 0.0, 0.6),
    ("die.corner_mass", 0.05, 5.0),
    ("die.extra_corner_mass.3", 0.0, 3.0),
    ("ground.friction", 0.0, 6.0),
    ("ground.damping", 0.0, 0.12),
];

/// What a command said: refused (exit 2) with these words, or ran.
#[derive(Debug, Clone, PartialEq)]
enum Verdict {
    Ran,
    Refused(String),
}

fn verdict(dir: &Path, args: &[String]) -> Verdict {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = dicesim_in(dir, &args);
    let err = String::from_utf8_lossy(&o.stderr).trim().to_string();
    match o.status.code() {
        Some(0) => Verdict::Ran,
        Some(2) => Verdict::Refused(err.trim_start_matches("dicesim: ").to_string()),
        other => panic!("dicesim {args:?}: exit {other:?}: {err}"),
    }
}

fn args(words: &[&str], more: &[String]) -> Vec<String> {
    words
        .iter()
        .map(|w| w.to_string())
        .chain(more.iter().cloned())
        .collect()
}

/// The number as the command line takes it back exactly.
fn num(v: f64) -> String {
    format!("{v:?}")
}

/// The paths' verdicts on the base setup `base` (`--set KEY=VALUE`s) with `key` at `value`.
fn check(dir: &Path, base: &[(String, f64)], key: &str, value: f64) -> Result<bool, TestCaseError> {
    let sets: Vec<String> = base
        .iter()
        .flat_map(|(k, v)| ["--set".to_string(), format!("{k}={}", num(*v))])
        .collect();
    let with =
        |extra: &[String]| -> Vec<String> { sets.iter().cloned().chain(extra.iter().cloned()).collect() };
    // The base as a preset file, for the commands that set the key themselves (a map's
    // axes, --vary, --fit): those refuse a --set they would overwrite, not a file's value.
    let base_toml = dir.join("base.toml");
    std::fs::write(&base_toml, preset_file(base)).unwrap();
    let from_file = vec!["--preset".to_string(), base_toml.to_str().unwrap().to_string()];
    let changed = ["--set".to_string(), format!("{key}={}", num(value))];
    // roll's verdict is the reference: the base is valid, so a refusal is the change's.
    let expected = verdict(dir, &args(&["roll"], &with(&changed)));
    prop_assert_eq!(
        verdict(dir, &args(&["roll"], &sets)),
        Verdict::Ran,
        "the base must roll"
    );
    let at = base_value(base, key);
    let (lo, hi) = if value < at { (value, at) } else { (at, value) };
    let mut paths: Vec<(&str, Vec<String>, Verdict)> = Vec::new();
    // A preset file: the base and the change, as `presets show` loads it.
    let toml = dir.join("case.toml");
    let mut values: Vec<(String, f64)> = base.to_vec();
    values.retain(|(k, _)| k != key);
    values.push((key.to_string(), value));
    std::fs::write(&toml, preset_file(&values)).unwrap();
    let file = toml.to_str().unwrap().to_string();
    paths.push((
        "preset file",
        vec!["presets".into(), "show".into(), file],
        expected.clone(),
    ));
    paths.push((
        "--set",
        args(&["presets", "show", "paper"], &with(&changed)),
        expected.clone(),
    ));
    if lo < hi {
        // A map of two nodes, the base's value and the changed one; the other axis holds one
        // other key at the base's own value (a map refuses one key on both axes).
        let axis = format!("{key}:{}:{}", num(lo), num(hi));
        let other = if key == "ground.friction" {
            "ground.damping"
        } else {
            "ground.friction"
        };
        let held = base_value(base, other);
        let other_axis = format!("{other}:{}:{}", num(held), num(held));
        paths.push((
            "map axis",
            args(
                &[
                    "basin",
                    "--y",
                    &other_axis,
                    "--res",
                    "2x1",
                    "--uniform",
                    "--x",
                    &axis,
                ],
                &from_file,
            ),
            expected.clone(),
        ));
    }
    let vary = format!("{key}={}", num(value));
    paths.push((
        "--vary",
        args(
            &["predict", "--rolls", "1", "--epsilon", "0.1", "--vary", &vary],
            &from_file,
        ),
        expected.clone(),
    ));
    paths.push((
        "--versus",
        args(&["batch", "--rolls", "1", "--versus", &vary], &sets),
        expected.clone(),
    ));
    for (what, command, expected) in &paths {
        let got = verdict(dir, command);
        match (expected, &got) {
            (Verdict::Ran, Verdict::Ran) => {}
            (Verdict::Refused(words), Verdict::Refused(said)) => prop_assert!(
                said.ends_with(words.as_str()),
                "{what}: roll said `{words}`, {what} `{said}`"
            ),
            _ => prop_assert!(false, "{what} {key} = {value}: roll {expected:?}, {what} {got:?}"),
        }
    }
    // A fit over the base's value and the changed one: its first candidate refused, if any,
    // is refused in roll's words for that candidate.
    if lo < hi && !key.starts_with("die.half_sizes") {
        let fit = format!("{key}:{}:{}", num(lo), num(hi));
        let values: Vec<f64> = (0..20)
            .map(|i| {
                if i == 19 {
                    hi
                } else {
                    lo + (hi - lo) * f64::from(i) / 19.0
                }
            })
            .collect();
        let first_refused = values.iter().find_map(|&v| {
            let c = ["--set".to_string(), format!("{key}={}", num(v))];
            match verdict(dir, &args(&["roll"], &with(&c))) {
                Verdict::Refused(words) => Some(words),
                Verdict::Ran => None,
            }
        });
        let got = verdict(
            dir,
            &args(
                &[
                    "compare",
                    "wolf-red",
                    "--throws",
                    "2",
                    "--candidates",
                    "20",
                    "--fit",
                    &fit,
                ],
                &from_file,
            ),
        );
        match (first_refused, got) {
            (None, Verdict::Ran) => {}
            // Refused for what its throws showed, not for its setup: every candidate valid.
            (None, Verdict::Refused(said)) if said.starts_with("no candidate of the fit rests") => {}
            (Some(words), Verdict::Refused(said)) => {
                prop_assert!(
                    said.ends_with(words.as_str()),
                    "fit: roll said `{words}`, fit `{said}`"
                )
            }
            (expected, got) => prop_assert!(false, "fit {fit}: roll {expected:?}, fit {got:?}"),
        }
    }
    Ok(expected != Verdict::Ran)
}

/// `key`'s value in the base setup: the one it sets, else the paper's.
fn base_value(base: &[(String, f64)], key: &str) -> f64 {
    base.iter()
        .find(|(k, _)| k == key)
        .map_or_else(|| paper(key), |(_, v)| *v)
}

/// The paper preset's value of `key` (those of [`KEYS`] the base does not set).
fn paper(key: &str) -> f64 {
    match key {
        "die.half_sizes.x" | "die.corner_mass" => 1.0,
        "die.extra_corner_mass.3" => 0.0,
        "ground.friction" => 1.2,
        "ground.damping" => 0.005,
        other => panic!("no paper value for {other}"),
    }
}

/// A preset file of the paper's die and table with `values` (keys of [`KEYS`]) in place.
fn preset_file(values: &[(String, f64)]) -> String {
    let get = |key: &str| values.iter().find(|(k, _)| k == key).map(|(_, v)| *v);
    let or_paper = |key: &str| get(key).unwrap_or_else(|| paper(key));
    let mut extra = [0.0; 8];
    extra[2] = or_paper("die.extra_corner_mass.3");
    format!(
        "format = 1\nname = \"case\"\n[die]\nhalf_sizes = [{}, 1.0, {}]\ncorner_radius = {}\n\
         pip_diameter = {}\npip_depth = {}\ncorner_mass = {}\nextra_corner_mass = {:?}\n\
         [ground]\nfriction = {}\ndamping = {}\n",
        num(or_paper("die.half_sizes.x")),
        num(get("die.half_sizes.z").unwrap_or(1.0)),
        num(get("die.corner_radius").unwrap_or(0.0)),
        num(get("die.pip_diameter").unwrap_or(0.0)),
        num(get("die.pip_depth").unwrap_or(0.0)),
        num(or_paper("die.corner_mass")),
        extra,
        num(or_paper("ground.friction")),
        num(or_paper("ground.damping")),
    )
}

#[test]
fn a_setup_gets_the_same_verdict_and_words_on_every_path() {
    let dir = tempfile::tempdir().unwrap();
    let config = Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    };
    let seed: [u8; 32] = *b"dicesim one validation, 36 item2";
    let mut runner = TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &seed));
    // A base die near the edges where rules meet (rounded, drilled, a half size of its own),
    // then one key changed anywhere in (and a little past) its range.
    let strategy = (
        0.6..1.4f64,
        0.0..1.0f64,
        0.0..1.0f64,
        0usize..KEYS.len(),
        0.0..1.0f64,
    );
    let refused = std::cell::Cell::new(0);
    let result = runner.run(&strategy, |(half, radius, pip, k, u)| {
        let (key, low, high) = KEYS[k];
        // Inside every rule: the rounding under half the smallest half size a, the pips
        // within the flat (at most a/2, and a less twice the radius).
        let a = half.min(1.0);
        let r = 0.4 * a * radius;
        let d = 0.9 * (0.5 * a).min(a - 2.0 * r) * pip;
        let base = vec![
            ("die.half_sizes.z".to_string(), half),
            ("die.corner_radius".to_string(), r),
            ("die.pip_diameter".to_string(), d),
            ("die.pip_depth".to_string(), 0.2 * d),
        ];
        let value = low + (high - low) * u;
        refused.set(refused.get() + u32::from(check(dir.path(), &base, key, value)?));
        Ok(())
    });
    result.unwrap();
    let refused = refused.get();
    println!("{CASES} setups through every path: {refused} refused by all, the others run by all");
    // Both verdicts must be in the sample for the comparison to mean anything.
    assert!(refused > 0 && refused < CASES, "{refused} of {CASES} refused");
}
