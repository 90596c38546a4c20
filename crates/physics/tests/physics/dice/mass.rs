//! Mass of the uniform solid: each regular die against its closed forms to 10⁻¹², the d10
//! against its own, and a random hull against a seeded Monte-Carlo estimate.

use super::{assert_close, d10, regular};
use dicesim_physics::polyhedron::{DieKind, convex_hull, solid_moments};
use nalgebra::{Matrix3, Vector3};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};

const DENSITY: f64 = 1.18;

fn check_tensor(what: &str, inertia: &Matrix3<f64>, expected: &Matrix3<f64>) {
    let scale = expected.trace();
    for i in 0..3 {
        for j in 0..3 {
            assert_close(
                &format!("{what} I[{i}{j}]"),
                inertia[(i, j)],
                expected[(i, j)],
                scale,
                1e-12,
            );
        }
    }
}

#[test]
fn each_regular_solid_has_its_volume_centre_and_inertia() {
    for height in [1.6, 0.7, 13.0] {
        for solid in regular() {
            let die = solid.kind.die(height, DENSITY);
            let name = format!("{} at {height} cm", solid.kind.name());
            let a = solid.edge(height);
            let volume = solid.volume * a.powi(3);
            let mass = die.mass_properties();
            assert_close(
                &format!("{name} mass"),
                mass.mass,
                volume * DENSITY,
                volume * DENSITY,
                1e-12,
            );
            assert_close(
                &format!("{name} volume"),
                solid_moments(die.shape()).volume,
                volume,
                volume,
                1e-12,
            );
            assert!(
                mass.centre_of_mass.norm() <= 1e-12 * a,
                "{name}: centre {}",
                mass.centre_of_mass
            );
            let expected = Matrix3::identity() * (solid.inertia * volume * DENSITY * a * a);
            check_tensor(&name, &mass.inertia, &expected);
            // The hull found the solid's faces at its inradius.
            for face in die.shape().faces() {
                assert_close(
                    &format!("{name} inradius"),
                    face.offset,
                    solid.inradius * a,
                    a,
                    1e-12,
                );
            }
            assert_eq!(die.shape().faces().len(), solid.faces);
            assert!(
                die.shape()
                    .faces()
                    .iter()
                    .all(|f| f.vertices.len() == solid.sides)
            );
        }
    }
}

#[test]
fn the_d10_has_its_volume_centre_and_inertia() {
    let die = DieKind::D10.die(1.6, DENSITY);
    let apex = die.shape().vertices().iter().map(|v| v.z).fold(0.0, f64::max);
    let [_, volume, izz, ixx, inradius, ..] = d10(apex);
    assert_close("d10 stands 1.6 cm tall", 2.0 * inradius, 1.6, 1.6, 1e-12);
    let mass = die.mass_properties();
    assert_close("d10 mass", mass.mass, volume * DENSITY, volume * DENSITY, 1e-12);
    assert!(
        mass.centre_of_mass.norm() <= 1e-12 * apex,
        "centre {}",
        mass.centre_of_mass
    );
    let m = volume * DENSITY;
    check_tensor(
        "d10",
        &mass.inertia,
        &Matrix3::from_diagonal(&Vector3::new(ixx * m, ixx * m, izz * m)),
    );
    let percentile = DieKind::Percentile.die(1.6, DENSITY);
    assert_eq!(percentile.mass_properties(), mass, "the d% is the d10's shape");
}

/// Unbiased estimate and standard error of `∫f dV` over a box by uniform samples.
struct Estimate {
    sum: f64,
    sum_sq: f64,
}

