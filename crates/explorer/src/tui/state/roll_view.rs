//! The live roll as the explorer knows it: the worker's snapshots absorbed into the newest
//! state, the roll's energy history and impacts, the outcome table, the batch and the
//! roll's export; the panels ask it rather than the snapshots. A snapshot carries only
//! what is new (samples since the last one, the table when it changed), so this is where
//! the roll's whole picture is kept in step: a new roll clears the history, a changed
//! future cuts it.

use super::camera::OrbitCamera;
use crate::tui::vocabulary::format::{fmt_num, group};
use crate::tui::vocabulary::key_table::{Action, Scope, label};
use crate::tui::vocabulary::solid::DieShape;
use crate::worker::{BatchProgress, Command, EnergySample, ExportStatus, OutcomeTable, Snapshot};
use dicesim_setup::number::human_bytes;

/// Rolls in one batch (`b`) until another size is chosen (`B`).
pub(crate) const BATCH_ROLLS: u64 = 10_000;
/// Batch sizes `B` walks through before offering to type one.
pub(crate) const BATCH_SIZES: [u64; 3] = [1_000, 10_000, 100_000];
/// The largest batch that may be typed: a few minutes on two cores.
pub(crate) const MAX_BATCH_ROLLS: u64 = 10_000_000;

#[derive(Debug, Clone)]
pub(crate) struct RollView {
    /// The newest worker snapshot (its history already moved into `history`).
    pub(crate) live: Snapshot,
    /// Energy samples of the roll on screen.
    pub(crate) history: Vec<EnergySample>,
    /// Steps at which the roll's impacts began, for the timeline.
    pub(crate) impacts: Vec<u64>,
    /// Steps at which a table value was changed mid-roll (the worker's record), marked on
    /// the timeline and the plot.
    pub(crate) edits: Vec<u64>,
    /// The samples of the run before the last restart or mid-roll change, drawn faded
    /// under the new one until the next.
    pub(crate) previous: Vec<EnergySample>,
    pub(crate) table: OutcomeTable,
    pub(crate) batch: Option<BatchProgress>,
    /// The export running (the roll's or a map's), how far it has got.
    pub(crate) export: Option<ExportStatus>,
    /// Rolls the next batch (`b`) asks for.
    pub(crate) batch_size: u64,
    /// The solid `live.params` describe, as drawn: made when the die's parameters change,
    /// not for every frame (a polyhedral die's hull and mass are a computation).
    pub(crate) shape: DieShape,
}

impl RollView {
    /// The roll of the worker's first snapshot (its notice, preset and curve taken already).
    pub(crate) fn new(mut first: Snapshot) -> RollView {
        RollView {
            history: std::mem::take(&mut first.history),
            impacts: first.timeline.impacts.take().unwrap_or_default(),
            edits: first.timeline.edits.take().unwrap_or_default(),
            previous: Vec::new(),
            table: first
                .table
                .take()
                .unwrap_or_else(|| OutcomeTable::new(first.params.die.face_numbers())),
            batch: first.batch,
            export: first.export,
            shape: DieShape::of(&first.params),
            live: first,
            batch_size: BATCH_ROLLS,
        }
    }

    /// Takes a snapshot in: new samples appended (after a new roll's reset, or a cut at a
    /// changed future), the table and impacts when they changed, the rest replaced.
    pub(crate) fn absorb(&mut self, mut s: Snapshot) {
        // A run of more than its start is kept to be drawn faded.
        if (s.history_reset || s.history_cut.is_some()) && self.history.len() > 1 {
            self.previous = self.history.clone();
        }
        if s.history_reset {
            self.history.clear();
        }
        if let Some(cut) = s.history_cut {
            self.history.retain(|h| h.time_s <= cut);
        }
        if let Some(impacts) = s.timeline.impacts.take() {
            self.impacts = impacts;
        }
        if let Some(edits) = s.timeline.edits.take() {
            self.edits = edits;
        }
        self.history.append(&mut s.history);
        if let Some(t) = s.table.take() {
            self.table = t;
        }
        self.batch = s.batch;
        self.export = s.export;
        if s.params.die != self.live.params.die {
            self.shape = DieShape::of(&s.params);
        }
        self.live = s;
    }

