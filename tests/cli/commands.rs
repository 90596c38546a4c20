//! The headless commands, run as a user runs them.

use std::process::{Command, Output};

fn dicesim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(args)
        .env(
            "DICESIM_PRESETS",
            std::env::temp_dir().join("dicesim-cli-tests-no-user-presets"),
        )
        .output()
        .expect("the binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

#[test]
fn roll_json_reports_a_settled_roll() {
    // The default preset throws sideways; this roll starts with no sideways motion.
    let o = dicesim(&[
        "roll",
        "--json",
        "--set",
        "initial.angular_velocity=[20,-35,10]",
        "--set",
        "initial.velocity=[0,0,0]",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["status"], "settled");
    let face = v["face"].as_u64().unwrap();
    assert!((1..=6).contains(&face));
    assert!(v["steps"].as_u64().unwrap() > 169, "the die must at least land");
    assert!((v["energy_threshold"].as_f64().unwrap() - 2_597.947_463_204_053).abs() < 1e-9);
    let time = v["time_s"].as_f64().unwrap();
    assert!((time - v["steps"].as_f64().unwrap() * 0.001).abs() < 1e-9);
    for key in ["position", "velocity", "angular_momentum"] {
        assert_eq!(v["final"][key].as_array().unwrap().len(), 3, "{key}");
    }
    // At the end the die rests near the ground: its centre is about half a side up.
    let z = v["final"]["position"][2].as_f64().unwrap();
    assert!((0.9..1.2).contains(&z), "final height {z}");
}

#[test]
fn roll_reports_instability_as_a_status() {
    let o = dicesim(&[
        "roll",
        "--json",
        "--set",
        "ground.stiffness=2e7",
        "--set",
        "ground.friction=0",
    ]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["status"], "unstable");
    assert!(v["face"].is_null());
}

#[test]
fn bad_set_exits_2_with_one_line_naming_the_key() {
    for (arg, needle) in [
        ("ground.stifness=1", "ground.stifness"),
        ("ground.friction=high", "ground.friction"),
        (
            "ground.friction=9",
            "`ground.friction` = 9 is outside the allowed range 0 to 5",
        ),
        ("initial.angular_velocity=[1,2]", "initial.angular_velocity"),
        ("nonsense", "nonsense"),
    ] {
        let o = dicesim(&["roll", "--set", arg]);
        assert_eq!(o.status.code(), Some(2), "{arg}");
        let err = String::from_utf8(o.stderr).unwrap();
        assert_eq!(err.trim_end().lines().count(), 1, "{arg}: {err}");
        assert!(err.contains(needle), "{arg}: {err}");
        assert!(o.stdout.is_empty(), "nothing is simulated for {arg}");
    }
}

#[test]
fn trace_header_and_rows() {
    // A plain drop: the default preset's throw and spin set to zero.
    let o = dicesim(&[
        "trace",
        "--steps",
        "5",
        "--every",
        "2",
        "--set",
        "initial.velocity=[0,0,0]",
        "--set",
        "initial.angular_velocity=[0,0,0]",
    ]);
    assert!(o.status.success());
    let text = stdout(&o);
    let mut lines = text.lines();
    let mut want = "step,time_s,x_cm,y_cm,z_cm,vx_cm_per_s,vy_cm_per_s,vz_cm_per_s,\
                    Lx_g_cm2_per_s,Ly_g_cm2_per_s,Lz_g_cm2_per_s,wx_rad_per_s,wy_rad_per_s,wz_rad_per_s,\
                    height_cm,lowest_corner_cm,speed_cm_per_s,spin_rate_rad_per_s,contact_force_dyn,\
                    e_trans_erg,e_rot_erg,e_grav_erg,e_elastic_erg,e_total_erg,\
                    contact_mode_load,corner_travel_load,damping_load,friction_load"
        .to_string();
    for k in 1..=8 {
        want += &format!(",c{k}x_cm,c{k}y_cm,c{k}z_cm");
    }
    let header = lines.next().unwrap();
    assert_eq!(header, want);
    let column = |name: &str| header.split(',').position(|c| c == name).unwrap();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.iter().map(|r| r[0] as u64).collect::<Vec<_>>(), [0, 2, 4, 5]);
    // The time of step n is n × Δt to Δt's decimals: 0.004, not the clock's sum.
    assert_eq!(rows[2][column("time_s")], 0.004);
    assert_eq!(text.lines().nth(3).unwrap().split(',').nth(1), Some("0.004"));
    assert!(rows.iter().all(|r| r.len() == 28 + 24));
    // Free fall, kick then drift: z_n = 15 − g·Δt²·n(n+1)/2, v_n = −g·Δt·n.
    let r4 = &rows[2];
    let z4 = 15.0 - 980e-6 * 10.0;
    assert!((r4[column("z_cm")] - z4).abs() < 1e-12);
    assert!((r4[column("vz_cm_per_s")] + 980e-3 * 4.0).abs() < 1e-12);
    // The quantities: the height is the centre's z, the die falls straight at |v_z|
    // without spin, its lowest point one half size below the centre, nothing touches.
    assert_eq!(r4[column("height_cm")], r4[column("z_cm")]);
    assert!((r4[column("speed_cm_per_s")] - 980e-3 * 4.0).abs() < 1e-12);
    assert_eq!(r4[column("spin_rate_rad_per_s")], 0.0);
    assert!((r4[column("lowest_corner_cm")] - (z4 - 1.0)).abs() < 1e-12);
    assert_eq!(r4[column("contact_force_dyn")], 0.0);
    // ½·M·v² with M = 8 g, and M·g·(z − a).
    let v = 980e-3 * 4.0;
    assert!((r4[column("e_trans_erg")] - 0.5 * 8.0 * v * v).abs() < 1e-9);
    assert!((r4[column("e_grav_erg")] - 8.0 * 980.0 * (z4 - 1.0)).abs() < 1e-6);
    // Corner 2 (−,−,+) sits one half size above and beside the centre.
    let c2 = column("c2x_cm");
    assert_eq!((r4[c2], r4[c2 + 1]), (-1.0, -1.0));
    assert!((r4[c2 + 2] - (z4 + 1.0)).abs() < 1e-12);
    // Energy columns add up.
    let terms: f64 = ["e_trans_erg", "e_rot_erg", "e_grav_erg", "e_elastic_erg"]
        .iter()
        .map(|c| r4[column(c)])
        .sum();
    assert!((terms - r4[column("e_total_erg")]).abs() < 1e-6);
}

#[test]
fn trace_without_steps_ends_with_the_roll() {
    let roll = dicesim(&["roll", "--json", "--set", "initial.angular_velocity=[5,8,0]"]);
    let v: serde_json::Value = serde_json::from_str(&stdout(&roll)).unwrap();
    let steps = v["steps"].as_u64().unwrap();
    let o = dicesim(&[
        "trace",
        "--every",
        "100",
        "--set",
        "initial.angular_velocity=[5,8,0]",
    ]);
    let text = stdout(&o);
    let last = text.lines().last().unwrap();
    assert_eq!(last.split(',').next().unwrap().parse::<u64>().unwrap(), steps);
    // Past the end of the roll with --steps.
    let o = dicesim(&["trace", "--every", "1000", "--steps", &(steps + 10).to_string()]);
    let text = stdout(&o);
    assert!(
        text.lines()
            .last()
            .unwrap()
            .starts_with(&format!("{},", steps + 10))
    );
}

#[test]
fn both_engines_write_byte_identical_files() {
    let dir = tempfile::tempdir().unwrap();
    let write = |engine: &str, ext: &str| {
        let path = dir.path().join(format!("{engine}.{ext}"));
        let o = dicesim(&[
            "batch",
            "--rolls",
            "3000",
            "--seed",
            "77",
            "--set",
            "random.random_orientation=true",
            "--engine",
            engine,
            "--out",
            path.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(stdout(&o).contains(&format!("{engine} engine")), "{}", stdout(&o));
        std::fs::read(&path).unwrap()
    };
    let csv = write("scalar", "csv");
    // The header and 3000 rolls.
    assert_eq!(csv.iter().filter(|&&b| b == b'\n').count(), 3001);
    assert!(csv == write("lanes", "csv"), "the CSVs differ");
    let json = |engine| {
        let mut v: serde_json::Value = serde_json::from_slice(&write(engine, "json")).unwrap();
        // Only the wall-clock figures may differ.
        for key in ["elapsed_s", "rolls_per_s", "steps_per_s"] {
            v["summary"][key] = serde_json::Value::Null;
        }
        v
    };
    let scalar = json("scalar");
    assert_eq!(scalar["rolls"].as_array().unwrap().len(), 3000);
    assert_eq!(scalar, json("lanes"));
}

#[test]
fn basin_maps_are_the_same_with_both_engines() {
    let dir = tempfile::tempdir().unwrap();
    let map = |engine: &str| {
        let path = dir.path().join(format!("{engine}.csv"));
        let o = dicesim(&[
            "basin",
            "--x",
            "ground.stiffness:20000:200000",
            "--y",
            "initial.angular_velocity.y:-30:30",
            "--res",
            "23x9",
            "--engine",
            engine,
            "--out",
            path.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read(&path).unwrap()
    };
    assert!(map("scalar") == map("lanes"), "the maps differ");
}

/// Sends SIGINT to a running `dicesim` after `after` and waits for it to end.
#[cfg(unix)]
fn interrupt(child: std::process::Child, after: std::time::Duration) -> Output {
    std::thread::sleep(after);
    signal_and_wait(child)
}

/// Sends SIGINT to `child` once its output's temporary file in `dir` holds at least
/// `min_bytes` (the work is then under way, however fast the machine), and waits for it.
/// The file is polled rather than waited for by a fixed time, so the test does not depend
/// on how quickly the machine rolls.
#[cfg(unix)]
fn interrupt_once_written(mut child: std::process::Child, dir: &std::path::Path, min_bytes: u64) -> Output {
    let start = std::time::Instant::now();
    loop {
        let written = std::fs::read_dir(dir)
            .unwrap()
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().ends_with(".part"))
            .filter_map(|e| e.metadata().ok())
            .any(|m| m.len() >= min_bytes);
        if written {
            break;
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "the command ended before its output reached {min_bytes} bytes"
        );
        // A guard against a hang, not a speed test.
        assert!(start.elapsed().as_secs() < 120, "no output was started");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    signal_and_wait(child)
}

/// Sends SIGINT to `child` and waits for it to end.
#[cfg(unix)]
fn signal_and_wait(mut child: std::process::Child) -> Output {
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let start = std::time::Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        // A guard against a hang, not a speed test: the cancel is answered in milliseconds.
        assert!(start.elapsed().as_secs() < 20, "Ctrl-C was not answered");
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    child.wait_with_output().unwrap()
}

#[cfg(unix)]
#[test]
fn ctrl_c_inside_long_rolls_keeps_an_exact_prefix() {
    use std::process::Stdio;
    let dir = tempfile::tempdir().unwrap();
    let spawn = |engine: &str, out: &std::path::Path, rolls: &str, long: bool| {
        let mut args = vec!["batch", "--rolls", rolls, "--jobs", "2", "--engine", engine];
        if long {
            // Rolls of 1.2·10⁷ steps each (thrown up from 10 m under weak gravity, Δt = 10 µs,
            // 120 s before it could land): a cancel must be noticed inside the rolls.
            args.extend([
                "--set",
                "integrator.dt=0.00001",
                "--set",
                "integrator.max_time=120",
            ]);
            args.extend(["--set", "world.gravity=10", "--set", "random.height=[1000,1000]"]);
            args.extend(["--set", "random.velocity=[1000,1000]"]);
        }
        args.extend(["--out", out.to_str().unwrap()]);
        Command::new(env!("CARGO_BIN_EXE_dicesim"))
            .args(&args)
            .env("DICESIM_PRESETS", dir.path().join("none"))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    for engine in ["scalar", "lanes"] {
        // Long rolls, signalled as soon as the output is started: at any speed a machine
        // could have, 64 rolls of 1.2·10⁷ steps on two threads are not done by then. What was
        // kept (nothing, most likely) is named and is the batch's start.
        let long = dir.path().join(format!("long-{engine}"));
        std::fs::create_dir(&long).unwrap();
        let out = long.join("long.csv");
        let o = interrupt_once_written(spawn(engine, &out, "64", true), &long, 0);
        let err = String::from_utf8_lossy(&o.stderr);
        {
            use std::os::unix::process::ExitStatusExt;
            // A death by signal names the signal: SIGINT itself would mean the handler was
            // not yet installed when the output was started.
            assert_eq!(
                o.status.code(),
                Some(130),
                "signal {:?}: {err}",
                o.status.signal()
            );
        }
        let text = std::fs::read_to_string(&out).unwrap();
        let rows = text.lines().count() - 1;
        assert!(
            err.contains(&format!("interrupted: kept the {rows} of 64 rolls completed")),
            "{err}"
        );
        assert!(rows < 64, "the long rolls finished before the cancel");
        if rows > 0 {
            let full = long.join("full.csv");
            let o = spawn(engine, &full, &rows.to_string(), true)
                .wait_with_output()
                .unwrap();
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            let full = std::fs::read_to_string(&full).unwrap();
            assert!(
                full.lines().skip(1).eq(text.lines().skip(1)),
                "the kept long rolls are not the batch's start"
            );
        }

        // Short rolls: what was kept is the start of the full batch, row for row.
        // Signalled once 64 KiB of rows are written, so some rows are kept at any speed.
        let short = dir.path().join(format!("short-{engine}"));
        std::fs::create_dir(&short).unwrap();
        let out = short.join("short.csv");
        let o = interrupt_once_written(spawn(engine, &out, "1000000", false), &short, 64 << 10);
        assert_eq!(
            o.status.code(),
            Some(130),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        let kept = std::fs::read_to_string(&out).unwrap();
        let rows = kept.lines().count() - 1;
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(&format!("kept the {rows} of 1000000 rolls")),
            "{err}"
        );
        assert!(rows > 0 && rows < 1_000_000);
        let full = dir.path().join(format!("full-{engine}.csv"));
        let o = dicesim(&[
            "batch",
            "--rolls",
            &rows.to_string(),
            "--engine",
            engine,
            "--out",
            full.to_str().unwrap(),
        ]);
        assert!(o.status.success());
        // The same file; the provenances in the sidecars differ in the batch's size only.
        let full_text = std::fs::read_to_string(&full).unwrap();
        assert!(full_text == kept, "the kept rows are not the batch's start");
        let sized = |p: &std::path::Path, n: usize| {
            let meta = std::fs::read(format!("{}.meta.json", p.display())).unwrap();
            serde_json::from_slice::<serde_json::Value>(&meta).unwrap()["provenance"]["rolls"] == n
        };
        assert!(sized(&out, 1_000_000) && sized(&full, rows));
    }
}

#[test]
fn completions_name_every_command_for_each_shell() {
    let bash = dicesim(&["completions", "bash"]);
    assert!(bash.status.success());
    let script = stdout(&bash);
    assert!(script.contains("complete -F _dicesim"), "{script}");
    for word in [
        "roll",
        "trace",
        "batch",
        "basin",
        "merge",
        "slurm",
        "presets",
        "completions",
        "--no-color",
        "--set",
    ] {
        assert!(script.contains(word), "bash completion lacks `{word}`");
    }
    for shell in ["zsh", "fish", "elvish", "powershell"] {
        let o = dicesim(&["completions", shell]);
        assert!(o.status.success(), "{shell}");
        assert!(stdout(&o).contains("basin"), "{shell} completion lacks `basin`");
    }
    let o = dicesim(&["completions", "tcsh"]);
    assert_eq!(o.status.code(), Some(2), "an unknown shell is a usage error");
}

#[test]
fn help_shows_examples_and_exit_statuses() {
    let o = dicesim(&["--help"]);
    let text = stdout(&o);
    assert!(
        text.contains("Examples:") && text.contains("130 interrupted"),
        "{text}"
    );
    for command in [
        "roll",
        "trace",
        "batch",
        "basin",
        "merge",
        "slurm",
        "presets",
        "tui",
        "completions",
        "man",
    ] {
        let o = dicesim(&[command, "--help"]);
        assert!(o.status.success(), "{command}");
        assert!(
            stdout(&o).contains("Examples:\n  dicesim"),
            "{command} --help has no examples"
        );
    }
}

#[test]
fn no_color_is_global_and_agrees_with_no_color_env() {
    // Accepted before and after any command, and by commands that print no colour.
    for args in [
        &["--no-color", "roll"][..],
        &["roll", "--no-color"],
        &["presets", "--no-color", "path"],
    ] {
        let o = dicesim(args);
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    // An error under NO_COLOR or --no-color carries no escape codes.
    let plain = Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(["roll", "--bogus"])
        .env("NO_COLOR", "1")
        .env("CLICOLOR_FORCE", "1")
        .output()
        .unwrap();
    assert!(
        !plain.stderr.contains(&0x1b),
        "{}",
        String::from_utf8_lossy(&plain.stderr)
    );
    let flagged = Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(["--no-color", "roll", "--bogus"])
        .env_remove("NO_COLOR")
        .env("CLICOLOR_FORCE", "1")
        .output()
        .unwrap();
    assert!(
        !flagged.stderr.contains(&0x1b),
        "{}",
        String::from_utf8_lossy(&flagged.stderr)
    );
    let coloured = Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(["roll", "--bogus"])
        .env_remove("NO_COLOR")
        .env("CLICOLOR_FORCE", "1")
        .output()
        .unwrap();
    assert!(
        coloured.stderr.contains(&0x1b),
        "the check above can fail: forced colour shows"
    );
}

#[test]
fn exit_statuses_follow_the_kind_of_failure() {
    // Bad input: 2, with one line naming it.
    let o = dicesim(&["batch", "--ics", "/nonexistent/ics.csv"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.starts_with("dicesim: --ics /nonexistent/ics.csv: "), "{err}");
    // An output folder that does not exist is found before any roll: bad input, 2.
    let o = dicesim(&["batch", "--rolls", "2", "--out", "/nonexistent/dir/rolls.csv"]);
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    // A failure while running (a write to a full device): 1.
    #[cfg(target_os = "linux")]
    {
        let dir = tempfile::tempdir().unwrap();
        let full = dir.path().join("rolls.csv");
        std::os::unix::fs::symlink("/dev/full", &full).unwrap();
        let o = dicesim(&["batch", "--rolls", "2", "--out", full.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    }
    // A reader that stops early is no failure: the exit status is 0 and nothing is printed.
    let mut child = Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(["trace", "--steps", "200000"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.stderr.is_empty(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn set_takes_one_component_of_a_vector() {
    let o = dicesim(&["presets", "show", "paper", "--set", "initial.velocity.y=25"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout(&o).contains("velocity = [30.0, 25.0, 0.0]"),
        "{}",
        stdout(&o)
    );
}

#[cfg(unix)]
#[test]
fn ctrl_c_in_a_basin_map_keeps_an_exact_prefix_of_its_cells() {
    use std::process::Stdio;
    let dir = tempfile::tempdir().unwrap();
    let axes = [
        "basin",
        "--x",
        "initial.angular_velocity.x:-60:60",
        "--y",
        "initial.angular_velocity.y:-60:60",
        "--uniform",
    ];
    let spawn = |res: &str, out: &std::path::Path| {
        Command::new(env!("CARGO_BIN_EXE_dicesim"))
            .args(axes)
            .args(["--res", res, "--jobs", "2", "--out", out.to_str().unwrap()])
            .env("DICESIM_PRESETS", dir.path().join("none"))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    // 80 000 cells: seconds of work, so the interrupt lands in the middle.
    let out = dir.path().join("part.csv");
    let o = interrupt(spawn("400x200", &out), std::time::Duration::from_millis(800));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{err}");
    let kept = std::fs::read_to_string(&out).unwrap();
    let cells = kept.lines().count() - 1;
    assert!(
        err.contains(&format!("interrupted: kept the {cells} of 80000 cells completed")),
        "{err}"
    );
    assert!(cells < 80_000, "the map finished before the interrupt");
    // The kept cells are the full map's first cells in row order, row for row.
    let full = dir.path().join("full.csv");
    let o = Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(axes)
        .args(["--res", "400x200", "--out", full.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let full = std::fs::read_to_string(&full).unwrap();
    // The header, then the cells.
    let start: Vec<&str> = full.lines().take(cells + 1).collect();
    assert!(
        kept.lines().eq(start.iter().copied()),
        "the kept cells are not the map's start"
    );
}

#[test]
fn a_loaded_die_reports_the_stopping_threshold_its_roll_applied() {
    // Loaded at corner 8, this roll settles face 5 up with a stop energy above the fair
    // die's threshold: a settled roll's stop energy is at most the threshold applied, so
    // the threshold reported must be at least it.
    let args = [
        "roll",
        "--set",
        "initial.angular_velocity=[-20,5,15]",
        "--set",
        "die.extra_corner_mass=[0,0,0,0,0,0,0,0.5]",
    ];
    let json = dicesim(&[&args[..], &["--json"]].concat());
    let v: serde_json::Value = serde_json::from_str(&stdout(&json)).unwrap();
    assert_eq!(v["status"], "settled");
    let (stop, threshold) = (
        v["stop_energy"].as_f64().unwrap(),
        v["energy_threshold"].as_f64().unwrap(),
    );
    let fair = dicesim(&["roll", "--json"]);
    let fair: serde_json::Value = serde_json::from_str(&stdout(&fair)).unwrap();
    assert!(
        stop > fair["energy_threshold"].as_f64().unwrap(),
        "the case this test is about"
    );
    assert!(
        stop <= threshold,
        "stop energy {stop} above the threshold reported {threshold}"
    );
    let text = stdout(&dicesim(&args));
    assert!(
        text.contains(&format!("(threshold {threshold:.1} erg, rigid-body)")),
        "{text}"
    );
}

#[test]
fn a_tiny_p_value_is_printed_as_the_explorer_prints_it_not_as_zero() {
    // A die loaded this heavily lands on a few faces: p is far below 10⁻⁴.
    let o = dicesim(&[
        "batch",
        "--rolls",
        "200",
        "--set",
        "die.extra_corner_mass=[0,0,0,0,0,0,0,4]",
    ]);
    let text = stdout(&o);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let counts: Vec<f64> = text
        .lines()
        .skip(2)
        .take(6)
        .map(|l| l.split_whitespace().nth(1).unwrap().parse().unwrap())
        .collect();
    // p recomputed from the printed counts: the 5-dof closed form of the χ² tail.
    let e = counts.iter().sum::<f64>() / 6.0;
    let chi2: f64 = counts.iter().map(|c| (c - e).powi(2) / e).sum();
    let p = statrs::function::erf::erfc((chi2 / 2.0).sqrt())
        + (2.0 / std::f64::consts::PI).sqrt() * (-chi2 / 2.0).exp() * (chi2.sqrt() + chi2.powf(1.5) / 3.0);
    assert!(p > 0.0 && p < 1e-4, "the case this test is about: p = {p}");
    let printed: f64 = text
        .split("p = ")
        .nth(1)
        .and_then(|r| r.lines().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{text}"));
    assert!(
        (printed - p).abs() <= 0.01 * p,
        "printed {printed}, computed {p}: {text}"
    );
}
