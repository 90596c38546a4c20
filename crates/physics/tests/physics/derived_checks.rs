//! The derived checks of docs/model.md's last section: facts any correct implementation passes.

use dicesim_physics::{InitialCondition, Params, Simulation, Status};
use nalgebra::{Matrix3, Vector3};

fn sim(params: &Params, initial: InitialCondition) -> Simulation {
    Simulation::new(params, &initial).unwrap()
}

/// Centre height of a die resting flat at equilibrium: each corner sinks M·g/(4k).
fn resting_height(p: &Params) -> f64 {
    p.die.half_size() - p.resting_depth()
}

#[test]
fn free_fall_is_kick_then_drift_and_first_contact_is_step_169() {
    let p = Params::default();
    let mut s = sim(&p, InitialCondition::default());
    let (z0, g, dt) = (15.0, p.world.gravity, p.integrator.dt);
    let mut first_contact = None;
    for n in 1..=200u64 {
        s.step();
        if first_contact.is_none() {
            let exact = z0 - g * dt * dt * (n * (n + 1)) as f64 / 2.0;
            assert!(
                (s.state().position.z - exact).abs() < 1e-11,
                "step {n}: {}",
                s.state().position.z
            );
            if s.in_contact() {
                first_contact = Some(n);
            }
        }
    }
    // Drift-then-kick (n(n−1)/2) would first touch at step 170.
    assert_eq!(first_contact, Some(169));
}

/// The one impact definition (docs/model.md, "Impacts"): the flat drop's first impact is its
/// first contact, step 169 (above), and a die placed resting on the table never starts one.
#[test]
fn the_first_impact_of_a_flat_drop_is_its_first_contact_and_a_resting_die_has_none() {
    use dicesim_physics::Impacts;
    let p = Params::default();
    let mut s = sim(&p, InitialCondition::default());
    let mut impacts = Impacts::new(s.in_contact());
    let mut first = None;
    for n in 1..=400u64 {
        s.step();
        if impacts.observe(s.in_contact()) && first.is_none() {
            first = Some(n);
        }
    }
    assert_eq!(first, Some(169));
    let mut resting = sim(
        &p,
        InitialCondition {
            height: resting_height(&p),
            ..Default::default()
        },
    );
    assert!(resting.in_contact(), "resting on the table from the start");
    let mut none = Impacts::new(resting.in_contact());
    for _ in 0..400 {
        resting.step();
        none.observe(resting.in_contact());
    }
    assert_eq!(none.count(), 0);
}

/// Rotation angle and axis of `r = m·r0` from corner offsets before and after.
fn rotation_between(before: &[Vector3<f64>; 8], after: &[Vector3<f64>; 8]) -> (f64, Vector3<f64>) {
    // Corners 5−1, 3−1, 2−1 span the body axes; R maps one frame onto the other.
    let frame = |r: &[Vector3<f64>; 8]| {
        Matrix3::from_columns(&[
            (r[4] - r[0]).normalize(),
            (r[2] - r[0]).normalize(),
            (r[1] - r[0]).normalize(),
        ])
    };
    let m = frame(after) * frame(before).transpose();
    let angle = ((m.trace() - 1.0) / 2.0).clamp(-1.0, 1.0).acos();
    let axis = Vector3::new(
        m[(2, 1)] - m[(1, 2)],
        m[(0, 2)] - m[(2, 0)],
        m[(1, 0)] - m[(0, 1)],
    )
    .normalize();
    (angle, axis)
}

