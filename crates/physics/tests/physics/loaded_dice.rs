//! Loaded dice (docs/model.md, "Loaded dice"): the mass model in flight, a die loaded
//! evenly, and the loaded rolls recorded before both engines rolled them, replayed. (The
//! bias a heavy corner gives, measured by batches, and the records written again by the
//! binary are the root's tests/loaded_dice.rs.)

use crate::common::data_path;
use dicesim_physics::lanes::{LaneResult, roll_in_lanes, roll_one_by_one};
use dicesim_physics::{FrictionLaw, InitialCondition, Params, Simulation, Status, StopEnergy};
use nalgebra::{Matrix3, Vector3};

fn loaded(extra: [f64; 8]) -> Params {
    let mut p = Params::default();
    p.die.extra_corner_mass = extra;
    p
}

/// A start high above the table with a tumbling spin: no contact for the steps we take.
fn in_flight() -> InitialCondition {
    InitialCondition {
        height: 900.0,
        angular_velocity: [31.0, -17.0, 44.0],
        orientation: [20.0, 35.0, -10.0],
        ..Default::default()
    }
}

/// The inertia tensor about the centre of mass from the corner offsets, computed here from
/// the masses directly: the uniform cube (isotropic `(2a)²/6·8m` about its centre, which is
/// the mean of the corner offsets) moved by the parallel-axis term, plus each extra mass.
fn inertia_from_masses(p: &Params, r: &[Vector3<f64>; 8]) -> Matrix3<f64> {
    let point = |m: f64, x: &Vector3<f64>| (Matrix3::identity() * x.dot(x) - x * x.transpose()) * m;
    let side = 2.0 * p.die.half_size();
    let uniform = 8.0 * p.die.corner_mass;
    let centre = r.iter().sum::<Vector3<f64>>() / 8.0;
    let mut i = Matrix3::identity() * (side * side / 6.0 * uniform) + point(uniform, &centre);
    for (x, &dm) in r.iter().zip(&p.die.extra_corner_mass) {
        i += point(dm, x);
    }
    i
}

/// Relative drift of the rotational energy over `seconds` of torque-free flight at `dt`.
fn rotational_drift(p: &Params, dt: f64, seconds: f64) -> f64 {
    let mut p = *p;
    p.integrator.dt = dt;
    let mut s = Simulation::new(&p, &in_flight()).unwrap();
    let l0 = s.state().angular_momentum;
    let e0 = s.energy().rotational;
    let mut worst: f64 = 0.0;
    for _ in 0..(seconds / dt).round() as u64 {
        s.step();
        assert!(!s.in_contact());
        // No torque acts, so L is never touched: bit for bit.
        assert_eq!(s.state().angular_momentum, l0);
        worst = worst.max((s.energy().rotational - e0).abs() / e0);
    }
    // The tensor turns with the die, and ω follows it.
    let i = inertia_from_masses(&p, &s.state().corner_offsets);
    let rebuilt = i * s.angular_velocity();
    assert!(
        (rebuilt - l0).norm() < 0.05 * l0.norm(),
        "I·ω = {rebuilt} against L = {l0}"
    );
    worst
}

#[test]
fn torque_free_flight_keeps_l_exactly_and_the_energy_within_the_step_error() {
    let mut extra = [0.0; 8];
    extra[7] = 3.0;
    extra[0] = 1.0;
    let p = loaded(extra);
    // The splitting about the principal axes keeps the energy to O(Δt²) without drift
    // (docs/model.md, "Rotation of an anisotropic body"): bounded over a fixed time and
    // shrinking about as Δt².
    let coarse = rotational_drift(&p, 1e-3, 0.4);
    let fine = rotational_drift(&p, 5e-4, 0.4);
    assert!(coarse > 0.0 && coarse < 5e-3, "drift {coarse}");
    let order = (coarse / fine).log2();
    assert!(
        (1.0..2.6).contains(&order),
        "drift {coarse} at 1 ms, {fine} at 0.5 ms"
    );
}

#[test]
fn the_step_follows_omega_from_the_current_tensor() {
    let mut extra = [0.0; 8];
    extra[2] = 2.0;
    let p = loaded(extra);
    let mut s = Simulation::new(&p, &in_flight()).unwrap();
    for _ in 0..50 {
        // After each step ω = I⁻¹·L with the tensor at the offsets the step turned it to.
        s.step();
        let i = inertia_from_masses(&p, &s.state().corner_offsets);
        let l = s.state().angular_momentum;
        assert!((i * s.angular_velocity() - l).norm() < 1e-12 * l.norm());
        // The masses balance about the centre of mass.
        let r = &s.state().corner_offsets;
        let moment: Vector3<f64> = r.iter().sum::<Vector3<f64>>() * p.die.corner_mass + r[2] * 2.0;
        assert!(moment.norm() < 1e-12, "{moment}");
    }
}

#[test]
fn gravity_acts_at_the_centre_of_mass() {
    // Free fall of the centre of mass is the fair die's, whatever the load: kick then drift.
    let mut extra = [0.0; 8];
    extra[4] = 5.0;
    let (fair, heavy) = (Params::default(), loaded(extra));
    let mut a = Simulation::new(&fair, &in_flight()).unwrap();
    let mut b = Simulation::new(&heavy, &in_flight()).unwrap();
    for _ in 0..300 {
        a.step();
        b.step();
        assert_eq!(a.state().position, b.state().position);
        assert_eq!(a.state().velocity, b.state().velocity);
    }
}

