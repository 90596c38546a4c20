//! Basin maps through the worker: partial maps first, then the complete one, equal to what
//! the experiment layer computes; a cancelled map stops sending.

use dicesim_experiment::{MapSpec, Method, run_map};
use dicesim_explorer::worker::{Command, MapAxis, MapRequest, MapUpdate, Simulator, Snapshot, Worker};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::preset::Preset;
use std::sync::atomic::AtomicBool;
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

const PATIENCE: Duration = Duration::from_secs(30);

fn spawn() -> (Worker, Receiver<Snapshot>, Receiver<MapUpdate>) {
    let (tx, rx) = channel();
    let (map_tx, map_rx) = channel();
    let worker = Worker::spawn_with_maps(Simulator::new(&Preset::default()).expect("valid"), tx, move |m| {
        map_tx.send(m).is_ok()
    });
    (worker, rx, map_rx)
}

fn request(generation: u64, cells: (usize, usize)) -> MapRequest {
    let axis = |key: &str, cells| MapAxis {
        key: ScanKey::named(key).unwrap(),
        min: -60.0,
        max: 60.0,
        cells,
    };
    MapRequest {
        generation,
        x: axis("initial.angular_velocity.x", cells.0),
        y: axis("initial.angular_velocity.y", cells.1),
    }
}

#[test]
fn partial_maps_come_first_then_the_complete_map() {
    let (worker, _rx, maps) = spawn();
    let r = request(7, (48, 36));
    worker.send(Command::MapStart(r));
    let mut partial = 0;
    let done = loop {
        let u = maps.recv_timeout(PATIENCE).expect("the map thread reports");
        assert_eq!(u.generation, 7);
        let map = u.map.clone().expect("the map computes");
        if map.complete {
            break u;
        }
        partial += 1;
    };
    assert!(partial >= 1, "coarse levels arrive before the complete map");
    let preset = Preset::default();
    assert_eq!((done.params, done.initial), (preset.params(), preset.initial));
    let spec = MapSpec {
        x: r.x.axis().expect("axis"),
        y: r.y.axis().expect("axis"),
        method: Method::Adaptive,
    };
    let expected = run_map(
        &done.params,
        &done.initial,
        &spec,
        1,
        &AtomicBool::new(false),
        &mut |_| {},
    )
    .expect("map");
    assert_eq!(done.map, Ok(expected));
}

#[test]
fn a_cancelled_map_stops_and_the_next_one_runs() {
    let (worker, rx, maps) = spawn();
    // Large enough to take many seconds: only a cancel ends it early.
    worker.send(Command::MapStart(request(1, (600, 600))));
    let first = maps.recv_timeout(PATIENCE).expect("a partial map");
    assert!(!first.map.expect("map").complete);
    worker.send(Command::MapCancel);
    // The snapshot answering the cancel comes after the map thread was told to stop.
    loop {
        let s = rx.recv_timeout(PATIENCE).expect("snapshot");
        if s.commands_handled == 2 {
            break;
        }
    }
    // At most one update was already on its way when the flag was set.
    let late: Vec<MapUpdate> =
        std::iter::from_fn(|| maps.recv_timeout(Duration::from_secs(3)).ok()).collect();
    assert!(late.len() <= 1, "{} updates after the cancel", late.len());
    assert!(late.iter().all(|u| u.map.as_ref().is_ok_and(|m| !m.complete)));
    worker.send(Command::MapStart(request(2, (16, 12))));
    let done = loop {
        let u = maps.recv_timeout(PATIENCE).expect("the next map reports");
        if u.generation == 2 && u.map.as_ref().is_ok_and(|m| m.complete) {
            break u;
        }
        assert_eq!(u.generation, 2, "nothing more from the cancelled map");
    };
    assert_eq!(done.map.expect("map").width(), 16);
    // Shutting down during a map ends every thread.
    worker.send(Command::MapStart(request(3, (600, 600))));
    maps.recv_timeout(PATIENCE).expect("a partial map");
    worker.shutdown();
}

#[test]
fn a_bad_range_is_reported_not_computed() {
    let (worker, _rx, maps) = spawn();
    let mut r = request(4, (8, 8));
    r.x.min = 1e9;
    worker.send(Command::MapStart(r));
    let u = maps.recv_timeout(PATIENCE).expect("an answer");
    assert_eq!(u.generation, 4);
    assert!(u.map.is_err_and(|e| e.contains("initial.angular_velocity.x")));
}
