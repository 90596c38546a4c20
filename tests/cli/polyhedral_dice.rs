//! A polyhedral die (`die.kind`) as a user meets it: `batch` rolls it and records the numbers
//! it shows; every command that rolls the box only refuses it with exit status 2, naming the
//! key and the command, and writes nothing; a step it cannot take is refused with the reason.

use crate::common::{dicesim_ok, dicesim_refused};

#[test]
fn the_commands_that_roll_the_box_only_refuse_a_polyhedral_die() {
    for (args, command) in [
        (&["roll", "--preset", "d20"][..], "`dicesim roll`"),
        (&["trace", "--preset", "d8"][..], "`dicesim trace`"),
        (&["predict", "--preset", "d12"][..], "`dicesim predict`"),
        (
            &["animate", "--preset", "d4", "--out", "a.gif"][..],
            "`dicesim animate`",
        ),
        (
            &["roll", "--set", "die.kind=d20", "--set", "integrator.dt=0.00025"][..],
            "`dicesim roll`",
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
