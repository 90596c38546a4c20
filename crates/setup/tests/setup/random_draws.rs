//! Golden draws: "random roll #n" of a seed is part of what users rely on (a batch's rolls
//! can be replayed by seed and index, a class can share "seed 1, roll 2"). These are the
//! initial conditions dicesim has drawn for a few `(seed, index)` pairs since its first
//! release; an upgrade of `rand` or of its ChaCha stream that changed any bit of them would
//! change every random roll, and must be a deliberate, announced change.

use dicesim_physics::InitialCondition;
use dicesim_physics::RandomRanges;
use dicesim_setup::random::RandomDraws;

fn bits(ic: &InitialCondition) -> Vec<u64> {
    std::iter::once(ic.height)
        .chain(ic.velocity)
        .chain(ic.angular_velocity)
        .chain(ic.orientation)
        .map(f64::to_bits)
        .collect()
}

fn assert_draw(ranges: &RandomRanges, seed: u64, index: u64, want: InitialCondition) {
    let got = ranges.draw(&InitialCondition::default(), seed, index);
    assert_eq!(got.angular_momentum, None);
    assert_eq!(
        bits(&got),
        bits(&want),
        "seed {seed}, roll {index}: drew {got:?}, expected {want:?}"
    );
}

#[test]
fn default_ranges_draw_the_same_rolls_as_ever() {
    let r = RandomRanges::default();
    assert_draw(
        &r,
        1,
        0,
        InitialCondition {
            height: 15.0,
            velocity: [-41.961629107021814, 9.656018093485486, -28.06754195162],
            angular_velocity: [-25.957129043551497, 25.27322684173305, -4.669419215170123],
            ..Default::default()
        },
    );
    assert_draw(
        &r,
        1,
        1,
        InitialCondition {
            height: 15.0,
            velocity: [-44.9086633997972, 5.87525496308465, -39.94643221240914],
            angular_velocity: [55.70645880463323, -18.65509489845647, 46.85559521496228],
            ..Default::default()
        },
    );
    assert_draw(
        &r,
        1,
        2,
        InitialCondition {
            height: 15.0,
            velocity: [18.274086153127584, -16.333367902390435, 1.1807909499181903],
            angular_velocity: [55.41783182688498, -6.668610356351657, -40.8332912283786],
            ..Default::default()
        },
    );
}

#[test]
fn random_orientations_and_heights_draw_the_same_rolls_as_ever() {
    let r = RandomRanges {
        height: [2.0, 20.0],
        random_orientation: true,
        ..Default::default()
    };
    assert_draw(
        &r,
        2026,
        0,
        InitialCondition {
            height: 12.793804132616945,
            velocity: [-24.602717875050306, -45.77773407251882, -31.283296703052187],
            angular_velocity: [-30.03763262477409, 25.789474143149775, 53.53929976834222],
            orientation: [142.40922047949334, -21.999750818471036, 77.95663741147104],
            ..Default::default()
        },
    );
    assert_draw(
        &r,
        2026,
        1,
        InitialCondition {
            height: 5.73390431803111,
            velocity: [-12.00432547581913, -38.957333010597495, 2.80416027853461],
            angular_velocity: [15.29480998200465, 3.9716471113325014, 19.56070737811058],
            orientation: [89.14038743157796, 36.18528912697132, 133.00313521486316],
            ..Default::default()
        },
    );
}
