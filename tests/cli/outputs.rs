//! Files written from the command line: never clobbered, checked before any work, written
//! whole or not at all.

use crate::common::dicesim_in;
use std::process::{Command, Output};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Rolls of millions of steps each: a run that computed before checking would take minutes.
const SLOW: [&str; 4] = ["--set", "ground.friction=0", "--set", "integrator.dt=1e-5"];

const BASIN: [&str; 6] = [
    "basin",
    "--x",
    "initial.height:1:2",
    "--y",
    "initial.angular_velocity.x:-5:5",
    "--res",
];

#[test]
fn an_existing_file_is_refused_without_force_and_replaced_with_it() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["old.csv", "old.json"] {
        std::fs::write(dir.path().join(name), "precious").unwrap();
        let o = dicesim_in(dir.path(), &["batch", "--rolls", "3", "--out", name]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert_eq!(
            stderr(&o).trim(),
            format!("dicesim: --out {name}: the file exists (--force replaces it)")
        );
        assert_eq!(
            std::fs::read_to_string(dir.path().join(name)).unwrap(),
            "precious"
        );
    }
    std::fs::write(dir.path().join("map.png"), "precious").unwrap();
    let mut args = BASIN.to_vec();
    args.extend(["4x3", "--out", "map.png"]);
    let o = dicesim_in(dir.path(), &args);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(dir.path().join("map.png")).unwrap(),
        "precious"
    );

    let o = dicesim_in(
        dir.path(),
        &["batch", "--rolls", "3", "--out", "old.csv", "--force"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path().join("old.csv")).unwrap();
    assert_eq!(text.lines().count(), 4, "a header and 3 rolls: {text}");
    args.push("--force");
    let o = dicesim_in(dir.path(), &args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        std::fs::read(dir.path().join("map.png"))
            .unwrap()
            .starts_with(b"\x89PNG")
    );
}

#[test]
fn a_bad_output_path_is_refused_before_any_roll() {
    let dir = tempfile::tempdir().unwrap();
    let mut slow = vec!["batch", "--rolls", "1000"];
    slow.extend(SLOW);
    for (out, why) in [
        ("/nonexistent/x.csv", "the folder /nonexistent does not exist"),
        ("x.txt", "expected a .csv, .json or .parquet file"),
    ] {
        let mut args = slow.clone();
        args.extend(["--out", out]);
        let o = dicesim_in(dir.path(), &args);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains(why), "{}", stderr(&o));
        assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
    }
    let mut args = BASIN.to_vec();
    args.extend(["100x100", "--out", "/nonexistent/map.svg"]);
    args.extend(SLOW);
    let o = dicesim_in(dir.path(), &args);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("the folder /nonexistent does not exist"));
}

#[cfg(target_os = "linux")]
#[test]
fn a_write_that_fails_reports_the_os_error_and_exits_1() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["full.svg", "full.png", "full.csv"] {
        std::os::unix::fs::symlink("/dev/full", dir.path().join(name)).unwrap();
        let mut args = BASIN.to_vec();
        args.extend(["3x2", "--out", name]);
        let o = dicesim_in(dir.path(), &args);
        assert_eq!(o.status.code(), Some(1), "{name}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("No space left on device"),
            "{name}: {}",
            stderr(&o)
        );
        assert!(!String::from_utf8_lossy(&o.stdout).contains("wrote"));
    }
}

#[cfg(unix)]
#[test]
fn the_first_ctrl_c_of_a_slow_batch_keeps_every_completed_roll() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["batch", "--rolls", "5000", "--out", "slow.csv"];
    args.extend(SLOW);
    let child = Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(&args)
        .current_dir(dir.path())
        .env("DICESIM_PRESETS", dir.path().join("none"))
        .stderr(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    nix::sys::signal::kill(
        nix::unistd::Pid::from_raw(child.id() as i32),
        nix::sys::signal::Signal::SIGINT,
    )
    .unwrap();
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    let message = stderr(&o);
    let kept: usize = message
        .split("kept the ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("says how many: {message}"));
    let text = std::fs::read_to_string(dir.path().join("slow.csv")).expect("the file is written");
    let ids: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(ids.len(), kept, "{message}");
    assert!(
        ids.iter().enumerate().all(|(i, id)| *id == i.to_string()),
        "an exact prefix"
    );
}

/// A merge's outputs are written all or none: a write that fails (a full disk, here a
/// link to /dev/full) leaves no other output of the merge behind, nor its sidecar.
#[cfg(target_os = "linux")]
#[test]
fn a_merge_with_several_outputs_writes_all_of_them_or_none() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for k in 0..2 {
        let shard = format!("{k}/2");
        let out = format!("p{k}.csv");
        let o = dicesim_in(d, &["batch", "--rolls", "20", "--shard", &shard, "--out", &out]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    std::os::unix::fs::symlink("/dev/full", d.join("full.parquet")).unwrap();
    let o = dicesim_in(
        d,
        &[
            "merge",
            "p0.part.json",
            "p1.part.json",
            "--out",
            "ok.csv",
            "--out",
            "full.parquet",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("No space left on device"), "{}", stderr(&o));
    assert!(
        !d.join("ok.csv").exists(),
        "the CSV written before the failure is gone"
    );
    assert!(!d.join("ok.csv.meta.json").exists());
    assert!(!String::from_utf8_lossy(&o.stdout).contains("wrote"));
    // Both writable: both written.
    let o = dicesim_in(
        d,
        &[
            "merge",
            "p0.part.json",
            "p1.part.json",
            "--out",
            "ok.csv",
            "--out",
            "ok.parquet",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        d.join("ok.csv").is_file() && d.join("ok.csv.meta.json").is_file() && d.join("ok.parquet").is_file()
    );
}
