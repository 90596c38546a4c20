//! What passes between the worker thread and the UI: the commands it takes, in order, and
//! the snapshot it reports after each batch of them and each tick, with the die, the roll's
//! new samples, the table and the jobs' progress in it. Plain data, built by the simulator
//! and read by the explorer's state; nothing here steps a roll or starts a thread.

use super::curve::CurveUpdate;
use super::map_jobs::MapRequest;
use dicesim_experiment::{BasinMap, FaceTally, Layer, RollRecord, ScanKey};
use dicesim_figures::animation::AnimationProgress;
use dicesim_figures::export::ExportProgress;
use dicesim_physics::{ContactForce, Energy, EnergyLedger, InitialCondition, Outcome, Params, Roll, Status};
use dicesim_setup::chaos::Separation;
use dicesim_setup::preset::{Preset, Speed};
use nalgebra::{Rotation3, Vector3};
use std::collections::VecDeque;

/// What the UI asks of the worker. Commands are applied in the order sent, none dropped.
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    TogglePlay,
    SetPlaying(bool),
    /// Pause, then take this many steps of Δt.
    Step(u64),
    /// Pause, then go this many steps of Δt back (at most to the start).
    StepBack(u64),
    /// Pause at this step of the roll (`u64::MAX`: its end), computing on if need be.
    Seek(u64),
    /// Pause where this happens in the roll, computing on as far as it takes.
    SeekEvent(RollEvent),
    /// The same initial condition again, from t = 0 (the same face every time).
    Replay,
    /// The next random initial condition from the preset's ranges.
    RandomRoll,
    /// A new value; values that act mid-roll (the ground's) change the running roll, others
    /// restart it.
    SetParam(&'static ScanKey, f64),
    SetSpeed(Speed),
    /// Random rolls computed into the outcome table.
    BatchStart(u64),
    BatchCancel,
    ClearTable,
    /// Compute a basin map around the current setup (cancelling the running one).
    MapStart(MapRequest),
    MapCancel,
    /// Play this exact setup from t = 0 (a cell of a basin map, replayed).
    PlaySetup(Box<Params>, InitialCondition),
    /// Roll a chaos twin beside the die, its start perturbed by this relative ε
    /// ([`dicesim_setup::chaos::perturbed`]), from t = 0; `None` removes it.
    SetTwin(Option<f64>),
    /// Roll a parameter twin beside the die: the same start in setup B, the current setup
    /// with these values (registry keys; not start values, not Δt), from t = 0; an empty
    /// list removes it. It takes the place of a chaos twin.
    SetParamTwin(Vec<(&'static ScanKey, f64)>),
    /// Another preset: its setup and its roll, a fresh outcome table.
    LoadPreset(Box<Preset>),
    /// Write the roll on screen, rolled again from t = 0, into this folder: its trace as
    /// CSV and its energy plot as PNG (on a thread of its own, with progress), the plot on
    /// the energy axis the screen shows (`log_scale`: logarithmic).
    Export {
        dir: std::path::PathBuf,
        log_scale: bool,
    },
    /// Write this basin map, as the screen shows it, into a folder: its cells as CSV and
    /// its picture as PNG (on the export's thread, like the roll's).
    ExportMap(Box<MapExport>),
    /// Write the roll on screen (with its chaos twin when one rolls), rolled again from
    /// t = 0, into this folder as an animated GIF: seen from the explorer's camera (degrees)
    /// and played at its speed (on the export's thread, like the roll's).
    ExportAnimation {
        dir: std::path::PathBuf,
        yaw_deg: f64,
        pitch_deg: f64,
    },
    ExportCancel,
    Quit,
}

/// A moment of the roll the event keys jump to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RollEvent {
    /// The first impact ([`dicesim_physics::Impacts`]) after the step on screen.
    NextImpact,
    /// The last impact before the step on screen.
    PreviousImpact,
    /// The step at which the stopping rule decided the face.
    FaceDecided,
}

/// A basin map to write (see [`Command::ExportMap`]).
#[derive(Debug, Clone, PartialEq)]
pub struct MapExport {
    pub(crate) dir: std::path::PathBuf,
    pub(crate) map: BasinMap,
    /// The setup every cell starts from, but for its two axis values.
    pub(crate) params: Params,
    pub(crate) initial: InitialCondition,
    pub(crate) layer: Layer,
    /// Pixels.
    pub(crate) size: (u32, u32),
}

/// The export running, as the status line tells it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum ExportStatus {
    /// The roll: rolled again to learn its length, then written.
    Roll(ExportProgress),
    /// A basin map, drawn at this many pixels.
    Map { size: (u32, u32) },
    /// The roll as an animation: rolled to its end, then its frames drawn.
    Animation(AnimationProgress),
}

/// Which roll is on screen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RollKind {
    /// The preset's own initial condition.
    Preset,
    /// Random roll number `n` (counted in the outcome table once).
    Random(u64),
    /// An initial condition the user edited.
    Edited,
}

