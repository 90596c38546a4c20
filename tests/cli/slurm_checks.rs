//! `dicesim slurm` writes shell scripts: every value it puts into one is checked, the whole
//! sweep is checked as an array task will parse it, and a refusal writes nothing at all.

use crate::common::dicesim_in;
use std::path::Path;

/// Runs `slurm` into `dir/sweep` with `options` and the sweep `command`; it must be
/// refused (exit 2) and leave no `sweep` folder. Returns stderr.
fn refused(dir: &Path, options: &[&str], command: &[&str]) -> String {
    let mut args = vec!["slurm", "--shards", "4", "--dir", "sweep"];
    args.extend(options);
    args.push("--");
    args.extend(command);
    let o = dicesim_in(dir, &args);
    let e = String::from_utf8(o.stderr).unwrap();
    assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
    assert!(!dir.join("sweep").exists(), "{args:?} wrote the folder");
    e
}

#[test]
fn values_that_would_inject_script_lines_or_options_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let batch = ["batch", "--rolls", "100"];
    for (flag, value) in [
        ("--partition", "gpu\ntouch x"),
        ("--account", "a\ntouch x"),
        ("--time", "1:00\ntouch x"),
        ("--mem", "1G\ntouch x"),
        ("--time", "1:00:00 --wrap=x"),
        ("--partition", "gpu --wrap=x"),
        ("--mem", "500M;x"),
        ("--time", "1:00\u{85}"),
    ] {
        let e = refused(d, &[flag, value], &batch);
        assert!(
            e.starts_with(&format!(
                "dicesim: {flag} `{}`: not a value for an #SBATCH line",
                value.escape_debug()
            )),
            "{e}"
        );
    }
    let e = refused(
        d,
        &[],
        &["batch", "--rolls", "100", "--set", "ground.friction=0.3\necho x"],
    );
    assert!(e.contains("holds a control character"), "{e}");
    assert!(!d.join("x").exists());
}

#[test]
fn the_sweep_is_checked_as_an_array_task_parses_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let e = refused(d, &[], &["batch", "--rolls", "100", "--set", "nonexist.key=1"]);
    assert!(
        e.starts_with("dicesim: the sweep's command line: ") && e.contains("nonexist"),
        "{e}"
    );
    let e = refused(d, &[], &["batch", "--rolls", "100", "--preset", "nonexistent"]);
    assert!(e.contains("nonexistent"), "{e}");
    let map = [
        "basin",
        "--x",
        "initial.height:5:20",
        "--y",
        "ground.friction:0.2:0.8",
    ];
    let e = refused(d, &[], &[&map[..], &["--adaptive"]].concat());
    assert!(
        e.contains("adaptive refinement compares cells across shards"),
        "{e}"
    );
    let e = refused(d, &[], &[&map[..], &["--res", "5000x5000"]].concat());
    assert!(e.contains("--res 5000x5000: 25000000 cells"), "{e}");
    let e = refused(
        d,
        &[],
        &["batch", "--rolls", "100", "--set", "random.height=[0,0]"],
    );
    assert!(e.contains("`random.height` = 0"), "{e}");
}

#[test]
fn a_bad_dir_creates_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = dicesim_in(
        d,
        &[
            "slurm",
            "--shards",
            "2",
            "--dir",
            "my sweep/x",
            "--",
            "batch",
            "--rolls",
            "10",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("may not hold spaces"));
    assert!(!d.join("my sweep").exists(), "no folder tree left behind");
}
