//! Presets from the command line: rolled by name or by default, saved, listed, shown and
//! located; errors exit 2 on stderr and write nothing. And the authors' program preset ends
//! where their reference run ended.

use crate::common;
use dicesim_experiment::roll_record;
use dicesim_physics::{FrictionLaw, Params, Simulation, StopEnergy};
use dicesim_setup::preset::{Preset, SHIPPED, Source, Store, load_file};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn shipped(name: &str) -> Preset {
    let (preset, source) = Store::new(None)
        .load(name)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(source, Source::Shipped);
    preset
}

#[test]
fn authors_program_reproduces_their_reference_run() {
    let p = shipped("authors-program");
    // Only the two documented options differ from the paper.
    let mut params = p.params();
    assert_eq!(params.ground.friction_law, FrictionLaw::WholeDieNorm);
    assert_eq!(params.integrator.stop_energy, StopEnergy::PointMasses);
    params.ground.friction_law = FrictionLaw::PerCorner;
    params.integrator.stop_energy = StopEnergy::RigidBody;
    assert_eq!(params, Params::default());

    // Its throw is reference case 14, and it ends where the authors' program ended.
    let table = common::Table::load("outcomes_original.csv");
    let row = table.rows.iter().find(|r| table.get(r, "id") == 14.0).unwrap();
    assert_eq!(p.initial, common::reference_initial(&table, row));
    let mut sim = Simulation::new(&p.params(), &p.initial).unwrap();
    let o = sim.run_to_end();
    assert_eq!(f64::from(o.face.unwrap()), table.get(row, "face"));
    assert_eq!(o.steps as f64, table.get(row, "steps"));

    // The same throw under the paper's rules lands elsewhere.
    let (paper, _) = dicesim_physics::roll(&Params::default(), &p.initial).unwrap();
    assert_ne!(paper.face, o.face);

    // Point-mass energy counts the spin three times: 2 × rotational energy more, in flight.
    let start = Simulation::new(&p.params(), &p.initial).unwrap();
    let extra = start.point_mass_energy() - start.energy().total();
    let rotational = start.energy().rotational;
    assert!(
        (extra - 2.0 * rotational).abs() < 1e-9 * rotational,
        "{extra} vs {rotational}"
    );
    // So it runs on at least as long as the rigid-body rule would.
    let mut rigid = p.params();
    rigid.integrator.stop_energy = StopEnergy::RigidBody;
    let (rigid_end, _) = dicesim_physics::roll(&rigid, &p.initial).unwrap();
    assert!(o.steps >= rigid_end.steps, "{} < {}", o.steps, rigid_end.steps);
}

fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

// ---------------------------------------------------------------------------------------------
// The command line

fn dicesim(user_dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dicesim"))
        .args(args)
        .env("DICESIM_PRESETS", user_dir)
        .output()
        .expect("the binary runs")
}

