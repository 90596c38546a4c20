//! The twins as the explorer keeps them: whether a chaos twin rolls and at which ε, its
//! drift from the die over the roll on screen and the setup's predictability curve; whether
//! differ mode sends value changes to the parameter twin's die B, and what B differs by. ε
//! only moves inside its range and by whole decades with the step keys; the curve shown is
//! never older than one already shown.

use crate::tui::vocabulary::format::fmt_num;
use crate::tui::vocabulary::param::Param;
use crate::worker::{Command, CurveUpdate, EnergySample, SeparationSample, Snapshot};
use dicesim_setup::chaos::{DEFAULT_EPSILON, EPSILON};
use dicesim_setup::keys::ScanKey;

/// What ε does, in the words shown on screen.
pub(crate) const DEFINITION: &str = "twin: height, velocity and spin × (1 + ε)";

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TwinView {
    /// Whether a chaos twin rolls beside the die (`T`).
    pub(crate) on: bool,
    /// Relative, the twin's start perturbation.
    pub(crate) epsilon: f64,
    /// The twin's separation samples of the roll on screen.
    pub(crate) history: Vec<SeparationSample>,
    /// The predictability curve of the setup, while a twin rolls (newest generation).
    pub(crate) curve: Option<CurveUpdate>,
    /// Whether value changes go to the parameter twin's setup B only (`D`, "differ").
    pub(crate) differ: bool,
    /// A parameter twin's energy and quantity samples of the roll on screen (B's curve).
    pub(crate) samples: Vec<EnergySample>,
    /// The values B differs from the die's setup by, in the order first changed.
    pub(crate) differs_by: Vec<(&'static ScanKey, f64)>,
}

impl Default for TwinView {
    fn default() -> TwinView {
        TwinView {
            on: false,
            epsilon: DEFAULT_EPSILON,
            history: Vec::new(),
            curve: None,
            differ: false,
            samples: Vec::new(),
            differs_by: Vec::new(),
        }
    }
}

impl TwinView {
    /// A preset's view: a twin at its ε, or none (the ε kept for the next `T`).
    pub(crate) fn apply(&mut self, twin: Option<f64>) {
        self.on = twin.is_some();
        // A preset's chaos twin takes the parameter twin's place.
        if self.on {
            self.differ = false;
            self.differs_by.clear();
        }
        if let Some(epsilon) = twin {
            self.epsilon = epsilon;
        }
    }

    /// The chaos twin on or off (it takes the parameter twin's place); the command that says so.
    pub(crate) fn toggle(&mut self) -> Command {
        self.on = !self.on;
        self.differ = false;
        self.differs_by.clear();
        Command::SetTwin(self.on.then_some(self.epsilon))
    }

    /// ε a decade smaller or larger (`factor` 0.1 or 10), clamped to its range; the
    /// command, if ε changed.
    pub(crate) fn step(&mut self, factor: f64) -> Option<Command> {
        // Decade steps land exactly on powers of ten, not on 9.999…e-10.
        let epsilon = 10f64
            .powi((self.epsilon * factor).log10().round() as i32)
            .clamp(EPSILON.min, EPSILON.max);
        (epsilon != self.epsilon).then(|| {
            self.epsilon = epsilon;
            Command::SetTwin(Some(epsilon))
        })
    }

    /// Differ mode on or off. On, the chaos twin goes (nothing differs yet, so no die B
    /// rolls until the first change); off, die B goes too. The command, if one is due.
    pub(crate) fn toggle_differ(&mut self) -> Option<Command> {
        if self.differ {
            self.differ = false;
            self.differs_by.clear();
            return Some(Command::SetParamTwin(Vec::new()));
        }
        self.differ = true;
        std::mem::take(&mut self.on).then_some(Command::SetTwin(None))
    }

    /// B now differs by `key` = `value` too (a key changed again keeps its place, with the
    /// new value); the command that rolls both dice again.
    pub(crate) fn differ_by(&mut self, key: &'static ScanKey, value: f64) -> Command {
        match self.differs_by.iter_mut().find(|(k, _)| *k == key) {
            Some(entry) => entry.1 = value,
            None => self.differs_by.push((key, value)),
        }
        Command::SetParamTwin(self.differs_by.clone())
    }

    /// A typed ε: the command, or why it is refused.
    pub(crate) fn set(&mut self, epsilon: f64) -> Result<Command, String> {
        if EPSILON.check(epsilon).is_err() {
            return Err(format!(
                "ε = {} is outside {}…{}",
                fmt_num(epsilon),
                fmt_num(EPSILON.min),
                fmt_num(EPSILON.max)
            ));
        }
        self.epsilon = epsilon;
        Ok(Command::SetTwin(Some(epsilon)))
    }

    /// Takes the twin's part of a snapshot: its new samples (after a reset or a cut, as the
    /// die's) and a curve no older than the one shown; no twin, no curve.
    pub(crate) fn absorb(&mut self, s: &mut Snapshot) {
        if s.history_reset {
            self.history.clear();
            self.samples.clear();
        }
        if let Some(cut) = s.history_cut {
            self.history.retain(|h| h.time_s <= cut);
            self.samples.retain(|h| h.time_s <= cut);
        }
        if let Some(twin) = &mut s.twin {
            self.history.append(&mut twin.history);
            self.samples.append(&mut twin.samples);
        } else {
            self.samples.clear();
        }
        if let Some(c) = s.curve.take()
            && self
                .curve
                .as_ref()
                .is_none_or(|old| c.generation >= old.generation)
        {
            self.curve = Some(c);
        }
        if s.twin.is_none() {
            self.curve = None;
        }
    }
}

/// `label value` pairs in the parameter list's words, e.g. `friction μ 0.3, damping γ 0.01`.
pub(crate) fn differs_text(values: &[(&'static ScanKey, f64)]) -> String {
    values
        .iter()
        .map(|(k, v)| format!("{} {}", Param::of(k).label(), fmt_num(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}
