//! The lane engine against the scalar `Simulation`: every roll's face, status, step count,
//! end time and final state must agree bit for bit.
//!
//! Per friction law and stop energy: 100 000 random initial conditions (random orientation,
//! throws and spins, heights 1.5–30 cm) cut at 0.6 s of simulated time (identity must hold
//! for any time limit, and the cut keeps the test fast: flight, impacts and the first
//! bounces, each ending as a timeout unless it settled or blew up first), 5 000 more rolled
//! to their natural end, and every reference initial condition. The same for three loaded
//! dice (their full inertia tensor and per-face stopping rule): 100 000 cut rolls and 500
//! whole ones each per law and stop energy. A loaded die's step rebuilds and inverts its
//! tensor and rebuilds the spin's rotation every step, in flight too: about twice a fair
//! step's instructions (callgrind over cut rolls like these: 1370 against 649 scalar, 551
//! against 308 per lane), and a chain of dependent divisions, a square root and a sine that
//! takes longer still, so a loaded cut roll costs 3–4 fair ones and these are most of this
//! file's time (about two minutes on two idle cores). Then a
//! mixed sample where neighbouring lanes carry different parameters, laws, stop energies and
//! dice, with soft, stiff, damped and coarse-Δt setups that end in every status. The
//! spring-friction law likewise, on a level and a tilted table (cube, loaded and rounded die:
//! 100 000 cut rolls and 2 000 whole ones each), and in every fourth lane of the mixed sample.

use crate::common::{Table, random_start, reference_initial, reference_params, state_bits};
use dicesim_physics::RandomRanges;
use dicesim_physics::lanes::{LaneResult, lanes_available, roll_in_lanes, roll_one_by_one};
use dicesim_physics::{FrictionLaw, InitialCondition, Outcome, Params, Status, StopEnergy};
use rand::{RngExt, SeedableRng};

/// Everything a roll's result carries, as bits.
#[derive(Debug, PartialEq, Eq)]
struct Bits {
    status: Status,
    face: Option<u8>,
    steps: u64,
    time_s: u64,
    start_face: u8,
    state: Vec<u64>,
    impacts: u64,
    /// The first impact's step, time and face down.
    first_impact: Option<(u64, u64, u8)>,
}

fn bits(r: &LaneResult<'_>) -> Bits {
    let Outcome {
        status,
        face,
        steps,
        time_s,
        impacts,
        first_impact,
    } = r.outcome;
    Bits {
        status,
        face,
        steps,
        time_s: time_s.to_bits(),
        start_face: r.start_face,
        state: state_bits(r.state),
        impacts,
        first_impact: first_impact.map(|f| (f.step, f.time_s.to_bits(), f.face_down)),
    }
}

type Engine = fn(
    usize,
    &mut dyn FnMut(usize) -> (Params, InitialCondition),
    &mut dyn FnMut(LaneResult<'_>),
    &dyn Fn() -> bool,
) -> bool;

fn run(engine: Engine, setups: &[(Params, InitialCondition)]) -> Vec<Option<Bits>> {
    let mut out: Vec<Option<Bits>> = (0..setups.len()).map(|_| None).collect();
    let finished = engine(
        setups.len(),
        &mut |i| setups[i],
        &mut |r| {
            assert!(out[r.index].is_none(), "roll {} reported twice", r.index);
            out[r.index] = Some(bits(&r));
        },
        &|| false,
    );
    assert!(finished);
    out
}

/// Rolls `setups` through both engines and asserts equal bits; returns the status counts.
fn assert_identical(what: &str, setups: &[(Params, InitialCondition)]) -> [usize; 3] {
    assert!(lanes_available(), "this test needs an x86-64 CPU with AVX2");
    let scalar = run(roll_one_by_one, setups);
    let lanes = run(roll_in_lanes, setups);
    let mut statuses = [0; 3];
    let mut differing = Vec::new();
    for (i, (s, l)) in scalar.iter().zip(&lanes).enumerate() {
        let s = s.as_ref().expect("the scalar engine rolls every setup");
        let l = l
            .as_ref()
            .unwrap_or_else(|| panic!("{what}: the lane engine skipped roll {i}"));
        statuses[s.status as usize] += 1;
        if s != l {
            differing.push(i);
        }
    }
    assert!(
        differing.is_empty(),
        "{what}: {} of {} rolls differ, first {:?}: scalar {:?}, lanes {:?}",
        differing.len(),
        setups.len(),
        differing.first(),
        scalar[differing[0]],
        lanes[differing[0]]
    );
    println!("{what}: {} rolls identical, statuses {statuses:?}", setups.len());
    statuses
}

const CUT_ROLLS: u64 = 100_000;
const CUT_TIME_S: f64 = 0.6;
const WHOLE_ROLLS: u64 = 5_000;
const LOADED_CUT_ROLLS: u64 = 100_000;
const LOADED_WHOLE_ROLLS: u64 = 500;

/// g of extra mass at corners 1..8: one heavy corner, two unequal corners, every corner a
/// little and unevenly.
const LOADED_DICE: [[f64; 8]; 3] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0],
    [0.0, 1.5, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0],
    [0.3, 0.05, 0.7, 0.0, 0.15, 1.1, 0.0, 0.2],
];

