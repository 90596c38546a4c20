//! Issue 49 ("Answers you can trust, round three"): defects 5 to 7 and the four small ones,
//! each run as the user ran it.

use crate::common::{dicesim_in, dicesim_ok, dicesim_refused};

/// Defect 6: the docs give seeds from 0 to 2⁶³ − 1; every way of giving one holds to it.
#[test]
fn seeds_past_2_63_are_refused_on_every_path() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for args in [
        &["batch", "--rolls", "2", "--seed", "18446744073709551615"][..],
        &["batch", "--rolls", "2", "--seed", "9223372036854775808"],
        &["predict", "--rolls", "2", "--seed", "9223372036854775808"],
        &["compare", "budden", "--no-fit", "--seed", "1,9223372036854775808"],
    ] {
        let e = dicesim_refused(d, args);
        assert!(
            e.contains("is above 2⁶³ − 1 = 9223372036854775807"),
            "{args:?}: {e}"
        );
    }
    // `--set`: said as a number too large, not "invalid type: string".
    let e = dicesim_refused(
        d,
        &[
            "batch",
            "--rolls",
            "2",
            "--set",
            "random.seed=9223372036854775808",
        ],
    );
    assert!(
        e.contains("--set random.seed: 9223372036854775808 is above 2⁶³ − 1"),
        "{e}"
    );
    assert!(!e.contains("invalid type"), "{e}");
    // A file: its name and line.
    std::fs::write(
        d.join("big.toml"),
        "format = 1\n\n[random]\nseed = 9223372036854775808\n",
    )
    .unwrap();
    let e = dicesim_refused(d, &["batch", "--rolls", "2", "--preset", "big.toml"]);
    assert!(
        e.contains("big.toml:4:1: `random.seed`: 9223372036854775808 is above 2⁶³ − 1"),
        "{e}"
    );
    // The largest seed itself rolls.
    dicesim_ok(d, &["batch", "--rolls", "2", "--seed", "9223372036854775807"]);
    dicesim_ok(
        d,
        &[
            "batch",
            "--rolls",
            "2",
            "--set",
            "random.seed=9223372036854775807",
        ],
    );
}

/// Small one: `--set ground.restitution=-0` was echoed as `= 0`.
#[test]
fn a_negative_zero_is_echoed_as_typed() {
    let dir = tempfile::tempdir().unwrap();
    let e = dicesim_refused(
        dir.path(),
        &[
            "roll",
            "--preset",
            "calibrated-table",
            "--set",
            "ground.restitution=-0",
        ],
    );
    assert!(
        e.contains("`ground.restitution` = -0 is outside the allowed range 0.2 to 1"),
        "{e}"
    );
}

/// Small one: `random.orientation_spread = 1e-320` wrote a pitch of `-0.0`.
#[test]
fn a_tiny_spread_writes_no_negative_zero() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    dicesim_ok(
        d,
        &[
            "batch",
            "--rolls",
            "20",
            "--set",
            "random.orientation_spread=1e-320",
            "--out",
            "s.csv",
        ],
    );
    let csv = std::fs::read_to_string(d.join("s.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for row in csv.lines().skip(1) {
        let cells: Vec<&str> = row.split(',').collect();
        for angle in ["yaw_deg", "pitch_deg", "roll_deg"] {
            let i = header.iter().position(|h| *h == angle).unwrap();
            assert_eq!(cells[i], "0.0", "{angle} in {row}");
        }
    }
}

/// Small one: a start below the resting depth was refused as "a corner starts inside the
/// table", while starts down to that depth (inside the table too) are allowed.
#[test]
fn a_start_below_the_resting_depth_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let e = dicesim_refused(dir.path(), &["roll", "--set", "initial.height=0.5"]);
    assert!(
        e.contains("a corner starts deeper in the table than the die sinks resting on it"),
        "{e}"
    );
    assert!(!e.contains("starts inside the table"), "{e}");
}

/// Small one: two curves of one value were run without a word.
#[test]
fn a_value_given_twice_to_vary_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let e = dicesim_refused(
        dir.path(),
        &[
            "predict",
            "--rolls",
            "5",
            "--preset",
            "calibrated-table",
            "--vary",
            "ground.restitution=0.3,0.3",
        ],
    );
    assert!(e.contains("`ground.restitution` = 0.3 is given twice"), "{e}");
}

/// Small one: a `--versus` B equal to A was run without a word.
#[test]
fn a_versus_equal_to_a_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // The paper's table has μ = 1.2 already.
    let e = dicesim_refused(d, &["batch", "--rolls", "10", "--versus", "ground.friction=1.2"]);
    assert!(e.contains("--versus ground.friction=1.2: B is A itself"), "{e}");
    let o = dicesim_in(d, &["batch", "--rolls", "10", "--versus", "ground.friction=0.6"]);
    assert!(o.status.success());
}

