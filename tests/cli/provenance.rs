//! Every output file says where it came from: the program version, its build and the setup
//! that defines it, never the threads, engine, shard or time, so files stay byte-identical
//! across them. A CSV says it in its sidecar `<file>.meta.json`, and starts with its header.

use crate::common::{dicesim_ok as ok, png_text};
use std::path::Path;

/// The provenance in a CSV's sidecar, after checking the CSV itself starts with its header
/// and the sidecar names every column of it.
fn first_line_json(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    assert!(!header[0].starts_with('#'), "{}", header[0]);
    let mut sidecar = path.as_os_str().to_owned();
    sidecar.push(".meta.json");
    let meta: serde_json::Value = serde_json::from_slice(&std::fs::read(sidecar).unwrap()).unwrap();
    let columns: Vec<&str> = (meta["columns"].as_array().unwrap().iter())
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(columns, header);
    meta["provenance"].clone()
}

/// The commit of the checkout the tests run in, as git names it (12 digits), if they run
/// in one.
fn git_commit() -> Option<String> {
    let dir = env!("CARGO_MANIFEST_DIR");
    let git = |args: &[&str]| {
        let out = std::process::Command::new("git")
            .args(args)
            .current_dir(dir)
            .output()
            .ok()?;
        out.status
            .success()
            .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
    };
    git(&["ls-files", "--error-unmatch", "crates/experiment/build.rs"])?;
    git(&["rev-parse", "--short=12", "HEAD"])
}

/// `dicesim --version` and every provenance name the build: the commit git gives for this
/// checkout (so two commits write two provenances), or, outside one, the stated unknown.
#[test]
fn the_version_and_every_provenance_name_the_commit_git_gives() {
    let dir = tempfile::tempdir().unwrap();
    let version = ok(dir.path(), &["--version"]);
    let version = version.trim();
    ok(dir.path(), &["batch", "--rolls", "2", "--out", "b.csv"]);
    let commit = first_line_json(&dir.path().join("b.csv"))["commit"]
        .as_str()
        .unwrap()
        .to_string();
    match git_commit() {
        Some(head) => {
            assert!(
                version.starts_with(&format!("dicesim {} (commit {head}", env!("CARGO_PKG_VERSION"))),
                "{version}, git says {head}"
            );
            assert!(commit == head || commit == format!("{head} modified"), "{commit}");
            assert_eq!(version.ends_with(", modified)"), commit.ends_with(" modified"));
        }
        None => {
            assert_eq!(
                version,
                format!("dicesim {} (unknown commit)", env!("CARGO_PKG_VERSION"))
            );
            assert_eq!(commit, "unknown");
        }
    }
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
    assert!(csv["commit"].is_string());
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
    // The header, each axis named with its unit, and the 12 cells.
    let text = std::fs::read_to_string(d.join("a.csv")).unwrap();
    assert!(
        text.lines()
            .next()
            .unwrap()
            .starts_with("i,j,initial_angular_velocity_x_rad_per_s,initial_height_cm,")
    );
    assert_eq!(text.lines().count(), 1 + 12);

    // The image carries the same provenance, and every value of the start the cells vary.
    let png = png_text(&d.join("a.png"));
    let provenance: serde_json::Value = serde_json::from_str(&png["dicesim-provenance"]).unwrap();
    assert_eq!(provenance, csv);
    let build = ok(d, &["--version"]);
    assert_eq!(png["Software"], build.trim());
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

/// `batch --json` on standard output is as complete as the JSON file: the setup with its
/// `--set` values, the program and its build.
#[test]
fn json_on_standard_output_carries_the_provenance_a_file_does() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let args = [
        "batch",
        "--rolls",
        "3",
        "--seed",
        "4",
        "--set",
        "ground.friction=0.7",
        "--json",
    ];
    let printed: serde_json::Value = serde_json::from_str(&ok(d, &args)).unwrap();
    ok(d, &[&args[..7], &["--out", "b.json"]].concat());
    let file: serde_json::Value = serde_json::from_slice(&std::fs::read(d.join("b.json")).unwrap()).unwrap();
    assert_eq!(printed["provenance"], file["provenance"]);
    assert_eq!(printed["provenance"]["preset"]["ground"]["friction"], 0.7);
    assert_eq!(
        printed["provenance"]["program"],
        format!("dicesim {}", env!("CARGO_PKG_VERSION"))
    );
    assert!(printed["provenance"]["commit"].is_string());
}

