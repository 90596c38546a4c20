//! Sweeps split into shards and merged back, run as a user runs them: the merged files
//! must be the one-machine files byte for byte, and a merge of parts that are not one
//! sweep must be refused without writing anything.

use crate::common::{dicesim_ok as ok, dicesim_refused as refused};
use std::path::Path;
use std::process::Command;

fn bytes(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The summary's lines about the rolls themselves (without the first and last: thread
/// count and speed).
fn counts(summary: &str) -> Vec<&str> {
    let lines: Vec<&str> = summary.lines().filter(|l| !l.starts_with("wrote ")).collect();
    lines[1..lines.len() - 1].to_vec()
}

/// A JSON summary without its wall-clock fields.
fn timeless(json: &str) -> serde_json::Value {
    let mut v: serde_json::Value = serde_json::from_str(json).unwrap();
    let summary = v["summary"].as_object_mut().unwrap();
    for key in ["elapsed_s", "rolls_per_s", "steps_per_s"] {
        assert!(summary.remove(key).is_some(), "the summary has {key}");
    }
    v["summary"].take()
}

#[test]
fn eight_shards_of_40000_rolls_merge_into_the_one_machine_csv_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let one_text = ok(d, &["batch", "--rolls", "40000", "--out", "one.csv"]);
    let one_json = ok(d, &["batch", "--rolls", "40000", "--json"]);
    for k in 0..8 {
        // Thread counts differ between shards: the results must not depend on them.
        let jobs = if k % 2 == 0 { "1" } else { "2" };
        let shard = format!("{k}/8");
        let out = format!("part-{k}.csv");
        ok(
            d,
            &[
                "batch", "--rolls", "40000", "--jobs", jobs, "--shard", &shard, "--out", &out,
            ],
        );
    }
    // Shard 3 of 8 is rolls 15 000 to 19 999 of the same streams, under the header of the
    // whole sweep, and its sidecar holds the whole sweep's provenance.
    let part3 = String::from_utf8(bytes(d, "part-3.csv")).unwrap();
    let one_csv = String::from_utf8(bytes(d, "one.csv")).unwrap();
    assert_eq!(part3.lines().next(), one_csv.lines().next());
    assert!(part3.starts_with("id,height_cm,"));
    assert!(part3.lines().nth(1).unwrap().starts_with("15000,"));
    assert!(part3.lines().last().unwrap().starts_with("19999,"));
    assert_eq!(part3.lines().count(), 5001);
    assert_eq!(bytes(d, "part-3.csv.meta.json"), bytes(d, "one.csv.meta.json"));

    // Parts in any order; a folder stands for the parts inside.
    let mut names: Vec<String> = (0..8).rev().map(|k| format!("part-{k}.part.json")).collect();
    names.insert(0, "merge".into());
    names.extend(["--out".into(), "merged.csv".into()]);
    let args: Vec<&str> = names.iter().map(String::as_str).collect();
    let merged_text = ok(d, &args);
    assert_eq!(bytes(d, "merged.csv"), bytes(d, "one.csv"));
    assert_eq!(bytes(d, "merged.csv.meta.json"), bytes(d, "one.csv.meta.json"));
    assert_eq!(counts(&merged_text), counts(&one_text));
    assert!(merged_text.starts_with("40000 rolls in 8 shards\n"));

    let merged_json = ok(d, &["merge", ".", "--json"]);
    let (one, merged) = (timeless(&one_json), timeless(&merged_json));
    // χ², p, the shares and the exact simulated seconds recomputed from merged counts.
    assert_eq!(one, merged);
    assert!(one["chi_square"].as_f64().is_some() && one["simulated_s"].as_f64().unwrap() > 0.0);
}

