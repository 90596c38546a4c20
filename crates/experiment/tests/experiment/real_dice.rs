//! Real dice bodies (docs/model.md, "Real dice"): every shipped preset rolls alike in both
//! engine widths; a general body's torque-free flight and the tennis-racket flip; the size
//! keys of a preset file.

use dicesim_experiment::trace;
use dicesim_physics::RandomRanges;
use dicesim_physics::lanes::{LaneResult, lanes_available, roll_in_lanes, roll_one_by_one};
use dicesim_physics::{InitialCondition, Params, Simulation};
use dicesim_setup::number::StepClock;
use dicesim_setup::preset::{Preset, SHIPPED};
use dicesim_setup::random::RandomDraws;
use nalgebra::Vector3;

/// A state's every number as bits, and its step count: what two engines must agree on.
fn state_bits(s: dicesim_physics::lanes::EndState<'_>) -> Vec<u64> {
    let mut v: Vec<f64> = Vec::with_capacity(80);
    v.extend(s.position.iter());
    v.extend(s.velocity.iter());
    v.extend(s.angular_momentum.iter());
    for k in 0..s.corner_offsets.len() {
        v.extend(s.corner_offsets[k].iter());
        v.extend(s.corner_forces[k].iter());
        v.push(s.corner_depths[k]);
    }
    v.push(s.time_s);
    let mut bits: Vec<u64> = v.into_iter().map(f64::to_bits).collect();
    bits.push(s.step);
    bits
}

/// A roll's result as bits: the whole final state, then end time, status, face, steps and
/// start face.
fn bits(r: &LaneResult<'_>) -> Vec<u64> {
    let mut out = state_bits(r.state);
    out.extend([
        r.outcome.time_s.to_bits(),
        r.outcome.status as u64,
        r.outcome.face.map_or(0, u64::from),
        r.outcome.steps,
        u64::from(r.start_face),
    ]);
    out
}

