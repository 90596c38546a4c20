//! No command drops a `--set`: one it cannot apply (a value it draws, sets itself or never
//! reads) exits 2 before any work, naming the key and why; one it can apply changes the
//! result.

use crate::common::{dicesim_ok, dicesim_refused};

/// Runs `args` and asserts a refusal naming `key` with words from `why`.
fn refused(args: &[&str], key: &str, why: &str) {
    let dir = tempfile::tempdir().unwrap();
    let stderr = dicesim_refused(dir.path(), args);
    assert!(
        stderr.contains(&format!("--set {key}:")) && stderr.contains(why),
        "dicesim {}: {stderr}",
        args.join(" ")
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "a refused command wrote nothing"
    );
}

#[test]
fn compare_refuses_what_its_throws_and_fit_replace() {
    refused(
        &["compare", "budden", "--set", "die.half_size=1.5"],
        "die.half_size",
        "only `die.corner_radius` applies",
    );
    refused(
        &["compare", "budden", "--set", "random.random_orientation=false"],
        "random.random_orientation",
        "uniformly random orientation",
    );
    refused(
        &["compare", "budden", "--set", "initial.orientation.pitch=30"],
        "initial.orientation.pitch",
        "orientation uniformly",
    );
    refused(
        &["compare", "weldon", "--set", "initial.height=30"],
        "initial.height",
        "`random.height`",
    );
    refused(
        &["compare", "wolf-red", "--seed", "4", "--set", "random.seed=5"],
        "random.seed",
        "--seed",
    );
    refused(
        &[
            "compare",
            "wolf-red",
            "--fit",
            "ground.friction:0.5:1.2",
            "--set",
            "ground.friction=0.8",
        ],
        "ground.friction",
        "--fit",
    );
}

#[test]
fn compare_budden_applies_a_corner_radius_to_every_cuboid() {
    let dir = tempfile::tempdir().unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec![
            "compare",
            "budden",
            "--throws",
            "40",
            "--candidates",
            "20",
            "--json",
        ];
        args.extend_from_slice(extra);
        let v: serde_json::Value = serde_json::from_str(&dicesim_ok(dir.path(), &args)).unwrap();
        v["ratios"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r["simulated"]["square"].as_u64().unwrap())
            .collect::<Vec<_>>()
    };
    let sharp = run(&[]);
    let rounded = run(&["--set", "die.corner_radius=0.2"]);
    // Rounded corners roll on where sharp ones stop: the square-face counts must move.
    assert_ne!(sharp, rounded, "the corner radius did not reach the cuboids");
}

#[test]
fn batch_refuses_what_its_draws_or_its_file_replace() {
    refused(
        &["batch", "--rolls", "10", "--set", "initial.velocity.x=3"],
        "initial.velocity.x",
        "`random.velocity`",
    );
    refused(
        &["batch", "--rolls", "10", "--seed", "3", "--set", "random.seed=4"],
        "random.seed",
        "--seed",
    );
    // --versus shares batch's setup and its rule.
    refused(
        &[
            "batch",
            "--rolls",
            "10",
            "--versus",
            "ground.friction=0.5",
            "--set",
            "initial.angular_velocity=[1,2,3]",
        ],
        "initial.angular_velocity",
        "`random.angular_velocity`",
    );
}

#[test]
fn basin_predict_animate_roll_and_trace_refuse_what_they_never_read() {
    refused(
        &[
            "basin",
            "--x",
            "ground.friction:0:1",
            "--y",
            "initial.velocity.x:0:50",
            "--set",
            "initial.velocity=[5,0,0]",
        ],
        "initial.velocity",
        "its axis `initial.velocity.x`",
    );
    refused(
        &[
            "basin",
            "--x",
            "ground.friction:0:1",
            "--y",
            "ground.damping:0:0.01",
            "--set",
            "random.height=[20,30]",
        ],
        "random.height",
        "draws no random throws",
    );
    refused(
        &["predict", "--set", "initial.height=20"],
        "initial.height",
        "`random.height`",
    );
    refused(
        &[
            "predict",
            "--vary",
            "ground.friction=0.5,1",
            "--set",
            "ground.friction=0.3",
        ],
        "ground.friction",
        "--vary",
    );
    refused(
        &[
            "animate",
            "--out",
            "a.gif",
            "--set",
            "random.random_orientation=true",
        ],
        "random.random_orientation",
        "draws no random throws",
    );
    refused(
        &["roll", "--set", "random.seed=5"],
        "random.seed",
        "draws no random throws",
    );
    refused(
        &["trace", "--set", "random.seed=5"],
        "random.seed",
        "draws no random throws",
    );
}
