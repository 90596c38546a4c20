//! A die set at rest on a face stays there at its derived depths (docs/model.md, "Resting
//! depth on a spring table"): every die on every face, held for a second of the step with its
//! other points clear of the table, then settled showing the number read with that face down.
//! Under the spring-friction law its face's points stay at the depths the springs' balance
//! gives; under the paper's law its kinetic friction chatters (docs/model.md, "Friction
//! chatter") and the depths swing about them, the springs' load averaging the weight.

use super::dice_table;
use dicesim_physics::polyhedron::DieKind;
use dicesim_physics::{ContactLaw, InitialCondition, PointRoll, Status};
use nalgebra::{Matrix3, Rotation3, Vector3};

/// `kind` (of `N` vertices) placed at rest on each face in turn at the depths
/// [`Die::rest_depth`](dicesim_physics::polyhedron::Die::rest_depth) derives, tilted as they
/// say, under `law`: for a second every other point stays clear of the table and the springs'
/// mean load is the weight (to 10⁻³), and under the spring-friction law every one of the
/// face's points stays within `tolerance` of its depth (a share of the mean depth) and the
/// centre does not slide; then the roll settles on that face.
fn stays_at_rest<const N: usize>(kind: DieKind, law: ContactLaw, tolerance: f64) {
    let mut params = dice_table();
    params.ground.contact = law;
    let (k, g) = (params.ground.stiffness, params.world.gravity);
    let die = kind.standard();
    let body = die.point_body::<N>(&params).expect("a die is a body");
    let centre = die.mass_properties().centre_of_mass;
    let steps = (1.0 / params.integrator.dt).round() as u64;
    for (f, face) in die.shape().faces().iter().enumerate() {
        let name = format!("{} on face {f}, {law:?}", kind.name());
        let rest = die
            .rest_depth(f, k, g)
            .expect("a die rests on all its face's points");
        let mean = rest.points.iter().sum::<f64>() / rest.points.len() as f64;
        // The face's normal straight down, then the small turn and the height that put its
        // points at their depths: z_c + q_z + (θ × q)_z = −d for each point q of the face.
        let level = Rotation3::rotation_between(&face.normal, &-Vector3::z())
            .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI));
        let (mut a, mut b) = (Matrix3::zeros(), Vector3::zeros());
        for (&v, d) in face.vertices.iter().zip(&rest.points) {
            let q = level * (die.shape().vertices()[v] - centre);
            let row = Vector3::new(1.0, q.y, -q.x);
            a += row * row.transpose();
            b += row * (-d - q.z);
        }
        let [height, tx, ty] = a.lu().solve(&b).expect("a face spans a plane").into();
        let (roll, pitch, yaw) = (Rotation3::new(Vector3::new(tx, ty, 0.0)) * level).euler_angles();
        let start = InitialCondition {
            height,
            velocity: [0.0; 3],
            angular_velocity: [0.0; 3],
            angular_momentum: None,
            orientation: [yaw, pitch, roll].map(f64::to_degrees),
        };
        let mut run = PointRoll::new(&params, &body, &start).expect("a valid start");
        let mut load = 0.0;
        for _ in 0..steps {
            run.step();
            let s = run.state();
            for (v, depth) in s.corner_depths.iter().enumerate() {
                match face.vertices.iter().position(|&w| w == v) {
                    Some(at) => {
                        load += depth;
                        assert!(
                            law == ContactLaw::Paper || (depth - rest.points[at]).abs() <= tolerance * mean,
                            "{name}, step {}: point {v} {depth} cm deep, derived {}",
                            s.step,
                            rest.points[at]
                        );
                    }
                    None => assert!(*depth <= 0.0, "{name}: point {v} touches, {depth} cm"),
                }
            }
            let slide = s.position.x.hypot(s.position.y);
            assert!(
                law == ContactLaw::Paper || slide <= tolerance * mean,
                "{name}: slid {slide} cm"
            );
        }
        // The springs' mean load is the weight, whatever the chatter.
        let weight = die.mass_properties().mass * g;
        let load = k * load / steps as f64;
        assert!(
            (load - weight).abs() <= 1e-3 * weight,
            "{name}: the springs held {load} dyn of {weight}"
        );
        let outcome = run.run_to_end();
        assert_eq!(outcome.status, Status::Settled, "{name}: {outcome:?}");
        let read = die.numbering().read_with_down(f);
        assert_eq!(outcome.face.map(u32::from), Some(read), "{name}");
    }
}

/// The regular solids' faces sit evenly about the centre's foot: their depths are
/// `M·g/(n·k)`, exact, and the state keeps them to rounding.
const EXACT: f64 = 1e-9;

/// The d10's tilted kite: its depths are the linear balance's, good to about a tenth of a
/// percent (docs/model.md), and the die swings that much about the true rest.
const TILTED: f64 = 3e-3;

#[test]
fn every_die_set_at_rest_on_a_face_stays_there_at_its_derived_depth() {
    for law in [ContactLaw::SpringFriction, ContactLaw::Paper] {
        stays_at_rest::<4>(DieKind::D4, law, EXACT);
        stays_at_rest::<8>(DieKind::D6, law, EXACT);
        stays_at_rest::<6>(DieKind::D8, law, EXACT);
        stays_at_rest::<12>(DieKind::D10, law, TILTED);
        stays_at_rest::<12>(DieKind::Percentile, law, TILTED);
        stays_at_rest::<20>(DieKind::D12, law, EXACT);
        stays_at_rest::<12>(DieKind::D20, law, EXACT);
    }
}

#[test]
fn the_regular_solids_rest_at_their_weight_over_their_springs() {
    // docs/model.md's table, at D = 1.6 cm on the paper's table: δ = M·g/(n·k).
    let params = dice_table();
    let (k, g) = (params.ground.stiffness, params.world.gravity);
    for (kind, n, depth) in [
        (DieKind::D4, 3.0, 6.8367e-4),
        (DieKind::D6, 4.0, 2.3683e-3),
        (DieKind::D8, 3.0, 2.7347e-3),
        (DieKind::D12, 5.0, 1.3145e-3),
        (DieKind::D20, 3.0, 1.9949e-3),
    ] {
        let die = kind.standard();
        let weight = die.mass_properties().mass * g;
        assert!((weight / (n * k) - depth).abs() < 1e-4 * depth, "{}", kind.name());
        for f in 0..die.shape().faces().len() {
            let rest = die.rest_depth(f, k, g).expect("rests");
            for d in rest.points {
                assert!((d - depth).abs() < 1e-4 * depth, "{}: {d} cm", kind.name());
            }
        }
    }
}