fn out(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

fn err(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

fn json(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", err(o));
    serde_json::from_str(&out(o)).unwrap()
}

#[test]
fn cli_rolls_a_shipped_preset_by_name() {
    let dir = tempdir();
    let v = json(&dicesim(
        dir.path(),
        &["roll", "--preset", "gentle-drop", "--json"],
    ));
    let p = shipped("gentle-drop");
    assert_eq!(v["preset"], "gentle-drop");
    assert_eq!(v["initial"]["height"].as_f64(), Some(p.initial.height));
    assert_eq!(v["status"], "settled");
    // The face that started up stays up.
    let start = roll_record(&p.params(), &p.initial, 0).start_face;
    assert_eq!(v["face"].as_u64(), Some(u64::from(start)));
}

#[test]
fn cli_without_a_preset_rolls_the_paper_preset() {
    let dir = tempdir();
    let default = dicesim(dir.path(), &["roll", "--json"]);
    let paper = dicesim(dir.path(), &["roll", "--json", "--preset", "paper"]);
    assert_eq!(json(&default), json(&paper));
    assert_eq!(json(&default)["preset"], "paper");
}

#[test]
fn cli_saves_a_preset_and_rolls_it() {
    let dir = tempdir();
    let o = dicesim(
        dir.path(),
        &["presets", "save", "mine", "--set", "ground.friction=0.3"],
    );
    assert!(o.status.success(), "{}", err(&o));
    let path = dir.path().join("mine.toml");
    assert_eq!(out(&o).trim(), format!("saved {}", path.display()));
    let v = json(&dicesim(dir.path(), &["roll", "--preset", "mine", "--json"]));
    assert_eq!(v["params"]["ground"]["friction"].as_f64(), Some(0.3));
    assert_eq!(v["preset"], "mine");
    // The rest is the default it started from.
    let saved = load_file(&path).unwrap();
    let expected = Preset {
        name: "mine".into(),
        // It says what it is rather than repeating the base's description.
        description: "The `paper` preset with ground.friction=0.3.".into(),
        ..Preset::default()
            .with_overrides(&["ground.friction=0.3"])
            .unwrap()
    };
    assert_eq!(saved, expected);
    let o = dicesim(
        dir.path(),
        &[
            "presets",
            "save",
            "told",
            "--description",
            "Low friction for the lab.",
            "--preset",
            "mine",
        ],
    );
    assert!(o.status.success(), "{}", err(&o));
    assert_eq!(
        load_file(&dir.path().join("told.toml")).unwrap().description,
        "Low friction for the lab."
    );

    // `--set` applies after the preset, validated the same way.
    let v = json(&dicesim(
        dir.path(),
        &[
            "roll",
            "--preset",
            "mine",
            "--set",
            "ground.friction=0.5",
            "--json",
        ],
    ));
    assert_eq!(v["params"]["ground"]["friction"].as_f64(), Some(0.5));
    let o = dicesim(
        dir.path(),
        &["roll", "--preset", "mine", "--set", "ground.friction=50"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        err(&o).contains("`ground.friction` = 50 is outside the allowed range 0 to 5"),
        "{}",
        err(&o)
    );
}

#[test]
fn cli_save_from_a_base_preset_and_force() {
    let dir = tempdir();
    let path = dir.path().join("ice2.toml");
    let save = |extra: &[&str]| {
        let mut args = vec!["presets", "save", "ice2", "--preset", "icy-table"];
        args.extend_from_slice(extra);
        dicesim(dir.path(), &args)
    };
    assert!(save(&["--set", "initial.height=5"]).status.success());
    let before = std::fs::read_to_string(&path).unwrap();
    let saved = load_file(&path).unwrap();
    assert_eq!(saved.ground.friction, shipped("icy-table").ground.friction);
    assert_eq!(saved.initial.height, 5.0);

    let o = save(&["--set", "initial.height=6"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        err(&o).contains("already exists") && err(&o).contains("--force"),
        "{}",
        err(&o)
    );
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        before,
        "nothing was written"
    );

    let o = save(&["--set", "initial.height=6", "--force"]);
    assert!(o.status.success(), "{}", err(&o));
    assert_eq!(load_file(&path).unwrap().initial.height, 6.0);
    assert_eq!(files_in(dir.path()), ["ice2.toml"]);
}

#[test]
fn cli_errors_exit_2_on_stderr_and_write_nothing() {
    let dir = tempdir();
    let o = dicesim(
        dir.path(),
        &["presets", "save", "../evil", "--set", "ground.friction=0.3"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        err(&o).starts_with("dicesim: bad preset name `../evil`"),
        "{}",
        err(&o)
    );
    assert_eq!(out(&o), "");
    let o = dicesim(
        dir.path(),
        &["presets", "save", "fine", "--set", "ground.friction=-1"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(files_in(dir.path()).is_empty(), "nothing was written");
    assert!(!dir.path().parent().unwrap().join("evil.toml").exists());

    let broken = write(
        dir.path(),
        "broken.toml",
        "[ground]\nfriction = 1.0\nfriction_law = 3\n",
    );
    let o = dicesim(dir.path(), &["roll", "--preset", "broken", "--json"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(out(&o), "");
    let prefix = format!("dicesim: {}:3:16: key `ground.friction_law`: ", broken.display());
    assert!(err(&o).starts_with(&prefix), "{}", err(&o));
    assert_eq!(err(&o).lines().count(), 1);
    let o = dicesim(dir.path(), &["trace", "--preset", "nowhere", "--steps", "2"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(err(&o).contains("no preset named `nowhere`"), "{}", err(&o));
}

#[test]
fn cli_lists_shows_and_locates_presets() {
    let dir = tempdir();
    assert!(
        dicesim(
            dir.path(),
            &["presets", "save", "mine", "--preset", "sticky-table"]
        )
        .status
        .success()
    );

    let o = dicesim(dir.path(), &["presets", "list"]);
    assert!(o.status.success(), "{}", err(&o));
    let text = out(&o);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), SHIPPED.len() + 1);
    let mine: Vec<&str> = lines[0].split_whitespace().collect();
    assert_eq!(&mine[..2], ["mine", "user"]);
    assert!(lines[0].contains("sticky"), "its description: {}", lines[0]);
    for (name, _) in SHIPPED {
        let line = lines
            .iter()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap();
        assert_eq!(line.split_whitespace().nth(1), Some("shipped"));
        let description = shipped(name).description;
        let first_words: Vec<&str> = description.split_whitespace().take(5).collect();
        assert!(line.contains(&first_words.join(" ")), "{line}");
    }

    let o = dicesim(dir.path(), &["presets", "show", "soft-table"]);
    assert!(o.status.success(), "{}", err(&o));
    assert_eq!(
        Preset::from_toml_str(&out(&o), "shown").unwrap(),
        shipped("soft-table")
    );
    assert!(out(&o).contains("stiffness = 50000.0"));
    let o = dicesim(
        dir.path(),
        &["presets", "show", "soft-table", "--set", "world.gravity=162"],
    );
    assert_eq!(
        Preset::from_toml_str(&out(&o), "shown").unwrap().world.gravity,
        162.0
    );

    let o = dicesim(dir.path(), &["presets", "path"]);
    assert_eq!(out(&o).trim(), dir.path().display().to_string());
}
