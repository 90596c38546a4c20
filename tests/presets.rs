//! Presets: every shipped preset does what its description says; every kind of bad file is
//! refused with a message that says where and what; saving is whole, atomic and reversible;
//! the command line loads, shows and saves them.

mod common;

use dicesim_experiment::roll_record;
use dicesim_physics::{FrictionLaw, InitialCondition, Outcome, Params, Simulation, Status, StopEnergy};
use dicesim_setup::preset::{
    CameraView, DEFAULT_NAME, FORMAT, Preset, PresetError, SHIPPED, Screen, Source, Speed, Store, ThemeName,
    View, load_file,
};
use dicesim_setup::random::RandomDraws;
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn shipped(name: &str) -> Preset {
    let (preset, source) = Store::new(None)
        .load(name)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(source, Source::Shipped);
    preset
}

/// A roll followed step by step.
struct Watched {
    outcome: Outcome,
    sim: Simulation,
    /// The face most nearly up, each time it changes (starting with the first).
    faces: Vec<u8>,
    /// Steps the first contact with the table lasted.
    first_contact_steps: u64,
    /// cm/s, the vertical velocity as the first contact ends.
    first_rebound_speed: f64,
    /// cm, the largest sideways (y) excursion of the centre.
    max_abs_y: f64,
}

fn watch(params: &Params, initial: &InitialCondition) -> Watched {
    let mut sim = Simulation::new(params, initial).unwrap();
    let mut faces = vec![sim.face_up()];
    let (mut contact_start, mut first_contact_steps, mut first_rebound_speed) = (None, 0, f64::NAN);
    let mut max_abs_y: f64 = 0.0;
    let outcome = loop {
        let end = sim.advance();
        let s = sim.state();
        max_abs_y = max_abs_y.max(s.position.y.abs());
        if faces.last() != Some(&sim.face_up()) {
            faces.push(sim.face_up());
        }
        match (contact_start, sim.in_contact()) {
            (None, true) => contact_start = Some(s.step),
            (Some(start), false) if first_contact_steps == 0 => {
                first_contact_steps = s.step - start;
                first_rebound_speed = s.velocity.z;
            }
            _ => {}
        }
        if let Some(o) = end {
            break o;
        }
    };
    Watched {
        outcome,
        sim,
        faces,
        first_contact_steps,
        first_rebound_speed,
        max_abs_y,
    }
}

/// A die dropped flat, without spin or sideways motion, from the preset's height.
fn flat_drop(p: &Preset) -> InitialCondition {
    InitialCondition {
        height: p.initial.height,
        ..InitialCondition::default()
    }
}

/// The preset's `[random]` rolls number 0..n.
fn random_rolls(p: &Preset, n: u64) -> Vec<InitialCondition> {
    (0..n)
        .map(|i| p.random.draw(&p.initial, p.random.seed, i))
        .collect()
}

fn mean(xs: impl IntoIterator<Item = f64>) -> f64 {
    let (sum, n) = xs.into_iter().fold((0.0, 0.0), |(s, n), x| (s + x, n + 1.0));
    sum / n
}

// ---------------------------------------------------------------------------------------------
// The shipped set

#[test]
fn every_shipped_preset_loads_rolls_and_settles() {
    for (name, _) in SHIPPED {
        let p = shipped(name);
        assert_eq!(p.name, *name);
        assert_eq!(p.format, FORMAT);
        assert!(
            p.description.split_whitespace().count() >= 30,
            "{name}: a teacher reads this aloud"
        );
        p.validate().unwrap();
        let params = p.params();
        assert!(params.stability_number() < 2.0, "{name}");
        let mut sim = Simulation::new(&params, &p.initial).unwrap();
        let outcome = sim.run_to_end();
        assert_eq!(outcome.status, Status::Settled, "{name}: {outcome:?}");
        assert!((1..=6).contains(&outcome.face.unwrap()), "{name}");
        // The die at least fell to the table (its corners reach √3 cm below the centre).
        let fall = (p.initial.height - 3f64.sqrt()).max(0.0);
        assert!(
            outcome.time_s >= (2.0 * fall / params.world.gravity).sqrt(),
            "{name}"
        );
    }
}

