//! The lane engine: four rolls stepped side by side in the 4 lanes of 256-bit AVX2 vectors,
//! each lane bit-identical to [`Simulation`] rolling alone.
//!
//! The step is the one kernel (kernel.rs) both engines run: here on a vector type
//! whose lane `l` holds roll `l` (a structure of arrays, one vector per coordinate), every
//! operation the exactly rounded twin of the scalar one. Each roll is set up by its own
//! [`Simulation`], loaded into a lane, and stored back into it when the kernel's end-of-step
//! test ends it; a lane whose roll ended takes the next roll at once. Every die the scalar
//! engine rolls, the lanes roll (a loaded die too), with the same results bit for bit.
//!
//! The one module that uses `unsafe`: the AVX2 intrinsics are `unsafe` to call, and each
//! call is reached only through `roll_in_lanes`, after `is_x86_feature_detected!` said the
//! CPU has AVX2 (the loads and stores are of arrays of exactly four lanes).
#![allow(unsafe_code)]

use super::body::face_most_nearly_up;
use super::contact::{Law, SpringFriction};
use super::initial::InitialCondition;
use super::kernel::{Faces, Kernel};
use super::model::Placement;
use super::params::{ParamError, Params, Solid};
use super::point_roll::{PointKernel, PointLaw, PointRoll};
use super::points::PointBody;
use super::polyhedron::body_points;
use super::sim::{EngineLaw, ImpactLog, Outcome, STEPS_BETWEEN_STOP_CHECKS, Simulation, State, Status};
use super::sim::{PaperPerCorner, PaperWholeDie, box_face_down};
use nalgebra::Vector3;

/// Whether this CPU can run the lane engine (x86-64 with AVX2).
pub fn lanes_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// A finished roll as the lane engine hands it out.
#[derive(Debug, Clone, Copy)]
pub struct LaneResult<'a> {
    /// The index the roll had in the `setup` sequence.
    pub index: usize,
    pub outcome: Outcome,
    /// The face most nearly up at t = 0 (a polyhedral die's: the number read were it to rest
    /// as it starts).
    pub start_face: u8,
    /// The state at the end, as [`Simulation::state`] (or [`PointRoll::state`] for a
    /// polyhedral die) has it after the same roll.
    pub state: EndState<'a>,
}

/// A roll's state at its end, whatever its body: the box's 8 corners or a polyhedral die's
/// `N` vertices (the fields of [`State`], its points as slices).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndState<'a> {
    /// cm, centre of mass.
    pub position: Vector3<f64>,
    /// cm/s, centre of mass.
    pub velocity: Vector3<f64>,
    /// g·cm²/s, about the centre of mass.
    pub angular_momentum: Vector3<f64>,
    /// cm, each contact point from the centre of mass, world frame.
    pub corner_offsets: &'a [Vector3<f64>],
    /// dyn, the contact force on each point.
    pub corner_forces: &'a [Vector3<f64>],
    /// cm, how far each point is below the ground.
    pub corner_depths: &'a [f64],
    /// s, simulated time.
    pub time_s: f64,
    /// Steps taken.
    pub step: u64,
}

impl<'a, const N: usize> From<&'a State<f64, N>> for EndState<'a> {
    fn from(s: &'a State<f64, N>) -> EndState<'a> {
        EndState {
            position: s.position,
            velocity: s.velocity,
            angular_momentum: s.angular_momentum,
            corner_offsets: &s.corner_offsets,
            corner_forces: &s.corner_forces,
            corner_depths: &s.corner_depths,
            time_s: s.time_s,
            step: s.step,
        }
    }
}

/// A roll either engine steps in a lane of its law `W`: the box's [`Simulation`] or a
/// polyhedral die's [`PointRoll`], each of `N` points, the body `B` per lane.
pub(crate) trait LaneRoll<W: Law, const N: usize>: Sized {
    type Body: Faces<N>;
    fn kernel(&self) -> &Kernel<f64, W, N, Self::Body>;
    fn kernel_mut(&mut self) -> &mut Kernel<f64, W, N, Self::Body>;
    fn impact_log_mut(&mut self) -> &mut ImpactLog;
    /// The face the record's start face is, at t = 0.
    fn start_face(&self) -> u8;
    /// The first impact's face down of `body` with its points at `offsets`.
    fn face_down(body: &Self::Body, offsets: &[Vector3<f64>; N]) -> u8;
    /// Ends the roll as `status` at the state stored back into it.
    fn finish(&mut self, status: Status) -> Outcome;
    fn end_state(&self) -> EndState<'_>;
}

impl<W: EngineLaw> LaneRoll<W, 8> for Simulation {
    type Body = super::model::Body;
    #[inline(always)]
    fn kernel(&self) -> &Kernel<f64, W> {
        W::of(&self.k).expect("a roll of this vector's law")
    }
    #[inline(always)]
    fn kernel_mut(&mut self) -> &mut Kernel<f64, W> {
        W::of_mut(&mut self.k).expect("a roll of this vector's law")
    }
    fn impact_log_mut(&mut self) -> &mut ImpactLog {
        &mut self.impact_log
    }
    fn start_face(&self) -> u8 {
        face_most_nearly_up(&self.state().corner_offsets)
    }
    fn face_down(_: &Self::Body, offsets: &[Vector3<f64>; 8]) -> u8 {
        box_face_down(offsets)
    }
    fn finish(&mut self, status: Status) -> Outcome {
        Simulation::finish(self, status)
    }
    fn end_state(&self) -> EndState<'_> {
        self.state().into()
    }
}

