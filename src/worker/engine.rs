//! The worker's state machine: one live roll, the outcome table and a batch, driven by
//! commands and by "advance to simulated time t". No thread and no clock live here, so tests
//! (and the thread in `mod.rs`) drive it step for step.

use super::curve::CurveSetup;
use super::export::ExportJob;
use super::map::{MapJob, MapOrder};
use super::timeline::{Keyframe, Timeline};
use super::twin::Twin;
use super::{
    BatchProgress, Command, DieState, EnergySample, Notice, OutcomeTable, Phase, RollKind, Snapshot,
    TimelineSnapshot,
};
use crate::experiment::registry::Role;
use crate::experiment::trace::{ExportProgress, Exported, human_bytes};
use crate::experiment::{RandomRanges, RollRecord, ScanKey};
use crate::output::safe_file_stem;
use crate::physics::{InitialCondition, ParamError, Params, Simulation, face_most_nearly_up};
use crate::preset::{Preset, Speed};

/// At most this many energy samples per roll: longer rolls keep each term's peak over a
/// stride of steps, so impact spikes survive the thinning.
const HISTORY_SAMPLES: u64 = 40_000;

/// The batch whose rolls the table is receiving.
#[derive(Debug, Clone, Copy)]
struct BatchState {
    id: u64,
    done: u64,
    total: u64,
}

/// A batch to start: its rolls are random rolls numbered on from the live ones, so no
/// initial condition enters the table twice.
#[derive(Debug, Clone)]
pub struct BatchRequest {
    pub(crate) id: u64,
    pub(crate) params: Params,
    pub(crate) rolls: Vec<(u64, InitialCondition)>,
}

/// The export the UI is waiting for.
#[derive(Debug, Clone, Copy)]
struct ExportState {
    id: u64,
    progress: ExportProgress,
}

/// Output gathered since the last snapshot.
#[derive(Debug, Default)]
struct Pending {
    history: Vec<EnergySample>,
    history_reset: bool,
    /// s: samples after this time belong to a future that changed (a table value mid-roll).
    history_cut: Option<f64>,
    table_changed: bool,
    notice: Option<Notice>,
    /// A preset was loaded (or the engine just started): the UI gets it whole.
    preset: Option<Box<Preset>>,
}

pub struct Engine {
    /// The preset as loaded (the UI compares the setup with it and saves from it).
    preset: Preset,
    /// The preset's initial condition: random draws take their orientation from it.
    base_initial: InitialCondition,
    random: RandomRanges,
    params: Params,
    initial: InitialCondition,
    sim: Simulation,
    /// Steps of Δt since the roll started: where on its timeline the roll on screen is.
    position: u64,
    timeline: Timeline,
    roll: RollKind,
    start_face: u8,
    /// Whether the live random roll has already entered the table (a replay must not count twice).
    counted: bool,
    playing: bool,
    speed: Speed,
    /// Whether a corner has touched the ground since the roll started.
    touched: bool,
    next_random: u64,
    table: OutcomeTable,
    batch: Option<BatchState>,
    batch_request: Option<BatchRequest>,
    batches_started: u64,
    /// The newest map order not yet taken by the map thread.
    map_order: Option<MapOrder>,
    stride: u64,
    peak: Option<EnergySample>,
    peak_steps: u64,
    pending: Pending,
    commands_handled: u64,
    /// Changes whenever the mapping from wall time to simulated time must restart.
    pacing_epoch: u64,
    /// The chaos twin, if one rolls beside the die.
    twin: Option<Twin>,
    export: Option<ExportState>,
    export_request: Option<ExportJob>,
    exports_started: u64,
}

impl Engine {
    /// A paused engine at the start of the preset's roll.
    pub fn new(preset: &Preset) -> Result<Engine, ParamError> {
        preset.validate()?;
        let params = preset.params();
        let sim = Simulation::new(&params, &preset.initial)?;
        let timeline = Timeline::new(
            1,
            Keyframe {
                position: 0,
                sim: sim.clone(),
                twin: None,
                touched: false,
            },
        );
        let mut engine = Engine {
            preset: preset.clone(),
            base_initial: preset.initial,
            random: preset.random,
            params,
            initial: preset.initial,
            sim,
            position: 0,
            timeline,
            roll: RollKind::Preset,
            start_face: 0,
            counted: false,
            playing: false,
            speed: Speed::default(),
            touched: false,
            next_random: 0,
            table: OutcomeTable::default(),
            batch: None,
            batch_request: None,
            batches_started: 0,
            map_order: None,
            stride: 1,
            peak: None,
            peak_steps: 0,
            pending: Pending::default(),
            commands_handled: 0,
            pacing_epoch: 0,
            twin: None,
            export: None,
            export_request: None,
            exports_started: 0,
        };
        engine.apply_view(preset);
        engine.restart(RollKind::Preset);
        engine.pending.preset = Some(Box::new(preset.clone()));
        Ok(engine)
    }

