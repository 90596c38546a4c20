//! Issue 49, item 4 (and defects 2 and 3): every size a user types has a limit, stated in
//! its option's `--help` and in docs/troubleshooting.md, and a request past it is refused
//! with exit 2 before any work — not an 8 GB allocation that aborts, nor a trace that never
//! ends.

use crate::common::dicesim_in;
use dicesim_experiment::limits::{self, SizeLimit};
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

#[test]
fn sizes_past_their_limits_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: [(&[&str], &SizeLimit); 8] = [
        // Defect 2: a billion candidates passed the roll limit, then allocated 8 GB.
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
        // Defect 3: a trace of 2⁶⁴ − 1 steps ran without end or progress.
        (
            &["trace", "--steps", "18446744073709551615"],
            &limits::TRACE_STEPS,
        ),
        (
            &["trace", "--steps", "12000001", "--out", "t.csv"],
            &limits::TRACE_STEPS,
        ),
        (
            &["batch", "--rolls", "100000000001", "--out", "b.csv"],
            &limits::BATCH_ROLLS,
        ),
        (
            &["predict", "--rolls", "100000000", "--out", "p.csv"],
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
    ];
    for (args, limit) in cases {
        let start = Instant::now();
        let o = dicesim_in(d, args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "{args:?} took {:?}",
            start.elapsed()
        );
        assert!(stderr.contains(&limit.stated()), "{args:?}: {stderr}");
        assert!(o.stdout.is_empty(), "{args:?} printed before refusing");
    }
    // Nothing was written, not even a temporary file.
    let left: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "{left:?}");
    // The limit itself is allowed.
    let o = dicesim_in(d, &["trace", "--steps", "3", "--every", "1"]);
    assert!(o.status.success());
}
