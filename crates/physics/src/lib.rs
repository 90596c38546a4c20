//! The paper's dice model (docs/model.md): pure, no I/O, no threads.
//!
//! Units are CGS throughout: cm, g, s; forces in dyn, energies in erg.

pub mod body;
pub(crate) mod energy;
pub mod initial;
pub(crate) mod kernel;
pub(crate) mod lane;
pub mod lanes;
pub(crate) mod mass;
pub mod params;
pub mod shape;
pub(crate) mod sim;
pub(crate) mod spin;
pub mod stability;
pub mod stopping;

pub use body::{PIP_LAYOUT, Pip, contact_sphere_centres, face_frame, pip_centres, pips};
pub use body::{face_most_nearly_up, opposite_face};
pub use energy::Energy;
pub use initial::{InitialCondition, RandomRanges};
pub use lane::Lane;
pub use params::{Die, FrictionLaw, Ground, Integrator, Limits, ParamError, Params, StopEnergy, World};
pub use shape::{FaceReadout, MassProperties, face_readouts, mass_properties};
pub use sim::{ContactForce, EnergyLedger, Outcome, Simulation, State, Status};
pub use stability::{Limit, Reading, Stability, UnstableReason};
pub use stopping::{StopRule, settles};

/// Rolls one die from `initial` to the end; the parameters must already be valid.
pub fn roll(params: &Params, initial: &InitialCondition) -> Result<(Outcome, Simulation), ParamError> {
    let mut sim = Simulation::new(params, initial)?;
    let outcome = sim.run_to_end();
    Ok((outcome, sim))
}
