//! The explorer's exports as jobs: the simulator orders one (what, the folder, the name it
//! asks for), the export runner runs it on a thread of its own, and only there does it
//! meet the file system: free names chosen and checked together (see
//! `output::free_outputs`), each file written whole or not at all. The roll gives its
//! trace (CSV) and energy plot (PNG, written by `experiment::trace`); a basin map its
//! cells (CSV) and its picture (PNG); the roll as an animation, one GIF (written by
//! `experiment::animation`).

use super::protocol::ExportStatus;
use dicesim_experiment::{BasinMap, Error, Layer};
use dicesim_figures::animation::{Animated, AnimationSpec, write_animation};
use dicesim_figures::export::{ExportFiles, Exported, export_roll};
use dicesim_figures::plot::{ImageFormat, image_bytes, map_record};
use dicesim_physics::{InitialCondition, Params};
use dicesim_setup::output::free_outputs;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

/// What an export writes.
#[derive(Debug, Clone)]
pub(crate) enum Exporting {
    /// The roll from t = 0: its trace, and its energy plot (`log_scale`: on a
    /// logarithmic energy axis, as the screen showed it).
    Roll {
        params: Params,
        initial: InitialCondition,
        title: String,
        log_scale: bool,
        /// What the files say of the roll (`provenance::roll`).
        provenance: serde_json::Value,
    },
    /// A basin map as the screen shows it: its cells, and its picture in `layer` at
    /// `size` pixels, recording the setup every cell starts from.
    Map {
        map: Box<BasinMap>,
        params: Params,
        initial: InitialCondition,
        /// The preset's name, for the picture's record.
        preset: String,
        layer: Layer,
        size: (u32, u32),
    },
    /// The roll from t = 0 (and its twin, if `spec` has one) as an animated GIF.
    Animation {
        params: Params,
        initial: InitialCondition,
        /// The preset's name, for the headline and the file's record.
        preset: String,
        spec: AnimationSpec,
    },
}

/// An export to run off the worker's thread: what, the folder and the name it asks for.
#[derive(Debug, Clone)]
pub(crate) struct ExportJob {
    pub(crate) id: u64,
    pub(crate) dir: PathBuf,
    /// The file name without a number or extension (`dicesim-paper-preset-roll`).
    pub(crate) stem: String,
    pub(crate) what: Exporting,
}

/// What an export wrote.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum WrittenExport {
    Roll(Exported),
    Map {
        csv: PathBuf,
        png: PathBuf,
        size: (u32, u32),
        cells: (usize, usize),
        complete: bool,
    },
    Animation {
        gif: PathBuf,
        animated: Animated,
    },
}

