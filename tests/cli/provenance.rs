//! Every output file says where it came from: the program version and the setup that
//! defines it, never the threads, engine, shard or time, so files stay byte-identical
//! across them.

use crate::common::{dicesim_ok as ok, png_text};
use std::path::Path;

fn first_line_json(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap();
    let line = text.lines().next().unwrap();
    serde_json::from_str(line.strip_prefix("# ").expect("a # provenance line")).unwrap()
}

#[test]
fn batch_files_record_the_program_and_the_whole_setup() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let loaded = [
        "--set",
        "die.extra_corner_mass=[0,0,0,0,0,0,0,0.25]",
        "--seed",
        "9",
    ];
    for (out, jobs) in [("a.csv", "1"), ("b.csv", "2"), ("a.json", "1"), ("b.json", "2")] {
        ok(
            d,
            &[
                &["batch", "--rolls", "20", "--jobs", jobs, "--out", out][..],
                &loaded[..],
            ]
            .concat(),
        );
    }
    // Threads change nothing in the CSV's bytes, nor in the JSON but its timing summary.
    assert!(std::fs::read(d.join("a.csv")).unwrap() == std::fs::read(d.join("b.csv")).unwrap());
    let read = |n: &str| -> serde_json::Value {
        serde_json::from_slice(&std::fs::read(d.join(n)).unwrap()).unwrap()
    };
    let (json, other) = (read("a.json"), read("b.json"));
    assert_eq!(json["provenance"], other["provenance"]);
    assert_eq!(json["rolls"], other["rolls"]);
    let csv = first_line_json(&d.join("a.csv"));
    assert_eq!(csv, json["provenance"]);
    assert_eq!(csv["program"], format!("dicesim {}", env!("CARGO_PKG_VERSION")));
    assert_eq!(csv["seed"], 9);
    assert_eq!(csv["rolls"], 20);
    assert_eq!(csv["preset"]["random"]["seed"], 9);
    assert_eq!(csv["preset"]["die"]["extra_corner_mass"][7], 0.25);
    assert!(csv.get("jobs").is_none() && csv.get("engine").is_none());
}

#[test]
fn predict_files_record_the_ranges_the_vary_and_the_epsilons() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let run = |jobs: &str, stem: &str| {
        let (csv, json) = (format!("{stem}.csv"), format!("{stem}.json"));
        ok(
            d,
            &[
                "predict",
                "--rolls",
                "3",
                "--epsilon",
                "1e-3,1.5e-2",
                "--vary",
                "ground.damping=0.001,0.02",
                "--jobs",
                jobs,
                "--out",
                &csv,
                "--out",
                &json,
            ],
        );
    };
    run("1", "a");
    run("2", "b");
    assert!(std::fs::read(d.join("a.csv")).unwrap() == std::fs::read(d.join("b.csv")).unwrap());
    let csv = first_line_json(&d.join("a.csv"));
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(d.join("a.json")).unwrap()).unwrap();
    assert_eq!(csv, json["provenance"]);
    assert_eq!(csv["vary"], "ground.damping=0.001,0.02");
    assert_eq!(csv["epsilons"], serde_json::json!([1e-3, 1.5e-2]));
    assert_eq!(csv["rolls"], 3);
    assert!(csv["preset"]["random"]["height"].is_array());
}

#[test]
fn map_files_record_the_program_the_setup_the_axes_and_the_method() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let map = [
        "basin",
        "--x",
        "initial.angular_velocity.x:-60:60",
        "--y",
        "initial.height:5:20",
        "--res",
        "4x3",
        "--uniform",
        "--set",
        "die.extra_corner_mass=[0,0,0,0,0,0,0,0.25]",
    ];
    for (out, jobs, engine) in [("a", "1", "scalar"), ("b", "2", "lanes")] {
        for ext in ["csv", "png"] {
            let out = format!("{out}.{ext}");
            let args = ["--jobs", jobs, "--engine", engine, "--out", &out];
            ok(d, &[&map[..], &args[..]].concat());
        }
    }
    // Threads and engine change no byte of either file.
    for f in ["csv", "png"] {
        let read = |stem: &str| std::fs::read(d.join(format!("{stem}.{f}"))).unwrap();
        assert!(read("a") == read("b"), "the {f} files differ");
    }
    let csv = first_line_json(&d.join("a.csv"));
    assert_eq!(csv["program"], format!("dicesim {}", env!("CARGO_PKG_VERSION")));
    assert_eq!(csv["preset"]["die"]["extra_corner_mass"][7], 0.25);
    assert_eq!(csv["x"]["axis"], "initial.angular_velocity.x:-60:60");
    assert_eq!(csv["x"]["nodes"], 4);
    assert_eq!(csv["y"]["axis"], "initial.height:5:20");
    assert_eq!(csv["y"]["nodes"], 3);
    assert_eq!(csv["method"], "uniform");
    assert!(csv.get("jobs").is_none() && csv.get("engine").is_none());
    // The header and the 12 cells follow the provenance line.
    let text = std::fs::read_to_string(d.join("a.csv")).unwrap();
    assert!(
        text.lines()
            .nth(1)
            .unwrap()
            .starts_with("i,j,initial.angular_velocity.x,initial.height,")
    );
    assert_eq!(text.lines().count(), 2 + 12);

    // The image carries the same provenance, and every value of the start the cells vary.
    let png = png_text(&d.join("a.png"));
    let provenance: serde_json::Value = serde_json::from_str(&png["dicesim-provenance"]).unwrap();
    assert_eq!(provenance, csv);
    assert_eq!(png["Software"], format!("dicesim {}", env!("CARGO_PKG_VERSION")));
    assert!(
        png["dicesim-setup"].contains("die.extra_corner_mass = [0, 0, 0, 0, 0, 0, 0, 0.25]"),
        "{}",
        png["dicesim-setup"]
    );
    assert!(
        png["Description"].contains("loaded: +0.25 g at corner 8"),
        "{png:?}"
    );
}

#[test]
fn the_predict_image_records_the_ranges_and_the_vary_not_one_roll() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(
        d,
        &[
            "predict",
            "--rolls",
            "3",
            "--seed",
            "5",
            "--epsilon",
            "1e-3,1.5e-2",
            "--vary",
            "ground.damping=0.001,0.02",
            "--set",
            "random.height=[4,7.5]",
            "--out",
            "p.csv",
            "--out",
            "p.png",
        ],
    );
    let csv = first_line_json(&d.join("p.csv"));
    let png = png_text(&d.join("p.png"));
    let provenance: serde_json::Value = serde_json::from_str(&png["dicesim-provenance"]).unwrap();
    assert_eq!(provenance, csv);
    assert_eq!(
        provenance["preset"]["random"]["height"],
        serde_json::json!([4.0, 7.5])
    );
    let caption = &png["Description"];
    for words in [
        "3 starts drawn with seed 5",
        "height 4…7.5 cm",
        "ε 0.001, 0.015",
        "--vary ground.damping=0.001,0.02",
    ] {
        assert!(caption.contains(words), "`{words}` not in {caption}");
    }
    // Not the preset's one roll: no single start's velocity vector, no per-roll setup.
    assert!(!caption.contains("velocity ("), "{caption}");
    assert!(!png.contains_key("dicesim-setup"), "{png:?}");
}
