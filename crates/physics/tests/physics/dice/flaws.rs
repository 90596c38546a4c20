//! The flaws: a bubble and a point mass with their exact mass corrections, a shaved face, and
//! the refusals that name why a body is impossible; the bubble's bias has the sign derived.

use super::assert_close;
use dicesim_physics::polyhedron::{Bubble, DieKind, FlawError, Flaws, PointMass, Shave, prism};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

#[test]
fn a_bubble_takes_out_a_ball() {
    let die = DieKind::D20.standard();
    let fair = die.mass_properties();
    let (p, r) = (Vector3::new(0.1, -0.2, 0.25), 0.08);
    let flawed = die
        .with_flaws(&Flaws {
            bubble: Some(Bubble { centre: p, radius: r }),
            ..Flaws::default()
        })
        .expect("inside");
    let m_b = die.density() * 4.0 / 3.0 * PI * r.powi(3);
    let props = flawed.mass_properties();
    assert_close("mass", props.mass, fair.mass - m_b, fair.mass, 1e-14);
    let c = -p * m_b / (fair.mass - m_b);
    assert!(
        (props.centre_of_mass - c).norm() < 1e-15,
        "centre {}",
        props.centre_of_mass
    );
    // Parallel axes by hand: the solid about c, less the ball about c.
    let shift = |m: f64, x: Vector3<f64>| (Matrix3::identity() * x.norm_squared() - x * x.transpose()) * m;
    let expected =
        fair.inertia + shift(fair.mass, -c) - Matrix3::identity() * (0.4 * m_b * r * r) - shift(m_b, p - c);
    for i in 0..9 {
        assert_close("inertia", props.inertia[i], expected[i], expected.trace(), 1e-13);
    }
    // Contact points are measured from the new centre.
    let points = flawed.contact_points();
    assert!((points[0].offset - (die.shape().vertices()[0] - c)).norm() < 1e-15);
}

#[test]
fn a_bubble_or_a_point_mass_outside_the_die_is_refused() {
    let die = DieKind::D6.standard();
    let bubble = |x: f64, r: f64| Flaws {
        bubble: Some(Bubble {
            centre: Vector3::new(x, 0.0, 0.0),
            radius: r,
        }),
        ..Flaws::default()
    };
    assert!(die.with_flaws(&bubble(0.6, 0.19)).is_ok());
    // +x is face 6: touching it, or through it.
    assert_eq!(
        die.with_flaws(&bubble(0.6, 0.2)),
        Err(FlawError::BubbleOutside { face: 6 })
    );
    assert_eq!(
        die.with_flaws(&bubble(0.9, 0.05)),
        Err(FlawError::BubbleOutside { face: 6 })
    );
    assert_eq!(die.with_flaws(&bubble(0.0, 0.0)), Err(FlawError::BubbleRadius));
    let point = |z: f64| Flaws {
        point_mass: Some(PointMass {
            position: Vector3::new(0.0, 0.0, z),
            mass: 0.5,
        }),
        ..Flaws::default()
    };
    let on_face = die.with_flaws(&point(0.8)).expect("on the surface");
    let m = die.mass_properties().mass;
    assert_close(
        "point mass's centre",
        on_face.mass_properties().centre_of_mass.z,
        0.5 * 0.8 / (m + 0.5),
        1.0,
        1e-15,
    );
    // −z is face 3.
    assert_eq!(
        die.with_flaws(&point(-0.81)),
        Err(FlawError::PointMassOutside { face: 3 })
    );
}

#[test]
fn a_shaved_cube_is_a_cuboid() {
    let die = DieKind::D6.standard();
    let depth = 0.1;
    let shave = Shave {
        normal: Vector3::x(),
        offset: 0.8 - depth,
    };
    let shaved = die
        .with_flaws(&Flaws {
            shave: Some(shave),
            ..Flaws::default()
        })
        .expect("a shave of face 6");
    let (lx, l) = (1.6 - depth, 1.6);
    let mass = die.density() * lx * l * l;
    let props = shaved.mass_properties();
    assert_close("mass", props.mass, mass, mass, 1e-13);
    assert_close("centre", props.centre_of_mass.x, -depth / 2.0, 1.0, 1e-15);
    let expected = [
        (l * l + l * l) / 12.0,
        (lx * lx + l * l) / 12.0,
        (lx * lx + l * l) / 12.0,
    ];
    for (i, per_mass) in expected.into_iter().enumerate() {
        assert_close("inertia", props.inertia[(i, i)], per_mass * mass, mass, 1e-13);
    }
    assert_eq!(shaved.numbering(), die.numbering(), "every face keeps its number");
    let six = die.numbering().numbers.iter().position(|&n| n == 6).expect("a 6");
    assert_close(
        "face 6 moved in",
        shaved.shape().faces()[six].offset,
        0.8 - depth,
        1.0,
        1e-15,
    );
}

