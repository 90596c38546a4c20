//! Every output file says where it came from: the program version and the setup that
//! defines it, never the threads, engine, shard or time, so files stay byte-identical
//! across them.

mod common;

use common::dicesim_in;
use std::path::Path;

fn ok(dir: &Path, args: &[&str]) {
    let o = dicesim_in(dir, args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

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
