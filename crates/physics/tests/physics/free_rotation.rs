//! Torque-free flight of bodies whose inertia is not isotropic (docs/model.md, "Rotation of
//! an anisotropic body"): the splitting keeps `L` and `|L|`, holds the rotational energy
//! within the bound derived there, and turns the tennis racket over at the period of the
//! exact free motion (Landau & Lifshitz, §37).

use dicesim_physics::{InitialCondition, Params, Simulation, mass_properties};
use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;

/// The tennis-racket preset's cuboid (half sizes 1.6, 1, 0.4 cm, 5.12 g) at its Δt, spun
/// about its middle axis (y) 0.1 % off in x and z at `rate` rad/s, high above a table it
/// never reaches in `seconds` (gravity moves the centre only, never the spin).
fn racket(rate: f64) -> (Params, InitialCondition) {
    let mut p = Params::default();
    p.die.half_sizes = [1.6, 1.0, 0.4];
    p.die.corner_mass = 0.64;
    p.world.gravity = 162.0;
    p.integrator.dt = 5e-4;
    p.integrator.max_time = 1e3;
    let initial = InitialCondition {
        height: 1e6,
        angular_velocity: [0.001 * rate, rate, 0.001 * rate],
        ..InitialCondition::default()
    };
    (p, initial)
}

/// The principal moments of `p`'s body (ascending, g·cm²) and its axes (columns, body frame).
fn principal(p: &Params) -> (Vector3<f64>, Matrix3<f64>) {
    let eigen = mass_properties(&p.die).inertia.symmetric_eigen();
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    (
        Vector3::from(order.map(|i| eigen.eigenvalues[i])),
        Matrix3::from_columns(&order.map(|i| eigen.eigenvectors.column(i).into_owned())),
    )
}

/// The body axes in the world frame as the step reads them off the contact spheres' centres
/// (corner 1 to corners 5, 3 and 2, orthonormalised in that order), the columns of `R`.
fn body_axes(sim: &Simulation) -> Matrix3<f64> {
    let r = &sim.state().corner_offsets;
    let x = (r[4] - r[0]).normalize();
    let y = r[2] - r[0];
    let y = (y - x * x.dot(&y)).normalize();
    Matrix3::from_columns(&[x, y, x.cross(&y)])
}

/// The largest relative change of a distance between two corners from `start`: how far the
/// body has strayed from rigid.
fn shape_drift(sim: &Simulation, start: &[Vector3<f64>; 8]) -> f64 {
    let r = &sim.state().corner_offsets;
    let mut worst: f64 = 0.0;
    for i in 0..8 {
        for j in 0..i {
            let (now, then) = ((r[i] - r[j]).norm(), (start[i] - start[j]).norm());
            worst = worst.max(((now - then) / then).abs());
        }
    }
    worst
}

/// erg, the bound docs/model.md derives on the splitting's rotational-energy error for a
/// body of principal moments `moments` (ascending) spinning with `|L| = l` at step `dt`:
/// `2·Δt²·|L|⁴·(c₁²|c₂ − c₃|/12 + c₁|c₂ − c₃|(c₂ + c₃)/6 + c₂²c₃/12 + c₂c₃²/6)`, `c_i = 1/(2I_i)`.
fn energy_bound(moments: &Vector3<f64>, l: f64, dt: f64) -> f64 {
    let [c1, c2, c3] = [0, 1, 2].map(|i| 0.5 / moments[i]);
    let d = (c2 - c3).abs();
    2.0 * dt
        * dt
        * l.powi(4)
        * (c1 * c1 * d / 12.0 + c1 * d * (c2 + c3) / 6.0 + c2 * c2 * c3 / 12.0 + c2 * c3 * c3 / 6.0)
}

/// What a flight of `seconds` did: the largest relative change of the rotational energy and
/// of `|L|` in the body frame, the bound on the first (relative), and the times the middle
/// principal axis crossed the plane normal to `L`, interpolated between steps.
struct Flight {
    energy_drift: f64,
    energy_bound: f64,
    body_l_drift: f64,
    shape_drift: f64,
    crossings: Vec<f64>,
}

