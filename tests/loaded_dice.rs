//! Loaded dice (docs/model.md, "Loaded dice"): the mass model in flight, a die loaded evenly,
//! and the bias a heavy corner gives, measured by a batch.

mod common;

use dicesim_experiment::{RandomRanges, Rolls, RunOptions, stream_batch};
use dicesim_physics::{InitialCondition, Params, Simulation};
use nalgebra::{Matrix3, Vector3};
use std::sync::atomic::AtomicBool;

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
    // Semi-implicit Euler turns the die by a fixed ω for a whole step while the tensor turns
    // with it. That ω is the exact flow's at the step's start, so the energy's first-order
    // change vanishes and each step errs by O(Δt²): over a fixed time the drift is bounded
    // and shrinks at least as fast as Δt (here about as Δt², docs/model.md).
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
        // Each step turns the die by ω = I⁻¹·L, the tensor taken at the offsets it starts from.
        let before = s.state().corner_offsets;
        s.step();
        let i = inertia_from_masses(&p, &before);
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
/// mass at the corners: same centre, isotropic inertia `(2a)²/6·8m + 16·Δm·a²`.
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
    // And it is fair: no face comes up more than chance allows.
    let summary = batch(&even, 900);
    assert_eq!(summary.status.settled, 900);
    assert!(summary.p_value.unwrap() > 0.001, "{:?}", summary.faces);
}

fn batch(p: &Params, count: u64) -> dicesim_experiment::BatchSummary {
    let ranges = RandomRanges {
        random_orientation: true,
        ..RandomRanges::default()
    };
    let base = InitialCondition::default();
    let rolls = Rolls::Random {
        ranges: &ranges,
        base: &base,
        seed: 15,
        first: 0,
        count,
    };
    let run = stream_batch(
        p,
        &rolls,
        &RunOptions::default(),
        &AtomicBool::new(false),
        &mut |_| Ok(()),
    )
    .unwrap();
    run.summary
}

#[test]
fn a_heavy_corner_keeps_its_three_faces_down() {
    // Corner 8 meets faces 4, 5 and 6; weighted, it ends down more often, so those faces come
    // up less often and their opposites 3, 2 and 1 more.
    let mut extra = [0.0; 8];
    extra[7] = 2.0;
    let summary = batch(&loaded(extra), 1500);
    let n = summary.faces.total() as f64;
    let counts = summary.faces.counts();
    let heavy = (counts[3] + counts[4] + counts[5]) as f64 / n;
    // The batch's own 95 % interval on that share lies below the fair die's 1/2.
    let se = (heavy * (1.0 - heavy) / n).sqrt();
    assert!(
        heavy + 1.96 * se < 0.5,
        "faces 4–6 came up in {heavy} of {n}: {counts:?}"
    );
    assert!(summary.p_value.unwrap() < 0.01, "{counts:?}");
    // The fair die's batch from the same starts shows no such deficit.
    let fair = batch(&Params::default(), 1500).faces.counts();
    let fair_heavy = (fair[3] + fair[4] + fair[5]) as f64 / fair.iter().sum::<u64>() as f64;
    assert!(fair_heavy > heavy + 2.0 * se, "{fair:?} against {counts:?}");
}

/// The records files of loaded rolls, byte for byte against `tests/data/loaded/`.
///
/// Those files were written by the program as it stood before the step became one kernel
/// for both engines, when a loaded die could only roll on the scalar engine (commit bab7ddc,
/// `dicesim batch … --engine scalar --jobs 1 --out FILE.csv` with the arguments below): the
/// reference data cover the fair die only, so this is what pins a loaded die's trajectory.
/// Both engines must write them again.
#[test]
fn loaded_rolls_match_the_records_written_before_the_lanes_had_loaded_dice() {
    let golden: [(&str, &[&str]); 2] = [
        (
            "loaded-corner.csv",
            &["--preset", "loaded-corner", "--rolls", "200", "--seed", "19"],
        ),
        (
            "loaded-two.csv",
            &[
                "--preset",
                "loaded-corner",
                "--set",
                "die.extra_corner_mass=[0,1.5,0,0,0,0.5,0,0]",
                "--set",
                "ground.friction_law=whole-die-norm",
                "--set",
                "integrator.stop_energy=point-masses",
                "--rolls",
                "100",
                "--seed",
                "23",
            ],
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (file, args) in golden {
        let expected =
            std::fs::read(format!("{}/tests/data/loaded/{file}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        for engine in ["scalar", "lanes"] {
            let out = dir.path().join(format!("{engine}-{file}"));
            let mut all = vec![
                "batch",
                "--engine",
                engine,
                "--jobs",
                "2",
                "--out",
                out.to_str().unwrap(),
            ];
            all.extend_from_slice(args);
            let run = common::dicesim_in(dir.path(), &all);
            assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
            // The records after the provenance line (which the older program did not write)
            // must be the older program's bytes.
            let written = std::fs::read(&out).unwrap();
            assert!(written.starts_with(b"# {"), "{file}: no provenance line");
            let records_start = written.iter().position(|&b| b == b'\n').unwrap() + 1;
            let written = &written[records_start..];
            assert!(
                written == expected.as_slice(),
                "{file} with the {engine} engine differs from the records written before"
            );
        }
    }
}
