//! The paper's dice model (docs/model.md): pure, no I/O, no threads.
//!
//! Units are CGS throughout: cm, g, s; forces in dyn, energies in erg.
//!
//! The modules are layered, each using only those before it: the data (`params`,
//! `initial`, and `lane`, `energy`, `impact`), the state and its point kinematics (`state`),
//! then the body — its geometry (`body`), the stopping rule's arithmetic (`stopping`), the
//! contact laws, one file each behind one trait (`contact/`), the three bodies a die can be
//! (`cube`, `mass`, `shape`) and `model`, which says which of them a die is and answers every
//! question about it — then the step written over a lane type, a law and a number of points
//! (`spin`, `kernel`), the scalar engine (`sim`), any body as its contact points (`points`)
//! and its scalar engine (`point_roll`), and on top the lane engine (`lanes`), one roll of
//! any die step by step (`roll`, the box's by `sim`, a die's by `point_roll`), the
//! stability readings (`stability`, and the spring-friction law's own in
//! `stability_contact`) and the dice of any convex shape (`polyhedron/`), each a `PointBody`.
//! The polyhedron's geometry (its hull, moments, numbering, flaws, `Die` and the regular
//! solids) uses only the mass properties' type, so `model` asks it what a polyhedral
//! `die.kind` weighs and where it stands; only its `rolled` and `stability` use the step.

pub mod body;
pub mod contact;
mod cube;
mod energy;
mod impact;
pub mod initial;
mod kernel;
mod lane;
pub mod lanes;
mod mass;
mod model;
pub mod params;
mod point_roll;
mod points;
pub mod polyhedron;
mod roll;
mod shape;
mod sim;
mod spin;
pub mod stability;
pub mod stability_contact;
mod state;
mod stopping;

pub use body::{PIP_LAYOUT, contact_sphere_centres, face_frame, pip_centres};
pub use body::{face_most_nearly_up, opposite_face};
pub use energy::Energy;
pub use impact::{Impacts, impact_starts};
pub use initial::{InitialCondition, RandomRanges};
pub use model::{Placement, check_setup, resting_depth_on_face, why_it_cannot_settle};
pub use params::{
    ContactLaw, Die, FrictionLaw, Ground, GroundKey, Integrator, Limits, ParamError, Params, Solid,
    StopEnergy, World,
};
pub use point_roll::{PointOutcome, PointRoll};
pub use points::{BodyError, MAX_FACES, PointBody};
pub use roll::{Roll, RollingDie};
pub use shape::{MassProperties, mass_properties};
pub use sim::{
    ContactForce, EnergyLedger, FirstImpact, Outcome, STEPS_BETWEEN_STOP_CHECKS, Simulation, State, Status,
    refuse_polyhedral_die,
};
pub use stability::{Limit, Reading, Stability, StabilityCheck, UnstableReason};
pub use stopping::StopRule;

/// Rolls one die from `initial` to the end; the parameters must already be valid.
pub fn roll(params: &Params, initial: &InitialCondition) -> Result<(Outcome, Simulation), ParamError> {
    let mut sim = Simulation::new(params, initial)?;
    let outcome = sim.run_to_end();
    Ok((outcome, sim))
}