fn fly(p: &Params, initial: &InitialCondition, seconds: f64) -> Flight {
    let (moments, axes) = principal(p);
    let mut sim = Simulation::new_unchecked(p, initial);
    let l = sim.state().angular_momentum;
    let (e0, l0) = (sim.energy().rotational, l.norm());
    let middle = |sim: &Simulation| (body_axes(sim) * axes.column(1)).dot(&l) / l0;
    let mut flight = Flight {
        energy_drift: 0.0,
        energy_bound: energy_bound(&moments, l0, p.integrator.dt) / e0,
        body_l_drift: 0.0,
        shape_drift: 0.0,
        crossings: Vec::new(),
    };
    let start = sim.state().corner_offsets;
    let mut before = middle(&sim);
    for _ in 0..(seconds / p.integrator.dt).round() as u64 {
        sim.step();
        assert!(!sim.in_contact(), "the flight reached the table");
        // No torque acts, so L is never touched: bit for bit.
        assert_eq!(sim.state().angular_momentum, l);
        let e = sim.energy().rotational;
        flight.energy_drift = flight.energy_drift.max(((e - e0) / e0).abs());
        let body_l = (body_axes(&sim).transpose() * l).norm();
        flight.body_l_drift = flight.body_l_drift.max(((body_l - l0) / l0).abs());
        let now = middle(&sim);
        if (before < 0.0) != (now < 0.0) {
            let t = sim.state().time_s;
            flight.crossings.push(t - p.integrator.dt * now / (now - before));
        }
        before = now;
    }
    flight.shape_drift = shape_drift(&sim, &start);
    flight
}

/// The complete elliptic integral of the first kind `K(m)`, `m = k²`, from the complementary
/// modulus `k' = √(1 − m)` given directly (near the separatrix `1 − m` is what is known
/// accurately): `π / (2·AGM(1, k'))`.
fn elliptic_k(complement: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, complement);
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (a + b)
}

/// s, the time between two crossings of the middle axis through the plane normal to `L` in
/// the exact free motion: half the period of `sn`, `2·K(k)/λ` (docs/model.md).
fn analytic_flip_period(moments: &Vector3<f64>, body_l: &Vector3<f64>) -> f64 {
    let [i1, i2, i3] = [moments[0], moments[1], moments[2]];
    let m2 = body_l.norm_squared();
    let two_e = (0..3).map(|i| body_l[i] * body_l[i] / moments[i]).sum::<f64>();
    // M² − 2E·I_j as Σ m_i²·(1 − I_j/I_i): no cancellation near the separatrix.
    let less = |ij: f64| {
        (0..3)
            .map(|i| body_l[i] * body_l[i] * (1.0 - ij / moments[i]))
            .sum::<f64>()
    };
    let (above_1, above_2, below_3) = (less(i1), less(i2), -less(i3));
    let (rate_sq, complement_sq) = if above_2 > 0.0 {
        (
            (i3 - i2) * above_1 / (i1 * i2 * i3),
            (i3 - i1) * above_2 / ((i3 - i2) * above_1),
        )
    } else {
        (
            (i2 - i1) * below_3 / (i1 * i2 * i3),
            (i3 - i1) * -above_2 / ((i2 - i1) * below_3),
        )
    };
    assert!(m2 > 0.0 && two_e > 0.0);
    2.0 * elliptic_k(complement_sq.sqrt()) / rate_sq.sqrt()
}

#[test]
fn the_tennis_racket_keeps_its_invariants_and_flips_at_the_elliptic_period() {
    for rate in [30.0, 150.0] {
        let (p, initial) = racket(rate);
        let flight = fly(&p, &initial, 10.0);
        println!(
            "{rate} rad/s: energy drift {:e} (bound {:e}), |L| in the body frame {:e}, rigid to {:e}, {} crossings",
            flight.energy_drift,
            flight.energy_bound,
            flight.body_l_drift,
            flight.shape_drift,
            flight.crossings.len()
        );
        assert!(flight.energy_drift < 1e-3, "{}", flight.energy_drift);
        assert!(
            flight.energy_drift < flight.energy_bound,
            "{}",
            flight.energy_drift
        );
        assert!(flight.body_l_drift < 1e-12, "{:e}", flight.body_l_drift);
        assert!(flight.shape_drift < 1e-14, "{:e}", flight.shape_drift);
        // The axes are the world's at the start, so L in the body frame is I·ω.
        let (moments, _) = principal(&p);
        let body_l = Vector3::from(initial.angular_velocity).component_mul(&moments);
        let period = analytic_flip_period(&moments, &body_l);
        let gaps: Vec<f64> = flight.crossings.windows(2).map(|w| w[1] - w[0]).collect();
        assert!(gaps.len() >= 8, "{rate} rad/s: only {} flips in 10 s", gaps.len());
        for (n, gap) in gaps.iter().enumerate() {
            assert!(
                (gap / period - 1.0).abs() < 0.01,
                "{rate} rad/s, flip {n}: {gap} s against the analytic {period} s"
            );
        }
        println!("{rate} rad/s: flips every {period:.4} s (analytic), gaps {gaps:.4?}");
    }
}

