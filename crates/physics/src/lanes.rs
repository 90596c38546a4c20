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
use super::contact::SpringFriction;
use super::initial::InitialCondition;
use super::params::{ParamError, Params};
use super::point_roll::{PointKernel, PointRoll};
use super::points::PointBody;
use super::sim::{Outcome, STEPS_BETWEEN_STOP_CHECKS, Simulation, State};
use super::sim::{PaperPerCorner, PaperWholeDie};

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
    /// The face most nearly up at t = 0.
    pub start_face: u8,
    /// The state at the end, as [`Simulation::state`] has it after the same roll.
    pub state: &'a State,
}

/// Rolls setups `0..count` (from `setup(i)`) to their ends, four at a time, and hands each
/// finished roll to `done`, in the order they finish. `stop()` is asked every
/// [`STEPS_BETWEEN_STOP_CHECKS`] steps; when it answers true the rolls still running are
/// dropped and `false` is returned (`true`: every roll finished).
///
/// Falls back to one [`Simulation`] after another where AVX2 is missing, with the same
/// results.
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

/// The scalar engine behind the same interface.
pub fn roll_one_by_one(
    count: usize,
    setup: &mut dyn FnMut(usize) -> (Params, InitialCondition),
    done: &mut dyn FnMut(LaneResult<'_>),
    stop: &dyn Fn() -> bool,
) -> bool {
    for index in 0..count {
        let (params, initial) = setup(index);
        let mut sim = Simulation::for_outcome(&params, &initial);
        let start_face = face_most_nearly_up(&sim.state().corner_offsets);
        match sim.run_until_stopped(stop) {
            Some(outcome) => done(LaneResult {
                index,
                outcome,
                start_face,
                state: sim.state(),
            }),
            None => return false,
        }
    }
    true
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
        unsafe {
            match &rolls[0].k {
                PointKernel::Paper(_) => avx2::roll_points::<PaperPerCorner, N>(&mut rolls),
                PointKernel::PaperWholeDie(_) => avx2::roll_points::<PaperWholeDie, N>(&mut rolls),
                PointKernel::SpringFriction(_) => avx2::roll_points::<SpringFriction, N>(&mut rolls),
            }
        }
        return Ok(rolls);
    }
    for roll in &mut rolls {
        roll.run_to_end();
    }
    Ok(rolls)
}

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use super::*;
    use crate::kernel::{Ends, Kernel, NoHook};
    use crate::lane::{Lane, lane3};
    use crate::point_roll::PointLaw;
    use crate::sim::{EngineLaw, ImpactLog, Laws, Status};
    use nalgebra::Vector3;
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

    /// Four rolls of the law `W`, one per lane, and the `Simulation` each was set up by.
    struct Lanes<W: EngineLaw> {
        k: Kernel<F4, W>,
        /// Lanes holding a roll that has not ended.
        live: F4,
        /// Per lane: the roll's index, its start face and its `Simulation`, which the lane's
        /// state is stored back into at the end.
        rolls: [Option<(usize, u8, Simulation)>; LANES],
        /// Per lane: its roll's impacts, seen state by state as the scalar engine sees them.
        impact_logs: [ImpactLog; LANES],
    }

    impl<W: EngineLaw> Lanes<W> {
        /// Four lanes from one roll's kernel (each is loaded before it steps, or parked).
        fn new(first: &Kernel<f64, W>) -> Lanes<W> {
            let mut lanes = Lanes {
                k: Kernel::splat(first),
                live: F4::zero(),
                rolls: [None, None, None, None],
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

        /// Puts roll `index` into lane `l`, in the state `Simulation` starts it in.
        #[inline(always)]
        fn load(&mut self, l: usize, index: usize, sim: Simulation) {
            let from = W::of(&sim.k).expect("a roll of this vector's law");
            self.k.set_lane(l, from);
            let bits = F4::bits(self.live) | 1 << l;
            self.live = F4::mask_from_bits(bits);
            self.impact_logs[l] = sim.impact_log;
            let start_face = face_most_nearly_up(&from.state.corner_offsets);
            self.rolls[l] = Some((index, start_face, sim));
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

        /// Stores lane `l`'s state back into its roll's `Simulation`.
        #[inline(always)]
        fn store(&mut self, l: usize) -> &mut Simulation {
            let (_, _, sim) = self.rolls[l].as_mut().expect("a live lane holds a roll");
            let to = W::of_mut(&mut sim.k).expect("a roll of this vector's law");
            self.k.lane_into(l, to);
            sim.impact_log = self.impact_logs[l];
            sim
        }

        /// Each live lane's contact after a step, as the scalar engine observes its own.
        #[inline(always)]
        fn observe_impacts(&mut self) {
            let (contact, live) = (F4::bits(self.k.in_contact), F4::bits(self.live));
            let s = &self.k.state;
            for l in 0..LANES {
                if live & (1 << l) != 0 {
                    self.impact_logs[l].observe(contact & (1 << l) != 0, || {
                        (
                            s.corner_offsets.each_ref().map(|r| lane3(r, l)),
                            s.step.lane(l) as u64,
                            s.time_s.lane(l),
                        )
                    });
                }
            }
        }

        /// The rolls that this step ended, handed to `done`; their lanes are emptied. Returns
        /// whether any ended.
        #[inline(always)]
        fn finish(&mut self, ends: &Ends<F4>, done: &mut dyn FnMut(LaneResult<'_>)) -> bool {
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
                let (index, start_face, sim) = self.rolls[l].take().expect("a live lane holds a roll");
                done(LaneResult {
                    index,
                    outcome,
                    start_face,
                    state: sim.state(),
                });
                self.park(l);
            }
            any
        }
    }

    /// The rolls of one law: their vector, once a roll of the law has come, and the rolls
    /// waiting for one of its lanes.
    struct Group<W: EngineLaw> {
        lanes: Option<Lanes<W>>,
        waiting: VecDeque<(usize, Simulation)>,
    }

    impl<W: EngineLaw> Group<W> {
        fn new() -> Group<W> {
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
            while let Some((_, sim)) = self.waiting.front() {
                if self.lanes.is_none() {
                    let first = W::of(&sim.k).expect("a roll of this group's law");
                    self.lanes = Some(Lanes::new(first));
                }
                let lanes = self.lanes.as_mut().expect("just made");
                let Some(l) = lanes.free_lane() else { return };
                let (index, sim) = self.waiting.pop_front().expect("a waiting roll");
                lanes.load(l, index, sim);
            }
        }

        fn live(&self) -> bool {
            self.lanes.as_ref().is_some_and(|lanes| F4::bits(lanes.live) != 0)
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

    /// Sets up rolls from `next` on and seats them in their laws' vectors while a vector has a
    /// free lane nothing waits for and no law has a vector's worth waiting; false when no
    /// vector has a roll left to step.
    #[target_feature(enable = "avx2")]
    #[inline(never)]
    fn seat_rolls(
        count: usize,
        next: &mut usize,
        setup: &mut dyn FnMut(usize) -> (Params, InitialCondition),
        paper: &mut Group<PaperPerCorner>,
        whole: &mut Group<PaperWholeDie>,
        spring: &mut Group<SpringFriction>,
    ) -> bool {
        paper.seat();
        whole.seat();
        spring.seat();
        while *next < count
            && (paper.wants() || whole.wants() || spring.wants())
            && paper.waiting.len() < LANES
            && whole.waiting.len() < LANES
            && spring.waiting.len() < LANES
        {
            let (params, initial) = setup(*next);
            let sim = Simulation::for_outcome(&params, &initial);
            match &sim.k {
                Laws::Paper(_) => paper.waiting.push_back((*next, sim)),
                Laws::PaperWholeDie(_) => whole.waiting.push_back((*next, sim)),
                Laws::SpringFriction(_) => spring.waiting.push_back((*next, sim)),
            }
            *next += 1;
            paper.seat();
            whole.seat();
            spring.seat();
        }
        paper.live() || whole.live() || spring.live()
    }

    /// [`roll_in_lanes`] with AVX2.
    ///
    /// The rolls go into vectors by their contact law, so a vector steps one law's code:
    /// each roll is set up in turn and seated in its law's vector, or waits there for a free
    /// lane. Rolls are set up only while some vector has a free lane nothing waits for, and
    /// no law has a vector's worth waiting, so a run of one law's rolls after another's
    /// keeps at most four set up ahead.
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
        let mut paper = Group::<PaperPerCorner>::new();
        let mut whole = Group::<PaperWholeDie>::new();
        let mut spring = Group::<SpringFriction>::new();
        let mut next = 0;
        let mut since_check = 0;
        // Whether a lane was emptied since rolls were last seated (a roll ended, or none
        // has been seated yet): only then are rolls set up and seated, not every step.
        let mut vacated = true;
        loop {
            if vacated {
                vacated = false;
                if !seat_rolls(count, &mut next, setup, &mut paper, &mut whole, &mut spring) {
                    return true;
                }
            }
            if let Some(lanes) = paper.lanes.as_mut().filter(|lanes| F4::bits(lanes.live) != 0) {
                let ends = step_paper(&mut lanes.k);
                vacated |= lanes.finish(&ends, done);
            }
            if let Some(lanes) = whole.lanes.as_mut().filter(|lanes| F4::bits(lanes.live) != 0) {
                let ends = step_whole_die(&mut lanes.k);
                vacated |= lanes.finish(&ends, done);
            }
            if let Some(lanes) = spring.lanes.as_mut().filter(|lanes| F4::bits(lanes.live) != 0) {
                let ends = step_spring_friction(&mut lanes.k);
                vacated |= lanes.finish(&ends, done);
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
    pub(super) unsafe fn roll_points<W: PointLaw, const N: usize>(rolls: &mut [PointRoll<N>]) {
        let first = W::of(&rolls[0].k).expect("the rolls' law");
        let mut k = Kernel::<F4, W, N, PointBody<N>>::splat(first);
        let mut held: [Option<usize>; LANES] = [None; LANES];
        let mut next = 0;
        for (l, lane) in held.iter_mut().enumerate() {
            k.park(l);
            if next < rolls.len() {
                k.set_lane(l, W::of(&rolls[next].k).expect("the rolls' law"));
                *lane = Some(next);
                next += 1;
            }
        }
        while held.iter().any(Option::is_some) {
            k.step(&mut NoHook);
            let ends = k.ends();
            for (l, lane) in held.iter_mut().enumerate() {
                let Some(index) = *lane else { continue };
                let bit = 1 << l;
                let status = if F4::bits(ends.unstable) & bit != 0 {
                    Status::Unstable
                } else if F4::bits(ends.settled) & bit != 0 {
                    Status::Settled
                } else if F4::bits(ends.timeout) & bit != 0 {
                    Status::Timeout
                } else {
                    continue;
                };
                let roll = &mut rolls[index];
                k.lane_into(l, W::of_mut(&mut roll.k).expect("the rolls' law"));
                roll.finish(status);
                *lane = None;
                k.park(l);
                if next < rolls.len() {
                    k.set_lane(l, W::of(&rolls[next].k).expect("the rolls' law"));
                    *lane = Some(next);
                    next += 1;
                }
            }
        }
    }
}