/// Defect 7: `--out /dev/stdout` is written in place (the docs said so; it was refused), a
/// folder is refused as bad input (exit 2, not 1), and a dangling link is refused before
/// any roll with the `--out` prefix, not found to exist after the rolling.
#[test]
fn out_paths_are_judged_before_any_roll() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Standard output a pipe: the CSV (its format the command's first), then the summary.
    let out = dicesim_ok(d, &["batch", "--rolls", "3", "--out", "/dev/stdout"]);
    assert!(out.starts_with("id,height_cm,"), "{out}");
    assert_eq!(
        out.lines()
            .filter(|l| l.starts_with(|c: char| c.is_ascii_digit()) && l.contains(",settled,"))
            .count(),
        3,
        "{out}"
    );
    assert!(out.contains("3 rolls on"), "{out}");
    // Standard output a file the shell made: both there, neither written over the other.
    let file = d.join("redirected.txt");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(["batch", "--rolls", "3", "--out", "/dev/stdout"])
        .env("DICESIM_PRESETS", d.join("none"))
        .stdout(std::fs::File::create(&file).unwrap())
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(
        text.starts_with("id,height_cm,") && text.contains("3 rolls on"),
        "{text}"
    );
    // A folder: refused as bad input, naming --out.
    std::fs::create_dir(d.join("rolls.csv")).unwrap();
    let e = dicesim_refused(d, &["batch", "--rolls", "3", "--out", "rolls.csv"]);
    assert!(e.contains("--out rolls.csv: is a folder, not a file"), "{e}");
    // A link to nothing: refused up front; --force replaces the link.
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(d.join("missing").join("x.csv"), d.join("dangling.csv")).unwrap();
        let e = dicesim_refused(d, &["batch", "--rolls", "3", "--out", "dangling.csv"]);
        assert!(
            e.starts_with("dicesim: --out dangling.csv: a symbolic link to "),
            "{e}"
        );
        assert!(
            e.contains("which does not exist (--force replaces the link)"),
            "{e}"
        );
        dicesim_ok(d, &["batch", "--rolls", "3", "--out", "dangling.csv", "--force"]);
        assert!(
            std::fs::symlink_metadata(d.join("dangling.csv"))
                .unwrap()
                .is_file()
        );
    }
}

/// Defect 5: the law switch worked one way only. `--set ground.contact=…` now switches from
/// any preset on every path (roll, batch --versus, presets save), dropping the keys only the
/// other law reads with a note naming each; a file that gives a key its law does not read is
/// refused with its name, line and the way out.
#[test]
fn choosing_a_contact_law_switches_both_ways_and_says_what_it_dropped() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let note = "dicesim: note: --set ground.contact=paper drops ground.restitution = ";
    // Every shipped spring-friction preset with a key of its own law set.
    for preset in [
        "calibrated-table",
        "calibrated-table-budden",
        "superball",
        "incline",
    ] {
        let o = dicesim_in(d, &["roll", "--preset", preset, "--set", "ground.contact=paper"]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{preset}: {stderr}");
        assert!(
            stderr.contains("which the \"paper\" contact law does not read"),
            "{preset}: {stderr}"
        );
    }
    let o = dicesim_in(
        d,
        &[
            "roll",
            "--preset",
            "calibrated-table",
            "--set",
            "ground.contact=paper",
        ],
    );
    assert!(String::from_utf8_lossy(&o.stderr).starts_with(note));
    // The switched setup is the paper's law with the preset's other values: its roll is the
    // roll of that setup written out whole.
    let saved = dicesim_in(
        d,
        &[
            "presets",
            "save",
            "switched",
            "--preset",
            "calibrated-table",
            "--set",
            "ground.contact=paper",
        ],
    );
    assert!(
        saved.status.success(),
        "{}",
        String::from_utf8_lossy(&saved.stderr)
    );
    let file = std::fs::read_dir(d.join("no-user-presets"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(
        !text.contains("restitution =") && !text.contains("static_friction ="),
        "{text}"
    );
    let from_file = dicesim_ok(d, &["roll", "--preset", file.to_str().unwrap(), "--json"]);
    let switched = dicesim_ok(
        d,
        &[
            "roll",
            "--preset",
            "calibrated-table",
            "--set",
            "ground.contact=paper",
            "--json",
        ],
    );
    let outcome = |s: &str| serde_json::from_str::<serde_json::Value>(s).unwrap()["outcome"].clone();
    assert_eq!(outcome(&from_file), outcome(&switched));
    // --versus switches B alone, and says so.
    let o = dicesim_in(
        d,
        &[
            "batch",
            "--rolls",
            "4",
            "--preset",
            "calibrated-table",
            "--versus",
            "ground.contact=paper",
        ],
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("dicesim: note: --versus ground.contact=paper drops ground.restitution"),
        "{stderr}"
    );
    // The other way, from a paper file whose damping is not the default.
    std::fs::write(d.join("damped.toml"), "format = 1\n\n[ground]\ndamping = 0.01\n").unwrap();
    let o = dicesim_in(
        d,
        &[
            "roll",
            "--preset",
            "damped.toml",
            "--set",
            "ground.contact=spring-friction",
        ],
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("--set ground.contact=spring-friction drops ground.damping = 0.01"),
        "{stderr}"
    );
    // A file that gives its own law's foreign key: its name, its line, the way out.
    std::fs::write(
        d.join("mixed.toml"),
        "format = 1\n\n[ground]\ncontact = \"spring-friction\"\ndamping = 0.01\n",
    )
    .unwrap();
    let e = dicesim_refused(d, &["roll", "--preset", "mixed.toml"]);
    assert!(e.contains("mixed.toml:5:1: `ground.damping` = 0.01"), "{e}");
    assert!(
        e.contains("remove the line, or choose that law with `contact = \"paper\"`"),
        "{e}"
    );
}
