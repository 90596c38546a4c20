//! The simulator, the worker's state machine: the live roll, the outcome table and the jobs ordered off
//! its thread (batch, export, map), driven by commands and by "advance to simulated time
//! t". No thread, no clock and no file live here, so tests (and the thread in `mod.rs`)
//! drive it step for step.

use super::curve::CurveSetup;
use super::export_jobs::{ExportJob, Exporting, WrittenExport};
use super::job::Order;
use super::live::LiveRoll;
use super::map_jobs::MapJob;
use super::protocol::{
    BatchProgress, Command, ExportStatus, MapExport, Notice, OutcomeTable, RollKind, Snapshot,
};
use super::twin_die::{Difference, Twin};
use dicesim_experiment::RollRecord;
use dicesim_experiment::versus::VersusTable;
use dicesim_figures::animation::render::Camera;
use dicesim_figures::animation::{AnimationProgress, AnimationSpec};
use dicesim_figures::export::ExportProgress;
use dicesim_physics::{InitialCondition, ParamError, Params};
use dicesim_setup::number::human_bytes;
use dicesim_setup::output::safe_file_stem;
use dicesim_setup::preset::Preset;
use dicesim_setup::random::RandomDraws;

/// A batch to start: its rolls are random rolls numbered on from the live ones, so no
/// initial condition enters the table twice.
#[derive(Debug, Clone)]
pub(crate) struct BatchRequest {
    pub(crate) id: u64,
    pub(crate) params: Params,
    pub(crate) rolls: Vec<(u64, InitialCondition)>,
    /// While a parameter twin rolls: its setup B, each throw rolled in both (the records
    /// then come in pairs, A's then B's).
    pub(crate) versus: Option<Params>,
}

/// The parameter twin's shared throws: A's ending against B's, for one pair of setups.
#[derive(Debug, Clone)]
struct Versus {
    a: Params,
    b: Params,
    table: VersusTable,
    /// The batch filling it, if one runs.
    batch: Option<u64>,
}

/// Frames per second and pixels of the explorer's animations: a slide's size, as
/// `dicesim animate` writes by default.
const ANIMATION_FPS: u32 = 25;
const ANIMATION_SIZE: (u32, u32) = (640, 480);

/// What happened since the last snapshot and is not yet reported, besides the roll's own
/// samples.
#[derive(Debug, Default)]
struct Unreported {
    table_changed: bool,
    notice: Option<Notice>,
    /// A preset was loaded (or the simulator just started): the UI gets it whole.
    preset: Option<Box<Preset>>,
}

pub struct Simulator {
    /// The preset as loaded: the UI compares the setup with it and saves from it; random
    /// rolls are drawn from its ranges around its start.
    preset: Preset,
    /// The index of the next random roll (live or in a batch).
    next_random: u64,
    table: OutcomeTable,
    live: LiveRoll,
    batch: Order<BatchProgress, BatchRequest>,
    export: Order<ExportStatus, ExportJob>,
    map: Order<(), MapJob>,
    unreported: Unreported,
    commands_handled: u64,
    /// The parameter twin's table of shared throws (batches run while it rolls).
    versus: Option<Versus>,
    /// The running export rolls again from t = 0 a roll that changed a value mid-roll on
    /// screen: its files are not what was shown, and the notice says so.
    export_rerolled: bool,
}

/// The twin a preset's view asks for, if any (its ε was checked with the preset).
fn twin_of(preset: &Preset) -> Option<Twin> {
    preset
        .view
        .twin
        .and_then(|epsilon| Twin::new(&preset.params(), &preset.initial, Difference::Start { epsilon }).ok())
}

impl Simulator {
    /// A paused simulator at the start of the preset's roll, at the preset's speed and with
    /// its twin (a key its view leaves out means the default: 1×, no twin).
    pub fn new(preset: &Preset) -> Result<Simulator, ParamError> {
        preset.validate()?;
        let params = preset.params();
        dicesim_physics::Roll::new(&params, &preset.initial)?;
        let live = LiveRoll::new(
            params,
            preset.initial,
            twin_of(preset),
            preset.view.speed.unwrap_or_default(),
        );
        Ok(Simulator {
            preset: preset.clone(),
            next_random: 0,
            table: OutcomeTable::new(params.die.face_numbers()),
            live,
            batch: Order::default(),
            export: Order::default(),
            map: Order::default(),
            unreported: Unreported {
                preset: Some(Box::new(preset.clone())),
                ..Unreported::default()
            },
            commands_handled: 0,
            export_rerolled: false,
            versus: None,
        })
    }

