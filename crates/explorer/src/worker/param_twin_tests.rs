//! The parameter twin in the worker: the same start rolled in setup B beside the die.

use super::{Command, Phase, Simulator};
use dicesim_physics::{Outcome, Params, Simulation};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::preset::Preset;

fn key(name: &str) -> &'static ScanKey {
    ScanKey::named(name).expect("a registry key")
}

/// Bits of a simulation's state and outcome (`==` on floats would let −0 pass for +0).
fn bits(sim: &Simulation) -> String {
    format!("{:?} {:?}", sim.state(), sim.outcome())
}

/// The roll of the paper's start in `params`, by the physics alone.
fn independent(params: &Params, preset: &Preset) -> Outcome {
    Simulation::new(params, &preset.initial)
        .expect("valid")
        .run_to_end()
}

fn ended(phase: Phase) -> Outcome {
    match phase {
        Phase::Ended(o) => o,
        other => panic!("the roll has not ended: {other:?}"),
    }
}

#[test]
fn a_twin_with_no_difference_rolls_bit_identical_to_the_die() {
    let preset = Preset::default();
    let mut e = Simulator::new(&preset).expect("valid");
    let mu = preset.params().ground.friction;
    e.handle(Command::SetParamTwin(vec![(key("ground.friction"), mu)]));
    e.run_to_end();
    let twin = e.live().twin.as_ref().expect("a parameter twin rolls");
    assert_eq!(
        bits(twin.sim.simulation().expect("the box")),
        bits(e.simulation())
    );
    let s = e.snapshot();
    let t = s.twin.expect("drawn");
    assert_eq!(t.differs_by, vec![(key("ground.friction"), mu)]);
    assert_eq!(t.epsilon, 0.0, "the same start");
    assert_eq!(t.phase, s.phase);
}

#[test]
fn friction_0_3_against_1_2_rolls_as_the_physics_gives_each() {
    let preset = Preset::default()
        .with_overrides(&["ground.friction=0.3"])
        .expect("valid overrides");
    let mut b = preset.params();
    b.ground.friction = 1.2;
    let (want_a, want_b) = (independent(&preset.params(), &preset), independent(&b, &preset));

    let mut e = Simulator::new(&preset).expect("valid");
    e.handle(Command::SetParamTwin(vec![(key("ground.friction"), 1.2)]));
    e.run_to_end();
    let s = e.snapshot();
    let got_b = ended(s.twin.expect("the twin").phase);
    assert_eq!(ended(s.phase), want_a, "A keeps μ = 0.3");
    assert_eq!(got_b, want_b, "B rolls with μ = 1.2");
    assert_eq!(e.params().ground.friction, 0.3, "A's setup is untouched");
    // The two frictions end the paper's roll on different faces (the physics says so above).
    assert_ne!(want_a.face, want_b.face, "{want_a:?} {want_b:?}");
}

#[test]
fn a_table_change_mid_roll_reaches_b_with_bs_own_value_kept() {
    let preset = Preset::default();
    let mut e = Simulator::new(&preset).expect("valid");
    e.handle(Command::SetParamTwin(vec![(key("ground.friction"), 1.2)]));
    e.handle(Command::Step(50));
    e.handle(Command::SetParam(key("ground.stiffness"), 2e5));
    let twin = e.live().twin.as_ref().expect("still rolls");
    let ground = twin.sim.params().ground;
    assert_eq!((ground.friction, ground.stiffness), (1.2, 2e5));
}

#[test]
fn a_start_value_or_another_dt_is_refused_and_changes_nothing() {
    let preset = Preset::default();
    let mut e = Simulator::new(&preset).expect("valid");
    for (name, value, words) in [
        ("initial.height", 20.0, "same start"),
        ("integrator.dt", preset.params().integrator.dt * 2.0, "Δt"),
        ("ground.friction", -1.0, "ground.friction"),
    ] {
        e.handle(Command::SetParamTwin(vec![(key(name), value)]));
        let s = e.snapshot();
        let notice = s.notice.expect("refused in words");
        let said = notice.said().expect("words");
        assert!(said.contains(words) && said.contains("twin B"), "{name}: {said}");
        assert!(s.twin.is_none(), "{name}: no twin rolls");
    }
    e.handle(Command::SetParamTwin(vec![(key("ground.friction"), 0.9)]));
    assert!(e.snapshot().twin.is_some());
    e.handle(Command::SetParamTwin(Vec::new()));
    assert!(e.snapshot().twin.is_none(), "an empty list removes it");
}

