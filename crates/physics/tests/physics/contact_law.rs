//! The spring-friction contact law against the results docs/model.md derives for it ("The
//! spring-friction contact", "Analytic checks"): an incline below and above its friction
//! angle, a ball sliding into rolling, a rough ball's spin reversed by a bounce, the sleeping
//! top either side of its critical rate, and the restitution of a flat drop.

use dicesim_physics::contact::{clamped_restitution, damping_ratio};
use dicesim_physics::{ContactLaw, InitialCondition, Params, Simulation, mass_properties};
use nalgebra::Vector3;

fn spring_friction() -> Params {
    let mut p = Params::default();
    p.ground.contact = ContactLaw::SpringFriction;
    p
}

/// A die at rest on its face 3, sunk to its resting depth.
fn resting(p: &Params) -> InitialCondition {
    InitialCondition {
        height: p.die.half_size() - p.resting_depth(),
        velocity: [0.0; 3],
        angular_velocity: [0.0; 3],
        ..InitialCondition::default()
    }
}

/// Steps `sim` for `seconds` of simulated time, calling `each` after every step.
fn run_for(sim: &mut Simulation, seconds: f64, mut each: impl FnMut(&Simulation)) {
    let steps = (seconds / sim.params().integrator.dt).round() as u64;
    for _ in 0..steps {
        sim.step();
        each(sim);
    }
}

/// The paper's cube resting on a table that tilts toward +x, raised from level to `tilt`
/// degrees slowly (a quarter degree every 20 ms, so its springs take up the load as it
/// comes) when `slowly`, else tilted from the start: (centre displacement over the 2 s after
/// the tilt is reached and the springs have settled for 0.2 s, cm; its acceleration along the
/// slope over the last 1.6 s of those, cm/s²).
fn on_the_incline(tilt: f64, static_friction: f64, kinetic: f64, slowly: bool) -> (f64, f64) {
    let mut p = spring_friction();
    p.ground.static_friction = static_friction;
    p.ground.friction = kinetic;
    p.integrator.max_time = 30.0;
    p.ground.tilt = if slowly { 0.0 } else { tilt };
    let mut sim = Simulation::new(&p, &resting(&p)).unwrap();
    let mut ground = p.ground;
    while slowly && ground.tilt < tilt {
        ground.tilt = (ground.tilt + 0.25).min(tilt);
        sim.set_ground(ground).unwrap();
        run_for(&mut sim, 0.02, |_| {});
    }
    run_for(&mut sim, 0.2, |_| {});
    let from = sim.state().position;
    run_for(&mut sim, 0.4, |_| {});
    let early_speed = sim.state().velocity.x;
    run_for(&mut sim, 1.6, |_| {});
    let s = sim.state();
    ((s.position - from).norm(), (s.velocity.x - early_speed) / 1.6)
}

fn slide_acceleration(tilt: f64, kinetic: f64) -> f64 {
    let theta = tilt.to_radians();
    980.0 * (theta.sin() - kinetic * theta.cos())
}

#[test]
fn on_an_incline_with_equal_coefficients_the_cube_holds_below_tan_theta_mu_and_slides_above() {
    let mu: f64 = 0.6;
    let friction_angle = mu.atan().to_degrees();
    for below in [20.0, friction_angle - 0.5] {
        let (creep, _) = on_the_incline(below, mu, mu, true);
        assert!(creep < 0.01, "{below}°: crept {creep} cm in 2 s");
    }
    // Placed on it at once, the die slides while its springs take up the load, then holds.
    let (creep, _) = on_the_incline(20.0, mu, mu, false);
    assert!(creep < 0.01, "placed at 20°: crept {creep} cm in 2 s");
    for above in [friction_angle + 0.5, 35.0] {
        for slowly in [true, false] {
            let (slid, a) = on_the_incline(above, mu, mu, slowly);
            let expected = slide_acceleration(above, mu);
            assert!(slid > 1.0, "{above}°: slid only {slid} cm");
            assert!(
                (a / expected - 1.0).abs() < 0.01,
                "{above}°: a = {a}, expected {expected}"
            );
        }
    }
}

