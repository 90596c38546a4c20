//! The explorer's impact keys against `dicesim trace`: the steps its worker jumps to, one
//! impact after another, are where the trace's rows start a contact after the die was clear
//! of the table (`lowest_corner_cm` below zero, by the physics' one definition of an
//! impact), and the face-decided jump lands on the trace's last row.

use crate::common::dicesim_ok;
use dicesim_explorer::worker::{Command, RollEvent, Simulator, Snapshot, Worker};
use dicesim_physics::impact_starts;
use dicesim_setup::preset::Store;
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

/// The snapshot after the worker has handled `n` commands.
fn handled(rx: &Receiver<Snapshot>, n: u64) -> Snapshot {
    loop {
        let s = rx
            .recv_timeout(Duration::from_secs(20))
            .expect("the worker reports");
        if s.commands_handled >= n {
            return s;
        }
    }
}

#[test]
fn the_explorers_impact_jumps_land_where_the_trace_starts_each_contact() {
    let dir = tempfile::tempdir().unwrap();
    let name = "slow-motion-classroom";
    let csv = dicesim_ok(dir.path(), &["trace", "--preset", name]);
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let col = |c: &str| header.iter().position(|h| *h == c).expect(c);
    let (step, lowest) = (col("step"), col("lowest_corner_cm"));
    let rows: Vec<(u64, bool)> = lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[step].parse().unwrap(), f[lowest].parse::<f64>().unwrap() < 0.0)
        })
        .collect();
    assert!(
        rows.iter().enumerate().all(|(i, r)| r.0 == i as u64),
        "a row a step"
    );
    let expected = impact_starts(rows.iter().map(|r| r.1));
    let decided = rows.last().expect("rows").0;
    assert!(expected.len() >= 3, "{expected:?}");

    let preset = Store::new(None).load(name).expect("shipped").0;
    let (tx, rx) = channel();
    let worker = Worker::spawn(Simulator::new(&preset).expect("valid"), tx);
    let mut sent = 0;
    let mut landed = Vec::new();
    for _ in 0..expected.len() {
        worker.send(Command::SeekEvent(RollEvent::NextImpact));
        sent += 1;
        landed.push(handled(&rx, sent).step);
    }
    assert_eq!(landed, expected);
    worker.send(Command::SeekEvent(RollEvent::PreviousImpact));
    sent += 1;
    assert_eq!(handled(&rx, sent).step, expected[expected.len() - 2]);
    worker.send(Command::Seek(0));
    worker.send(Command::SeekEvent(RollEvent::FaceDecided));
    sent += 2;
    let s = handled(&rx, sent);
    assert_eq!((s.step, s.timeline.decided), (decided, Some(decided)));
}
