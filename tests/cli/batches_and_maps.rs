//! Batches and basin maps: reproducibility, statistics, physics facts and file outputs.

use dicesim_experiment::ics::parse_initial_conditions;
use dicesim_experiment::{
    Axis, BasinMap, MapSpec, Method, RandomRanges, RollRecord, Rolls, run_batch, run_map,
};
use dicesim_physics::{InitialCondition, Params, Status};
use std::path::Path;
use std::process::{Command, Output};
use std::sync::atomic::AtomicBool;

fn dicesim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(args)
        .output()
        .expect("the dicesim binary runs")
}

fn batch(params: &Params, ranges: &RandomRanges, seed: u64, count: u64, jobs: usize) -> Vec<RollRecord> {
    let base = InitialCondition::default();
    let rolls = Rolls::Random {
        ranges,
        base: &base,
        seed,
        first: 0,
        count,
    };
    let b = run_batch(params, &rolls, jobs, &AtomicBool::new(false), &mut |_| {}).unwrap();
    assert!(!b.cancelled);
    b.records
}

#[test]
fn per_roll_results_do_not_depend_on_the_job_count() {
    let (p, r) = (Params::default(), RandomRanges::default());
    let one = batch(&p, &r, 11, 1500, 1);
    let two = batch(&p, &r, 11, 1500, 2);
    assert_eq!(one.len(), 1500);
    // Bitwise: PartialEq on f64 fields compares exact values.
    assert_eq!(one, two);
    assert!(one.iter().enumerate().all(|(i, r)| r.id == i as u64));
    let other_seed = batch(&p, &r, 12, 50, 2);
    assert_ne!(one[..50], other_seed[..]);
}

/// Random orientations dropped without spin or velocity from a centre height of `height` cm.
fn drop_ranges(height: f64) -> RandomRanges {
    RandomRanges {
        seed: 1,
        height: [height, height],
        velocity: [0.0, 0.0],
        angular_velocity: [0.0, 0.0],
        random_orientation: true,
        orientation_spread: 0.0,
    }
}

#[test]
fn a_gentle_drop_keeps_the_start_face_and_a_high_one_does_not() {
    // docs/model.md: from 1.8 cm the start face stays up in 99.8% of rolls; from 8 cm up each
    // face comes up about 1/6 of the time. 400 rolls put 95% far outside chance for the
    // first, and 40% about 6 standard errors above 1/6 for the second.
    let p = Params::default();
    for (height, low, high) in [(1.8, 0.95, 1.0), (15.0, 0.0, 0.40)] {
        let records = batch(&p, &drop_ranges(height), 5, 400, 2);
        let summary =
            dicesim_experiment::BatchSummary::new(p.die.face_numbers(), &records, Default::default());
        assert_eq!(summary.status.settled, 400, "{height} cm: {:?}", summary.status);
        let same = summary.start_face_shares[0];
        assert!(
            (low..=high).contains(&same),
            "{height} cm: start face kept in {same}"
        );
    }
}

fn map(method: Method, jobs: usize, partials: &mut Vec<BasinMap>) -> BasinMap {
    let spec = MapSpec {
        x: Axis::parse("initial.angular_velocity.x:-40:40", 65).unwrap(),
        y: Axis::parse("initial.angular_velocity.y:-40:40", 33).unwrap(),
        method,
    };
    // Low enough that the basins are wide and refinement pays (no switch to uniform).
    let base = InitialCondition {
        height: 1.8,
        ..Default::default()
    };
    run_map(
        &Params::default(),
        &base,
        &spec,
        jobs,
        &AtomicBool::new(false),
        &mut |m| partials.push(m.clone()),
    )
    .unwrap()
}

#[test]
fn refined_map_equals_the_uniform_grid_where_both_rolled() {
    let mut partials = Vec::new();
    let adaptive = map(Method::Adaptive, 2, &mut partials);
    let uniform = map(Method::Uniform, 1, &mut Vec::new());
    assert!(adaptive.complete && uniform.complete);
    assert_eq!(uniform.sampled, 65 * 33);
    assert!(adaptive.sampled < uniform.sampled, "refinement rolled every cell");
    assert_eq!(adaptive.switched_to_uniform, None);
    let mut faces = std::collections::BTreeSet::new();
    let mut shared = 0;
    for (a, u) in adaptive.cells.iter().zip(&uniform.cells) {
        let (a, u) = (a.unwrap(), u.unwrap());
        assert!(u.sampled);
        if a.sampled {
            assert_eq!(a.outcome, u.outcome);
            assert_eq!(a.start_face, u.start_face);
            shared += 1;
        }
        faces.extend(u.outcome.face);
    }
    assert_eq!(shared, adaptive.sampled);
    assert!(faces.len() >= 3, "the map should cross several basins: {faces:?}");
    // Partial maps arrive coarse first, each rolling more, the last one complete and final.
    assert!(partials.len() >= 3);
    assert!(partials.windows(2).all(|w| w[0].sampled < w[1].sampled));
    assert!(partials[..partials.len() - 1].iter().all(|m| !m.complete));
    assert_eq!(partials.last(), Some(&adaptive));
    assert!(partials[0].cells.iter().all(Option::is_some));
    // The same map with another job count.
    assert_eq!(map(Method::Adaptive, 1, &mut Vec::new()), adaptive);
}

