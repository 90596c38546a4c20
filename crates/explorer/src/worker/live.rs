//! The live roll: the die (and its chaos twin) stepped in lock-step along a timeline that
//! can be stepped back and scrubbed, its energy history thinned to what a plot needs, and
//! the pacing epoch that tells the pacer when wall time and simulated time part. It knows
//! nothing of the outcome table, the preset or the jobs: a random roll that ends is handed
//! to the simulator once ([`LiveRoll::take_finished`]).

use super::play_on::played_out;
use super::protocol::{
    DieState, EnergySample, Notice, Phase, RollEvent, RollKind, TimelineSnapshot, TwinSnapshot,
};
use super::timeline::{Keyframe, Timeline};
use super::twin_die::Twin;
use dicesim_experiment::{RollRecord, ScanKey};
use dicesim_physics::{InitialCondition, Params, Roll, RollingDie, Status};
use dicesim_setup::preset::Speed;
use dicesim_setup::registry::Role;

/// At most this many energy samples per roll: longer rolls keep each term's peak over a
/// stride of steps, so impact spikes survive the thinning.
const HISTORY_SAMPLES: u64 = 40_000;

/// The roll's energy samples not yet sent, each term's peak over a stride of steps.
#[derive(Debug, Default)]
struct EnergyTrace {
    /// Steps one sample covers.
    stride: u64,
    /// Each term's peak over the steps since the last sample.
    peak: Option<EnergySample>,
    peak_steps: u64,
    /// Samples since the last snapshot.
    fresh: Vec<EnergySample>,
    /// A new roll started: earlier samples belong to another roll.
    reset: bool,
    /// s: samples after this time belong to a future that changed (a table value mid-roll).
    cut: Option<f64>,
}

impl EnergyTrace {
    /// A new roll of at most `max_steps` steps, from its first sample.
    fn restart(&mut self, max_steps: u64, first: EnergySample) {
        self.stride = max_steps.div_ceil(HISTORY_SAMPLES).max(1);
        self.peak = None;
        self.peak_steps = 0;
        self.fresh.clear();
        self.reset = true;
        self.fresh.push(first);
    }

    /// A step's sample: kept as each term's peak until a stride is full or the roll ends.
    fn record(&mut self, s: EnergySample, ended: bool) {
        let peak = match self.peak {
            None => s,
            Some(p) => EnergySample {
                time_s: s.time_s,
                energy: p.energy.max_each(&s.energy),
                total: p.total.max(s.total),
                quantities: std::array::from_fn(|i| {
                    let (a, b) = (p.quantities[i], s.quantities[i]);
                    if b.abs() > a.abs() { b } else { a }
                }),
            },
        };
        self.peak_steps += 1;
        if self.peak_steps >= self.stride || ended {
            self.fresh.push(peak);
            self.peak = None;
            self.peak_steps = 0;
        } else {
            self.peak = Some(peak);
        }
    }

    /// The roll goes on from here as another one: samples after `time_s` are forgotten
    /// (`forget`, when stepped back) and the peak starts afresh.
    fn diverge(&mut self, time_s: f64, forget: bool) {
        if forget {
            self.cut = Some(time_s);
        }
        self.peak = None;
        self.peak_steps = 0;
    }

    /// What a snapshot sends: the fresh samples, whether to clear first, where to cut.
    fn take(&mut self) -> (Vec<EnergySample>, bool, Option<f64>) {
        (
            std::mem::take(&mut self.fresh),
            std::mem::take(&mut self.reset),
            self.cut.take(),
        )
    }
}

pub(crate) struct LiveRoll {
    pub(super) params: Params,
    pub(super) initial: InitialCondition,
    pub(super) sim: Roll,
    /// Steps of Δt since the roll started: where on its timeline the roll on screen is.
    position: u64,
    timeline: Timeline,
    pub(super) roll: RollKind,
    start_face: u8,
    /// Whether a corner has touched the ground since the roll started.
    touched: bool,
    /// The chaos twin, if one rolls beside the die.
    pub(super) twin: Option<Twin>,
    trace: EnergyTrace,
    /// A random roll that ended and was not yet handed over; `counted` once handed, so a
    /// replay never enters the table twice.
    finished: Option<RollRecord>,
    counted: bool,
    pub(super) playing: bool,
    pub(super) speed: Speed,
    /// A table value changed mid-roll: the roll on screen is no longer the one its start
    /// gives, so a re-roll from t = 0 (an export, a replay) differs from what was shown.
    pub(super) changed_mid_roll: bool,
    /// Changes whenever the mapping from wall time to simulated time must restart.
    pacing_epoch: u64,
}

