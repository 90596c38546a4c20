//! What a contact law is ([`Law`]) and what it sees of a body ([`Touch`]).

use crate::lane::{Lane, set_bits};
use crate::params::Params;
use crate::state::{State, contact_point, point_velocity};
use crate::stopping::StopRule;
use nalgebra::{Vector2, Vector3};
use std::fmt::Debug;

/// A contact law: the table's force on a body at each contact point, written once over a
/// lane type (one roll on `f64`, several side by side in a vector; bit for bit alike).
pub(crate) trait Law: Copy + Debug + Send + Sync + 'static {
    /// The law's numbers for one roll (per lane), derived once from the parameters.
    type Constants<L: Lane>: Copy + Debug;
    /// What the law remembers at one contact point between steps (per lane).
    type Point<L: Lane>: Copy + Debug + PartialEq;

    /// The law's constants for `p`'s table and a body of `mass` (g) whose edge energy is
    /// `edge_energy` (erg).
    fn constants(p: &Params, mass: f64, edge_energy: f64) -> Self::Constants<f64>;
    /// One roll's constants in every lane.
    fn splat<L: Lane>(c: &Self::Constants<f64>) -> Self::Constants<L>;
    /// One roll's constants into lane `l`.
    fn set_lane<L: Lane>(c: &mut Self::Constants<L>, l: usize, from: &Self::Constants<f64>);
    /// Lane `l` emptied for good: whatever the law adds to a body in flight (a tilted
    /// table's weight along it) set to zero, so the parked lane stays still.
    fn park<L: Lane>(c: &mut Self::Constants<L>, l: usize);

    /// A point's memory off the table.
    fn free_point<L: Lane>() -> Self::Point<L>;
    /// Lane `l` of a point's memory, and setting it.
    fn point_lane<L: Lane>(point: &Self::Point<L>, l: usize) -> Self::Point<f64>;
    fn set_point_lane<L: Lane>(point: &mut Self::Point<L>, l: usize, from: &Self::Point<f64>);
    /// cm, the tangential spring `ξ` a point holds in the table's plane; zero for a law
    /// that keeps none.
    fn tangential_spring(point: &Self::Point<f64>) -> Vector2<f64>;

    /// dyn/cm, the table's normal stiffness `k`, and `½·k` (the elastic energy `½·k·d²`).
    fn stiffness<L: Lane>(c: &Self::Constants<L>) -> L;
    fn half_stiffness<L: Lane>(c: &Self::Constants<L>) -> L;
    /// cm/s², gravity in the table's frame under this law.
    fn gravity(p: &Params) -> [f64; 3];
    /// The kick of a contact step: `v ← v + ((ΣF + W)/M)·Δt` with the body's weight `W`,
    /// whose z part is `weight_z` (dyn).
    fn kick<L: Lane>(
        c: &Self::Constants<L>,
        v: &mut Vector3<L>,
        force: &Vector3<L>,
        weight_z: L,
        mass: L,
        dt: L,
    );
    /// erg, the weight's potential at `position`, given its normal part `normal`.
    fn potential<L: Lane>(c: &Self::Constants<L>, normal: L, position: &Vector3<L>) -> L;
    /// Every contact point's depth, force and memory at the current state (`rounded`: the
    /// points are spheres, each of its own radius in [`Touch::radii`], touching at their
    /// lowest points).
    fn forces<L: Lane, const N: usize>(
        c: &Self::Constants<L>,
        dt: L,
        rounded: bool,
        touch: Touch<'_, L, Self::Point<L>, N>,
    );
    /// The lanes of `settled` the law lets settle at this kinetic energy (erg).
    fn settles<L: Lane>(c: &Self::Constants<L>, settled: L::Mask, kinetic: L) -> L::Mask;
    /// The stopping rule `rule` of a level table, for a body of edge energy `edge_energy`,
    /// as this law's table has it.
    fn stop_rule(rule: StopRule, p: &Params, edge_energy: f64) -> StopRule;
}

/// A body's contact points at one state, as a law reads them and writes its results: the
/// state's offsets, velocity, depths and forces, the body's angular velocity, the law's
/// memory at each point, and which points touch.
pub(crate) struct Touch<'a, L: Lane, P, const N: usize> {
    pub(crate) state: &'a mut State<L, N>,
    /// rad/s, the body's angular velocity.
    pub(crate) angular_velocity: &'a Vector3<L>,
    pub(crate) points: &'a mut [P; N],
    /// Lanes with a point below the table (the law sets it).
    pub(crate) in_contact: &'a mut L::Mask,
    /// Bit k: point k is below the table in some lane (the law sets it).
    pub(crate) touching_corners: &'a mut u64,
    /// cm, each point's sphere radius: its lowest point is this far below its centre.
    pub(crate) radii: &'a [L; N],
}

impl<L: Lane, P, const N: usize> Touch<'_, L, P, N> {
    /// cm/s, the velocity of point `k`'s contact (a rounded body's: its sphere's lowest
    /// point).
    #[inline(always)]
    pub(crate) fn velocity_at<const ROUNDED: bool>(&self, k: usize) -> Vector3<L> {
        let r = contact_point::<ROUNDED, L>(&self.state.corner_offsets[k], self.radii[k]);
        point_velocity(&self.state.velocity, self.angular_velocity, &r)
    }

    /// Which points (or point spheres, `ROUNDED`) are in the table, per lane, and their
    /// depths into it, cm: the same for every law. Returns the masks and their union.
    #[inline(always)]
    pub(crate) fn press<const ROUNDED: bool>(&mut self) -> ([L::Mask; N], L::Mask) {
        let s = &mut *self.state;
        let z0 = s.position.z;
        let zero = L::zero();
        let mut touching = [L::mask_from_bits(0); N];
        let mut any = L::mask_from_bits(0);
        for (k, t) in touching.iter_mut().enumerate() {
            let z = s.corner_offsets[k].z + z0;
            let z = if ROUNDED { z - self.radii[k] } else { z };
            *t = z.lt(zero);
            s.corner_depths[k] = (-z).or_zero(*t);
            any = any | *t;
        }
        (touching, any)
    }
}

/// The points touching in some lane, as bits.
#[inline(always)]
pub(crate) fn touching_bits<L: Lane, const N: usize>(touching: &[L::Mask; N]) -> u64 {
    let mut bits = 0u64;
    for (k, t) in touching.iter().enumerate() {
        if L::bits(*t) != 0 {
            bits |= 1 << k;
        }
    }
    bits
}

/// The points of `N` in `bits`, in point order. The bits are masked to the `N` points first,
/// so the compiler knows every index is below `N` and checks none.
#[inline(always)]
pub(crate) fn corners<const N: usize>(bits: u64) -> impl Iterator<Item = usize> {
    let every = if N >= 64 { u64::MAX } else { (1 << N) - 1 };
    set_bits(bits & every)
}
