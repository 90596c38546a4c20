//! Every path that rolls checks its starts the way `roll` checks its one start: no corner
//! may begin inside the table deeper than the die's resting depth. The lowest height each
//! error names is derived here from the die's geometry, not taken from the program.

use crate::common::dicesim_in;
use std::path::Path;

/// cm: the default die's half size and its resting depth M·g/(4k) (8 g, 980 cm/s²,
/// 500 000 dyn/cm).
const HALF_SIZE: f64 = 1.0;
const RESTING_DEPTH: f64 = 8.0 * 980.0 / (4.0 * 500_000.0);

fn refused(dir: &Path, args: &[&str]) -> String {
    let o = dicesim_in(dir, args);
    let e = String::from_utf8(o.stderr).unwrap();
    assert_eq!(o.status.code(), Some(2), "dicesim {}: {e}", args.join(" "));
    assert!(
        o.stdout.is_empty(),
        "nothing rolled: {}",
        String::from_utf8_lossy(&o.stdout)
    );
    e
}

#[test]
fn every_path_refuses_a_start_with_a_corner_in_the_table() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Upright, the lowest corners sit one half size below the centre.
    let upright = format!("{}", HALF_SIZE - RESTING_DEPTH);
    let e = refused(d, &["roll", "--set", "initial.height=0"]);
    assert!(e.contains(&format!("allowed range {upright} to")), "{e}");
    let e = refused(d, &["batch", "--rolls", "10", "--set", "random.height=[0,0]"]);
    assert!(
        e.contains("`random.height` = 0") && e.contains(&format!("allowed range {upright} to")),
        "{e}"
    );
    std::fs::write(d.join("h0.csv"), "id,height\n0,15\n1,0\n").unwrap();
    let e = refused(d, &["batch", "--ics", "h0.csv", "--out", "o.csv"]);
    assert!(e.starts_with("dicesim: --ics h0.csv: id 1: `height` = 0"), "{e}");
    assert!(!d.join("o.csv").exists());
    let e = refused(
        d,
        &[
            "basin",
            "--x",
            "initial.height:0:2",
            "--y",
            "initial.angular_velocity.x:0:1",
            "--res",
            "4x4",
        ],
    );
    assert!(e.starts_with("dicesim: the node initial.height = 0, "), "{e}");
    let e = refused(d, &["predict", "--vary", "initial.height=0", "--rolls", "4"]);
    assert!(e.contains("`random.height` = 0"), "{e}");
}

#[test]
fn a_random_orientation_needs_the_height_of_the_farthest_corner() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Some orientation points a corner straight down: √3 half sizes below the centre.
    let lowest = 3f64.sqrt() * HALF_SIZE - RESTING_DEPTH;
    let args = |low: f64| {
        vec![
            "batch".to_string(),
            "--rolls".into(),
            "20".into(),
            "--set".into(),
            "random.random_orientation=true".into(),
            "--set".into(),
            format!("random.height=[{low},2]"),
        ]
    };
    let run = |low: f64| {
        let a = args(low);
        dicesim_in(d, &a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let o = run(lowest - 0.01);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains(
            "a drawn orientation can start a corner deeper in the table than the die sinks resting on it"
        ),
        "{e}"
    );
    let named: f64 = e
        .split("allowed range ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("names the lowest height: {e}"));
    assert!((named - lowest).abs() < 1e-9, "{named} vs {lowest}");
    assert!(run(lowest + 0.01).status.success());
}
