//! How fast each die rolls in each engine (docs/speed.md): rolls a second and steps × points a
//! second, the scalar engine's [`PointRoll`] one throw after another against the lanes'
//! [`roll_points_in_lanes`], on the dice' table from the fairness tests' throws. A measurement,
//! not a check: run it alone, on an idle machine (`uptime`), in the test profile (optimised):
//!
//! ```text
//! cargo test -p dicesim-physics --test physics -- --ignored --nocapture dice::speed
//! ```

use super::{dice_table, throw};
use dicesim_physics::PointRoll;
use dicesim_physics::lanes::roll_points_in_lanes;
use dicesim_physics::polyhedron::DieKind;
use std::time::Instant;

/// `throws` throws of `kind` (of `N` points) by each engine: rolls/s, steps × points/s, and
/// the lanes over the scalar engine. Both engines must end every throw alike.
fn rates<const N: usize>(kind: DieKind, throws: u64) -> f64 {
    let params = dice_table();
    let body = kind.standard().point_body::<N>(&params).expect("a die is a body");
    let starts: Vec<_> = (0..throws).map(|i| throw(2026, i)).collect();
    let clock = Instant::now();
    let scalar: Vec<_> = starts
        .iter()
        .map(|s| PointRoll::new(&params, &body, s).expect("valid").run_to_end())
        .collect();
    let scalar_s = clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let lanes = roll_points_in_lanes(&params, &body, &starts).expect("valid");
    let lanes_s = clock.elapsed().as_secs_f64();
    let steps: u64 = scalar.iter().map(|o| o.steps).sum();
    for (s, l) in scalar.iter().zip(&lanes) {
        assert_eq!(Some(*s), l.outcome(), "the engines end alike");
    }
    let point_steps = (steps * N as u64) as f64;
    println!(
        "{:>4}: scalar {:>7.0} rolls/s {:>6.1} M point-steps/s | lanes {:>7.0} rolls/s {:>6.1} M point-steps/s | {:.2}× ({} steps a roll)",
        kind.name(),
        throws as f64 / scalar_s,
        point_steps / scalar_s / 1e6,
        throws as f64 / lanes_s,
        point_steps / lanes_s / 1e6,
        scalar_s / lanes_s,
        steps / throws
    );
    point_steps / lanes_s
}

#[test]
#[ignore = "a measurement: see the module's doc for the command"]
fn every_die_in_each_engine() {
    let throws = std::env::var("DICE_SPEED_THROWS")
        .ok()
        .and_then(|t| t.parse().ok())
        .unwrap_or(2_000);
    let d6 = rates::<8>(DieKind::D6, throws);
    rates::<4>(DieKind::D4, throws);
    rates::<6>(DieKind::D8, throws);
    rates::<12>(DieKind::D10, throws);
    rates::<20>(DieKind::D12, throws);
    let d20 = rates::<12>(DieKind::D20, throws);
    println!("d20's lanes point-steps/s over the d6's: {:.2}", d20 / d6);
}