    /// The parts of a preset's `[view]` the worker owns: the playback speed and the chaos
    /// twin (rolled from the next restart). A preset opens the same way every time, so a
    /// key the view leaves out means the default: 1×, no twin.
    fn apply_view(&mut self, preset: &Preset) {
        self.speed = preset.view.speed.unwrap_or_default();
        // ε was checked with the preset; the twin is placed by `restart`.
        self.twin = preset
            .view
            .twin
            .and_then(|epsilon| Twin::new(&preset.params(), &preset.initial, epsilon).ok());
    }

    pub fn params(&self) -> &Params {
        &self.params
    }

    /// What the twin screen's predictability curve is of: the random throws `R` draws,
    /// rolled with the current values; `None` while no twin rolls.
    pub(crate) fn curve_setup(&self) -> Option<CurveSetup> {
        self.twin.as_ref().map(|_| CurveSetup {
            params: self.params,
            ranges: self.random,
            base: self.base_initial,
        })
    }

    #[cfg(test)]
    pub(crate) fn simulation(&self) -> &Simulation {
        &self.sim
    }

    /// s, simulated: how far the roll has got (the later of the die and its twin, since
    /// the one still rolling keeps the clock going).
    pub(crate) fn time_s(&self) -> f64 {
        let die = self.sim.state().time_s;
        self.twin.as_ref().map_or(die, |t| die.max(t.sim.state().time_s))
    }

    /// Whether the roll on screen has ended: the die's, and its twin's if there is one.
    pub(crate) fn roll_over(&self) -> bool {
        self.sim.outcome().is_some() && self.twin.as_ref().is_none_or(Twin::ended)
    }

    pub(crate) fn is_playing(&self) -> bool {
        self.playing
    }

    pub(crate) fn speed(&self) -> Speed {
        self.speed
    }

    /// Whether time should keep moving without a command (a playing roll or a batch).
    pub(crate) fn busy(&self) -> bool {
        self.playing || self.batch.is_some() || self.export.is_some()
    }

    pub(crate) fn pacing_epoch(&self) -> u64 {
        self.pacing_epoch
    }