#[test]
fn an_impossible_shave_is_refused() {
    let die = DieKind::D6.standard();
    let shave = |normal: Vector3<f64>, offset: f64| Flaws {
        shave: Some(Shave { normal, offset }),
        ..Flaws::default()
    };
    assert_eq!(
        die.with_flaws(&shave(Vector3::x(), 0.9)),
        Err(FlawError::ShaveMisses)
    );
    // Tilted: it cuts a corner strip of face 6 but leaves the rest of it.
    let tilted = Vector3::new(1.0, 0.0, 0.3).normalize();
    assert_eq!(
        die.with_flaws(&shave(tilted, tilted.dot(&Vector3::new(0.8, 0.0, 0.5)))),
        Err(FlawError::ShaveLeavesFace { face: 6 })
    );
    // Steep enough to take the whole top face (4) with it.
    let steep = Vector3::new(1.0, 0.0, 0.9).normalize();
    assert_eq!(
        die.with_flaws(&shave(steep, steep.dot(&Vector3::new(-0.85, 0.0, 0.8)))),
        Err(FlawError::ShaveRemovesFace { face: 4 })
    );
    // A long square prism whose end is cut so slanted that its centre no longer stands over
    // the new end face.
    let bar = prism(4, 0.5, 4.0, 1.18).expect("a square bar");
    let slant = Vector3::new(40f64.to_radians().sin(), 0.0, 40f64.to_radians().cos());
    let offset = slant.dot(&Vector3::new(-0.5, 0.0, 2.0)) - 0.05;
    let end = bar.numbering().numbers[0];
    assert_eq!(
        bar.with_flaws(&shave(slant, offset)),
        Err(FlawError::ShaveTopples { face: end })
    );
    // Less slanted, it still stands.
    let gentle = Vector3::new(5f64.to_radians().sin(), 0.0, 5f64.to_radians().cos());
    assert!(
        bar.with_flaws(&shave(gentle, gentle.dot(&Vector3::new(-0.5, 0.0, 2.0)) - 0.05))
            .is_ok()
    );
}

#[test]
fn a_bubble_toward_a_face_makes_that_face_come_up() {
    // docs/model.md, "Which way a bubble biases the die": the face away from the bubble holds
    // the die harder, by s·(1 − r_i/r_m) to first order, s = m_b·e/M the centre's shift.
    let die = DieKind::D20.standard();
    let f = 0;
    let n = die.shape().faces()[f].normal;
    let g = die.numbering().opposite[f].expect("an opposite face");
    let fair = die.tipping().rise;
    let (r_i, r_m) = (
        die.rest_height(f),
        die.edge_height(
            die.shape().faces()[f].vertices[0],
            die.shape().faces()[f].vertices[1],
        ),
    );
    let mut previous = 0.0;
    for e in [0.2, 0.4, 0.6] {
        let bubble = Bubble {
            centre: n * e,
            radius: 0.1,
        };
        let flawed = die
            .with_flaws(&Flaws {
                bubble: Some(bubble),
                ..Flaws::default()
            })
            .expect("inside");
        let props = flawed.mass_properties();
        let s = -props.centre_of_mass.dot(&n);
        assert!(s > 0.0, "the centre moves away from the bubble");
        let away = flawed.face_tipping(g).expect("rests").rise;
        let toward = flawed.face_tipping(f).expect("rests").rise;
        let expected = s * (1.0 - r_i / r_m);
        // The neglected second-order term is s²/(2·r_m)·(1 − r_i²/r_m²) < s²/r_m.
        assert_close("away from the bubble", away - fair, expected, s * s / r_m, 1.0);
        assert_close("toward the bubble", toward - fair, -expected, s * s / r_m, 1.0);
        assert!(away - toward > previous, "the bias grows with the offset");
        previous = away - toward;
        // Resting on the heavy face g, the number read is the bubble face's.
        assert_eq!(flawed.numbering().read_with_down(g), die.numbering().numbers[f]);
    }
}

#[test]
fn a_rounding_that_does_not_fit_is_refused() {
    let die = DieKind::D20.standard();
    let round = |rounding: Vec<f64>| Flaws {
        rounding,
        ..Flaws::default()
    };
    assert!(die.with_flaws(&round(vec![0.05; 12])).is_ok());
    assert_eq!(
        die.with_flaws(&round(vec![0.05; 5])),
        Err(FlawError::RoundingCount {
            given: 5,
            vertices: 12
        })
    );
    let mut negative = vec![0.05; 12];
    negative[7] = -0.01;
    assert_eq!(
        die.with_flaws(&round(negative)),
        Err(FlawError::RoundingValue { vertex: 8 })
    );
    // A sphere tangent to a vertex's faces reaches the far side of the die once its radius
    // passes the inradius.
    assert!(matches!(
        die.with_flaws(&round(vec![0.9])),
        Err(FlawError::RoundingTooLarge { vertex: 1, .. })
    ));
    let message = FlawError::RoundingTooLarge { vertex: 1, face: 20 }.to_string();
    assert_eq!(
        message,
        "vertex 1's rounding reaches past face 20: the radius is too large"
    );
}

#[test]
fn new_flaws_replace_the_old_ones() {
    let die = DieKind::D6.standard();
    let shave = |depth: f64| Flaws {
        shave: Some(Shave {
            normal: Vector3::x(),
            offset: 0.8 - depth,
        }),
        ..Flaws::default()
    };
    let once = die.with_flaws(&shave(0.1)).expect("a shave");
    let again = once.with_flaws(&shave(0.1)).expect("the same shave");
    assert_eq!(
        again, once,
        "a shave is made on the die as made, not on a shaved one"
    );
    assert_eq!(once.with_flaws(&Flaws::default()).expect("no flaw"), die);
}
