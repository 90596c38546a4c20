//! The lane type the kernel is written over: `f64` for one roll, or a vector of several
//! rolls side by side (the 4-lane AVX2 vector in lanes.rs).
//!
//! It stands alone, below everything written over it (the step in kernel.rs, a loaded
//! die's inertia tensor in mass.rs, the stopping test in stopping.rs), so that those can
//! use it without importing each other.

use nalgebra::{Scalar, Vector3};
use std::fmt::Debug;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// The indices of the set bits of `bits`, lowest first: the corners (or lanes) a loop visits,
/// in corner (lane) order.
///
/// Each turn costs one branch, the loop's exit, where testing each of the eight corners costs
/// eight whose outcome changes as corners touch and leave the ground: the scalar engine
/// mispredicted about 1.2 more branches per step that way than the program before the shared
/// kernel, which summed all eight corners.
#[inline(always)]
pub(crate) fn set_bits(bits: impl Into<u64>) -> impl Iterator<Item = usize> {
    let bits: u64 = bits.into();
    let mut rest = bits;
    std::iter::from_fn(move || {
        (rest != 0).then(|| {
            let i = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            i
        })
    })
}

/// A floating-point lane type: `f64` (one roll) or a vector of several rolls. Every
/// arithmetic operation acts on each lane alone and rounds exactly as the `f64` one does.
pub trait Lane:
    Scalar
    + Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Per-lane truth values.
    type Mask: Copy
        + Debug
        + BitAnd<Output = Self::Mask>
        + BitOr<Output = Self::Mask>
        + Not<Output = Self::Mask>;
    /// Steps taken, per lane.
    type Count: Copy + Debug + PartialEq;
    /// One `T` per lane.
    type PerLane<T: Copy>: Copy + AsRef<[T]> + AsMut<[T]>;
    /// The number of lanes.
    const WIDTH: usize;

    fn splat(x: f64) -> Self;
    fn sqrt(self) -> Self;
    /// Clears the sign bit, as `f64::abs`.
    fn abs(self) -> Self;
    /// `<`, `<=`, `>`, `!=` per lane (false with a NaN, except `!=`).
    fn lt(self, other: Self) -> Self::Mask;
    fn le(self, other: Self) -> Self::Mask;
    fn gt(self, other: Self) -> Self::Mask;
    fn ne(self, other: Self) -> Self::Mask;
    /// Neither infinite nor NaN.
    fn finite(self) -> Self::Mask;
    /// Whether the position, the velocity and every corner offset are finite, per lane: the
    /// end-of-step test asks it of these 30 values every step, so each width answers it its
    /// fastest exact way.
    fn all_finite(
        position: &Vector3<Self>,
        velocity: &Vector3<Self>,
        offsets: &[Vector3<Self>],
    ) -> Self::Mask;
    /// `if mask { yes } else { no }` per lane.
    fn select(mask: Self::Mask, yes: Self, no: Self) -> Self;
    /// `if mask { self } else { +0.0 }` per lane.
    fn or_zero(self, mask: Self::Mask) -> Self;
    /// Bit `l` set where lane `l` of `mask` is.
    fn bits(mask: Self::Mask) -> u32;
    fn mask_from_bits(bits: u32) -> Self::Mask;
    fn to_lanes(self) -> Self::PerLane<f64>;
    fn from_lanes(lanes: Self::PerLane<f64>) -> Self;
    /// The lanes of a value held in memory, to write single lanes in place (no copy of the
    /// value out and back in).
    fn lanes_mut(&mut self) -> &mut Self::PerLane<f64>;
    fn per_lane<T: Copy>(f: impl FnMut(usize) -> T) -> Self::PerLane<T>;
    fn count_up(count: Self::Count) -> Self::Count;
    /// `n` steps in every lane, and in lane `l` alone.
    fn count_of(n: u64) -> Self::Count;
    fn put_count(count: &mut Self::Count, l: usize, n: u64);
    /// Lane `l` of a count.
    fn count_lane(count: Self::Count, l: usize) -> u64;
    fn count_reached(count: Self::Count, limit: Self::Count) -> Self::Mask;

    #[inline(always)]
    fn zero() -> Self {
        Self::splat(0.0)
    }
    #[inline(always)]
    fn lane(self, l: usize) -> f64 {
        self.to_lanes().as_ref()[l]
    }
}

impl Lane for f64 {
    type Mask = bool;
    type Count = u64;
    type PerLane<T: Copy> = [T; 1];
    const WIDTH: usize = 1;

