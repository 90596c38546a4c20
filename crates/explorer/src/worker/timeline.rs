//! The roll's history, so it can be stepped back and scrubbed: keyframes (whole copies of
//! the die's and the twin's simulations) every few steps, and the impacts seen so far.
//!
//! Any step n is reached by restoring the last keyframe at or before n and stepping on from
//! there; the model is deterministic, so that state is bit for bit the one the roll had.
//! Keyframes are spaced so a roll keeps at most [`MAX_KEYFRAMES`] of them, whatever its
//! length and Δt (a capped roll at Δt = 10 µs has 3 million steps and is re-stepped at most
//! 1 500 steps to reach any of them).

use dicesim_physics::{Impacts, Roll};
use nalgebra::Vector3;

/// Most regular keyframes one roll keeps (each a copy of one or two simulations, about a
/// kilobyte each).
pub(crate) const MAX_KEYFRAMES: u64 = 2_000;

/// Most impacts the timeline marks; a die chattering on the table for the whole time cap
/// could otherwise start millions.
const MAX_IMPACTS: usize = 10_000;

/// The simulator's roll state at one step: enough to carry on from there exactly.
#[derive(Debug, Clone)]
pub(crate) struct Keyframe {
    /// Steps of Δt since the roll started.
    pub(crate) position: u64,
    pub(crate) sim: Roll,
    pub(crate) twin: Option<Roll>,
    /// Whether a corner had touched the table by then.
    pub(crate) touched: bool,
}

#[derive(Debug, Clone)]
pub(crate) struct Timeline {
    /// Steps between regular keyframes.
    every: u64,
    /// Sorted by position; the first is the roll's start. Besides the regular ones, a
    /// keyframe marks where a table value changed mid-roll (re-stepping across it must
    /// use the new value).
    keyframes: Vec<Keyframe>,
    /// The furthest step computed: beyond it nothing is known yet.
    pub(crate) furthest: u64,
    /// Whether the roll ended at `furthest`.
    pub(crate) ended: bool,
    /// The step at which the stopping rule decided the face, once computed (the die plays
    /// on past it to rest).
    pub(crate) decided: Option<u64>,
    /// Steps at which an impact began (the physics' one definition, [`Impacts`]), in order.
    pub(crate) impacts: Vec<u64>,
    /// cm, the centre of mass at each of `impacts`: where the die was when it began.
    impact_centres: Vec<Vector3<f64>>,
    /// cm, the centre at the start if the die starts on the table (its first contact
    /// begins there, with no impact).
    start_centre: Option<Vector3<f64>>,
    /// The contact of the computed steps, as far as the frontier.
    contact: Impacts,
    /// Steps at which a table value was changed mid-roll, in order: the one record of
    /// edits that the timeline strip and the plot both mark.
    pub(crate) edits: Vec<u64>,
    /// The impacts or the edits changed since the UI last got them.
    pub(crate) impacts_changed: bool,
}

impl Timeline {
    /// A timeline for a roll of at most `max_steps` steps, starting at `start`.
    pub(crate) fn new(max_steps: u64, start: Keyframe) -> Timeline {
        let contact = Impacts::new(start.sim.in_contact());
        let start_centre = start.sim.in_contact().then(|| start.sim.position());
        Timeline {
            every: max_steps.div_ceil(MAX_KEYFRAMES).max(1),
            keyframes: vec![start],
            furthest: 0,
            ended: false,
            decided: None,
            impacts: Vec::new(),
            impact_centres: Vec::new(),
            start_centre,
            contact,
            edits: Vec::new(),
            impacts_changed: true,
        }
    }

    /// Whether the step after `position` is new (not yet computed).
    pub(crate) fn at_frontier(&self, position: u64) -> bool {
        position >= self.furthest
    }

    /// Whether step `position` is to be kept as a keyframe.
    pub(crate) fn keyframe_due(&self, position: u64) -> bool {
        position.is_multiple_of(self.every)
    }

    /// A newly computed step, `in_contact` or clear of the table with its centre of mass at
    /// `centre` (cm): the frontier moves on, its keyframe (when one is due) is kept, an
    /// impact is marked where one begins.
    pub(crate) fn recorded(
        &mut self,
        position: u64,
        keyframe: Option<Keyframe>,
        (in_contact, centre): (bool, Vector3<f64>),
        ended: bool,
    ) {
        self.furthest = position;
        self.ended = ended;
        self.keyframes.extend(keyframe);
        if self.contact.observe(in_contact) && self.impacts.len() < MAX_IMPACTS {
            self.impacts.push(position);
            self.impact_centres.push(centre);
            self.impacts_changed = true;
        }
    }

    /// cm, where the centre of mass was when the contact going on at step `position` began:
    /// at its impact, or at the start for a die set down on the table.
    pub(crate) fn contact_began(&self, position: u64) -> Option<Vector3<f64>> {
        match self.impacts.partition_point(|&p| p <= position) {
            0 => self.start_centre,
            i => self.impact_centres.get(i - 1).copied(),
        }
    }

    /// The keyframe to carry on from to reach `target`: the last at or before it.
    pub(crate) fn before(&self, target: u64) -> &Keyframe {
        let i = self.keyframes.partition_point(|k| k.position <= target);
        &self.keyframes[i.saturating_sub(1)]
    }

    /// The keyframe exactly at `position`, if one was kept.
    pub(crate) fn at(&self, position: u64) -> Option<&Keyframe> {
        self.keyframes
            .binary_search_by_key(&position, |k| k.position)
            .ok()
            .map(|i| &self.keyframes[i])
    }

