//! The worker thread's protocol: commands in, snapshots out, in order, none lost, and a
//! clean stop when the UI goes.

use dicesim_experiment::{FaceTally, RandomRanges, ScanKey, roll_record};
use dicesim_explorer::worker::{Command, Notice, Phase, Simulator, Snapshot, Speed, Worker};
use dicesim_physics::{Simulation, Status};
use dicesim_setup::preset::Preset;
use dicesim_setup::random::RandomDraws;
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::Duration;

/// Generous: only a hung worker takes this long.
const PATIENCE: Duration = Duration::from_secs(20);

fn spawn() -> (Worker, Receiver<Snapshot>) {
    let (tx, rx) = channel();
    let worker = Worker::spawn(Simulator::new(&Preset::default()).expect("valid"), tx);
    (worker, rx)
}

/// Snapshots until one satisfies `done`; panics if the worker stops or hangs.
fn wait_for(rx: &Receiver<Snapshot>, mut done: impl FnMut(&Snapshot) -> bool) -> Snapshot {
    loop {
        let s = rx.recv_timeout(PATIENCE).expect("the worker keeps reporting");
        if done(&s) {
            return s;
        }
    }
}

#[test]
fn first_snapshot_is_the_start_of_the_preset_roll() {
    let (_worker, rx) = spawn();
    let s = rx.recv_timeout(PATIENCE).expect("first snapshot");
    assert_eq!((s.step, s.time_s, s.commands_handled), (0, 0.0, 0));
    assert!(!s.playing);
    assert_eq!(s.phase, Phase::Falling);
    assert_eq!(s.history.len(), 1);
}

#[test]
fn every_command_arrives_in_order() {
    let (worker, rx) = spawn();
    for _ in 0..50 {
        assert!(worker.send(Command::Step(1)));
    }
    let frictions: Vec<f64> = (1..=40).map(|i| i as f64 * 0.1).collect();
    for &mu in &frictions {
        worker.send(Command::SetParam(ScanKey::named("ground.friction").unwrap(), mu));
    }
    let s = wait_for(&rx, |s| s.commands_handled == 90);
    assert_eq!(s.step, 50, "fifty single steps, none lost");
    assert_eq!(
        s.params.ground.friction,
        *frictions.last().expect("values"),
        "the last value sent wins"
    );
    let mut previous = 0;
    let mut seen = 0;
    let mut history = 0;
    worker.send(Command::Replay);
    worker.send(Command::SetPlaying(false));
    loop {
        let s = rx.recv_timeout(PATIENCE).expect("snapshot");
        assert!(s.commands_handled >= previous, "counts never go back");
        previous = s.commands_handled;
        seen += 1;
        history = if s.history_reset {
            s.history.len()
        } else {
            history + s.history.len()
        };
        if s.commands_handled == 92 && !s.playing {
            assert_eq!(
                history as u64,
                s.step + 1,
                "one energy sample per step, from t = 0"
            );
            break;
        }
    }
    assert!(seen >= 1);
}

#[test]
fn instant_playback_shows_the_end_the_physics_computes() {
    let (worker, rx) = spawn();
    worker.send(Command::SetSpeed(Speed::INSTANT));
    worker.send(Command::SetPlaying(true));
    let s = wait_for(&rx, |s| matches!(s.phase, Phase::Ended(_)) && !s.playing);
    let preset = Preset::default();
    let expected = Simulation::new(&preset.params(), &preset.initial)
        .expect("valid")
        .run_to_end();
    assert_eq!(s.phase, Phase::Ended(expected));
    // The face is decided where the physics stops the roll; the die plays on to rest past
    // it (the paper's roll still rocks at its stop), and playback stops there.
    assert_eq!(s.timeline.decided, Some(expected.steps));
    assert!(
        s.timeline.ended && s.step > expected.steps,
        "{} ≤ {}",
        s.step,
        expected.steps
    );
    assert!(s.energy.kinetic() < 0.01 * s.stop_threshold || s.time_s >= expected.time_s + 2.0);
}

