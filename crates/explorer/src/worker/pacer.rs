//! Playback pacing: how many steps of Δt the roll owes the wall clock at a speed.
//!
//! The count is worked out from the wall time since pacing (re)started and the steps already
//! taken, never from a running sum of per-tick fractions: at speed s after a wall time w the
//! roll has taken ⌊s·w/Δt⌋ steps, so it is within one step of s·w at every tick and cannot
//! drift. A fraction of a step that is not yet due stays owed to the next tick (at 1/100× and
//! Δt = 2.4 ms a step falls due only every 14 ticks).

use super::simulator::Simulator;
use std::time::{Duration, Instant};

/// Where the worker reads the time from: the wall clock, or a test's clock.
pub(crate) trait Clock {
    fn now(&self) -> Instant;
}

/// The real wall clock.
pub(crate) struct WallClock;

impl Clock for WallClock {
    fn now(&self) -> Instant {
        Instant::now()
    }
}

/// s of wall time between snapshots while something moves.
pub(crate) const TICK: Duration = Duration::from_micros(16_667);

/// Steps per tick at "instant": a roll of the default 30 s cap finishes in one tick, and
/// the longest allowed (120 s at 10 µs) in a second or two without blocking commands.
pub(crate) const INSTANT_STEPS_PER_TICK: u64 = 200_000;

/// Ticks' worth of steps one tick may take to catch up (a late tick, a busy machine), and
/// at least [`CATCH_UP_STEPS`]. Further behind than that, the physics cannot keep up at
/// this speed and Δt: the clock slips instead of the roll racing ahead in bursts.
const CATCH_UP_TICKS: f64 = 4.0;
const CATCH_UP_STEPS: u64 = 1000;

/// Wall time mapped to steps since pacing last restarted.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pacer {
    /// The simulator's pacing epoch this pacer belongs to.
    epoch: u64,
    /// The wall instant step `taken = 0` belongs to.
    origin: Instant,
    /// Steps handed out since `origin`.
    taken: u64,
}

impl Pacer {
    pub(crate) fn new(epoch: u64, now: Instant) -> Pacer {
        Pacer {
            epoch,
            origin: now,
            taken: 0,
        }
    }

    /// Steps of `dt` s due at `now` at `factor` simulated seconds per wall second.
    pub(crate) fn due(&mut self, now: Instant, factor: f64, dt: f64) -> u64 {
        let budget = ((CATCH_UP_TICKS * TICK.as_secs_f64() * factor / dt).ceil() as u64)
            .clamp(CATCH_UP_STEPS, INSTANT_STEPS_PER_TICK);
        let exact = now.saturating_duration_since(self.origin).as_secs_f64() * factor / dt;
        // ⌊x⌋ of a quotient that should be whole (1 s · 0.01 / 0.001) may land a hair below.
        let owed = ((exact * (1.0 + 1e-12)).floor() as u64).saturating_sub(self.taken);
        if owed > budget {
            let kept = Duration::from_secs_f64((self.taken + budget) as f64 * dt / factor);
            if let Some(origin) = now.checked_sub(kept) {
                self.origin = origin;
            }
        }
        let steps = owed.min(budget);
        self.taken += steps;
        steps
    }
}

