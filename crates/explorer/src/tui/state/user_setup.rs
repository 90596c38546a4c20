//! The setup as the user has set it: the values, the playback speed and the preset they
//! came from. The user's values run ahead of the worker's: each change returns the command
//! that tells the worker, every command is counted on its way out (the app's outbox), and a
//! snapshot's values are taken only once the worker has handled every command sent
//! ([`UserSetup::adopt`]), so an edit never flickers back to the value it replaced.

use crate::tui::vocabulary::format::{fmt_num, fmt_range};
use crate::tui::vocabulary::param::{Param, all};
use crate::worker::{Command, RollKind, Snapshot, Speed};
use dicesim_physics::params::Detail;
use dicesim_physics::{InitialCondition, Params};
use dicesim_setup::preset::Preset;

#[derive(Debug, Clone)]
pub(crate) struct UserSetup {
    pub(crate) params: Params,
    pub(crate) initial: InitialCondition,
    pub(crate) speed: Speed,
    /// The preset the setup was loaded from (or last saved as): the questions over unsaved
    /// changes compare with it.
    pub(crate) preset: Preset,
    /// The start the last random roll (`R`) drew from the preset's ranges: a draw is the
    /// preset's own doing, not a change of the user's, so no question guards it.
    drawn: Option<InitialCondition>,
}

impl UserSetup {
    /// The setup of the worker's first snapshot.
    pub(crate) fn new(first: &Snapshot, preset: Preset) -> UserSetup {
        UserSetup {
            params: first.params,
            initial: first.initial,
            speed: first.speed,
            preset,
            drawn: None,
        }
    }

    /// Whether the setup differs from the open preset's (questions guard such changes).
    pub(crate) fn modified(&self) -> bool {
        self.params != self.preset.params()
            || (self.initial != self.preset.initial && Some(self.initial) != self.drawn)
    }

    /// Takes the worker's values, unless it has not handled all `commands_sent` yet (then
    /// the user's own values are newer).
    pub(crate) fn adopt(&mut self, s: &Snapshot, commands_sent: u64) {
        if s.commands_handled >= commands_sent {
            self.params = s.params;
            self.initial = s.initial;
            self.speed = s.speed;
            if let RollKind::Random(_) = s.roll {
                self.drawn = Some(s.initial);
            }
        }
    }

    /// Sets `p`; the command that tells the worker. A value outside its range, one that
    /// would start the die inside the table, or one that no body can have with the other
    /// values (a corner radius not below the smallest half size, pips too wide or too deep)
    /// is refused in words and changes nothing.
    pub(crate) fn set_param(&mut self, p: Param, value: f64) -> Result<Command, String> {
        let (mut params, mut initial) = (self.params, self.initial);
        // The value is checked as `roll` checks a setup: its range, then the rules that tie
        // it to the others (said in their own words), then a start clear of the table.
        p.set(&mut params, &mut initial, value)
            .map_err(|e| match e.detail.as_deref() {
                Some(Detail::Refused(why)) => format!("{}: {why}", fmt_num(value)),
                _ if e.limits == p.limits() => format!(
                    "{} is outside {} {}",
                    fmt_num(value),
                    fmt_range(p),
                    p.limits().unit
                ),
                _ if e.limits.key == "initial.height" => format!(
                    "{}: corner in the table; ≥ {} cm",
                    fmt_num(value),
                    fmt_num(e.limits.min)
                ),
                _ => e.to_string(),
            })?;
        (self.params, self.initial) = (params, initial);
        Ok(Command::SetParam(p.scan_key(), value))
    }

    /// `p` a step up or down (`coarse`: a big step), inside its range; the command, if the
    /// value changed.
    pub(crate) fn nudge(&mut self, p: Param, steps: i32, coarse: bool) -> Option<Command> {
        let now = p.get(&self.params, &self.initial);
        let next = p.nudged(now, steps, coarse);
        (next != now).then(|| self.set_param(p, next).ok()).flatten()
    }

    /// Another playback speed; the command, if it is another.
    pub(crate) fn set_speed(&mut self, speed: Speed) -> Option<Command> {
        (speed != self.speed).then(|| {
            self.speed = speed;
            Command::SetSpeed(speed)
        })
    }

    /// Loads `preset`'s setup (the worker sends the preset itself back with its roll).
    pub(crate) fn load(&mut self, preset: Box<Preset>) -> Command {
        self.params = preset.params();
        self.initial = preset.initial;
        self.drawn = None;
        Command::LoadPreset(preset)
    }

    /// Plays exactly this setup from t = 0 (a map cell replayed).
    pub(crate) fn play(&mut self, params: Params, initial: InitialCondition) -> Command {
        self.params = params;
        self.initial = initial;
        Command::PlaySetup(Box::new(params), initial)
    }

    /// What a saved setup says about itself when no description is typed: its base and the
    /// values changed from it, as `presets save --set` words it.
    pub(crate) fn automatic_description(&self) -> String {
        let base = (self.preset.params(), self.preset.initial);
        let changed: Vec<String> = all()
            .iter()
            .filter_map(|p| {
                let (now, was) = (p.get(&self.params, &self.initial), p.get(&base.0, &base.1));
                (now != was).then(|| format!("{}={}", p.key(), fmt_num(now)))
            })
            .collect();
        if changed.is_empty() {
            format!("The `{}` preset, saved from the explorer.", self.preset.name)
        } else {
            format!("The `{}` preset with {}.", self.preset.name, changed.join(", "))
        }
    }
}
