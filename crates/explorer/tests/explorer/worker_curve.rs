//! The twin's predictability curve through the worker: it starts with the twin, fills in,
//! and ends equal to what `dicesim predict` computes for the same setup and seed, on any
//! thread count; a changed setup restarts it under a new generation, the twin turned off
//! stops it, and quitting does not wait for it.

use dicesim_experiment::predict::{PredictCurve, run_prediction};
use dicesim_experiment::{RunOptions, ScanKey};
use dicesim_explorer::worker::{
    CURVE_STARTS, Command, CurveSetup, CurveState, CurveUpdate, Simulator, Snapshot, Worker,
};
use dicesim_setup::preset::Preset;
use std::sync::atomic::AtomicBool;
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::Duration;

/// Generous: only a hung worker takes this long.
const PATIENCE: Duration = Duration::from_secs(60);

fn spawn(preset: &Preset) -> (Worker, Receiver<Snapshot>) {
    let (tx, rx) = channel();
    let worker = Worker::spawn(Simulator::new(preset).expect("valid"), tx);
    (worker, rx)
}

/// The next snapshot that carries a curve update, with it.
fn next_curve(rx: &Receiver<Snapshot>) -> (Snapshot, CurveUpdate) {
    loop {
        let mut s = rx.recv_timeout(PATIENCE).expect("the worker keeps reporting");
        if let Some(c) = s.curve.take() {
            return (s, c);
        }
    }
}

/// Snapshots up to the one answering the `n`th command, each passed to `check`.
fn until_handled(rx: &Receiver<Snapshot>, n: u64, mut check: impl FnMut(&Snapshot)) -> Snapshot {
    loop {
        let s = rx.recv_timeout(PATIENCE).expect("snapshot");
        check(&s);
        if s.commands_handled == n {
            return s;
        }
    }
}

/// Curve updates up to the complete curve (or a failure), checking that they grow.
fn until_complete(rx: &Receiver<Snapshot>, generation: u64) -> (Vec<CurveUpdate>, PredictCurve) {
    let mut partial = Vec::new();
    loop {
        let (_, u) = next_curve(rx);
        assert_eq!(u.generation, generation, "nothing of another generation");
        assert_eq!(u.count, CURVE_STARTS);
        match &u.state {
            CurveState::Complete(c) => return (partial, c.clone()),
            CurveState::Computing(Some(c)) => {
                let before = partial.last().map_or(0, |p: &CurveUpdate| match &p.state {
                    CurveState::Computing(Some(c)) => c.starts,
                    _ => 0,
                });
                assert!(
                    c.starts > before && c.starts < CURVE_STARTS,
                    "{} after {before}",
                    c.starts
                );
                partial.push(u);
            }
            other => panic!("{other:?}"),
        }
    }
}

/// What `dicesim predict` computes for `setup`, on one thread.
fn expected(setup: &CurveSetup) -> PredictCurve {
    let p = run_prediction(
        &setup.params,
        &setup.ranges,
        &setup.base,
        &setup.spec(),
        &RunOptions {
            jobs: 1,
            ..RunOptions::default()
        },
        &AtomicBool::new(false),
        &mut |_| {},
    )
    .expect("the experiment runs");
    p.curves.into_iter().next().expect("one curve")
}

fn setup_of(preset: &Preset) -> CurveSetup {
    CurveSetup {
        params: preset.params(),
        ranges: preset.random,
        base: preset.initial,
    }
}

/// Equal to the last bit, not merely within rounding.
fn assert_same_bits(a: &PredictCurve, b: &PredictCurve) {
    assert_eq!(a, b);
    let bits = |c: &PredictCurve| -> Vec<u64> {
        c.points
            .iter()
            .flat_map(|p| [p.same_share, p.interval[0], p.interval[1]])
            .chain([c.chance, c.half])
            .map(f64::to_bits)
            .collect()
    };
    assert_eq!(bits(a), bits(b));
}