    /// The live roll (the pacer plays it; tests look into it).
    pub(crate) fn live(&mut self) -> &mut LiveRoll {
        &mut self.live
    }

    /// The values the live roll is rolled with.
    #[cfg(test)]
    pub(crate) fn params(&self) -> &Params {
        self.live.params()
    }

    /// What the twin screen's predictability curve is of: the random throws `R` draws,
    /// rolled with the current values; `None` while no chaos twin rolls.
    pub(crate) fn curve_setup(&self) -> Option<CurveSetup> {
        self.live
            .twin
            .as_ref()
            .and_then(Twin::epsilon)
            .map(|_| CurveSetup {
                params: self.live.params,
                ranges: self.preset.random,
                base: self.preset.initial,
            })
    }

    /// The box's engine of the roll on screen (tests of the box read its bits).
    #[cfg(test)]
    pub(crate) fn simulation(&self) -> &dicesim_physics::Simulation {
        self.live.simulation().simulation().expect("the box")
    }

    /// The roll on screen, of any die.
    #[cfg(test)]
    pub(crate) fn roll(&self) -> &dicesim_physics::Roll {
        self.live.simulation()
    }

    /// Whether time should keep moving without a command (a playing roll, a batch or an export).
    pub(crate) fn busy(&self) -> bool {
        self.live.is_playing() || self.batch.id().is_some() || self.export.id().is_some()
    }

    /// Applies one command; returns false for [`Command::Quit`].
    pub(crate) fn handle(&mut self, command: Command) -> bool {
        self.commands_handled += 1;
        let go_on = self.apply(command);
        self.count_finished_roll();
        go_on
    }

    fn apply(&mut self, command: Command) -> bool {
        let notice = match command {
            Command::TogglePlay => {
                let play = !self.live.is_playing();
                self.live.set_playing(play);
                None
            }
            Command::SetPlaying(play) => {
                self.live.set_playing(play);
                None
            }
            Command::Step(n) => self.live.step_forward(n),
            Command::StepBack(n) => {
                self.live.step_back(n);
                None
            }
            Command::Seek(target) => {
                self.live.seek(target);
                None
            }
            Command::SeekEvent(event) => self.live.seek_event(event),
            Command::Replay => {
                self.live.replay();
                None
            }
            Command::RandomRoll => {
                let index = self.next_random;
                self.next_random += 1;
                let r = &self.preset.random;
                let initial = r.draw(&self.preset.initial, r.seed, index);
                self.live
                    .play_from(self.live.params, initial, RollKind::Random(index));
                None
            }
            Command::SetParam(param, value) => self.live.set_param(param, value).err(),
            Command::SetSpeed(speed) => {
                self.live.set_speed(speed);
                None
            }
            Command::BatchStart(rolls) => self.start_batch(rolls),
            Command::BatchCancel => self
                .batch
                .cancel()
                .map(|b| Notice::Said(format!("batch cancelled after {} of {} rolls", b.done, b.total))),
            Command::ClearTable => {
                self.table = OutcomeTable::new(self.live.params.die.face_numbers());
                self.versus = None;
                self.unreported.table_changed = true;
                None
            }
            Command::MapStart(request) => {
                let (params, initial) = (self.live.params, self.live.initial);
                self.map.place((), |id| MapJob {
                    id,
                    request,
                    params,
                    initial,
                });
                None
            }
            Command::MapCancel => {
                self.map.cancel();
                None
            }
            Command::PlaySetup(params, initial) => match params.validate().and_then(|_| initial.validate()) {
                Err(e) => Some(Notice::Said(e.to_string())),
                Ok(()) => {
                    self.live.play_from(*params, initial, RollKind::Edited);
                    None
                }
            },
            Command::SetTwin(None) => {
                self.live.set_twin(None);
                None
            }
            Command::SetTwin(Some(epsilon)) => self.set_twin(Difference::Start { epsilon }),
            Command::SetParamTwin(values) if values.is_empty() => {
                self.live.set_twin(None);
                None
            }
            Command::SetParamTwin(values) => self.set_twin(Difference::Setup { values }),
            Command::LoadPreset(preset) => Some(self.load_preset(*preset)),
            Command::Export { dir, log_scale } => self.export_roll(dir, log_scale),
            Command::ExportMap(map) => self.export_map(*map),
            Command::ExportAnimation {
                dir,
                yaw_deg,
                pitch_deg,
            } => self.export_animation(dir, Camera { yaw_deg, pitch_deg }),
            Command::ExportCancel => self
                .export
                .cancel()
                .map(|_| Notice::Said("export cancelled: nothing was written".to_string())),
            Command::Quit => return false,
        };
        if notice.is_some() {
            self.unreported.notice = notice;
        }
        true
    }