impl<W: PointLaw, const N: usize> LaneRoll<W, N> for PointRoll<N> {
    type Body = PointBody<N>;
    #[inline(always)]
    fn kernel(&self) -> &Kernel<f64, W, N, PointBody<N>> {
        W::of(&self.k).expect("a roll of this vector's law")
    }
    #[inline(always)]
    fn kernel_mut(&mut self) -> &mut Kernel<f64, W, N, PointBody<N>> {
        W::of_mut(&mut self.k).expect("a roll of this vector's law")
    }
    fn impact_log_mut(&mut self) -> &mut ImpactLog {
        &mut self.impact_log
    }
    fn start_face(&self) -> u8 {
        PointRoll::start_face(self)
    }
    fn face_down(body: &PointBody<N>, offsets: &[Vector3<f64>; N]) -> u8 {
        body.face_down(offsets)
    }
    fn finish(&mut self, status: Status) -> Outcome {
        PointRoll::finish(self, status);
        self.full_outcome().expect("just ended")
    }
    fn end_state(&self) -> EndState<'_> {
        self.state().into()
    }
}

/// A polyhedral die's roll, of as many points as its solid has vertices (the d4 4, the d8
/// 6, the d10, d% and d20 12, the d12 20).
// Each roll is set up once and moved into its lane's vector, which holds it by value as it
// holds a `Simulation`; a box would put it behind a pointer for no gain.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
pub(crate) enum DiceRoll {
    P4(PointRoll<4>),
    P6(PointRoll<6>),
    P12(PointRoll<12>),
    P20(PointRoll<20>),
}

/// `$body` with `$r` bound to the [`PointRoll`] in a [`DiceRoll`], whatever its points.
macro_rules! on_points {
    ($roll:expr, $r:ident => $body:expr) => {
        match $roll {
            DiceRoll::P4($r) => $body,
            DiceRoll::P6($r) => $body,
            DiceRoll::P12($r) => $body,
            DiceRoll::P20($r) => $body,
        }
    };
}
pub(crate) use on_points;

/// A polyhedral die's bodies, kept while a run's setups repeat their parameters: the hull,
/// mass and stopping rule are made once, not per roll.
#[derive(Default)]
pub(crate) struct DiceBodies {
    last: Option<(Params, DiceBody)>,
}

/// One run keeps one of these and copies it into each roll, which holds its body by value as
/// a `PointRoll` does: sized by the largest die, with no pointer to follow per roll. A die
/// of a vertex count between these is carried by the next one up (padded,
/// [`Die::point_body`](crate::polyhedron::Die::point_body)): its last points sit at its
/// centre of mass.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy)]
pub(crate) enum DiceBody {
    P4(PointBody<4>),
    P6(PointBody<6>),
    P12(PointBody<12>),
    P20(PointBody<20>),
}

impl DiceBodies {
    /// The roll of `params`' polyhedral die from `initial`, not checked (as
    /// [`Simulation::for_outcome`] is not).
    pub(crate) fn roll(&mut self, params: &Params, initial: &InitialCondition) -> DiceRoll {
        let body = match &self.last {
            Some((p, body)) if p == params => *body,
            _ => {
                let body = dice_body(params);
                self.last = Some((*params, body));
                body
            }
        };
        body.roll(params, initial)
    }
}

impl DiceBody {
    /// This body's roll on `params`' table from `initial`, not checked.
    pub(crate) fn roll(self, params: &Params, initial: &InitialCondition) -> DiceRoll {
        match self {
            DiceBody::P4(b) => DiceRoll::P4(PointRoll::new_unchecked(params, &b, initial)),
            DiceBody::P6(b) => DiceRoll::P6(PointRoll::new_unchecked(params, &b, initial)),
            DiceBody::P12(b) => DiceRoll::P12(PointRoll::new_unchecked(params, &b, initial)),
            DiceBody::P20(b) => DiceRoll::P20(PointRoll::new_unchecked(params, &b, initial)),
        }
    }
}

/// The body of `params`' polyhedral die (validated): as many points as it has vertices, or
/// the next count the engines carry ([`body_points`]), the rest at its centre of mass.
// Padding rather than a body per vertex count: each count is its kernels for three laws in
// two engines over again, and the points that never touch cost only their share of the
// step's loops over points.
pub(crate) fn dice_body(params: &Params) -> DiceBody {
    let die = params.polyhedral_die().expect("a polyhedral die");
    let made = "a validated die makes its body";
    let vertices = die.shape().vertices().len();
    match body_points(vertices) {
        Some(4) => DiceBody::P4(die.point_body(params).expect(made)),
        Some(6) => DiceBody::P6(die.point_body(params).expect(made)),
        Some(12) => DiceBody::P12(die.point_body(params).expect(made)),
        Some(20) => DiceBody::P20(die.point_body(params).expect(made)),
        _ => unreachable!("the validation refuses a die of {vertices} vertices"),
    }
}