#[test]
fn a_map_split_in_4_merges_into_the_one_machine_csv_and_png() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let map = [
        "basin",
        "--x",
        "initial.angular_velocity.x:-60:60",
        "--y",
        "initial.height:5:20",
        "--res",
        "40x18",
    ];
    let with = |extra: &[&str]| -> Vec<String> { map.iter().chain(extra).map(|s| s.to_string()).collect() };
    let run = |extra: &[&str]| {
        let args = with(extra);
        ok(d, &args.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let one = run(&["--uniform", "--out", "one.csv"]);
    run(&["--uniform", "--out", "one.png"]);
    for k in 0..4 {
        let shard = format!("{k}/4");
        let out = format!("rows-{k}.csv");
        run(&["--shard", &shard, "--out", &out]);
    }
    // 18 rows in 4 shards: rows 0–3, 4–8, 9–12, 13–17.
    let rows1 = String::from_utf8(bytes(d, "rows-1.csv")).unwrap();
    // The header, then the rows; the sweep's provenance (the same on every shard and on
    // one machine) in the sidecar.
    assert_eq!(rows1.lines().count(), 1 + 5 * 40);
    let one_csv = String::from_utf8(bytes(d, "one.csv")).unwrap();
    assert_eq!(rows1.lines().next(), one_csv.lines().next());
    assert!(rows1.lines().nth(1).unwrap().starts_with("0,4,"));
    assert_eq!(bytes(d, "rows-1.csv.meta.json"), bytes(d, "one.csv.meta.json"));
    let merged = ok(d, &["merge", ".", "--out", "map.csv", "--out", "map.png"]);
    assert_eq!(bytes(d, "map.csv"), bytes(d, "one.csv"));
    assert_eq!(bytes(d, "map.csv.meta.json"), bytes(d, "one.csv.meta.json"));
    assert_eq!(bytes(d, "map.png"), bytes(d, "one.png"));
    let head = |s: &str| s.lines().take(5).map(String::from).collect::<Vec<_>>();
    assert_eq!(head(&merged), head(&one));
    // A merge that writes nothing reads no cell, and still counts every cell the parts rolled.
    let summary_only = ok(d, &["merge", "."]);
    assert_eq!(head(&summary_only), head(&one), "{summary_only}");

    // An adaptive map cannot be sharded: its refinement compares cells across rows.
    let args = with(&["--adaptive", "--shard", "0/2", "--out", "a.csv"]);
    let e = refused(d, &args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(
        e.contains("adaptive refinement compares cells across shards"),
        "{e}"
    );
}

#[test]
fn merge_refuses_missing_duplicated_or_foreign_parts() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for k in 0..4 {
        ok(
            d,
            &[
                "batch",
                "--rolls",
                "200",
                "--shard",
                &format!("{k}/4"),
                "--out",
                &format!("p{k}.csv"),
            ],
        );
    }
    let all = ["p0.part.json", "p1.part.json", "p2.part.json", "p3.part.json"];
    let merge = |parts: &[&str]| {
        let mut args = vec!["merge"];
        args.extend(parts);
        args.extend(["--out", "m.csv"]);
        refused(d, &args)
    };
    assert_eq!(
        merge(&all[..3]),
        "dicesim: shard 3/4 is missing: a merge needs all 4\n"
    );
    std::fs::copy(d.join("p1.part.json"), d.join("again.part.json")).unwrap();
    assert_eq!(
        merge(&[
            "p0.part.json",
            "p1.part.json",
            "again.part.json",
            "p2.part.json",
            "p3.part.json"
        ]),
        "dicesim: shard 1/4 appears twice: p1.part.json and again.part.json\n"
    );
    ok(
        d,
        &[
            "batch",
            "--rolls",
            "200",
            "--seed",
            "2",
            "--shard",
            "2/4",
            "--out",
            "seed2.csv",
        ],
    );
    assert_eq!(
        merge(&["p0.part.json", "p1.part.json", "seed2.part.json", "p3.part.json"]),
        "dicesim: seed2.part.json is not a shard of the same sweep as p0.part.json: it has seed 2, not 1\n"
    );
    ok(
        d,
        &[
            "batch",
            "--rolls",
            "200",
            "--set",
            "ground.friction=0.3",
            "--shard",
            "2/4",
            "--out",
            "mu.csv",
        ],
    );
    let e = merge(&["p0.part.json", "p1.part.json", "mu.part.json", "p3.part.json"]);
    assert!(
        e.contains(
            "mu.part.json is not a shard of the same sweep as p0.part.json: it has a setup with fingerprint"
        ),
        "{e}"
    );
    ok(
        d,
        &["batch", "--rolls", "300", "--shard", "2/4", "--out", "more.csv"],
    );
    let e = merge(&["p0.part.json", "p1.part.json", "more.part.json", "p3.part.json"]);
    assert!(e.contains("it has a total of rolls 300, not 200"), "{e}");
    // A part whose records were cut short.
    let full = std::fs::read_to_string(d.join("p1.csv")).unwrap();
    let cut: String = full.lines().take(20).map(|l| format!("{l}\n")).collect();
    std::fs::write(d.join("p1.csv"), &cut).unwrap();
    assert_eq!(
        merge(&all),
        format!(
            "dicesim: p1.csv (records of p1.part.json): {} bytes, but the shard wrote {}: the file was cut, extended or replaced\n",
            cut.len(),
            full.len()
        )
    );
    assert!(!d.join("m.csv").exists(), "a refused merge writes nothing");
    let leftovers: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with(".dicesim-"))
        .collect();
    assert!(leftovers.is_empty(), "no temporary file is left behind");
    let e = refused(d, &["merge", "p1.csv"]);
    assert!(
        e.starts_with("dicesim: p1.csv: not a dicesim part summary"),
        "{e}"
    );
    let e = refused(d, &["batch", "--rolls", "10", "--shard", "4/4", "--out", "x.csv"]);
    assert!(
        e.contains("`4/4`: K counts from 0, so it must be below N = 4"),
        "{e}"
    );
}

