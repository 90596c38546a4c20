//! The contact laws: what the table does to a body at each of its contact points
//! (docs/model.md, "Contact laws").
//!
//! Each law is a type in a file of its own — the paper's (paper.rs) and the spring-friction
//! law (spring_friction.rs) — implementing [`Law`]: its constants, derived once per roll from
//! the parameters; its memory at each contact point (the tangential spring's `ξ`, or
//! nothing); and its force at a point. The step (kernel.rs), the scalar engine (sim.rs) and
//! the lane engine (lanes.rs) are generic over the law, so each law's step is compiled on its
//! own and a lane vector holds rolls of one law only.
//!
//! A law sees the body only through [`Touch`]: its contact points' offsets and the motion of
//! the body, and the forces, depths and point memories it writes. It knows nothing of the
//! body's kind, its rotation or the stopping rule, which are the kernel's.

mod law;
pub(crate) mod paper;
pub(crate) mod spring_friction;

pub(crate) use law::{Law, Touch, corners};
pub(crate) use paper::{Paper, PerCornerSlip, WholeDieSlip};
pub(crate) use spring_friction::SpringFriction;
pub use spring_friction::{
    clamped_restitution, damping_ratio, downhill_pass_share, gravity_in_table_frame, why_a_tilt_cannot_hold,
};