/// A trace written to a file names the setup it rolled in its sidecar: the values as
/// rolled, and that `--set` changed them from the preset.
#[test]
fn a_trace_file_names_the_setup_it_rolled() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(
        d,
        &[
            "trace",
            "--every",
            "100",
            "--set",
            "ground.stiffness=600000",
            "--out",
            "t.csv",
        ],
    );
    let provenance = first_line_json(&d.join("t.csv"));
    assert_eq!(provenance["preset"]["name"], "paper");
    assert_eq!(provenance["preset"]["ground"]["stiffness"], 600000.0);
    assert_eq!(provenance["changed_from_preset"], true);
    assert_eq!(provenance["roll"], "the preset's roll");
    // The rows are the ones standard output gets.
    let printed = ok(
        d,
        &["trace", "--every", "100", "--set", "ground.stiffness=600000"],
    );
    assert_eq!(std::fs::read_to_string(d.join("t.csv")).unwrap(), printed);
    // A trace file is never replaced without --force, nor is its sidecar.
    std::fs::remove_file(d.join("t.csv")).unwrap();
    let o = crate::common::dicesim_in(d, &["trace", "--out", "t.csv"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("t.csv.meta.json: the file exists (--force replaces it)")
    );
}

/// An SVG map carries what a PNG's text chunks do, in its `<metadata>`; a PNG says its
/// physical size.
#[test]
fn an_svg_map_carries_its_provenance_and_a_png_its_resolution() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let map = [
        "basin",
        "--x",
        "initial.height:5:20",
        "--y",
        "ground.friction:0.4:1.2",
        "--res",
        "3x2",
    ];
    for out in ["m.svg", "m.png", "m.csv"] {
        ok(d, &[&map[..], &["--out", out]].concat());
    }
    let svg = std::fs::read_to_string(d.join("m.svg")).unwrap();
    let start = svg
        .find(r#"<entry keyword="dicesim-provenance">"#)
        .expect("the provenance")
        + 36;
    let text = &svg[start..start + svg[start..].find("</entry>").unwrap()];
    let unescaped = text
        .replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    let provenance: serde_json::Value = serde_json::from_str(&unescaped).unwrap();
    assert_eq!(provenance, first_line_json(&d.join("m.csv")));
    let file = std::fs::File::open(d.join("m.png")).unwrap();
    let reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    let dims = reader.info().pixel_dims.expect("a pHYs chunk");
    assert_eq!(dims.unit, png::Unit::Meter);
    // 150 pixels per inch, to the nearest pixel per metre.
    assert_eq!(dims.xppu, (150.0f64 / 0.0254).round() as u32);
}

/// A spring-friction setup's provenance states its ground as its preset file does: exactly
/// the keys that law reads, its defaults included, and none of the paper law's (issue 49,
/// defect 4); alike in `roll --json`, a batch's CSV sidecar and its Parquet metadata. The
/// preset written from it is read back and rolls as the shipped one.
#[test]
fn a_spring_friction_provenance_states_the_keys_its_law_reads_and_rebuilds_the_setup() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let json = |args: &[&str]| -> serde_json::Value { serde_json::from_str(&ok(d, args)).unwrap() };
    let roll = json(&["roll", "--preset", "calibrated-table-budden", "--json"]);
    let stated = roll["provenance"]["preset"].clone();
    let mut keys: Vec<&str> = stated["ground"]
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    keys.sort_unstable();
    assert_eq!(
        keys,
        [
            "contact",
            "friction",
            "restitution",
            "static_friction",
            "stiffness",
            "tangential_stiffness_ratio",
            "tilt",
            "tilt_direction"
        ]
    );
    assert_eq!(stated["ground"]["static_friction"], 1.2);
    assert_eq!(stated["ground"]["tilt"], 0.0);
    for out in ["b.csv", "b.parquet"] {
        ok(
            d,
            &[
                "batch",
                "--preset",
                "calibrated-table-budden",
                "--rolls",
                "3",
                "--out",
                out,
            ],
        );
    }
    let csv = first_line_json(&d.join("b.csv"));
    assert_eq!(csv["preset"], stated);
    // The Parquet file's metadata is the CSV's provenance, text for text.
    let parquet = std::fs::File::open(d.join("b.parquet")).unwrap();
    dicesim_experiment::parquet::read_records(parquet, Some(&csv.to_string()), None, &mut |_| Ok(()))
        .unwrap();
    std::fs::write(d.join("rebuilt.toml"), toml::to_string(&stated).unwrap()).unwrap();
    assert_eq!(json(&["roll", "--preset", "rebuilt.toml", "--json"]), roll);
}
