//! Issue 49, item 4 (and defects 2 and 3): every size a user types has a limit, stated in
//! its option's `--help` and in docs/troubleshooting.md, and a request past it is refused
//! with exit 2 before any work — not an 8 GB allocation that aborts, nor a trace that never
//! ends.

use crate::common::dicesim_in;
use dicesim_experiment::limits::{self, SizeLimit};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

#[test]
fn every_limit_is_stated_in_the_help_and_the_docs() {
    let dir = tempfile::tempdir().unwrap();
    let docs =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/troubleshooting.md")).unwrap();
    for limit in limits::ALL {
        let stated = limit.stated();
        assert!(
            docs.contains(&stated),
            "docs/troubleshooting.md does not state `{stated}`"
        );
        for command in limit.commands {
            let o = dicesim_in(dir.path(), &[command, "--help"]);
            // clap folds lines: compare with the whitespace run together.
            let help = String::from_utf8(o.stdout)
                .unwrap()
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" ");
            assert!(
                help.contains(&stated),
                "`dicesim {command} --help` does not state `{stated}`"
            );
        }
    }
}

/// Runs `dicesim args` in `dir`, killed if it is not done within 20 s (a request past a
/// limit that is not refused runs for hours or aborts on memory); its exit code and stderr.
fn refused_within(dir: &Path, args: &[&str]) -> (Option<i32>, String, bool) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(args)
        .current_dir(dir)
        .env("DICESIM_PRESETS", dir.join("no-user-presets"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(20) {
            child.kill().unwrap();
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let o = child.wait_with_output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        o.stdout.is_empty(),
    )
}

/// Each request is refused with exit 2, at once, naming the limit, printing and writing
/// nothing.
fn assert_refused(cases: &[(&[&str], &SizeLimit)]) {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (args, limit) in cases {
        let (code, stderr, quiet) = refused_within(d, args);
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(&limit.stated()), "{args:?}: {stderr}");
        assert!(quiet, "{args:?} printed before refusing");
    }
    // Nothing was written, not even a temporary file.
    let left: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

/// Defect 2: a billion candidates passed the roll limit, then allocated 8 GB at once.
#[test]
fn a_billion_candidates_are_refused_at_once() {
    assert_refused(&[
        (
            &[
                "compare",
                "wolf-red",
                "--candidates",
                "1000000000",
                "--fit",
                "ground.friction:0:1",
                "--throws",
                "1",
            ],
            &limits::CANDIDATES,
        ),
        (
            &[
                "compare",
                "wolf-red",
                "--candidates",
                "1001",
                "--fit",
                "ground.friction:0:1",
                "--throws",
                "1",
            ],
            &limits::CANDIDATES,
        ),
    ]);
}

/// Defect 3: a trace of 2⁶⁴ − 1 steps ran without end or progress.
#[test]
fn a_trace_without_end_is_refused_at_once() {
    assert_refused(&[
        (
            &["trace", "--steps", "18446744073709551615"],
            &limits::TRACE_STEPS,
        ),
        (
            &["trace", "--steps", "12000001", "--out", "t.csv"],
            &limits::TRACE_STEPS,
        ),
    ]);
    // The limit itself is allowed.
    let dir = tempfile::tempdir().unwrap();
    assert!(
        dicesim_in(dir.path(), &["trace", "--steps", "3"])
            .status
            .success()
    );
}

#[test]
fn every_other_size_past_its_limit_is_refused_at_once() {
    assert_refused(&[
        (
            &["batch", "--rolls", "100000000001", "--out", "b.csv"],
            &limits::BATCH_ROLLS,
        ),
        (
            &["predict", "--rolls", "100000000", "--out", "p.csv"],
            &limits::EXPERIMENT_ROLLS,
        ),
        (
            &["compare", "wolf-red", "--throws", "1000000001"],
            &limits::EXPERIMENT_ROLLS,
        ),
        (
            &[
                "basin",
                "--x",
                "initial.height:2:20",
                "--y",
                "ground.friction:0:1",
                "--res",
                "4096x2048",
                "--out",
                "m.csv",
            ],
            &limits::MAP_CELLS,
        ),
        // A roll of 2.5 s at 50 frames/s played 100 times slower: 12 500 frames.
        (
            &[
                "animate",
                "--fps",
                "50",
                "--speed",
                "1/100",
                "--set",
                "ground.damping=0",
                "--out",
                "a.gif",
            ],
            &limits::FRAMES,
        ),
    ]);
}
