//! The face restitution `e_f` (docs/model.md, "A loss that tells a face fall from a bounce in
//! flight") against what it does to one impact: a landing from flight never reads it, and a
//! fall onto a face over an edge keeps the energy its `e_f` gives, whatever `e`.

use dicesim_physics::contact::{clamped_restitution, damping_ratio, flat_drop_contact_time};
use dicesim_physics::{ContactLaw, InitialCondition, Params, Simulation};

fn spring_friction(e: f64, e_f: Option<f64>) -> Params {
    let mut p = Params::default();
    p.ground.contact = ContactLaw::SpringFriction;
    p.ground.restitution = e;
    p.ground.face_restitution = e_f;
    p
}

/// Steps the same start under `p` and under `p` with the face restitution `e_f`, asserting
/// every step's state bit for bit alike, until the die has touched the table and left it
/// again; returns the vertical velocity before the first touch and after leaving, cm/s.
fn alike_until_it_leaves(p: &Params, e_f: f64, initial: &InitialCondition) -> (f64, f64) {
    let mut face = *p;
    face.ground.face_restitution = Some(e_f);
    let mut plain = Simulation::new(p, initial).unwrap();
    let mut with = Simulation::new(&face, initial).unwrap();
    let mut impact = None;
    for step in 0.. {
        let before = plain.state().velocity.z;
        plain.step();
        with.step();
        let (a, b) = (plain.state(), with.state());
        assert!(
            a.position == b.position
                && a.velocity == b.velocity
                && a.angular_momentum == b.angular_momentum
                && a.corner_forces == b.corner_forces,
            "step {step}: e_f = {e_f} changed a landing from flight"
        );
        if impact.is_none() && plain.in_contact() {
            impact = Some(before);
        }
        if let Some(impact) = impact
            && !plain.in_contact()
        {
            return (impact, a.velocity.z);
        }
        assert!(step < 1_000_000, "the die never left the table");
    }
    unreachable!()
}

#[test]
fn a_landing_from_flight_never_reads_the_face_restitution() {
    // A flat drop tilted 0.1° at 100 cm/s: its two edges touch 35 µs apart, far within the
    // flat drop's contact time, so both land from flight, keep `e` and are bit for bit the law
    // without `e_f`. On the default table (ω_n = √(4k/M) = 500 rad/s) at e = 0.5 (ζ = 0.2553)
    // that time is (π − 2·asin ζ)/(ω_n·√(1 − ζ²)) = 5.43 ms.
    let mut p = spring_friction(0.5, None);
    p.integrator.dt = 1e-5;
    p.world.gravity = 10.0;
    let t_c = flat_drop_contact_time(p.ground.stiffness, 8.0, damping_ratio(0.5));
    assert!((t_c - 5.431e-3).abs() < 1e-6, "t_c = {t_c}");
    let tilted = InitialCondition {
        height: 1.01,
        velocity: [0.0, 0.0, -100.0],
        angular_velocity: [0.0; 3],
        orientation: [0.0, 0.1, 0.0],
        ..InitialCondition::default()
    };
    for e_f in [0.2, 0.9] {
        let (impact, rebound) = alike_until_it_leaves(&p, e_f, &tilted);
        assert!(
            (rebound / -impact - 0.5).abs() < 0.02,
            "e_f = {e_f}: {rebound} / {impact}"
        );
    }
    // A corner strike with spin, on the paper's table and step.
    let p = spring_friction(0.8, None);
    let corner = InitialCondition {
        height: 3.0,
        velocity: [20.0, 0.0, -50.0],
        angular_velocity: [5.0, -7.0, 2.0],
        orientation: [10.0, 35.26, 45.0],
        ..InitialCondition::default()
    };
    alike_until_it_leaves(&p, 0.2, &corner);
}

/// The paper's cube tipped to 44° on its edge (1° short of balance, the edge 2 µm above the
/// table) and let fall onto its face, on a stiff table (k = 2·10⁷ dyn/cm, Δt = 20 µs, a contact
/// of about 1 ms) with a stiff tangential spring (k_t/k = 2): the total energy 5 ms after the
/// far edge strikes over the energy just before it, both from the die resting on its face.
fn face_fall_keeps(e: f64, e_f: Option<f64>) -> f64 {
    let mut p = spring_friction(e, e_f);
    p.ground.stiffness = 2e7;
    p.ground.tangential_stiffness_ratio = 2.0;
    p.integrator.dt = 2e-5;
    let mut sim = Simulation::new(
        &p,
        &InitialCondition {
            // The edge 2 µm above the table: its centre at a·√2·cos 1° above it.
            height: 2f64.sqrt() * 1f64.to_radians().cos() + 2e-4,
            velocity: [0.0; 3],
            angular_velocity: [0.0; 3],
            orientation: [0.0, 0.0, 44.0],
            ..InitialCondition::default()
        },
    )
    .unwrap();
    let pivot: Vec<usize> = (0..8)
        .filter(|&k| sim.state().corner_offsets[k].z < -1.0)
        .collect();
    assert_eq!(pivot.len(), 2, "one edge lowest");
    let mut struck = None;
    loop {
        let energy = sim.energy().total();
        sim.step();
        let s = sim.state();
        let far_edge_touches = (0..8).any(|k| !pivot.contains(&k) && s.corner_depths[k] > 0.0);
        if struck.is_none() && far_edge_touches {
            struck = Some((energy, s.time_s));
        }
        if let Some((before, at)) = struck
            && s.time_s >= at + 0.005
        {
            return sim.energy().total() / before;
        }
        assert!(s.time_s < 2.0, "the die never fell onto its face");
    }
}

/// `R(e) = (1 + 15·e²)/16`, the energy a rigid cube keeps falling onto its face over an edge
/// that sticks, with the landing edge's rebound `e(ζ/√1.25)`: the two points of the edge act on
/// the edge's effective mass 5M/8, not M/4 each, so its damping ratio is `ζ/√1.25`.
fn face_fall_rigid(e: f64) -> f64 {
    let edge = clamped_restitution(damping_ratio(e) / 1.25f64.sqrt());
    (1.0 + 15.0 * edge * edge) / 16.0
}

#[test]
fn a_face_fall_keeps_what_the_face_restitution_gives_whatever_e() {
    // e_f = 0.3: R = 0.166. The rest of the law (the tangential springs' damping, the lifting
    // edge's own dashpot) moves it by a few per cent; a fall that took `e` instead would keep
    // about R(0.8) = 0.69.
    let expected = face_fall_rigid(0.3);
    assert!((expected - 0.166).abs() < 1e-3, "{expected}");
    let lively = face_fall_keeps(0.8, Some(0.3));
    let dead = face_fall_keeps(0.5, Some(0.3));
    for kept in [lively, dead] {
        assert!(
            (kept / expected - 1.0).abs() < 0.08,
            "kept {kept}, R = {expected}"
        );
    }
    assert!(
        (lively / dead - 1.0).abs() < 0.06,
        "e moved the face fall: {lively} against {dead}"
    );
    // Without the key the face fall takes `e`: the law as it was.
    let plain = face_fall_keeps(0.8, None);
    assert!((plain / face_fall_rigid(0.8) - 1.0).abs() < 0.08, "kept {plain}");
    assert!((face_fall_keeps(0.3, None) / dead - 1.0).abs() < 0.03);
}