    /// A random live roll that ended enters the table (once).
    fn count_finished_roll(&mut self) {
        if let Some(r) = self.live.take_finished() {
            self.table.add(r);
            self.unreported.table_changed = true;
        }
    }

    /// Orders a batch of `rolls` random rolls, numbered on from the live ones. The same
    /// up-front check as `dicesim batch`: a range whose lowest drop could put a corner into
    /// the table is refused before any roll is drawn.
    fn start_batch(&mut self, rolls: u64) -> Option<Notice> {
        let r = &self.preset.random;
        if let Err(e) = r.check_clear_of_table(&self.live.params, &self.preset.initial) {
            return Some(Notice::Said(format!("batch not started: {e}")));
        }
        if self.batch.id().is_some() || rolls == 0 {
            return None;
        }
        let first = self.next_random;
        self.next_random += rolls;
        let list = (first..first + rolls)
            .map(|i| (i, r.draw(&self.preset.initial, r.seed, i)))
            .collect();
        let params = self.live.params;
        let versus = self
            .live
            .twin
            .as_ref()
            .and_then(|t| t.setup_b(&params, &self.live.initial));
        self.batch.place(
            BatchProgress {
                done: 0,
                total: rolls,
            },
            |id| BatchRequest {
                id,
                params,
                rolls: list,
                versus,
            },
        );
        if let Some(b) = versus {
            // Another pair of setups starts a table of its own.
            if self.versus.as_ref().is_none_or(|v| v.a != params || v.b != b) {
                self.versus = Some(Versus {
                    a: params,
                    b,
                    table: VersusTable::default(),
                    batch: None,
                });
            }
            if let Some(v) = &mut self.versus {
                v.batch = self.batch.id();
            }
        }
        None
    }

    /// Switches to `preset`: its setup, its roll from t = 0 (paused), a fresh table (the
    /// counts belonged to another setup), a twin if one rolled; a running batch is cancelled.
    fn load_preset(&mut self, preset: Preset) -> Notice {
        if let Err(e) = preset.validate() {
            return Notice::Said(format!("{}: {e}", preset.name));
        }
        self.batch.cancel();
        self.next_random = 0;
        self.table = OutcomeTable::new(preset.params().die.face_numbers());
        self.versus = None;
        self.unreported.table_changed = true;
        // A twin that rolls stays on at its ε unless the preset asks for its own: a lesson
        // turns it on, then opens presets to compare them with it.
        // A parameter twin stays on too, with B's values on the new preset's setup.
        let kept = self.live.twin.as_ref().map(|t| t.difference.clone());
        let twin = twin_of(&preset).or_else(|| {
            kept.and_then(|difference| Twin::new(&preset.params(), &preset.initial, difference).ok())
        });
        self.live.load(
            preset.params(),
            preset.initial,
            twin,
            preset.view.speed.unwrap_or_default(),
        );
        let notice = Notice::Said(format!("loaded {}", preset.name));
        self.unreported.preset = Some(Box::new(preset.clone()));
        self.preset = preset;
        notice
    }

    /// The roll on screen as a file name part: `preset-roll`, `random-roll-4`, `edited-roll`.
    fn roll_name(&self) -> String {
        match self.live.roll {
            RollKind::Preset => "preset-roll".to_string(),
            RollKind::Random(n) => format!("random-roll-{n}"),
            RollKind::Edited => "edited-roll".to_string(),
        }
    }

