//! Dice rolled: each die's body of points through the step, both engines bit for bit, each
//! settled roll showing the number a player reads off the die at rest, and the stopping rule
//! the cube's at the paper's size.

use super::{dice_table, throw};
use dicesim_physics::lanes::roll_points_in_lanes;
use dicesim_physics::polyhedron::{Die, DieKind};
use dicesim_physics::{InitialCondition, Params, PointRoll, Status};
use nalgebra::{Matrix3, Rotation3, Vector3};

/// `die` (of `N` vertices) thrown from each of `starts` on the dice' table, through both
/// engines: every roll settles, the lanes give the scalar engine's bits, and the number shown
/// is the one a player reads off the die at rest. The numbers shown, in the starts' order.
pub fn roll_both_engines<const N: usize>(die: &Die, starts: &[InitialCondition]) -> Vec<u8> {
    let params = dice_table();
    let body = die.point_body::<N>(&params).expect("a die is a body");
    let lanes = roll_points_in_lanes(&params, &body, starts).expect("valid starts");
    let bits = |r: &PointRoll<N>| r.state().corner_offsets.map(|v| v.map(f64::to_bits));
    starts
        .iter()
        .zip(&lanes)
        .map(|(start, lane)| {
            let mut roll = PointRoll::new(&params, &body, start).expect("a valid start");
            let outcome = roll.run_to_end();
            assert_eq!(
                Some(outcome),
                lane.outcome(),
                "the lanes give the scalar engine's end"
            );
            assert_eq!(bits(&roll), bits(lane), "the lanes give the scalar engine's bits");
            assert_eq!(outcome.status, Status::Settled, "{start:?}: {outcome:?}");
            let face = outcome.face.expect("a settled roll shows a face");
            // The die as it stopped: its orientation read off its points, the face most nearly
            // down found in it, and read as a player does. The rule stops a die that can no
            // longer tip over an edge, which may still rock on its face past the tilt at which
            // `Die::reading` calls it flat, so the face is not asked to lie flat yet.
            let turn: Matrix3<f64> = body.orientation(&roll.state().corner_offsets);
            let down = Rotation3::from_matrix_unchecked(turn).inverse() * -Vector3::z();
            let read = die.numbering().read_with_down(die.face_most_nearly_down(&down));
            assert_eq!(u32::from(face), read, "{start:?}");
            face
        })
        .collect()
}

/// The numbers `throws` random throws of `kind` show, sorted and deduplicated.
fn shown<const N: usize>(kind: DieKind, throws: u64) -> Vec<u8> {
    let starts: Vec<InitialCondition> = (0..throws).map(|i| throw(51, i)).collect();
    let mut faces = roll_both_engines::<N>(&kind.standard(), &starts);
    faces.sort_unstable();
    faces.dedup();
    faces
}

#[test]
fn a_d20_rolls_to_the_number_a_player_reads() {
    let faces = shown::<12>(DieKind::D20, 16);
    assert!(faces.len() > 6, "16 random throws show many faces: {faces:?}");
}

#[test]
fn every_die_rolls_to_the_number_a_player_reads() {
    for (kind, faces) in [
        (DieKind::D4, shown::<4>(DieKind::D4, 8)),
        (DieKind::D6, shown::<8>(DieKind::D6, 8)),
        (DieKind::D8, shown::<6>(DieKind::D8, 8)),
        (DieKind::D10, shown::<12>(DieKind::D10, 8)),
        (DieKind::Percentile, shown::<12>(DieKind::Percentile, 8)),
        (DieKind::D12, shown::<20>(DieKind::D12, 8)),
    ] {
        assert!(
            faces.len() > 1,
            "{}: 8 throws show more than one face: {faces:?}",
            kind.name()
        );
    }
}

#[test]
fn a_d6_stops_by_the_paper_cubes_rule() {
    // At the paper's size (side 2 cm, 8 g) the d6's rule is the cube's: E_edge = M g a (√2 − 1).
    let params = Params::default();
    let die = DieKind::D6.die(2.0, 1.0);
    let (rule, edge) = die.stop_rule(&params);
    let weight = 8.0 * params.world.gravity;
    let expected = weight * (2f64.sqrt() - 1.0);
    assert!(
        (edge - expected).abs() < 1e-12 * expected,
        "{edge} against {expected}"
    );
    let k = params.ground.stiffness;
    let e_max = (0.8 * expected).min(expected - weight * weight / (4.0 * k) - 0.1 * expected);
    assert!((rule.energy_threshold - e_max).abs() < 1e-9 * expected);
    assert!((rule.kinetic_threshold - (e_max + weight * weight / (8.0 * k))).abs() < 1e-9 * expected);
    // On a table too soft to hold it, no state settles.
    let soft = Params {
        ground: dicesim_physics::Ground {
            stiffness: 100.0,
            ..params.ground
        },
        ..params
    };
    assert!(!die.stop_rule(&soft).0.can_settle());
}