/// One tick of playback at `now`: the steps the speed asks for (at instant, a tick's worth
/// of computing). Pacing restarts whenever the simulator's epoch moved (play, pause, speed,
/// a new roll, a seek), since nothing is owed across those.
pub(crate) fn play_tick(simulator: &mut Simulator, pacer: &mut Option<Pacer>, now: Instant) -> u64 {
    let live = simulator.live();
    if !live.is_playing() {
        return 0;
    }
    let epoch = live.pacing_epoch();
    let p = match pacer {
        Some(p) if p.epoch == epoch => p,
        _ => pacer.insert(Pacer::new(epoch, now)),
    };
    let steps = match live.speed().factor() {
        None => INSTANT_STEPS_PER_TICK,
        Some(factor) => p.due(now, factor, live.params().integrator.dt),
    };
    simulator.advance_steps(steps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::worker::{Command, Speed};
    use dicesim_setup::preset::Preset;
    use std::cell::Cell;

    /// A clock the test moves by hand.
    struct TestClock {
        start: Instant,
        elapsed: Cell<Duration>,
    }

    impl Clock for TestClock {
        fn now(&self) -> Instant {
            self.start + self.elapsed.get()
        }
    }

    /// A roll that cannot end before its 120 s cap: a die thrown up at 10 m/s under a
    /// gravity of 10 cm/s² lands after 200 s.
    fn simulator(dt: f64, speed: Speed) -> Simulator {
        let mut preset = Preset::default();
        preset.integrator.dt = dt;
        preset.integrator.max_time = 120.0;
        preset.world.gravity = 10.0;
        preset.initial.height = 1000.0;
        preset.initial.velocity = [0.0, 0.0, 1000.0];
        let mut e = Simulator::new(&preset).expect("valid");
        e.handle(Command::SetSpeed(speed));
        e.handle(Command::SetPlaying(true));
        e
    }

    fn speed(label: &str) -> Speed {
        Speed::from_label(label).expect("on the ladder")
    }

    /// Ticks of uneven length (as a loaded machine delivers them) for a minute of wall time,
    /// or what the 120 s cap allows at 100× (a second: 100 s simulated); after
    /// each, the roll's step count must be exactly ⌊s·w/Δt⌋ (within one step of s·w).
    fn paced(dt: f64, label: &str) {
        let s = speed(label);
        let factor = s.factor().expect("not instant");
        let wall_s = (110.0 / factor).min(60.0);
        let mut e = simulator(dt, s);
        let clock = TestClock {
            start: Instant::now(),
            elapsed: Cell::new(Duration::ZERO),
        };
        let mut pacer = None;
        play_tick(&mut e, &mut pacer, clock.now());
        let mut tick = 0u64;
        let start_step = e.simulation().state().step;
        while clock.elapsed.get().as_secs_f64() < wall_s {
            tick += 1;
            // 12 to 21 ms, a fixed pattern: never a whole number of steps per tick.
            let jitter = Duration::from_micros(12_000 + (tick * 7_919) % 9_000);
            clock.elapsed.set(clock.elapsed.get() + jitter);
            play_tick(&mut e, &mut pacer, clock.now());
            let wall = clock.elapsed.get().as_secs_f64();
            let steps = e.simulation().state().step - start_step;
            let simulated = steps as f64 * dt;
            assert!(
                (simulated - factor * wall).abs() <= dt,
                "{label} at Δt {dt}: {steps} steps ({simulated} s) after {wall} s of wall time"
            );
        }
        let wall = clock.elapsed.get().as_secs_f64();
        let steps = e.simulation().state().step - start_step;
        assert_eq!(
            steps,
            (factor * wall / dt + 1e-9).floor() as u64,
            "{label} at Δt {dt} over {wall} s"
        );
    }

    #[test]
    fn a_hundredth_at_one_millisecond_is_ten_steps_a_second_for_a_minute() {
        paced(1e-3, "1/100×");
        let mut e = simulator(1e-3, speed("1/100×"));
        let start = Instant::now();
        let mut pacer = None;
        play_tick(&mut e, &mut pacer, start);
        for second in 1..=10u64 {
            play_tick(&mut e, &mut pacer, start + Duration::from_secs(second));
            assert_eq!(e.simulation().state().step, 10 * second);
        }
    }

    #[test]
    fn every_speed_keeps_to_the_wall_clock_at_one_millisecond() {
        for label in ["1/100×", "1/20×", "1×", "100×"] {
            paced(1e-3, label);
        }
    }

    #[test]
    fn every_speed_keeps_to_the_wall_clock_at_two_point_four_milliseconds() {
        for label in ["1/100×", "1/20×", "1×", "100×"] {
            paced(2.4e-3, label);
        }
    }

    #[test]
    fn pausing_owes_nothing_and_a_hopeless_lag_slips_instead_of_bursting() {
        let mut e = simulator(1e-3, speed("1×"));
        let start = Instant::now();
        let mut pacer = None;
        play_tick(&mut e, &mut pacer, start);
        play_tick(&mut e, &mut pacer, start + Duration::from_secs(1));
        assert_eq!(e.simulation().state().step, 1000);
        e.handle(Command::SetPlaying(false));
        e.handle(Command::SetPlaying(true));
        // Ten paused seconds later: pacing starts again, nothing is owed.
        play_tick(&mut e, &mut pacer, start + Duration::from_secs(11));
        assert_eq!(e.simulation().state().step, 1000);
        // A stall of a whole minute: at most the catch-up budget, then on at speed.
        play_tick(&mut e, &mut pacer, start + Duration::from_secs(71));
        let after_stall = e.simulation().state().step;
        assert_eq!(after_stall, 1000 + CATCH_UP_STEPS);
        play_tick(&mut e, &mut pacer, start + Duration::from_secs(72));
        assert_eq!(e.simulation().state().step, after_stall + 1000);
    }
}
