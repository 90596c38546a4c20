//! A polyhedral die (`die.kind`) as a user meets it: every command rolls it. `roll` reports
//! the number a player reads, the one `batch` records for the same throw in either engine;
//! `trace` has a column triple per point of the die; `batch --versus` tabulates its numbers;
//! `animate --face-pair` marks a face and its opposite, refused on the d4, which has none.
//! The explorer alone still refuses it, with exit status 2, naming the key, writing nothing;
//! a step it cannot take is refused with the reason.

use crate::common::{dicesim_ok, dicesim_refused, png_text};
use serde_json::Value;

/// The cells of a CSV's column `name` (its header the first line), as text.
fn column(csv: &str, name: &str) -> Vec<String> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let k = header
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    lines
        .map(|l| l.split(',').nth(k).expect("a cell").to_string())
        .collect()
}

#[test]
fn the_explorer_alone_refuses_a_polyhedral_die() {
    for (args, command) in [
        (&["tui", "--preset", "d10"][..], "the explorer"),
        (
            &["animate", "--present", "--preset", "d20", "--out", "a.gif"][..],
            "`dicesim animate --present`",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let stderr = dicesim_refused(dir.path(), args);
        assert!(
            stderr.contains("`die.kind`")
                && stderr.contains(command)
                && stderr.contains("rolls the box only for now"),
            "dicesim {}: {stderr}",
            args.join(" ")
        );
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "{args:?} wrote nothing"
        );
    }
}

/// Each shipped die rolled once from its preset's throw: `roll --json` reports a number the
/// die shows (docs/dice.md: 1 to N, 0 to 9 on the d10, the tens 0 to 90 on the d%), and it is
/// the face, status and steps `batch` records for that throw given as `--ics` (an `id` alone:
/// every other value the preset's), by the scalar engine and by the lanes; the text report
/// names the number as a player reads it (`face 00` on the d%).
#[test]
fn a_single_roll_of_each_die_reads_the_number_batch_records_for_its_throw() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("throw.csv"), "id\n0\n").unwrap();
    let numbers =
        |first: u32, step: u32, count: u32| -> Vec<u32> { (0..count).map(|k| (first + k) * step).collect() };
    for (preset, shows) in [
        ("d4", numbers(1, 1, 4)),
        ("d8", numbers(1, 1, 8)),
        ("d10", numbers(0, 1, 10)),
        ("d100", numbers(0, 10, 10)),
        ("d12", numbers(1, 1, 12)),
        ("d20", numbers(1, 1, 20)),
    ] {
        let roll: Value =
            serde_json::from_str(&dicesim_ok(d, &["roll", "--preset", preset, "--json"])).unwrap();
        assert_eq!(roll["status"], "settled", "{preset}: {roll}");
        let face = roll["face"].as_u64().expect("a face") as u32;
        assert!(
            shows.contains(&face),
            "{preset}: face {face}, not one of {shows:?}"
        );
        assert!(roll["final"]["point_offsets"].is_array() && roll["final"]["corner_offsets"].is_null());
        for engine in ["scalar", "lanes"] {
            let out = format!("{preset}-{engine}.csv");
            dicesim_ok(
                d,
                &[
                    "batch",
                    "--preset",
                    preset,
                    "--ics",
                    "throw.csv",
                    "--engine",
                    engine,
                    "--out",
                    &out,
                ],
            );
            let csv = std::fs::read_to_string(d.join(&out)).unwrap();
            assert_eq!(column(&csv, "face"), [face.to_string()], "{preset}, {engine}");
            assert_eq!(column(&csv, "status"), ["settled"], "{preset}, {engine}");
            assert_eq!(
                column(&csv, "steps"),
                [roll["steps"].to_string()],
                "{preset}, {engine}"
            );
        }
        let text = dicesim_ok(d, &["roll", "--preset", preset]);
        let read = if preset == "d100" {
            format!("{face:02}")
        } else {
            face.to_string()
        };
        assert!(
            text.starts_with(&format!("face {read} (settled)\n")),
            "{preset}: {text}"
        );
    }
}

