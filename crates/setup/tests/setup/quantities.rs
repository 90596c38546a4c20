//! Every quantity of the registry, read at the start of the paper's roll, equals its value
//! worked out by hand from the preset's numbers (docs/model.md: a uniform solid cube of
//! eight 1 g corners, I = (2a)²/6·M).

use dicesim_physics::Simulation;
use dicesim_setup::preset::Store;
use dicesim_setup::quantity::{QUANTITIES, read_all};

/// The paper's throw as its preset states it (presets/paper.toml), and the analytic value of
/// every quantity at t = 0, by the quantity's CSV column.
fn expected_at_start() -> Vec<(&'static str, f64)> {
    let (a, m_corner, g, dt) = (1.0, 1.0, 980.0, 0.001);
    let (k, gamma, mu) = (500_000.0, 0.005, 1.2);
    let mass = 8.0 * m_corner;
    let inertia = (2.0 * a) * (2.0 * a) / 6.0 * mass;
    let (height, v) = (15.0, [30.0, 0.0, 0.0]);
    let w = [12.0, -20.0, 6.0];
    let spin2: f64 = w.iter().map(|x| x * x).sum();
    let speed = f64::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    // Corners at (±a, ±a, ±a) (orientation 0): each moves at v + ω × r.
    let mut fastest: f64 = 0.0;
    let mut falling: f64 = 0.0;
    for sx in [-a, a] {
        for sy in [-a, a] {
            for sz in [-a, a] {
                let u = [
                    v[0] + w[1] * sz - w[2] * sy,
                    v[1] + w[2] * sx - w[0] * sz,
                    v[2] + w[0] * sy - w[1] * sx,
                ];
                fastest = fastest.max((u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt());
                falling = falling.max(-u[2]);
            }
        }
    }
    let corner_frequency = (k / m_corner).sqrt();
    // docs/model.md, "Stability": a cube rocking flat on its face, ω_rock = √(6k/M).
    let rocking = (6.0 * k / mass).sqrt();
    vec![
        ("height_cm", height),
        ("lowest_corner_cm", height - a),
        ("speed_cm_per_s", speed),
        ("spin_rate_rad_per_s", spin2.sqrt()),
        ("contact_force_dyn", 0.0),
        ("e_trans_erg", 0.5 * mass * speed * speed),
        ("e_rot_erg", 0.5 * inertia * spin2),
        ("e_grav_erg", mass * g * (height - a)),
        ("e_elastic_erg", 0.0),
        (
            "e_total_erg",
            0.5 * mass * speed * speed + 0.5 * inertia * spin2 + mass * g * (height - a),
        ),
        // Against docs/model.md's limit of 1.25; read now, before any corner strikes, so
        // unstiffened by the damping.
        ("contact_mode_load", rocking * dt / 1.25),
        ("corner_travel_load", fastest * dt / a),
        (
            "damping_load",
            gamma * falling / (2.0 / (corner_frequency * dt)).max(1.0),
        ),
        ("friction_load", mu * corner_frequency * dt / 2.0),
    ]
}

#[test]
fn every_quantity_at_the_start_of_the_papers_roll_is_its_analytic_value() {
    let p = Store::new(None).load("paper").expect("shipped preset").0;
    let sim = Simulation::new(&p.params(), &p.initial).unwrap();
    let readings = read_all(&sim);
    let expected = expected_at_start();
    assert_eq!(
        expected.len(),
        QUANTITIES.len(),
        "every quantity has its hand value"
    );
    for (column, want) in &expected {
        let i = QUANTITIES
            .iter()
            .position(|q| q.column == *column)
            .unwrap_or_else(|| panic!("{column}"));
        let got = readings[i];
        assert!(
            (got - want).abs() <= 1e-9 * want.abs().max(1.0),
            "{column}: {got} vs {want}"
        );
    }
    // The quoted figures of the issue: 15 cm, 30 cm/s, |(12, −20, 6)| = √580 rad/s.
    let by = |c: &str| readings[QUANTITIES.iter().position(|q| q.column == c).unwrap()];
    assert_eq!(by("height_cm"), 15.0);
    assert_eq!(by("speed_cm_per_s"), 30.0);
    assert!((by("spin_rate_rad_per_s") - 580f64.sqrt()).abs() < 1e-12);
}

/// A d20 of height h (across its faces) thrown without spin: its centre's readings are the
/// throw's, its lowest point a midradius below the centre (in its own frame an edge is down:
/// docs/dice.md's vertices), and its points' limits its own (docs/model.md, "A polyhedral die's
/// readings"): each of its 12 points carries M/12 and may move h/2 a step.
#[test]
fn a_d20s_quantities_are_its_own_body_s() {
    use dicesim_physics::{InitialCondition, Roll, RollingDie, Solid};
    let mut params = dicesim_physics::Params::default();
    params.die.kind = Solid::D20;
    params.die.height = 1.6;
    params.die.density = 1.18;
    params.integrator.dt = 0.000_25;
    let initial = InitialCondition {
        height: 10.0,
        velocity: [30.0, 0.0, -40.0],
        ..Default::default()
    };
    let roll = Roll::new(&params, &initial).unwrap();
    // The icosahedron of inradius r = h/2 has edge a = r·4√3/(3 + √5) and volume
    // 5(3 + √5)a³/12.
    let (h, s5) = (1.6f64, 5f64.sqrt());
    let a = h / 2.0 * 4.0 * 3f64.sqrt() / (3.0 + s5);
    let mass = 1.18 * 5.0 * (3.0 + s5) * a.powi(3) / 12.0;
    let (k, dt, gamma, mu) = (500_000.0, 0.000_25, 0.005, 1.2);
    let point_frequency = (k / (mass / 12.0)).sqrt();
    let readings = read_all(&roll);
    let by = |c: &str| readings[QUANTITIES.iter().position(|q| q.column == c).unwrap()];
    let close = |c: &str, want: f64| {
        let got = by(c);
        assert!(
            (got - want).abs() <= 1e-9 * want.abs().max(1.0),
            "{c}: {got} vs {want}"
        );
    };
    close("height_cm", 10.0);
    close("lowest_corner_cm", 10.0 - a * (1.0 + s5) / 4.0);
    close("speed_cm_per_s", 50.0);
    close("spin_rate_rad_per_s", 0.0);
    close("corner_travel_load", 50.0 * dt / (h / 2.0));
    close(
        "damping_load",
        gamma * 40.0 / (2.0 / (point_frequency * dt)).max(1.0),
    );
    close("friction_load", mu * point_frequency * dt / 2.0);
    assert_eq!(roll.point_offsets().len(), 12);
    assert!((roll.point_mass() - mass / 12.0).abs() < 1e-12 * mass);
}

/// Two d20s thrown alike are apart by nothing; one yawed by θ is apart by θ at the same
/// centre (the separation reads any die's orientation, not a box's corners).
#[test]
fn the_separation_of_two_d20s_is_their_yaw() {
    use dicesim_physics::{InitialCondition, Roll, Solid};
    use dicesim_setup::chaos::separation;
    let mut params = dicesim_physics::Params::default();
    params.die.kind = Solid::D20;
    params.integrator.dt = 0.000_25;
    let initial = InitialCondition::default();
    let a = Roll::new(&params, &initial).unwrap();
    let same = separation(&a, &a.clone());
    assert_eq!((same.centre, same.angle), (0.0, 0.0));
    let yawed = InitialCondition {
        orientation: [3.0, 0.0, 0.0],
        ..initial
    };
    let b = Roll::new(&params, &yawed).unwrap();
    let apart = separation(&a, &b);
    assert_eq!(apart.centre, 0.0);
    assert!((apart.angle - 3f64.to_radians()).abs() < 1e-12, "{apart:?}");
}