#[test]
fn a_batch_beside_a_parameter_twin_tallies_each_throw_in_both_setups() {
    let preset = Preset::default();
    let mut e = Simulator::new(&preset).expect("valid");
    e.handle(Command::SetParamTwin(vec![(key("ground.friction"), 0.3)]));
    e.handle(Command::BatchStart(24));
    let request = e.take_batch_request().expect("ordered");
    let rolls = request.rolls.clone();
    e.run_request_here(request);
    let s = e.snapshot();
    let table = s.versus.expect("the shared throws' table");
    assert_eq!(table.throws(), 24);
    // Each throw as the physics gives it in A (the paper's μ) and in B (μ = 0.3).
    let mut b = preset.params();
    b.ground.friction = 0.3;
    let ending = |p: &Params, i: usize| {
        let o = Simulation::new(p, &rolls[i].1).expect("valid").run_to_end();
        match o.face {
            Some(f) if o.status == dicesim_physics::Status::Settled => f as usize - 1,
            _ => dicesim_experiment::versus::NO_FACE,
        }
    };
    let mut want = [[0u64; 7]; 7];
    for i in 0..rolls.len() {
        want[ending(&preset.params(), i)][ending(&b, i)] += 1;
    }
    assert_eq!(table.counts, want);
    let diagonal: u64 = (0..6).map(|f| table.counts[f][f]).sum();
    assert_eq!(diagonal, table.agreeing());
    // A's throws entered the outcome table too.
    assert_eq!(s.table.expect("changed").rolls(), 24);
}

#[test]
fn a_batch_beside_a_twin_with_no_difference_agrees_on_every_throw() {
    let preset = Preset::default();
    let mut e = Simulator::new(&preset).expect("valid");
    let mu = preset.params().ground.friction;
    e.handle(Command::SetParamTwin(vec![(key("ground.friction"), mu)]));
    e.handle(Command::BatchStart(24));
    e.run_batch_here();
    let table = e.snapshot().versus.expect("the shared throws' table");
    assert_eq!(table.throws(), 24);
    for (a, row) in table.counts.iter().enumerate() {
        for (b, n) in row.iter().enumerate() {
            assert!(a == b || *n == 0, "off the diagonal: {a} {b} {n}");
        }
    }
    assert_eq!(table.agreement().map(|a| a.0), Some(1.0));
}

#[test]
fn the_parameter_twins_samples_are_bs_own_roll() {
    let preset = Preset::default();
    let mut e = Simulator::new(&preset).expect("valid");
    e.handle(Command::SetParamTwin(vec![(key("ground.friction"), 0.3)]));
    e.handle(Command::Step(400));
    let samples = e.snapshot().twin.expect("B rolls").samples;
    let last = *samples.last().expect("sampled");
    // B by the physics alone: μ = 0.3, stepped to the sample's time.
    let mut b = preset.params();
    b.ground.friction = 0.3;
    let mut sim = Simulation::new(&b, &preset.initial).expect("valid");
    while sim.state().time_s < last.time_s {
        sim.advance();
    }
    assert_eq!(sim.state().time_s, last.time_s);
    assert_eq!(last.quantities, dicesim_setup::quantity::read_all(&sim));
    // And not A's: the die's own sample at that time differs.
    let mut a = Simulation::new(&preset.params(), &preset.initial).expect("valid");
    while a.state().time_s < last.time_s {
        a.advance();
    }
    assert_ne!(last.quantities, dicesim_setup::quantity::read_all(&a));
}