    /// Whether the roll on screen is not the named preset's as it stands: a value of the
    /// table or die changed (or, for the preset's own roll, of its start).
    fn changed_from_preset(&self) -> bool {
        self.live.params != self.preset.params()
            || (self.live.roll == RollKind::Preset && self.live.initial != self.preset.initial)
    }

    /// The name the roll's exports ask for (`dicesim-paper-preset-roll`, or
    /// `dicesim-paper-changed-preset-roll` for the preset with a value changed), without a
    /// number or extension.
    fn export_stem(&self) -> String {
        // The preset's name comes from a file: it names the export, it never leads elsewhere.
        let changed = if self.changed_from_preset() {
            "-changed"
        } else {
            ""
        };
        format!(
            "dicesim-{}{changed}-{}",
            safe_file_stem(&self.preset.name),
            self.roll_name()
        )
    }

    /// What the roll's exports say of it: the setup as rolled (the preset's name, the
    /// values on screen), which roll, whether it was changed from the preset.
    fn roll_provenance(&self) -> serde_json::Value {
        let mut rolled = self.preset.clone();
        let params = self.live.params;
        (rolled.die, rolled.ground, rolled.world, rolled.integrator) =
            (params.die, params.ground, params.world, params.integrator);
        rolled.initial = self.live.initial;
        let which = self.roll_name().replace('-', " ");
        dicesim_experiment::provenance::roll(&rolled, &which, self.changed_from_preset())
    }

    /// Orders the roll on screen written into `dir` (see [`Command::Export`]): the files
    /// are chosen, checked and written where the job runs (see [`ExportJob::run`]).
    fn export_roll(&mut self, dir: std::path::PathBuf, log_scale: bool) -> Option<Notice> {
        if self.export.id().is_some() {
            return Some(Notice::ExportRunning);
        }
        let roll = self.roll_name();
        let title = format!(
            "{} · {} — energy against time",
            self.preset.name,
            roll.replace('-', " ")
        );
        let (params, initial) = (self.live.params, self.live.initial);
        let stem = self.export_stem();
        let provenance = self.roll_provenance();
        let progress = ExportProgress {
            writing: false,
            steps_done: 0,
            steps_total: params.max_steps(),
            bytes: 0,
        };
        self.export_rerolled = self.live.changed_mid_roll;
        self.export.place(ExportStatus::Roll(progress), |id| ExportJob {
            id,
            dir,
            stem,
            what: Exporting::Roll {
                params,
                initial,
                title,
                log_scale,
                provenance,
            },
        });
        None
    }

    /// Orders a basin map written (see [`Command::ExportMap`]), the same way as the roll.
    fn export_map(&mut self, m: MapExport) -> Option<Notice> {
        if self.export.id().is_some() {
            return Some(Notice::ExportRunning);
        }
        let preset = self.preset.name.clone();
        self.export_rerolled = false;
        self.export
            .place(ExportStatus::Map { size: m.size }, |id| ExportJob {
                id,
                dir: m.dir,
                stem: "basin-map".to_string(),
                what: Exporting::Map {
                    map: Box::new(m.map),
                    params: m.params,
                    initial: m.initial,
                    preset,
                    layer: m.layer,
                    size: m.size,
                },
            });
        None
    }

    /// A twin differing by `difference` beside the die; both start again from t = 0, side
    /// by side. A difference the twin refuses changes nothing and says why.
    fn set_twin(&mut self, difference: Difference) -> Option<Notice> {
        match Twin::new(&self.live.params, &self.live.initial, difference) {
            Ok(twin) => {
                self.live.set_twin(Some(twin));
                None
            }
            Err(e) => Some(Notice::Said(e)),
        }
    }