fn random_setups(params: Params, seed: u64, count: u64) -> Vec<(Params, InitialCondition)> {
    let ranges = RandomRanges {
        seed,
        height: [1.5, 30.0],
        velocity: [-80.0, 80.0],
        angular_velocity: [-80.0, 80.0],
        random_orientation: true,
        orientation_spread: 0.0,
    };
    let base = InitialCondition::default();
    (0..count)
        .map(|i| (params, random_start(&ranges, &base, seed, i)))
        .collect()
}

fn reference_setups(params: Params) -> Vec<(Params, InitialCondition)> {
    ["original", "paper"]
        .iter()
        .flat_map(|variant| {
            let table = Table::load(&format!("outcomes_{variant}.csv"));
            table
                .rows
                .iter()
                .map(|row| reference_initial(&table, row))
                .collect::<Vec<_>>()
        })
        .map(|ic| (params, ic))
        .collect()
}

fn law_and_stop(law: FrictionLaw, stop: StopEnergy, seed: u64) {
    let mut params = reference_params("paper");
    params.ground.friction_law = law;
    params.integrator.stop_energy = stop;
    let what = format!("{law:?} friction, {} stop energy", stop.name());
    let cut = Params {
        integrator: dicesim_physics::Integrator {
            max_time: CUT_TIME_S,
            ..params.integrator
        },
        ..params
    };
    let statuses = assert_identical(&format!("{what}, cut"), &random_setups(cut, seed, CUT_ROLLS));
    assert!(statuses.iter().sum::<usize>() == CUT_ROLLS as usize);
    let statuses = assert_identical(
        &format!("{what}, whole rolls"),
        &random_setups(params, seed + 100, WHOLE_ROLLS),
    );
    assert!(statuses[Status::Settled as usize] > 4_500, "{what}: {statuses:?}");
    assert_identical(&format!("{what}, reference"), &reference_setups(params));
    for (d, extra) in LOADED_DICE.into_iter().enumerate() {
        let load = |p: Params| Params {
            die: dicesim_physics::Die {
                extra_corner_mass: extra,
                ..p.die
            },
            ..p
        };
        let what = format!("{what}, loaded die {extra:?}");
        let seed = seed + 1000 * (d as u64 + 1);
        let statuses = assert_identical(
            &format!("{what}, cut"),
            &random_setups(load(cut), seed, LOADED_CUT_ROLLS),
        );
        assert!(statuses.iter().sum::<usize>() == LOADED_CUT_ROLLS as usize);
        let statuses = assert_identical(
            &format!("{what}, whole rolls"),
            &random_setups(load(params), seed + 100, LOADED_WHOLE_ROLLS),
        );
        assert!(statuses[Status::Settled as usize] > 450, "{what}: {statuses:?}");
    }
}

#[test]
fn per_corner_rigid_body_stop() {
    law_and_stop(FrictionLaw::PerCorner, StopEnergy::RigidBody, 11);
}

#[test]
fn per_corner_point_mass_stop() {
    law_and_stop(FrictionLaw::PerCorner, StopEnergy::PointMasses, 12);
}

#[test]
fn whole_die_norm_rigid_body_stop() {
    law_and_stop(FrictionLaw::WholeDieNorm, StopEnergy::RigidBody, 13);
}

#[test]
fn whole_die_norm_point_mass_stop() {
    law_and_stop(FrictionLaw::WholeDieNorm, StopEnergy::PointMasses, 14);
}

const SPRING_CUT_ROLLS: u64 = 100_000;
const SPRING_WHOLE_ROLLS: u64 = 2_000;