#[test]
fn the_repository_presets_folder_is_the_shipped_set() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    on_disk.sort();
    let mut compiled: Vec<String> = SHIPPED.iter().map(|(n, _)| n.to_string()).collect();
    compiled.sort();
    assert_eq!(
        on_disk, compiled,
        "every file in presets/ is compiled in, and only those"
    );
    for (name, _) in SHIPPED {
        assert_eq!(
            load_file(&dir.join(format!("{name}.toml"))).unwrap(),
            shipped(name)
        );
    }
}

#[test]
fn the_default_is_the_paper_preset_everywhere() {
    assert_eq!(DEFAULT_NAME, "paper");
    let paper = shipped("paper");
    assert_eq!(Preset::default(), paper);
    let (p, source) = Store::new(None).load_or_default(None).unwrap();
    assert_eq!((p, source), (paper, Source::Shipped));
}

#[test]
fn paper_has_the_papers_constants_and_a_lively_first_roll() {
    let p = shipped("paper");
    assert_eq!(p.params(), Params::default());
    let w = watch(&p.params(), &p.initial);
    let mut seen = w.faces.clone();
    seen.sort();
    seen.dedup();
    assert_eq!(
        seen,
        [1, 2, 3, 4, 5, 6],
        "it tumbles through every face: {:?}",
        w.faces
    );
    assert_ne!(
        w.outcome.face,
        Some(w.faces[0]),
        "it ends on another face than it started"
    );
}

#[test]
fn slow_motion_classroom_rolls_like_a_wheel_and_never_shows_2_or_5() {
    let p = shipped("slow-motion-classroom");
    // A spin about y alone, a push along x: the motion stays in the x–z plane.
    assert_eq!(
        [p.initial.angular_velocity[0], p.initial.angular_velocity[2]],
        [0.0, 0.0]
    );
    assert_eq!(p.initial.velocity[1], 0.0);
    let w = watch(&p.params(), &p.initial);
    assert!(w.max_abs_y < 1e-9, "it left its plane by {} cm", w.max_abs_y);
    assert!(w.faces.iter().all(|f| [1, 3, 4, 6].contains(f)), "{:?}", w.faces);
    assert!([1, 3, 4, 6].contains(&w.outcome.face.unwrap()));
    for f in [1, 3, 4, 6] {
        assert!(w.faces.contains(&f), "it rolls over fully: {:?}", w.faces);
    }
}