#[test]
fn parquet_and_summary_only_shards_merge_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let one = ok(d, &["batch", "--rolls", "3000", "--out", "one.parquet"]);
    std::fs::create_dir(d.join("counts")).unwrap();
    for k in 0..3 {
        let shard = format!("{k}/3");
        ok(
            d,
            &[
                "batch",
                "--rolls",
                "3000",
                "--shard",
                &shard,
                "--out",
                &format!("q{k}.parquet"),
            ],
        );
        ok(
            d,
            &[
                "batch",
                "--rolls",
                "3000",
                "--shard",
                &shard,
                "--part",
                &format!("counts/s{k}.part.json"),
            ],
        );
    }
    ok(
        d,
        &[
            "merge",
            "q0.part.json",
            "q1.part.json",
            "q2.part.json",
            "--out",
            "m.parquet",
            "--out",
            "m.csv",
        ],
    );
    assert_eq!(bytes(d, "m.parquet"), bytes(d, "one.parquet"));
    ok(d, &["batch", "--rolls", "3000", "--out", "one.csv"]);
    assert_eq!(bytes(d, "m.csv"), bytes(d, "one.csv"));
    // Summary-only parts: the counts, and nothing to write.
    let summary = ok(d, &["merge", "counts"]);
    assert_eq!(counts(&summary), counts(&one));
    let e = refused(d, &["merge", "counts", "--out", "x.csv"]);
    assert!(e.contains("the parts hold only summaries"), "{e}");
}

#[test]
fn the_slurm_scripts_run_a_sweep_task_by_task() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let sweep = d.join("sweep");
    let written = ok(
        d,
        &[
            "slurm",
            "--shards",
            "3",
            "--cpus-per-task",
            "2",
            "--dir",
            sweep.to_str().unwrap(),
            "--",
            "batch",
            "--rolls",
            "900",
        ],
    );
    assert!(
        written.contains("shards.sbatch (3 array tasks, 2 CPUs each)"),
        "{written}"
    );
    assert!(written.contains("sbatch --dependency=afterok:"), "{written}");
    let script = std::fs::read_to_string(sweep.join("shards.sbatch")).unwrap();
    for line in [
        "#SBATCH --array=0-2\n",
        "#SBATCH --cpus-per-task=2\n",
        "--shard \"$k/3\"",
    ] {
        assert!(script.contains(line), "{line} in {script}");
    }
    // bash reads #SBATCH lines as comments: each task and then the merge, as Slurm runs them.
    for k in 0..3 {
        let o = Command::new("bash")
            .arg(sweep.join("shards.sbatch"))
            .env("SLURM_ARRAY_TASK_ID", k.to_string())
            .env("SLURM_CPUS_PER_TASK", "1")
            .env("DICESIM_PRESETS", d.join("no-user-presets"))
            .current_dir(d)
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "task {k}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let o = Command::new("bash")
        .arg(sweep.join("merge.sbatch"))
        .current_dir(d)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "merge: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let one = ok(d, &["batch", "--rolls", "900", "--out", "one.csv"]);
    assert_eq!(
        std::fs::read(sweep.join("batch.csv")).unwrap(),
        bytes(d, "one.csv")
    );
    let merged = std::fs::read_to_string(sweep.join("summary.txt")).unwrap();
    assert_eq!(counts(&merged), counts(&one));
    // A second sweep into the same folder would mix parts.
    let e = refused(
        d,
        &[
            "slurm", "--shards", "2", "--dir", "sweep", "--", "batch", "--rolls", "5",
        ],
    );
    assert!(e.contains("already holds the parts of a sweep"), "{e}");
}

#[test]
fn a_part_summary_or_a_script_is_replaced_only_with_force() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let shard = [
        "batch",
        "--rolls",
        "40",
        "--shard",
        "0/2",
        "--part",
        "a.part.json",
    ];
    ok(d, &shard);
    let first = bytes(d, "a.part.json");
    let err = refused(d, &shard);
    assert!(
        err.contains("a.part.json: the file exists (--force replaces it)"),
        "{err}"
    );
    assert_eq!(bytes(d, "a.part.json"), first, "the refused run changed the part");
    ok(d, &[&shard[..], &["--force"]].concat());

    let sweep = d.join("sweep");
    let slurm = [
        "slurm",
        "--shards",
        "2",
        "--dir",
        sweep.to_str().unwrap(),
        "--",
        "batch",
        "--rolls",
        "90",
    ];
    ok(d, &slurm);
    let err = refused(d, &slurm);
    assert!(
        err.contains("shards.sbatch: the file exists (--force replaces it)"),
        "{err}"
    );
    ok(d, &[&slurm[..5], &["--force"], &slurm[5..]].concat());
}
