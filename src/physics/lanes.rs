//! The lane engine: four rolls stepped side by side in the 4 lanes of 256-bit AVX2 vectors,
//! each lane bit-identical to [`Simulation`] rolling alone.
//!
//! The state is kept as a structure of arrays (one vector per coordinate, lane `l` holding
//! roll `l`), and every lane does the scalar step's arithmetic operation for operation:
//! `+ − × ÷ √` are correctly rounded in both, Rust never fuses a multiply and an add, sums
//! run in corner order, and where the scalar path leaves a value at +0.0 (a corner above the
//! ground, a roll out of contact) the lane selects +0.0 rather than computing a product that
//! might be −0.0. The spin rebuild (libm's sin and cos) is the one scalar function
//! `sim::spin`, called per lane whose angular momentum changed. The end-of-step decision is
//! made by `Simulation::check_end` itself on the lane's state stored back into the roll's
//! `Simulation`; the vector code only screens out lanes that surely go on (one place,
//! `Lanes::may_end`, which replicates the stopping rule's comparisons). A lane whose roll
//! ended takes the next roll at once.
//!
//! The one module that uses `unsafe`: the AVX2 intrinsics are `unsafe` to call, and each
//! call is reached only through `roll_in_lanes`, after `is_x86_feature_detected!` said the
//! CPU has AVX2 (the loads and stores are of arrays of exactly four lanes).
#![allow(unsafe_code)]