    /// Whether frames should keep coming without input (a moving roll, a running batch or export).
    pub(crate) fn animating(&self) -> bool {
        self.live.playing || self.batch.is_some() || self.export.is_some()
    }

    /// `b`: a batch of the chosen size, or the running one cancelled.
    pub(crate) fn batch_command(&self) -> Command {
        if self.batch.is_some() {
            Command::BatchCancel
        } else {
            Command::BatchStart(self.batch_size)
        }
    }

    /// The export key: the roll written into the current folder (its energy plot on the
    /// axis the screen shows), or the running export cancelled.
    pub(crate) fn export_command(&self, log_scale: bool) -> Command {
        if self.export.is_some() {
            Command::ExportCancel
        } else {
            Command::Export {
                dir: ".".into(),
                log_scale,
            }
        }
    }

    /// The animation key: the roll on screen written into the current folder as an
    /// animated GIF seen from `camera`, or the running export cancelled.
    pub(crate) fn animation_command(&self, camera: &OrbitCamera) -> Command {
        if self.export.is_some() {
            Command::ExportCancel
        } else {
            Command::ExportAnimation {
                dir: ".".into(),
                yaw_deg: camera.yaw_deg,
                pitch_deg: camera.pitch_deg,
            }
        }
    }

    /// `B`: 1 000 → 10 000 → 100 000 → type one → 1 000 …; the notice, or `None` when
    /// the next step is typing one. `typing`: pressed while a size is being typed, the
    /// step after typing one (the size is still the last one).
    pub(crate) fn next_batch_size(&mut self, typing: bool) -> Option<String> {
        let at = BATCH_SIZES
            .iter()
            .position(|&n| n == self.batch_size)
            .filter(|_| !typing);
        let i = at.map_or(Some(0), |i| (i + 1 < BATCH_SIZES.len()).then_some(i + 1))?;
        self.batch_size = BATCH_SIZES[i];
        Some(format!(
            "batch size {} ({}: the next size, after {} type one)",
            group(self.batch_size),
            label(Scope::Die, Action::BatchSize),
            group(BATCH_SIZES[BATCH_SIZES.len() - 1])
        ))
    }

    /// A typed batch size: a whole number of rolls from 1 to [`MAX_BATCH_ROLLS`]; the
    /// notice, or why it is refused.
    pub(crate) fn set_batch_size(&mut self, rolls: f64) -> Result<String, String> {
        if rolls.fract() == 0.0 && (1.0..=MAX_BATCH_ROLLS as f64).contains(&rolls) {
            self.batch_size = rolls as u64;
            Ok(format!("batch size {}", group(self.batch_size)))
        } else {
            Err(format!(
                "{} rolls: a whole number from 1 to {}",
                fmt_num(rolls),
                group(MAX_BATCH_ROLLS)
            ))
        }
    }

    /// What the status line says while an export runs: the roll's size first, then how far.
    pub(crate) fn export_status(&self) -> Option<String> {
        let p = match self.export? {
            ExportStatus::Roll(p) => p,
            ExportStatus::Map { size: (w, h) } => {
                return Some(format!(
                    "exporting the basin map at {w}×{h} px · {} cancels",
                    label(Scope::Map, Action::ExportMap)
                ));
            }
            ExportStatus::Animation(p) => {
                let cancel = label(Scope::Die, Action::ExportAnimation);
                let share = 100.0 * p.done as f64 / p.total.max(1) as f64;
                return Some(if p.drawing {
                    format!(
                        "exporting the animation: frame {} of {} · {cancel} cancels",
                        p.done, p.total
                    )
                } else {
                    format!(
                        "exporting the animation: rolling, {share:.0}% of the time cap · {cancel} cancels"
                    )
                });
            }
        };
        let share = 100.0 * p.steps_done as f64 / p.steps_total.max(1) as f64;
        let cancel = label(Scope::Die, Action::Export);
        Some(if p.writing {
            format!(
                "exporting the roll: {share:.0}% of {} rows, {} · {cancel} cancels",
                p.steps_total + 1,
                human_bytes(p.bytes)
            )
        } else if p.bytes == 0 {
            format!("exporting the roll: measuring its length · {cancel} cancels")
        } else {
            format!(
                "exporting the roll: measuring its length, {share:.0}% of the time cap (at most {}) · {cancel} cancels",
                human_bytes(p.bytes)
            )
        })
    }
}