#[test]
fn torque_free_spin_turns_by_n_omega_dt_about_omega() {
    let p = Params::default();
    let omega = Vector3::new(3.0, -4.0, 12.0); // |ω| = 13 rad/s
    let mut s = sim(
        &p,
        InitialCondition {
            height: 100.0,
            angular_velocity: omega.into(),
            ..Default::default()
        },
    );
    let before = s.state().corner_offsets;
    let l0 = s.state().angular_momentum;
    let n = 200;
    for _ in 0..n {
        s.step();
        assert_eq!(
            s.state().angular_momentum,
            l0,
            "L must not change without contact"
        );
        assert!((s.angular_velocity().norm() - 13.0).abs() < 1e-12);
    }
    let (angle, axis) = rotation_between(&before, &s.state().corner_offsets);
    assert!(
        (angle - n as f64 * 13.0 * p.integrator.dt).abs() < 1e-10,
        "angle {angle}"
    );
    assert!((axis - omega.normalize()).norm() < 1e-9, "axis {axis}");
    // The body stays rigid: every corner keeps its distance from the centre.
    for r in s.state().corner_offsets {
        assert!((r.norm() - 3f64.sqrt()).abs() < 1e-12);
    }
}

#[test]
fn resting_die_sinks_mg_over_4k() {
    let p = Params::default();
    let mut s = sim(
        &p,
        InitialCondition {
            height: 1.0,
            ..Default::default()
        },
    );
    for _ in 0..5000 {
        s.step();
    }
    let depths = s.state().corner_depths;
    let want = p.total_mass() * p.world.gravity / (4.0 * p.ground.stiffness);
    assert!((want - 3.92e-3).abs() < 1e-5);
    for k in [0, 2, 4, 6] {
        // After 5 s the damped bounce has decayed to ~10⁻⁶ of the depth.
        assert!(
            (depths[k] - want).abs() < 1e-5 * want,
            "corner {}: {}",
            k + 1,
            depths[k]
        );
    }
    for k in [1, 3, 5, 7] {
        assert_eq!(depths[k], 0.0);
    }
}

/// Largest tilt (rad) of the die's body z axis from vertical over `steps` steps, and the
/// centre-of-mass x velocity after `probe_steps`.
fn slide(friction: f64, speed: f64, steps: usize, probe_steps: usize) -> (f64, f64) {
    let mut p = Params::default();
    p.ground.friction = friction;
    let initial = InitialCondition {
        height: resting_height(&p),
        velocity: [speed, 0.0, 0.0],
        ..Default::default()
    };
    let mut s = sim(&p, initial);
    let mut max_tilt: f64 = 0.0;
    let mut probe = f64::NAN;
    for n in 1..=steps {
        s.step();
        let r = &s.state().corner_offsets;
        let up = (r[1] - r[0]).normalize();
        max_tilt = max_tilt.max(up.z.clamp(-1.0, 1.0).acos());
        if n == probe_steps {
            probe = s.state().velocity.x;
        }
    }
    (max_tilt, probe)
}

#[test]
fn flat_slide_with_mu_below_one_decelerates_at_mu_g() {
    let (mu, v0) = (0.5, 100.0);
    let (tilt, v) = slide(mu, v0, 100, 100);
    let expected = v0 - mu * 980.0 * 0.1;
    assert!(
        (v - expected).abs() < 0.02 * v0,
        "v after 0.1 s = {v}, μ·g predicts {expected}"
    );
    assert!(tilt < 0.02, "a μ < 1 slide must not trip (tilt {tilt} rad)");
}

#[test]
fn flat_slide_with_mu_above_one_trips() {
    let (tilt, _) = slide(1.5, 300.0, 400, 1);
    assert!(
        tilt > 0.5,
        "a μ > 1 slide must trip over its front edge (tilt {tilt} rad)"
    );
}

/// Rebound speed (cm/s) of a die dropped flat onto the ground at `v_in`, no friction.
fn rebound_speed(v_in: f64) -> f64 {
    let mut p = Params::default();
    p.ground.friction = 0.0;
    // Gravity barely acts during the ~6 ms contact and a small Δt resolves the impact.
    p.world.gravity = 10.0;
    p.integrator.dt = 1e-5;
    let initial = InitialCondition {
        height: 1.0 + 1e-6,
        velocity: [0.0, 0.0, -v_in],
        ..Default::default()
    };
    let mut s = sim(&p, initial);
    let mut touched = false;
    for _ in 0..100_000 {
        s.step();
        touched |= s.in_contact();
        if touched && !s.in_contact() {
            return s.state().velocity.z;
        }
    }
    panic!("the die never left the ground");
}

