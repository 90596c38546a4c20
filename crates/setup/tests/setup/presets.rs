//! Preset files: the repository's presets folder is the compiled-in set and the paper's is
//! the default; every kind of bad file is refused with a message that says where and what;
//! saving is whole, atomic and reversible.

use dicesim_physics::{FrictionLaw, InitialCondition, StopEnergy};
use dicesim_setup::preset::{
    CameraView, DEFAULT_NAME, FORMAT, Preset, PresetError, SHIPPED, Screen, Source, Speed, Store, ThemeName,
    View, load_file,
};
use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn shipped(name: &str) -> Preset {
    let (preset, source) = Store::new(None)
        .load(name)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(source, Source::Shipped);
    preset
}

// ---------------------------------------------------------------------------------------------
// The shipped set

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

// ---------------------------------------------------------------------------------------------
// Loading: search order and errors

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
    // The target is a folder: refused before anything is written, as any bad path is
    // (issue 49, defect 7), even with replacing allowed.
    std::fs::create_dir(dir.path().join("taken.toml")).unwrap();
    let mut p = Preset {
        name: "taken".to_string(),
        ..Preset::default()
    };
    let e = store.save(&p, true).unwrap_err();
    assert!(matches!(e, PresetError::Io { .. }), "{e:?}");
    assert!(e.to_string().contains("taken.toml: is a folder"), "{e}");
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
            assert!(matches!(e, PresetError::Write { .. }), "{e:?}");
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
            proptest::option::of((any::<bool>(), any::<bool>(), any::<bool>())),
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
            readouts: view.6.map(|(spin, lean, slid)| dicesim_setup::preset::Readouts { spin, lean, slid }),
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
// The setup as JSON (what a provenance states)

/// `to_json` is the file `to_toml` writes, key for key and value for value: for every
/// shipped preset, and for a spin given as momentum, a loaded die and a view.
#[test]
fn the_json_form_is_the_written_file_read_back() {
    let mut presets: Vec<Preset> = SHIPPED.iter().map(|(name, _)| shipped(name)).collect();
    let mut spun = shipped("paper");
    spun.initial.angular_momentum = Some([1.0, -2.5, 3.0]);
    let mut loaded = shipped("loaded-corner");
    loaded.view.theme = Some(ThemeName::Projector);
    loaded.view.twin = Some(1e-9);
    presets.extend([spun, loaded]);
    for preset in presets {
        let file: serde_json::Value = toml::from_str(&preset.to_toml()).unwrap();
        assert_eq!(preset.to_json(), file, "{}", preset.name);
    }
}

/// A spring-friction table's JSON holds exactly the keys that law reads, defaults included,
/// and none of the paper law's (issue 49, defect 4).
#[test]
fn a_spring_friction_grounds_json_holds_the_keys_its_law_reads() {
    let ground = shipped("calibrated-table-budden").to_json()["ground"].clone();
    let mut keys: Vec<&str> = ground.as_object().unwrap().keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(
        keys,
        [
            "contact",
            "friction",
            "restitution",
            "static_friction",
            "stiffness",
            "tangential_stiffness_ratio",
            "tilt",
            "tilt_direction"
        ]
    );
    let paper = shipped("paper").to_json()["ground"].clone();
    assert!(
        paper.get("damping").is_some() && paper.get("restitution").is_none(),
        "{paper}"
    );
}
