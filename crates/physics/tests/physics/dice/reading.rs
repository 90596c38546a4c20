//! Numbers and reading: every number once, opposite faces summing as on real dice, and the
//! face read from an orientation, with "no face" on an edge or a vertex.

use dicesim_physics::Solid;
use dicesim_physics::polyhedron::{DieKind, ReadAt, prism};
use nalgebra::{Rotation3, Vector3};

#[test]
fn every_number_appears_once() {
    for (kind, expected) in [
        (DieKind::D4, (1..=4).collect::<Vec<u32>>()),
        (DieKind::D6, (1..=6).collect()),
        (DieKind::D8, (1..=8).collect()),
        (DieKind::D10, (0..=9).collect()),
        (DieKind::Percentile, (0..=9).map(|n| 10 * n).collect()),
        (DieKind::D12, (1..=12).collect()),
        (DieKind::D20, (1..=20).collect()),
    ] {
        let mut numbers = kind.standard().numbering().numbers.clone();
        numbers.sort_unstable();
        assert_eq!(numbers, expected, "{}", kind.name());
    }
}

#[test]
fn opposite_faces_sum_as_on_real_dice() {
    for (kind, sum) in [
        (DieKind::D6, 7),
        (DieKind::D8, 9),
        (DieKind::D10, 9),
        (DieKind::Percentile, 90),
        (DieKind::D12, 13),
        (DieKind::D20, 21),
    ] {
        let die = kind.standard();
        assert_eq!(die.numbering().read_at, ReadAt::TopFace);
        for (f, face) in die.shape().faces().iter().enumerate() {
            let g = die.numbering().opposite[f].expect("every face has an opposite");
            assert!(
                (face.normal + die.shape().faces()[g].normal).norm() < 1e-12,
                "{}: not opposite",
                kind.name()
            );
            assert_eq!(
                die.numbering().numbers[f] + die.numbering().numbers[g],
                sum,
                "{}",
                kind.name()
            );
        }
    }
}

/// What a batch's summary counts as "opposite" (`Solid::opposite_number`) is the number the
/// solid's own numbering carries on the parallel face, for every face of every die.
#[test]
fn the_opposite_number_a_tally_uses_is_on_the_parallel_face() {
    for solid in Solid::ALL {
        if solid == Solid::Convex {
            // Numbered by its corners: no opposite a solid alone can name.
            assert_eq!(solid.opposite_number(1), None);
            continue;
        }
        let Some(kind) = solid.regular() else {
            // The box: its faces 1–6 as the paper numbers them.
            assert_eq!(
                (1..=6).map(|f| solid.opposite_number(f)).collect::<Vec<_>>(),
                [6, 5, 4, 3, 2, 1].map(Some)
            );
            continue;
        };
        assert_eq!(Solid::showing(solid.face_numbers()), Some(solid));
        let die = kind.standard();
        for (f, &n) in die.numbering().numbers.iter().enumerate() {
            let number = u8::try_from(n).unwrap();
            let parallel =
                die.numbering().opposite[f].map(|g| u8::try_from(die.numbering().numbers[g]).unwrap());
            assert_eq!(
                solid.opposite_number(number),
                parallel,
                "{} face {n}",
                solid.name()
            );
        }
    }
}

#[test]
fn the_d10_has_even_numbers_round_one_apex_and_odd_round_the_other() {
    let die = DieKind::D10.standard();
    for (face, &n) in die.shape().faces().iter().zip(&die.numbering().numbers) {
        assert_eq!(face.normal.z > 0.0, n % 2 == 0, "face {n}");
    }
}

/// The die turned so that `face`'s normal points straight down.
fn resting_on(normal: &Vector3<f64>) -> Rotation3<f64> {
    Rotation3::rotation_between(normal, &-Vector3::z())
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI))
}

#[test]
fn a_die_on_a_face_reads_the_number_up() {
    for kind in DieKind::ALL {
        let die = kind.standard();
        for (f, face) in die.shape().faces().iter().enumerate() {
            let reading = die.reading_at(&resting_on(&face.normal)).expect("a face is down");
            assert_eq!(reading.face, f);
            let up = match die.numbering().read_at {
                ReadAt::TopFace => die.numbering().numbers[die.numbering().opposite[f].expect("opposite")],
                ReadAt::TopVertex | ReadAt::BottomFace => die.numbering().numbers[f],
            };
            assert_eq!(reading.number, up, "{}", kind.name());
        }
    }
    // The paper's cube dropped at the identity shows 4.
    assert_eq!(
        DieKind::D6
            .standard()
            .reading_at(&Rotation3::identity())
            .map(|r| r.number),
        Some(4)
    );
}

#[test]
fn the_d4_reads_the_vertex_up() {
    let die = DieKind::D4.standard();
    for (f, face) in die.shape().faces().iter().enumerate() {
        let r = resting_on(&face.normal);
        let top = (0..4).max_by(|&a, &b| {
            (r * die.shape().vertices()[a])
                .z
                .total_cmp(&(r * die.shape().vertices()[b]).z)
        });
        assert_eq!(
            die.reading_at(&r).map(|x| x.number),
            top.map(|k| k as u32 + 1),
            "face {f}"
        );
    }
}

#[test]
fn an_edge_or_a_vertex_down_is_no_face() {
    for kind in DieKind::ALL {
        let die = kind.standard();
        for edge in die.shape().edges() {
            let [f, g] = edge.faces;
            let down = die.shape().faces()[f].normal + die.shape().faces()[g].normal;
            assert_eq!(die.reading(&down), None, "{}: on an edge", kind.name());
            // A small tilt off a face is still that face.
            let tilted = die.shape().faces()[f].normal * 20.0 + die.shape().faces()[g].normal;
            assert_eq!(
                die.reading(&tilted).map(|r| r.face),
                Some(f),
                "{}: near a face",
                kind.name()
            );
        }
        for v in die.shape().vertices() {
            assert_eq!(die.reading(v), None, "{}: on a vertex", kind.name());
        }
    }
}

#[test]
fn a_prism_without_opposite_faces_is_read_at_the_face_down() {
    let d3 = prism(3, 0.8, 2.5, 1.18).expect("a triangular prism");
    assert_eq!(d3.numbering().read_at, ReadAt::BottomFace);
    let coin = prism(16, 1.2, 0.3, 1.18).expect("a coin");
    assert_eq!(coin.numbering().read_at, ReadAt::TopFace);
    let mut numbers = coin.numbering().numbers.clone();
    numbers.sort_unstable();
    assert_eq!(numbers, (1..=18).collect::<Vec<u32>>());
}

#[test]
fn a_die_is_named_as_players_name_it() {
    for kind in DieKind::ALL {
        assert_eq!(DieKind::from_name(kind.name()), Ok(kind));
    }
    assert_eq!(
        DieKind::from_name("d7"),
        Err("no die called \"d7\": one of d4, d6, d8, d10, d%, d12, d20".to_string())
    );
}