#[test]
fn the_splitting_errs_as_the_square_of_the_step() {
    let (mut p, initial) = racket(150.0);
    let coarse = fly(&p, &initial, 1.0).energy_drift;
    p.integrator.dt *= 0.5;
    let fine = fly(&p, &initial, 1.0).energy_drift;
    let order = (coarse / fine).log2();
    assert!(
        (1.7..2.3).contains(&order),
        "{coarse:e} then {fine:e}: order {order}"
    );
}

#[test]
fn isotropic_bodies_keep_the_papers_rotation() {
    // A rounded cube and a cube loaded alike at every corner turn by ω·Δt as the paper's cube
    // does, exact for them: L and the rotational energy ½·ω·L never change in flight.
    let mut rounded = Params::default();
    rounded.die.corner_radius = 0.2;
    let mut even = Params::default();
    even.die.extra_corner_mass = [0.5; 8];
    let initial = InitialCondition {
        height: 1e6,
        angular_velocity: [7.0, 3.0, -11.0],
        orientation: [20.0, 35.0, -10.0],
        ..InitialCondition::default()
    };
    for p in [rounded, even] {
        let mut sim = Simulation::new_unchecked(&p, &initial);
        let e0 = sim.energy().rotational;
        for _ in 0..2000 {
            sim.step();
            let drift = ((sim.energy().rotational - e0) / e0).abs();
            assert!(drift < 1e-12, "{drift:e}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    /// Any triaxial body (a cuboid of three half sizes, loaded at two corners so that its
    /// principal axes leave the body axes), any orientation and spin: over 10 s of flight at
    /// 1 ms, L stands still, `|L|` in the body frame keeps to 10⁻¹², the body stays rigid to
    /// 10⁻¹⁴, and the rotational energy keeps to 0.1 % and within the derived bound.
    #[test]
    fn any_triaxial_body_keeps_its_invariants(
        half_sizes in prop::array::uniform3(0.3f64..2.0),
        extras in prop::array::uniform2(0.0f64..2.0),
        corners in prop::array::uniform2(0usize..8),
        orientation in prop::array::uniform3(-180.0f64..180.0),
        spin in prop::array::uniform3(-40.0f64..40.0),
    ) {
        let mut p = Params::default();
        p.die.half_sizes = half_sizes;
        p.die.extra_corner_mass[corners[0]] += extras[0];
        p.die.extra_corner_mass[corners[1]] += extras[1];
        p.integrator.dt = 1e-3;
        p.integrator.max_time = 1e3;
        let (moments, _) = principal(&p);
        prop_assume!(moments[2] - moments[0] > 1e-6 * moments[2]);
        prop_assume!(Vector3::from(spin).norm() > 1.0);
        let initial = InitialCondition {
            height: 1e8,
            angular_velocity: spin,
            orientation,
            ..InitialCondition::default()
        };
        let flight = fly(&p, &initial, 10.0);
        prop_assert!(flight.body_l_drift < 1e-12, "|L| {:e}", flight.body_l_drift);
        prop_assert!(flight.shape_drift < 1e-14, "rigid to {:e}", flight.shape_drift);
        prop_assert!(flight.energy_drift < 1e-3, "energy {:e}", flight.energy_drift);
        prop_assert!(
            flight.energy_drift <= flight.energy_bound,
            "energy {:e} above the bound {:e}", flight.energy_drift, flight.energy_bound
        );
    }
}