#[test]
fn gentle_drop_keeps_the_start_face_and_height_is_what_randomises() {
    let p = shipped("gentle-drop");
    let params = p.params();
    let first = roll_record(&params, &p.initial, 0);
    assert_ne!(p.initial.orientation, [0.0; 3], "it starts tilted");
    assert_eq!(first.outcome.face, Some(first.start_face));

    assert!(p.random.random_orientation);
    let rolls = random_rolls(&p, 40);
    let starts: Vec<u8> = rolls
        .iter()
        .map(|ic| roll_record(&params, ic, 0).start_face)
        .collect();
    assert!(
        starts.iter().any(|&f| f != starts[0]),
        "the random tilts start on different faces"
    );
    for (i, ic) in rolls.iter().enumerate() {
        let r = roll_record(&params, ic, i as u64);
        assert_eq!(r.outcome.status, Status::Settled);
        assert_eq!(r.outcome.face, Some(r.start_face), "roll {i}: {ic:?}");
    }
    // The same throws from the paper's 15 cm mostly end elsewhere.
    let kept_from_high = rolls
        .iter()
        .map(|ic| roll_record(&params, &InitialCondition { height: 15.0, ..*ic }, 0))
        .filter(|r| r.outcome.face == Some(r.start_face))
        .count();
    assert!(
        kept_from_high < rolls.len() / 2,
        "{kept_from_high} of {} kept",
        rolls.len()
    );
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

#[test]
fn soft_table_sinks_ten_times_deeper_and_impacts_last_longer() {
    let p = shipped("soft-table");
    let params = p.params();
    let paper = Params::default();
    assert_eq!(params.ground.stiffness * 10.0, paper.ground.stiffness);
    assert_eq!(params.ground.damping, paper.ground.damping);

    // At rest (stepped on well past the end of the roll) each corner sinks M·g/(4k).
    let mut w = watch(&params, &p.initial);
    for _ in 0..3000 {
        w.sim.step();
    }
    let mut depths = w.sim.state().corner_depths;
    depths.sort_by(|a, b| b.total_cmp(a));
    let depth = mean(depths[..4].iter().copied());
    assert!(
        (depth / params.resting_depth() - 1.0).abs() < 0.05,
        "{depth} cm vs {} cm",
        params.resting_depth()
    );
    assert!((params.resting_depth() / paper.resting_depth() - 10.0).abs() < 1e-9);

    // A flat drop: contact lasts about √10 ≈ 3.2 times longer, the rebound is about as fast.
    let soft = watch(&params, &flat_drop(&p));
    let hard = watch(&paper, &flat_drop(&p));
    let ratio = soft.first_contact_steps as f64 / hard.first_contact_steps as f64;
    assert!((2.5..4.0).contains(&ratio), "contact {ratio} times longer");
    let rebound = soft.first_rebound_speed / hard.first_rebound_speed;
    assert!((0.8..1.25).contains(&rebound), "rebound ratio {rebound}");
}

#[test]
fn icy_table_slides_like_a_curling_stone_where_the_paper_table_trips_it() {
    let p = shipped("icy-table");
    let icy = p.params();
    assert!((icy.ground.friction * 12.0 - Params::default().ground.friction).abs() < 1e-12);
    assert_eq!(p.initial.angular_velocity, [0.0; 3]);

    let w = watch(&icy, &p.initial);
    assert_eq!(w.faces, [4], "the same face stays up all the way");
    assert_eq!(w.outcome.face, Some(4));
    // Sliding flat it decelerates at μ·g: the distance is (v₀² − v²)/(2μg).
    let s = w.sim.state();
    let (v0, v) = (p.initial.velocity[0], s.velocity.xy().norm());
    assert!(v > 10.0, "still gliding at the end: {v} cm/s");
    let expected = (v0 * v0 - v * v) / (2.0 * icy.ground.friction * icy.world.gravity);
    let travelled = s.position.xy().norm();
    assert!(
        (travelled / expected - 1.0).abs() < 0.03,
        "{travelled} cm vs {expected} cm"
    );

    let mut grippy = icy;
    grippy.ground.friction = Params::default().ground.friction;
    let tripped = watch(&grippy, &p.initial);
    assert!(
        tripped.faces.len() >= 3,
        "the paper's friction trips it: {:?}",
        tripped.faces
    );
}

#[test]
fn sticky_table_bounces_lower_tumbles_less_and_settles_sooner() {
    let p = shipped("sticky-table");
    let sticky = p.params();
    assert_eq!(sticky.ground.damping, 4.0 * Params::default().ground.damping);
    let mut lively = sticky;
    lively.ground.damping = Params::default().ground.damping;

    let drop = flat_drop(&p);
    let (a, b) = (watch(&sticky, &drop), watch(&lively, &drop));
    assert!(a.first_rebound_speed > 0.0 && a.first_rebound_speed < 0.8 * b.first_rebound_speed);

    let throws: Vec<InitialCondition> = std::iter::once(p.initial).chain(random_rolls(&p, 11)).collect();
    let (s, l): (Vec<Watched>, Vec<Watched>) = throws
        .iter()
        .map(|ic| (watch(&sticky, ic), watch(&lively, ic)))
        .unzip();
    let steps = |ws: &[Watched]| mean(ws.iter().map(|w| w.outcome.steps as f64));
    let turns = |ws: &[Watched]| mean(ws.iter().map(|w| (w.faces.len() - 1) as f64));
    assert!(steps(&s) < steps(&l), "{} vs {} steps", steps(&s), steps(&l));
    assert!(
        turns(&s) < turns(&l),
        "{} vs {} face changes",
        turns(&s),
        turns(&l)
    );
}

#[test]
fn on_the_edge_of_stability_settles_though_many_throws_do_not() {
    let p = shipped("on-the-edge-of-stability");
    let params = p.params();
    let number = params.stability_number();
    assert!((1.4..1.6).contains(&number), "ω_rock·Δt = {number}");
    // "each step shorter than about a third of one rock": 2/ω_rock of the period 2π/ω_rock.
    assert!((params.integrator.dt / Params::default().integrator.dt - 2.4).abs() < 1e-12);
    let paper = shipped("paper");
    assert_eq!(p.initial, paper.initial, "the paper's throw");
    let mut same_but_dt = params;
    same_but_dt.integrator.dt = paper.params().integrator.dt;
    assert_eq!(same_but_dt, paper.params());

    let (o, _) = dicesim_physics::roll(&params, &p.initial).unwrap();
    assert_eq!(o.status, Status::Settled);

    let unstable: Vec<InitialCondition> = random_rolls(&p, 30)
        .into_iter()
        .filter(|ic| roll_record(&params, ic, 0).outcome.status == Status::Unstable)
        .collect();
    assert!(unstable.len() >= 2, "only {} of 30 unstable", unstable.len());
    for ic in &unstable {
        let r = roll_record(&same_but_dt, ic, 0);
        assert_eq!(r.outcome.status, Status::Settled, "{ic:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// Loading: search order and errors

/// The number just before `marker` in `text` (`"44 % of the time"` → 44).
fn number_before(text: &str, marker: &str) -> f64 {
    let at = text
        .find(marker)
        .unwrap_or_else(|| panic!("`{marker}` in {text:?}"));
    let digits: String = text[..at]
        .trim_end()
        .chars()
        .rev()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    digits
        .parse()
        .unwrap_or_else(|_| panic!("a number before `{marker}`"))
}

#[test]
fn loaded_corner_shows_the_bias_and_the_rolls_a_class_needs_that_it_states() {
    use dicesim_experiment::{Rolls, RunOptions, stream_batch};
    let p = shipped("loaded-corner");
    let params = p.params();
    assert!(params.die.is_loaded());
    let stated_share = number_before(&p.description, "% of the time together") / 100.0;
    let stated_rolls = number_before(&p.description, "rolls before");
    let rolls = Rolls::Random {
        ranges: &p.random,
        base: &p.initial,
        seed: p.random.seed,
        first: 0,
        count: 4000,
    };
    let run = stream_batch(
        &params,
        &rolls,
        &RunOptions::default(),
        &std::sync::atomic::AtomicBool::new(false),
        &mut |_| Ok(()),
    )
    .unwrap();
    let s = run.summary;
    assert_eq!(s.status.settled, 4000);
    let c = s.faces.counts();
    let heavy = (c[3] + c[4] + c[5]) as f64 / s.faces.total() as f64;
    // 4000 rolls measure a share to ±0.8 points (one standard error).
    assert!(
        (heavy - stated_share).abs() < 0.025,
        "faces 4–6 came up {heavy}, the description says {stated_share}"
    );
    // And the rolls the test needs to ±20 % (the measured bias's own error at 4000 rolls).
    let needed = s.rolls_to_detect.expect("a bias is measured") as f64;
    assert!(
        (0.7..1.4).contains(&(needed / stated_rolls)),
        "{needed} rolls needed, the description says {stated_rolls}"
    );
}

fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn user_folder_wins_over_shipped_and_paths_are_loaded_directly() {
    let dir = tempdir();
    let store = Store::new(Some(dir.path().to_path_buf()));
    let mine = write(dir.path(), "icy-table.toml", "[ground]\nfriction = 0.05\n");
    let (p, source) = store.load("icy-table").unwrap();
    assert_eq!(source, Source::User(mine.clone()));
    assert_eq!(p.ground.friction, 0.05);
    assert_eq!(p.name, "icy-table", "a file without a name takes its stem");

    let elsewhere = tempdir();
    let lab = write(
        elsewhere.path(),
        "lab.toml",
        "name = \"Lab 3\"\n[world]\ngravity = 162.0\n",
    );
    let (p, source) = store.load(lab.to_str().unwrap()).unwrap();
    assert_eq!((p.world.gravity, p.name.as_str()), (162.0, "Lab 3"));
    assert_eq!(source, Source::Path(lab));

    let listed = store.list();
    let icy: Vec<_> = listed.iter().filter(|e| e.name == "icy-table").collect();
    assert_eq!(icy.len(), 1, "the user's copy hides the shipped one");
    assert_eq!(icy[0].source, Source::User(mine));
    assert_eq!(listed.len(), SHIPPED.len());
}

#[test]
fn list_skips_temporary_files_and_shows_broken_presets_with_their_error() {
    let dir = tempdir();
    write(dir.path(), ".tmpA1b2C3", "half a preset");
    write(dir.path(), "notes.txt", "not a preset");
    write(dir.path(), "broken.toml", "[ground\n");
    write(dir.path(), "good.toml", "description = \"ok\"\n");
    let listed = Store::new(Some(dir.path().to_path_buf())).list();
    let names: Vec<&str> = listed.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(&names[..2], ["broken", "good"]);
    assert_eq!(names.len(), 2 + SHIPPED.len());
    let e = listed[0].preset.as_ref().unwrap_err().to_string();
    assert!(e.contains("broken.toml:1:"), "{e}");
}

/// Loads `text` as a user preset named `p`; returns the error and the file's path.
fn load_error(text: &str) -> (String, String) {
    let dir = tempdir();
    let path = write(dir.path(), "p.toml", text);
    let e = Store::new(Some(dir.path().to_path_buf())).load("p").unwrap_err();
    (e.to_string(), path.display().to_string())
}

#[test]
fn file_errors_name_file_line_column_key_and_range() {
    let (e, file) = load_error("name = \"x\"\n[ground\n");
    assert!(e.starts_with(&format!("{file}:2:")), "{e}");
    assert!(e.contains("unclosed table"), "{e}");

    let (e, file) = load_error("[die]\nhalf_size = 1.0\ncorner_mas = 2.0\n");
    assert!(
        e.starts_with(&format!(
            "{file}:3:1: key `die.corner_mas`: unknown field `corner_mas`"
        )),
        "{e}"
    );

    let (e, file) = load_error("[integrator]\ndt = \"fast\"\n");
    assert_eq!(
        e,
        format!("{file}:2:6: key `integrator.dt`: invalid type: string \"fast\", expected f64")
    );

    let (e, file) = load_error("[world]\n\ngravity = 98000.0\n");
    assert_eq!(
        e,
        format!("{file}:3:1: `world.gravity` = 98000 is outside the allowed range 10 to 10000 cm/s²")
    );

    let (e, file) = load_error("format = 7\n[new_section]\n");
    assert!(
        e.starts_with(&format!("{file}:1:1: preset format 7 is newer")),
        "{e}"
    );
    assert!(e.contains(&format!("reads format {FORMAT}")), "{e}");
}

#[test]
fn bad_names_are_refused_without_touching_the_disk() {
    let dir = tempdir();
    let store = Store::new(Some(dir.path().join("presets")));
    for name in ["..", "../escape", "a b", "x.y", ""] {
        let p = Preset {
            name: name.to_string(),
            ..Preset::default()
        };
        let e = store.save(&p, true).unwrap_err();
        assert!(matches!(e, PresetError::BadName { .. }), "{name}: {e:?}");
        assert!(
            e.to_string().starts_with(&format!("bad preset name `{name}`")),
            "{e}"
        );
    }
    assert!(matches!(store.load("a b"), Err(PresetError::BadName { .. })));
    assert!(!dir.path().join("presets").exists(), "nothing was created");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn an_unknown_name_lists_what_there_is() {
    let e = Store::new(None).load("gentle-dorp").unwrap_err().to_string();
    assert!(e.starts_with("no preset named `gentle-dorp`"), "{e}");
    assert!(e.contains("gentle-drop"), "{e}");
}

// ---------------------------------------------------------------------------------------------
// Saving

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn save_writes_the_whole_file_atomically_and_never_clobbers_unasked() {
    let dir = tempdir();
    let folder = dir.path().join("nested").join("presets");
    let store = Store::new(Some(folder.clone()));
    let mut p = shipped("gentle-drop")
        .with_overrides(&["ground.friction=0.7"])
        .unwrap();
    p.name = "mine".to_string();
    let path = store.save(&p, false).unwrap();
    assert_eq!(path, folder.join("mine.toml"));
    assert_eq!(files_in(&folder), ["mine.toml"], "no temporary file left behind");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o644);
    }
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text, p.to_toml());
    assert!(text.contains("stiffness = 500000.0") && text.contains("# dyn/cm per corner (k)"));
    assert!(store.exists("mine"));
    assert_eq!(
        store.load("mine").unwrap(),
        (p.clone(), Source::User(path.clone()))
    );

    // Again, unconfirmed: refused, the old file intact.
    let mut q = p.clone();
    q.ground.friction = 0.1;
    let e = store.save(&q, false).unwrap_err();
    assert!(matches!(e, PresetError::Exists { .. }), "{e:?}");
    assert!(e.to_string().contains("already exists") && e.to_string().contains("mine.toml"));
    assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
    assert_eq!(files_in(&folder), ["mine.toml"]);

    // An invalid preset is refused before anything is written.
    let mut bad = q.clone();
    bad.ground.friction = 9.0;
    assert!(matches!(store.save(&bad, true), Err(PresetError::OutOfRange(_))));
    assert_eq!(std::fs::read_to_string(&path).unwrap(), text);

    // Confirmed: replaced.
    store.save(&q, true).unwrap();
    assert_eq!(store.load("mine").unwrap().0.ground.friction, 0.1);
    assert_eq!(files_in(&folder), ["mine.toml"]);
}

#[test]
fn a_failed_write_leaves_the_old_state_and_no_temporary_file() {
    let dir = tempdir();
    let store = Store::new(Some(dir.path().to_path_buf()));
    // The rename itself fails: the target is a folder.
    std::fs::create_dir(dir.path().join("taken.toml")).unwrap();
    let mut p = Preset {
        name: "taken".to_string(),
        ..Preset::default()
    };
    let e = store.save(&p, true).unwrap_err();
    assert!(matches!(e, PresetError::Io { .. }), "{e:?}");
    assert!(e.to_string().contains("taken.toml"), "{e}");
    assert_eq!(
        files_in(dir.path()),
        ["taken.toml"],
        "the temporary file was removed"
    );
    assert!(dir.path().join("taken.toml").is_dir());

    // A read-only folder: the temporary file cannot even be created.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        p.name = "kept".to_string();
        let old = store.save(&p, false).unwrap();
        let text = std::fs::read_to_string(&old).unwrap();
        std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o555)).unwrap();
        let privileged = std::fs::write(dir.path().join("probe"), "").is_ok();
        if privileged {
            // Root ignores the mode bits; the folder-as-target case above still holds.
            std::fs::remove_file(dir.path().join("probe")).unwrap();
        } else {
            let mut q = p.clone();
            q.ground.friction = 0.2;
            let e = store.save(&q, true).unwrap_err();
            assert!(matches!(e, PresetError::Io { .. }), "{e:?}");
            assert_eq!(
                std::fs::read_to_string(&old).unwrap(),
                text,
                "the old file is intact"
            );
            assert_eq!(files_in(dir.path()), ["kept.toml", "taken.toml"]);
        }
        std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
    }
}

