//! When a roll on screen is over: its stopping rule decides the face, but a settled die
//! plays on a little so it is seen coming to rest. The live die and its twin both ask.

use dicesim_physics::{Roll, Status};

/// s of simulated time a settled die plays on past its stopping rule at most.
const PLAY_ON_S: f64 = 2.0;

/// A die that plays on past its stopping rule is at rest once its kinetic energy is below
/// this share of the rule's threshold.
const AT_REST_SHARE: f64 = 0.01;

/// Whether a die's roll is over on screen. Its stopping rule decides the face (and ends
/// the roll's data: the outcome, the table, the exports) while the die may still rock or
/// slide a little; a settled die plays on until it is at rest or [`PLAY_ON_S`] later,
/// whichever comes first, so a class never sees it freeze mid-motion. A roll that did not
/// settle, or went unstable, is over at once.
pub(crate) fn played_out(sim: &Roll) -> bool {
    match sim.outcome() {
        None => false,
        Some(o) if o.status != Status::Settled => true,
        Some(o) => {
            sim.energy().kinetic() < AT_REST_SHARE * sim.stop_threshold()
                || sim.time_s() >= o.time_s + PLAY_ON_S
        }
    }
}