    /// Orders the roll on screen written as an animation (see [`Command::ExportAnimation`]):
    /// its setup and twin as they are now, at the playback speed (1× when instant, which
    /// has no pace to film at).
    fn export_animation(&mut self, dir: std::path::PathBuf, camera: Camera) -> Option<Notice> {
        if self.export.id().is_some() {
            return Some(Notice::ExportRunning);
        }
        let spec = AnimationSpec {
            speed: self.live.speed.factor().unwrap_or(1.0),
            twin: self.live.twin.as_ref().and_then(Twin::epsilon),
            camera,
            ..AnimationSpec::new(ANIMATION_FPS, ANIMATION_SIZE)
        };
        if let Err(e) = spec.validate() {
            return Some(Notice::Said(format!("cannot export the animation: {e}")));
        }
        let progress = AnimationProgress {
            drawing: false,
            done: 0,
            total: self.live.params.max_steps(),
        };
        let stem = self.export_stem();
        let (params, initial) = (self.live.params, self.live.initial);
        let preset = self.preset.name.clone();
        self.export_rerolled = self.live.changed_mid_roll;
        self.export
            .place(ExportStatus::Animation(progress), |id| ExportJob {
                id,
                dir,
                stem,
                what: Exporting::Animation {
                    params,
                    initial,
                    preset,
                    spec,
                },
            });
        None
    }

    /// The export to start, once: whoever runs it reports back with
    /// [`Simulator::export_progress`] and [`Simulator::finish_export`].
    pub(crate) fn take_export_request(&mut self) -> Option<ExportJob> {
        self.export.take_request()
    }

    /// The export the UI waits for, if any.
    pub(crate) fn export_id(&self) -> Option<u64> {
        self.export.id()
    }

    pub(crate) fn export_progress(&mut self, id: u64, progress: ExportStatus) {
        if let Some(status) = self.export.state_of(id) {
            *status = progress;
        }
    }

    /// Export `id` has stopped: the notice says what was written, or why nothing was.
    pub(crate) fn finish_export(
        &mut self,
        id: u64,
        result: Result<WrittenExport, dicesim_experiment::Error>,
    ) {
        let Some(status) = self.export.finish(id) else {
            return;
        };
        // Said first, where a narrow status line still shows it.
        let rerolled = if self.export_rerolled && result.is_ok() {
            "re-rolled from t = 0, not the roll shown (a value changed mid-roll): "
        } else {
            ""
        };
        let words = match (status, result) {
            // Both files named first: a narrow status line cuts the sizes, not the .png.
            (_, Ok(WrittenExport::Roll(done))) => format!(
                "exported {} and .png ({}, {} rows)",
                done.trace.display(),
                human_bytes(done.bytes),
                done.rows
            ),
            (
                _,
                Ok(WrittenExport::Map {
                    png,
                    size,
                    cells,
                    complete,
                    ..
                }),
            ) => format!(
                "{}basin map saved to {} and .csv ({}×{} px, {}×{} cells)",
                if complete { "" } else { "partial " },
                png.display(),
                size.0,
                size.1,
                cells.0,
                cells.1
            ),
            (_, Ok(WrittenExport::Animation { gif, animated })) => format!(
                "animation saved to {} ({} frames, {:.2} s{})",
                gif.display(),
                animated.frames,
                animated.duration_s,
                match animated.outcome.face {
                    Some(f) => format!(", face {f}"),
                    None => String::new(),
                }
            ),
            (_, Err(dicesim_experiment::Error::Cancelled)) => {
                "export cancelled: nothing was written".to_string()
            }
            (ExportStatus::Map { .. }, Err(e)) => format!("cannot export the map: {e}"),
            (ExportStatus::Animation(_), Err(e)) => format!("cannot export the animation: {e}"),
            (ExportStatus::Roll(_), Err(e)) => e.to_string(),
        };
        self.unreported.notice = Some(Notice::Said(format!("{rerolled}{words}")));
    }

    /// Runs the requested export on this thread to its end (tests).
    #[cfg(test)]
    pub(crate) fn run_export_here(&mut self) {
        if let Some(job) = self.take_export_request() {
            let result = job.run(&std::sync::atomic::AtomicBool::new(false), &mut |_| {});
            self.finish_export(job.id, result);
        }
    }

    /// The preset as loaded.
    #[cfg(test)]
    pub(crate) fn preset(&self) -> &Preset {
        &self.preset
    }