fn limits(l: dicesim_physics::Limits) -> std::ops::RangeInclusive<f64> {
    l.min..=l.max
}

fn vec3(l: dicesim_physics::Limits) -> impl Strategy<Value = [f64; 3]> {
    [limits(l), limits(l), limits(l)]
}

fn range2(l: dicesim_physics::Limits) -> impl Strategy<Value = [f64; 2]> {
    (limits(l), limits(l)).prop_map(|(a, b)| [a.min(b), a.max(b)])
}

prop_compose! {
    fn any_preset()(
        name in "[A-Za-z0-9_-]{1,24}",
        description in "[ -~\n\t\"\\\\é°·]{0,300}",
        die in (limits(dicesim_setup::registry::HALF_SIZES.limits), limits(dicesim_setup::registry::CORNER_MASS.limits)),
        ground in (
            limits(dicesim_setup::registry::STIFFNESS.limits),
            limits(dicesim_setup::registry::DAMPING.limits),
            limits(dicesim_setup::registry::FRICTION.limits),
            any::<bool>(),
        ),
        gravity in limits(dicesim_setup::registry::GRAVITY.limits),
        integrator in (
            limits(dicesim_setup::registry::DT.limits),
            limits(dicesim_setup::registry::STOP_ENERGY_FRACTION.limits),
            limits(dicesim_setup::registry::MAX_TIME.limits),
            any::<bool>(),
        ),
        height in limits(dicesim_setup::registry::HEIGHT.limits),
        velocity in vec3(dicesim_setup::registry::VELOCITY.limits),
        spin in prop_oneof![
            vec3(dicesim_setup::registry::ANGULAR_VELOCITY.limits).prop_map(|w| (w, None)),
            vec3(dicesim_setup::registry::ANGULAR_MOMENTUM.limits).prop_map(|l| ([0.0; 3], Some(l))),
        ],
        orientation in vec3(dicesim_setup::registry::ORIENTATION.limits),
        random in (
            0..=i64::MAX as u64,
            range2(dicesim_setup::registry::HEIGHT.limits),
            range2(dicesim_setup::registry::VELOCITY.limits),
            range2(dicesim_setup::registry::ANGULAR_VELOCITY.limits),
            any::<bool>(),
        ),
        view in (
            prop_oneof![Just(None), Just(Some(Speed::SLOWEST)), Just(Some(Speed::INSTANT)), Just(Some(Speed::default()))],
            proptest::option::of((-360.0..=360.0f64, -10.0..=89.0f64, -8..=8i32)),
            proptest::option::of(prop_oneof![Just(ThemeName::Dark), Just(ThemeName::Light), Just(ThemeName::Projector)]),
            proptest::option::of(any::<bool>()),
            proptest::option::of(1e-15..=0.1f64),
            proptest::option::of(prop_oneof![Just(Screen::Die), Just(Screen::Map)]),
        ),
    ) -> Preset {
        let mut p = Preset {
            name,
            description,
            ..Preset::default()
        };
        (p.die.half_sizes, p.die.corner_mass) = ([die.0; 3], die.1);
        (p.ground.stiffness, p.ground.damping, p.ground.friction) = (ground.0, ground.1, ground.2);
        p.ground.friction_law = if ground.3 { FrictionLaw::WholeDieNorm } else { FrictionLaw::PerCorner };
        p.world.gravity = gravity;
        (p.integrator.dt, p.integrator.stop_energy_fraction, p.integrator.max_time) =
            (integrator.0, integrator.1, integrator.2);
        p.integrator.stop_energy = if integrator.3 { StopEnergy::PointMasses } else { StopEnergy::RigidBody };
        p.initial = InitialCondition {
            height,
            velocity,
            angular_velocity: spin.0,
            angular_momentum: spin.1,
            orientation,
        };
        // A start inside the table is refused: lift it clear, as a valid preset must be.
        let lowest = -p.initial.lowest_corner_offset(&p.params()) - p.params().resting_depth();
        p.initial.height = p.initial.height.max(lowest);
        p.random.seed = random.0;
        (p.random.height, p.random.velocity, p.random.angular_velocity) = (random.1, random.2, random.3);
        p.random.random_orientation = random.4;
        p.view = View {
            speed: view.0,
            camera: view.1.map(|(yaw, pitch, zoom)| CameraView { yaw, pitch, zoom }),
            theme: view.2,
            arrows: view.3,
            twin: view.4,
            screen: view.5,
        };
        p
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn saving_then_loading_gives_the_same_preset(p in any_preset()) {
        let dir = tempdir();
        let store = Store::new(Some(dir.path().to_path_buf()));
        let path = store.save(&p, false).unwrap();
        let (loaded, source) = store.load(&p.name).unwrap();
        prop_assert_eq!(&loaded, &p);
        prop_assert_eq!(source, Source::User(path));
        prop_assert_eq!(Preset::from_toml_str(&p.to_toml(), "again").unwrap(), p);
    }
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