type Engine = fn(
    usize,
    &mut dyn FnMut(usize) -> (Params, InitialCondition),
    &mut dyn FnMut(LaneResult<'_>),
    &dyn Fn() -> bool,
) -> bool;

fn run(engine: Engine, setups: &[(Params, InitialCondition)]) -> Vec<Vec<u64>> {
    let mut out = vec![Vec::new(); setups.len()];
    assert!(engine(
        setups.len(),
        &mut |i| setups[i],
        &mut |r| out[r.index] = bits(&r),
        &|| false
    ));
    out
}

fn shipped(name: &str) -> Preset {
    let text = SHIPPED.iter().find(|(n, _)| *n == name).expect("shipped").1;
    Preset::from_toml_str(text, name).expect("valid")
}

/// Random throws of a preset (its `[random]` ranges, from any orientation), some cut at
/// 0.4 s (flight and the first impacts) and some rolled to their end.
fn throws(p: &Preset, cut: usize, whole: usize) -> Vec<(Params, InitialCondition)> {
    let random = RandomRanges {
        random_orientation: true,
        ..p.random
    };
    (0..cut + whole)
        .map(|i| {
            let mut params = p.params();
            if i < cut {
                params.integrator.max_time = 0.4;
            }
            (params, random.draw(&p.initial, 20, i as u64))
        })
        .collect()
}

#[test]
fn every_shipped_preset_rolls_alike_in_both_widths() {
    assert!(lanes_available(), "this test needs an x86-64 CPU with AVX2");
    let mut mixed = Vec::new();
    for (name, _) in SHIPPED {
        let p = shipped(name);
        let mut setups = throws(&p, 60, 12);
        // The preset's own roll too (the tennis racket's flip is that one).
        setups.push((p.params(), p.initial));
        let (scalar, lanes) = (run(roll_one_by_one, &setups), run(roll_in_lanes, &setups));
        for (i, (s, l)) in scalar.iter().zip(&lanes).enumerate() {
            assert_eq!(s, l, "{name}: roll {i} differs between the widths");
        }
        mixed.extend(setups.into_iter().step_by(7));
    }
    // Neighbouring lanes carrying different bodies: sharp, rounded, drilled, loaded.
    let (scalar, lanes) = (run(roll_one_by_one, &mixed), run(roll_in_lanes, &mixed));
    assert_eq!(scalar, lanes, "mixed presets differ between the widths");
}

/// The body's y axis in the world frame, from its sphere centres (corner 1 to corner 3).
fn middle_axis(sim: &Simulation) -> Vector3<f64> {
    let r = &sim.state().corner_offsets;
    (r[2] - r[0]).normalize()
}

#[test]
fn the_tennis_racket_flips_at_least_twice_in_flight() {
    // The middle axis turns over against L: from within 18° of L to within 18° of −L and
    // back, each crossing one flip, counted until the first touch of the table.
    let p = shipped("tennis-racket");
    let mut sim = Simulation::new(&p.params(), &p.initial).unwrap();
    let l = sim.state().angular_momentum.normalize();
    let near = 18f64.to_radians().cos();
    let mut side = 0i8;
    let mut flips = 0;
    while !sim.in_contact() {
        let c = middle_axis(&sim).dot(&l);
        let now = if c >= near {
            1
        } else if c <= -near {
            -1
        } else {
            0
        };
        if now != 0 && now != side {
            if side != 0 {
                flips += 1;
                println!("flip {flips} at {:.3} s", sim.state().time_s);
            }
            side = now;
        }
        sim.step();
        assert!(sim.state().time_s < 10.0, "it never landed");
    }
    assert!(
        flips >= 2,
        "only {flips} flips before landing at {} s",
        sim.state().time_s
    );
}

/// The largest relative drift of `½·L·ω` and of `|L|` in the body frame over 1 s of
/// torque-free flight at this Δt.
fn flight_drift(dt: f64) -> (f64, f64) {
    let mut p = shipped("tennis-racket").params();
    p.integrator.dt = dt;
    p.world.gravity = 10.0;
    let initial = InitialCondition {
        height: 500.0,
        velocity: [0.0; 3],
        angular_velocity: [7.0, 3.0, -11.0],
        orientation: [20.0, 35.0, -10.0],
        ..InitialCondition::default()
    };
    let mut sim = Simulation::new(&p, &initial).unwrap();
    let body_l = |sim: &Simulation| {
        let r = &sim.state().corner_offsets;
        let l = sim.state().angular_momentum;
        let axes = [
            (r[4] - r[0]).normalize(),
            (r[2] - r[0]).normalize(),
            (r[1] - r[0]).normalize(),
        ];
        Vector3::new(axes[0].dot(&l), axes[1].dot(&l), axes[2].dot(&l)).norm()
    };
    let (e0, l0) = (sim.energy().rotational, body_l(&sim));
    let (mut e_drift, mut l_drift) = (0.0f64, 0.0f64);
    let steps = (1.0 / dt).round() as usize;
    for _ in 0..steps {
        sim.step();
        assert!(!sim.in_contact());
        e_drift = e_drift.max(((sim.energy().rotational - e0) / e0).abs());
        l_drift = l_drift.max(((body_l(&sim) - l0) / l0).abs());
    }
    (e_drift, l_drift)
}

#[test]
fn torque_free_flight_errs_by_order_dt_squared() {
    let (e1, l1) = flight_drift(1e-3);
    let (e2, l2) = flight_drift(5e-4);
    // The splitting about the principal axes (docs/model.md, "Rotation of an anisotropic
    // body"): second order, halving Δt quarters the energy's error, and no drift.
    let ratio = e1 / e2;
    println!("½L·ω errs by {e1:e} at 1 ms, {e2:e} at 0.5 ms; |L| in the body frame {l1:e}, {l2:e}");
    assert!(
        e1 > 0.0 && (3.2..4.8).contains(&ratio),
        "error {e1:e} then {e2:e}, ratio {ratio}"
    );
    assert!(e1 < 1e-4, "{e1}");
    // L stands still in flight and the body turns by rotations, so |L| in the body frame
    // keeps to rounding.
    assert!(l1 < 1e-12 && l2 < 1e-12, "{l1:e} {l2:e}");
}

/// On `tennis-racket` the ledger's total (the rigid-body energy the explorer's ledger shows
/// as "total") changes by less than 0.5 % across each flight between bounces, read from the
/// trace `dicesim trace` prints: in flight only semi-implicit Euler's `½·M·g²·Δt²` per step
/// and the splitting's bounded error remain (docs/model.md). The paper's rotation gained 20 %
/// in the flight after the first bounce.
#[test]
fn the_tennis_racket_keeps_its_energy_across_every_flight() {
    let p = shipped("tennis-racket");
    let params = p.params();
    let mut sim = dicesim_physics::Roll::new(&params, &p.initial).unwrap();
    let clock = StepClock::new(params.integrator.dt);
    // `values` leaves out the step, the header's first column.
    let header = trace::header();
    let column = |name: &str| header.iter().position(|h| h == name).expect(name) - 1;
    let (total, force, time) = (
        column("e_total_erg"),
        column("contact_force_dyn"),
        column("time_s"),
    );
    // Each flight's (start time, start total, end total), a flight being the rows with no
    // contact force.
    let mut flights: Vec<(f64, f64, f64)> = Vec::new();
    let mut flying = false;
    trace::follow(&mut sim, None, 1, &mut |sim| {
        let v = trace::values(sim, &clock);
        if v[force] == 0.0 {
            if !flying {
                flights.push((v[time], v[total], v[total]));
            }
            flights.last_mut().expect("a flight").2 = v[total];
        }
        flying = v[force] == 0.0;
        Ok::<(), ()>(())
    })
    .unwrap();
    assert!(flights.len() >= 3, "it bounced only {} times", flights.len() - 1);
    for (start, before, after) in flights {
        let change = (after - before) / before;
        assert!(
            change.abs() < 0.005,
            "the flight from {start} s: {before} erg to {after} erg, {:+.2} %",
            100.0 * change
        );
    }
}

#[test]
fn the_older_half_size_loads_as_three_and_both_are_refused() {
    let p = Preset::from_toml_str("[die]\nhalf_size = 0.8\n", "old.toml").unwrap();
    assert_eq!(p.die.half_sizes, [0.8; 3]);
    let e = Preset::from_toml_str(
        "[die]\nhalf_size = 0.8\nhalf_sizes = [1.0, 1.0, 0.9]\n",
        "both.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("both.toml:3:1: key `die.half_sizes`"), "{e}");
    assert!(
        e.contains("`half_sizes`") && e.contains("`half_size`") && e.contains("not both"),
        "{e}"
    );
    // A cube is written the older way; any other body with its three half sizes, and read
    // back the same.
    for name in ["paper", "plate", "rounded-die"] {
        let p = shipped(name);
        let again = Preset::from_toml_str(&p.to_toml(), name).unwrap();
        assert_eq!(again.die, p.die, "{name}");
    }
    let overridden = shipped("paper")
        .with_overrides(&["die.half_sizes=[1.0, 0.9, 1.0]"])
        .unwrap();
    assert_eq!(overridden.die.half_sizes, [1.0, 0.9, 1.0]);
    let back = overridden.with_overrides(&["die.half_size=0.7"]).unwrap();
    assert_eq!(back.die.half_sizes, [0.7; 3]);
}

#[test]
fn bodies_out_of_shape_are_refused_naming_the_rule() {
    let refused = |toml: &str| Preset::from_toml_str(toml, "p.toml").unwrap_err().to_string();
    let e = refused("[die]\nhalf_sizes = [1.0, 0.5, 1.0]\ncorner_radius = 0.5\n");
    assert!(
        e.contains("`die.corner_radius` = 0.5") && e.contains("below the smallest half size, 0.5 cm"),
        "{e}"
    );
    let e = refused("[die]\ncorner_radius = 0.4\npip_diameter = 0.3\n");
    assert!(
        e.contains("`die.pip_diameter` = 0.3") && e.contains("at most 0.2 cm"),
        "{e}"
    );
    let e = refused("[die]\npip_diameter = 0.3\npip_depth = 0.2\n");
    assert!(
        e.starts_with("p.toml:3:1:") && e.contains("at most half the pip diameter, 0.15 cm"),
        "{e}"
    );
    let e = refused("[die]\ncorner_radius = 0.1\n[integrator]\nstop_energy = \"point-masses\"\n");
    assert!(
        e.contains("`integrator.stop_energy`") && e.contains("paper's sharp cube"),
        "{e}"
    );
    // The paper's die keeps the authors' energy.
    Preset::from_toml_str("[integrator]\nstop_energy = \"point-masses\"\n", "p.toml").unwrap();
}

/// Budden's cuboid of ratio x/y: two square faces 2 cm across (faces 1 and 6), x = ratio·2
/// cm apart, solid steel of 7.8 g/cm³.
#[test]
fn a_budden_cuboid_has_its_sizes_steel_mass_and_the_cuboid_inertia() {
    use dicesim_experiment::compare_budden::cuboid;
    use dicesim_physics::mass_properties;
    for ratio in [0.47, 1.16, 2.65] {
        let die = cuboid(ratio);
        assert_eq!(die.half_sizes, [ratio, 1.0, 1.0]);
        let m = mass_properties(&die);
        // 7.8 g/cm³ × (2·ratio cm × 2 cm × 2 cm).
        let mass = 7.8 * 8.0 * ratio;
        assert!((m.mass - mass).abs() < 1e-12 * mass, "{ratio}: {}", m.mass);
        assert!(m.centre_of_mass.norm() < 1e-12);
        // A solid cuboid of sides 2a, 2b, 2c about its centre: M(b² + c²)/3 and the others.
        let [a, b, c] = [ratio, 1.0, 1.0];
        let inertia = [
            mass * (b * b + c * c) / 3.0,
            mass * (a * a + c * c) / 3.0,
            mass * (a * a + b * b) / 3.0,
        ];
        for (i, &expected) in inertia.iter().enumerate() {
            assert!(
                (m.inertia[(i, i)] - expected).abs() < 1e-9 * expected,
                "{ratio} {i}"
            );
            for j in (0..3).filter(|&j| j != i) {
                assert!(m.inertia[(i, j)].abs() < 1e-9);
            }
        }
    }
}

/// A cuboid set down on each of its six faces stays there, and the square-face count agrees
/// with where its centre comes to rest: at the half length (ratio · 1 cm) above the table
/// on a square face, 1 cm on a long one.
#[test]
fn a_budden_cuboid_at_rest_on_each_face_is_counted_square_or_not() {
    use dicesim_experiment::compare_budden::{cuboid, is_square_face};
    let ratio = 0.63;
    let params = Params {
        die: cuboid(ratio),
        ..Params::default()
    };
    // Each orientation turns a different body axis to the vertical, either way up.
    let orientations = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 180.0],
        [0.0, 0.0, 90.0],
        [0.0, 0.0, -90.0],
        [0.0, 90.0, 0.0],
        [0.0, -90.0, 0.0],
    ];
    let mut faces = Vec::new();
    for orientation in orientations {
        // Dropped flat from 1 cm: 1 cm of fall is more energy than the stop rule lets a
        // settled body keep (tipping this cuboid off a square face takes 0.55 cm of rise),
        // so it lands, bounces and settles before the roll ends.
        let vertical = if orientation[1] != 0.0 { ratio } else { 1.0 };
        let initial = InitialCondition {
            height: vertical + 1.0,
            velocity: [0.0; 3],
            angular_velocity: [0.0; 3],
            angular_momentum: None,
            orientation,
        };
        let mut sim = Simulation::new(&params, &initial).unwrap();
        let outcome = sim.run_to_end();
        let face = outcome.face.expect("it settles on a face");
        let height = sim.state().position.z;
        // The roll ends once its energy is below the stop rule's threshold `E` for the face
        // down, still bobbing on the springs: with the potential measured from the lowest rest
        // height `z₀ = ratio`, its centre may end as deep as `d` below its half size `v`
        // where `w·(v − d − z₀) + 2k·d² = E` (weight `w`, four springs of stiffness `k`): 0.151
        // cm on a square face of this steel cuboid, whose half sizes differ by 0.37 cm.
        let e = sim.stop_rule_now().energy_threshold;
        let w = params.total_mass() * params.world.gravity;
        let k = params.ground.stiffness;
        let c = w * (vertical - ratio) - e;
        let deepest = (w + (w * w - 8.0 * k * c).max(0.0).sqrt()) / (4.0 * k);
        assert!(
            deepest < 0.2 && height > vertical - deepest && height < vertical + 0.15,
            "{orientation:?}: rests at {height} cm (as deep as {deepest} cm allowed)"
        );
        assert_eq!(
            is_square_face(face),
            vertical == ratio,
            "{orientation:?}: face {face}"
        );
        faces.push(face);
    }
    faces.sort_unstable();
    assert_eq!(faces, [1, 2, 3, 4, 5, 6]);
}
