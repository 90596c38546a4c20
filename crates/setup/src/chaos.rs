//! The chaos twin: a second die whose start differs from the first by a relative ε, and how
//! far apart the two have drifted.
//!
//! ε is defined on the start's magnitudes that set the motion: the twin's drop height, its
//! centre-of-mass velocity and its spin (ω, or L when the start states L) are each the first
//! die's times (1 + ε). The orientation is the same. So at t = 0 the centres are ε·h apart.

use dicesim_physics::{InitialCondition, Limits, Outcome, Params, Roll, RollingDie};
use serde::Serialize;

/// The range a user may set ε in: from a few units in the last place of a double to 10%.
pub const EPSILON: Limits = Limits {
    key: "twin.epsilon",
    unit: "",
    min: 1e-15,
    max: 1e-1,
};

/// The ε a twin rolls at when none is asked for: far below anything a hand controls, and
/// still the two dice part within a roll.
pub const DEFAULT_EPSILON: f64 = 1e-9;

/// The twin's start: height, velocity and spin times (1 + ε).
pub fn perturbed(initial: &InitialCondition, epsilon: f64) -> InitialCondition {
    let f = 1.0 + epsilon;
    InitialCondition {
        height: initial.height * f,
        velocity: initial.velocity.map(|v| v * f),
        angular_velocity: initial.angular_velocity.map(|w| w * f),
        angular_momentum: initial.angular_momentum.map(|l| l.map(|x| x * f)),
        orientation: initial.orientation,
    }
}

/// How far apart two dice are.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Separation {
    /// cm, between the centres of mass.
    pub centre: f64,
    /// rad, the angle of the rotation that turns one die's orientation into the other's.
    pub angle: f64,
}

/// The separation of two dice at their current states (the box's `Simulation`s or any
/// die's `Roll`s).
pub fn separation(a: &dyn RollingDie, b: &dyn RollingDie) -> Separation {
    let centre = (a.position() - b.position()).norm();
    // ‖R₁ − R₂‖_F = 2√2·sin(θ/2): exact for tiny angles, where acos of the trace is not.
    let (ra, rb) = (a.orientation(), b.orientation());
    let frobenius = (0..3)
        .map(|i| (ra.matrix().column(i) - rb.matrix().column(i)).norm_squared())
        .sum::<f64>()
        .sqrt();
    let angle = 2.0 * (frobenius / (2.0 * std::f64::consts::SQRT_2)).min(1.0).asin();
    Separation { centre, angle }
}

/// Rolls a die and its twin to their ends in lock-step; returns both outcomes and the
/// separation after each step (index 0 is t = 0).
pub fn roll_twins(
    params: &Params,
    initial: &InitialCondition,
    epsilon: f64,
) -> (Outcome, Outcome, Vec<Separation>) {
    let mut a = Roll::new_unchecked(params, initial);
    let mut b = Roll::new_unchecked(params, &perturbed(initial, epsilon));
    let mut trace = vec![separation(&a, &b)];
    loop {
        if let (Some(oa), Some(ob)) = (a.outcome(), b.outcome()) {
            return (oa, ob, trace);
        }
        for s in [&mut a, &mut b] {
            if s.outcome().is_none() {
                s.advance();
            }
        }
        trace.push(separation(&a, &b));
    }
}