/// Where the roll is, in the words of the model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Phase {
    /// No corner has touched the ground yet.
    Falling,
    /// Pressed into the table: the ground pushes with more than twice the die's weight (the
    /// squeeze of an impact; where impacts begin is the physics' [`dicesim_physics::Impacts`]).
    InContact,
    /// After the first impact: tumbling, sliding, or briefly in the air.
    Rolling,
    Ended(Outcome),
}

impl Phase {
    pub(crate) fn label(&self) -> String {
        match self {
            Phase::Falling => "falling".to_string(),
            Phase::InContact => "in contact".to_string(),
            Phase::Rolling => "rolling".to_string(),
            Phase::Ended(o) => match (o.status, o.face) {
                (Status::Settled, Some(f)) => format!("settled: face {f}"),
                (Status::Settled, None) => "settled: no face up".to_string(),
                (Status::Timeout, _) => "did not settle".to_string(),
                (Status::Unstable, _) => "unstable".to_string(),
            },
        }
    }
}

/// One energy sample of the live roll, erg (each term's peak when samples are thinned).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergySample {
    /// s, simulated.
    pub(crate) time_s: f64,
    pub(crate) energy: Energy,
    pub(crate) total: f64,
    /// Every quantity of [`dicesim_setup::quantity::QUANTITIES`] (each one's value of
    /// largest magnitude over the steps when samples are thinned), for the plot of any of them.
    pub(crate) quantities: dicesim_setup::quantity::Readings,
}

impl EnergySample {
    /// A roll's energy and every quantity now (the die's, or a parameter twin's).
    pub(crate) fn of(roll: &Roll) -> EnergySample {
        let energy = roll.energy();
        EnergySample {
            time_s: roll.time_s(),
            energy,
            total: energy.total(),
            quantities: dicesim_setup::quantity::read_all(roll),
        }
    }
}

/// How far the twin has drifted from the die at one instant (each term's newest value).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SeparationSample {
    /// s, simulated.
    pub(crate) time_s: f64,
    pub(crate) separation: Separation,
}

/// The chaos twin as drawn: its die, how its roll went, and its drift from the first die.
#[derive(Debug, Clone, PartialEq)]
pub struct TwinSnapshot {
    /// Relative: the chaos twin's start perturbation (0 for a parameter twin).
    pub(crate) epsilon: f64,
    /// The values setup B differs by (empty for the chaos twin).
    pub(crate) differs_by: Vec<(&'static ScanKey, f64)>,
    pub(crate) die: DieState,
    pub(crate) phase: Phase,
    pub(crate) separation: Separation,
    /// Samples since the previous snapshot (after clearing, if the snapshot's
    /// `history_reset`).
    pub(crate) history: Vec<SeparationSample>,
    /// A parameter twin's own samples since the previous snapshot, as `history`'s (empty
    /// for the chaos twin).
    pub(crate) samples: Vec<EnergySample>,
}

/// The die as drawn.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DieState {
    /// cm, world positions of its contact points: the box's corners 1..8, a polyhedral die's
    /// vertices (their spheres' centres) in its vertex order.
    pub(crate) corners: Vec<Vector3<f64>>,
    /// Each point's contact force (depth > 0 means it touches the ground).
    pub(crate) forces: Vec<ContactForce>,
    /// The body frame's turn into the world ([`dicesim_physics::Roll::orientation`]): the
    /// box's axes as columns; a polyhedral die's vertices' frame about its centre of mass.
    pub(crate) orientation: Rotation3<f64>,
    /// cm, centre of mass.
    pub(crate) centre: Vector3<f64>,
    /// cm/s, centre-of-mass velocity.
    pub(crate) velocity: Vector3<f64>,
    /// rad/s, ω (world frame).
    pub(crate) angular_velocity: Vector3<f64>,
    /// g·cm²/s, L about the centre of mass.
    pub(crate) angular_momentum: Vector3<f64>,
    /// The number read now: the face most nearly up's (the d4's at its top vertex).
    pub(crate) face_up: u8,
    /// The number read at t = 0.
    pub(crate) start_face: u8,
    /// cm, how far the centre of mass has moved along the table since the contact going on
    /// began (docs/explorer.md, "Readouts"); `None` clear of the table (and for a twin).
    pub(crate) slid_cm: Option<f64>,
}

impl DieState {
    /// The die as drawn, from a roll's current state (the live die's or the twin's).
    pub(crate) fn of(roll: &Roll, start_face: u8) -> DieState {
        DieState {
            corners: roll.point_positions(),
            forces: roll.contact_forces(),
            orientation: roll.orientation(),
            centre: roll.position(),
            velocity: roll.velocity(),
            angular_velocity: roll.angular_velocity(),
            angular_momentum: roll.angular_momentum(),
            face_up: roll.face_up(),
            start_face,
            slid_cm: None,
        }
    }
}

/// Where the roll on screen is on its timeline, and what is known of it.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct TimelineSnapshot {
    /// Steps of Δt since the roll started.
    pub(crate) position: u64,
    /// The furthest step computed so far.
    pub(crate) furthest: u64,
    /// Whether the roll ends at `furthest`.
    pub ended: bool,
    /// The step at which the stopping rule found the die settled, once it has: the roll's
    /// data (its outcome, the table, the exports) end there, while the die on screen plays
    /// on until it is at rest.
    pub decided: Option<u64>,
    /// Steps at which impacts began, whenever they (or the edits) changed.
    pub(crate) impacts: Option<Vec<u64>>,
    /// Steps at which a table value was changed mid-roll, sent with the impacts.
    pub(crate) edits: Option<Vec<u64>>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BatchProgress {
    pub done: u64,
    pub(crate) total: u64,
}