/// The spring-friction law (its tangential springs are state both widths carry), on a level
/// and a tilted table: the paper's cube, a loaded die and a rounded die, 100 000 cut rolls and
/// 2 000 whole ones each.
#[test]
fn spring_friction_law() {
    use dicesim_physics::ContactLaw;
    let mut level = Params::default();
    level.ground.contact = ContactLaw::SpringFriction;
    level.ground.static_friction = 1.4;
    let mut tilted = level;
    tilted.ground.tilt = 20.0;
    tilted.ground.tilt_direction = 70.0;
    let loaded = |p: Params| Params {
        die: dicesim_physics::Die {
            extra_corner_mass: LOADED_DICE[2],
            ..p.die
        },
        ..p
    };
    let rounded = |p: Params| Params {
        die: dicesim_physics::Die {
            corner_radius: 0.2,
            ..p.die
        },
        ..p
    };
    type Body = fn(Params) -> Params;
    let bodies: [(&str, Body); 3] = [("cube", |p| p), ("loaded die", loaded), ("rounded die", rounded)];
    for (t, table) in [("level", level), ("tilted", tilted)].into_iter().enumerate() {
        for (b, (body, make)) in bodies.iter().enumerate() {
            let params = make(table.1);
            let what = format!("spring-friction, {} table, {body}", table.0);
            let seed = 21 + 10 * t as u64 + b as u64;
            let cut = Params {
                integrator: dicesim_physics::Integrator {
                    max_time: CUT_TIME_S,
                    ..params.integrator
                },
                ..params
            };
            // Half the cut rolls on each table keeps the file's time; each body gets 100 000.
            let statuses = assert_identical(
                &format!("{what}, cut"),
                &random_setups(cut, seed, SPRING_CUT_ROLLS / 2),
            );
            assert!(statuses.iter().sum::<usize>() == (SPRING_CUT_ROLLS / 2) as usize);
            let statuses = assert_identical(
                &format!("{what}, whole rolls"),
                &random_setups(params, seed + 100, SPRING_WHOLE_ROLLS / 2),
            );
            assert!(statuses[Status::Settled as usize] > 0, "{what}: {statuses:?}");
        }
    }
}

/// Neighbouring lanes with different parameters, and setups at the edges of the ranges:
/// soft and stiff tables, heavy damping, no friction, coarse Δt (unstable rolls), short
/// time limits (timeouts), spins up to the limit, drops from rest onto an edge.
#[test]
fn mixed_parameters_in_neighbouring_lanes() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(5);
    let base = InitialCondition::default();
    let ranges = RandomRanges {
        random_orientation: true,
        ..RandomRanges::default()
    };
    let setups: Vec<(Params, InitialCondition)> = (0..4000u64)
        .map(|i| {
            let mut p = Params::default();
            let log_uniform =
                |rng: &mut rand::rngs::StdRng, lo: f64, hi: f64| (rng.random_range(lo.ln()..hi.ln())).exp();
            p.ground.stiffness = log_uniform(&mut rng, 1e3, 1e7);
            p.ground.damping = rng.random_range(0.0..0.05);
            p.ground.friction = rng.random_range(0.0..2.0);
            p.ground.friction_law = if rng.random_bool(0.5) {
                FrictionLaw::PerCorner
            } else {
                FrictionLaw::WholeDieNorm
            };
            p.integrator.stop_energy = if rng.random_bool(0.5) {
                StopEnergy::RigidBody
            } else {
                StopEnergy::PointMasses
            };
            // Every fourth lane on the spring-friction law, some on a tilted table, so the
            // two laws share vectors.
            if i % 4 == 3 {
                p.ground.contact = dicesim_physics::ContactLaw::SpringFriction;
                p.ground.damping = Params::default().ground.damping;
                p.ground.friction_law = FrictionLaw::PerCorner;
                p.ground.static_friction = p.ground.friction + rng.random_range(0.0..0.5);
                p.ground.restitution = rng.random_range(0.2..1.0);
                p.ground.tangential_stiffness_ratio = rng.random_range(0.1..1.5);
                p.ground.tilt = if rng.random_bool(0.3) {
                    rng.random_range(0.0..40.0)
                } else {
                    0.0
                };
                p.ground.tilt_direction = rng.random_range(0.0..360.0);
                // Every other one with a face restitution of its own (drawn from the index,
                // so the other lanes' draws stay as they were).
                if i % 8 == 7 {
                    p.ground.face_restitution = Some(0.2 + 0.2 * ((i / 8) % 5) as f64);
                }
                // and every other one on a compliant table.
                if i % 8 == 3 {
                    p.ground.table_mass = Some(5.0 * (1 + (i / 8) % 7) as f64);
                    p.ground.table_stiffness = Some(1e4 * ((i / 8) % 3) as f64);
                    p.ground.table_damping = Some(10.0 * ((i / 8) % 4) as f64);
                }
            }
            p.integrator.dt = log_uniform(&mut rng, 1e-4, 1e-2);
            p.integrator.max_time = rng.random_range(0.2..5.0);
            p.die.half_sizes = [rng.random_range(0.5..2.0); 3];
            // Every third lane a loaded die, so fair and loaded dice share vectors.
            if i % 3 == 2 {
                p.die.extra_corner_mass = std::array::from_fn(|_| {
                    if rng.random_bool(0.4) {
                        rng.random_range(0.0..3.0)
                    } else {
                        0.0
                    }
                });
            }
            let mut ic = random_start(&ranges, &base, 9, i);
            ic.height = rng.random_range(0.5..40.0);
            if i % 10 == 0 {
                ic.angular_velocity = [rng.random_range(-3000.0..3000.0), 0.0, 0.0];
            }
            if i % 10 == 1 {
                ic.velocity = [0.0; 3];
                ic.angular_velocity = [0.0; 3];
                ic.orientation = [0.0, 45.0, 0.0];
            }
            (p, ic)
        })
        .collect();
    let statuses = assert_identical("mixed parameters", &setups);
    assert!(
        statuses.iter().all(|&n| n > 50),
        "every status is exercised: {statuses:?}"
    );
}

