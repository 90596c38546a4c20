//! A d20 rolled: the die's body of 12 points through the step, both engines bit for bit, each
//! settled roll showing the number a player reads off the die at rest, and its stopping rule
//! the cube's at the paper's size.

use crate::common::random_start;
use dicesim_physics::lanes::roll_points_in_lanes;
use dicesim_physics::polyhedron::DieKind;
use dicesim_physics::{InitialCondition, Params, PointRoll, RandomRanges, Status};
use nalgebra::{Matrix3, Rotation3};

#[test]
fn a_d20_rolls_to_the_number_a_player_reads() {
    let params = Params::default();
    let die = DieKind::D20.standard();
    let body = die.point_body::<12>(&params).expect("a d20 is a body");
    let ranges = RandomRanges::default();
    let starts: Vec<InitialCondition> = (0..16)
        .map(|i| random_start(&ranges, &InitialCondition::default(), 51, i))
        .collect();
    let lanes = roll_points_in_lanes(&params, &body, &starts).expect("valid starts");
    let mut faces = Vec::new();
    for (start, lane) in starts.iter().zip(&lanes) {
        let mut roll = PointRoll::new(&params, &body, start).expect("a valid start");
        let outcome = roll.run_to_end();
        assert_eq!(
            Some(outcome),
            lane.outcome(),
            "the lanes give the scalar engine's end"
        );
        let bits = |r: &PointRoll<12>| r.state().corner_offsets.map(|v| v.map(f64::to_bits));
        assert_eq!(bits(&roll), bits(lane), "the lanes give the scalar engine's bits");
        assert_eq!(outcome.status, Status::Settled, "{start:?}: {outcome:?}");
        let face = outcome.face.expect("a settled roll shows a face");
        // The die at rest: its orientation read off its points, then read as a player does.
        let turn: Matrix3<f64> = body.orientation(&roll.state().corner_offsets);
        let reading = die
            .reading_at(&Rotation3::from_matrix_unchecked(turn))
            .expect("at rest on a face");
        assert_eq!(u32::from(face), reading.number);
        faces.push(face);
    }
    faces.sort_unstable();
    faces.dedup();
    assert!(faces.len() > 6, "16 random throws show many faces: {faces:?}");
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
