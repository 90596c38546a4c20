//! Dice of any convex shape (docs/model.md, "Dice of any convex shape"; docs/dice.md): their
//! hull, the exact mass of the uniform solid, their numbers and how they are read, how firmly
//! they rest, and the flaws that make a real die unfair. Pure: nalgebra and serde.
//!
//! The files, each using only those before it: `hull` (the polyhedron of a list of vertices),
//! `moments` (its volume, centre and inertia), `numbering` (the numbers on its faces),
//! `flaws` (a bubble, a point mass, a shave, rounding), `die` (the [`Die`] a body is made
//! from), `stability` (tipping barrier and resting depth), `solids` (the d4 to the d20 and
//! prisms), `rolled` (a die as the [`PointBody`](crate::PointBody) the step rolls, with
//! its stopping rule) and `keys` (the die a preset's `[die]` keys describe, flaws and all,
//! each impossible one refused by its key).

mod die;
mod flaws;
mod hull;
mod keys;
mod moments;
mod numbering;
mod rolled;
mod solids;
mod stability;

pub use die::{ContactPoint, Die, Reading};
pub use flaws::{Bubble, FlawError, Flaws, PointMass, Shave};
pub use hull::{Edge, Face, HullError, MAX_VERTICES, Polyhedron, convex_hull, face_order};
pub(crate) use keys::made_die;
pub use keys::{BODY_POINTS, body_points};
pub use moments::{SolidMoments, solid_moments};
pub use numbering::{Numbering, ReadAt, opposite_faces};
pub use solids::{DieKind, RESIN_DENSITY, STANDARD_HEIGHT, prism};
pub use stability::{RestDepth, Tipping};