#[test]
fn a_stop_request_ends_the_lanes_within_a_check_interval() {
    let mut p = Params::default();
    p.integrator.max_time = 10_000.0;
    p.integrator.dt = 1e-5;
    // A die spinning in free fall from 1000 cm: hundreds of thousands of steps per roll.
    let ic = InitialCondition {
        height: 1000.0,
        angular_velocity: [5.0, 1.0, 0.0],
        ..Default::default()
    };
    let asked = std::cell::Cell::new(0);
    let finished = roll_in_lanes(
        8,
        &mut |_| (p, ic),
        &mut |r| panic!("roll {} cannot end this soon", r.index),
        &|| {
            asked.set(asked.get() + 1);
            asked.get() == 3
        },
    );
    assert!(!finished);
    assert_eq!(asked.get(), 3);
}

/// A flat drop under the spring-friction law bounces the number of times docs/model.md
/// ("Impacts", "A flat drop's bounces") derives, in both widths alike: the least restitution
/// allowed from 2 cm above rest once, restitution 0.5 from 10 cm above rest three times.
#[test]
fn a_flat_drop_bounces_as_its_restitution_and_height_say() {
    use dicesim_physics::ContactLaw;
    for (restitution, drop_cm, expected) in [(0.2, 2.0, 1), (0.5, 10.0, 3)] {
        let mut params = Params::default();
        params.ground.contact = ContactLaw::SpringFriction;
        params.ground.restitution = restitution;
        let a = params.die.half_sizes[2];
        let initial = InitialCondition {
            height: a + drop_cm,
            velocity: [0.0; 3],
            angular_velocity: [0.0; 3],
            angular_momentum: None,
            orientation: [0.0; 3],
        };
        // Four copies fill every lane.
        let setups = vec![(params, initial); 4];
        let (scalar, lanes) = (run(roll_one_by_one, &setups), run(roll_in_lanes, &setups));
        assert_eq!(scalar, lanes, "e = {restitution}: the widths differ");
        let r = scalar[0].as_ref().unwrap();
        assert_eq!(r.status, Status::Settled, "e = {restitution}");
        assert_eq!(r.impacts, expected, "e = {restitution}, {drop_cm} cm");
        // Face 4 up, so face 3 down at the first impact, which is the fall's end:
        // √(2·drop/g) s, to within the step.
        let (step, _, face_down) = r.first_impact.unwrap();
        assert_eq!(face_down, 3);
        let fall_steps = (2.0 * drop_cm / params.world.gravity).sqrt() / params.integrator.dt;
        assert!(
            (step as f64 - fall_steps).abs() <= 1.5,
            "first impact at step {step}, fall {fall_steps}"
        );
    }
}