/// A d20's trace: after the state and the quantities, three columns for each of its 12
/// vertices (`p1x_cm` … `p12z_cm`, no corner columns), each row's points at the icosahedron's
/// circumradius from the centre (`R = r·√(10 + 2√5)/4 · 2√3/φ²`, `r` = 0.8 cm, half its
/// height across the faces), and the last row the step `roll` ends on.
#[test]
fn a_d20_trace_has_three_columns_per_point_each_at_its_circumradius() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let csv = dicesim_ok(d, &["trace", "--preset", "d20", "--every", "50"]);
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let points: Vec<&str> = header
        .iter()
        .copied()
        .filter(|h| h.starts_with('p') && h.ends_with("_cm"))
        .collect();
    let expected: Vec<String> = (1..=12)
        .flat_map(|k| ["x", "y", "z"].map(|a| format!("p{k}{a}_cm")))
        .collect();
    assert_eq!(points, expected);
    assert!(header.ends_with(&expected.iter().map(String::as_str).collect::<Vec<_>>()[..]));
    assert!(!header.iter().any(|h| h.starts_with("c1")), "{header:?}");
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let circumradius = 0.8 * (10.0 + 2.0 * 5f64.sqrt()).sqrt() / 4.0 * 2.0 * 3f64.sqrt() / (phi * phi);
    let cell = |row: &str, name: &str| -> f64 {
        let k = header.iter().position(|h| *h == name).unwrap();
        row.split(',').nth(k).unwrap().parse().unwrap()
    };
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert!(rows.len() > 10, "{} rows", rows.len());
    for row in &rows {
        let centre = ["x_cm", "y_cm", "z_cm"].map(|c| cell(row, c));
        for k in 1..=12 {
            let p = ["x", "y", "z"].map(|a| cell(row, &format!("p{k}{a}_cm")));
            let r = (0..3).map(|i| (p[i] - centre[i]).powi(2)).sum::<f64>().sqrt();
            assert!(
                (r - circumradius).abs() < 1e-9,
                "point {k} at {r} cm, {circumradius} expected"
            );
        }
    }
    let roll: Value = serde_json::from_str(&dicesim_ok(d, &["roll", "--preset", "d20", "--json"])).unwrap();
    let last = rows.last().unwrap().split(',').next().unwrap();
    assert_eq!(last, roll["steps"].to_string());
}

/// `batch --versus` on a d20 and a d10: a row and a column per number the die shows (the
/// d10's 0 first) and no face, and each count the throws whose faces `batch` records in A
/// and in B, rolled apart with the same seed, pair that way.
#[test]
fn versus_tabulates_every_number_of_a_d20_and_a_d10() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (preset, numbers) in [
        ("d20", (1..=20).collect::<Vec<u64>>()),
        ("d10", (0..10).collect()),
    ] {
        let a = [
            "--preset",
            preset,
            "--rolls",
            "40",
            "--seed",
            "2",
            "--set",
            "ground.friction=0.6",
        ];
        let versus: Value = serde_json::from_str(&dicesim_ok(
            d,
            &[&["batch"][..], &a, &["--versus", "ground.friction=1.2", "--json"]].concat(),
        ))
        .unwrap();
        let listed: Vec<u64> = versus["faces_a"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_u64().unwrap())
            .collect();
        assert_eq!(listed, numbers, "{preset}");
        assert_eq!(versus["faces_b"], versus["faces_a"]);
        let table: Vec<Vec<u64>> = serde_json::from_value(versus["table"].clone()).unwrap();
        let n = numbers.len();
        assert_eq!((table.len(), table[0].len()), (n + 1, n + 1), "{preset}");
        // The same throws in A and in B, each rolled by `batch`.
        let faces = |friction: &str, out: &str| {
            dicesim_ok(
                d,
                &[&["batch"][..], &a[..6], &["--set", friction, "--out", out]].concat(),
            );
            let csv = std::fs::read_to_string(d.join(out)).unwrap();
            let (face, status) = (column(&csv, "face"), column(&csv, "status"));
            face.iter()
                .zip(&status)
                .map(|(f, s)| match (s.as_str(), f.parse::<u64>()) {
                    ("settled", Ok(f)) => numbers.iter().position(|&m| m == f).unwrap(),
                    _ => n,
                })
                .collect::<Vec<usize>>()
        };
        let (fa, fb) = (
            faces("ground.friction=0.6", &format!("{preset}-a.csv")),
            faces("ground.friction=1.2", &format!("{preset}-b.csv")),
        );
        let mut want = vec![vec![0u64; n + 1]; n + 1];
        for (i, j) in fa.iter().zip(&fb) {
            want[*i][*j] += 1;
        }
        assert_eq!(table, want, "{preset}");
        let agreeing: u64 = (0..n).map(|k| want[k][k]).sum();
        assert_eq!(versus["agreeing"], agreeing);
        let text = dicesim_ok(
            d,
            &[&["batch"][..], &a, &["--versus", "ground.friction=1.2"]].concat(),
        );
        let head = text.lines().nth(1).unwrap();
        let labels: Vec<&str> = head.split_whitespace().collect();
        assert_eq!(labels.len(), 3 + n + 1, "{head}");
        assert_eq!(
            labels[3..3 + n],
            numbers.iter().map(u64::to_string).collect::<Vec<_>>()[..]
        );
    }
}