/// A die with every corner loaded alike is a fair die, only heavier and with more of its
/// mass at the corners: same centre, isotropic inertia `(2a)²/6·8m + 16·Δm·a²` (and fair,
/// which a batch shows: the root's tests/loaded_dice.rs).
#[test]
fn all_extras_equal_is_a_heavier_fair_die() {
    let even = loaded([0.5; 8]);
    let mut heavier = Params::default();
    heavier.die.corner_mass = 1.5;
    // In flight from the same ω, it moves and turns as the heavier fair die.
    let mut a = Simulation::new(&heavier, &in_flight()).unwrap();
    let mut b = Simulation::new(&even, &in_flight()).unwrap();
    let expected_inertia = 16.0 / 3.0 + 16.0 * 0.5;
    assert!((b.state().angular_momentum - Vector3::new(31.0, -17.0, 44.0) * expected_inertia).norm() < 1e-9);
    for _ in 0..300 {
        a.step();
        b.step();
        assert_eq!(a.state().position, b.state().position);
        for (ra, rb) in a.state().corner_offsets.iter().zip(&b.state().corner_offsets) {
            assert!((ra - rb).norm() < 1e-12, "{ra} against {rb}");
        }
        let i = inertia_from_masses(&even, &b.state().corner_offsets);
        assert!((i - Matrix3::identity() * expected_inertia).norm() < 1e-12);
    }
}

/// The loaded rolls of `crates/physics/tests/data/loaded/`: their starts as the program
/// drew them before the step became one kernel for both engines (the root's
/// tests/loaded_dice.rs says how, and checks the binary writes them again), their endings
/// as rolled since a loaded die turns by the splitting about its principal axes
/// (docs/model.md, "Rotation of an anisotropic body", which changed every one of them).
/// Each row's start, replayed here, must end as recorded in both engines, its start face,
/// face, status, step count and end time bit for bit. The reference data cover the fair die
/// only, so these pin a loaded die's trajectory.
#[test]
fn loaded_rolls_end_as_recorded_before_the_lanes_had_loaded_dice() {
    let corner = loaded([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5]);
    let mut two = loaded([0.0, 1.5, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0]);
    two.ground.friction_law = FrictionLaw::WholeDieNorm;
    two.integrator.stop_energy = StopEnergy::PointMasses;
    for (file, params, count) in [("loaded-corner.csv", corner, 200), ("loaded-two.csv", two, 100)] {
        let records = Records::load(file);
        assert_eq!(records.rows.len(), count, "{file}");
        for (name, engine) in [("scalar", roll_one_by_one as Engine), ("lanes", roll_in_lanes)] {
            let mut ended = vec![None; count];
            let finished = engine(
                count,
                &mut |i| (params, records.initial(i)),
                &mut |r: LaneResult<'_>| {
                    ended[r.index] = Some((
                        r.start_face,
                        r.outcome.face,
                        r.outcome.status,
                        r.outcome.steps,
                        r.outcome.time_s.to_bits(),
                    ))
                },
                &|| false,
            );
            assert!(finished);
            for (i, ended) in ended.into_iter().enumerate() {
                assert_eq!(ended, Some(records.ending(i)), "{file}, roll {i}, {name} engine");
            }
        }
    }
}

type Engine = fn(
    usize,
    &mut dyn FnMut(usize) -> (Params, InitialCondition),
    &mut dyn FnMut(LaneResult<'_>),
    &dyn Fn() -> bool,
) -> bool;

/// A records file read by the csv crate, its columns by name.
struct Records {
    header: csv::StringRecord,
    rows: Vec<csv::StringRecord>,
}

impl Records {
    fn load(file: &str) -> Records {
        let path = data_path("loaded").join(file);
        let mut reader = csv::Reader::from_path(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let header = reader.headers().unwrap().clone();
        let rows = reader.records().map(Result::unwrap).collect();
        Records { header, rows }
    }

    fn text(&self, i: usize, column: &str) -> &str {
        let at = self.header.iter().position(|h| h == column);
        &self.rows[i][at.unwrap_or_else(|| panic!("no column {column}"))]
    }

    /// The number as written: Rust's shortest text of an f64, which parses to its bits.
    fn number(&self, i: usize, column: &str) -> f64 {
        self.text(i, column).parse().unwrap()
    }

    fn xyz(&self, i: usize, prefix: &str) -> [f64; 3] {
        ["x", "y", "z"].map(|a| self.number(i, &format!("{prefix}_{a}")))
    }

    /// Roll `i`'s start: a spin stated as ω (no angular momentum column is filled).
    fn initial(&self, i: usize) -> InitialCondition {
        assert_eq!(self.text(i, "angular_momentum_x"), "", "roll {i}");
        InitialCondition {
            height: self.number(i, "height"),
            velocity: self.xyz(i, "velocity"),
            angular_velocity: self.xyz(i, "angular_velocity"),
            angular_momentum: None,
            orientation: ["yaw", "pitch", "roll"].map(|c| self.number(i, c)),
        }
    }

    /// Roll `i`'s start face, face, status, steps and end time (as bits).
    fn ending(&self, i: usize) -> (u8, Option<u8>, Status, u64, u64) {
        let face = self.text(i, "face");
        (
            self.text(i, "start_face").parse().unwrap(),
            (!face.is_empty()).then(|| face.parse().unwrap()),
            Status::from_name(self.text(i, "status")).unwrap(),
            self.text(i, "steps").parse().unwrap(),
            self.number(i, "time_s").to_bits(),
        )
    }
}