#[test]
fn a_random_hull_agrees_with_a_monte_carlo_estimate() {
    let mut rng = ChaCha8Rng::seed_from_u64(51);
    // Points on an ellipsoid are all corners of their hull; shifted off the origin so that the
    // first moments are tested too.
    let centre = Vector3::new(0.3, -0.2, 0.5);
    let axes = Vector3::new(1.0, 0.7, 0.45);
    let points: Vec<Vector3<f64>> = (0..24)
        .map(|_| {
            let u: Vector3<f64> = Vector3::from_fn(|_, _| rng.random_range(-1.0..1.0));
            centre + u.normalize().component_mul(&axes)
        })
        .collect();
    let hull = convex_hull(&points).expect("points on an ellipsoid are convex");
    let moments = solid_moments(&hull);
    // At unit density the mass is the volume; the inertia about the computed centre.
    let props = moments.mass_properties(1.0);
    let c = props.centre_of_mass;
    let (lo, hi) = (centre - axes, centre + axes);
    let box_volume = (hi - lo).iter().product::<f64>();
    let samples = 2_000_000;
    // ∫1, ∫x, ∫y, ∫z, and the inertia's six components ∫(|r|²δ_ij − r_i·r_j), r = x − c.
    let mut estimates: Vec<Estimate> = (0..10)
        .map(|_| Estimate {
            sum: 0.0,
            sum_sq: 0.0,
        })
        .collect();
    for _ in 0..samples {
        let x = Vector3::from_fn(|i, _| rng.random_range(lo[i]..hi[i]));
        if !hull.contains(&x) {
            continue;
        }
        let r = x - c;
        let i = Matrix3::identity() * r.norm_squared() - r * r.transpose();
        let f = [
            1.0,
            x.x,
            x.y,
            x.z,
            i[(0, 0)],
            i[(1, 1)],
            i[(2, 2)],
            i[(0, 1)],
            i[(0, 2)],
            i[(1, 2)],
        ];
        for (e, v) in estimates.iter_mut().zip(f) {
            e.sum += v;
            e.sum_sq += v * v;
        }
    }
    let n = samples as f64;
    let v = props.mass;
    let i = props.inertia;
    let exact = [
        v,
        v * c.x,
        v * c.y,
        v * c.z,
        i[(0, 0)],
        i[(1, 1)],
        i[(2, 2)],
        i[(0, 1)],
        i[(0, 2)],
        i[(1, 2)],
    ];
    for (k, (e, exact)) in estimates.iter().zip(exact).enumerate() {
        let mean = e.sum / n;
        let sd = (e.sum_sq / n - mean * mean).sqrt();
        let (estimate, error) = (mean * box_volume, sd * box_volume / n.sqrt());
        assert!(
            (estimate - exact).abs() <= 4.5 * error,
            "moment {k}: exact {exact}, Monte Carlo {estimate} ± {error}"
        );
        // Sharp enough that a 1 % error in any component is seen.
        let scale = if k < 4 { v } else { i.trace() };
        assert!(
            4.5 * error < 0.01 * exact.abs().max(0.1 * scale),
            "moment {k}: the estimate is too loose to test ({error})"
        );
    }
}

#[test]
fn a_die_turned_and_moved_anywhere_keeps_its_faces_and_its_mass() {
    let mut rng = ChaCha8Rng::seed_from_u64(48);
    for kind in DieKind::ALL {
        let die = kind.die(1.6, DENSITY);
        let fair = die.mass_properties();
        for _ in 0..20 {
            let axis = Vector3::from_fn(|_, _| rng.random_range(-1.0..1.0));
            let turn =
                nalgebra::Rotation3::new(axis.normalize() * rng.random_range(0.0..std::f64::consts::PI));
            let shift = Vector3::from_fn(|_, _| rng.random_range(-50.0..50.0));
            let moved: Vec<Vector3<f64>> = die.shape().vertices().iter().map(|v| turn * v + shift).collect();
            let other =
                dicesim_physics::polyhedron::Die::from_vertices(&moved, DENSITY).expect("still convex");
            assert_eq!(
                other.shape().faces().len(),
                die.shape().faces().len(),
                "{}",
                kind.name()
            );
            let props = other.mass_properties();
            assert_close(kind.name(), props.mass, fair.mass, fair.mass, 1e-12);
            assert!(
                (props.centre_of_mass - shift).norm() <= 1e-12 * 50.0,
                "{}: centre",
                kind.name()
            );
            let turned = turn.matrix() * fair.inertia * turn.matrix().transpose();
            check_tensor(kind.name(), &props.inertia, &turned);
        }
    }
}
