//! `dicesim compare --counts`: "Is my die fair?", a player's own counts of a die held
//! against the simulated die, run as a player runs it.

use super::common::{dicesim_in, dicesim_ok, dicesim_refused};

/// A counts file of a d20 with `rows` after two notes and the header (so the first face is
/// on line 4).
fn d20_file(rows: &[(u32, &str)]) -> String {
    let mut text = "# die: d20\n# surface: a wooden table\nface,count\n".to_string();
    for (face, count) in rows {
        text.push_str(&format!("{face},{count}\n"));
    }
    text
}

/// Twenty faces counted `count` times each.
fn even(count: &str) -> Vec<(u32, &'static str)> {
    let count: &'static str = Box::leak(count.to_string().into_boxed_str());
    (1..=20).map(|f| (f, count)).collect()
}

#[test]
fn bad_counts_are_refused_naming_the_line_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let mut unknown = even("6");
    unknown[19] = (21, "6");
    let mut negative = even("6");
    negative[6] = (7, "-2");
    let mut fraction = even("6");
    fraction[2] = (3, "6.5");
    let six = "# die: d20\nface,count\n1,10\n2,10\n3,10\n4,10\n5,10\n6,10\n".to_string();
    let cases: [(&str, String, &str); 8] = [
        (
            "unknown.csv",
            d20_file(&unknown),
            "unknown.csv, line 23: face 21: a d20 shows 1–20",
        ),
        (
            "negative.csv",
            d20_file(&negative),
            "negative.csv, line 10: the count `-2` is negative",
        ),
        (
            "fraction.csv",
            d20_file(&fraction),
            "fraction.csv, line 6: the count `6.5` is not a whole number",
        ),
        // 20 faces of 4: 80 rolls, 4 expected a face, fewer than the χ² test's 5.
        (
            "few.csv",
            d20_file(&even("4")),
            "few.csv, line 23: 80 rolls of a d20 expect 4 per face",
        ),
        (
            "six.csv",
            six.clone(),
            "six.csv, line 8: 6 faces counted, but a d20 shows 1–20 (20 numbers): 7–20 missing",
        ),
        // A d6's counts named as such, held against the d20.
        (
            "d6.csv",
            six.replace("d20", "d6"),
            "d6.csv, line 1: the counts are of a d6, but the die rolled is a d20",
        ),
        ("empty.csv", String::new(), "empty.csv, line 1: no counts"),
        (
            "notes.csv",
            "# die: d20\n# nothing counted yet\n".to_string(),
            "notes.csv, line 2: no counts",
        ),
    ];
    for (name, text, expected) in cases {
        std::fs::write(dir.path().join(name), text).unwrap();
        let stderr = dicesim_refused(
            dir.path(),
            &[
                "compare", "--counts", name, "--preset", "d20", "--throws", "20", "--out", "out.csv",
                "--out", "out.png", "--out", "out.json",
            ],
        );
        assert!(stderr.contains(expected), "{name}: {stderr}");
        for out in ["out.csv", "out.png", "out.json"] {
            assert!(!dir.path().join(out).exists(), "{name}: {out} was written");
        }
    }
    // On the command line, each pair is an item.
    let stderr = dicesim_refused(
        dir.path(),
        &["compare", "--counts", "1=10,2=-1", "--preset", "d20"],
    );
    assert!(
        stderr.contains("--counts, item 2: the count `-1` is negative"),
        "{stderr}"
    );
    // A d6's six counts are refused against the paper's d6 only for what they are not.
    let stderr = dicesim_refused(
        dir.path(),
        &["compare", "--counts", "1=10,2=10,3=10,4=10,5=10,7=10"],
    );
    assert!(
        stderr.contains("--counts, item 6: face 7: a d6 shows 1–6"),
        "{stderr}"
    );
    let stderr = dicesim_refused(dir.path(), &["compare", "--counts", "missing.csv"]);
    assert!(
        stderr.contains("cannot read the counts file `missing.csv`"),
        "{stderr}"
    );
    let stderr = dicesim_refused(dir.path(), &["compare", "weldon", "--counts", "1=10"]);
    assert!(stderr.contains("cannot be used with"), "{stderr}");
}