impl ExportJob {
    /// Chooses free names in the folder, checks them and writes the files on this
    /// thread; nothing is written if a check fails, and a cancel before the last file
    /// leaves none.
    pub(crate) fn run(
        &self,
        cancel: &AtomicBool,
        progress: &mut dyn FnMut(ExportStatus),
    ) -> Result<WrittenExport, Error> {
        let dir = std::fs::canonicalize(&self.dir).unwrap_or_else(|_| self.dir.clone());
        let outputs = || free_outputs(&dir, &self.stem, ["csv", "png"]);
        match &self.what {
            Exporting::Roll {
                params,
                initial,
                title,
                log_scale,
                provenance,
            } => {
                let [csv, png] = outputs().map_err(|e| Error::Export(e.to_string()))?;
                let files = ExportFiles {
                    trace: csv,
                    plot: png,
                    log_scale: *log_scale,
                    provenance: provenance.clone(),
                };
                export_roll(params, initial, title, &files, cancel, &mut |p| {
                    progress(ExportStatus::Roll(p))
                })
                .map(WrittenExport::Roll)
            }
            Exporting::Map {
                map,
                params,
                initial,
                preset,
                layer,
                size,
            } => {
                let [csv, png] = outputs()?;
                // The caption and the PNG's text chunks say which setup every cell started from.
                let record = map_record(map, *layer, Some((preset, params, initial)));
                let picture = image_bytes(map, *layer, &record, *size, ImageFormat::Png)?;
                if cancel.load(Ordering::Relaxed) {
                    return Err(Error::Cancelled);
                }
                // Both files (and the CSV's sidecar) or none.
                let mut setup = dicesim_setup::preset::Preset {
                    name: preset.clone(),
                    initial: *initial,
                    ..Default::default()
                };
                (setup.die, setup.ground, setup.world, setup.integrator) =
                    (params.die, params.ground, params.world, params.integrator);
                let provenance = dicesim_experiment::provenance::map(&setup, map);
                let meta = dicesim_experiment::data_file::sidecar(&provenance, &map.csv_columns());
                let mut cells = csv.stage(Some(&meta))?;
                map.write_csv(&mut cells).map_err(|e| csv.failed(&e))?;
                let mut image = png.stage(None)?;
                std::io::Write::write_all(&mut image, &picture).map_err(|e| png.failed(&e))?;
                dicesim_setup::output::commit(vec![cells, image])?;
                Ok(WrittenExport::Map {
                    csv: csv.path().to_path_buf(),
                    png: png.path().to_path_buf(),
                    size: *size,
                    cells: (map.width(), map.height()),
                    complete: map.complete,
                })
            }
            Exporting::Animation {
                params,
                initial,
                preset,
                spec,
            } => {
                let [gif] = free_outputs(&dir, &self.stem, ["gif"])?;
                write_animation(preset, params, initial, spec, &gif, cancel, &mut |p| {
                    progress(ExportStatus::Animation(p))
                })
                .map(|animated| WrittenExport::Animation {
                    gif: gif.path().to_path_buf(),
                    animated,
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Command, ExportStatus, Notice, Simulator};
    use dicesim_figures::animation::gif_comments;
    use dicesim_physics::Simulation;
    use dicesim_setup::chaos::perturbed;
    use dicesim_setup::preset::{Preset, Speed};
    use std::sync::atomic::{AtomicBool, Ordering};

    fn files_in(dir: &std::path::Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .expect("a folder")
            .map(|e| e.expect("an entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    fn animation_command(dir: &std::path::Path) -> Command {
        Command::ExportAnimation {
            dir: dir.to_path_buf(),
            yaw_deg: 50.0,
            pitch_deg: 40.0,
        }
    }

    /// A roll whose table was changed from the preset's is exported under a name that says
    /// so, and its trace's sidecar names the values it rolled.
    #[test]
    fn a_changed_setup_is_named_so_and_its_trace_says_what_it_rolled() {
        let dir = tempfile::tempdir().expect("temp dir");
        let mut simulator = Simulator::new(&Preset::default()).expect("valid preset");
        let stiffness = dicesim_setup::keys::ScanKey::named("ground.stiffness").expect("a key");
        simulator.handle(Command::SetParam(stiffness, 600_000.0));
        simulator.handle(Command::Export {
            dir: dir.path().to_path_buf(),
            log_scale: false,
        });
        let job = simulator.take_export_request().expect("an export ordered");
        assert_eq!(job.stem, "dicesim-paper-changed-preset-roll");
        job.run(&AtomicBool::new(false), &mut |_| {}).expect("written");
        assert_eq!(
            files_in(dir.path()),
            [
                "dicesim-paper-changed-preset-roll.csv",
                "dicesim-paper-changed-preset-roll.csv.meta.json",
                "dicesim-paper-changed-preset-roll.png"
            ]
        );
        let meta = std::fs::read(dir.path().join("dicesim-paper-changed-preset-roll.csv.meta.json"))
            .expect("sidecar");
        let meta: serde_json::Value = serde_json::from_slice(&meta).expect("JSON");
        let provenance = &meta["provenance"];
        assert_eq!(provenance["preset"]["name"], "paper");
        assert_eq!(provenance["preset"]["ground"]["stiffness"], 600_000.0);
        assert_eq!(provenance["changed_from_preset"], true);
        assert_eq!(provenance["roll"], "preset roll");
        assert_eq!(provenance["commit"], dicesim_experiment::COMMIT);
    }

    #[test]
    fn the_animation_export_records_the_faces_the_physics_gives_die_and_twin() {
        let dir = tempfile::tempdir().expect("temp dir");
        let preset = Preset::default();
        let mut simulator = Simulator::new(&preset).expect("valid preset");
        simulator.handle(Command::SetTwin(Some(1e-9)));
        // 2×: half the frames of real time, so the test stays quick.
        simulator.handle(Command::SetSpeed(Speed::from_label("2×").expect("on the ladder")));
        simulator.handle(animation_command(dir.path()));
        assert!(
            matches!(simulator.snapshot().export, Some(ExportStatus::Animation(_))),
            "the export is shown running"
        );
        let job = simulator.take_export_request().expect("an export ordered");
        let mut drawn = 0;
        let result = job.run(&AtomicBool::new(false), &mut |p| {
            if let ExportStatus::Animation(p) = p {
                drawn = drawn.max(if p.drawing { p.done } else { 0 });
            }
        });
        simulator.finish_export(job.id, result);
        let snapshot = simulator.snapshot();
        assert_eq!(snapshot.export, None, "the export is over");
        let [name] = &files_in(dir.path())[..] else {
            panic!("one file: {:?}", files_in(dir.path()))
        };
        assert!(name.ends_with(".gif"), "{name}");
        let path = std::fs::canonicalize(dir.path()).unwrap().join(name);
        let Some(Notice::Said(words)) = snapshot.notice else {
            panic!("a notice")
        };
        assert!(
            words.starts_with(&format!("animation saved to {}", path.display())),
            "{words}"
        );

        let bytes = std::fs::read(&path).expect("written");
        let comments = gif_comments(&bytes);
        let recorded = comments
            .iter()
            .find_map(|c| c.strip_prefix("dicesim-outcome: "))
            .expect("the outcome is recorded");
        let v: serde_json::Value = serde_json::from_str(recorded).expect("JSON");
        // The roll and its twin again, straight from the physics.
        let params = preset.params();
        let die = Simulation::new(&params, &preset.initial).unwrap().run_to_end();
        let twin = Simulation::new(&params, &perturbed(&preset.initial, 1e-9))
            .unwrap()
            .run_to_end();
        assert!(die.face.is_some(), "the preset's roll settles on a face");
        assert_eq!(v["die"]["face"], serde_json::json!(die.face));
        assert_eq!(v["die"]["steps"], serde_json::json!(die.steps));
        assert_eq!(v["twin"]["face"], serde_json::json!(twin.face));
        assert_eq!(v["twin"]["epsilon"], serde_json::json!(1e-9));
        assert_eq!(v["speed"], serde_json::json!(2.0));
        assert_eq!(v["camera"]["yaw"], serde_json::json!(50.0));
        assert_eq!(v["camera"]["pitch"], serde_json::json!(40.0));
        assert_eq!(
            v["frames"].as_u64(),
            Some(drawn),
            "every frame drawn was reported"
        );
        assert!(words.contains(&format!("{} frames", drawn)), "{words}");
        assert!(
            words.ends_with(&format!(", face {})", die.face.unwrap())),
            "{words}"
        );
    }

    #[test]
    fn an_instant_explorer_films_in_real_time_and_a_removed_twin_is_not_filmed() {
        let mut simulator = Simulator::new(&Preset::default()).expect("valid preset");
        simulator.handle(Command::SetTwin(Some(1e-6)));
        simulator.handle(Command::SetTwin(None));
        simulator.handle(Command::SetSpeed(Speed::INSTANT));
        simulator.handle(animation_command(std::path::Path::new(".")));
        let job = simulator.take_export_request().expect("an export ordered");
        let super::Exporting::Animation { spec, .. } = job.what else {
            panic!("an animation: {:?}", job.what)
        };
        assert_eq!(spec.speed, 1.0, "instant has no pace: real time");
        assert_eq!(spec.twin, None);
        assert_eq!((spec.camera.yaw_deg, spec.camera.pitch_deg), (50.0, 40.0));
    }

    #[test]
    fn a_cancelled_animation_writes_nothing_and_a_second_never_overwrites_the_first() {
        let dir = tempfile::tempdir().expect("temp dir");
        let mut simulator = Simulator::new(&Preset::default()).expect("valid preset");
        simulator.handle(Command::SetSpeed(Speed::from_label("5×").expect("on the ladder")));
        simulator.handle(animation_command(dir.path()));
        let job = simulator.take_export_request().expect("an export ordered");
        // Cancelled half-way through writing the frames, as the key does from the UI.
        let cancel = AtomicBool::new(false);
        let result = job.run(&cancel, &mut |p| {
            if let ExportStatus::Animation(p) = p
                && p.drawing
                && p.done * 2 >= p.total
            {
                cancel.store(true, Ordering::Relaxed);
            }
        });
        assert!(
            matches!(result, Err(dicesim_experiment::Error::Cancelled)),
            "{result:?}"
        );
        simulator.finish_export(job.id, result);
        assert_eq!(
            simulator.snapshot().notice,
            Some(Notice::Said("export cancelled: nothing was written".to_string()))
        );
        assert_eq!(files_in(dir.path()), Vec::<String>::new(), "nothing written");

        // Asked again while one runs: refused, the running one untouched.
        simulator.handle(animation_command(dir.path()));
        simulator.handle(animation_command(dir.path()));
        assert_eq!(simulator.snapshot().notice, Some(Notice::ExportRunning));
        simulator.run_export_here();
        simulator.handle(animation_command(dir.path()));
        simulator.run_export_here();
        let names = files_in(dir.path());
        assert_eq!(names.len(), 2, "a free name each time: {names:?}");
        assert!(names.iter().all(|n| n.ends_with(".gif")), "{names:?}");
        let [a, b] = [0, 1].map(|i| std::fs::read(dir.path().join(&names[i])).unwrap());
        assert_eq!(a, b, "the same roll gives the same bytes");
    }
}
