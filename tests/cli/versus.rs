//! `dicesim batch --versus` from the command line: the same bits for any job count, bad
//! values refused naming the key, Ctrl-C keeping a whole prefix of the throws. (What the
//! two setups' table says is tested with the experiment crate.)

use crate::common::{dicesim_ok, dicesim_refused};

#[test]
fn the_command_gives_the_same_bits_for_any_job_count() {
    let dir = tempfile::tempdir().unwrap();
    let run = |jobs: &str, out: &str| {
        let text = dicesim_ok(
            dir.path(),
            &[
                "batch",
                "--rolls",
                "700",
                "--seed",
                "5",
                "--versus",
                "ground.friction=0.3",
                "--versus",
                "ground.damping=0.01",
                "--jobs",
                jobs,
                "--json",
                "--out",
                out,
            ],
        );
        let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
        v["jobs"] = serde_json::Value::Null;
        (v, std::fs::read(dir.path().join(out)).unwrap())
    };
    let (one, csv_one) = run("1", "one.csv");
    let (two, csv_two) = run("2", "two.csv");
    assert_eq!(one, two);
    assert!(csv_one == csv_two, "the per-throw CSVs differ");
    // The table's 49 cells add up to the throws, the share is the diagonal over the
    // faced throws.
    let table: Vec<Vec<u64>> = serde_json::from_value(one["table"].clone()).unwrap();
    let total: u64 = table.iter().flatten().sum();
    assert_eq!(total, 700);
    let diagonal: u64 = (0..6).map(|f| table[f][f]).sum();
    let faced: u64 = table[..6].iter().map(|r| r[..6].iter().sum::<u64>()).sum();
    let share = diagonal as f64 / faced as f64;
    assert!((one["agreement"].as_f64().unwrap() - share).abs() < 1e-12);
    // The CSV: the header, one row a throw with both endings.
    let text = String::from_utf8(csv_one).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let (a, b) = (
        header.iter().position(|c| *c == "a_face").unwrap(),
        header.iter().position(|c| *c == "b_face").unwrap(),
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 700);
    let agree = rows.iter().filter(|r| !r[a].is_empty() && r[a] == r[b]).count() as u64;
    assert_eq!(agree, diagonal);
    // The text table says the same share.
    let text = dicesim_ok(
        dir.path(),
        &[
            "batch",
            "--rolls",
            "700",
            "--seed",
            "5",
            "--versus",
            "ground.friction=0.3",
            "--versus",
            "ground.damping=0.01",
        ],
    );
    let percent = format!("{:.1}%", 100.0 * diagonal as f64 / faced as f64);
    assert!(
        text.contains(&format!("agreement  {percent} ({diagonal} of {faced})")),
        "{text}"
    );
}

#[test]
fn bad_versus_values_are_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let err = dicesim_refused(
        dir.path(),
        &["batch", "--rolls", "10", "--versus", "ground.friction=-1"],
    );
    assert!(err.contains("ground.friction"), "{err}");
    let err = dicesim_refused(
        dir.path(),
        &["batch", "--rolls", "10", "--versus", "initial.height=9"],
    );
    assert!(
        err.contains("initial.height") && err.contains("throws are shared"),
        "{err}"
    );
    let err = dicesim_refused(
        dir.path(),
        &["batch", "--rolls", "10", "--versus", "ground.grip=3"],
    );
    assert!(err.contains("ground.grip"), "{err}");
    assert!(!dir.path().join("x.csv").exists());
}

/// Ctrl-C during a long `--versus` run keeps the throws rolled in both setups, a whole
/// prefix of them, says how many, and exits with status 130.
#[cfg(unix)]
#[test]
fn ctrl_c_keeps_a_whole_prefix_of_the_throws() {
    use nix::sys::signal::{Signal, kill};
    use nix::unistd::Pid;
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    // Drops from 1.5 cm without throw or spin: each settles in a few hundred steps.
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .current_dir(dir.path())
        .args([
            "batch",
            "--rolls",
            "100000000",
            "--versus",
            "ground.friction=0.3",
            "--out",
            "x.csv",
            "--set",
            "random.height=[1.5,1.5]",
            "--set",
            "random.velocity=[0,0]",
            "--set",
            "random.angular_velocity=[0,0]",
        ])
        .env("DICESIM_PRESETS", dir.path().join("no-user-presets"))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Until the file being written holds some throws.
    let start = Instant::now();
    let writing = || {
        std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(|e| e.ok())
            .any(|e| {
                let name = e.file_name().to_string_lossy().into_owned();
                name.ends_with(".part") && e.metadata().is_ok_and(|m| m.len() > 100_000)
            })
    };
    while !writing() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the write never started"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    kill(Pid::from_raw(child.id() as i32), Signal::SIGINT).unwrap();
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{err}");
    assert!(
        err.contains("interrupted: kept the ") && err.contains(" throws completed"),
        "{err}"
    );
    let text = std::fs::read_to_string(dir.path().join("x.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let b_status = header.iter().position(|c| *c == "b_status").unwrap();
    let rows: Vec<Vec<&str>> = text.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert!(!rows.is_empty());
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r[0], i.to_string(), "a prefix of the throws");
        assert_eq!(r.len(), header.len());
        assert!(!r[b_status].is_empty(), "throw {i} was rolled in B too");
    }
    assert!(
        err.contains(&format!("kept the {} of 100000000", rows.len())),
        "{err}"
    );
}