/// Rolls setups `0..count` (from `setup(i)`) to their ends, four at a time, and hands each
/// finished roll to `done`, in the order they finish. `stop()` is asked every
/// [`STEPS_BETWEEN_STOP_CHECKS`] steps; when it answers true the rolls still running are
/// dropped and `false` is returned (`true`: every roll finished).
///
/// The box rolls as [`Simulation`] rolls it, a polyhedral die (`die.kind`) as
/// [`PointRoll`] does, each in vectors of its own body and law. Falls back to
/// [`roll_one_by_one`] where AVX2 is missing, with the same results.
pub fn roll_in_lanes(
    count: usize,
    setup: &mut dyn FnMut(usize) -> (Params, InitialCondition),
    done: &mut dyn FnMut(LaneResult<'_>),
    stop: &dyn Fn() -> bool,
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if lanes_available() {
        // SAFETY: AVX2 is present, checked just above.
        return unsafe { avx2::roll_all(count, setup, done, stop) };
    }
    roll_one_by_one(count, setup, done, stop)
}

/// The face most nearly up at t = 0 of `params`' die placed at `initial`, the box or a
/// polyhedral one: the start face a roll's record carries.
pub fn start_face(params: &Params, initial: &InitialCondition) -> u8 {
    if params.die.is_polyhedral() {
        on_points!(DiceBodies::default().roll(params, initial), r => r.start_face())
    } else {
        face_most_nearly_up(&Placement::new(params).start_offsets(initial))
    }
}

/// The scalar engine behind the same interface: the box by [`Simulation`], a polyhedral die
/// by [`PointRoll`].
pub fn roll_one_by_one(
    count: usize,
    setup: &mut dyn FnMut(usize) -> (Params, InitialCondition),
    done: &mut dyn FnMut(LaneResult<'_>),
    stop: &dyn Fn() -> bool,
) -> bool {
    let mut dice = DiceBodies::default();
    for index in 0..count {
        let (params, initial) = setup(index);
        if params.die.is_polyhedral() {
            let mut roll = dice.roll(&params, &initial);
            let finished = on_points!(&mut roll, r => r.run_until_stopped(stop).map(|outcome| {
                done(LaneResult {
                    index,
                    outcome,
                    start_face: r.start_face(),
                    state: r.state().into(),
                })
            }));
            if finished.is_none() {
                return false;
            }
            continue;
        }
        let mut sim = Simulation::for_outcome(&params, &initial);
        let start_face = face_most_nearly_up(&sim.state().corner_offsets);
        match sim.run_until_stopped(stop) {
            Some(outcome) => done(LaneResult {
                index,
                outcome,
                start_face,
                state: sim.state().into(),
            }),
            None => return false,
        }
    }
    true
}

/// One roll of `params`' die, the box or a polyhedral one, from `initial` to its end by the
/// scalar engine ([`roll_one_by_one`]): its outcome and start face, or `None` once `stop()`
/// answered true. What rolls one record of any die.
pub fn roll_one(
    params: &Params,
    initial: &InitialCondition,
    stop: &dyn Fn() -> bool,
) -> Option<(Outcome, u8)> {
    let mut rolled = None;
    roll_one_by_one(
        1,
        &mut |_| (*params, *initial),
        &mut |r| rolled = Some((r.outcome, r.start_face)),
        stop,
    );
    rolled
}

/// Rolls `body` from each of `initials` on `params`' table (both validated) to its end,
/// four at a time in the lanes where the CPU has AVX2 (else one after another), and returns
/// the finished rolls in the order of `initials`: bit for bit those [`PointRoll`] rolls
/// alone.
pub fn roll_points_in_lanes<const N: usize>(
    params: &Params,
    body: &PointBody<N>,
    initials: &[InitialCondition],
) -> Result<Vec<PointRoll<N>>, ParamError> {
    let mut rolls = Vec::with_capacity(initials.len());
    for initial in initials {
        rolls.push(PointRoll::new(params, body, initial)?);
    }
    #[cfg(target_arch = "x86_64")]
    if lanes_available() && !rolls.is_empty() {
        // SAFETY: AVX2 is present, checked just above.
        return Ok(unsafe {
            match &rolls[0].k {
                PointKernel::Paper(_) => avx2::roll_points::<PaperPerCorner, N>(rolls),
                PointKernel::PaperWholeDie(_) => avx2::roll_points::<PaperWholeDie, N>(rolls),
                PointKernel::SpringFriction(_) => avx2::roll_points::<SpringFriction, N>(rolls),
            }
        });
    }
    for roll in &mut rolls {
        roll.run_to_end();
    }
    Ok(rolls)
}

/// Which vector a polyhedral die's roll steps in: its law, its solid and its points (a
/// shave or a convex die's corners change the points of one solid).
type DiceVector = (u8, Solid, usize);

/// The [`DiceVector`] of `roll`.
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
fn dice_vector(roll: &DiceRoll, params: &Params) -> DiceVector {
    let (law, points) = on_points!(roll, r => (match &r.k {
        PointKernel::Paper(_) => 0,
        PointKernel::PaperWholeDie(_) => 1,
        PointKernel::SpringFriction(_) => 2,
    }, points_of(r)));
    (law, params.die.kind, points)
}

/// The points `N` of a roll's body.
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
fn points_of<const N: usize>(_: &PointRoll<N>) -> usize {
    N
}

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use super::*;
    use crate::kernel::{Ends, NoHook};
    use crate::lane::{Lane, lane3};
    use crate::sim::Laws;
    use std::arch::x86_64::*;
    use std::collections::VecDeque;
    use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

    const LANES: usize = 4;

    /// Four f64 in one AVX register (or four lane masks: all bits set = true).
    #[derive(Clone, Copy)]
    #[repr(transparent)]
    pub(super) struct F4(__m256d);

    // The wrappers are always inlined into `roll_all`, which enables AVX2, so each becomes the
    // one instruction it names.
    macro_rules! binary {
        ($trait:ident, $method:ident, $intrinsic:ident) => {
            impl $trait for F4 {
                type Output = F4;
                #[inline(always)]
                fn $method(self, other: F4) -> F4 {
                    // SAFETY: only reached from `roll_all`, which runs with AVX2 present.
                    F4(unsafe { $intrinsic(self.0, other.0) })
                }
            }
        };
    }
    binary!(Add, add, _mm256_add_pd);
    binary!(Sub, sub, _mm256_sub_pd);
    binary!(Mul, mul, _mm256_mul_pd);
    binary!(Div, div, _mm256_div_pd);
    binary!(BitAnd, bitand, _mm256_and_pd);
    binary!(BitOr, bitor, _mm256_or_pd);

    impl Neg for F4 {
        type Output = F4;
        /// Flips the sign bit, as scalar `-x` does (not `0 − x`).
        #[inline(always)]
        fn neg(self) -> F4 {
            F4::splat(-0.0).xor(self)
        }
    }

    impl Not for F4 {
        type Output = F4;
        #[inline(always)]
        fn not(self) -> F4 {
            self.xor(F4::from_bits(0b1111))
        }
    }

    // nalgebra's vectors hold any `Debug + PartialEq` scalar; both look at the bits.
    impl std::fmt::Debug for F4 {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            self.to_lanes().fmt(f)
        }
    }

    impl PartialEq for F4 {
        fn eq(&self, other: &F4) -> bool {
            self.to_lanes().map(f64::to_bits) == other.to_lanes().map(f64::to_bits)
        }
    }

    impl F4 {
        #[inline(always)]
        fn xor(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_xor_pd(self.0, other.0) })
        }
        /// `self >= other` (false with a NaN).
        #[inline(always)]
        fn ge(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_GE_OQ>(self.0, other.0) })
        }
        /// The mask whose lane `l` is set where bit `l` of `bits` is, from a table (no
        /// stores to reload).
        #[inline(always)]
        fn from_bits(bits: u32) -> F4 {
            static MASKS: [[u64; 4]; 16] = {
                let mut t = [[0; 4]; 16];
                let mut b = 0;
                while b < 16 {
                    let mut l = 0;
                    while l < 4 {
                        if b & (1 << l) != 0 {
                            t[b][l] = u64::MAX;
                        }
                        l += 1;
                    }
                    b += 1;
                }
                t
            };
            // SAFETY: as above; the table row is 4 u64, read unaligned.
            F4(unsafe { _mm256_loadu_pd(MASKS[bits as usize & 15].as_ptr().cast()) })
        }
        #[inline(always)]
        fn set_lane(&mut self, l: usize, x: f64) {
            let mut a = self.to_lanes();
            a[l] = x;
            *self = F4::from_lanes(a);
        }
    }

    impl Lane for F4 {
        type Mask = F4;
        /// Steps taken, as exact whole numbers.
        type Count = F4;
        type PerLane<T: Copy> = [T; LANES];
        const WIDTH: usize = LANES;

        #[inline(always)]
        fn splat(x: f64) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_set1_pd(x) })
        }
        #[inline(always)]
        fn zero() -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_setzero_pd() })
        }
        #[inline(always)]
        fn sqrt(self) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_sqrt_pd(self.0) })
        }
        /// |x|, clearing the sign bit as `f64::abs` does.
        #[inline(always)]
        fn abs(self) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0) })
        }
        #[inline(always)]
        fn lt(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_LT_OQ>(self.0, other.0) })
        }
        #[inline(always)]
        fn le(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_LE_OQ>(self.0, other.0) })
        }
        #[inline(always)]
        fn gt(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_GT_OQ>(self.0, other.0) })
        }
        /// True with a NaN, as `!=`.
        #[inline(always)]
        fn ne(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_NEQ_UQ>(self.0, other.0) })
        }
        /// |x| < ∞ is false for ±∞ and NaN.
        #[inline(always)]
        fn finite(self) -> F4 {
            self.abs().lt(F4::splat(f64::INFINITY))
        }
        /// A sum of finite values can overflow to ±∞, and a NaN or ∞ term always makes the
        /// sum non-finite; so the sum screens, and only a lane it flags is looked at value by
        /// value (vector adds in independent groups are cheaper here than the scalar
        /// engine's integer trick).
        #[inline(always)]
        fn all_finite(p: &Vector3<F4>, v: &Vector3<F4>, offsets: &[Vector3<F4>]) -> F4 {
            let mut sum = (p.x + p.y) + (p.z + v.x) + (v.y + v.z);
            for r in offsets {
                sum = sum + (r.x + r.y) + r.z;
            }
            let screen = sum.finite();
            if F4::bits(screen) == 0b1111 {
                return screen;
            }
            let finite3 = |r: &Vector3<F4>| r.x.finite() & r.y.finite() & r.z.finite();
            offsets
                .iter()
                .fold(finite3(p) & finite3(v), |all, r| all & finite3(r))
        }
        #[inline(always)]
        fn select(mask: F4, yes: F4, no: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_blendv_pd(no.0, yes.0, mask.0) })
        }
        #[inline(always)]
        fn or_zero(self, mask: F4) -> F4 {
            self & mask
        }
        #[inline(always)]
        fn bits(mask: F4) -> u32 {
            // SAFETY: as above.
            unsafe { _mm256_movemask_pd(mask.0) as u32 }
        }
        #[inline(always)]
        fn mask_from_bits(bits: u32) -> F4 {
            F4::from_bits(bits)
        }
        #[inline(always)]
        fn to_lanes(self) -> [f64; LANES] {
            // SAFETY: `__m256d` is four f64 in lane order, with no invalid bit patterns.
            unsafe { std::mem::transmute::<__m256d, [f64; LANES]>(self.0) }
        }
        #[inline(always)]
        fn from_lanes(lanes: [f64; LANES]) -> F4 {
            // SAFETY: as in `to_lanes`.
            F4(unsafe { std::mem::transmute::<[f64; LANES], __m256d>(lanes) })
        }
        #[inline(always)]
        fn lanes_mut(&mut self) -> &mut [f64; LANES] {
            // SAFETY: `F4` is `repr(transparent)` over `__m256d`, four f64 in lane order with
            // no invalid bit patterns, aligned at least as strictly as `[f64; 4]`.
            unsafe { &mut *(self as *mut F4).cast::<[f64; LANES]>() }
        }
        #[inline(always)]
        fn per_lane<T: Copy>(f: impl FnMut(usize) -> T) -> [T; LANES] {
            std::array::from_fn(f)
        }
        #[inline(always)]
        fn count_up(count: F4) -> F4 {
            count + F4::splat(1.0)
        }
        fn count_of(n: u64) -> F4 {
            F4::splat(n as f64)
        }
        fn put_count(count: &mut F4, l: usize, n: u64) {
            count.set_lane(l, n as f64);
        }
        fn count_lane(count: F4, l: usize) -> u64 {
            count.lane(l) as u64
        }
        #[inline(always)]
        fn count_reached(count: F4, limit: F4) -> F4 {
            count.ge(limit)
        }
    }

    /// Four rolls of the law `W`, one per lane, each a roll `R` of `N` points, which the
    /// lane's state is stored back into at the end.
    struct Lanes<W: Law, R: LaneRoll<W, N>, const N: usize> {
        k: Kernel<F4, W, N, R::Body>,
        /// Lanes holding a roll that has not ended.
        live: F4,
        /// Per lane: the roll's index, its start face and the roll.
        rolls: [Option<(usize, u8, R)>; LANES],
        /// Per lane: its roll's impacts, seen state by state as the scalar engine sees them.
        impact_logs: [ImpactLog; LANES],
    }

    impl<W: Law, R: LaneRoll<W, N>, const N: usize> Lanes<W, R, N> {
        /// Four lanes from one roll's kernel (each is loaded before it steps, or parked).
        fn new(first: &Kernel<f64, W, N, R::Body>) -> Self {
            let mut lanes = Lanes {
                k: Kernel::splat(first),
                live: F4::zero(),
                rolls: std::array::from_fn(|_| None),
                impact_logs: [ImpactLog::new(false); LANES],
            };
            for l in 0..LANES {
                lanes.k.park(l);
            }
            lanes
        }

        /// A lane without a roll, if any.
        fn free_lane(&self) -> Option<usize> {
            (0..LANES).find(|&l| self.rolls[l].is_none())
        }

        /// Puts roll `index` into lane `l`, in the state its scalar engine starts it in.
        #[inline(always)]
        fn load(&mut self, l: usize, index: usize, mut roll: R) {
            self.k.set_lane(l, roll.kernel());
            let bits = F4::bits(self.live) | 1 << l;
            self.live = F4::mask_from_bits(bits);
            self.impact_logs[l] = *roll.impact_log_mut();
            let start_face = roll.start_face();
            self.rolls[l] = Some((index, start_face, roll));
        }

        /// Empties lane `l` for good: a still fair die high above the ground without
        /// gravity, so it never touches nor spins and costs the other lanes nothing (it turns
        /// by the identity).
        #[inline(always)]
        fn park(&mut self, l: usize) {
            let bits = F4::bits(self.live) & !(1 << l);
            self.live = F4::mask_from_bits(bits);
            self.k.park(l);
        }

        /// Stores lane `l`'s state back into its roll.
        #[inline(always)]
        fn store(&mut self, l: usize) -> &mut R {
            let (_, _, roll) = self.rolls[l].as_mut().expect("a live lane holds a roll");
            self.k.lane_into(l, roll.kernel_mut());
            *roll.impact_log_mut() = self.impact_logs[l];
            roll
        }

        /// Each live lane's contact after a step, as the scalar engine observes its own.
        #[inline(always)]
        fn observe_impacts(&mut self) {
            let (contact, live) = (F4::bits(self.k.in_contact), F4::bits(self.live));
            let s = &self.k.state;
            for (l, body) in self.k.bodies.iter().enumerate() {
                if live & (1 << l) != 0 {
                    self.impact_logs[l].observe(contact & (1 << l) != 0, || {
                        let offsets = s.corner_offsets.each_ref().map(|r| lane3(r, l));
                        (
                            R::face_down(body, &offsets),
                            s.step.lane(l) as u64,
                            s.time_s.lane(l),
                        )
                    });
                }
            }
        }

        /// The rolls that this step ended, each handed to `ended` with its index, start face
        /// and outcome; their lanes are emptied. Returns whether any ended.
        #[inline(always)]
        fn finish(&mut self, ends: &Ends<F4>, ended: &mut impl FnMut(usize, u8, Outcome, R)) -> bool {
            self.observe_impacts();
            let mut ending = F4::bits((ends.unstable | ends.settled | ends.timeout) & self.live);
            let any = ending != 0;
            while ending != 0 {
                let l = ending.trailing_zeros() as usize;
                ending &= ending - 1;
                let status = if F4::bits(ends.unstable) & (1 << l) != 0 {
                    Status::Unstable
                } else if F4::bits(ends.settled) & (1 << l) != 0 {
                    Status::Settled
                } else {
                    Status::Timeout
                };
                let outcome = self.store(l).finish(status);
                let (index, start_face, roll) = self.rolls[l].take().expect("a live lane holds a roll");
                ended(index, start_face, outcome, roll);
                self.park(l);
            }
            any
        }
    }

    /// Hands a finished roll to `done` as a [`LaneResult`].
    #[inline(always)]
    fn hand_on<W: Law, R: LaneRoll<W, N>, const N: usize>(
        done: &mut dyn FnMut(LaneResult<'_>),
    ) -> impl FnMut(usize, u8, Outcome, R) + '_ {
        move |index, start_face, outcome, roll: R| {
            done(LaneResult {
                index,
                outcome,
                start_face,
                state: roll.end_state(),
            })
        }
    }

    /// The rolls of one law and body: their vector, once a roll has come, and the rolls
    /// waiting for one of its lanes.
    struct Group<W: Law, R: LaneRoll<W, N>, const N: usize> {
        lanes: Option<Lanes<W, R, N>>,
        waiting: VecDeque<(usize, R)>,
    }

    impl<W: Law, R: LaneRoll<W, N>, const N: usize> Group<W, R, N> {
        fn new() -> Self {
            Group {
                lanes: None,
                waiting: VecDeque::new(),
            }
        }

        /// Whether a lane is free and no roll waits for it.
        fn wants(&self) -> bool {
            self.waiting.is_empty()
                && self
                    .lanes
                    .as_ref()
                    .is_none_or(|lanes| lanes.free_lane().is_some())
        }

        /// Loads waiting rolls into free lanes (with AVX2, as the loads are vector code).
        #[target_feature(enable = "avx2")]
        #[inline(never)]
        fn seat(&mut self) {
            while let Some((_, roll)) = self.waiting.front() {
                if self.lanes.is_none() {
                    self.lanes = Some(Lanes::new(roll.kernel()));
                }
                let lanes = self.lanes.as_mut().expect("just made");
                let Some(l) = lanes.free_lane() else { return };
                let (index, roll) = self.waiting.pop_front().expect("a waiting roll");
                lanes.load(l, index, roll);
            }
        }

        fn live(&self) -> bool {
            self.lanes.as_ref().is_some_and(|lanes| F4::bits(lanes.live) != 0)
        }
    }

    /// A polyhedral die's group, whatever its law and points, as the batch loop steps it.
    trait DiceGroup {
        fn wants(&self) -> bool;
        fn waiting(&self) -> usize;
        fn live(&self) -> bool;
        /// Queues a roll of this group's law and points.
        fn push(&mut self, index: usize, roll: DiceRoll);
        /// # Safety
        /// The CPU must support AVX2.
        unsafe fn seat(&mut self);
        /// One step of the group's vector, the rolls it ended handed to `done`; whether any
        /// ended.
        ///
        /// # Safety
        /// The CPU must support AVX2.
        unsafe fn step(&mut self, done: &mut dyn FnMut(LaneResult<'_>)) -> bool;
    }

    /// A [`PointRoll`] of `N` points out of a [`DiceRoll`].
    trait FromDiceRoll: Sized {
        fn from_dice_roll(roll: DiceRoll) -> Option<Self>;
    }

    macro_rules! from_dice_roll {
        ($($variant:ident $n:literal),*) => {$(
            impl FromDiceRoll for PointRoll<$n> {
                fn from_dice_roll(roll: DiceRoll) -> Option<Self> {
                    match roll {
                        DiceRoll::$variant(r) => Some(r),
                        _ => None,
                    }
                }
            }
        )*};
    }
    from_dice_roll!(P4 4, P6 6, P12 12, P20 20);

    impl<W: PointLaw, const N: usize> DiceGroup for Group<W, PointRoll<N>, N>
    where
        PointRoll<N>: FromDiceRoll,
    {
        fn wants(&self) -> bool {
            Group::wants(self)
        }
        fn waiting(&self) -> usize {
            self.waiting.len()
        }
        fn live(&self) -> bool {
            Group::live(self)
        }
        fn push(&mut self, index: usize, roll: DiceRoll) {
            let roll = PointRoll::<N>::from_dice_roll(roll).expect("a roll of this group's points");
            self.waiting.push_back((index, roll));
        }
        unsafe fn seat(&mut self) {
            // SAFETY: the caller has AVX2.
            unsafe { Group::seat(self) }
        }
        // With AVX2 enabled here too: the vector code of `finish` (the lanes' masks) is
        // inlined into this method, and without the feature each mask operation would be a
        // call of its own (a quarter of a d20's time in lanes, measured).
        #[target_feature(enable = "avx2")]
        unsafe fn step(&mut self, done: &mut dyn FnMut(LaneResult<'_>)) -> bool {
            let Some(lanes) = self.lanes.as_mut().filter(|lanes| F4::bits(lanes.live) != 0) else {
                return false;
            };
            let ends = step_points(&mut lanes.k);
            lanes.finish(&ends, &mut hand_on::<W, PointRoll<N>, N>(done))
        }
    }

    /// The group for a roll of `r`'s law and points, empty.
    fn dice_group<const N: usize>(r: &PointRoll<N>) -> Box<dyn DiceGroup>
    where
        PointRoll<N>: FromDiceRoll,
    {
        match &r.k {
            PointKernel::Paper(_) => Box::new(Group::<PaperPerCorner, PointRoll<N>, N>::new()),
            PointKernel::PaperWholeDie(_) => Box::new(Group::<PaperWholeDie, PointRoll<N>, N>::new()),
            PointKernel::SpringFriction(_) => Box::new(Group::<SpringFriction, PointRoll<N>, N>::new()),
        }
    }

    /// The polyhedral dice' groups of a run, one per law and solid, made as their first
    /// rolls come.
    #[derive(Default)]
    struct Dice {
        bodies: DiceBodies,
        groups: Vec<(DiceVector, Box<dyn DiceGroup>)>,
    }

    impl Dice {
        /// Sets up roll `index` and queues it in its group.
        fn push(&mut self, index: usize, params: &Params, initial: &InitialCondition) {
            let roll = self.bodies.roll(params, initial);
            let key = dice_vector(&roll, params);
            let at = match self.groups.iter().position(|(k, _)| *k == key) {
                Some(at) => at,
                None => {
                    self.groups.push((key, on_points!(&roll, r => dice_group(r))));
                    self.groups.len() - 1
                }
            };
            self.groups[at].1.push(index, roll);
        }

        fn wants(&self) -> bool {
            self.groups.iter().any(|(_, g)| g.wants())
        }

        fn full(&self) -> bool {
            self.groups.iter().any(|(_, g)| g.waiting() >= LANES)
        }

        fn live(&self) -> bool {
            self.groups.iter().any(|(_, g)| g.live())
        }

        #[target_feature(enable = "avx2")]
        fn seat(&mut self) {
            for (_, g) in &mut self.groups {
                // SAFETY: this function runs with AVX2.
                unsafe { g.seat() };
            }
        }

        /// One step of every live group; whether any roll ended.
        #[target_feature(enable = "avx2")]
        fn step(&mut self, done: &mut dyn FnMut(LaneResult<'_>)) -> bool {
            let mut vacated = false;
            for (_, g) in &mut self.groups {
                // SAFETY: this function runs with AVX2.
                vacated |= unsafe { g.step(done) };
            }
            vacated
        }
    }

    /// One step of the paper's law's vector, and how it leaves each lane: inline in the
    /// batch loop, whose code stays what it was for the paper's die.
    #[inline(always)]
    fn step_paper(k: &mut Kernel<F4, PaperPerCorner>) -> Ends<F4> {
        k.step(&mut NoHook);
        k.ends()
    }

    /// One step of the authors' whole-die norm's vector; out of line as the next.
    #[target_feature(enable = "avx2")]
    #[inline(never)]
    fn step_whole_die(k: &mut Kernel<F4, PaperWholeDie>) -> Ends<F4> {
        k.step(&mut NoHook);
        k.ends()
    }

    /// One step of the spring-friction law's vector, and how it leaves each lane; out of
    /// line, called only from [`roll_all`], which has AVX2 too.
    #[target_feature(enable = "avx2")]
    #[inline(never)]
    fn step_spring_friction(k: &mut Kernel<F4, SpringFriction>) -> Ends<F4> {
        k.step(&mut NoHook);
        k.ends()
    }

    /// One step of a polyhedral die's vector under any law, out of line.
    #[target_feature(enable = "avx2")]
    #[inline(never)]
    fn step_points<W: Law, const N: usize>(k: &mut Kernel<F4, W, N, PointBody<N>>) -> Ends<F4> {
        k.step(&mut NoHook);
        k.ends()
    }

    /// Sets up rolls from `next` on and seats them in their vectors while a vector has a free
    /// lane nothing waits for and no vector has a vector's worth waiting; false when no
    /// vector has a roll left to step.
    #[target_feature(enable = "avx2")]
    #[inline(never)]
    fn seat_rolls(
        count: usize,
        next: &mut usize,
        setup: &mut dyn FnMut(usize) -> (Params, InitialCondition),
        paper: &mut Group<PaperPerCorner, Simulation, 8>,
        whole: &mut Group<PaperWholeDie, Simulation, 8>,
        spring: &mut Group<SpringFriction, Simulation, 8>,
        dice: &mut Dice,
    ) -> bool {
        paper.seat();
        whole.seat();
        spring.seat();
        dice.seat();
        while *next < count
            && (paper.wants() || whole.wants() || spring.wants() || dice.wants())
            && paper.waiting.len() < LANES
            && whole.waiting.len() < LANES
            && spring.waiting.len() < LANES
            && !dice.full()
        {
            let (params, initial) = setup(*next);
            if params.die.is_polyhedral() {
                dice.push(*next, &params, &initial);
            } else {
                let sim = Simulation::for_outcome(&params, &initial);
                match &sim.k {
                    Laws::Paper(_) => paper.waiting.push_back((*next, sim)),
                    Laws::PaperWholeDie(_) => whole.waiting.push_back((*next, sim)),
                    Laws::SpringFriction(_) => spring.waiting.push_back((*next, sim)),
                }
            }
            *next += 1;
            paper.seat();
            whole.seat();
            spring.seat();
            dice.seat();
        }
        paper.live() || whole.live() || spring.live() || dice.live()
    }

    /// [`roll_in_lanes`] with AVX2.
    ///
    /// The rolls go into vectors by their contact law, so a vector steps one law's code, and
    /// a polyhedral die's by its law and solid: each roll is set up in turn and seated in
    /// its vector, or waits there for a free lane. Rolls are set up only while some vector
    /// has a free lane nothing waits for, and no vector has a vector's worth waiting, so a
    /// run of one law's rolls after another's keeps at most four set up ahead.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn roll_all(
        count: usize,
        setup: &mut dyn FnMut(usize) -> (Params, InitialCondition),
        done: &mut dyn FnMut(LaneResult<'_>),
        stop: &dyn Fn() -> bool,
    ) -> bool {
        let mut paper = Group::<PaperPerCorner, Simulation, 8>::new();
        let mut whole = Group::<PaperWholeDie, Simulation, 8>::new();
        let mut spring = Group::<SpringFriction, Simulation, 8>::new();
        let mut dice = Dice::default();
        let mut next = 0;
        let mut since_check = 0;
        // Whether a lane was emptied since rolls were last seated (a roll ended, or none
        // has been seated yet): only then are rolls set up and seated, not every step.
        let mut vacated = true;
        loop {
            if vacated {
                vacated = false;
                if !seat_rolls(
                    count,
                    &mut next,
                    setup,
                    &mut paper,
                    &mut whole,
                    &mut spring,
                    &mut dice,
                ) {
                    return true;
                }
            }
            if let Some(lanes) = paper.lanes.as_mut().filter(|lanes| F4::bits(lanes.live) != 0) {
                let ends = step_paper(&mut lanes.k);
                vacated |= lanes.finish(&ends, &mut hand_on::<PaperPerCorner, Simulation, 8>(done));
            }
            if let Some(lanes) = whole.lanes.as_mut().filter(|lanes| F4::bits(lanes.live) != 0) {
                let ends = step_whole_die(&mut lanes.k);
                vacated |= lanes.finish(&ends, &mut hand_on::<PaperWholeDie, Simulation, 8>(done));
            }
            if let Some(lanes) = spring.lanes.as_mut().filter(|lanes| F4::bits(lanes.live) != 0) {
                let ends = step_spring_friction(&mut lanes.k);
                vacated |= lanes.finish(&ends, &mut hand_on::<SpringFriction, Simulation, 8>(done));
            }
            if !dice.groups.is_empty() {
                vacated |= dice.step(done);
            }
            since_check += 1;
            if since_check == STEPS_BETWEEN_STOP_CHECKS {
                since_check = 0;
                if stop() {
                    return false;
                }
            }
        }
    }

    /// [`roll_points_in_lanes`] with AVX2, the rolls all on the law `W`: each roll loaded
    /// into a lane as [`PointRoll`] placed it, stepped until it ends, and stored back.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn roll_points<W: PointLaw, const N: usize>(
        rolls: Vec<PointRoll<N>>,
    ) -> Vec<PointRoll<N>> {
        let mut group = Group::<W, PointRoll<N>, N>::new();
        let mut finished: Vec<Option<PointRoll<N>>> = (0..rolls.len()).map(|_| None).collect();
        group.waiting.extend(rolls.into_iter().enumerate());
        group.seat();
        while let Some(lanes) = group.lanes.as_mut().filter(|lanes| F4::bits(lanes.live) != 0) {
            let ends = step_points(&mut lanes.k);
            if lanes.finish(&ends, &mut |index, _, _, roll| finished[index] = Some(roll)) {
                group.seat();
            }
        }
        finished
            .into_iter()
            .map(|roll| roll.expect("every roll ends"))
            .collect()
    }
}
