//! `dicesim animate` as a user runs it: the face its file records and shows agrees with
//! `dicesim roll --json`, two runs write the same bytes, and bad input writes nothing.

use crate::common::{dicesim_ok as ok, dicesim_refused as refused, png_text};

#[test]
fn the_recorded_outcome_is_the_rolls_own() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for preset in ["paper", "loaded-corner", "icy-table"] {
        let roll: serde_json::Value =
            serde_json::from_str(&ok(d, &["roll", "--preset", preset, "--json"])).unwrap();
        let out = format!("{preset}.png");
        ok(
            d,
            &[
                "animate", "--preset", preset, "--size", "160x120", "--fps", "20", "--out", &out,
            ],
        );
        let text = png_text(&d.join(&out));
        let outcome: serde_json::Value = serde_json::from_str(&text["dicesim-outcome"]).unwrap();
        assert_eq!(outcome["die"]["face"], roll["face"], "{preset}");
        assert_eq!(outcome["die"]["status"], roll["status"], "{preset}");
        assert_eq!(outcome["die"]["steps"], roll["steps"], "{preset}");
        // ⌈T·fps⌉ ± 1 frames, and the file holds as many as it says.
        let frames = outcome["frames"].as_u64().unwrap() as f64;
        let expected = (roll["time_s"].as_f64().unwrap() * 20.0).ceil();
        assert!(
            (frames - expected).abs() <= 1.0,
            "{preset}: {frames} frames, {expected} expected"
        );
        let reader = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(d.join(&out)).unwrap(),
        ))
        .read_info()
        .unwrap();
        let actl = reader.info().animation_control.expect("an animated PNG");
        assert_eq!(f64::from(actl.num_frames), frames, "{preset}");
        assert!(
            text["dicesim-setup"].starts_with(&format!("preset = \"{preset}\"")),
            "{preset}"
        );
    }
}

/// The printed summary lines its values up by characters (`ε` is two bytes), and `--zoom`
/// with `--face-pair` is recorded in the file.
#[test]
fn the_summary_lines_up_by_characters_and_the_view_is_recorded() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = ok(
        d,
        &[
            "animate",
            "--twin",
            "--size",
            "160x120",
            "--fps",
            "10",
            "--zoom",
            "--face-pair",
            "5",
            "--out",
            "z.png",
        ],
    );
    let column = |name: &str| {
        // The column, in characters, where the value after the name's padding begins.
        let line = text.lines().find(|l| l.starts_with(name)).expect(name);
        let padding = line.find("  ").expect("padded");
        line.chars().count() - line[padding..].trim_start().chars().count()
    };
    assert_eq!(column("twin (ε"), column("die"), "{text}");
    assert_eq!(column("wrote"), column("die"), "{text}");
    let outcome: serde_json::Value =
        serde_json::from_str(&png_text(&d.join("z.png"))["dicesim-outcome"]).unwrap();
    assert_eq!(outcome["zoom"], true);
    assert_eq!(outcome["face_pair"], 2);
    let e = refused(d, &["animate", "--face-pair", "7", "--out", "y.gif"]);
    assert!(e.contains("7"), "{e}");
    assert!(!d.join("y.gif").exists());
}

#[test]
fn two_runs_write_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for name in ["a.gif", "b.gif"] {
        ok(
            d,
            &["animate", "--twin", "1e-6", "--size", "200x150", "--out", name],
        );
    }
    assert!(std::fs::read(d.join("a.gif")).unwrap() == std::fs::read(d.join("b.gif")).unwrap());
}

#[test]
fn bad_input_is_refused_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("old.gif"), "old").unwrap();
    let e = refused(d, &["animate", "--out", "old.gif"]);
    assert!(
        e.contains("old.gif: the file exists (--force replaces it)"),
        "{e}"
    );
    assert_eq!(std::fs::read_to_string(d.join("old.gif")).unwrap(), "old");
    for (args, words) in [
        (vec!["--out", "roll.mp4"], "expected a .gif or .png file"),
        (
            vec!["--size", "20x20", "--out", "x.gif"],
            "from 64x64 to 3840x2160",
        ),
        (vec!["--fps", "0", "--out", "x.gif"], "0 is not in 1..=50"),
        (vec!["--twin", "0.5", "--out", "x.gif"], "twin.epsilon"),
        (vec!["--twin", "much", "--out", "x.gif"], "expected a number"),
        (
            vec!["--set", "ground.friction=-1", "--out", "x.gif"],
            "ground.friction",
        ),
    ] {
        let mut all = vec!["animate"];
        all.extend(&args);
        let e = refused(d, &all);
        assert!(e.contains(words), "{args:?}: {e}");
    }
    let left: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, ["old.gif"], "nothing else written");
}
