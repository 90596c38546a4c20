//! The paper's dice model (docs/model.md): pure, no I/O, no threads.
//!
//! Units are CGS throughout: cm, g, s; forces in dyn, energies in erg.

pub mod body;
pub mod energy;
pub mod initial;
pub mod params;
pub mod registry;
pub mod sim;

pub use body::{face_most_nearly_up, face_of_highest_corners, opposite_face};
pub use energy::Energy;
pub use initial::{InitialCondition, RandomRanges};
pub use params::{Die, FrictionLaw, Ground, Integrator, Limits, ParamError, Params, StopEnergy, World};
pub use sim::{ContactForce, EnergyLedger, Outcome, Simulation, State, Status};

/// Rolls one die from `initial` to the end; the parameters must already be valid.
pub fn roll(params: &Params, initial: &InitialCondition) -> Result<(Outcome, Simulation), ParamError> {
    let mut sim = Simulation::new(params, initial)?;
    let outcome = sim.run_to_end();
    Ok((outcome, sim))
}
