//! A signal that stops a write never leaves a temporary file behind: a first stop signal
//! (Ctrl-C, SIGTERM from `kill` or a Slurm time limit, SIGHUP, SIGQUIT) keeps what is
//! complete, a second stops at once and removes the file being written, and `merge`, which
//! has no use for half a result, removes it at the first. Each says what was kept.

#![cfg(unix)]

use nix::sys::signal::{Signal, kill};
use nix::unistd::Pid;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn spawn(dir: &Path, args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .current_dir(dir)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// The temporary files in `dir` (`.NAME.XXXX.part`).
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.') && n.ends_with(".part"))
        .collect()
}

/// Whether a temporary file in `dir` holds data (the empty one `--out`'s check makes and
/// deletes at once is not the write).
fn writing(dir: &Path) -> bool {
    temporaries(dir)
        .iter()
        .any(|n| std::fs::metadata(dir.join(n)).is_ok_and(|m| m.len() > 0))
}

/// Waits until the command is writing (its temporary file holds data), then sends
/// `signals` 1 ms apart; returns the exit code and stderr.
fn stop_while_writing(dir: &Path, child: Child, signals: &[Signal]) -> (Option<i32>, String) {
    let start = Instant::now();
    while !writing(dir) {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the write never started"
        );
        std::thread::sleep(Duration::from_millis(1));
    }
    for &s in signals {
        kill(Pid::from_raw(child.id() as i32), s).unwrap();
        std::thread::sleep(Duration::from_millis(1));
    }
    let o = child.wait_with_output().unwrap();
    (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned())
}

/// Rolls that settle in a few hundred steps: many of them, quickly.
const QUICK: [&str; 6] = [
    "--set",
    "random.height=[1.5,1.5]",
    "--set",
    "random.velocity=[0,0]",
    "--set",
    "random.angular_velocity=[0,0]",
];

fn batch(rolls: &str, out: &str) -> Vec<String> {
    ["batch", "--rolls", rolls, "--out", out]
        .iter()
        .chain(QUICK.iter())
        .map(|s| s.to_string())
        .collect()
}

#[test]
fn every_stop_signal_keeps_a_whole_prefix_and_leaves_no_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for signal in [Signal::SIGTERM, Signal::SIGHUP, Signal::SIGQUIT, Signal::SIGINT] {
        let out = format!("{signal:?}.csv");
        let args = batch("100000000", &out);
        let child = spawn(d, &args.iter().map(String::as_str).collect::<Vec<_>>());
        let (code, err) = stop_while_writing(d, child, &[signal]);
        // As a shell reports a process the signal stopped, the completed work kept first:
        // 143 for SIGTERM, 129 for SIGHUP, 131 for SIGQUIT, 130 for Ctrl-C (they all said 130).
        assert_eq!(code, Some(128 + signal as i32), "{signal:?}: {err}");
        assert!(err.contains("interrupted: kept the "), "{signal:?}: {err}");
        assert!(temporaries(d).is_empty(), "{signal:?}: {:?}", temporaries(d));
        let text = std::fs::read_to_string(d.join(&out)).unwrap();
        let ids: Vec<&str> = text
            .lines()
            .skip(1)
            .map(|l| l.split(',').next().unwrap())
            .collect();
        assert!(
            ids.iter().enumerate().all(|(i, id)| *id == i.to_string()),
            "{signal:?}: a prefix"
        );
    }
}

#[test]
fn two_signals_at_once_stop_at_once_and_remove_the_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let args = batch("100000000", "twice.csv");
    let child = spawn(d, &args.iter().map(String::as_str).collect::<Vec<_>>());
    let (code, err) = stop_while_writing(d, child, &[Signal::SIGINT, Signal::SIGINT]);
    assert_eq!(code, Some(130), "{err}");
    // Either the second signal stopped it at once, or the first had already kept a prefix;
    // never silently, never with the temporary file left.
    if d.join("twice.csv").exists() {
        assert!(err.contains("interrupted: kept the "), "{err}");
    } else {
        assert!(
            err.contains(
                "dicesim: stopped again by signal 2: the file being written was removed, nothing was written"
            ),
            "{err}"
        );
    }
    assert!(temporaries(d).is_empty(), "{:?}", temporaries(d));
}

