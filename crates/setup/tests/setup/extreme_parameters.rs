//! Whatever the parameters, a roll ends in a status (or is refused by validation), never a
//! panic or an endless loop.

use dicesim_physics::params::{Limits, MAX_STEPS_CAP};
use dicesim_physics::{FrictionLaw, InitialCondition, Params, Simulation, StopEnergy};
use dicesim_setup::registry;
use proptest::prelude::*;

/// Values across a field's range and beyond it, NaN and infinities included.
fn across_and_beyond(l: Limits) -> impl Strategy<Value = f64> {
    let span = l.max - l.min;
    prop_oneof![
        6 => l.min..=l.max,
        1 => l.max..l.max + 10.0 * span.max(1.0),
        1 => l.min - 10.0 * span.max(1.0)..l.min,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
    ]
}

fn any_params() -> impl Strategy<Value = Params> {
    (
        (
            across_and_beyond(registry::HALF_SIZES.limits),
            across_and_beyond(registry::CORNER_MASS.limits),
        ),
        (
            across_and_beyond(registry::STIFFNESS.limits),
            across_and_beyond(registry::DAMPING.limits),
            across_and_beyond(registry::FRICTION.limits),
        ),
        across_and_beyond(registry::GRAVITY.limits),
        // Short time caps keep each case fast; the dt range is covered in full.
        (across_and_beyond(registry::DT.limits), 0.01f64..2.0),
        (any::<bool>(), any::<bool>()),
    )
        .prop_map(|((a, m), (k, gamma, mu), g, (dt, max_time), (law, stop))| {
            let mut p = Params::default();
            p.die.half_sizes = [a; 3];
            p.die.corner_mass = m;
            p.ground.stiffness = k;
            p.ground.damping = gamma;
            p.ground.friction = mu;
            p.ground.friction_law = if law {
                FrictionLaw::WholeDieNorm
            } else {
                FrictionLaw::PerCorner
            };
            p.world.gravity = g;
            p.integrator.dt = dt;
            p.integrator.max_time = max_time;
            p.integrator.stop_energy = if stop {
                StopEnergy::PointMasses
            } else {
                StopEnergy::RigidBody
            };
            p
        })
}

fn any_initial() -> impl Strategy<Value = InitialCondition> {
    (
        -5.0f64..40.0,
        prop::array::uniform3(-300.0f64..300.0),
        prop::array::uniform3(-200.0f64..200.0),
        prop::array::uniform3(-180.0f64..180.0),
    )
        .prop_map(
            |(height, velocity, angular_velocity, orientation)| InitialCondition {
                height,
                velocity,
                angular_velocity,
                orientation,
                angular_momentum: None,
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn every_roll_ends_or_is_refused(params in any_params(), initial in any_initial()) {
        match Simulation::new(&params, &initial) {
            Ok(mut sim) => {
                let outcome = sim.run_to_end();
                prop_assert!(outcome.steps <= params.max_steps());
                prop_assert!(outcome.face.is_none_or(|f| (1..=6).contains(&f)));
            }
            Err(e) => {
                // The error names a field whose value is really out of its range.
                let msg = e.to_string();
                prop_assert!(msg.contains(&e.key) && msg.contains("allowed range"), "{}", msg);
                prop_assert!(!(e.value >= e.limits.min && e.value <= e.limits.max), "{}", msg);
            }
        }
    }

    #[test]
    fn unvalidated_parameters_still_end(params in any_params(), initial in any_initial()) {
        let mut sim = Simulation::new_unchecked(&params, &initial);
        let outcome = sim.run_to_end();
        prop_assert!(outcome.steps <= MAX_STEPS_CAP);
    }
}
