//! What passes between `update` and the event loop: a [`Msg`] in, the [`Effect`]s it asks
//! for out, collected in one [`Outbox`] while `update` runs.

use crate::worker::{Command, MapUpdate, Snapshot};
use dicesim_setup::preset::Preset;
use ratatui::crossterm::event::Event;

/// What the event loop hands to `update`: terminal input or a worker snapshot.
#[derive(Debug, Clone)]
pub(crate) enum Msg {
    Input(Event),
    Worker(Box<Snapshot>),
    /// A basin map from the worker's map thread.
    Map(Box<MapUpdate>),
    /// A signal that ends the explorer (the event loop handles it before `update`).
    Signal(i32),
}

impl From<Snapshot> for Msg {
    fn from(s: Snapshot) -> Msg {
        Msg::Worker(Box::new(s))
    }
}

impl From<MapUpdate> for Msg {
    fn from(m: MapUpdate) -> Msg {
        Msg::Map(Box::new(m))
    }
}

/// What the explorer asks of the world outside `update`: the event loop runs these in the
/// order asked, so `update` itself never touches the disk or a thread.
#[derive(Debug, Clone, PartialEq)]
// A worker command carries a whole setup (a loaded die's eight corner masses among it); an
// effect lives only from `update` to the event loop, so boxing it would buy nothing.
#[allow(clippy::large_enum_variant)]
pub(crate) enum Effect {
    /// A command for the simulation thread.
    Worker(Command),
    /// List the presets (shipped and the user's folder) and open the picker on them.
    ListPresets,
    /// Write this preset into the user's folder; an existing file of its name is replaced
    /// only with `replace` (else the save dialog asks).
    SavePreset { preset: Box<Preset>, replace: bool },
}

impl Effect {
    /// The worker command, if this is one.
    #[cfg(test)]
    pub(crate) fn command(self) -> Option<Command> {
        match self {
            Effect::Worker(c) => Some(c),
            _ => None,
        }
    }
}

/// Tests compare the effects of a key with the worker commands they expect.
impl PartialEq<Command> for Effect {
    fn eq(&self, other: &Command) -> bool {
        matches!(self, Effect::Worker(c) if c == other)
    }
}

/// What one `update` sends out, in the order asked: the one channel from the state to the
/// event loop. Every worker command leaves through it and is counted, so the user's setup
/// knows when the worker has caught up with its edits ([`Snapshot::commands_handled`]).
#[derive(Debug, Clone, Default)]
pub(crate) struct Outbox {
    effects: Vec<Effect>,
    /// Commands sent to the worker since the explorer started.
    commands_sent: u64,
}

impl Outbox {
    /// Queues a command for the worker.
    pub(crate) fn command(&mut self, c: Command) {
        self.commands_sent += 1;
        self.effects.push(Effect::Worker(c));
    }

    /// Queues an effect (a worker command among them, counted as [`Outbox::command`] counts it).
    pub(crate) fn ask(&mut self, effect: Effect) {
        match effect {
            Effect::Worker(c) => self.command(c),
            other => self.effects.push(other),
        }
    }

    /// Commands sent to the worker since the explorer started.
    pub(crate) fn commands_sent(&self) -> u64 {
        self.commands_sent
    }

    /// The worker commands queued since the last [`Outbox::take`], to be changed in place
    /// (one for every one queued, so the count stays true).
    pub(crate) fn commands_mut(&mut self) -> impl Iterator<Item = &mut Command> {
        self.effects.iter_mut().filter_map(|e| match e {
            Effect::Worker(c) => Some(c),
            _ => None,
        })
    }

    /// Everything queued since the last take, in order: what the event loop is to do.
    pub(crate) fn take(&mut self) -> Vec<Effect> {
        std::mem::take(&mut self.effects)
    }
}
