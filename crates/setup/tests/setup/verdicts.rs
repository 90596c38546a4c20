//! The verdicts over the whole allowed range: thousands of parameter sets drawn across every
//! range (log-uniform where a range spans decades), each rolled from a random start.
//!
//! Every `settled` roll must be honest (a face, close to rest on the table); the stability
//! predictor must rarely call an unstable set stable, and an unstable roll's stated reason
//! must name a limit the set really passes. The figures are printed (`--nocapture`).

use dicesim_physics::resting_depth_on_face;
use dicesim_physics::{
    FrictionLaw, InitialCondition, Limit, Limits, Params, Simulation, Stability, Status, StopEnergy,
    UnstableReason,
};
use dicesim_setup::registry::{
    ANGULAR_VELOCITY, CORNER_MASS, DAMPING, DT, FRICTION, GRAVITY, HALF_SIZES, HEIGHT, ORIENTATION,
    STIFFNESS, STOP_ENERGY_FRACTION, VELOCITY,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::cell::RefCell;

/// Parameter sets in the sample.
const CASES: u32 = 2000;
/// No roll runs longer than this many steps: long enough for most stable sets to settle,
/// short enough that the whole sample runs in seconds.
const MAX_STEPS: f64 = 10_000.0;

fn uniform(l: Limits, u: f64) -> f64 {
    l.min + (l.max - l.min) * u
}

fn log_uniform(l: Limits, u: f64) -> f64 {
    (l.min.ln() + (l.max.ln() - l.min.ln()) * u)
        .exp()
        .clamp(l.min, l.max)
}

/// A signed magnitude, log-uniform from 0.1 to the range's end.
fn signed_log(l: Limits, sign: f64, u: f64) -> f64 {
    let magnitude = (0.1f64.ln() + (l.max.ln() - 0.1f64.ln()) * u).exp();
    if sign < 0.5 { -magnitude } else { magnitude }
}

/// One parameter set and start from 24 uniform numbers in [0, 1).
fn draw(u: &[f64; 24]) -> (Params, InitialCondition) {
    let mut p = Params::default();
    p.die.half_sizes = [log_uniform(HALF_SIZES.limits, u[0]); 3];
    p.die.corner_mass = log_uniform(CORNER_MASS.limits, u[1]);
    p.ground.stiffness = log_uniform(STIFFNESS.limits, u[2]);
    p.ground.damping = uniform(DAMPING.limits, u[3]);
    p.ground.friction = uniform(FRICTION.limits, u[4]);
    p.ground.friction_law = if u[5] < 0.5 {
        FrictionLaw::PerCorner
    } else {
        FrictionLaw::WholeDieNorm
    };
    p.world.gravity = log_uniform(GRAVITY.limits, u[6]);
    p.integrator.dt = log_uniform(DT.limits, u[7]);
    p.integrator.stop_energy_fraction = uniform(STOP_ENERGY_FRACTION.limits, u[8]);
    p.integrator.stop_energy = if u[9] < 0.5 {
        StopEnergy::RigidBody
    } else {
        StopEnergy::PointMasses
    };
    p.integrator.max_time = (MAX_STEPS * p.integrator.dt).min(120.0);
    let mut ic = InitialCondition {
        orientation: [0, 1, 2].map(|i| uniform(ORIENTATION.limits, u[10 + i]) / 2.0),
        velocity: [0, 1, 2].map(|i| signed_log(VELOCITY.limits, u[13 + i], u[16 + i])),
        ..InitialCondition::default()
    };
    // Spin on a third of the starts is left at rest, so gentle drops are in the sample too.
    ic.angular_velocity = if u[19] < 1.0 / 3.0 {
        [0.0; 3]
    } else {
        [0, 1, 2].map(|i| {
            signed_log(
                ANGULAR_VELOCITY.limits,
                u[20 + i],
                (u[19] + 0.37 * i as f64) % 1.0,
            )
        })
    };
    // From just clear of the table to a hundred half sizes above it.
    let clearance = -ic.lowest_corner_offset(&p);
    let lift = p.die.half_size() * (10f64.ln() * (-2.0 + 4.0 * u[23])).exp();
    ic.height = (clearance + lift).min(HEIGHT.limits.max);
    (p, ic)
}

#[derive(Default)]
struct Figures {
    rolls: u32,
    settled: u32,
    timeout: u32,
    unstable: u32,
    called_stable: u32,
    called_stable_unstable: u32,
    unstable_reason_exceeded: u32,
    /// In rest depths: the deepest and the highest lowest corner among settled rolls.
    deepest: f64,
    highest: f64,
    /// Per limit: sets past it, and of those the ones that did not end unstable.
    past: [u32; 6],
    past_not_unstable: [u32; 6],
    depths: Vec<f64>,
}

#[test]
fn verdicts_hold_across_every_allowed_range() {
    let config = Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    };
    let seed: [u8; 32] = *b"dicesim verdicts over the ranges";
    let mut runner = TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &seed));
    let figures = RefCell::new(Figures::default());
    let result = runner.run(&proptest::array::uniform24(0.0..1.0f64), |u| {
        let (p, ic) = draw(&u);
        let mut sim = Simulation::new(&p, &ic).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let outcome = sim.run_to_end();
        let prediction = Stability::predict(&p, &ic);
        let mut f = figures.borrow_mut();
        f.rolls += 1;
        for r in prediction.readings() {
            let i = r.limit as usize;
            if r.exceeded() {
                f.past[i] += 1;
                f.past_not_unstable[i] += (outcome.status != Status::Unstable) as u32;
            }
        }
        if prediction.is_stable() {
            f.called_stable += 1;
            f.called_stable_unstable += (outcome.status == Status::Unstable) as u32;
        }
        match outcome.status {
            Status::Settled => {
                f.settled += 1;
                let what = format!("{p:?} {ic:?} {outcome:?}");
                prop_assert!(outcome.face.is_some(), "settled without a face: {what}");
                let rule = sim.stop_rule();
                prop_assert!(rule.can_settle());
                prop_assert!(
                    sim.stop_kinetic_energy() <= rule.kinetic_threshold,
                    "kinetic {} above {}: {what}",
                    sim.stop_kinetic_energy(),
                    rule.kinetic_threshold
                );
                prop_assert!(sim.energy().kinetic() <= rule.kinetic_threshold, "{what}");
                prop_assert!(sim.state().position.z >= 0.0, "centre below the table: {what}");
                // The lowest corner, in rest depths above (+) or below (−) the table.
                let lowest = sim
                    .corner_positions()
                    .iter()
                    .map(|c| c.z)
                    .fold(f64::INFINITY, f64::min);
                let in_depths = lowest / resting_depth_on_face(&p);
                f.deepest = f.deepest.min(in_depths);
                f.highest = f.highest.max(in_depths);
                f.depths.push(-in_depths);
                // What the rule's energy bound allows (docs/model.md, "Stopping rule"): with
                // E − V_rest ≤ K_max, a corner d deep gives ½·k·((d − 4δ)² − 12δ²) ≤ K_max,
                // and one h in the air M·g·h ≤ K_max. Point masses count the same energies.
                let (k, delta) = (p.ground.stiffness, p.resting_depth());
                let slack = 1.0 + 1e-9;
                let deepest = 4.0 * delta + (12.0 * delta * delta + 2.0 * rule.kinetic_threshold / k).sqrt();
                let highest = rule.kinetic_threshold / (p.total_mass() * p.world.gravity);
                prop_assert!(
                    -lowest <= deepest * slack,
                    "lowest corner {lowest} cm, bound {deepest}: {what}"
                );
                prop_assert!(
                    lowest <= highest * slack,
                    "lowest corner {lowest} cm, bound {highest}: {what}"
                );
            }
            Status::Timeout => f.timeout += 1,
            Status::Unstable => {
                f.unstable += 1;
                f.unstable_reason_exceeded += UnstableReason::new(&p, &ic).0.exceeded() as u32;
            }
        }
        Ok(())
    });
    let f = figures.into_inner();
    let pct = |a: u32, b: u32| 100.0 * f64::from(a) / f64::from(b.max(1));
    println!(
        "{} rolls: settled {}, timeout {}, unstable {}",
        f.rolls, f.settled, f.timeout, f.unstable
    );
    println!(
        "called stable {}: ended unstable {} ({:.2} %)",
        f.called_stable,
        f.called_stable_unstable,
        pct(f.called_stable_unstable, f.called_stable)
    );
    println!(
        "ended unstable {}: the stated reason names an exceeded limit in {} ({:.2} %)",
        f.unstable,
        f.unstable_reason_exceeded,
        pct(f.unstable_reason_exceeded, f.unstable)
    );
    println!(
        "settled rolls' lowest corner: from {:.2} rest depths below to {:.2} above the table",
        -f.deepest, f.highest
    );
    let mut d = f.depths.clone();
    d.sort_by(f64::total_cmp);
    if !d.is_empty() {
        let q = |x: f64| d[((d.len() - 1) as f64 * x) as usize];
        println!(
            "depth quantiles (rest depths) 50% {:.2} 90% {:.2} 99% {:.2}",
            q(0.5),
            q(0.9),
            q(0.99)
        );
    }
    for (i, limit) in [
        Limit::ContactMode,
        Limit::CornerTravel,
        Limit::Damping,
        Limit::FrictionChatter,
        Limit::ImpactDepth,
        Limit::TangentialMode,
    ]
    .iter()
    .enumerate()
    {
        assert_eq!(*limit as usize, i);
        println!(
            "past the {} limit: {} sets, {} of them did not end unstable",
            limit.name(),
            f.past[i],
            f.past_not_unstable[i]
        );
    }
    result.unwrap();
    assert_eq!(f.rolls, CASES);
    assert!(
        f.settled >= CASES / 20,
        "the sample must exercise the stopping rule"
    );
    assert!(f.unstable >= CASES / 20, "the sample must exercise the predictor");
    assert!(pct(f.called_stable_unstable, f.called_stable) <= 1.0);
    assert!(pct(f.unstable_reason_exceeded, f.unstable) >= 95.0);
}
