//! Tipping barriers against the hand-derived values of docs/model.md, rounding's effect on
//! them, and the resting depth on a spring table.

use super::{assert_close, d10, regular};
use dicesim_physics::polyhedron::{DieKind, Flaws};
use nalgebra::Vector3;

const G: f64 = 981.0;

#[test]
fn each_regular_die_tips_at_its_hand_derived_barrier() {
    for solid in regular() {
        let die = solid.kind.standard();
        let a = solid.edge(1.6);
        let expected = (solid.midradius - solid.inradius) * a;
        let tipping = die.tipping();
        assert_close(solid.kind.name(), tipping.rise, expected, expected, 1e-12);
        // Every face alike.
        for f in 0..solid.faces {
            let rise = die
                .face_tipping(f)
                .expect("a regular die rests on every face")
                .rise;
            assert_close(solid.kind.name(), rise, expected, expected, 1e-12);
        }
        let mass = die.mass_properties().mass;
        assert_close(
            "energy",
            tipping.energy(mass, G),
            mass * G * expected,
            mass * G * expected,
            1e-12,
        );
    }
    // The table of docs/model.md at 1.6 cm.
    let table = [
        ("d4", 0.292820),
        ("d6", 0.331371),
        ("d8", 0.179796),
        ("d12", 0.140456),
        ("d20", 0.056373),
    ];
    for (solid, (name, rise)) in regular().iter().zip(table) {
        assert_eq!(solid.kind.name(), name);
        assert_close(name, solid.kind.standard().tipping().rise, rise, 1.0, 5e-7);
    }
}

#[test]
fn the_d10_tips_over_an_apex_edge() {
    let die = DieKind::D10.standard();
    let apex = die.shape().vertices().iter().map(|v| v.z).fold(0.0, f64::max);
    let [_, _, _, _, inradius, apex_edge, zigzag_edge] = d10(apex);
    assert!(apex_edge < zigzag_edge);
    let tipping = die.tipping();
    assert_close(
        "d10",
        tipping.rise,
        apex_edge - inradius,
        apex_edge - inradius,
        1e-12,
    );
    assert_close("d10 table", tipping.rise, 0.088903, 1.0, 5e-7);
    let (i, j) = tipping.edge;
    let on_axis = |k: usize| die.shape().vertices()[k].x == 0.0 && die.shape().vertices()[k].y == 0.0;
    assert!(
        on_axis(i) || on_axis(j),
        "the least tip is over an edge from an apex"
    );
    for f in 0..10 {
        let zigzag = die.shape().faces()[f]
            .vertices
            .iter()
            .zip(die.shape().faces()[f].vertices.iter().cycle().skip(1))
            .filter(|&(&a, &b)| !on_axis(a) && !on_axis(b))
            .map(|(&a, &b)| die.edge_height(a, b))
            .collect::<Vec<_>>();
        assert_eq!(zigzag.len(), 2);
        for h in zigzag {
            assert_close("zigzag edge", h, zigzag_edge, zigzag_edge, 1e-12);
        }
    }
}

#[test]
fn even_rounding_scales_every_barrier_by_one_less_its_share_of_the_inradius() {
    // Every die here has all its faces at one inradius, so its corner spheres' centres are
    // the die shrunk by 1 − r/r_i (docs/model.md, "Rounded corners").
    for kind in [
        DieKind::D4,
        DieKind::D6,
        DieKind::D8,
        DieKind::D10,
        DieKind::D12,
        DieKind::D20,
    ] {
        let die = kind.standard();
        let inradius = die.rest_height(0);
        for r in [0.01, 0.05, 0.1] {
            let rounded = die
                .with_flaws(&Flaws {
                    rounding: vec![r],
                    ..Flaws::default()
                })
                .expect("a small rounding");
            let expected = die.tipping().rise * (1.0 - r / inradius);
            assert_close(kind.name(), rounded.tipping().rise, expected, expected, 1e-11);
            // Still resting at its inradius.
            assert_close(kind.name(), rounded.rest_height(0), inradius, inradius, 1e-12);
        }
    }
}

#[test]
fn one_rounder_vertex_lowers_the_barriers_round_it_alone() {
    let die = DieKind::D20.standard();
    let mut rounding = vec![0.02; 12];
    rounding[0] = 0.08;
    let uneven = die
        .with_flaws(&Flaws {
            rounding,
            ..Flaws::default()
        })
        .expect("uneven rounding");
    let even = die
        .with_flaws(&Flaws {
            rounding: vec![0.02],
            ..Flaws::default()
        })
        .expect("even rounding");
    for (f, face) in die.shape().faces().iter().enumerate() {
        let (a, b) = (
            uneven.face_tipping(f).expect("rests").rise,
            even.face_tipping(f).expect("rests").rise,
        );
        if face.vertices.contains(&0) {
            assert!(a < b - 1e-4, "face {f} round the rounder vertex: {a} against {b}");
        } else {
            assert_close("a face away from it", a, b, b, 1e-9);
        }
    }
}