#[test]
fn on_an_incline_the_cube_holds_below_its_derived_angle_and_slides_at_the_kinetic_rate() {
    let (static_friction, kinetic): (f64, f64) = (0.6, 0.5);
    // The uphill corners let go first: it holds while tan θ ≤ (μs + μk)/(2 − μs + μk).
    let holds_up_to = ((static_friction + kinetic) / (2.0 - static_friction + kinetic))
        .atan()
        .to_degrees();
    for below in [0.5f64.atan().to_degrees(), holds_up_to - 0.5] {
        let (creep, _) = on_the_incline(below, static_friction, kinetic, true);
        assert!(creep < 0.01, "{below}°: crept {creep} cm in 2 s");
    }
    // Between that angle and tan θ = μs it depends on what the uphill corners hold, anything
    // from μk·N to μs·N; above tan θ = μs it slides, and at the kinetic rate.
    for tilt in [static_friction.atan().to_degrees() + 0.5, 35.0] {
        let (slid, a) = on_the_incline(tilt, static_friction, kinetic, true);
        let expected = slide_acceleration(tilt, kinetic);
        assert!(slid > 1.0, "{tilt}°: slid only {slid} cm");
        assert!(
            (a / expected - 1.0).abs() < 0.01,
            "{tilt}°: a = {a}, expected {expected}"
        );
    }
}

/// A rounded die so round that it is a ball to 10⁻⁴ cm.
fn near_ball() -> Params {
    let mut p = spring_friction();
    p.die.corner_radius = 0.9999;
    p
}

