//! Which engine rolls a batch or a map, and rolling a run of setups with it.
//!
//! Both engines give every roll bit for bit the same result (crates/physics/tests/physics/lanes.rs),
//! so the choice changes speed only.

use crate::record::RollRecord;
use dicesim_physics::lanes::{LaneResult, lanes_available, roll_in_lanes, roll_one_by_one};
use dicesim_physics::{InitialCondition, Params};
use serde::Serialize;

/// The engine that steps the rolls.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Engine {
    /// The lane engine where the CPU has AVX2, the scalar one elsewhere.
    #[default]
    Auto,
    /// One `Simulation` after another.
    Scalar,
    /// Four rolls per AVX2 vector (the scalar engine where AVX2 is missing).
    Lanes,
}

impl Engine {
    pub fn name(self) -> &'static str {
        match self {
            Engine::Auto => "auto",
            Engine::Scalar => "scalar",
            Engine::Lanes => "lanes",
        }
    }

    /// The engine named `name` (`auto`, `scalar` or `lanes`, as [`Engine::name`] gives it).
    pub fn from_name(name: &str) -> Option<Engine> {
        [Engine::Auto, Engine::Scalar, Engine::Lanes]
            .into_iter()
            .find(|e| e.name() == name)
    }

    /// The engine that really runs on this CPU: `Scalar` or `Lanes`.
    pub fn resolve(self) -> Engine {
        match self {
            Engine::Scalar => Engine::Scalar,
            Engine::Auto | Engine::Lanes if lanes_available() => Engine::Lanes,
            Engine::Auto | Engine::Lanes => Engine::Scalar,
        }
    }
}

/// Rolls `setups` (id, parameters, initial condition) with `engine` and returns their
/// records in the given order: all of them, or, once `stop()` answered true (it is asked
/// inside rolls every few thousand steps), the longest prefix that had finished.
pub(crate) fn roll_setups(
    engine: Engine,
    setups: &[(u64, Params, InitialCondition)],
    stop: &dyn Fn() -> bool,
) -> Vec<RollRecord> {
    let mut done: Vec<Option<RollRecord>> = vec![None; setups.len()];
    let roll = match engine.resolve() {
        Engine::Lanes => roll_in_lanes,
        _ => roll_one_by_one,
    };
    roll(
        setups.len(),
        &mut |i| (setups[i].1, setups[i].2),
        &mut |r: LaneResult<'_>| {
            let (id, params, initial) = setups[r.index];
            done[r.index] = Some(RollRecord {
                id,
                initial,
                outcome: crate::record::reported(r.outcome, &params),
                start_face: r.start_face,
            });
        },
        stop,
    );
    done.into_iter().map_while(|r| r).collect()
}
