//! The compliant table (docs/model.md, "A compliant table") against what it does to one flat
//! drop: momentum shared with a free table top, the die leaving at
//! `e_eff = (e_rel·m_T − M)/(M + m_T)`, falling with the body's mass and reaching today's `e` as
//! the top grows heavy.

use dicesim_physics::contact::{clamped_restitution, damping_ratio};
use dicesim_physics::{ContactLaw, InitialCondition, Params, Simulation};

/// A flat drop of the paper's cube (8 g) at `speed` cm/s onto a table top of `table_mass` g on
/// no spring (`None`: a rigid table), gravity 10 cm/s² and Δt = 10 µs so that the contact is
/// the spring's alone: the vertical velocity when the die leaves the top over the impact speed
/// (negative: it still moves down, slower than the top).
fn flat_drop(e: f64, table_mass: Option<f64>, speed: f64) -> f64 {
    flat_drop_of(1.0, e, table_mass, speed)
}

/// [`flat_drop`] of the cube whose corners weigh `corner_mass` g each.
fn flat_drop_of(corner_mass: f64, e: f64, table_mass: Option<f64>, speed: f64) -> f64 {
    let mut p = Params::default();
    p.die.corner_mass = corner_mass;
    p.ground.contact = ContactLaw::SpringFriction;
    p.ground.restitution = e;
    p.ground.table_mass = table_mass;
    p.integrator.dt = 1e-5;
    p.world.gravity = 10.0;
    let mut sim = Simulation::new(
        &p,
        &InitialCondition {
            height: 1.0 + 0.5 * speed * p.integrator.dt,
            velocity: [0.0, 0.0, -speed],
            angular_velocity: [0.0; 3],
            ..InitialCondition::default()
        },
    )
    .unwrap();
    let mut impact = None;
    loop {
        let before = sim.state().velocity.z;
        sim.step();
        if impact.is_none() && sim.in_contact() {
            impact = Some(-before);
        }
        if let Some(impact) = impact
            && !sim.in_contact()
        {
            return sim.state().velocity.z / impact;
        }
        assert!(sim.state().time_s < 1.0, "the die never left the table top");
    }
}

/// `e_eff` of docs/model.md: the contact springs on the relative motion of reduced mass
/// `M·m_T/(M + m_T)` rebound with `e_rel = e(ζ·√(1 + M/m_T))`, and momentum is shared.
fn shared(e: f64, mass: f64, table_mass: f64) -> f64 {
    let relative = clamped_restitution(damping_ratio(e) * (1.0 + mass / table_mass).sqrt());
    (relative * table_mass - mass) / (mass + table_mass)
}

#[test]
fn a_drop_onto_a_free_table_top_shares_its_momentum_and_leaves_at_e_eff() {
    // M/m_T from 0.05 to 1: e_eff from 0.71 down through zero (the die follows the top down).
    for table_mass in [160.0, 40.0, 16.0, 8.0] {
        let expected = shared(0.8, 8.0, table_mass);
        for speed in [50.0, 200.0] {
            let measured = flat_drop(0.8, Some(table_mass), speed);
            assert!(
                (measured - expected).abs() < 0.02,
                "m_T = {table_mass} g at {speed} cm/s: {measured}, e_eff = {expected}"
            );
        }
    }
    assert!(
        shared(0.8, 8.0, 8.0) < 0.0,
        "an equal top takes more than the die keeps"
    );
    // A heavy top is the rigid table: e itself.
    let heavy = flat_drop(0.8, Some(1e6), 100.0);
    let rigid = flat_drop(0.8, None, 100.0);
    assert!(
        (heavy - rigid).abs() < 1e-3 && (rigid - 0.8).abs() < 0.02,
        "{heavy} {rigid}"
    );
}

#[test]
fn a_heavier_body_keeps_less_on_the_same_top() {
    // The same 40 g top under the 8 g die and under a die eight times as heavy (64 g): the
    // restitution falls with the body's mass, which no restitution of one point can make (the
    // law's dashpot scales with the body).
    let light = flat_drop(0.8, Some(40.0), 100.0);
    let heavy = flat_drop_of(8.0, 0.8, Some(40.0), 100.0);
    assert!((light - shared(0.8, 8.0, 40.0)).abs() < 0.02, "{light}");
    assert!((heavy - shared(0.8, 64.0, 40.0)).abs() < 0.02, "{heavy}");
    assert!(heavy < light - 0.5);
}
