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
use super::initial::InitialCondition;
use super::params::Params;
use super::sim::{Outcome, STEPS_BETWEEN_STOP_CHECKS, Simulation, State};

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

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use super::*;
    use crate::kernel::{Kernel, NoHook, lane3};
    use crate::lane::Lane;
    use crate::sim::{ImpactLog, Status};
    use nalgebra::{Vector2, Vector3};
    use std::arch::x86_64::*;
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
        fn all_finite(p: &Vector3<F4>, v: &Vector3<F4>, offsets: &[Vector3<F4>; 8]) -> F4 {
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
        #[inline(always)]
        fn count_reached(count: F4, limit: F4) -> F4 {
            count.ge(limit)
        }
    }

    fn set_mask(mask: &mut F4, l: usize, on: bool) {
        let mut bits = F4::bits(*mask);
        if on {
            bits |= 1 << l;
        } else {
            bits &= !(1 << l);
        }
        *mask = F4::from_bits(bits);
    }

    #[inline(always)]
    fn set2(v: &mut Vector2<F4>, l: usize, x: &Vector2<f64>) {
        v.x.set_lane(l, x.x);
        v.y.set_lane(l, x.y);
    }

    #[inline(always)]
    fn set3(v: &mut Vector3<F4>, l: usize, x: &Vector3<f64>) {
        v.x.set_lane(l, x.x);
        v.y.set_lane(l, x.y);
        v.z.set_lane(l, x.z);
    }

    /// Four rolls, one per lane, and the `Simulation` each was set up by.
    struct Lanes {
        k: Kernel<F4>,
        /// Lanes holding a roll that has not ended.
        live: F4,
        /// Per lane: the roll's index, its start face and its `Simulation`, which the lane's
        /// state is stored back into at the end.
        rolls: [Option<(usize, u8, Simulation)>; LANES],
        /// Per lane: its roll's impacts, seen state by state as the scalar engine sees them.
        impact_logs: [ImpactLog; LANES],
    }

    impl Lanes {
        /// Four lanes from one roll's kernel (each is loaded before it steps, or parked).
        fn new(first: &Kernel<f64>) -> Lanes {
            let s = &first.state;
            let splat3 = |v: &Vector3<f64>| Vector3::new(F4::splat(v.x), F4::splat(v.y), F4::splat(v.z));
            let splat2 = |v: &Vector2<f64>| Vector2::new(F4::splat(v.x), F4::splat(v.y));
            let c = &first.c;
            let k = Kernel {
                state: State {
                    position: splat3(&s.position),
                    velocity: splat3(&s.velocity),
                    angular_momentum: splat3(&s.angular_momentum),
                    corner_offsets: s.corner_offsets.each_ref().map(splat3),
                    corner_forces: s.corner_forces.each_ref().map(splat3),
                    corner_depths: s.corner_depths.map(F4::splat),
                    tangential_springs: s.tangential_springs.each_ref().map(splat2),
                    time_s: F4::splat(s.time_s),
                    step: F4::splat(s.step as f64),
                },
                angular_velocity: splat3(&first.angular_velocity),
                turned_axes: first.turned_axes.each_ref().map(splat3),
                turned_angular_velocity: splat3(&first.turned_angular_velocity),
                rotation: first.rotation.map(F4::splat),
                rotating: F4::from_bits(if first.rotating { 0b1111 } else { 0 }),
                in_contact: F4::from_bits(if first.in_contact { 0b1111 } else { 0 }),
                touching_corners: first.touching_corners,
                c: crate::kernel::Constants {
                    dt: F4::splat(c.dt),
                    mass: F4::splat(c.mass),
                    weight_z: F4::splat(c.weight_z),
                    flight_kick: splat3(&c.flight_kick),
                    stiffness: F4::splat(c.stiffness),
                    damping: F4::splat(c.damping),
                    friction: F4::splat(c.friction),
                    weight_x: F4::splat(c.weight_x),
                    weight_y: F4::splat(c.weight_y),
                    normal_damping: F4::splat(c.normal_damping),
                    tangential_stiffness: F4::splat(c.tangential_stiffness),
                    tangential_damping: F4::splat(c.tangential_damping),
                    tangential_compliance: F4::splat(c.tangential_compliance),
                    static_friction: F4::splat(c.static_friction),
                    kinetic_cap: F4::splat(c.kinetic_cap),
                    half_mass: F4::splat(c.half_mass),
                    mass_gravity: F4::splat(c.mass_gravity),
                    half_stiffness: F4::splat(c.half_stiffness),
                    half_size: F4::splat(c.half_size),
                    half_corner_mass: F4::splat(c.half_corner_mass),
                    corner_mass_gravity: F4::splat(c.corner_mass_gravity),
                    mass_gravity_half_size: F4::splat(c.mass_gravity_half_size),
                    corner_masses: c.corner_masses.map(F4::splat),
                    gravity: F4::splat(c.gravity),
                    loaded_mass_gravity_half_size: F4::splat(c.loaded_mass_gravity_half_size),
                    uniform_inertia: F4::splat(c.uniform_inertia),
                    uniform_mass: F4::splat(c.uniform_mass),
                    extra_masses: c.extra_masses.map(F4::splat),
                    inverse_inertia: c.inverse_inertia.map(F4::splat),
                    axis_scale: c.axis_scale.map(F4::splat),
                    inverse_moments: c.inverse_moments.map(F4::splat),
                    principal_axes: c.principal_axes.map(F4::splat),
                    principal_corners: c.principal_corners.each_ref().map(splat3),
                    split: F4::from_bits(if c.split { 0b1111 } else { 0 }),
                    corner_radius: F4::splat(c.corner_radius),
                    energy_threshold: F4::splat(c.energy_threshold),
                    kinetic_threshold: F4::splat(c.kinetic_threshold),
                    runaway: F4::splat(c.runaway),
                    max_steps: F4::splat(c.max_steps as f64),
                    whole_die_norm: F4::from_bits(if c.whole_die_norm { 0b1111 } else { 0 }),
                    point_masses: F4::from_bits(if c.point_masses { 0b1111 } else { 0 }),
                    loaded: F4::from_bits(if c.loaded { 0b1111 } else { 0 }),
                    shaped: F4::from_bits(if c.shaped { 0b1111 } else { 0 }),
                    rounded: if c.rounded != 0 { 0b1111 } else { 0 },
                    turning: F4::from_bits(if c.turning { 0b1111 } else { 0 }),
                    spring: F4::from_bits(if c.spring { 0b1111 } else { 0 }),
                    spring_lanes: if c.spring_lanes != 0 { 0b1111 } else { 0 },
                },
                bodies: [first.bodies[0]; LANES],
            };
            Lanes {
                k,
                live: F4::zero(),
                rolls: [None, None, None, None],
                impact_logs: [ImpactLog::new(false); LANES],
            }
        }

        /// Puts roll `index` into lane `l`, in the state `Simulation` starts it in.
        #[inline(always)]
        fn load(&mut self, l: usize, index: usize, sim: Simulation) {
            let from = &sim.k;
            let (k, s) = (&mut self.k, &from.state);
            set3(&mut k.state.position, l, &s.position);
            set3(&mut k.state.velocity, l, &s.velocity);
            set3(&mut k.state.angular_momentum, l, &s.angular_momentum);
            for c in 0..8 {
                set3(&mut k.state.corner_offsets[c], l, &s.corner_offsets[c]);
                set3(&mut k.state.corner_forces[c], l, &s.corner_forces[c]);
                k.state.corner_depths[c].set_lane(l, s.corner_depths[c]);
                set2(&mut k.state.tangential_springs[c], l, &s.tangential_springs[c]);
            }
            k.state.time_s.set_lane(l, s.time_s);
            k.state.step.set_lane(l, s.step as f64);
            set3(&mut k.angular_velocity, l, &from.angular_velocity);
            set3(&mut k.turned_angular_velocity, l, &from.turned_angular_velocity);
            for axis in 0..3 {
                set3(&mut k.turned_axes[axis], l, &from.turned_axes[axis]);
            }
            for e in 0..9 {
                k.rotation[e].set_lane(l, from.rotation[e]);
            }
            set_mask(&mut k.rotating, l, from.rotating);
            set_mask(&mut k.in_contact, l, from.in_contact);
            k.touching_corners = (0..8)
                .filter(|&c| F4::bits(k.state.corner_depths[c].gt(F4::zero())) != 0)
                .fold(0, |bits, c| bits | 1 << c);
            let (c, f) = (&mut k.c, &from.c);
            c.dt.set_lane(l, f.dt);
            c.mass.set_lane(l, f.mass);
            c.weight_z.set_lane(l, f.weight_z);
            set3(&mut c.flight_kick, l, &f.flight_kick);
            c.stiffness.set_lane(l, f.stiffness);
            c.damping.set_lane(l, f.damping);
            c.friction.set_lane(l, f.friction);
            c.weight_x.set_lane(l, f.weight_x);
            c.weight_y.set_lane(l, f.weight_y);
            c.normal_damping.set_lane(l, f.normal_damping);
            c.tangential_stiffness.set_lane(l, f.tangential_stiffness);
            c.tangential_damping.set_lane(l, f.tangential_damping);
            c.tangential_compliance.set_lane(l, f.tangential_compliance);
            c.static_friction.set_lane(l, f.static_friction);
            c.kinetic_cap.set_lane(l, f.kinetic_cap);
            c.half_mass.set_lane(l, f.half_mass);
            c.mass_gravity.set_lane(l, f.mass_gravity);
            c.half_stiffness.set_lane(l, f.half_stiffness);
            c.half_size.set_lane(l, f.half_size);
            c.half_corner_mass.set_lane(l, f.half_corner_mass);
            c.corner_mass_gravity.set_lane(l, f.corner_mass_gravity);
            c.mass_gravity_half_size.set_lane(l, f.mass_gravity_half_size);
            for corner in 0..8 {
                c.corner_masses[corner].set_lane(l, f.corner_masses[corner]);
            }
            c.gravity.set_lane(l, f.gravity);
            c.loaded_mass_gravity_half_size
                .set_lane(l, f.loaded_mass_gravity_half_size);
            c.uniform_inertia.set_lane(l, f.uniform_inertia);
            c.uniform_mass.set_lane(l, f.uniform_mass);
            for corner in 0..8 {
                c.extra_masses[corner].set_lane(l, f.extra_masses[corner]);
            }
            for e in 0..6 {
                c.inverse_inertia[e].set_lane(l, f.inverse_inertia[e]);
            }
            for axis in 0..3 {
                c.axis_scale[axis].set_lane(l, f.axis_scale[axis]);
                c.inverse_moments[axis].set_lane(l, f.inverse_moments[axis]);
            }
            for e in 0..9 {
                c.principal_axes[e].set_lane(l, f.principal_axes[e]);
            }
            for corner in 0..8 {
                set3(&mut c.principal_corners[corner], l, &f.principal_corners[corner]);
            }
            set_mask(&mut c.split, l, f.split);
            c.corner_radius.set_lane(l, f.corner_radius);
            c.energy_threshold.set_lane(l, f.energy_threshold);
            c.kinetic_threshold.set_lane(l, f.kinetic_threshold);
            c.runaway.set_lane(l, f.runaway);
            c.max_steps.set_lane(l, f.max_steps as f64);
            set_mask(&mut c.whole_die_norm, l, f.whole_die_norm);
            set_mask(&mut c.point_masses, l, f.point_masses);
            set_mask(&mut c.loaded, l, f.loaded);
            set_mask(&mut c.shaped, l, f.shaped);
            c.rounded = (c.rounded & !(1 << l)) | (f.rounded << l);
            set_mask(&mut c.turning, l, f.turning);
            set_mask(&mut c.spring, l, f.spring);
            c.spring_lanes = (c.spring_lanes & !(1 << l)) | (f.spring_lanes << l);
            k.bodies[l] = from.bodies[0];
            set_mask(&mut self.live, l, true);
            self.impact_logs[l] = sim.impact_log;
            let start_face = face_most_nearly_up(&s.corner_offsets);
            self.rolls[l] = Some((index, start_face, sim));
        }

        /// Empties lane `l` for good: a still fair die high above the ground without
        /// gravity, so it never touches nor spins and costs the other lanes nothing (it turns
        /// by the identity).
        fn park(&mut self, l: usize) {
            let k = &mut self.k;
            set_mask(&mut self.live, l, false);
            set_mask(&mut k.in_contact, l, false);
            set_mask(&mut k.rotating, l, true);
            for (e, entry) in k.rotation.iter_mut().enumerate() {
                entry.set_lane(l, if e % 4 == 0 { 1.0 } else { 0.0 });
            }
            set3(&mut k.state.position, l, &Vector3::new(0.0, 0.0, 1e9));
            set3(&mut k.state.velocity, l, &Vector3::zeros());
            k.c.weight_x.set_lane(l, 0.0);
            k.c.weight_y.set_lane(l, 0.0);
            k.c.weight_z.set_lane(l, 0.0);
            set3(&mut k.c.flight_kick, l, &Vector3::zeros());
            // It never touches, so either law steps it alike: it takes its neighbour's, and
            // a vector of one law keeps that law's step.
            let neighbour = (l + 1) % LANES;
            let spring = k.c.spring_lanes & (1 << neighbour) != 0;
            set_mask(&mut k.c.spring, l, spring);
            k.c.spring_lanes = (k.c.spring_lanes & !(1 << l)) | ((spring as u32) << l);
            set_mask(&mut k.c.loaded, l, false);
            set_mask(&mut k.c.shaped, l, false);
            k.c.rounded &= !(1 << l);
            set_mask(&mut k.c.turning, l, false);
            set_mask(&mut k.c.split, l, false);
            k.c.corner_radius.set_lane(l, 0.0);
            k.bodies[l] = k.bodies[(l + 1) % LANES];
            for c in 0..8 {
                set3(&mut k.state.corner_forces[c], l, &Vector3::zeros());
                k.state.corner_depths[c].set_lane(l, 0.0);
                set2(&mut k.state.tangential_springs[c], l, &Vector2::zeros());
            }
        }

        /// Stores lane `l`'s state back into its roll's `Simulation`.
        #[inline(always)]
        fn store(&mut self, l: usize) -> &mut Simulation {
            let (_, _, sim) = self.rolls[l].as_mut().expect("a live lane holds a roll");
            let (k, to) = (&self.k, &mut sim.k);
            let (from, s) = (&k.state, &mut to.state);
            s.position = lane3(&from.position, l);
            s.velocity = lane3(&from.velocity, l);
            s.angular_momentum = lane3(&from.angular_momentum, l);
            for c in 0..8 {
                s.corner_offsets[c] = lane3(&from.corner_offsets[c], l);
                s.corner_forces[c] = lane3(&from.corner_forces[c], l);
                s.corner_depths[c] = from.corner_depths[c].lane(l);
                let xi = &from.tangential_springs[c];
                s.tangential_springs[c] = Vector2::new(xi.x.lane(l), xi.y.lane(l));
            }
            s.time_s = from.time_s.lane(l);
            s.step = from.step.lane(l) as u64;
            to.angular_velocity = lane3(&k.angular_velocity, l);
            to.rotation = k.rotation.map(|e| e.lane(l));
            to.rotating = F4::bits(k.rotating) & (1 << l) != 0;
            to.in_contact = F4::bits(k.in_contact) & (1 << l) != 0;
            to.touching_corners = (0..8)
                .filter(|&c| s.corner_depths[c] > 0.0)
                .fold(0, |bits, c| bits | 1 << c);
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
    }

    /// One step with lanes on the spring-friction law, and how it leaves each lane; called
    /// only from [`roll_all`], which has AVX2 too.
    #[target_feature(enable = "avx2")]
    #[inline(never)]
    fn step_spring_friction(k: &mut Kernel<F4>) -> crate::kernel::Ends<F4> {
        k.step::<true>(&mut NoHook);
        k.ends_by::<true>()
    }

    /// [`roll_in_lanes`] with AVX2.
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
        if count == 0 {
            return true;
        }
        let (params, initial) = setup(0);
        let first = Simulation::for_outcome(&params, &initial);
        let mut lanes = Lanes::new(&first.k);
        lanes.load(0, 0, first);
        let mut next = 1;
        for l in 1..LANES {
            if next < count {
                let (params, initial) = setup(next);
                lanes.load(l, next, Simulation::for_outcome(&params, &initial));
                next += 1;
            } else {
                lanes.park(l);
            }
        }
        let mut since_check = 0;
        while F4::bits(lanes.live) != 0 {
            // The paper's step inline, the other law's out of line: the batch loop's code
            // stays what it was for the paper's die.
            let ends = if lanes.k.c.spring_lanes == 0 {
                lanes.k.step::<false>(&mut NoHook);
                lanes.k.ends_by::<false>()
            } else {
                step_spring_friction(&mut lanes.k)
            };
            lanes.observe_impacts();
            let mut ending = F4::bits((ends.unstable | ends.settled | ends.timeout) & lanes.live);
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
                let outcome = lanes.store(l).finish(status);
                let (index, start_face, sim) = lanes.rolls[l].take().expect("a live lane holds a roll");
                done(LaneResult {
                    index,
                    outcome,
                    start_face,
                    state: sim.state(),
                });
                if next < count {
                    let (params, initial) = setup(next);
                    lanes.load(l, next, Simulation::for_outcome(&params, &initial));
                    next += 1;
                } else {
                    lanes.park(l);
                }
            }
            since_check += 1;
            if since_check == STEPS_BETWEEN_STOP_CHECKS {
                since_check = 0;
                if stop() {
                    return false;
                }
            }
        }
        true
    }
}