/// The tangential velocity of the fastest touching contact point (a sphere's bottom), cm/s.
fn fastest_contact_point(sim: &Simulation) -> f64 {
    let s = sim.state();
    let w = sim.angular_velocity();
    let r = sim.params().die.corner_radius;
    (0..8)
        .filter(|&k| s.corner_depths[k] > 0.0)
        .map(|k| {
            let point = s.corner_offsets[k] - Vector3::new(0.0, 0.0, r);
            let u = s.velocity + w.cross(&point);
            (u.x * u.x + u.y * u.y).sqrt()
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_ball_launched_sliding_ends_rolling_at_v0_over_one_plus_k2_over_r2_and_is_not_braked() {
    let mut p = near_ball();
    p.integrator.dt = 1e-4;
    p.ground.friction = 0.3;
    p.ground.static_friction = 0.3;
    let props = mass_properties(&p.die);
    let k2 = props.inertia[(1, 1)] / props.mass;
    let radius = p.die.half_size();
    let v0 = 100.0;
    let rolling = v0 / (1.0 + k2 / (radius * radius));
    // The slip stops at v0/(μk·g·(1 + R²/k²)), 0.097 s here; look from 0.3 s on.
    let slip_ends = v0 / (0.3 * 980.0 * (1.0 + radius * radius / k2));
    assert!(slip_ends < 0.15);
    let mut sim = Simulation::new(
        &p,
        &InitialCondition {
            velocity: [v0, 0.0, 0.0],
            ..resting(&p)
        },
    )
    .unwrap();
    run_for(&mut sim, 0.3, |_| {});
    let mut fastest: f64 = 0.0;
    let mut speeds = Vec::new();
    run_for(&mut sim, 1.7, |sim| {
        fastest = fastest.max(fastest_contact_point(sim));
        speeds.push(sim.state().velocity.x);
    });
    for v in [speeds[0], *speeds.last().unwrap()] {
        assert!(
            (v / rolling - 1.0).abs() < 0.01,
            "rolls at {v}, expected {rolling}"
        );
    }
    assert!(fastest < 0.1, "a contact point moved at {fastest} cm/s");
    // Rolling on: less than 0.1 % lost over 1.7 s.
    assert!(speeds[0] - speeds.last().unwrap() < 1e-3 * rolling, "{speeds:?}");
}

#[test]
fn a_rough_ball_with_backspin_leaves_with_forward_spin_by_the_docs_formulas() {
    let mut p = near_ball();
    p.integrator.dt = 1e-5;
    // Gravity's impulse over the contact is kept out of the contact's numbers.
    p.world.gravity = 10.0;
    p.ground.restitution = 0.8;
    p.ground.static_friction = 1.0;
    p.ground.friction = 1.0;
    let props = mass_properties(&p.die);
    let (mass, inertia, radius) = (props.mass, props.inertia[(1, 1)], p.die.half_size());
    let (vx, wy, v_in) = (200.0, -50.0, 200.0);
    let mut sim = Simulation::new(
        &p,
        &InitialCondition {
            height: radius + 0.5 * v_in * p.integrator.dt,
            velocity: [vx, 0.0, -v_in],
            angular_velocity: [0.0, wy, 0.0],
            ..InitialCondition::default()
        },
    )
    .unwrap();
    let mut touched = false;
    while !touched || sim.in_contact() {
        sim.step();
        touched |= sim.in_contact();
    }
    let u0 = vx - radius * wy;
    let tangential_mass = 1.0 / (1.0 / mass + radius * radius / inertia);
    let ratio = p.ground.tangential_stiffness_ratio;
    assert!(
        ratio * u0 / v_in <= p.ground.static_friction,
        "it sticks throughout"
    );
    // The 8 sphere bottoms press together: the ball's damping ratio is √2·ζ.
    let beta = clamped_restitution(2f64.sqrt() * damping_ratio(p.ground.restitution));
    let vx_out = vx - tangential_mass / mass * (1.0 + beta) * u0;
    let wy_out = wy + radius * tangential_mass / inertia * (1.0 + beta) * u0;
    let (v, w) = (sim.state().velocity, sim.angular_velocity());
    assert!(w.y > 0.0, "the spin reversed: ω′_y = {}", w.y);
    assert!(
        (w.y / wy_out - 1.0).abs() < 0.02,
        "ω′_y = {}, expected {wy_out}",
        w.y
    );
    assert!(
        (v.x / vx_out - 1.0).abs() < 0.02,
        "v′_x = {}, expected {vx_out}",
        v.x
    );
    assert!((v.z / (beta * v_in) - 1.0).abs() < 0.02, "v′_z = {}", v.z);
}

#[test]
fn the_papers_law_cannot_reverse_a_balls_spin() {
    let mut p = near_ball();
    p.ground.contact = ContactLaw::Paper;
    p.integrator.dt = 1e-5;
    let mut sim = Simulation::new(
        &p,
        &InitialCondition {
            height: 1.001,
            velocity: [200.0, 0.0, -200.0],
            angular_velocity: [0.0, -50.0, 0.0],
            ..InitialCondition::default()
        },
    )
    .unwrap();
    let mut touched = false;
    while !touched || sim.in_contact() {
        sim.step();
        touched |= sim.in_contact();
    }
    // Kinetic friction only drives the contact point's slip toward zero (from u₀ = 250 cm/s):
    // it leaves rolling forward at most, never with the slip reversed as a stuck spring does.
    let (v, w) = (sim.state().velocity, sim.angular_velocity());
    let slip = v.x - p.die.half_size() * w.y;
    assert!(slip > -0.01 * 250.0, "v′_x {} ω′_y {}: slip {slip}", v.x, w.y);
}

/// The paper's cube standing on corner 1 with its diagonal `tilt` degrees off the vertical
/// toward +x, spun at `rate` rad/s about it: (largest angle of the diagonal from the vertical
/// in 2 s, degrees; when a second corner first touched, s).
fn sleeping_top(rate: f64, tilt: f64) -> (f64, Option<f64>) {
    let mut p = spring_friction();
    p.integrator.dt = 1e-4;
    let l = p.die.half_size() * 3f64.sqrt();
    let weight = p.total_mass() * p.world.gravity;
    // Roll 45° about x takes the diagonal (1, 1, 1) to (1, 0, √2); the pitch then turns it
    // to `tilt` from the vertical.
    let pitch = tilt - 1f64.atan2(2f64.sqrt()).to_degrees();
    let axis = Vector3::new(tilt.to_radians().sin(), 0.0, tilt.to_radians().cos());
    let initial = InitialCondition {
        // The tip at its rest depth under the whole weight.
        height: l * tilt.to_radians().cos() - weight / p.ground.stiffness,
        velocity: [0.0; 3],
        angular_velocity: (axis * rate).into(),
        angular_momentum: None,
        orientation: [0.0, pitch, 45.0],
    };
    let mut sim = Simulation::new_unchecked(&p, &initial);
    let diagonal = |sim: &Simulation| {
        let r = &sim.state().corner_offsets;
        (r[7] - r[0]).normalize()
    };
    assert!((diagonal(&sim).z.acos().to_degrees() - tilt).abs() < 1e-9);
    let (mut widest, mut second): (f64, Option<f64>) = (0.0, None);
    run_for(&mut sim, 2.0, |sim| {
        widest = widest.max(diagonal(sim).z.acos().to_degrees());
        let s = sim.state();
        if second.is_none() && (1..8).any(|k| s.corner_depths[k] > 0.0) {
            second = Some(s.time_s);
        }
    });
    (widest, second)
}

#[test]
fn the_sleeping_top_stands_above_its_critical_rate_and_falls_below_it() {
    let p = Params::default();
    let (mass, a, g) = (p.total_mass(), p.die.half_size(), p.world.gravity);
    let l = a * 3f64.sqrt();
    let i3 = p.inertia();
    let i1 = i3 + mass * l * l;
    let critical = 2.0 * (mass * g * l * i1).sqrt() / i3;
    assert!((critical - 236.7).abs() < 0.05, "ω_c = {critical}");
    let (widest, second) = sleeping_top(1.2 * critical, 1.0);
    assert!(widest < 5.0, "at 1.2 ω_c the diagonal leaned {widest}°");
    assert_eq!(second, None, "at 1.2 ω_c a second corner touched");
    let (_, second) = sleeping_top(0.7 * critical, 1.0);
    assert!(second.is_some_and(|t| t < 1.0), "at 0.7 ω_c: {second:?}");
}

/// A flat drop of the paper's cube at `speed` cm/s: rebound speed over impact speed.
fn flat_drop_restitution(e: f64, speed: f64, dt: f64, gravity: f64) -> f64 {
    let mut p = spring_friction();
    p.ground.restitution = e;
    p.integrator.dt = dt;
    p.world.gravity = gravity;
    let mut sim = Simulation::new(
        &p,
        &InitialCondition {
            height: 1.0 + 0.5 * speed * dt,
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
    }
}

#[test]
fn a_flat_drop_rebounds_at_the_set_restitution_whatever_the_speed() {
    // At 10 cm/s² gravity's impulse over the contact is 0.06 cm/s: the contact's own number.
    for e in [0.2, 0.5, 0.9] {
        for speed in [50.0, 100.0, 200.0, 300.0] {
            let measured = flat_drop_restitution(e, speed, 1e-5, 10.0);
            assert!((measured - e).abs() < 0.02, "e = {e} at {speed} cm/s: {measured}");
        }
    }
    // At 1 ms a contact lasts about 6 steps; the spread over speeds stays small.
    let coarse: Vec<f64> = [50.0, 300.0]
        .map(|v| flat_drop_restitution(0.5, v, 1e-3, 10.0))
        .into();
    assert!((coarse[0] - coarse[1]).abs() < 0.002, "{coarse:?}");
    assert!(coarse.iter().all(|x| (x - 0.5).abs() < 0.02), "{coarse:?}");
}

#[test]
fn a_point_that_leaves_the_table_forgets_its_spring() {
    let mut p = spring_friction();
    p.ground.restitution = 0.9;
    let mut sim = Simulation::new(
        &p,
        &InitialCondition {
            height: 3.0,
            velocity: [80.0, 0.0, 0.0],
            angular_velocity: [3.0, -7.0, 2.0],
            orientation: [10.0, 20.0, 30.0],
            ..InitialCondition::default()
        },
    )
    .unwrap();
    let (mut held, mut leaves) = (false, 0);
    run_for(&mut sim, 1.0, |sim| {
        let (s, springs) = (sim.state(), sim.tangential_springs());
        for (k, xi) in springs.iter().enumerate() {
            if s.corner_depths[k] > 0.0 {
                held |= xi.norm() > 0.0;
            } else {
                assert_eq!(
                    (xi.x, xi.y),
                    (0.0, 0.0),
                    "corner {} off the table holds a spring",
                    k + 1
                );
            }
        }
        leaves += (!sim.in_contact()) as u32;
    });
    assert!(held && leaves > 0, "the die touched, held and bounced off");
}