/// `animate --face-pair` on a d20 marks the face and its opposite (they sum to 21) and
/// records the lower (4 for 17); on a d10 the pair sums to 9 (2 for 2 and for 7); a number the die does not show, and any
/// number on the d4 (no face lies opposite a face), are refused before anything is written.
#[test]
fn a_face_pair_is_a_face_and_its_opposite_on_any_die_but_the_d4() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (preset, face, lower) in [("d20", "17", 4), ("d10", "2", 2), ("d10", "7", 2)] {
        let out = format!("{preset}-{face}.png");
        dicesim_ok(
            d,
            &[
                "animate",
                "--preset",
                preset,
                "--face-pair",
                face,
                "--size",
                "160x120",
                "--fps",
                "5",
                "--out",
                &out,
            ],
        );
        let text = png_text(&d.join(&out));
        let outcome: Value = serde_json::from_str(&text["dicesim-outcome"]).unwrap();
        assert_eq!(outcome["face_pair"], lower, "{preset} {face}");
    }
    for (preset, face, words) in [
        ("d4", "2", "has no opposite faces"),
        ("d20", "21", "faces are 1 to 20"),
        ("d10", "10", "faces are 0 to 9"),
        ("d100", "15", "faces are 00 to 90 in steps of 10"),
        ("paper", "7", "faces are 1 to 6"),
    ] {
        let e = dicesim_refused(
            d,
            &[
                "animate",
                "--preset",
                preset,
                "--face-pair",
                face,
                "--out",
                "x.gif",
            ],
        );
        assert!(
            e.contains(words) && e.contains("--face-pair"),
            "{preset} {face}: {e}"
        );
        assert!(!d.join("x.gif").exists());
    }
}

#[test]
fn batch_rolls_a_d20_and_records_the_numbers_it_shows() {
    let dir = tempfile::tempdir().unwrap();
    dicesim_ok(
        dir.path(),
        &[
            "batch", "--preset", "d20", "--rolls", "60", "--seed", "3", "--out", "d20.csv",
        ],
    );
    let text = std::fs::read_to_string(dir.path().join("d20.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (face, status) = (column("face"), column("status"));
    let faces: Vec<u8> = lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            assert_eq!(cells[status], "settled", "{l}");
            cells[face].parse().unwrap()
        })
        .collect();
    assert_eq!(faces.len(), 60);
    assert!(faces.iter().all(|f| (1..=20).contains(f)), "{faces:?}");
    // Sixty throws of a fair d20 show a face above 6 with probability 1 − (6/20)⁶⁰.
    assert!(faces.iter().any(|f| *f > 6), "{faces:?}");
}