    #[inline(always)]
    fn splat(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline(always)]
    fn lt(self, other: f64) -> bool {
        self < other
    }
    #[inline(always)]
    fn le(self, other: f64) -> bool {
        self <= other
    }
    #[inline(always)]
    fn gt(self, other: f64) -> bool {
        self > other
    }
    #[inline(always)]
    fn ne(self, other: f64) -> bool {
        self != other
    }
    #[inline(always)]
    fn finite(self) -> bool {
        self.is_finite()
    }
    /// A value is not finite exactly when its 11 exponent bits are all set; adding one at
    /// the exponent's lowest bit then carries into the sign bit. OR-ing that over the values
    /// needs no branch per value, and integer ORs may be regrouped, so the compiler
    /// vectorises it.
    #[inline(always)]
    fn all_finite(position: &Vector3<f64>, velocity: &Vector3<f64>, offsets: &[Vector3<f64>]) -> bool {
        const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
        const EXPONENT_ONE: u64 = 1 << 52;
        let flags = |v: &Vector3<f64>| {
            let flag = |x: f64| (x.to_bits() & EXPONENT) + EXPONENT_ONE;
            flag(v.x) | flag(v.y) | flag(v.z)
        };
        let mut any = flags(position) | flags(velocity);
        for r in offsets {
            any |= flags(r);
        }
        any >> 63 == 0
    }
    #[inline(always)]
    fn select(mask: bool, yes: f64, no: f64) -> f64 {
        if mask { yes } else { no }
    }
    #[inline(always)]
    fn or_zero(self, mask: bool) -> f64 {
        if mask { self } else { 0.0 }
    }
    #[inline(always)]
    fn bits(mask: bool) -> u32 {
        mask as u32
    }
    #[inline(always)]
    fn mask_from_bits(bits: u32) -> bool {
        bits & 1 != 0
    }
    #[inline(always)]
    fn to_lanes(self) -> [f64; 1] {
        [self]
    }
    #[inline(always)]
    fn from_lanes(lanes: [f64; 1]) -> f64 {
        lanes[0]
    }
    #[inline(always)]
    fn lanes_mut(&mut self) -> &mut [f64; 1] {
        std::array::from_mut(self)
    }
    #[inline(always)]
    fn per_lane<T: Copy>(mut f: impl FnMut(usize) -> T) -> [T; 1] {
        [f(0)]
    }
    #[inline(always)]
    fn count_up(count: u64) -> u64 {
        count + 1
    }
    fn count_of(n: u64) -> u64 {
        n
    }
    fn put_count(count: &mut u64, _: usize, n: u64) {
        *count = n;
    }
    fn count_lane(count: u64, _: usize) -> u64 {
        count
    }
    #[inline(always)]
    fn count_reached(count: u64, limit: u64) -> bool {
        count >= limit
    }
}

// Vectors of lanes, operation for operation as nalgebra computes them on `f64`.

/// The bits of every lane.
#[inline(always)]
pub(crate) fn all_lanes<L: Lane>() -> u32 {
    (1 << L::WIDTH) - 1
}

#[inline(always)]
pub(crate) fn v3<L: Lane>(x: L, y: L, z: L) -> Vector3<L> {
    Vector3::new(x, y, z)
}

#[inline(always)]
pub(crate) fn zero3<L: Lane>() -> Vector3<L> {
    v3(L::zero(), L::zero(), L::zero())
}

#[inline(always)]
pub(crate) fn add3<L: Lane>(a: &Vector3<L>, b: &Vector3<L>) -> Vector3<L> {
    v3(a.x + b.x, a.y + b.y, a.z + b.z)
}

#[inline(always)]
pub(crate) fn scale3<L: Lane>(a: &Vector3<L>, s: L) -> Vector3<L> {
    v3(a.x * s, a.y * s, a.z * s)
}

/// nalgebra's cross product, operation for operation.
#[inline(always)]
pub(crate) fn cross3<L: Lane>(a: &Vector3<L>, b: &Vector3<L>) -> Vector3<L> {
    v3(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

#[inline(always)]
pub(crate) fn select3<L: Lane>(mask: L::Mask, yes: &Vector3<L>, no: &Vector3<L>) -> Vector3<L> {
    v3(
        L::select(mask, yes.x, no.x),
        L::select(mask, yes.y, no.y),
        L::select(mask, yes.z, no.z),
    )
}

/// Lane `l` of a vector of lanes.
#[inline(always)]
pub(crate) fn lane3<L: Lane>(v: &Vector3<L>, l: usize) -> Vector3<f64> {
    Vector3::new(v.x.lane(l), v.y.lane(l), v.z.lane(l))
}

/// Sets lane `l` of `x` to `value`.
#[inline(always)]
pub(crate) fn put<L: Lane>(x: &mut L, l: usize, value: f64) {
    x.lanes_mut().as_mut()[l] = value;
}

/// Sets lane `l` of `mask` to `on`.
#[inline(always)]
pub(crate) fn put_mask<L: Lane>(mask: &mut L::Mask, l: usize, on: bool) {
    *mask = L::mask_from_bits((L::bits(*mask) & !(1 << l)) | ((on as u32) << l));
}

/// A mask of every lane or none.
#[inline(always)]
pub(crate) fn mask_of<L: Lane>(on: bool) -> L::Mask {
    L::mask_from_bits(if on { all_lanes::<L>() } else { 0 })
}