/// `q` solving `ln(1−q) + q = ln(1+p) − p` for `0 < q < 1` (docs/model.md, "Derived checks").
fn restitution_q(p: f64) -> f64 {
    let target = (1.0 + p).ln() - p;
    let f = |q: f64| (1.0 - q).ln() + q - target;
    let (mut lo, mut hi) = (0.0, 1.0 - 1e-15);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        // f decreases from 0 at q = 0 to −∞ at q = 1; target < 0.
        if f(mid) > 0.0 { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

#[test]
fn restitution_follows_the_gamma_v_law() {
    let gamma = Params::default().ground.damping;
    for v_in in [20.0, 100.0, 300.0] {
        let v_out = rebound_speed(v_in);
        let q = restitution_q(gamma * v_in);
        let want = q / gamma;
        assert!(
            (v_out - want).abs() < 0.01 * want,
            "v_in {v_in}: out {v_out}, law {want}"
        );
        // e ≈ 1 − (2/3)·γ·v for small γ·v.
        if v_in <= 20.0 {
            assert!((v_out / v_in - (1.0 - 2.0 / 3.0 * gamma * v_in)).abs() < 0.01);
        }
    }
    // No rebound exceeds 1/γ, however hard the impact.
    assert!(rebound_speed(2000.0) < 1.0 / gamma);
}

#[test]
fn flight_invariant_e_minus_half_m_g_dt_vz_is_constant() {
    let p = Params::default();
    let initial = InitialCondition {
        velocity: [30.0, -20.0, 40.0],
        angular_velocity: [5.0, 7.0, -3.0],
        ..Default::default()
    };
    let mut s = sim(&p, initial);
    let invariant = |s: &Simulation| {
        s.energy().total() - 0.5 * p.total_mass() * p.world.gravity * p.integrator.dt * s.state().velocity.z
    };
    let i0 = invariant(&s);
    let mut total_changed = false;
    while !s.in_contact() {
        let e_before = s.energy().total();
        s.step();
        if s.in_contact() {
            break;
        }
        assert!(
            (invariant(&s) - i0).abs() < 1e-7,
            "step {}: {}",
            s.state().step,
            invariant(&s) - i0
        );
        total_changed |= s.energy().total() != e_before;
    }
    assert!(
        total_changed,
        "the total itself is not conserved by semi-implicit Euler"
    );
}

#[test]
fn paper_defaults_stay_bounded_long_after_settling() {
    let p = Params::default();
    let initial = InitialCondition {
        angular_velocity: [20.0, -35.0, 10.0],
        ..Default::default()
    };
    let mut s = sim(&p, initial);
    let e0 = s.energy().total();
    let (mut max_free, mut max_any): (f64, f64) = (e0, e0);
    for _ in 0..20_000 {
        s.advance();
        let e = s.energy().total();
        max_any = max_any.max(e);
        if !s.in_contact() {
            max_free = max_free.max(e);
        }
    }
    eprintln!("initial {e0} erg, largest in flight {max_free}, largest in contact {max_any}");
    assert_eq!(s.outcome().unwrap().status, Status::Settled);
    // Off the ground the energy may only fall (bar rounding); during a stiff impact the
    // sampled energy of semi-implicit Euler overshoots by O((ω·Δt)²), a few percent here.
    assert!(
        max_free <= e0 * (1.0 + 1e-9),
        "energy in flight grew from {e0} to {max_free}"
    );
    assert!(
        max_any <= e0 * 1.10,
        "energy during contact grew from {e0} to {max_any}"
    );
    assert!(
        s.energy().total() < p.edge_energy(),
        "long after settling the die rests on a face"
    );
}

#[test]
fn far_past_the_stability_limit_the_roll_ends_unstable_promptly() {
    let mut p = Params::default();
    p.ground.stiffness = 2e7;
    p.ground.friction = 0.0;
    assert!(p.stability_number() > 2.0);
    let outcome = sim(&p, InitialCondition::default()).run_to_end();
    assert_eq!(outcome.status, Status::Unstable);
    assert_eq!(outcome.face, None);
    // First contact is at step 169: instability shows within a few bounces.
    assert!(outcome.steps < 2000, "took {} steps", outcome.steps);
}

#[test]
fn a_die_that_never_lands_times_out() {
    let mut p = Params::default();
    p.integrator.max_time = 0.5;
    let outcome = sim(
        &p,
        InitialCondition {
            height: 1000.0,
            ..Default::default()
        },
    )
    .run_to_end();
    assert_eq!(outcome.status, Status::Timeout);
    assert_eq!(outcome.steps, 500);
}

#[test]
fn same_input_gives_bit_identical_results() {
    let p = Params::default();
    let initial = InitialCondition {
        velocity: [12.5, -3.25, 7.0],
        angular_velocity: [33.0, -17.0, 41.0],
        orientation: [10.0, 20.0, 30.0],
        ..Default::default()
    };
    let run = move || {
        let mut s = sim(&p, initial);
        let o = s.run_to_end();
        let st = s.state().clone();
        (
            o.steps,
            o.face,
            st.position.map(f64::to_bits),
            st.angular_momentum.map(f64::to_bits),
        )
    };
    let first = run();
    for _ in 0..3 {
        assert_eq!(run(), first);
    }
    let from_thread = std::thread::spawn(run).join().unwrap();
    assert_eq!(from_thread, first);
}

#[test]
fn energy_ledger_closes_and_its_remainder_is_the_integrators() {
    let p = Params::default();
    let initial = InitialCondition {
        velocity: [40.0, 10.0, 0.0],
        angular_velocity: [20.0, -35.0, 10.0],
        ..Default::default()
    };
    let mut s = sim(&p, initial);
    // Free flight: the only loss is semi-implicit Euler's ½·M·g²·Δt² per step.
    let per_step = 0.5 * p.total_mass() * p.world.gravity.powi(2) * p.integrator.dt.powi(2);
    for _ in 0..150 {
        s.step();
    }
    let l = s.energy_ledger();
    assert_eq!((l.damping_loss, l.friction_loss), (0.0, 0.0));
    assert!((l.integrator_loss - 150.0 * per_step).abs() < 1e-6, "{l:?}");
    // Through the impacts: damping and friction take out energy, the books still balance,
    // and the integrator's share stays a small part of what the ground dissipated.
    s.run_to_end();
    let l = s.energy_ledger();
    assert!(l.damping_loss > 0.0 && l.friction_loss > 0.0, "{l:?}");
    let sum = l.current + l.damping_loss + l.friction_loss + l.integrator_loss;
    assert!((sum - l.initial).abs() < 1e-6 * l.initial);
    eprintln!("{l:?}");
    let dissipated = l.damping_loss + l.friction_loss;
    assert!(l.integrator_loss.abs() < 0.1 * dissipated, "{l:?}");
}

#[test]
fn friction_loss_of_a_flat_slide_is_mu_m_g_times_distance() {
    let mut p = Params::default();
    p.ground.friction = 0.5;
    let initial = InitialCondition {
        height: resting_height(&p),
        velocity: [100.0, 0.0, 0.0],
        ..Default::default()
    };
    let mut s = sim(&p, initial);
    // 0.15 s of sliding: the die slows from 100 to ~26 cm/s and never stops slipping.
    for _ in 0..150 {
        s.step();
    }
    let slid = s.state().position.x;
    let l = s.energy_ledger();
    let expected = p.ground.friction * p.total_mass() * p.world.gravity * slid;
    assert!(
        (l.friction_loss - expected).abs() < 0.02 * expected,
        "{l:?}, μ·M·g·Δx = {expected}"
    );
    // The kinetic energy the slide lost went to friction, not to the integrator.
    assert!(l.integrator_loss.abs() < 0.02 * l.friction_loss, "{l:?}");
}
