//! The die's dynamic state, written over a lane type, and the kinematics every contact law
//! reads off it: where a contact point is and how fast it moves.
//!
//! It sits below the contact laws (contact/) and the step (kernel.rs), which both use it.

use super::lane::{Lane, v3};
use nalgebra::Vector3;

/// The dynamic state of the die at one instant (one per lane in a lane type), a body of `N`
/// contact points (the paper's cube's 8 corners unless said otherwise).
#[derive(Debug, Clone, PartialEq)]
pub struct State<L: Lane = f64, const N: usize = 8> {
    /// cm, centre of mass.
    pub position: Vector3<L>,
    /// cm/s, centre of mass.
    pub velocity: Vector3<L>,
    /// g·cm²/s, about the centre of mass.
    pub angular_momentum: Vector3<L>,
    /// cm, the contact points (corners 1..8 of a cube; a rounded body's sphere centres)
    /// relative to the centre of mass, world frame.
    pub corner_offsets: [Vector3<L>; N],
    /// dyn, the contact force on each point at this state `(friction x, friction y, P)`.
    pub corner_forces: [Vector3<L>; N],
    /// cm, how far each point is below the ground (0 above it).
    pub corner_depths: [L; N],
    /// s, simulated time.
    pub time_s: L,
    /// Steps taken since the initial condition.
    pub step: L::Count,
}

/// Where a corner's contact force acts, relative to the centre of mass: a rounded body's
/// contact sphere's lowest point, the radius below its centre (lanes of a sharp body among
/// rounded ones have radius +0.0, and `z − 0` is `z`). `ROUNDED` is decided once per call of
/// the stage, so a sharp die's step compiles without it.
#[inline(always)]
pub(crate) fn contact_point<const ROUNDED: bool, L: Lane>(r: &Vector3<L>, radius: L) -> Vector3<L> {
    if ROUNDED { v3(r.x, r.y, r.z - radius) } else { *r }
}

/// Velocity of a contact point at offset `r` from the centre of mass, `u = v + ω × r`, cm/s,
/// in the authors' operation order.
#[inline(always)]
pub(crate) fn point_velocity<L: Lane>(v: &Vector3<L>, w: &Vector3<L>, r: &Vector3<L>) -> Vector3<L> {
    v3(
        v.x + (r.z * w.y - r.y * w.z),
        v.y + (r.x * w.z - r.z * w.x),
        v.z + (r.y * w.x - r.x * w.y),
    )
}
