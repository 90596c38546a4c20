//! The physics crate's integration tests, one binary built from the physics and its
//! dev-dependencies alone: agreement with the authors' program, the two engines bit for
//! bit, loaded dice, and the derived checks of docs/model.md.

mod common;
mod compliant_table;
mod contact_law;
mod derived_checks;
mod dice;
mod face_restitution;
mod free_rotation;
mod lanes;
mod loaded_dice;
mod point_bodies;
mod reference;
mod stability_bodies;