    /// Up to `n` steps of the live roll; stops at its end. Returns the steps taken.
    pub fn advance_steps(&mut self, n: u64) -> u64 {
        let taken = self.live.advance_steps(n);
        self.count_finished_roll();
        taken
    }

    /// Plays the roll to its end at once (what "instant" shows).
    #[cfg(test)]
    pub(crate) fn run_to_end(&mut self) {
        self.live.run_to_end();
        self.count_finished_roll();
    }

    /// The batch to start, once: whoever runs it reports back with [`Simulator::add_batch_records`]
    /// and [`Simulator::finish_batch`].
    pub(crate) fn take_batch_request(&mut self) -> Option<BatchRequest> {
        self.batch.take_request()
    }

    /// The map to start, once: the worker's map runner computes it.
    pub(crate) fn take_map_request(&mut self) -> Option<MapJob> {
        self.map.take_request()
    }

    /// The map the UI waits for, if any.
    pub(crate) fn map_id(&self) -> Option<u64> {
        self.map.id()
    }

    /// Map `id` has ended (its last update is on its way to the UI).
    pub(crate) fn finish_map(&mut self, id: u64) {
        self.map.finish(id);
    }

    /// The batch the table is receiving, if any.
    pub(crate) fn batch_id(&self) -> Option<u64> {
        self.batch.id()
    }

    /// Enters finished rolls of batch `id`; rolls of a cancelled batch are dropped.
    pub(crate) fn add_batch_records(&mut self, id: u64, records: &[RollRecord]) {
        if records.is_empty() {
            return;
        }
        let Some(b) = self.batch.state_of(id) else { return };
        match self.versus.as_mut().filter(|v| v.batch == Some(id)) {
            // Pairs of one throw: A's record enters the outcome table, both the versus table.
            Some(v) => {
                b.done += records.len() as u64 / 2;
                for pair in records.chunks_exact(2) {
                    self.table.add(pair[0]);
                    v.table.add(&pair[0], &pair[1]);
                }
            }
            None => {
                b.done += records.len() as u64;
                for r in records {
                    self.table.add(*r);
                }
            }
        }
        self.unreported.table_changed = true;
    }

    /// Batch `id` has stopped (finished, cancelled or failed to start).
    pub(crate) fn finish_batch(&mut self, id: u64, result: Result<(), String>) {
        let Some(b) = self.batch.finish(id) else { return };
        // The table goes with the news, even when its last rolls came a tick earlier: a
        // snapshot that ends the batch always shows the table it ended with.
        self.unreported.table_changed = true;
        self.unreported.notice = Some(Notice::Said(match result {
            Ok(()) => format!("batch of {} rolls done", b.total),
            Err(e) => format!("batch stopped: {e}"),
        }));
    }

    /// Runs the requested batch on this thread to its end (tests and anything else that
    /// wants the table filled deterministically).
    #[cfg(test)]
    pub(crate) fn run_batch_here(&mut self) {
        if let Some(request) = self.take_batch_request() {
            self.run_request_here(request);
        }
    }

    /// Runs a batch taken with [`Simulator::take_batch_request`] on this thread to its end.
    #[cfg(test)]
    pub(crate) fn run_request_here(&mut self, request: BatchRequest) {
        use dicesim_experiment::{Rolls, run_batch};
        let rolls = Rolls::Given(&request.rolls);
        let never = std::sync::atomic::AtomicBool::new(false);
        if let Some(b) = &request.versus {
            let options = dicesim_experiment::RunOptions::default();
            let result = dicesim_experiment::versus::stream_versus(
                &request.params,
                b,
                &rolls,
                &options,
                &never,
                &mut |chunk| {
                    self.add_batch_records(request.id, chunk);
                    Ok(())
                },
            );
            self.finish_batch(request.id, result.map(|_| ()).map_err(|e| e.to_string()));
            return;
        }
        let mut seen = 0;
        let result = run_batch(&request.params, &rolls, 0, &never, &mut |records| {
            self.add_batch_records(request.id, &records[seen..]);
            seen = records.len();
        });
        self.finish_batch(request.id, result.map(|_| ()).map_err(|e| e.to_string()));
    }

    #[cfg(test)]
    pub(crate) fn phase(&self) -> super::protocol::Phase {
        self.live.phase()
    }

