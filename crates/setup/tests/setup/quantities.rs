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