#[test]
fn a_polyhedral_die_on_a_step_it_cannot_take_is_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let stderr = dicesim_refused(
        dir.path(),
        &[
            "batch",
            "--preset",
            "d4",
            "--set",
            "integrator.dt=0.001",
            "--rolls",
            "10",
        ],
    );
    assert!(
        stderr.contains("integrator.dt") && stderr.contains("runs away"),
        "{stderr}"
    );
    let stderr = dicesim_refused(
        dir.path(),
        &[
            "batch",
            "--preset",
            "d20",
            "--set",
            "die.half_size=0.8",
            "--rolls",
            "10",
        ],
    );
    assert!(
        stderr.contains("die.half_sizes") && stderr.contains("describes the box only"),
        "{stderr}"
    );
}

/// A d20's sweep in three shards merges into the one-machine records, and `--verify` rolls
/// its records again as a batch rolls them (the die, not the box).
#[test]
fn a_d20_sweep_in_shards_merges_and_verifies() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let sweep = ["batch", "--preset", "d20", "--rolls", "30", "--seed", "5"];
    dicesim_ok(d, &[&sweep[..], &["--out", "one.csv"]].concat());
    std::fs::create_dir(d.join("parts")).unwrap();
    for k in 0..3 {
        let (shard, out) = (format!("{k}/3"), format!("parts/part-{k}.csv"));
        dicesim_ok(d, &[&sweep[..], &["--shard", &shard, "--out", &out]].concat());
    }
    let summary = dicesim_ok(d, &["merge", "parts", "--out", "m.csv", "--verify", "30"]);
    assert_eq!(
        std::fs::read(d.join("m.csv")).unwrap(),
        std::fs::read(d.join("one.csv")).unwrap()
    );
    assert!(summary.contains("(19 dof)"), "{summary}");
}

/// A convex die of its corners and a die's flaws as a user meets them: `batch` rolls the thick
/// coin and records its numbers 1 to 10 (a convex die of 16 corners, rolled as a 20-point body);
/// a flaw that makes no body is refused naming the file, the line and the key, and a box given
/// a flaw is refused naming the key, each writing nothing.
#[test]
fn batch_rolls_a_convex_die_and_refuses_a_flaw_that_makes_no_body_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    dicesim_ok(
        d,
        &[
            "batch",
            "--preset",
            "thick-coin",
            "--rolls",
            "40",
            "--seed",
            "3",
            "--out",
            "coin.csv",
        ],
    );
    let text = std::fs::read_to_string(d.join("coin.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let face = header.iter().position(|h| *h == "face").unwrap();
    let faces: Vec<u8> = lines
        .map(|l| l.split(',').nth(face).unwrap().parse().unwrap())
        .collect();
    assert_eq!(faces.len(), 40);
    assert!(faces.iter().all(|f| (1..=10).contains(f)), "{faces:?}");
    std::fs::write(
        d.join("bubble.toml"),
        "[die]\nkind = \"d20\"\nbubble_radius = 0.35\nbubble_toward = 20\nbubble_offset = 0.5\n\
         [integrator]\ndt = 0.00025\n",
    )
    .unwrap();
    let stderr = dicesim_refused(
        d,
        &[
            "batch",
            "--preset",
            "bubble.toml",
            "--rolls",
            "10",
            "--out",
            "b.csv",
        ],
    );
    assert!(
        stderr.contains("bubble.toml:5:")
            && stderr.contains("`die.bubble_offset`")
            && stderr.contains("reaches face 20"),
        "{stderr}"
    );
    let stderr = dicesim_refused(
        d,
        &[
            "batch",
            "--set",
            "die.worn_rounding=0.1",
            "--rolls",
            "10",
            "--out",
            "b.csv",
        ],
    );
    assert!(
        stderr.contains("`die.worn_rounding`") && stderr.contains("`die.corner_radius`"),
        "{stderr}"
    );
    assert!(!d.join("b.csv").exists(), "a refusal writes nothing");
}