#[test]
fn a_signal_during_a_merge_removes_its_file_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut args = batch("20000", "a.csv");
    args.extend(["--shard".to_string(), "0/1".to_string()]);
    let o = Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .current_dir(d)
        .args(&args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for signal in [Signal::SIGTERM, Signal::SIGINT] {
        // A signal can land after the merge put its file in place; the program must then say
        // so, and the test tries again for a signal that lands mid-write.
        let mut removed = false;
        for _ in 0..5 {
            let child = spawn(d, &["merge", "a.part.json", "--out", "m.csv"]);
            let (code, err) = stop_while_writing(d, child, &[signal]);
            assert_eq!(code, Some(128 + signal as i32), "{err}");
            assert!(temporaries(d).is_empty(), "{:?}", temporaries(d));
            let said =
                |what: &str| err.contains(&format!("dicesim: stopped by signal {}: {what}", signal as i32));
            if said("m.csv had been written before it") {
                assert!(d.join("m.csv").exists(), "{err}");
                std::fs::remove_file(d.join("m.csv")).unwrap();
                continue;
            }
            assert!(
                said("the file being written was removed, nothing was written"),
                "{err}"
            );
            assert!(!d.join("m.csv").exists());
            removed = true;
            break;
        }
        assert!(
            removed,
            "no {signal:?} in five landed while the merge was writing"
        );
    }
}

/// Waits for `child` to end at most `limit` after `kill`ing it with `signal` once; returns
/// its exit code and stderr, or kills it and fails.
fn ended_within(child: Child, signal: Signal, limit: Duration, what: &str) -> (Option<i32>, String) {
    let pid = child.id();
    kill(Pid::from_raw(pid as i32), signal).unwrap();
    let sent = Instant::now();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(child.wait_with_output());
    });
    match rx.recv_timeout(limit + Duration::from_secs(30)) {
        Ok(o) => {
            let o = o.unwrap();
            let took = sent.elapsed();
            let err = String::from_utf8_lossy(&o.stderr).into_owned();
            assert!(
                took <= limit,
                "{what}: ended {took:?} after one {signal:?}: {err}"
            );
            (o.status.code(), err)
        }
        Err(_) => {
            let _ = kill(Pid::from_raw(pid as i32), Signal::SIGKILL);
            panic!("{what}: still running 30 s after one {signal:?}");
        }
    }
}

#[test]
fn one_stop_signal_ends_predict_basin_compare_and_animate_within_two_seconds() {
    // Work that runs for minutes: an adaptive basin map's last levels (after a cancel every
    // chunk still stepped its rolls to their first stop check: 4 s at 1000×1000), a long
    // prediction, a long comparison and a slow-motion animation.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: [(&str, &[&str]); 4] = [
        (
            "basin",
            &[
                "basin",
                "--x",
                "initial.angular_velocity.x:-60:60",
                "--y",
                "initial.height:2:20",
                "--res",
                "1000x1000",
                "--out",
                "map.png",
            ],
        ),
        ("predict", &["predict", "--rolls", "10000000", "--out", "p.png"]),
        (
            "compare",
            &["compare", "wolf-red", "--throws", "100000000", "--out", "c.png"],
        ),
        (
            "animate",
            &[
                "animate",
                "--out",
                "a.gif",
                "--size",
                "1600x1200",
                "--fps",
                "50",
                "--speed",
                "1/10",
            ],
        ),
    ];
    for (what, args) in cases {
        let child = spawn(d, args);
        // Well into the work, its signal handler long installed.
        std::thread::sleep(Duration::from_millis(1500));
        let (code, err) = ended_within(child, Signal::SIGTERM, Duration::from_secs(2), what);
        assert_eq!(code, Some(143), "{what}: {err}");
        assert!(temporaries(d).is_empty(), "{what}: {:?}", temporaries(d));
    }
}

/// Issue 49, defect 3: `trace --out` left its `.tr.csv.XXXXXX.part` and its sidecar's when
/// stopped; now every stop signal removes both, says nothing was written, and exits 128 + N.
#[test]
fn a_signal_during_a_trace_removes_its_file_and_its_sidecars() {
    for signal in [Signal::SIGINT, Signal::SIGTERM, Signal::SIGHUP] {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let child = spawn(
            d,
            &[
                "trace",
                "--steps",
                "12000000",
                "--set",
                "integrator.max_time=120",
                "--out",
                "tr.csv",
            ],
        );
        let (code, stderr) = stop_while_writing(d, child, &[signal]);
        assert_eq!(code, Some(128 + signal as i32), "{signal}: {stderr}");
        assert!(stderr.contains("nothing was written"), "{signal}: {stderr}");
        let left: Vec<_> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert!(left.is_empty(), "{signal}: {left:?}");
    }
}