impl LiveRoll {
    /// The roll from `initial` at t = 0, paused (values checked by the caller).
    pub(crate) fn new(
        params: Params,
        initial: InitialCondition,
        twin: Option<Twin>,
        speed: Speed,
    ) -> LiveRoll {
        let sim = Roll::new_unchecked(&params, &initial);
        let timeline = Timeline::new(
            1,
            Keyframe {
                position: 0,
                sim: sim.clone(),
                twin: None,
                touched: false,
            },
        );
        let mut live = LiveRoll {
            params,
            initial,
            sim,
            position: 0,
            timeline,
            roll: RollKind::Preset,
            start_face: 0,
            touched: false,
            twin,
            trace: EnergyTrace::default(),
            finished: None,
            counted: false,
            playing: false,
            speed,
            changed_mid_roll: false,
            pacing_epoch: 0,
        };
        live.restart(RollKind::Preset);
        live
    }

    pub(crate) fn params(&self) -> &Params {
        &self.params
    }

    #[cfg(test)]
    pub(crate) fn simulation(&self) -> &Roll {
        &self.sim
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

    /// s, simulated: how far the roll has got (the later of the die and its twin, since
    /// the one still rolling keeps the clock going).
    pub(crate) fn time_s(&self) -> f64 {
        let die = self.sim.time_s();
        self.twin.as_ref().map_or(die, |t| die.max(t.sim.time_s()))
    }

    /// Whether the roll on screen has ended: the die's, and its twin's if there is one.
    pub(crate) fn roll_over(&self) -> bool {
        played_out(&self.sim) && self.twin.as_ref().is_none_or(Twin::ended)
    }

    pub(crate) fn is_playing(&self) -> bool {
        self.playing
    }

    pub(crate) fn speed(&self) -> Speed {
        self.speed
    }

    pub(crate) fn pacing_epoch(&self) -> u64 {
        self.pacing_epoch
    }

    pub(crate) fn set_speed(&mut self, speed: Speed) {
        self.speed = speed;
        self.pacing_epoch += 1;
    }

    pub(crate) fn set_playing(&mut self, play: bool) {
        if play && self.roll_over() {
            // Resuming a finished roll means watching it again.
            self.restart(self.roll);
        }
        self.playing = play;
        self.pacing_epoch += 1;
    }

    /// Pauses, then `n` steps on; at the end of the roll nothing moves and the notice says why.
    pub(crate) fn step_forward(&mut self, n: u64) -> Option<Notice> {
        self.playing = false;
        self.pacing_epoch += 1;
        if self.roll_over() {
            return Some(Notice::RollEnded);
        }
        self.advance_steps(n);
        None
    }

    pub(crate) fn step_back(&mut self, n: u64) {
        self.seek(self.position.saturating_sub(n));
    }

    /// Another preset's roll: its values, its twin and speed, from t = 0, paused. The pacing
    /// epoch goes on counting, so the pacer never mistakes the new roll for the old.
    pub(crate) fn load(
        &mut self,
        params: Params,
        initial: InitialCondition,
        twin: Option<Twin>,
        speed: Speed,
    ) {
        (self.params, self.initial) = (params, initial);
        self.twin = twin;
        self.speed = speed;
        self.playing = false;
        self.restart(RollKind::Preset);
    }

    /// Another start: random roll `kind`, an edit, a replayed cell; plays it from t = 0.
    pub(crate) fn play_from(&mut self, params: Params, initial: InitialCondition, kind: RollKind) {
        (self.params, self.initial) = (params, initial);
        if let RollKind::Random(_) = kind {
            self.counted = false;
        }
        self.restart(kind);
        self.playing = true;
    }

    /// The same start again from t = 0, playing.
    pub(crate) fn replay(&mut self) {
        self.restart(self.roll);
        self.playing = true;
    }

    /// A twin (`None`: no twin); with one, both dice start again, playing.
    pub(crate) fn set_twin(&mut self, twin: Option<Twin>) {
        let on = twin.is_some();
        self.twin = twin;
        if on {
            self.restart(self.roll);
            self.playing = true;
        }
    }

    /// A new value: one that acts mid-roll (the ground's) changes the running roll from
    /// here, others restart it (a new initial condition is a roll of its own).
    pub(crate) fn set_param(&mut self, key: &ScanKey, value: f64) -> Result<(), Notice> {
        let (mut params, mut initial) = (self.params, self.initial);
        key.set_checked(&mut params, &mut initial, value)
            .map_err(|e| Notice::Said(e.to_string()))?;
        self.params = params;
        self.initial = initial;
        // At step 0 there is no "mid" yet: the whole roll has the new value, as a fresh one.
        if key.spec.acts_mid_roll && self.sim.outcome().is_none() && self.position > 0 {
            let refused = self.sim.set_ground(params.ground).err();
            self.changed_mid_roll = true;
            // The twin feels the same table (with B's own values, for a parameter twin).
            if let Some(twin) = &mut self.twin {
                twin.set_ground(&params, &initial);
            }
            // From here on the roll is another one: its computed future is forgotten.
            let stepped_back = !self.timeline.at_frontier(self.position);
            self.trace.diverge(self.sim.time_s(), stepped_back);
            self.timeline.diverge(self.keyframe());
            if let Some(e) = refused {
                return Err(Notice::Said(e.to_string()));
            }
        } else {
            let kind = if key.spec.role == Role::Initial {
                RollKind::Edited
            } else {
                self.roll
            };
            self.restart(kind);
        }
        Ok(())
    }

    /// Places the die at the current initial condition; the history starts again.
    pub(crate) fn restart(&mut self, kind: RollKind) {
        self.roll = kind;
        self.changed_mid_roll = false;
        self.sim = Roll::new_unchecked(&self.params, &self.initial);
        self.start_face = self.sim.start_face();
        self.touched = self.sim.in_contact();
        self.trace.restart(self.params.max_steps(), self.sample());
        if let Some(difference) = self.twin.as_ref().map(|t| t.difference.clone()) {
            // The difference was checked when the twin was made.
            self.twin = Twin::new(&self.params, &self.initial, difference).ok();
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
    pub(crate) fn seek(&mut self, target: u64) {
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

    /// Pauses at the step where `event` happens: the next impact after the step on screen,
    /// the last one before it, or where the face was decided, computing on as far as it
    /// takes. Where there is none, the roll stays where it was and the notice says why.
    pub(crate) fn seek_event(&mut self, event: RollEvent) -> Option<Notice> {
        let from = self.position;
        let dt = self.params.integrator.dt;
        let at = |n: u64| format!("{:.3} s", n as f64 * dt);
        let found = match event {
            RollEvent::PreviousImpact => self.timeline.impacts.iter().rev().find(|&&p| p < from).copied(),
            RollEvent::NextImpact => self.compute_until(|t| t.impacts.iter().find(|&&p| p > from).copied()),
            RollEvent::FaceDecided => self.compute_until(|t| t.decided),
        };
        let Some(step) = found else {
            self.seek(from);
            let end = at(self.timeline.furthest);
            return Some(Notice::Said(match event {
                RollEvent::PreviousImpact => format!("no impact before {}", at(from)),
                RollEvent::NextImpact => format!("no impact after {}: the roll ends at {end}", at(from)),
                RollEvent::FaceDecided => format!("no face was decided: the roll ended at {end} unsettled"),
            }));
        };
        self.seek(step);
        let impact = self.timeline.impacts.partition_point(|&p| p < step) + 1;
        Some(Notice::Said(match event {
            RollEvent::FaceDecided => {
                format!(
                    "face decided at {} (step {step}): from here on it cannot change",
                    at(step)
                )
            }
            _ => format!(
                "impact {impact} begins at {} (step {step}): the first step in contact",
                at(step)
            ),
        }))
    }

    /// The first step `found` names, computing the roll on from its frontier until it names
    /// one or the roll ends.
    fn compute_until(&mut self, found: impl Fn(&Timeline) -> Option<u64>) -> Option<u64> {
        if let Some(step) = found(&self.timeline) {
            return Some(step);
        }
        if self.timeline.ended {
            return None;
        }
        self.seek(self.timeline.furthest);
        while !self.roll_over() {
            self.step();
            if let Some(step) = found(&self.timeline) {
                return Some(step);
            }
        }
        None
    }

    fn sample(&self) -> EnergySample {
        EnergySample::of(&self.sim)
    }

    /// One step with its bookkeeping, the die and its twin in lock-step; returns whether
    /// the roll can go on (a die whose roll has ended waits for the other).
    fn step(&mut self) -> bool {
        // Steps already on the timeline are re-stepped to show them, not recorded again.
        let new = self.timeline.at_frontier(self.position);
        let die_rolling = !played_out(&self.sim);
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
                twin.stepped(&self.sim, self.trace.stride, done);
            }
            let position = self.position;
            let keyframe = self.timeline.keyframe_due(position).then(|| self.keyframe());
            self.timeline.recorded(
                position,
                keyframe,
                (self.sim.in_contact(), self.sim.position()),
                done,
            );
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

    /// One step of the die; a `new` step also gives its energy sample and, at the end of
    /// a random roll not yet counted, its record for the outcome table.
    fn step_die(&mut self, new: bool) {
        let ended = self.sim.advance();
        self.touched |= self.sim.in_contact();
        if !new {
            return;
        }
        self.trace
            .record(self.sample(), ended.is_some() || played_out(&self.sim));
        if let Some(outcome) = ended.filter(|o| o.status == Status::Settled) {
            self.timeline.decided = Some(outcome.steps);
        }
        if let Some(outcome) = ended
            && let RollKind::Random(id) = self.roll
            && !self.counted
        {
            self.counted = true;
            self.finished = Some(RollRecord {
                id,
                initial: self.initial,
                outcome,
                start_face: self.start_face,
            });
        }
    }

    /// A random roll that has ended since the last call, for the outcome table (once).
    pub(crate) fn take_finished(&mut self) -> Option<RollRecord> {
        self.finished.take()
    }

    /// Up to `n` steps; stops at the end of the roll. Returns the steps taken.
    pub(crate) fn advance_steps(&mut self, n: u64) -> u64 {
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
        if self.pressed_hard() {
            Phase::InContact
        } else {
            Phase::Rolling
        }
    }

    /// Pressed hard into the table: the ground pushes far harder than it takes to carry the
    /// die (the squeeze of an impact, which the timeline marks where it begins).
    fn pressed_hard(&self) -> bool {
        if !self.sim.in_contact() || self.sim.outcome().is_some() {
            return false;
        }
        let push: f64 = RollingDie::point_forces(&self.sim).iter().map(|f| f.z).sum();
        push > 2.0 * self.params.total_mass() * self.params.world.gravity
    }

    /// The die as drawn now, with its step (the later of the die's and the twin's).
    pub(crate) fn die(&self) -> (DieState, u64) {
        let own = self.sim.steps();
        let step = self.twin.as_ref().map_or(own, |t| own.max(t.sim.steps()));
        let mut die = DieState::of(&self.sim, self.start_face);
        // Slid since the contact began: along the table (its plane is x-y, gravity tilted
        // for an incline), while a corner is in it.
        die.slid_cm = self
            .sim
            .in_contact()
            .then(|| self.timeline.contact_began(self.position))
            .flatten()
            .map(|from| (die.centre - from).xy().norm());
        (die, step)
    }

    /// The energy samples since the last call: (samples, clear first, cut after this time).
    pub(crate) fn take_history(&mut self) -> (Vec<EnergySample>, bool, Option<f64>) {
        self.trace.take()
    }

    /// Where the roll is on its timeline (the impacts only when they changed).
    pub(crate) fn timeline_snapshot(&mut self) -> TimelineSnapshot {
        TimelineSnapshot {
            decided: self.timeline.decided,
            position: self.position,
            furthest: self.timeline.furthest,
            ended: self.timeline.ended,
            edits: self.timeline.impacts_changed.then(|| self.timeline.edits.clone()),
            impacts: std::mem::take(&mut self.timeline.impacts_changed)
                .then(|| self.timeline.impacts.clone()),
        }
    }

    pub(crate) fn twin_snapshot(&mut self) -> Option<TwinSnapshot> {
        match &mut self.twin {
            Some(t) => Some(t.snapshot(&self.sim)),
            None => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::worker::{Command, Phase, Simulator};
    use dicesim_physics::Simulation;
    use dicesim_setup::preset::Preset;

    /// Bits of the die's state (`==` on floats would let −0 pass for +0).
    fn bits(sim: &Simulation) -> String {
        format!("{:?} {:?}", sim.state(), sim.outcome())
    }

    fn at_rest(energy: dicesim_physics::Energy, stop_threshold: f64) -> bool {
        energy.kinetic() < 0.01 * stop_threshold
    }

    #[test]
    fn a_settled_die_plays_on_to_rest_and_its_data_end_at_the_stop() {
        let preset = Preset::default();
        // The roll as the physics alone gives it, stopped by its rule.
        let mut plain = Simulation::new(&preset.params(), &preset.initial).expect("valid");
        let outcome = plain.run_to_end();
        assert_eq!(outcome.status, Status::Settled);
        assert!(
            !at_rest(plain.energy(), plain.stop_threshold()),
            "the paper's die is still moving when its face is decided"
        );

        let mut e = Simulator::new(&preset).expect("valid");
        e.run_to_end();
        let end = e.timeline().furthest;
        assert_eq!(e.timeline().decided, Some(outcome.steps));
        assert!(
            end > outcome.steps,
            "played on: {end} steps, decided at {}",
            outcome.steps
        );
        assert_eq!(e.phase(), Phase::Ended(outcome), "the outcome is the stop's");
        // It ends at the first step at rest (or 2 s on), no earlier, no later.
        let rest_or_late = |s: &Simulation| {
            at_rest(s.energy(), s.stop_threshold()) || s.state().time_s >= outcome.time_s + 2.0
        };
        assert!(rest_or_late(e.simulation()));
        e.handle(Command::Seek(end - 1));
        assert!(!rest_or_late(e.simulation()), "one step earlier it still moved");
        // Up to the stop, the bits are the plain roll's.
        e.handle(Command::Seek(outcome.steps));
        assert_eq!(bits(e.simulation()), bits(&plain));
        // The export rolls to the stop only: one row per step from t = 0 to it.
        let dir = tempfile::tempdir().expect("temp dir");
        e.handle(Command::Export {
            dir: dir.path().to_path_buf(),
            log_scale: false,
        });
        e.run_export_here();
        let notice = e.snapshot().notice.expect("a notice");
        let words = notice.said().expect("words");
        assert!(words.contains(&format!("{} rows", outcome.steps + 1)), "{words}");
    }

    #[test]
    fn a_random_roll_enters_the_table_with_the_stops_outcome() {
        let preset = Preset::default();
        let mut e = Simulator::new(&preset).expect("valid");
        e.handle(Command::RandomRoll);
        e.run_to_end();
        let table = e.snapshot().table.expect("the table changed");
        let r = table.last.front().copied().expect("the roll is in it");
        let plain = Simulation::new(&preset.params(), &r.initial)
            .expect("valid")
            .run_to_end();
        assert_eq!(r.outcome, plain);
        assert_eq!(table.rolls(), 1);
    }

    #[test]
    fn a_roll_that_does_not_settle_ends_where_it_stops() {
        let preset = Preset::default()
            .with_overrides(&["ground.stiffness=2e7"])
            .expect("valid overrides");
        let mut e = Simulator::new(&preset).expect("valid");
        e.run_to_end();
        let Phase::Ended(o) = e.phase() else {
            panic!("ended")
        };
        assert_ne!(o.status, Status::Settled, "{o:?}");
        assert_eq!(e.timeline().furthest, o.steps, "no playing on");
        assert_eq!(e.timeline().decided, None);
    }
}