#[test]
fn a_players_counts_are_held_against_a_fair_die_and_the_simulated_one() {
    let dir = tempfile::tempdir().unwrap();
    // A d6 rolled 120 times with the 6 up 35 times: by hand, χ² against equal shares (20
    // expected a face) is (5² + 5² + 5² + 5² + 5² + 15²)/20… the counts below: 15, 15, 15,
    // 15, 25, 35 → (25 + 25 + 25 + 25 + 25 + 225)/20 = 17.5 on 5 dof.
    let inline = "1=15,2=15,3=15,4=15,5=25,6=35";
    std::fs::write(
        dir.path().join("d6.csv"),
        "# die: d6\nface,count\n6,35\n5,25\n4,15\n3,15\n2,15\n1,15\n",
    )
    .unwrap();
    let run = |counts: &str| {
        let out = dicesim_ok(
            dir.path(),
            &[
                "compare",
                "--counts",
                counts,
                "--preset",
                "casino-die",
                "--throws",
                "600",
                "--seed",
                "4",
                "--json",
            ],
        );
        serde_json::from_str::<serde_json::Value>(&out).unwrap()
    };
    let (file, pairs) = (run("d6.csv"), run(inline));
    assert_eq!(
        file["candidates"], pairs["candidates"],
        "the file and the pairs are the same counts"
    );
    assert_eq!(
        file["data"]["counts"],
        serde_json::json!([15, 15, 15, 15, 25, 35])
    );
    let fair = &file["data_against_fair"];
    assert!(
        (fair["chi_square"].as_f64().unwrap() - 17.5).abs() < 1e-12,
        "{fair}"
    );
    assert_eq!(fair["dof"], 5);
    // P(χ²₅ ≥ 17.5) = 0.003645 (the χ² table's; scipy.stats.chi2.sf(17.5, 5)).
    assert!(
        (fair["p_value"].as_f64().unwrap() - 0.003_645).abs() < 1e-5,
        "{fair}"
    );
    let f = &file["fairness"];
    assert_eq!(f["die"], "d6");
    assert_eq!(f["consistent_with_fair"], false);
    // The 6's residual against a fair die: (35 − 20)/√(120·(1/6)·(5/6)) = 15/√(50/3).
    let r6 = f["residuals_against_fair"][5].as_f64().unwrap();
    assert!((r6 - 15.0 / (50.0f64 / 3.0).sqrt()).abs() < 1e-12, "{r6}");
    // The simulated die is the casino die: 600 rolls, counted in the die's order.
    let c = &file["candidates"][0];
    let simulated: u64 = c["counts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap())
        .sum();
    assert_eq!(simulated + c["uncounted"].as_u64().unwrap(), 600);
    // What a player reads.
    let text = dicesim_ok(
        dir.path(),
        &[
            "compare",
            "--counts",
            "d6.csv",
            "--preset",
            "casino-die",
            "--throws",
            "600",
            "--seed",
            "4",
        ],
    );
    assert!(
        text.starts_with("Is my die fair? 120 rolls of a d6 from d6.csv: die: d6"),
        "{text}"
    );
    assert!(
        text.contains("your counts: unlikely for a fair die (p = 0.0036;"),
        "{text}"
    );
    assert!(
        text.contains("faces beyond ±2 of a fair die's chance (adjusted residual): 6 (+3.7)"),
        "{text}"
    );
    assert!(
        text.contains("rolls a player needs to detect the simulated die's flaw:"),
        "{text}"
    );
    // The die the file names chooses the preset when none is given: a d20's counts roll the d20.
    let d20: String = (1..=20).map(|f| format!("{f}=5")).collect::<Vec<_>>().join(",");
    std::fs::write(dir.path().join("d20.csv"), d20_file(&even("5"))).unwrap();
    let text = dicesim_ok(dir.path(), &["compare", "--counts", "d20.csv", "--throws", "200"]);
    assert!(text.contains("the simulated d20 (d20, 200 rolls)"), "{text}");
    assert!(
        text.contains("your counts: consistent with a fair die (p = 1.0000;"),
        "{text}"
    );
    let o = dicesim_in(dir.path(), &["compare", "--counts", &d20, "--throws", "20"]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "pairs name no die: the paper's d6 is refused them"
    );
}