/// How many finished rolls the table lists.
pub(crate) const LAST_ROLLS: usize = 12;

/// The outcome table: face counts of random rolls and the last few rolls.
#[derive(Debug, Clone, PartialEq)]
pub struct OutcomeTable {
    /// Settled rolls with a face up.
    pub tally: FaceTally,
    /// Rolls that settled balanced on an edge or a corner: no face up.
    pub(crate) without_face: u64,
    /// Rolls that reached the time cap still moving.
    pub(crate) did_not_settle: u64,
    pub(crate) unstable: u64,
    /// Newest first.
    pub last: VecDeque<RollRecord>,
}

/// The empty table of the default setup's die: what the screen holds before the worker's
/// first table.
impl Default for OutcomeTable {
    fn default() -> Self {
        OutcomeTable::new(Params::DEFAULT.die.face_numbers())
    }
}

impl OutcomeTable {
    /// An empty table of a die that shows `numbers`.
    pub(crate) fn new(numbers: &'static [u8]) -> OutcomeTable {
        OutcomeTable {
            tally: FaceTally::new(numbers),
            without_face: 0,
            did_not_settle: 0,
            unstable: 0,
            last: VecDeque::new(),
        }
    }

    pub(crate) fn add(&mut self, r: RollRecord) {
        match (r.outcome.status, r.outcome.face) {
            (Status::Settled, Some(f)) => self.tally.add(f),
            (Status::Settled, None) => self.without_face += 1,
            (Status::Timeout, _) => self.did_not_settle += 1,
            (Status::Unstable, _) => self.unstable += 1,
        }
        self.last.push_front(r);
        self.last.truncate(LAST_ROLLS);
    }

    /// Every roll entered, settled or not.
    pub fn rolls(&self) -> u64 {
        self.tally.total() + self.without_face + self.did_not_settle + self.unstable
    }
}

/// What the worker has to tell the user. The explorer words it: the worker knows no keys,
/// so a notice that would point at one is a variant of its own.
#[derive(Debug, Clone, PartialEq)]
pub enum Notice {
    /// A step forward was asked for at the end of a finished roll (replaying moves it).
    RollEnded,
    /// An export was asked for while one runs (asking again would cancel it).
    ExportRunning,
    /// Anything else, in words that name no key (a refused value, a finished batch).
    Said(String),
}

impl Notice {
    /// The words, for notices that need no key to say them.
    pub fn said(&self) -> Option<&str> {
        match self {
            Notice::Said(words) => Some(words),
            _ => None,
        }
    }
}

/// The worker's report after each batch of commands and each tick.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Commands applied so far: the UI knows its own edits have arrived when this catches up.
    pub commands_handled: u64,
    pub params: Params,
    pub initial: InitialCondition,
    pub(crate) roll: RollKind,
    pub playing: bool,
    pub(crate) speed: Speed,
    pub(crate) die: DieState,
    pub energy: Energy,
    /// Where the energy went since t = 0 (measured in the physics, step by step).
    pub(crate) ledger: EnergyLedger,
    /// Every quantity of [`dicesim_setup::quantity::QUANTITIES`] at the state on screen,
    /// for the plots' readout at the time marker.
    pub(crate) readings: dicesim_setup::quantity::Readings,
    /// erg, the stopping threshold.
    pub stop_threshold: f64,
    /// s, simulated.
    pub time_s: f64,
    pub step: u64,
    pub phase: Phase,
    /// Energy samples since the previous snapshot (after clearing, if `history_reset`).
    pub history: Vec<EnergySample>,
    /// A new roll started: earlier samples belong to another roll.
    pub history_reset: bool,
    /// s: samples after this time are of a future that changed (a table value mid-roll
    /// while stepped back): drop them.
    pub(crate) history_cut: Option<f64>,
    pub timeline: TimelineSnapshot,
    pub batch: Option<BatchProgress>,
    /// The whole table, when it changed.
    pub table: Option<OutcomeTable>,
    /// While batches ran with a parameter twin on: A's ending against B's over their
    /// shared throws (until the table is cleared or another preset loads).
    pub(crate) versus: Option<dicesim_experiment::versus::VersusTable>,
    /// A one-line message for the user (a refused value, a finished batch).
    pub notice: Option<Notice>,
    /// The chaos twin, stepped in lock-step with the die.
    pub twin: Option<TwinSnapshot>,
    /// The preset loaded, in the first snapshot and whenever another is loaded.
    pub(crate) preset: Option<Box<Preset>>,
    /// The running export, how far it has got.
    pub(crate) export: Option<ExportStatus>,
    /// The twin's predictability curve, whenever it started, grew or ended (while a twin
    /// rolls).
    pub curve: Option<CurveUpdate>,
}
