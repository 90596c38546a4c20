//! Bodies given as their contact points (docs/model.md, "A body of N points"): a regular
//! tetrahedron (N = 4, isotropic) and a 4×4×4 grid box (N = 64, anisotropic, so it turns by
//! the splitting), each through both contact laws and both engines. What they must do is
//! derived in the docs: in free flight the energy falls by exactly `½·M·g²·Δt²` a step (the
//! box's rotational energy within 0.1 %, its `L` unchanged); at rest on a face of `n`
//! symmetric points each sinks `M·g/(n·k)`; and the lane engine gives every roll the scalar
//! engine's bits.

use dicesim_physics::lanes::roll_points_in_lanes;
use dicesim_physics::{ContactLaw, InitialCondition, Params, PointBody, PointRoll, Status, StopRule};
use nalgebra::{Matrix3, Vector3};

const MASS: f64 = 8.0;

/// A rule that settles a body resting on a face of `n` points only once its energy is
/// within 10⁻⁵ erg of the lowest, `−M·g·d + n·½·k·d² = −(M·g)²/(2·n·k)` at `d = M·g/(n·k)`
/// (measured from the face's rest height on a rigid table): then its points' depths are
/// within `√(2·10⁻⁵/(n·k))`, under 0.1 % of `d`, of rest.
fn rule(n: f64) -> StopRule {
    let p = Params::default();
    let weight = MASS * p.world.gravity;
    StopRule {
        energy_threshold: -weight * weight / (2.0 * n * p.ground.stiffness) + 1e-5,
        kinetic_threshold: 1e-5,
    }
}

/// A regular tetrahedron of circumradius 1 cm, its base (face 1) down at z = −1/3: a solid
/// one's `I = M·a²/20` with `a² = 8/3`. Its edge pass from the base: the centre `1/3` above
/// it, `√3/3` from a base edge, so `M·g·(√3 − 1)/3`.
fn tetrahedron() -> PointBody<4> {
    let r = 8f64.sqrt() / 3.0;
    let s = 3f64.sqrt() / 2.0;
    let vertices = [
        Vector3::new(0.0, 0.0, 1.0),
        Vector3::new(r, 0.0, -1.0 / 3.0),
        Vector3::new(-r / 2.0, r * s, -1.0 / 3.0),
        Vector3::new(-r / 2.0, -r * s, -1.0 / 3.0),
    ];
    // Face k + 1 is the one opposite vertex k: its outward normal is −v_k.
    let faces: Vec<(Vector3<f64>, u8)> = vertices.iter().zip([1, 2, 3, 4]).map(|(v, n)| (-v, n)).collect();
    let edge_energy = MASS * 980.0 * (3f64.sqrt() - 1.0) / 3.0;
    let inertia = Matrix3::identity() * (MASS * (8.0 / 3.0) / 20.0);
    PointBody::new(
        vertices,
        0.0,
        MASS,
        Vector3::zeros(),
        inertia,
        &faces,
        rule(3.0),
        edge_energy,
    )
    .expect("a tetrahedron")
}

/// Half sizes of the grid box, cm.
const HALF: [f64; 3] = [1.5, 1.0, 0.6];

/// 4×4×4 points spanning a box of half sizes [`HALF`], a solid box's tensor
/// `M/3·diag(b² + c², a² + c², a² + b²)`, faces numbered as a die's (opposite faces sum to 7,
/// −z is 1). Its lowest edge pass, from its largest face over its longest edge:
/// `M·g·(√(b² + c²) − c)`.
fn grid_box() -> PointBody<64> {
    let at = |i: usize, h: f64| h * (-1.0 + 2.0 * i as f64 / 3.0);
    let vertices: [Vector3<f64>; 64] = std::array::from_fn(|k| {
        Vector3::new(at(k / 16, HALF[0]), at(k / 4 % 4, HALF[1]), at(k % 4, HALF[2]))
    });
    let [a, b, c] = HALF.map(|h| h * h);
    let inertia = Matrix3::from_diagonal(&Vector3::new(b + c, a + c, a + b)) * (MASS / 3.0);
    let faces = [
        (-Vector3::z(), 1),
        (Vector3::z(), 6),
        (-Vector3::x(), 2),
        (Vector3::x(), 5),
        (-Vector3::y(), 3),
        (Vector3::y(), 4),
    ];
    let edge_energy = MASS * 980.0 * ((b + c).sqrt() - HALF[2]);
    PointBody::new(
        vertices,
        0.0,
        MASS,
        Vector3::zeros(),
        inertia,
        &faces,
        rule(16.0),
        edge_energy,
    )
    .expect("a grid box")
}

fn params(law: ContactLaw) -> Params {
    let mut p = Params::default();
    p.ground.contact = law;
    p.integrator.max_time = 10.0;
    p
}

/// A flat drop from 0.3 cm (it lands on the face down and comes to rest there), and three
/// throws from 6–12 cm with spins of 10–40 rad/s.
fn starts(lowest: f64) -> [InitialCondition; 4] {
    let flat = InitialCondition {
        height: lowest + 0.3,
        velocity: [0.0; 3],
        angular_velocity: [0.0; 3],
        ..InitialCondition::default()
    };
    let throw = |height: f64, velocity: [f64; 3], spin: [f64; 3], orientation: [f64; 3]| InitialCondition {
        height,
        velocity,
        angular_velocity: spin,
        orientation,
        ..InitialCondition::default()
    };
    [
        flat,
        throw(6.0, [30.0, -10.0, 0.0], [10.0, -25.0, 5.0], [20.0, 35.0, -10.0]),
        throw(9.0, [-20.0, 40.0, 10.0], [-30.0, 12.0, 40.0], [-70.0, 10.0, 60.0]),
        throw(12.0, [5.0, 5.0, -30.0], [3.0, 33.0, -21.0], [45.0, -45.0, 15.0]),
    ]
}