#[test]
fn an_interleaved_map_switches_to_uniform_and_equals_it() {
    // A 15 cm drop: the basins interleave on the scale of one cell, so nearly every split
    // block still differs and the adaptive method rolls every cell after its first pass.
    let spec = |method| MapSpec {
        x: Axis::parse("initial.angular_velocity.x:-60:60", 65).unwrap(),
        y: Axis::parse("initial.angular_velocity.y:-60:60", 33).unwrap(),
        method,
    };
    let run = |method| {
        run_map(
            &Params::default(),
            &InitialCondition::default(),
            &spec(method),
            2,
            &AtomicBool::new(false),
            &mut |_| {},
        )
        .unwrap()
    };
    let adaptive = run(Method::Adaptive);
    let uniform = run(Method::Uniform);
    let (passes, share) = adaptive.switched_to_uniform.expect("the map switches");
    assert_eq!(passes, 1);
    assert!(share > dicesim_experiment::UNIFORM_SWITCH_SHARE);
    assert!(adaptive.complete);
    assert_eq!(adaptive.sampled, 65 * 33);
    assert_eq!(adaptive.cells, uniform.cells);
    assert!(
        adaptive
            .method_report()
            .contains("every remaining cell was rolled")
    );
}

#[test]
fn a_one_dimensional_scan_is_a_row() {
    let spec = MapSpec {
        x: Axis::parse("initial.height:2:6", 9).unwrap(),
        y: Axis::parse("ground.friction:0.8:1.2", 1).unwrap(),
        method: Method::Uniform,
    };
    let m = run_map(
        &Params::default(),
        &InitialCondition::default(),
        &spec,
        2,
        &AtomicBool::new(false),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!((m.width(), m.height(), m.sampled), (9, 1, 9));
    let mut p = Params::default();
    p.ground.friction = 1.0;
    let ic = InitialCondition {
        height: 4.5,
        ..Default::default()
    };
    let direct = dicesim_experiment::roll_record(&p, &ic, 0);
    assert_eq!(m.cell(5, 0).unwrap().outcome, direct.outcome);
}

fn temp_dir() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn run_ok(args: &[&str]) -> String {
    let out = dicesim(args);
    assert!(
        out.status.success(),
        "dicesim {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    // A plain table: its provenance is in the sidecar beside it.
    let mut reader = csv::ReaderBuilder::new().from_path(path).unwrap();
    let header = reader.headers().unwrap().iter().map(str::to_string).collect();
    let rows = reader
        .records()
        .map(|r| r.unwrap().iter().map(str::to_string).collect())
        .collect();
    (header, rows)
}

#[test]
fn batch_files_parse_back_and_match_for_any_job_count() {
    let dir = temp_dir();
    let csv1 = dir.path().join("one.csv");
    let csv2 = dir.path().join("two.csv");
    let json = dir.path().join("rolls.json");
    let s = |p: &Path| p.to_str().unwrap().to_string();
    run_ok(&[
        "batch",
        "--rolls",
        "120",
        "--seed",
        "4",
        "--jobs",
        "1",
        "--out",
        &s(&csv1),
    ]);
    run_ok(&[
        "batch",
        "--rolls",
        "120",
        "--seed",
        "4",
        "--jobs",
        "2",
        "--out",
        &s(&csv2),
    ]);
    assert_eq!(std::fs::read(&csv1).unwrap(), std::fs::read(&csv2).unwrap());
    let summary_text = run_ok(&[
        "batch",
        "--rolls",
        "120",
        "--seed",
        "4",
        "--out",
        &s(&json),
        "--json",
    ]);

    let (header, rows) = read_csv(&csv1);
    assert_eq!(rows.len(), 120);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rolls = v["rolls"].as_array().unwrap();
    assert_eq!(rolls.len(), 120);
    let mut counts = [0u64; 6];
    for (row, roll) in rows.iter().zip(rolls) {
        assert_eq!(
            row[col("id")].parse::<u64>().unwrap(),
            roll["id"].as_u64().unwrap()
        );
        assert_eq!(row[col("status")], roll["outcome"]["status"].as_str().unwrap());
        assert_eq!(
            row[col("steps")].parse::<u64>().unwrap(),
            roll["outcome"]["steps"].as_u64().unwrap()
        );
        // serde_json's default float parser may be one ulp off; the CSV round trip is exact
        // (checked by re-rolling it below).
        let close =
            |a: f64, b: &serde_json::Value| (a - b.as_f64().unwrap()).abs() <= 1e-12 * a.abs().max(1.0);
        assert!(close(
            row[col("time_s")].parse().unwrap(),
            &roll["outcome"]["time_s"]
        ));
        assert!(close(
            row[col("height_cm")].parse().unwrap(),
            &roll["initial"]["height"]
        ));
        assert_eq!(
            row[col("start_face")].parse::<u64>().unwrap(),
            roll["start_face"].as_u64().unwrap()
        );
        if let Some(f) = roll["outcome"]["face"].as_u64() {
            assert_eq!(row[col("face")].parse::<u64>().unwrap(), f);
            counts[f as usize - 1] += 1;
        }
    }
    // The summary on stdout and in the file agree with the per-roll faces.
    let printed: serde_json::Value = serde_json::from_str(&summary_text).unwrap();
    for summary in [&printed["summary"], &v["summary"]] {
        let reported: Vec<u64> = summary["faces"]["counts"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_u64().unwrap())
            .collect();
        assert_eq!(reported, counts);
        // χ² and its p-value recomputed independently: Σ(c − n/6)²/(n/6), and the 5-dof
        // closed form erfc(√(x/2)) + √(2/π)·e^(−x/2)·(√x + x^1.5/3).
        let n: u64 = counts.iter().sum();
        let e = n as f64 / 6.0;
        let chi2: f64 = counts.iter().map(|&c| (c as f64 - e).powi(2) / e).sum();
        let p = statrs::function::erf::erfc((chi2 / 2.0).sqrt())
            + (2.0 / std::f64::consts::PI).sqrt()
                * (-chi2 / 2.0).exp()
                * (chi2.sqrt() + chi2.powf(1.5) / 3.0);
        assert!((summary["chi_square"].as_f64().unwrap() - chi2).abs() < 1e-9);
        assert!((summary["p_value"].as_f64().unwrap() - p).abs() < 1e-9);
    }
    assert_eq!(printed["completed"], 120);
    assert_eq!(printed["interrupted"], false);

    // The per-roll CSV is a valid --ics file: rolling it again gives the same file, with
    // a provenance that says they were given rather than drawn.
    let again = dir.path().join("again.csv");
    run_ok(&["batch", "--ics", &s(&csv1), "--out", &s(&again)]);
    assert!(
        std::fs::read(&csv1).unwrap() == std::fs::read(&again).unwrap(),
        "the same rolls"
    );
    let provenance = |p: &Path| -> serde_json::Value {
        let meta = std::fs::read(format!("{}.meta.json", p.display())).unwrap();
        serde_json::from_slice::<serde_json::Value>(&meta).unwrap()["provenance"].clone()
    };
    assert_eq!(provenance(&csv1)["seed"], 4);
    assert!(
        provenance(&again)["initial_conditions"]
            .as_str()
            .unwrap()
            .starts_with("given (--ics), fingerprint ")
    );
}

#[test]
fn ics_file_rolls_its_rows_with_the_preset_filling_the_rest() {
    let dir = temp_dir();
    let ics = dir.path().join("ics.csv");
    std::fs::write(&ics, "id,height,angular_velocity_x\n10,3,5\n20,15,-20\n").unwrap();
    // A preset of the paper's defaults alone, so the expectations below need no shipped preset.
    let preset = dir.path().join("defaults.toml");
    std::fs::write(&preset, "format = 1\nname = \"defaults\"\n").unwrap();
    let out = dir.path().join("out.csv");
    run_ok(&[
        "batch",
        "--preset",
        preset.to_str().unwrap(),
        "--set",
        "initial.velocity=[10,0,0]",
        "--ics",
        ics.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let (header, rows) = read_csv(&out);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[1][col("id")], "20");
    // Reals written as reals, under names with their units.
    assert_eq!(rows[1][col("velocity_x_cm_per_s")], "10.0");
    assert_eq!(rows[1][col("angular_velocity_x_rad_per_s")], "-20.0");
    let base = InitialCondition {
        velocity: [10.0, 0.0, 0.0],
        ..Default::default()
    };
    let parsed =
        parse_initial_conditions(&std::fs::read_to_string(&ics).unwrap(), &base, 16.0 / 3.0).unwrap();
    let direct = dicesim_experiment::roll_record(&Params::default(), &parsed[1].1, 20);
    assert_eq!(rows[1][col("steps")], direct.outcome.steps.to_string());
    assert_eq!(rows[1][col("status")], direct.outcome.status.name());
}

#[test]
fn malformed_ics_row_names_its_line_and_runs_nothing() {
    let dir = temp_dir();
    let ics = dir.path().join("ics.csv");
    std::fs::write(&ics, "id,height\n1,3\n2,lots\n").unwrap();
    let out = dir.path().join("out.csv");
    let o = dicesim(&[
        "batch",
        "--ics",
        ics.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("line 3: `height_cm` = `lots` is not a number"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn bad_axes_are_refused_with_the_key_or_range_named() {
    let cases = [
        (
            "initial.angular_velocty.x:-5:5",
            "`initial.angular_velocty.x` is not a numeric setup key",
        ),
        ("initial.angular_velocity:-5:5", "name one component"),
        (
            "initial.height:8:2",
            "--x `initial.height:8:2`: MIN (8) must be below MAX (2)",
        ),
        (
            "ground.friction:0:7",
            "`ground.friction` = 7 is outside the allowed range 0 to 5",
        ),
        ("initial.height:2", "expected KEY:MIN:MAX"),
    ];
    for (x, expected) in cases {
        let o = dicesim(&[
            "basin",
            "--x",
            x,
            "--y",
            "initial.angular_velocity.y:-5:5",
            "--res",
            "4x4",
        ]);
        assert_eq!(o.status.code(), Some(2), "{x}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(expected), "{x}: {err}");
    }
    let o = dicesim(&[
        "basin",
        "--x",
        "initial.height:2:8",
        "--y",
        "initial.height:2:8",
        "--res",
        "4",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("expected WxH"));
}

#[test]
fn basin_writes_csv_png_and_svg() {
    let dir = temp_dir();
    let common = [
        "basin",
        "--set",
        "initial.height=2.5",
        "--x",
        "initial.angular_velocity.x:-30:30",
        "--y",
        "initial.angular_velocity.y:-30:30",
        "--res",
        "17x9",
    ];
    let path = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let csv = path("map.csv");
    let text = run_ok(&[&common[..], &["--uniform", "--out", &csv]].concat());
    assert!(text.contains("uniform grid: every cell rolled"), "{text}");
    let (header, rows) = read_csv(Path::new(&csv));
    assert_eq!(
        header[..4],
        [
            "i",
            "j",
            "initial_angular_velocity_x_rad_per_s",
            "initial_angular_velocity_y_rad_per_s"
        ]
    );
    assert_eq!(rows.len(), 17 * 9);
    assert_eq!(rows[0][2..4], ["-30.0", "-30.0"]);
    assert_eq!(rows[17 * 9 - 1][2..4], ["30.0", "30.0"]);
    assert!(rows.iter().all(|r| r[9] == "1"));
    assert!(rows.iter().all(|r| r[6] == Status::Settled.name()));

    let text = run_ok(&[&common[..], &["--out", &path("map.png")]].concat());
    assert!(text.contains("adaptive:"), "{text}");
    let png = std::fs::read(path("map.png")).unwrap();
    assert_eq!(png[..8], *b"\x89PNG\r\n\x1a\n");

    let svg_path = path("time.svg");
    run_ok(&[&common[..], &["--layer", "settle-time", "--out", &svg_path]].concat());
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    assert!(svg.starts_with("<svg"));
    // The axes in the explorer's words, with their units; the caption never states the
    // spin the map varies, and never by its raw key.
    assert!(svg.contains("spin ωx (rad/s): -30 to 30"), "the x axis in words");
    assert!(!svg.contains("initial.angular_velocity.x (rad/s)"));
    assert!(
        svg.contains("spin (ωx, ωy, 6) rad/s"),
        "the varied spin as its symbols"
    );
    assert!(svg.contains("settle time (s)"));
    assert!(svg.contains("uniform grid 17×9"));

    // `--out` repeated, as predict and compare take it: one map, each file of it, the CSV
    // byte for byte the one a run writing it alone writes.
    let (both_csv, both_png) = (path("both.csv"), path("both.png"));
    let text = run_ok(
        &[
            &common[..],
            &["--uniform", "--out", &both_png, "--out", &both_csv],
        ]
        .concat(),
    );
    assert!(
        text.contains(&format!("wrote               {both_png}")),
        "{text}"
    );
    assert!(
        text.contains(&format!("wrote               {both_csv}")),
        "{text}"
    );
    assert_eq!(std::fs::read(&both_csv).unwrap(), std::fs::read(&csv).unwrap());
    assert_eq!(std::fs::read(&both_png).unwrap()[..8], *b"\x89PNG\r\n\x1a\n");
}