    /// Applies one command; returns false for [`Command::Quit`].
    pub(crate) fn handle(&mut self, command: Command) -> bool {
        self.commands_handled += 1;
        match command {
            Command::TogglePlay => {
                let play = !self.playing;
                self.set_playing(play);
            }
            Command::SetPlaying(play) => self.set_playing(play),
            Command::Step(n) => {
                self.playing = false;
                self.pacing_epoch += 1;
                if self.roll_over() {
                    self.pending.notice = Some(Notice::RollEnded);
                } else {
                    self.advance_steps(n);
                }
            }
            Command::StepBack(n) => self.seek(self.position.saturating_sub(n)),
            Command::Seek(target) => self.seek(target),
            Command::Replay => {
                self.restart(self.roll);
                self.playing = true;
            }
            Command::RandomRoll => {
                let index = self.next_random;
                self.next_random += 1;
                self.initial = self.random.draw(&self.base_initial, self.random.seed, index);
                self.counted = false;
                self.restart(RollKind::Random(index));
                self.playing = true;
            }
            Command::SetParam(param, value) => self.set_param(param, value),
            Command::SetSpeed(speed) => {
                self.speed = speed;
                self.pacing_epoch += 1;
            }
            Command::BatchStart(rolls) => {
                // The same up-front check as `dicesim batch`: a range whose lowest drop
                // could put a corner into the table is refused before any roll is drawn.
                if let Err(e) = self.random.check_clear_of_table(&self.params, &self.base_initial) {
                    self.pending.notice = Some(Notice::Said(format!("batch not started: {e}")));
                } else if self.batch.is_none() && rolls > 0 {
                    let id = self.batches_started;
                    self.batches_started += 1;
                    let first = self.next_random;
                    self.next_random += rolls;
                    let rolls_list = (first..first + rolls)
                        .map(|i| (i, self.random.draw(&self.base_initial, self.random.seed, i)))
                        .collect();
                    self.batch = Some(BatchState {
                        id,
                        done: 0,
                        total: rolls,
                    });
                    self.batch_request = Some(BatchRequest {
                        id,
                        params: self.params,
                        rolls: rolls_list,
                    });
                }
            }
            Command::BatchCancel => {
                self.batch_request = None;
                if let Some(b) = self.batch.take() {
                    self.pending.notice = Some(Notice::Said(format!(
                        "batch cancelled after {} of {} rolls",
                        b.done, b.total
                    )));
                }
            }
            Command::ClearTable => {
                self.table = OutcomeTable::default();
                self.pending.table_changed = true;
            }
            Command::MapStart(request) => {
                self.map_order = Some(MapOrder::Start(Box::new(MapJob {
                    request,
                    params: self.params,
                    initial: self.initial,
                })))
            }
            Command::MapCancel => self.map_order = Some(MapOrder::Cancel),
            Command::PlaySetup(params, initial) => {
                if let Err(e) = params.validate().and_then(|_| initial.validate()) {
                    self.pending.notice = Some(Notice::Said(e.to_string()));
                } else {
                    (self.params, self.initial) = (*params, initial);
                    self.restart(RollKind::Edited);
                    self.playing = true;
                }
            }
            Command::SetTwin(None) => self.twin = None,
            Command::SetTwin(Some(epsilon)) => match Twin::new(&self.params, &self.initial, epsilon) {
                Ok(twin) => {
                    self.twin = Some(twin);
                    // Both dice start again from t = 0, side by side.
                    self.restart(self.roll);
                    self.playing = true;
                }
                Err(e) => self.pending.notice = Some(Notice::Said(e.to_string())),
            },
            Command::LoadPreset(preset) => self.load_preset(*preset),
            Command::Export { dir, log_scale } => self.export(&dir, log_scale),
            Command::ExportCancel => {
                self.export_request = None;
                if self.export.take().is_some() {
                    self.pending.notice =
                        Some(Notice::Said("export cancelled: nothing was written".to_string()));
                }
            }
            Command::Quit => return false,
        }
        true
    }

    /// Switches to `preset`: its setup, its roll from t = 0 (paused), a fresh table (the
    /// counts belonged to another setup); a running batch is cancelled.
    fn load_preset(&mut self, preset: Preset) {
        if let Err(e) = preset.validate() {
            self.pending.notice = Some(Notice::Said(format!("{}: {e}", preset.name)));
            return;
        }
        self.batch_request = None;
        self.batch = None;
        self.base_initial = preset.initial;
        self.random = preset.random;
        self.params = preset.params();
        self.initial = preset.initial;
        self.next_random = 0;
        self.table = OutcomeTable::default();
        self.pending.table_changed = true;
        self.playing = false;
        self.apply_view(&preset);
        self.restart(RollKind::Preset);
        self.pending.notice = Some(Notice::Said(format!("loaded {}", preset.name)));
        self.pending.preset = Some(Box::new(preset.clone()));
        self.preset = preset;
    }

    /// Asks for the roll on screen to be written into `dir` (see [`Command::Export`]): the
    /// files are chosen, checked and written on the export thread (see [`ExportJob::run`]).
    fn export(&mut self, dir: &std::path::Path, log_scale: bool) {
        if self.export.is_some() {
            self.pending.notice = Some(Notice::ExportRunning);
            return;
        }
        let roll = match self.roll {
            RollKind::Preset => "preset-roll".to_string(),
            RollKind::Random(n) => format!("random-roll-{n}"),
            RollKind::Edited => "edited-roll".to_string(),
        };
        let title = format!(
            "{} · {} — energy against time",
            self.preset.name,
            roll.replace('-', " ")
        );
        let id = self.exports_started;
        self.exports_started += 1;
        self.export = Some(ExportState {
            id,
            progress: ExportProgress {
                writing: false,
                steps_done: 0,
                steps_total: self.params.max_steps(),
                bytes: 0,
            },
        });
        self.export_request = Some(ExportJob {
            id,
            params: self.params,
            initial: self.initial,
            title,
            dir: dir.to_path_buf(),
            // The preset's name comes from a file: it names the export, it never leads elsewhere.
            stem: format!("dicesim-{}-{roll}", safe_file_stem(&self.preset.name)),
            log_scale,
        });
    }