use super::body::face_most_nearly_up;
use super::initial::InitialCondition;
use super::params::{FrictionLaw, Params, StopEnergy};
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
    use crate::physics::sim::spin;
    use nalgebra::{Matrix3, Vector3};
    use std::arch::x86_64::*;
    use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

    const LANES: usize = 4;

    /// Four f64 in one AVX register (or four lane masks: all bits set = true).
    #[derive(Clone, Copy)]
    #[repr(transparent)]
    struct F4(__m256d);

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
            self.xor(F4::all_set())
        }
    }

    impl F4 {
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
        fn all_set() -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_castsi256_pd(_mm256_set1_epi64x(-1)) })
        }
        #[inline(always)]
        fn from_array(a: [f64; 4]) -> F4 {
            // SAFETY: as above; the load is unaligned.
            F4(unsafe { _mm256_loadu_pd(a.as_ptr()) })
        }
        #[inline(always)]
        fn to_array(self) -> [f64; 4] {
            let mut a = [0.0; 4];
            // SAFETY: as above; the store is unaligned.
            unsafe { _mm256_storeu_pd(a.as_mut_ptr(), self.0) };
            a
        }
        #[inline(always)]
        fn lane(self, l: usize) -> f64 {
            self.to_array()[l]
        }
        #[inline(always)]
        fn set_lane(&mut self, l: usize, x: f64) {
            let mut a = self.to_array();
            a[l] = x;
            *self = F4::from_array(a);
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
        fn xor(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_xor_pd(self.0, other.0) })
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
        /// Lane masks of `self < other` (false with a NaN, as `<`).
        #[inline(always)]
        fn lt(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_LT_OQ>(self.0, other.0) })
        }
        /// `self <= other` (false with a NaN).
        #[inline(always)]
        fn le(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_LE_OQ>(self.0, other.0) })
        }
        /// `self > other` (false with a NaN).
        #[inline(always)]
        fn gt(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_GT_OQ>(self.0, other.0) })
        }
        /// `self >= other` (false with a NaN).
        #[inline(always)]
        fn ge(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_GE_OQ>(self.0, other.0) })
        }
        /// `self != other` (true with a NaN, as `!=`).
        #[inline(always)]
        fn ne(self, other: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_cmp_pd::<_CMP_NEQ_UQ>(self.0, other.0) })
        }
        /// Lanes where `self` is finite (|x| < ∞ is false for ±∞ and NaN).
        #[inline(always)]
        fn finite(self) -> F4 {
            self.abs().lt(F4::splat(f64::INFINITY))
        }
        /// `if mask { self } else { other }` per lane.
        #[inline(always)]
        fn select(mask: F4, yes: F4, no: F4) -> F4 {
            // SAFETY: as above.
            F4(unsafe { _mm256_blendv_pd(no.0, yes.0, mask.0) })
        }
        /// `if mask { self } else { +0.0 }` per lane.
        #[inline(always)]
        fn or_zero(self, mask: F4) -> F4 {
            self & mask
        }
        /// One bit per lane of a mask.
        #[inline(always)]
        fn bits(self) -> u32 {
            // SAFETY: as above.
            unsafe { _mm256_movemask_pd(self.0) as u32 }
        }
    }

    #[derive(Clone, Copy)]
    struct V3 {
        x: F4,
        y: F4,
        z: F4,
    }

    impl V3 {
        #[inline(always)]
        fn zero() -> V3 {
            V3 {
                x: F4::zero(),
                y: F4::zero(),
                z: F4::zero(),
            }
        }
        #[inline(always)]
        fn add(self, o: V3) -> V3 {
            V3 {
                x: self.x + o.x,
                y: self.y + o.y,
                z: self.z + o.z,
            }
        }
        #[inline(always)]
        fn scale(self, s: F4) -> V3 {
            V3 {
                x: self.x * s,
                y: self.y * s,
                z: self.z * s,
            }
        }
        /// nalgebra's cross product, operation for operation.
        #[inline(always)]
        fn cross(self, b: V3) -> V3 {
            V3 {
                x: self.y * b.z - self.z * b.y,
                y: self.z * b.x - self.x * b.z,
                z: self.x * b.y - self.y * b.x,
            }
        }
        #[inline(always)]
        fn select(mask: F4, yes: V3, no: V3) -> V3 {
            V3 {
                x: F4::select(mask, yes.x, no.x),
                y: F4::select(mask, yes.y, no.y),
                z: F4::select(mask, yes.z, no.z),
            }
        }
        #[inline(always)]
        fn get(&self, l: usize) -> Vector3<f64> {
            Vector3::new(self.x.lane(l), self.y.lane(l), self.z.lane(l))
        }
        #[inline(always)]
        fn set(&mut self, l: usize, v: &Vector3<f64>) {
            self.x.set_lane(l, v.x);
            self.y.set_lane(l, v.y);
            self.z.set_lane(l, v.z);
        }
    }

    /// Each lane's constants (lanes may come from different parameters, e.g. in a map
    /// over the stiffness), as the scalar path derives them.
    #[derive(Clone, Copy)]
    struct LaneConstants {
        dt: F4,
        mass: F4,
        weight_z: F4,
        /// The kick of a step in flight, `Simulation`'s quotients with every force +0.0.
        flight_kick: V3,
        stiffness: F4,
        damping: F4,
        friction: F4,
        /// `0.5·M`, `M·g`, `0.5·k`: the energy's leading products, grouped as the scalar
        /// path groups them (left to right).
        half_mass: F4,
        mass_gravity: F4,
        half_stiffness: F4,
        half_size: F4,
        /// Point-mass energy: `0.5·m`, `m·g`, `M·g·a`.
        half_corner_mass: F4,
        corner_mass_gravity: F4,
        mass_gravity_half_size: F4,
        /// The stopping rule's thresholds (`stopping::StopRule`).
        energy_threshold: F4,
        kinetic_threshold: F4,
        runaway: F4,
        max_steps: F4,
        /// Lanes on the whole-die-norm friction law / on the point-mass stop energy.
        whole_die_norm: F4,
        point_masses: F4,
    }

    /// Four rolls in structure-of-arrays form.
    struct Lanes {
        position: V3,
        velocity: V3,
        angular_momentum: V3,
        angular_velocity: V3,
        /// Row-major step rotation; meaningful in lanes of `rotating`.
        rotation: [F4; 9],
        rotating: F4,
        offsets: [V3; 8],
        forces: [V3; 8],
        depths: [F4; 8],
        /// Bit k: corner k is below the ground in some lane. A corner outside it has +0.0
        /// depth and force in every lane, and the sums below skip it (see [`Lanes::step`]).
        touching_corners: u8,
        in_contact: F4,
        time_s: F4,
        /// Steps taken, as exact whole numbers.
        step: F4,
        c: LaneConstants,
        /// Lanes holding a roll that has not ended.
        live: F4,
        /// Per lane: the roll's index and its `Simulation`, which the lane's state is stored
        /// back into for the end-of-step decision and the result.
        rolls: [Option<(usize, u8, Simulation)>; LANES],
        /// Per lane: inertia and Δt for the spin rebuild.
        inertia: [f64; LANES],
        dt: [f64; LANES],
    }

    impl Lanes {
        #[inline(always)]
        fn new() -> Lanes {
            let z = F4::zero();
            Lanes {
                position: V3::zero(),
                velocity: V3::zero(),
                angular_momentum: V3::zero(),
                angular_velocity: V3::zero(),
                rotation: [z; 9],
                rotating: z,
                offsets: [V3::zero(); 8],
                forces: [V3::zero(); 8],
                depths: [z; 8],
                touching_corners: 0,
                in_contact: z,
                time_s: z,
                step: z,
                c: LaneConstants {
                    dt: z,
                    mass: F4::splat(1.0),
                    weight_z: z,
                    flight_kick: V3::zero(),
                    stiffness: z,
                    damping: z,
                    friction: z,
                    half_mass: z,
                    mass_gravity: z,
                    half_stiffness: z,
                    half_size: z,
                    half_corner_mass: z,
                    corner_mass_gravity: z,
                    mass_gravity_half_size: z,
                    energy_threshold: z,
                    kinetic_threshold: z,
                    runaway: z,
                    max_steps: z,
                    whole_die_norm: z,
                    point_masses: z,
                },
                live: z,
                rolls: [None, None, None, None],
                inertia: [1.0; LANES],
                dt: [0.0; LANES],
            }
        }

        /// Puts roll `index` into lane `l`, in the state `Simulation` starts it in.
        #[inline(always)]
        fn load(&mut self, l: usize, index: usize, params: &Params, initial: &InitialCondition) {
            let sim = Simulation::for_outcome(params, initial);
            let s = &sim.state;
            self.position.set(l, &s.position);
            self.velocity.set(l, &s.velocity);
            self.angular_momentum.set(l, &s.angular_momentum);
            self.angular_velocity.set(l, &sim.angular_velocity);
            self.set_rotation(l, sim.step_rotation.as_ref());
            for k in 0..8 {
                self.offsets[k].set(l, &s.corner_offsets[k]);
                self.forces[k].set(l, &s.corner_forces[k]);
                self.depths[k].set_lane(l, s.corner_depths[k]);
            }
            set_mask(&mut self.in_contact, l, sim.in_contact);
            self.touching_corners = (0..8)
                .filter(|&k| self.depths[k].gt(F4::zero()).bits() != 0)
                .fold(0, |bits, k| bits | 1 << k);
            self.time_s.set_lane(l, s.time_s);
            self.step.set_lane(l, s.step as f64);
            let (mass, gravity) = (params.total_mass(), params.world.gravity);
            let (a, m) = (params.die.half_size, params.die.corner_mass);
            let c = &mut self.c;
            c.dt.set_lane(l, params.integrator.dt);
            c.mass.set_lane(l, mass);
            c.weight_z.set_lane(l, mass * -gravity);
            let (dt, zero) = (params.integrator.dt, 0.0);
            let kick = Vector3::new(
                (zero / mass) * dt,
                (zero / mass) * dt,
                ((zero + mass * -gravity) / mass) * dt,
            );
            c.flight_kick.set(l, &kick);
            c.stiffness.set_lane(l, params.ground.stiffness);
            c.damping.set_lane(l, params.ground.damping);
            c.friction.set_lane(l, params.ground.friction);
            c.half_mass.set_lane(l, 0.5 * mass);
            c.mass_gravity.set_lane(l, mass * gravity);
            c.half_stiffness.set_lane(l, 0.5 * params.ground.stiffness);
            c.half_size.set_lane(l, a);
            c.half_corner_mass.set_lane(l, 0.5 * m);
            c.corner_mass_gravity.set_lane(l, m * gravity);
            c.mass_gravity_half_size.set_lane(l, mass * gravity * a);
            let rule = sim.stop_rule();
            c.energy_threshold.set_lane(l, rule.energy_threshold);
            c.kinetic_threshold.set_lane(l, rule.kinetic_threshold);
            c.runaway.set_lane(l, sim.runaway_energy);
            c.max_steps.set_lane(l, params.max_steps() as f64);
            let whole = params.ground.friction_law == FrictionLaw::WholeDieNorm;
            set_mask(&mut c.whole_die_norm, l, whole);
            let point = params.integrator.stop_energy == StopEnergy::PointMasses;
            set_mask(&mut c.point_masses, l, point);
            self.inertia[l] = params.inertia();
            self.dt[l] = params.integrator.dt;
            set_mask(&mut self.live, l, true);
            let start_face = face_most_nearly_up(&s.corner_offsets);
            self.rolls[l] = Some((index, start_face, sim));
        }

        /// Empties lane `l` for good: a still die high above the ground without gravity, so
        /// it never touches and costs the other lanes nothing (it turns by the identity).
        fn park(&mut self, l: usize) {
            set_mask(&mut self.live, l, false);
            set_mask(&mut self.in_contact, l, false);
            self.set_rotation(l, Some(&Matrix3::identity()));
            self.position.set(l, &Vector3::new(0.0, 0.0, 1e9));
            self.velocity.set(l, &Vector3::zeros());
            self.c.weight_z.set_lane(l, 0.0);
            self.c.flight_kick.set(l, &Vector3::zeros());
            for k in 0..8 {
                self.forces[k].set(l, &Vector3::zeros());
                self.depths[k].set_lane(l, 0.0);
            }
        }

        #[inline(always)]
        fn set_rotation(&mut self, l: usize, m: Option<&Matrix3<f64>>) {
            set_mask(&mut self.rotating, l, m.is_some());
            if let Some(m) = m {
                for i in 0..3 {
                    for j in 0..3 {
                        self.rotation[3 * i + j].set_lane(l, m[(i, j)]);
                    }
                }
            }
        }

        /// Stores lane `l`'s state back into its roll's `Simulation`.
        #[inline(always)]
        fn store(&mut self, l: usize) -> &mut Simulation {
            let (_, _, sim) = self.rolls[l].as_mut().expect("a live lane holds a roll");
            let s = &mut sim.state;
            s.position = self.position.get(l);
            s.velocity = self.velocity.get(l);
            s.angular_momentum = self.angular_momentum.get(l);
            for k in 0..8 {
                s.corner_offsets[k] = self.offsets[k].get(l);
                s.corner_forces[k] = self.forces[k].get(l);
                s.corner_depths[k] = self.depths[k].lane(l);
            }
            s.time_s = self.time_s.lane(l);
            s.step = self.step.lane(l) as u64;
            sim.angular_velocity = self.angular_velocity.get(l);
            sim.in_contact = self.in_contact.bits() & (1 << l) != 0;
            // The step rotation is not stored: nothing after the end reads it.
            sim
        }

        /// One step of every lane: the scalar [`Simulation::step`] in vector form.
        #[inline(always)]
        fn step(&mut self) {
            let c = self.c;
            let contact_bits = self.in_contact.bits();
            let touching = self.touching_corners;
            // 1. kick. Out of contact every force is +0.0 and each lane's kick is its flight
            // constant, as in the scalar step. Skipping corners whose force is +0.0 in every
            // lane keeps the scalar's sum bit for bit: adding +0.0 only turns a −0.0 into
            // +0.0, and doing that once at the end gives the same as anywhere in between.
            if contact_bits != 0 {
                let mut f: Option<V3> = None;
                for k in (0..8).filter(|k| touching & (1 << k) != 0) {
                    f = Some(f.map_or(self.forces[k], |f| f.add(self.forces[k])));
                }
                let f = f.unwrap_or_else(V3::zero);
                let force = if touching != 0xff { f.add(V3::zero()) } else { f };
                // A lane in flight among them gets its flight constant this way too: its
                // forces are +0.0, so these are the very quotients the constant holds.
                let v = &mut self.velocity;
                v.x = v.x + (force.x / c.mass) * c.dt;
                v.y = v.y + (force.y / c.mass) * c.dt;
                v.z = v.z + ((force.z + c.weight_z) / c.mass) * c.dt;
            } else {
                self.velocity = self.velocity.add(c.flight_kick);
            }
            // 2. drift.
            self.position = self.position.add(self.velocity.scale(c.dt));
            // 3. torque and L, then 4. the spin, in lanes that touched the ground.
            if contact_bits != 0 {
                // The scalar sum starts from +0.0, so a skipped corner's ±0.0 term changes
                // nothing (the offsets are finite: a lane ends as soon as they are not).
                let mut torque = V3::zero();
                for k in (0..8).filter(|k| touching & (1 << k) != 0) {
                    torque = torque.add(self.offsets[k].cross(self.forces[k]));
                }
                let l_new = self.angular_momentum.add(torque.scale(c.dt));
                self.angular_momentum = if contact_bits == 0b1111 {
                    l_new
                } else {
                    V3::select(self.in_contact, l_new, self.angular_momentum)
                };
                self.respin(contact_bits);
            }
            // 5. rotate the corner rows, each entry (a₁b₁ + a₂b₂) + a₃b₃.
            // Parked lanes turn too (by the identity), so the usual case is all four lanes
            // turning and the rows are stored whole: a per-lane select against memory
            // compiles to masked stores, which are slow.
            let rotating = self.rotating.bits();
            if rotating != 0 {
                let m = &self.rotation;
                for r in &mut self.offsets {
                    let turned = V3 {
                        x: (r.x * m[0] + r.y * m[3]) + r.z * m[6],
                        y: (r.x * m[1] + r.y * m[4]) + r.z * m[7],
                        z: (r.x * m[2] + r.y * m[5]) + r.z * m[8],
                    };
                    *r = if rotating == 0b1111 {
                        turned
                    } else {
                        V3::select(self.rotating, turned, *r)
                    };
                }
            }
            // 6. forces at the new state.
            self.update_forces();
            // 7. the clock.
            self.time_s = self.time_s + c.dt;
            self.step = self.step + F4::splat(1.0);
        }

        /// ω and the step rotation rebuilt by [`spin`] in the lanes of `lanes`. The lanes
        /// are gathered into plain arrays and each vector is loaded once at the end: writing
        /// one lane at a time into a vector would stall on every write.
        #[inline(always)]
        fn respin(&mut self, lanes: u32) {
            let w = &self.angular_velocity;
            let mut omega = [w.x.to_array(), w.y.to_array(), w.z.to_array()];
            let mut m: [[f64; 4]; 9] = std::array::from_fn(|e| self.rotation[e].to_array());
            let l = &self.angular_momentum;
            let momentum = [l.x.to_array(), l.y.to_array(), l.z.to_array()];
            let mut rotating = self.rotating.bits();
            for lane in (0..LANES).filter(|lane| lanes & (1 << lane) != 0) {
                let l = Vector3::new(momentum[0][lane], momentum[1][lane], momentum[2][lane]);
                let (w, rotation) = spin(&l, self.inertia[lane], self.dt[lane]);
                for i in 0..3 {
                    omega[i][lane] = w[i];
                }
                match rotation {
                    Some(r) => {
                        rotating |= 1 << lane;
                        for i in 0..3 {
                            for j in 0..3 {
                                m[3 * i + j][lane] = r[(i, j)];
                            }
                        }
                    }
                    None => rotating &= !(1 << lane),
                }
            }
            self.angular_velocity = V3 {
                x: F4::from_array(omega[0]),
                y: F4::from_array(omega[1]),
                z: F4::from_array(omega[2]),
            };
            self.rotation = m.map(F4::from_array);
            self.rotating = F4::from_bits(rotating);
        }

        #[inline(always)]
        fn corner_velocity(&self, r: &V3) -> V3 {
            let (v, w) = (&self.velocity, &self.angular_velocity);
            V3 {
                x: v.x + (r.z * w.y - r.y * w.z),
                y: v.y + (r.x * w.z - r.z * w.x),
                z: v.z + (r.y * w.x - r.x * w.y),
            }
        }

        #[inline(always)]
        fn update_forces(&mut self) {
            let c = self.c;
            let z0 = self.position.z;
            let zero = F4::zero();
            let mut touching = [zero; 8];
            let mut any = zero;
            for (k, t) in touching.iter_mut().enumerate() {
                let z = self.offsets[k].z + z0;
                *t = z.lt(zero);
                self.depths[k] = (-z).or_zero(*t);
                any = any | *t;
            }
            // Lanes that neither touch now nor did before keep their +0.0 forces; a lane that
            // just left the ground gets +0.0 from the masks below.
            if (any | self.in_contact).bits() == 0 {
                return;
            }
            self.in_contact = any;
            let laws = c.whole_die_norm.bits();
            let per_corner_lanes = laws != 0b1111;
            let whole_lanes = laws != 0;
            let mut touching_corners = 0u8;
            for (k, t) in touching.iter().enumerate() {
                if t.bits() != 0 {
                    touching_corners |= 1 << k;
                }
            }
            let previous = std::mem::replace(&mut self.touching_corners, touching_corners);
            for k in (0..8).filter(|k| (previous & !touching_corners) & (1 << k) != 0) {
                self.forces[k] = V3::zero();
            }
            // The whole-die norm needs every corner's velocity, the per-corner law only
            // those of corners that touch.
            let norm = if whole_lanes {
                let (mut a, mut b, mut cc) = (zero, zero, zero);
                for r in &self.offsets {
                    let uk = self.corner_velocity(r);
                    a = a + uk.x * uk.x;
                    b = b + uk.x * uk.y;
                    cc = cc + uk.y * uk.y;
                }
                let half_diff = (a - cc) / F4::splat(2.0);
                ((a + cc) / F4::splat(2.0) + (half_diff * half_diff + b * b).sqrt()).sqrt()
            } else {
                zero
            };
            let norm_nonzero = norm.ne(zero);
            for k in (0..8).filter(|k| touching_corners & (1 << k) != 0) {
                let uk = self.corner_velocity(&self.offsets[k]);
                let normal = self.depths[k] * c.stiffness;
                let vertical = normal * (F4::splat(1.0) - c.damping * uk.z);
                let (mut fx, mut fy) = (zero, zero);
                if per_corner_lanes {
                    let slip = (uk.x * uk.x + uk.y * uk.y).sqrt();
                    let sliding = slip.gt(zero);
                    let scale = -(c.friction * vertical.abs());
                    fx = (scale * (uk.x / slip)).or_zero(sliding);
                    fy = (scale * (uk.y / slip)).or_zero(sliding);
                }
                if whole_lanes {
                    let wx = (-((uk.x / norm) * vertical) * c.friction).or_zero(norm_nonzero);
                    let wy = (-((uk.y / norm) * vertical) * c.friction).or_zero(norm_nonzero);
                    fx = F4::select(c.whole_die_norm, wx, fx);
                    fy = F4::select(c.whole_die_norm, wy, fy);
                }
                self.forces[k] = V3 {
                    x: fx.or_zero(touching[k]),
                    y: fy.or_zero(touching[k]),
                    z: vertical.or_zero(touching[k]),
                };
            }
        }

        /// Lanes whose roll may end at this state: a superset of those where
        /// [`Simulation::check_end`] ends it, computed from the same energies bit for bit,
        /// so a lane left out surely goes on. The decision itself is the scalar one.
        #[inline(always)]
        fn may_end(&self) -> u32 {
            let c = &self.c;
            let zero = F4::zero();
            let (v, w, l) = (&self.velocity, &self.angular_velocity, &self.angular_momentum);
            let translational = c.half_mass * ((v.x * v.x + v.y * v.y) + v.z * v.z);
            let rotational = F4::splat(0.5) * ((w.x * l.x + w.y * l.y) + w.z * l.z);
            let gravitational = c.mass_gravity * (self.position.z - c.half_size);
            let mut elastic = zero;
            // Terms are ≥ +0.0, so leaving out the +0.0 of corners that touch nowhere is exact.
            if self.in_contact.bits() != 0 {
                for k in (0..8).filter(|k| self.touching_corners & (1 << k) != 0) {
                    let d = self.depths[k];
                    elastic = elastic + (c.half_stiffness * d) * d;
                }
            }
            let elastic = elastic.or_zero(self.in_contact);
            let kinetic = translational + rotational;
            let potential = gravitational + elastic;
            let rigid = (kinetic + gravitational) + elastic;
            let mut finite = rigid.finite();
            let p = &self.position;
            let v = &self.velocity;
            let mut sum = (p.x + p.y) + (p.z + v.x) + (v.y + v.z);
            for r in &self.offsets {
                sum = sum + (r.x + r.y) + r.z;
            }
            // A sum of finite values can overflow to ±∞, which only flags a lane for the
            // exact check; a NaN or ∞ term always makes the sum non-finite.
            finite = finite & sum.finite();
            let (stop, stop_kinetic) = if c.point_masses.bits() != 0 {
                let (point_kinetic, point_total) = self.point_mass_parts();
                (
                    F4::select(c.point_masses, point_total, rigid),
                    F4::select(c.point_masses, point_kinetic, kinetic),
                )
            } else {
                (rigid, kinetic)
            };
            // `stopping::settles`, comparison for comparison.
            let settles = stop.le(c.energy_threshold)
                & stop_kinetic.le(c.kinetic_threshold)
                & potential.le(c.energy_threshold);
            let ends = !finite | rigid.gt(c.runaway) | settles | self.step.ge(c.max_steps);
            (ends & self.live).bits()
        }

        /// The authors' point-mass energy as `(kinetic, total)`, in vector form.
        #[inline(always)]
        fn point_mass_parts(&self) -> (F4, F4) {
            let c = &self.c;
            let u: [V3; 8] = std::array::from_fn(|k| self.corner_velocity(&self.offsets[k]));
            let mut kinetic = F4::zero();
            for uk in &u {
                kinetic = kinetic + uk.x * uk.x;
            }
            for uk in &u {
                kinetic = kinetic + uk.y * uk.y;
            }
            for uk in &u {
                kinetic = kinetic + uk.z * uk.z;
            }
            let (mut heights, mut ground) = (F4::zero(), F4::zero());
            for k in 0..8 {
                heights = heights + (self.offsets[k].z + self.position.z);
                ground = ground + self.depths[k] * self.forces[k].z;
            }
            let kinetic = c.half_corner_mass * kinetic;
            let total = kinetic + c.corner_mass_gravity * heights + F4::splat(0.5) * ground
                - c.mass_gravity_half_size;
            (kinetic, total)
        }
    }

    fn set_mask(mask: &mut F4, l: usize, on: bool) {
        let mut bits = mask.bits();
        if on {
            bits |= 1 << l;
        } else {
            bits &= !(1 << l);
        }
        *mask = F4::from_bits(bits);
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
        let mut lanes = Lanes::new();
        let mut next = 0;
        for l in 0..LANES.min(count) {
            let (params, initial) = setup(next);
            lanes.load(l, next, &params, &initial);
            next += 1;
        }
        let mut since_check = 0;
        while lanes.live.bits() != 0 {
            lanes.step();
            let mut ending = lanes.may_end();
            while ending != 0 {
                let l = ending.trailing_zeros() as usize;
                ending &= ending - 1;
                let sim = lanes.store(l);
                let Some(outcome) = sim.check_end() else { continue };
                sim.set_outcome(outcome);
                let (index, start_face, sim) = lanes.rolls[l].take().expect("a live lane holds a roll");
                done(LaneResult {
                    index,
                    outcome,
                    start_face,
                    state: sim.state(),
                });
                if next < count {
                    let (params, initial) = setup(next);
                    lanes.load(l, next, &params, &initial);
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
