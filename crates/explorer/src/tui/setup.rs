//! The setup as the user has set it: the values, the playback speed and the preset they
//! came from. The user's values run ahead of the worker's: every command leaves through
//! [`UserSetup::send`], which counts it, and a snapshot's values are taken only once the worker
//! has handled every command sent ([`UserSetup::adopt`]), so an edit never flickers back to the
//! value it replaced.

use super::format::{fmt_num, fmt_range};
use super::param::Param;
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
    /// Commands sent to the worker so far (see [`Snapshot::commands_handled`]).
    commands_sent: u64,
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
            commands_sent: 0,
        }
    }

    /// Whether the setup differs from the open preset's (questions guard such changes).
    pub(crate) fn modified(&self) -> bool {
        self.params != self.preset.params()
            || (self.initial != self.preset.initial && Some(self.initial) != self.drawn)
    }

    /// Queues a command for the worker.
    pub(crate) fn send(&mut self, out: &mut Vec<Command>, c: Command) {
        self.commands_sent += 1;
        out.push(c);
    }

    /// Takes the worker's values, unless it has not seen every command yet (then the
    /// user's own values are newer).
    pub(crate) fn adopt(&mut self, s: &Snapshot) {
        if s.commands_handled >= self.commands_sent {
            self.params = s.params;
            self.initial = s.initial;
            self.speed = s.speed;
            if let RollKind::Random(_) = s.roll {
                self.drawn = Some(s.initial);
            }
        }
    }

    /// Sets `p` and tells the worker; a value outside its range, one that would start the
    /// die inside the table, or one that no body can have with the other values (a corner
    /// radius not below the smallest half size, pips too wide or too deep) is refused in
    /// words and changes nothing.
    pub(crate) fn set_param(&mut self, out: &mut Vec<Command>, p: Param, value: f64) -> Result<(), String> {
        let (mut params, mut initial) = (self.params, self.initial);
        p.set(&mut params, &mut initial, value).map_err(|e| {
            if e.limits == p.limits() {
                format!(
                    "{} is outside {} {}",
                    fmt_num(value),
                    fmt_range(p),
                    p.limits().unit
                )
            } else {
                // The value is in range, but the die would start inside the table.
                format!(
                    "{}: corner in the table; ≥ {} cm",
                    fmt_num(value),
                    fmt_num(e.limits.min)
                )
            }
        })?;
        if let Err(e) = params.validate() {
            return Err(match e.detail.as_deref() {
                Some(Detail::Refused(why)) => format!("{}: {why}", fmt_num(value)),
                _ => e.to_string(),
            });
        }
        (self.params, self.initial) = (params, initial);
        self.send(out, Command::SetParam(p.scan_key(), value));
        Ok(())
    }

    /// `p` a step up or down (`coarse`: a big step), inside its range.
    pub(crate) fn nudge(&mut self, out: &mut Vec<Command>, p: Param, steps: i32, coarse: bool) {
        let now = p.get(&self.params, &self.initial);
        let next = p.nudged(now, steps, coarse);
        if next != now {
            let _ = self.set_param(out, p, next);
        }
    }

    pub(crate) fn set_speed(&mut self, out: &mut Vec<Command>, speed: Speed) {
        if speed != self.speed {
            self.speed = speed;
            self.send(out, Command::SetSpeed(speed));
        }
    }

    /// Loads `preset`'s setup (the worker sends the preset itself back with its roll).
    pub(crate) fn load(&mut self, out: &mut Vec<Command>, preset: Box<Preset>) {
        self.params = preset.params();
        self.initial = preset.initial;
        self.drawn = None;
        self.send(out, Command::LoadPreset(preset));
    }

    /// Plays exactly this setup from t = 0 (a map cell replayed).
    pub(crate) fn play(&mut self, out: &mut Vec<Command>, params: Params, initial: InitialCondition) {
        self.params = params;
        self.initial = initial;
        self.send(out, Command::PlaySetup(Box::new(params), initial));
    }
}