    /// The roll goes on differently from `now` (a table value changed): what was computed
    /// after it is forgotten, and `now` is kept as a keyframe.
    pub(crate) fn diverge(&mut self, now: Keyframe) {
        let in_contact = now.sim.in_contact();
        let position = now.position;
        self.keyframes.retain(|k| k.position < position);
        self.keyframes.push(now);
        self.furthest = position;
        self.ended = false;
        self.decided = self.decided.filter(|&d| d <= position);
        let kept = self.impacts.partition_point(|&p| p <= position);
        if kept < self.impacts.len() {
            self.impacts.truncate(kept);
            self.impact_centres.truncate(kept);
            self.impacts_changed = true;
        }
        // A contact going on across the change is the same impact.
        self.contact = Impacts::new(in_contact);
        // Edits after this one were of the future just forgotten; one here replaces them.
        // A change at step 0 is no mid-roll edit: the whole roll has the new value.
        self.edits.retain(|&p| p < position);
        if position > 0 {
            self.edits.push(position);
        }
        self.impacts_changed = true;
    }

    /// How many keyframes are kept (for tests of the memory bound).
    #[cfg(test)]
    pub(crate) fn keyframes(&self) -> usize {
        self.keyframes.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::worker::{Command, Simulator};
    use dicesim_setup::keys::ScanKey;
    use dicesim_setup::preset::Preset;

    /// Bits of everything the state holds (`==` on floats would let −0 pass for +0).
    fn bits(sim: &dicesim_physics::Simulation) -> String {
        format!("{:?} {:?} {:?}", sim.state(), sim.energy_ledger(), sim.outcome())
    }

    /// The state after `n` steps from the start, stepped straight through.
    fn stepped(preset: &Preset, n: u64) -> String {
        let mut e = Simulator::new(preset).expect("valid");
        e.advance_steps(n);
        bits(e.simulation())
    }

    #[test]
    fn seeking_anywhere_gives_the_state_stepping_there_gives() {
        let preset = Preset::default();
        let mut e = Simulator::new(&preset).expect("valid");
        e.run_to_end();
        let end = e.timeline().furthest;
        assert!(e.timeline().ended && end > 500, "{end}");
        assert!(!e.timeline().impacts.is_empty(), "the paper's roll bounces");
        let every = preset.params().max_steps().div_ceil(MAX_KEYFRAMES);
        for n in [
            end / 2,
            0,
            1,
            every - 1,
            every,
            every + 1,
            7 * every + 3,
            end - 1,
            end,
            3,
        ] {
            e.handle(Command::Seek(n));
            assert_eq!(e.position(), n);
            assert_eq!(bits(e.simulation()), stepped(&preset, n), "seek to {n}");
        }
        e.handle(Command::Seek(u64::MAX));
        assert_eq!(e.position(), end, "End stops at the roll's end");
        assert_eq!(bits(e.simulation()), stepped(&preset, end));
    }

    #[test]
    fn stepping_back_then_playing_on_is_the_same_roll_and_records_nothing_twice() {
        let preset = Preset::default();
        let mut e = Simulator::new(&preset).expect("valid");
        e.advance_steps(500);
        let _ = e.snapshot();
        e.handle(Command::StepBack(1));
        assert_eq!(e.position(), 499);
        assert_eq!(bits(e.simulation()), stepped(&preset, 499));
        e.handle(Command::StepBack(200));
        e.handle(Command::SetPlaying(true));
        e.advance_steps(400);
        assert_eq!(e.position(), 699);
        assert_eq!(bits(e.simulation()), stepped(&preset, 699));
        let s = e.snapshot();
        // Samples only for the 199 steps past the old frontier of 500, never for 300..500.
        assert!(
            s.history.iter().all(|h| h.time_s > 0.5 - 1e-9),
            "{:?}",
            s.history.first()
        );
        assert!(!s.history.is_empty());
        assert_eq!(s.timeline.furthest, 699);
    }

    #[test]
    fn a_table_change_while_stepped_back_forgets_the_old_future() {
        let preset = Preset::default();
        let mut e = Simulator::new(&preset).expect("valid");
        e.advance_steps(800);
        e.handle(Command::Seek(300));
        let _ = e.snapshot();
        let key = ScanKey::named("ground.friction").expect("a scan key");
        e.handle(Command::SetParam(key, 0.2));
        let s = e.snapshot();
        assert_eq!(s.history_cut, Some(e.simulation().state().time_s));
        assert_eq!(s.timeline.furthest, 300);
        e.handle(Command::Seek(600));
        // The same roll as one whose friction changed at step 300 while playing straight on.
        let mut straight = Simulator::new(&preset).expect("valid");
        straight.advance_steps(300);
        straight.handle(Command::SetParam(key, 0.2));
        straight.advance_steps(300);
        assert_eq!(bits(e.simulation()), bits(straight.simulation()));
        // And back across the change: the old friction before it, the new after.
        e.handle(Command::Seek(100));
        assert_eq!(bits(e.simulation()), stepped(&preset, 100));
        e.handle(Command::Seek(600));
        assert_eq!(bits(e.simulation()), bits(straight.simulation()));
    }

    #[test]
    fn memory_stays_bounded_for_three_million_steps() {
        let mut preset = Preset::default();
        preset.integrator.dt = 1e-5;
        preset.integrator.max_time = 30.0;
        let max_steps = preset.params().max_steps();
        assert_eq!(max_steps, 3_000_000);
        let mut e = Simulator::new(&preset).expect("valid");
        e.run_to_end();
        let end = e.timeline().furthest;
        assert!(
            e.timeline().keyframes() as u64 <= MAX_KEYFRAMES + 1,
            "{} keyframes for {end} steps",
            e.timeline().keyframes()
        );
        e.handle(Command::Seek(end / 3));
        assert_eq!(bits(e.simulation()), stepped(&preset, end / 3));
    }
}