#[test]
fn a_ground_change_mid_roll_keeps_the_roll_and_others_restart_it() {
    let (worker, rx) = spawn();
    worker.send(Command::Step(100));
    worker.send(Command::SetParam(ScanKey::named("ground.damping").unwrap(), 0.01));
    let s = wait_for(&rx, |s| s.commands_handled == 2);
    assert_eq!((s.step, s.params.ground.damping), (100, 0.01));
    worker.send(Command::SetParam(ScanKey::named("initial.height").unwrap(), 5.0));
    let s = wait_for(&rx, |s| s.commands_handled == 3);
    assert_eq!((s.step, s.initial.height), (0, 5.0));
    assert!(s.history_reset);
    worker.send(Command::SetParam(
        ScanKey::named("ground.friction").unwrap(),
        99.0,
    ));
    let s = wait_for(&rx, |s| s.commands_handled == 4);
    assert!(
        s.notice
            .as_ref()
            .and_then(Notice::said)
            .is_some_and(|n| n.contains("ground.friction")),
        "an out-of-range value is refused"
    );
    assert_eq!(s.params.ground.friction, Preset::default().ground.friction);
}

#[test]
fn a_batch_fills_the_table_with_the_rolls_the_experiment_layer_computes() {
    let (worker, rx) = spawn();
    worker.send(Command::BatchStart(300));
    let s = wait_for(&rx, |s| {
        s.batch.is_none() && s.table.as_ref().is_some_and(|t| t.rolls() == 300)
    });
    let table = s.table.expect("table");
    let preset = Preset::default();
    let ranges: RandomRanges = preset.random;
    let params = preset.params();
    let records: Vec<_> = (0..300)
        .map(|i| roll_record(&params, &ranges.draw(&preset.initial, ranges.seed, i), i))
        .collect();
    let mut expected = FaceTally::new(params.die.face_numbers());
    (records.iter())
        .filter(|r| r.outcome.status == Status::Settled)
        .filter_map(|r| r.outcome.face)
        .for_each(|f| expected.add(f));
    assert_eq!(table.tally, expected);
    assert_eq!(table.last.front().map(|r| r.id), Some(299), "newest first");
    // The next random roll continues the numbering instead of repeating a batch roll.
    worker.send(Command::SetSpeed(Speed::INSTANT));
    worker.send(Command::RandomRoll);
    let s = wait_for(&rx, |s| s.table.as_ref().is_some_and(|t| t.rolls() == 301));
    assert_eq!(s.table.expect("table").last.front().map(|r| r.id), Some(300));
    worker.send(Command::ClearTable);
    let s = wait_for(&rx, |s| s.table.is_some());
    assert_eq!(s.table.expect("table").rolls(), 0);
}

#[test]
fn a_batch_can_be_cancelled_and_the_worker_stops_cleanly_during_one() {
    let (worker, rx) = spawn();
    worker.send(Command::BatchStart(5_000_000));
    wait_for(&rx, |s| s.batch.is_some_and(|b| b.done > 0));
    worker.send(Command::BatchCancel);
    let s = wait_for(&rx, |s| s.batch.is_none());
    assert!(
        s.notice
            .as_ref()
            .and_then(Notice::said)
            .is_some_and(|n| n.contains("cancelled"))
    );
    worker.send(Command::BatchStart(5_000_000));
    wait_for(&rx, |s| s.batch.is_some());
    worker.shutdown();
    // Every snapshot already sent can still be read; then the channel reports the end.
    while rx.recv_timeout(PATIENCE).is_ok() {}
}

#[test]
fn shutdown_while_playing_ends_the_thread_and_its_channel() {
    let (worker, rx) = spawn();
    worker.send(Command::SetSpeed(Speed::SLOWEST));
    worker.send(Command::SetPlaying(true));
    wait_for(&rx, |s| s.playing);
    worker.shutdown();
    loop {
        match rx.recv_timeout(PATIENCE) {
            Ok(_) => continue,
            Err(RecvTimeoutError::Disconnected) => break,
            Err(RecvTimeoutError::Timeout) => panic!("the worker did not stop"),
        }
    }
}

#[test]
fn the_worker_stops_when_the_ui_drops_its_receiver() {
    let (worker, rx) = spawn();
    worker.send(Command::SetPlaying(true));
    drop(rx);
    // Dropping joins the thread: it must notice the closed channel and end.
    drop(worker);
}

#[test]
fn a_paused_worker_sends_nothing_until_asked() {
    let (worker, rx) = spawn();
    rx.recv_timeout(PATIENCE).expect("first snapshot");
    assert_eq!(
        rx.recv_timeout(Duration::from_millis(300)),
        Err(RecvTimeoutError::Timeout)
    );
    worker.send(Command::Step(3));
    let s = rx.recv_timeout(PATIENCE).expect("a snapshot answers the command");
    assert_eq!(s.step, 3);
    assert_eq!(
        rx.recv_timeout(Duration::from_millis(300)),
        Err(RecvTimeoutError::Timeout)
    );
}