#[test]
fn the_curve_fills_in_and_ends_equal_to_the_experiment_bit_for_bit() {
    let preset = Preset::default();
    let (worker, rx) = spawn(&preset);
    worker.send(Command::SetTwin(Some(1e-9)));
    // The snapshot answering the twin says a curve has started, empty.
    let (s, first) = next_curve(&rx);
    assert_eq!(s.commands_handled, 1);
    assert!(s.twin.is_some());
    assert_eq!(first.state, CurveState::Computing(None));
    let (partial, complete) = until_complete(&rx, first.generation);
    assert!(!partial.is_empty(), "partial curves come before the complete one");
    assert_eq!(complete.starts, CURVE_STARTS);
    assert_same_bits(&complete, &expected(&setup_of(&preset)));
    // Another ε is the same setup: the curve stays as it is.
    worker.send(Command::SetTwin(Some(1e-6)));
    worker.send(Command::SetPlaying(false));
    until_handled(&rx, 3, |s| assert!(s.curve.is_none(), "{:?}", s.curve));
    // Off and on again on the same setup: the complete curve at once, not rolled again.
    worker.send(Command::SetTwin(None));
    let off = until_handled(&rx, 4, |_| {});
    assert!(off.twin.is_none() && off.curve.is_none());
    worker.send(Command::SetTwin(Some(1e-9)));
    let (_, again) = next_curve(&rx);
    assert!(again.generation > first.generation);
    assert_eq!(again.state, CurveState::Complete(complete));
}

#[test]
fn a_changed_setup_restarts_the_curve_and_the_old_one_is_never_seen_again() {
    let preset = Preset::default();
    let (worker, rx) = spawn(&preset);
    worker.send(Command::SetTwin(Some(1e-9)));
    let (_, first) = next_curve(&rx);
    // Wait until it has grown, then change the table.
    loop {
        let (_, u) = next_curve(&rx);
        if matches!(u.state, CurveState::Computing(Some(_))) {
            break;
        }
    }
    let damping = ScanKey::named("ground.damping").unwrap();
    worker.send(Command::SetParam(damping, 0.01));
    // Until the worker takes the edit, its ticks go on reporting the old curve (grown, or
    // complete on a fast or idle machine): all of them of the old generation. Reading the
    // next curve update as the restart was the race this test once lost under load.
    let mut s = until_handled(&rx, 2, |s| {
        if s.commands_handled < 2
            && let Some(old) = &s.curve
        {
            assert_eq!(
                old.generation, first.generation,
                "only the old curve before the edit"
            );
        }
    });
    let restarted = s
        .curve
        .take()
        .expect("the restart comes with the edit's snapshot");
    assert_eq!(s.params.ground.damping, 0.01);
    assert_eq!(restarted.state, CurveState::Computing(None));
    assert!(restarted.generation > first.generation);
    let (_, complete) = until_complete(&rx, restarted.generation);
    let mut changed = setup_of(&preset);
    changed.params.ground.damping = 0.01;
    assert_same_bits(&complete, &expected(&changed));
    assert_ne!(complete, expected(&setup_of(&preset)), "the table matters");
}

#[test]
fn turning_the_twin_off_stops_the_curve() {
    let (worker, rx) = spawn(&Preset::default());
    worker.send(Command::SetTwin(Some(1e-9)));
    next_curve(&rx);
    worker.send(Command::SetTwin(None));
    worker.send(Command::SetPlaying(false));
    assert!(until_handled(&rx, 3, |_| {}).twin.is_none());
    // Paused, without a twin: nothing computes, so the worker falls silent (a curve still
    // rolling would keep it reporting on every tick).
    let mut late = Vec::new();
    loop {
        match rx.recv_timeout(Duration::from_secs(2)) {
            Ok(s) => late.push(s),
            Err(RecvTimeoutError::Timeout) => break,
            Err(RecvTimeoutError::Disconnected) => panic!("the worker stopped"),
        }
        assert!(late.len() < 10, "the worker keeps ticking: something still runs");
    }
    assert!(late.iter().all(|s| s.curve.is_none()));
}

#[test]
fn quitting_cancels_a_curve_that_would_take_hours() {
    // No friction and Δt = 10 µs: every roll is millions of steps long, 3 200 of them.
    let mut preset = Preset::default();
    preset.ground.friction = 0.0;
    preset.integrator.dt = 1e-5;
    let (worker, rx) = spawn(&preset);
    worker.send(Command::SetTwin(Some(1e-9)));
    let (_, first) = next_curve(&rx);
    assert_eq!(first.state, CurveState::Computing(None));
    std::thread::sleep(Duration::from_millis(300));
    let (done_tx, done_rx) = channel();
    std::thread::spawn(move || {
        worker.shutdown();
        let _ = done_tx.send(());
    });
    done_rx
        .recv_timeout(PATIENCE)
        .expect("shutdown returns: the curve's rolls saw the cancel flag");
}
