//! A polyhedral die (`die.kind`) rolls wherever the box rolls in batches: both engines
//! (`roll_in_lanes`, `roll_one_by_one`) give every roll of every die the same outcome bit for
//! bit (status, face, steps, time, impacts, first impact, start face and the final state),
//! alone or beside the box and other dice in one run, and each outcome is a whole one: a die
//! thrown from 15 cm lands (at least one impact, the first with a face of the die down), a
//! settled roll shows one of its numbers.

use super::throw;
use crate::common::state_bits;
use dicesim_physics::lanes::{LaneResult, lanes_available, roll_in_lanes, roll_one_by_one};
use dicesim_physics::{ContactLaw, InitialCondition, Params, Solid, Status};

/// Everything a roll's result carries, as bits.
#[derive(Debug, PartialEq, Eq)]
struct Bits {
    status: Status,
    face: Option<u8>,
    steps: u64,
    time_s: u64,
    impacts: u64,
    first_impact: Option<(u64, u64, u8)>,
    start_face: u8,
    state: Vec<u64>,
}

fn bits(r: &LaneResult<'_>) -> Bits {
    let o = r.outcome;
    Bits {
        status: o.status,
        face: o.face,
        steps: o.steps,
        time_s: o.time_s.to_bits(),
        impacts: o.impacts,
        first_impact: o.first_impact.map(|f| (f.step, f.time_s.to_bits(), f.face_down)),
        start_face: r.start_face,
        state: state_bits(r.state),
    }
}

type Engine = fn(
    usize,
    &mut dyn FnMut(usize) -> (Params, InitialCondition),
    &mut dyn FnMut(LaneResult<'_>),
    &dyn Fn() -> bool,
) -> bool;

fn run(engine: Engine, setups: &[(Params, InitialCondition)]) -> Vec<Bits> {
    let mut out: Vec<Option<Bits>> = (0..setups.len()).map(|_| None).collect();
    assert!(engine(
        setups.len(),
        &mut |i| setups[i],
        &mut |r| {
            assert!(out[r.index].is_none(), "roll {} reported twice", r.index);
            out[r.index] = Some(bits(&r));
        },
        &|| false,
    ));
    out.into_iter()
        .enumerate()
        .map(|(i, b)| b.unwrap_or_else(|| panic!("roll {i} never reported")))
        .collect()
}

/// The dice' table (Δt = 0.25 ms) with the die `kind`.
fn dice(kind: Solid) -> Params {
    let mut p = super::dice_table();
    p.die.kind = kind;
    p.validate().unwrap();
    p
}

/// Rolls `setups` through both engines, asserts equal bits roll by roll, and returns them.
fn identical(what: &str, setups: &[(Params, InitialCondition)]) -> Vec<Bits> {
    assert!(lanes_available(), "this test needs an x86-64 CPU with AVX2");
    let scalar = run(roll_one_by_one, setups);
    let lanes = run(roll_in_lanes, setups);
    for (i, (s, l)) in scalar.iter().zip(&lanes).enumerate() {
        assert_eq!(s, l, "{what}: roll {i} differs between the engines");
    }
    scalar
}

/// Every die, three seeds: the engines agree on every field, the counts of the statuses sum
/// to the rolls, every throw lands with one of the die's faces down and every settled roll
/// shows one of its numbers.
#[test]
fn every_die_rolls_alike_in_both_engines_with_a_whole_outcome() {
    const THROWS: u64 = 16;
    // A convex die rolls in dice/keys.rs, with the corners it needs.
    for kind in Solid::ALL
        .into_iter()
        .filter(|k| ![Solid::Box, Solid::Convex].contains(k))
    {
        let p = dice(kind);
        let numbers = p.die.face_numbers();
        for seed in [3, 11, 2026] {
            let setups: Vec<_> = (0..THROWS).map(|i| (p, throw(seed, i))).collect();
            let rolls = identical(&format!("{} seed {seed}", kind.name()), &setups);
            let mut statuses = [0u64; 3];
            for (i, r) in rolls.iter().enumerate() {
                statuses[r.status as usize] += 1;
                let what = format!("{} seed {seed} throw {i}", kind.name());
                assert!(r.impacts >= 1, "{what}: thrown from 15 cm, it lands");
                let (step, _, down) = r
                    .first_impact
                    .unwrap_or_else(|| panic!("{what}: no first impact"));
                assert!(step > 0 && step <= r.steps, "{what}: first impact at step {step}");
                assert!(numbers.contains(&down), "{what}: face down {down}");
                assert!(
                    numbers.contains(&r.start_face),
                    "{what}: start face {}",
                    r.start_face
                );
                // Position, velocity and momentum, 7 numbers a vertex, the time and the step.
                assert_eq!(r.state.len(), 9 + 7 * vertices(kind) + 2, "{what}");
                if r.status == Status::Settled {
                    let face = r.face.unwrap_or_else(|| panic!("{what}: settled without a face"));
                    assert!(numbers.contains(&face), "{what}: face {face}");
                }
            }
            assert_eq!(statuses.iter().sum::<u64>(), THROWS);
            assert_eq!(
                statuses[Status::Unstable as usize],
                0,
                "{} seed {seed}",
                kind.name()
            );
        }
    }
}

/// The vertices of each die (docs/dice.md, "Size and material").
fn vertices(kind: Solid) -> usize {
    match kind {
        Solid::D4 => 4,
        Solid::D8 => 6,
        Solid::D10 | Solid::Percentile | Solid::D20 => 12,
        Solid::D12 => 20,
        Solid::Box => 8,
        Solid::Convex => unreachable!("a convex die's vertices are its own"),
    }
}

/// One run of many bodies and laws in turn (the box, each die, the spring-friction table):
/// each roll is what it is rolled alone, in either engine, whatever its neighbours.
#[test]
fn dice_beside_the_box_and_each_other_roll_as_they_roll_alone() {
    let mut setups = Vec::new();
    let mut spring = dice(Solid::D20);
    spring.ground.contact = ContactLaw::SpringFriction;
    let bodies = [
        Params::default(),
        dice(Solid::D4),
        dice(Solid::D20),
        dice(Solid::D10),
        spring,
        dice(Solid::Percentile),
        dice(Solid::D12),
        dice(Solid::D8),
    ];
    for i in 0..40 {
        setups.push((bodies[i % bodies.len()], throw(7, i as u64)));
    }
    let mixed = identical("mixed", &setups);
    for (i, setup) in setups.iter().enumerate() {
        let alone = run(roll_one_by_one, std::slice::from_ref(setup));
        assert_eq!(mixed[i], alone[0], "roll {i} beside others against alone");
    }
    // The d10 and the d% are one shape: the same throw ends on opposite numbers of the same
    // face pair, so the d%'s reading is ten times the d10's.
    let d10 = identical("d10", &[(dice(Solid::D10), throw(5, 0))]);
    let percent = identical("d%", &[(dice(Solid::Percentile), throw(5, 0))]);
    assert_eq!(d10[0].steps, percent[0].steps);
    assert_eq!(d10[0].face.map(|f| 10 * f), percent[0].face);
}