#[test]
fn a_die_rests_at_its_weight_over_its_springs() {
    let k = 1e6;
    for kind in DieKind::ALL {
        let die = kind.standard();
        let props = die.mass_properties();
        let weight = props.mass * G;
        for (f, face) in die.shape().faces().iter().enumerate() {
            let n = face.vertices.len() as f64;
            let rest = die
                .rest_depth(f, k, G)
                .expect("a die rests on all its face's points");
            // The springs carry the weight, and their moments about the centre cancel.
            assert_close(
                kind.name(),
                rest.points.iter().sum::<f64>() * k,
                weight,
                weight,
                1e-12,
            );
            let moment: Vector3<f64> = face
                .vertices
                .iter()
                .zip(&rest.points)
                .map(|(&v, d)| {
                    (die.shape().vertices()[v] - props.centre_of_mass).cross(&face.normal) * (k * d)
                })
                .sum();
            assert!(moment.norm() < 1e-9 * weight, "{}: moment {moment}", kind.name());
            if !matches!(kind, DieKind::D10 | DieKind::Percentile) {
                // A regular solid's face sits evenly about the centre's foot: level.
                assert_close(
                    kind.name(),
                    rest.centre,
                    weight / (n * k),
                    weight / (n * k),
                    1e-12,
                );
                for d in rest.points {
                    assert_close(kind.name(), d, weight / (n * k), weight / (n * k), 1e-10);
                }
            }
        }
    }
}

/// The dice' table with `kind` of 1.6 cm at 1.18 g/cm³, as the shipped presets have them.
fn shipped(kind: dicesim_physics::Solid) -> dicesim_physics::Params {
    let mut p = super::dice_table();
    p.die.kind = kind;
    p.die.height = 1.6;
    p.die.density = 1.18;
    p
}

#[test]
fn a_dies_stability_readings_are_its_own_body_s() {
    use dicesim_physics::{InitialCondition, Limit, Solid, Stability};
    // The d4 of height h: its centroid h/4 above a face and 3h/4 from each vertex; edge
    // a = h·√(3/2), volume a³/(6√2), I = M·a²/20 = 3·M·h²/40 about any axis. One vertex on
    // the table: 1/m = 1/M + (3h/4)²/I = 8.5/M (docs/model.md, "Fair dice come out fair").
    let h = 1.6;
    let mut p = shipped(Solid::D4);
    // Undamped, so that nothing stiffens the springs while a point strikes.
    p.ground.damping = 0.0;
    let a = h * 1.5f64.sqrt();
    let mass = 1.18 * a.powi(3) / (6.0 * 2f64.sqrt());
    let (k, dt) = (p.ground.stiffness, p.integrator.dt);
    // Placed on a face (its start orientation, docs/dice.md) on the table top, at rest but for
    // a spin ω about x: no landing speed, and its farthest vertex moves at ω·3h/4.
    let spin = 40.0;
    let initial = InitialCondition {
        height: 0.25 * h,
        angular_velocity: [spin, 0.0, 0.0],
        ..Default::default()
    };
    let readings = Stability::predict(&p, &initial);
    let reading = |limit| readings.reading(limit).expect("the paper's law reads it");
    let rock = reading(Limit::ContactMode);
    assert_close("ω_rock·Δt", rock.value, (8.5 * k / mass).sqrt() * dt, 1.0, 1e-12);
    let travel = reading(Limit::CornerTravel);
    assert_close("point travel", travel.value, spin * 0.75 * h * dt, 1.0, 1e-12);
    assert_close("travel allowed", travel.allowed, h / 4.0, 1.0, 1e-12);
    // Every regular solid is as wide across its thinnest pair of point planes as it stands
    // tall (face to face; the d4 face to vertex): so deep may a point press.
    for kind in [Solid::D4, Solid::D8, Solid::D12, Solid::D20] {
        let p = shipped(kind);
        let depth = Stability::predict(&p, &InitialCondition::default())
            .reading(Limit::ImpactDepth)
            .unwrap();
        assert_close(kind.name(), depth.allowed, h, h, 1e-12);
    }
}