    /// Where the roll on screen is on its timeline.
    #[cfg(test)]
    pub(crate) fn position(&self) -> u64 {
        self.live.position()
    }

    #[cfg(test)]
    pub(crate) fn timeline(&self) -> &super::timeline::Timeline {
        self.live.timeline()
    }

    /// Everything the UI draws, plus what happened since the last snapshot.
    pub fn snapshot(&mut self) -> Snapshot {
        let unreported = std::mem::take(&mut self.unreported);
        let live = &mut self.live;
        let (history, history_reset, history_cut) = live.take_history();
        let (die, step) = live.die();
        Snapshot {
            commands_handled: self.commands_handled,
            params: live.params,
            initial: live.initial,
            roll: live.roll,
            playing: live.playing,
            speed: live.speed,
            die,
            energy: live.sim.energy(),
            ledger: live.sim.energy_ledger(),
            readings: dicesim_setup::quantity::read_all(&live.sim),
            stop_threshold: live.sim.stop_threshold(),
            time_s: live.time_s(),
            step,
            phase: live.phase(),
            history,
            history_reset,
            history_cut,
            timeline: live.timeline_snapshot(),
            batch: self.batch.state().copied(),
            table: unreported.table_changed.then(|| self.table.clone()),
            versus: self.versus.as_ref().map(|v| v.table),
            notice: unreported.notice,
            preset: unreported.preset,
            export: self.export.state().copied(),
            curve: None,
            twin: live.twin_snapshot(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::worker::Command;
    use dicesim_setup::keys::ScanKey;

    /// The notice of an export of the roll on screen into a fresh folder.
    fn exported(e: &mut Simulator) -> String {
        let dir = tempfile::tempdir().expect("temp dir");
        e.handle(Command::Export {
            dir: dir.path().to_path_buf(),
            log_scale: false,
        });
        e.run_export_here();
        let notice = e.snapshot().notice.expect("the export says how it went");
        notice.said().expect("in words").to_string()
    }

    /// The export's notice names both files before its sizes, so a status line cut at 80
    /// columns still says where the plot went.
    #[test]
    fn an_exports_notice_names_both_files_first() {
        let mut e = Simulator::new(&Preset::default()).expect("valid");
        e.run_to_end();
        let words = exported(&mut e);
        let csv = words.find(".csv and .png").expect("the two files together");
        assert!(csv < words.find('(').expect("the sizes"), "{words}");
    }

    #[test]
    fn an_export_after_a_mid_roll_change_says_it_rolled_again() {
        let mut e = Simulator::new(&Preset::default()).expect("valid");
        e.advance_steps(300);
        let friction = ScanKey::named("ground.friction").expect("a scan key");
        e.handle(Command::SetParam(friction, 0.2));
        e.handle(Command::Seek(u64::MAX));
        let words = exported(&mut e);
        assert!(words.starts_with("re-rolled from t = 0"), "{words}");
        assert!(words.contains("exported "), "{words}");
        // A roll played straight from its start is the roll the export gives: no word of it.
        e.handle(Command::Replay);
        e.run_to_end();
        let words = exported(&mut e);
        assert!(!words.contains("re-rolled"), "{words}");
        // A value that restarts the roll (not one acting mid-roll) is no mid-roll change.
        let height = ScanKey::named("initial.height").expect("a scan key");
        e.handle(Command::SetParam(height, 12.0));
        e.run_to_end();
        assert!(!exported(&mut e).contains("re-rolled"));
        // A table value changed before the roll has moved is the whole roll's: no word either,
        // and what is shown is what a fresh roll with that value gives.
        let stiffness = ScanKey::named("ground.stiffness").expect("a scan key");
        let mut e = Simulator::new(&Preset::default()).expect("valid");
        e.handle(Command::SetParam(stiffness, 550_000.0));
        e.run_to_end();
        assert!(!exported(&mut e).contains("re-rolled"));
        let mut preset = Preset::default();
        preset.ground.stiffness = 550_000.0;
        let mut fresh = Simulator::new(&preset).expect("valid");
        fresh.run_to_end();
        assert_eq!(e.phase(), fresh.phase(), "the same roll as a fresh one");
    }
}