/// A roll's end (status, face, steps, time's bits) and its final state's every number as bits.
type Bits = (Option<(Status, Option<u8>, u64, u64)>, Vec<u64>);

fn bits<const N: usize>(roll: &PointRoll<N>) -> Bits {
    let s = roll.state();
    let mut v: Vec<f64> = [s.position, s.velocity, s.angular_momentum]
        .iter()
        .flat_map(|x| x.iter().copied())
        .collect();
    for k in 0..N {
        v.extend(s.corner_offsets[k].iter());
        v.extend(s.corner_forces[k].iter());
        v.push(s.corner_depths[k]);
        v.extend(roll.tangential_springs()[k].iter());
    }
    let outcome = roll
        .outcome()
        .map(|o| (o.status, o.face, o.steps, o.time_s.to_bits()));
    (outcome, v.into_iter().map(f64::to_bits).collect())
}

/// Rolls `body` from each start through both engines, checks the flight energy of every
/// scalar roll step by step, and returns the flat drop's finished roll.
fn roll_both_engines<const N: usize>(body: &PointBody<N>, law: ContactLaw, lowest: f64) -> PointRoll<N> {
    let p = params(law);
    let starts = starts(lowest);
    let (g, dt) = (p.world.gravity, p.integrator.dt);
    let per_step = 0.5 * MASS * g * g * dt * dt;
    let isotropic = (body.inertia() - Matrix3::identity() * body.inertia()[(0, 0)]).norm() == 0.0;
    let mut scalar = Vec::new();
    for start in &starts {
        let mut roll = PointRoll::new(&p, body, start).expect("a valid start");
        let (mut flights, first_spin) = (0, roll.energy().rotational);
        let (l, mut landed) = (roll.state().angular_momentum, roll.in_contact());
        // The first flight, step by step.
        while roll.outcome().is_none() {
            let before = roll.energy();
            roll.advance();
            landed |= roll.in_contact();
            if !landed {
                flights += 1;
                let after = roll.energy();
                let linear = |e: &dicesim_physics::Energy| e.translational + e.gravitational;
                let fall = linear(&before) - linear(&after);
                assert!(
                    (fall - per_step).abs() < 1e-9 * linear(&before).abs().max(1.0),
                    "N = {N}, {law:?}: a flight step lost {fall} erg, not ½·M·g²·Δt² = {per_step}"
                );
                if isotropic {
                    assert_eq!(
                        after.rotational, before.rotational,
                        "N = {N}: ω = L/I is constant in flight"
                    );
                } else {
                    let drift = (after.rotational - first_spin).abs() / first_spin.max(1e-300);
                    assert!(
                        first_spin == 0.0 || drift < 1e-3,
                        "N = {N}: the splitting drifted {drift}"
                    );
                }
                assert_eq!(roll.state().angular_momentum, l, "L is not touched in flight");
            }
        }
        assert!(flights > 0 || start.height < 1.0, "N = {N}: the throw flew");
        scalar.push(roll);
    }
    let lanes = roll_points_in_lanes(&p, body, &starts).expect("valid starts");
    for (k, (one, four)) in scalar.iter().zip(&lanes).enumerate() {
        assert_eq!(
            bits(one),
            bits(four),
            "N = {N}, {law:?}, start {k}: the engines differ"
        );
    }
    scalar.swap_remove(0)
}

/// The drop's rest: `n` points touch, each `M·g/(n·k)` deep, the others clear.
fn assert_rests_on<const N: usize>(roll: &PointRoll<N>, n: usize, face_down: u8) {
    let outcome = roll.outcome().expect("ended");
    assert_eq!(outcome.status, Status::Settled, "N = {N}: {outcome:?}");
    assert_eq!(roll.face_down(), face_down);
    let p = Params::default();
    let depth = MASS * p.world.gravity / (n as f64 * p.ground.stiffness);
    let s = roll.state();
    let touching: Vec<f64> = s.corner_depths.iter().copied().filter(|&d| d > 0.0).collect();
    assert_eq!(touching.len(), n, "N = {N}: depths {:?}", s.corner_depths);
    for d in touching {
        assert!(
            (d - depth).abs() < 2e-3 * depth,
            "N = {N}: a point sinks {d} cm, derived {depth}"
        );
    }
}

#[test]
fn a_tetrahedron_rolls_alike_in_both_engines_and_rests_on_three_points() {
    let body = tetrahedron();
    for law in [ContactLaw::Paper, ContactLaw::SpringFriction] {
        let rest = roll_both_engines(&body, law, 1.0 / 3.0);
        assert_rests_on(&rest, 3, 1);
    }
}

/// Under the paper's law the box's sixteen points chatter (docs/model.md, "Friction chatter":
/// the explicit kinetic friction reverses a resting point's slip every step, and sixteen
/// points keep about 0.3 erg moving at Δt = 0.5 ms, more at 1 ms), so it never comes within
/// 10⁻⁵ erg of rest; the spring-friction law's static friction holds it.
#[test]
fn a_box_of_64_points_rolls_alike_in_both_engines_and_rests_on_sixteen() {
    let body = grid_box();
    roll_both_engines(&body, ContactLaw::Paper, HALF[2]);
    let rest = roll_both_engines(&body, ContactLaw::SpringFriction, HALF[2]);
    assert_rests_on(&rest, 16, 1);
    assert_eq!(rest.face_up(), 6, "opposite faces sum to 7");
}