    /// The export to start, once: whoever runs it reports back with
    /// [`Engine::export_progress`] and [`Engine::finish_export`].
    pub(crate) fn take_export_request(&mut self) -> Option<ExportJob> {
        self.export_request.take()
    }

    /// The export the UI waits for, if any.
    pub(crate) fn export_id(&self) -> Option<u64> {
        self.export.map(|e| e.id)
    }

    pub(crate) fn export_progress(&mut self, id: u64, progress: ExportProgress) {
        if let Some(e) = &mut self.export
            && e.id == id
        {
            e.progress = progress;
        }
    }

    /// Export `id` has stopped: the notice says what was written, or why nothing was.
    pub(crate) fn finish_export(&mut self, id: u64, result: Result<Exported, crate::experiment::Error>) {
        if self.export_id() != Some(id) {
            return;
        }
        self.export = None;
        self.pending.notice = Some(Notice::Said(match result {
            Ok(done) => format!(
                "exported {} ({}, {} rows) and .png",
                done.trace.display(),
                human_bytes(done.bytes),
                done.rows
            ),
            Err(crate::experiment::Error::Cancelled) => "export cancelled: nothing was written".to_string(),
            Err(e) => e.to_string(),
        }));
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

    fn set_playing(&mut self, play: bool) {
        if play && self.roll_over() {
            // Resuming a finished roll means watching it again.
            self.restart(self.roll);
        }
        self.playing = play;
        self.pacing_epoch += 1;
    }

    fn set_param(&mut self, key: &ScanKey, value: f64) {
        let (mut params, mut initial) = (self.params, self.initial);
        if let Err(e) = key.set_checked(&mut params, &mut initial, value) {
            self.pending.notice = Some(Notice::Said(e.to_string()));
            return;
        }
        self.params = params;
        self.initial = initial;
        if key.spec.acts_mid_roll && self.sim.outcome().is_none() {
            if let Err(e) = self.sim.set_ground(params.ground) {
                self.pending.notice = Some(Notice::Said(e.to_string()));
            }
            // The twin feels the same table, so only ε tells the two apart.
            if let Some(twin) = &mut self.twin {
                let _ = twin.sim.set_ground(params.ground);
            }
            // From here on the roll is another one: its computed future is forgotten.
            if !self.timeline.at_frontier(self.position) {
                self.pending.history_cut = Some(self.sim.state().time_s);
            }
            self.peak = None;
            self.peak_steps = 0;
            let impact = self.impact_now();
            self.timeline.diverge(self.keyframe(), impact);
        } else {
            // A new initial condition is a roll of its own; other values re-run the same one.
            let kind = if key.spec.role == Role::Initial {
                RollKind::Edited
            } else {
                self.roll
            };
            self.restart(kind);
        }
    }

    /// Places the die at the current initial condition; the history starts again.
    fn restart(&mut self, kind: RollKind) {
        self.roll = kind;
        self.sim = Simulation::new_unchecked(&self.params, &self.initial);
        self.start_face = face_most_nearly_up(&self.sim.state().corner_offsets);
        self.touched = self.sim.in_contact();
        self.stride = self.params.max_steps().div_ceil(HISTORY_SAMPLES).max(1);
        self.peak = None;
        self.peak_steps = 0;
        self.pending.history.clear();
        self.pending.history_reset = true;
        self.pending.history.push(self.sample());
        if let Some(epsilon) = self.twin.as_ref().map(|t| t.epsilon) {
            // ε was checked when the twin was made.
            self.twin = Twin::new(&self.params, &self.initial, epsilon).ok();
            if let Some(twin) = &mut self.twin {
                twin.sample(&self.sim);
            }
        }
        self.position = 0;
        self.timeline = Timeline::new(self.params.max_steps(), self.keyframe());
        self.pacing_epoch += 1;
    }

    /// The roll's state now, as a keyframe.
    fn keyframe(&self) -> Keyframe {
        Keyframe {
            position: self.position,
            sim: self.sim.clone(),
            twin: self.twin.as_ref().map(|t| t.sim.clone()),
            touched: self.touched,
        }
    }

    /// Carries on from `k` (a twin removed since is not brought back).
    fn restore(&mut self, k: &Keyframe) {
        self.position = k.position;
        self.sim = k.sim.clone();
        self.touched = k.touched;
        if let (Some(twin), Some(sim)) = (&mut self.twin, &k.twin) {
            twin.sim = sim.clone();
        }
    }

    /// Pauses at step `target` of the roll (at most its end): from the nearest keyframe,
    /// or by computing on if the roll has not got there yet.
    fn seek(&mut self, target: u64) {
        self.playing = false;
        self.pacing_epoch += 1;
        let target = if self.timeline.ended {
            target.min(self.timeline.furthest)
        } else {
            target
        };
        let from = self.timeline.before(target.min(self.timeline.furthest));
        if target < self.position || from.position > self.position {
            let from = from.clone();
            self.restore(&from);
        }
        while self.position < target && !self.roll_over() {
            self.step();
        }
        self.playing = false;
    }

    fn sample(&self) -> EnergySample {
        let energy = self.sim.energy();
        EnergySample {
            time_s: self.sim.state().time_s,
            energy,
            total: energy.total(),
        }
    }

    /// One step with its bookkeeping, the die and its twin in lock-step; returns whether
    /// the roll can go on (a die whose roll has ended waits for the other).
    fn step(&mut self) -> bool {
        // Steps already on the timeline are re-stepped to show them, not recorded again.
        let new = self.timeline.at_frontier(self.position);
        let die_rolling = self.sim.outcome().is_none();
        if let Some(twin) = &mut self.twin {
            twin.step();
        }
        if die_rolling {
            self.step_die(new);
        }
        self.position += 1;
        let done = self.roll_over();
        if new {
            if let Some(twin) = &mut self.twin {
                twin.stepped(&self.sim, self.stride, done);
            }
            let impact = self.impact_now();
            let position = self.position;
            let keyframe = self.timeline.keyframe_due(position).then(|| self.keyframe());
            self.timeline.recorded(position, keyframe, impact, done);
        } else if let Some(k) = self.timeline.at(self.position) {
            // Where a table value changed mid-roll, the roll carries on with the new one.
            let k = k.clone();
            self.restore(&k);
        }
        if done {
            self.playing = false;
            return false;
        }
        true
    }

    /// One step of the die; a `new` step also gives its energy sample and, at the roll's
    /// end, its entry in the outcome table.
    fn step_die(&mut self, new: bool) {
        let ended = self.sim.advance();
        self.touched |= self.sim.in_contact();
        if !new {
            return;
        }
        let s = self.sample();
        let peak = match self.peak {
            None => s,
            Some(p) => EnergySample {
                time_s: s.time_s,
                energy: p.energy.max_each(&s.energy),
                total: p.total.max(s.total),
            },
        };
        self.peak_steps += 1;
        if self.peak_steps >= self.stride || ended.is_some() {
            self.pending.history.push(peak);
            self.peak = None;
            self.peak_steps = 0;
        } else {
            self.peak = Some(peak);
        }
        if let Some(outcome) = ended
            && let RollKind::Random(id) = self.roll
            && !self.counted
        {
            self.counted = true;
            self.table.add(RollRecord {
                id,
                initial: self.initial,
                outcome,
                start_face: self.start_face,
            });
            self.pending.table_changed = true;
        }
    }

    /// Up to `n` steps; stops at the end of the roll. Returns the steps taken.
    pub fn advance_steps(&mut self, n: u64) -> u64 {
        let mut taken = 0;
        while taken < n && !self.roll_over() {
            taken += 1;
            if !self.step() {
                break;
            }
        }
        taken
    }

    /// Plays the roll to its end at once (what "instant" shows).
    #[cfg(test)]
    pub(crate) fn run_to_end(&mut self) {
        self.playing = true;
        while !self.roll_over() && self.step() {}
        self.playing = false;
    }

    /// The batch to start, once: whoever runs it reports back with [`Engine::add_batch_records`]
    /// and [`Engine::finish_batch`].
    pub(crate) fn take_batch_request(&mut self) -> Option<BatchRequest> {
        self.batch_request.take()
    }

    /// The newest map order, once: the worker's map thread follows it.
    pub(crate) fn take_map_order(&mut self) -> Option<MapOrder> {
        self.map_order.take()
    }

    /// The batch the table is receiving, if any.
    pub(crate) fn batch_id(&self) -> Option<u64> {
        self.batch.map(|b| b.id)
    }

    /// Enters finished rolls of batch `id`; rolls of a cancelled batch are dropped.
    pub(crate) fn add_batch_records(&mut self, id: u64, records: &[RollRecord]) {
        let Some(b) = &mut self.batch else { return };
        if b.id != id || records.is_empty() {
            return;
        }
        b.done += records.len() as u64;
        for r in records {
            self.table.add(*r);
        }
        self.pending.table_changed = true;
    }

    /// Batch `id` has stopped (finished, cancelled or failed to start).
    pub(crate) fn finish_batch(&mut self, id: u64, result: Result<(), String>) {
        let Some(b) = self.batch else { return };
        if b.id != id {
            return;
        }
        self.batch = None;
        // The table goes with the news, even when its last rolls came a tick earlier: a
        // snapshot that ends the batch always shows the table it ended with.
        self.pending.table_changed = true;
        self.pending.notice = Some(Notice::Said(match result {
            Ok(()) => format!("batch of {} rolls done", b.total),
            Err(e) => format!("batch stopped: {e}"),
        }));
    }

    /// Runs the requested batch on this thread to its end (tests and anything else that
    /// wants the table filled deterministically).
    #[cfg(test)]
    pub(crate) fn run_batch_here(&mut self) {
        use crate::experiment::{Rolls, run_batch};
        let Some(request) = self.take_batch_request() else {
            return;
        };
        let rolls = Rolls::Given(&request.rolls);
        let never = std::sync::atomic::AtomicBool::new(false);
        let mut seen = 0;
        let result = run_batch(&request.params, &rolls, 0, &never, &mut |records| {
            self.add_batch_records(request.id, &records[seen..]);
            seen = records.len();
        });
        self.finish_batch(request.id, result.map(|_| ()).map_err(|e| e.to_string()));
    }

    pub(crate) fn phase(&self) -> Phase {
        if let Some(o) = self.sim.outcome() {
            return Phase::Ended(o);
        }
        if !self.sim.in_contact() {
            return if self.touched {
                Phase::Rolling
            } else {
                Phase::Falling
            };
        }
        if self.impact_now() {
            Phase::InContact
        } else {
            Phase::Rolling
        }
    }

    /// An impact: the ground pushes far harder than it takes to carry the die.
    fn impact_now(&self) -> bool {
        if !self.sim.in_contact() || self.sim.outcome().is_some() {
            return false;
        }
        let push: f64 = self.sim.state().corner_forces.iter().map(|f| f.z).sum();
        push > 2.0 * self.params.total_mass() * self.params.world.gravity
    }

    /// Where the roll on screen is on its timeline.
    #[cfg(test)]
    pub(crate) fn position(&self) -> u64 {
        self.position
    }

    #[cfg(test)]
    pub(crate) fn timeline(&self) -> &Timeline {
        &self.timeline
    }

    /// Everything the UI draws, plus what happened since the last snapshot.
    pub fn snapshot(&mut self) -> Snapshot {
        let pending = std::mem::take(&mut self.pending);
        let s = self.sim.state();
        Snapshot {
            commands_handled: self.commands_handled,
            params: self.params,
            initial: self.initial,
            roll: self.roll,
            playing: self.playing,
            speed: self.speed,
            die: DieState::of(&self.sim, self.start_face),
            energy: self.sim.energy(),
            ledger: self.sim.energy_ledger(),
            stop_threshold: self.sim.stop_threshold(),
            time_s: self.time_s(),
            step: self
                .twin
                .as_ref()
                .map_or(s.step, |t| s.step.max(t.sim.state().step)),
            phase: self.phase(),
            history: pending.history,
            history_reset: pending.history_reset,
            history_cut: pending.history_cut,
            timeline: TimelineSnapshot {
                position: self.position,
                furthest: self.timeline.furthest,
                ended: self.timeline.ended,
                impacts: std::mem::take(&mut self.timeline.impacts_changed)
                    .then(|| self.timeline.impacts.clone()),
            },
            batch: self.batch.map(|b| BatchProgress {
                done: b.done,
                total: b.total,
            }),
            table: pending.table_changed.then(|| self.table.clone()),
            notice: pending.notice,
            preset: pending.preset,
            export: self.export.map(|e| e.progress),
            curve: None,
            twin: match &mut self.twin {
                Some(t) => Some(t.snapshot(&self.sim)),
                None => None,
            },
        }
    }
}
