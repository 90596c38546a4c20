//! The paper's step, written once over a lane type: the scalar engine runs it on `f64`
//! (one roll), the lane engine on a 4-lane AVX2 vector (four rolls side by side).
//!
//! Bit identity between the two widths rests on three facts: every operation used here
//! (`+ − × ÷ √`, `abs`, negation, comparisons) is exactly rounded, or exact, in both
//! widths; Rust never fuses a multiply and an add; and where one lane's value must stay
//! +0.0 (a corner above the ground, a roll in flight) the kernel selects +0.0 rather than
//! computing a product that might be −0.0. So a lane of the vector does the scalar roll's
//! arithmetic operation for operation, and both reproduce the authors' reference
//! trajectories (crates/physics/tests/data/reference/README.md §2 and §9: sums in corner
//! order, divisions where they divided).
//!
//! Two stages run per roll in scalar code whatever the width, each for a reason given where
//! it happens: the spin (libm's `sin`/`cos`, [`super::spin`]) and, only for a loaded die
//! near rest, the stopping rule of the face it lies on.

use super::contact::{Law, Touch, corners};
use super::energy::Energy;
use super::initial::InitialCondition;
use super::lane::{
    Lane, add3, all_lanes, cross3, lane3, mask_of, put, put_mask, scale3, select3, set_bits, v3, zero3,
};
use super::mass::InertiaTensor;
use super::model::Body;
use super::params::{Params, StopEnergy};
use super::shape;
use super::spin::{free_turn, spin, spin_lanes, step_rotation};
use super::state::{State, contact_point, point_velocity};
use super::stopping::{StopRule, settles};
use nalgebra::{Matrix3, Vector3};

/// The bits of every one of `N` points.
#[inline(always)]
fn every_point<const N: usize>() -> u64 {
    if N >= 64 { u64::MAX } else { (1 << N) - 1 }
}

/// `Σ ρ_k × F_k` over the touching corners, in corner order from +0.0.
#[inline(always)]
fn torque<const ROUNDED: bool, L: Lane, const N: usize>(
    offsets: &[Vector3<L>; N],
    forces: &[Vector3<L>; N],
    touching: u64,
    radii: &[L; N],
) -> Vector3<L> {
    let mut torque = zero3();
    for k in corners::<N>(touching) {
        let arm = contact_point::<ROUNDED, L>(&offsets[k], radii[k]);
        torque = add3(&torque, &cross3(&arm, &forces[k]));
    }
    torque
}

/// The rigid-body energy terms, erg (docs/model.md, "Energy"), per lane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EnergyTerms<L> {
    pub(crate) translational: L,
    pub(crate) rotational: L,
    pub(crate) gravitational: L,
    pub(crate) elastic: L,
}

impl From<EnergyTerms<f64>> for Energy {
    fn from(e: EnergyTerms<f64>) -> Energy {
        Energy {
            translational: e.translational,
            rotational: e.rotational,
            gravitational: e.gravitational,
            elastic: e.elastic,
        }
    }
}

/// How each lane's roll ends at this state (at most one mask set per lane).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ends<M> {
    pub(crate) unstable: M,
    pub(crate) settled: M,
    pub(crate) timeout: M,
}

/// ω and the step rotation of one roll from its `spin_input`: the angular momentum of a
/// fair die (ω = L/I with its isotropic inertia, g·cm²), or the ω of a body whose inertia
/// turns with it (a loaded die's I(t)⁻¹·L, a general body's R·I⁻¹·Rᵀ·L), which
/// [`Kernel::respin`] computes in every lane at once and the rotation is built from as it
/// is (the program before the shared kernel divided it by an inertia of 1, which is exact).
#[inline(always)]
fn scalar_spin(
    spin_input: &Vector3<f64>,
    inertia: f64,
    dt: f64,
    turning: bool,
) -> (Vector3<f64>, Option<Matrix3<f64>>) {
    if turning {
        (*spin_input, step_rotation(spin_input, dt))
    } else {
        spin(spin_input, inertia, dt)
    }
}

/// The constants of one roll per lane, derived once from the parameters (each lane may come
/// from different parameters, e.g. in a map over the stiffness; every lane has the law `W`):
/// the body's, the law's and the stopping rule's, each in a part of its own.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Constants<L: Lane, W: Law, const N: usize = 8> {
    /// s, the step.
    pub(crate) dt: L,
    pub(crate) body: BodyConstants<L, N>,
    pub(crate) law: W::Constants<L>,
    pub(crate) stop: StopConstants<L>,
}

/// What the step needs of the body: its mass and weight, its inertia in the form its
/// rotation reads it, its contact points' rounding, and the energies it is measured by.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BodyConstants<L: Lane, const N: usize = 8> {
    /// g, the total mass `M`.
    pub(crate) mass: L,
    /// dyn, the weight's part along the table's normal (negative; `−M·g·cos θ` on a tilted
    /// table, whose law adds the part in its plane).
    pub(crate) weight_z: L,
    /// cm/s, the kick of a step in flight: the contact kick's quotients with every force
    /// +0.0, `((0 + W_z)/M)·Δt` and `((0 + W_x)/M)·Δt` (or `(0/M)·Δt` under a law whose
    /// weight is straight down), the same for every flight step of a run.
    pub(crate) flight_kick: Vector3<L>,
    /// `0.5·M`, `M·g_n`: the energy's leading products, grouped as the scalar formulas
    /// group them (left to right).
    pub(crate) half_mass: L,
    pub(crate) mass_gravity: L,
    /// cm, the height of the centre the potential is measured from (the cube's `a`).
    pub(crate) half_size: L,
    /// The fair die's point-mass energy: `0.5·m`, `m·g`, `M·g·a`.
    pub(crate) half_corner_mass: L,
    pub(crate) corner_mass_gravity: L,
    pub(crate) mass_gravity_half_size: L,
    /// A loaded die's point-mass energy: each corner's mass `m + Δm_k`, `g`, `M·g·a`.
    pub(crate) corner_masses: [L; N],
    pub(crate) gravity: L,
    pub(crate) loaded_mass_gravity_half_size: L,
    /// g·cm², the body's one isotropic inertia ([`Body::mean_inertia`]): the fair die's
    /// `ω = L/I` divides by it in both engines. With the uniform cube's mass `M_u` (g) and
    /// the extra mass at each corner (g) it also builds a loaded die's tensor, as `I_u`; a
    /// fair die's own values (no extra mass) in a fair lane, whose tensor is never used.
    pub(crate) uniform_inertia: L,
    pub(crate) uniform_mass: L,
    pub(crate) extra_masses: [L; 8],
    /// A general body's inverse inertia tensor about its centre of mass, body frame, by its
    /// upper triangle (1/(g·cm²)), and `1/(2·b_i)` (1/cm) to read its axes off the spheres
    /// ([`shape::angular_velocity`]).
    pub(crate) inverse_inertia: [L; 6],
    pub(crate) axis_scale: [L; 3],
    /// A body whose inertia is not isotropic ([`Body::principal_frame`]): `1/I_i` of its
    /// principal moments (1/(g·cm²)) and its principal axes in the body frame
    /// (`principal_axes[3j + i]`: body component `j` of axis `i`), which the splitting turns
    /// it about ([`free_turn`]); and the lanes that have one (a loaded cube's `axis_scale`
    /// is then `1/(2a)`).
    pub(crate) inverse_moments: [L; 3],
    pub(crate) principal_axes: [L; 9],
    /// cm, each contact point (contact-sphere centre) relative to the centre of mass along
    /// the principal axes: where the step places it once the axes have turned.
    pub(crate) principal_corners: [Vector3<L>; N],
    /// The points the body's axes are read off, `[o, x, y]`: its x axis along
    /// `(r_x − r_o)·s₀`, its y axis along `(r_y − r_o)·s₁` made normal to x ([`free_turn`]);
    /// a cube's corners 1, 5 and 3. The same in every lane of a vector (plain indices).
    pub(crate) frame: [usize; 3],
    pub(crate) split: L::Mask,
    /// cm, each point's rounding radius: its contact sphere's lowest point is this far below
    /// its centre (a box's corners all alike; a die's each its own).
    pub(crate) corner_radii: [L; N],
    /// Lanes with a loaded die; with a general body; whose inertia turns with the body
    /// (loaded or general: ω changes in flight too).
    pub(crate) loaded: L::Mask,
    pub(crate) shaped: L::Mask,
    pub(crate) turning: L::Mask,
    /// Lanes whose stopping rule depends on the face down: a loaded die's and a general
    /// body's (the box's turning lanes), and a body of points whose faces rest at different
    /// heights or hold it differently ([`crate::PointBody`]), whatever its spin.
    pub(crate) faced: L::Mask,
    /// Bit l: lane l's body has rounded corners. Plain bits, not a mask: the step asks
    /// only whether any lane has, and a sharp die's step should not pay for asking.
    pub(crate) rounded: u32,
}

/// The stopping rule's numbers (docs/model.md, "Stopping rule" and "Stability").
#[derive(Debug, Clone, Copy)]
pub(crate) struct StopConstants<L: Lane> {
    /// erg, the thresholds; for a body with a rule per face ([`BodyConstants::faced`]) the
    /// largest over its faces, which only screens (the rule of the face down decides).
    pub(crate) energy_threshold: L,
    pub(crate) kinetic_threshold: L,
    /// erg, a rigid-body energy above this is a runaway (fixed at t = 0).
    pub(crate) runaway: L,
    pub(crate) max_steps: L::Count,
    /// Lanes that stop on the authors' point-mass energy.
    pub(crate) point_masses: L::Mask,
}

impl<W: Law> Constants<f64, W> {
    /// The constants of `p` under the law `W`, with `runaway` still +∞ (it needs the initial
    /// energy).
    pub(crate) fn new(p: &Params, body: &Body) -> Self {
        let edge_energy = body.edge_energy();
        let rule = W::stop_rule(body.widest_stop_rule(), p, edge_energy);
        Constants {
            dt: p.integrator.dt,
            body: BodyConstants::new(p, body, W::gravity(p)),
            law: W::constants(p, body.mass(), edge_energy),
            stop: StopConstants {
                energy_threshold: rule.energy_threshold,
                kinetic_threshold: rule.kinetic_threshold,
                runaway: f64::INFINITY,
                max_steps: p.max_steps(),
                point_masses: p.integrator.stop_energy == StopEnergy::PointMasses,
            },
        }
    }
}

impl<W: Law, const N: usize> Constants<f64, W, N> {
    /// The constants of a body of `N` points with the body constants `body`, on `p`'s table
    /// under the law `W`, stopping by `rule` on a level table; `runaway` still +∞.
    pub(crate) fn with_body(
        p: &Params,
        body: BodyConstants<f64, N>,
        edge_energy: f64,
        rule: StopRule,
    ) -> Self {
        let rule = W::stop_rule(rule, p, edge_energy);
        Constants {
            dt: p.integrator.dt,
            law: W::constants(p, body.mass, edge_energy),
            body,
            stop: StopConstants {
                energy_threshold: rule.energy_threshold,
                kinetic_threshold: rule.kinetic_threshold,
                runaway: f64::INFINITY,
                max_steps: p.max_steps(),
                point_masses: false,
            },
        }
    }
}

impl<L: Lane, W: Law, const N: usize> Constants<L, W, N> {
    /// One roll's constants in every lane.
    pub(crate) fn splat(c: &Constants<f64, W, N>) -> Self {
        let s = &c.stop;
        Constants {
            dt: L::splat(c.dt),
            body: BodyConstants::splat(&c.body),
            law: W::splat(&c.law),
            stop: StopConstants {
                energy_threshold: L::splat(s.energy_threshold),
                kinetic_threshold: L::splat(s.kinetic_threshold),
                runaway: L::splat(s.runaway),
                max_steps: L::count_of(s.max_steps),
                point_masses: mask_of::<L>(s.point_masses),
            },
        }
    }

    /// One roll's constants into lane `l`.
    #[inline(always)]
    pub(crate) fn set_lane(&mut self, l: usize, from: &Constants<f64, W, N>) {
        put(&mut self.dt, l, from.dt);
        self.body.set_lane(l, &from.body);
        W::set_lane(&mut self.law, l, &from.law);
        let (s, f) = (&mut self.stop, &from.stop);
        put(&mut s.energy_threshold, l, f.energy_threshold);
        put(&mut s.kinetic_threshold, l, f.kinetic_threshold);
        put(&mut s.runaway, l, f.runaway);
        L::put_count(&mut s.max_steps, l, f.max_steps);
        put_mask::<L>(&mut s.point_masses, l, f.point_masses);
    }

    /// Lane `l` emptied for good: a still fair die without weight, so it never touches nor
    /// spins ([`BodyConstants::park`]).
    #[inline(always)]
    pub(crate) fn park(&mut self, l: usize) {
        self.body.park(l);
        W::park(&mut self.law, l);
    }
}

impl BodyConstants<f64> {
    /// `body`'s constants under `gravity` (cm/s², the table's frame).
    fn new(p: &Params, body: &Body, [gx, gy, gz]: [f64; 3]) -> Self {
        let shape = body.shape();
        let mass = body.mass();
        let gravity = p.world.gravity;
        let (dt, zero) = (p.integrator.dt, 0.0);
        let (weight_x, weight_y, weight_z) = (mass * gx, mass * gy, mass * gz);
        // A general body's potential is measured from its lowest rest height.
        let a = body.reference_height();
        let m = p.die.corner_mass;
        let (corner_masses, loaded_total) = match body {
            Body::LoadedCube(_, load) => load.point_masses(),
            Body::PaperCube(_) | Body::Shaped(_) => ([m; 8], mass),
        };
        let loaded = matches!(body, Body::LoadedCube(..));
        let principal = body.principal_frame();
        let axis_scale = match body {
            Body::Shaped(shape) => shape.axis_scale,
            Body::LoadedCube(cube, _) => [1.0 / (2.0 * cube.half_size()); 3],
            Body::PaperCube(_) => [0.0; 3],
        };
        BodyConstants {
            mass,
            weight_z,
            // `0 + 0` is the paper's `0`, so its kick keeps its bits.
            flight_kick: Vector3::new(
                ((zero + weight_x) / mass) * dt,
                ((zero + weight_y) / mass) * dt,
                ((zero + weight_z) / mass) * dt,
            ),
            half_mass: 0.5 * mass,
            // The potential of the normal weight; a tilted table's law adds its downhill part.
            mass_gravity: mass * -gz,
            half_size: a,
            half_corner_mass: 0.5 * m,
            corner_mass_gravity: m * gravity,
            mass_gravity_half_size: mass * gravity * a,
            corner_masses,
            gravity,
            loaded_mass_gravity_half_size: loaded_total * gravity * a,
            uniform_inertia: body.mean_inertia(),
            uniform_mass: 8.0 * m,
            extra_masses: p.die.extra_corner_mass,
            inverse_inertia: shape.map_or([0.0; 6], |s| s.inverse_inertia),
            axis_scale,
            inverse_moments: principal.map_or([0.0; 3], |(moments, _)| moments.map(|i| 1.0 / i).into()),
            principal_axes: principal.map_or([0.0; 9], |(_, axes)| {
                std::array::from_fn(|entry| axes[(entry / 3, entry % 3)])
            }),
            principal_corners: match principal {
                Some((_, axes)) => body
                    .start_offsets(&InitialCondition::default())
                    .map(|r| axes.transpose() * r),
                None => [Vector3::zeros(); 8],
            },
            frame: [0, 4, 2],
            split: principal.is_some(),
            corner_radii: [shape.map_or(0.0, |s| s.radius); 8],
            loaded,
            shaped: shape.is_some(),
            turning: loaded || shape.is_some(),
            faced: loaded || shape.is_some(),
            rounded: shape.is_some_and(|s| s.radius > 0.0) as u32,
        }
    }
}

impl<L: Lane, const N: usize> BodyConstants<L, N> {
    /// One roll's body in every lane.
    pub(crate) fn splat(c: &BodyConstants<f64, N>) -> Self {
        let s3 = |v: &Vector3<f64>| v3(L::splat(v.x), L::splat(v.y), L::splat(v.z));
        BodyConstants {
            mass: L::splat(c.mass),
            weight_z: L::splat(c.weight_z),
            flight_kick: s3(&c.flight_kick),
            half_mass: L::splat(c.half_mass),
            mass_gravity: L::splat(c.mass_gravity),
            half_size: L::splat(c.half_size),
            half_corner_mass: L::splat(c.half_corner_mass),
            corner_mass_gravity: L::splat(c.corner_mass_gravity),
            mass_gravity_half_size: L::splat(c.mass_gravity_half_size),
            corner_masses: c.corner_masses.map(L::splat),
            gravity: L::splat(c.gravity),
            loaded_mass_gravity_half_size: L::splat(c.loaded_mass_gravity_half_size),
            uniform_inertia: L::splat(c.uniform_inertia),
            uniform_mass: L::splat(c.uniform_mass),
            extra_masses: c.extra_masses.map(L::splat),
            inverse_inertia: c.inverse_inertia.map(L::splat),
            axis_scale: c.axis_scale.map(L::splat),
            inverse_moments: c.inverse_moments.map(L::splat),
            principal_axes: c.principal_axes.map(L::splat),
            principal_corners: c.principal_corners.each_ref().map(s3),
            frame: c.frame,
            split: mask_of::<L>(c.split),
            corner_radii: c.corner_radii.map(L::splat),
            loaded: mask_of::<L>(c.loaded),
            shaped: mask_of::<L>(c.shaped),
            turning: mask_of::<L>(c.turning),
            faced: mask_of::<L>(c.faced),
            rounded: if c.rounded != 0 { all_lanes::<L>() } else { 0 },
        }
    }

    /// One roll's body into lane `l`.
    #[inline(always)]
    fn set_lane(&mut self, l: usize, f: &BodyConstants<f64, N>) {
        assert_eq!(
            self.frame, f.frame,
            "the bodies of one vector read their axes alike"
        );
        put(&mut self.mass, l, f.mass);
        put(&mut self.weight_z, l, f.weight_z);
        put3(&mut self.flight_kick, l, &f.flight_kick);
        put(&mut self.half_mass, l, f.half_mass);
        put(&mut self.mass_gravity, l, f.mass_gravity);
        put(&mut self.half_size, l, f.half_size);
        put(&mut self.half_corner_mass, l, f.half_corner_mass);
        put(&mut self.corner_mass_gravity, l, f.corner_mass_gravity);
        put(&mut self.mass_gravity_half_size, l, f.mass_gravity_half_size);
        for corner in 0..8 {
            put(&mut self.extra_masses[corner], l, f.extra_masses[corner]);
        }
        for point in 0..N {
            put(&mut self.corner_masses[point], l, f.corner_masses[point]);
            put3(&mut self.principal_corners[point], l, &f.principal_corners[point]);
        }
        put(&mut self.gravity, l, f.gravity);
        put(
            &mut self.loaded_mass_gravity_half_size,
            l,
            f.loaded_mass_gravity_half_size,
        );
        put(&mut self.uniform_inertia, l, f.uniform_inertia);
        put(&mut self.uniform_mass, l, f.uniform_mass);
        for e in 0..6 {
            put(&mut self.inverse_inertia[e], l, f.inverse_inertia[e]);
        }
        for axis in 0..3 {
            put(&mut self.axis_scale[axis], l, f.axis_scale[axis]);
            put(&mut self.inverse_moments[axis], l, f.inverse_moments[axis]);
        }
        for e in 0..9 {
            put(&mut self.principal_axes[e], l, f.principal_axes[e]);
        }
        put_mask::<L>(&mut self.split, l, f.split);
        for point in 0..N {
            put(&mut self.corner_radii[point], l, f.corner_radii[point]);
        }
        put_mask::<L>(&mut self.loaded, l, f.loaded);
        put_mask::<L>(&mut self.shaped, l, f.shaped);
        put_mask::<L>(&mut self.turning, l, f.turning);
        put_mask::<L>(&mut self.faced, l, f.faced);
        self.rounded = (self.rounded & !(1 << l)) | (f.rounded << l);
    }

    /// Lane `l` as a still fair die without weight: it never touches nor spins and costs the
    /// other lanes nothing.
    #[inline(always)]
    fn park(&mut self, l: usize) {
        put(&mut self.weight_z, l, 0.0);
        put3(&mut self.flight_kick, l, &Vector3::zeros());
        put_mask::<L>(&mut self.loaded, l, false);
        put_mask::<L>(&mut self.shaped, l, false);
        self.rounded &= !(1 << l);
        put_mask::<L>(&mut self.turning, l, false);
        put_mask::<L>(&mut self.faced, l, false);
        put_mask::<L>(&mut self.split, l, false);
        for point in 0..N {
            put(&mut self.corner_radii[point], l, 0.0);
        }
    }
}

/// Sets lane `l` of a vector of lanes.
#[inline(always)]
pub(crate) fn put3<L: Lane>(v: &mut Vector3<L>, l: usize, x: &Vector3<f64>) {
    put(&mut v.x, l, x.x);
    put(&mut v.y, l, x.y);
    put(&mut v.z, l, x.z);
}

/// Calls the kernel makes into an engine's bookkeeping during a step; the energy ledger is
/// the one user, and a run that does not keep it passes [`NoHook`].
pub(crate) trait StepHook<L: Lane, W: Law, const N: usize, B: Faces<N>> {
    /// Before the kick, at the state the contact forces were computed from.
    fn before_kick(&mut self, kernel: &Kernel<L, W, N, B>);
    /// After the kick and the new ω, before the corners turn.
    fn after_spin(&mut self, kernel: &Kernel<L, W, N, B>);
}

/// No bookkeeping.
pub(crate) struct NoHook;

impl<L: Lane, W: Law, const N: usize, B: Faces<N>> StepHook<L, W, N, B> for NoHook {
    #[inline(always)]
    fn before_kick(&mut self, _: &Kernel<L, W, N, B>) {}
    #[inline(always)]
    fn after_spin(&mut self, _: &Kernel<L, W, N, B>) {}
}

/// What the engines ask of a body by the face it lies on, at its points' offsets (cm, world
/// frame, about the centre of mass): the stopping rule there (a loaded die's, a general
/// body's and an uneven die's depend on the face down; the end-of-step test asks in the lanes
/// of [`BodyConstants::faced`]), and the face up of a body at rest (the outcome).
pub(crate) trait Faces<const N: usize>: Copy + std::fmt::Debug {
    fn stop_rule_at(&self, offsets: &[Vector3<f64>; N]) -> StopRule;
    fn face_up_at_rest(&self, offsets: &[Vector3<f64>; N]) -> Option<u8>;
}

impl Faces<8> for Body {
    fn stop_rule_at(&self, offsets: &[Vector3<f64>; 8]) -> StopRule {
        Body::stop_rule_at(self, offsets)
    }

    fn face_up_at_rest(&self, offsets: &[Vector3<f64>; 8]) -> Option<u8> {
        Body::face_up_at_rest(self, offsets)
    }
}

/// One roll per lane, all on the contact law `W`, of a body of `N` contact points (`B` says
/// its stopping rule by the face down): the state plus everything the step needs.
#[derive(Debug, Clone)]
pub(crate) struct Kernel<L: Lane, W: Law, const N: usize = 8, B: Faces<N> = Body> {
    pub(crate) state: State<L, N>,
    /// The law's memory at each contact point.
    pub(crate) points: [W::Point<L>; N],
    /// rad/s, `I⁻¹·L`, kept in step with the angular momentum.
    pub(crate) angular_velocity: Vector3<L>,
    /// In lanes of [`Constants::split`]: the principal axes (world frame) this step's turn
    /// takes the body to, and `I⁻¹·L` there, which become the corners and `angular_velocity`
    /// once the hook has seen the step before the turn.
    pub(crate) turned_axes: [Vector3<L>; 3],
    pub(crate) turned_angular_velocity: Vector3<L>,
    /// Row-major step rotation applied to the corner rows; meaningful in lanes of
    /// `rotating` (ω ≠ 0). It depends on ω alone, so it is rebuilt only when ω changed.
    pub(crate) rotation: [L; 9],
    pub(crate) rotating: L::Mask,
    /// Lanes with a corner below the ground at the current state.
    pub(crate) in_contact: L::Mask,
    /// Bit k: corner k is below the ground in some lane. A corner outside it has +0.0
    /// depth and force in every lane, and the sums skip it (see [`Kernel::step`]).
    pub(crate) touching_corners: u64,
    pub(crate) c: Constants<L, W, N>,
    /// Each lane's body: what the end-of-step test asks for the stopping rule of the face
    /// down, and the outcome rule asks at the end.
    pub(crate) bodies: L::PerLane<B>,
}

impl<W: Law, const N: usize, B: Faces<N>> Kernel<f64, W, N, B> {
    /// This roll under the law `V` with the constants `c` (the ground changed mid-roll): the
    /// same state and motion, each point's memory forgotten; its forces are still the old
    /// law's until [`Kernel::update_forces`].
    pub(crate) fn under<V: Law>(&self, c: Constants<f64, V, N>, body: B) -> Kernel<f64, V, N, B> {
        Kernel {
            state: self.state.clone(),
            points: [V::free_point(); N],
            angular_velocity: self.angular_velocity,
            turned_axes: self.turned_axes,
            turned_angular_velocity: self.turned_angular_velocity,
            rotation: self.rotation,
            rotating: self.rotating,
            in_contact: self.in_contact,
            touching_corners: self.touching_corners,
            c,
            bodies: [body],
        }
    }

    /// The body `body` (its constants `c`) placed at `initial` with its points at
    /// `corner_offsets` (cm, world frame) and angular momentum `angular_momentum`, its spin
    /// and its forces computed.
    pub(crate) fn placed(
        c: Constants<f64, W, N>,
        body: B,
        initial: &InitialCondition,
        corner_offsets: [Vector3<f64>; N],
        angular_momentum: Vector3<f64>,
    ) -> Self {
        let state = State {
            position: Vector3::new(0.0, 0.0, initial.height),
            velocity: Vector3::from(initial.velocity),
            angular_momentum,
            corner_offsets,
            corner_forces: [Vector3::zeros(); N],
            corner_depths: [0.0; N],
            time_s: 0.0,
            step: 0,
        };
        let mut kernel = Kernel {
            state,
            points: [W::free_point(); N],
            angular_velocity: Vector3::zeros(),
            turned_axes: [Vector3::zeros(); 3],
            turned_angular_velocity: Vector3::zeros(),
            rotation: [0.0; 9],
            rotating: false,
            in_contact: false,
            touching_corners: 0,
            c,
            bodies: [body],
        };
        kernel.respin(1);
        kernel.update_forces();
        kernel
    }
}

impl<W: Law> Kernel<f64, W> {
    /// The die placed at `initial`, its spin and its forces computed (no range checks).
    pub(crate) fn new(params: &Params, initial: &InitialCondition) -> Self {
        let body = Body::new(params);
        let c = Constants::<f64, W>::new(params, &body);
        let corner_offsets = body.start_offsets(initial);
        let angular_momentum = body.initial_angular_momentum(initial, &corner_offsets);
        Kernel::placed(c, body, initial, corner_offsets, angular_momentum)
    }
}

impl<L: Lane, W: Law, const N: usize, B: Faces<N>> Kernel<L, W, N, B> {
    /// One roll's kernel in every lane (each lane is loaded before it steps, or parked).
    pub(crate) fn splat(first: &Kernel<f64, W, N, B>) -> Self {
        let s = &first.state;
        let s3 = |v: &Vector3<f64>| v3(L::splat(v.x), L::splat(v.y), L::splat(v.z));
        let mut points = [W::free_point::<L>(); N];
        for (point, from) in points.iter_mut().zip(&first.points) {
            for l in 0..L::WIDTH {
                W::set_point_lane(point, l, from);
            }
        }
        Kernel {
            state: State {
                position: s3(&s.position),
                velocity: s3(&s.velocity),
                angular_momentum: s3(&s.angular_momentum),
                corner_offsets: s.corner_offsets.each_ref().map(s3),
                corner_forces: s.corner_forces.each_ref().map(s3),
                corner_depths: s.corner_depths.map(L::splat),
                time_s: L::splat(s.time_s),
                step: L::count_of(s.step),
            },
            points,
            angular_velocity: s3(&first.angular_velocity),
            turned_axes: first.turned_axes.each_ref().map(s3),
            turned_angular_velocity: s3(&first.turned_angular_velocity),
            rotation: first.rotation.map(L::splat),
            rotating: mask_of::<L>(first.rotating),
            in_contact: mask_of::<L>(first.in_contact),
            touching_corners: first.touching_corners,
            c: Constants::splat(&first.c),
            bodies: L::per_lane(|_| first.bodies[0]),
        }
    }

    /// Puts the roll `from` into lane `l`, as it is.
    #[inline(always)]
    pub(crate) fn set_lane(&mut self, l: usize, from: &Kernel<f64, W, N, B>) {
        let s = &from.state;
        let to = &mut self.state;
        put3(&mut to.position, l, &s.position);
        put3(&mut to.velocity, l, &s.velocity);
        put3(&mut to.angular_momentum, l, &s.angular_momentum);
        for c in 0..N {
            put3(&mut to.corner_offsets[c], l, &s.corner_offsets[c]);
            put3(&mut to.corner_forces[c], l, &s.corner_forces[c]);
            put(&mut to.corner_depths[c], l, s.corner_depths[c]);
            W::set_point_lane(&mut self.points[c], l, &from.points[c]);
        }
        put(&mut to.time_s, l, s.time_s);
        L::put_count(&mut to.step, l, s.step);
        put3(&mut self.angular_velocity, l, &from.angular_velocity);
        put3(
            &mut self.turned_angular_velocity,
            l,
            &from.turned_angular_velocity,
        );
        for axis in 0..3 {
            put3(&mut self.turned_axes[axis], l, &from.turned_axes[axis]);
        }
        for e in 0..9 {
            put(&mut self.rotation[e], l, from.rotation[e]);
        }
        put_mask::<L>(&mut self.rotating, l, from.rotating);
        put_mask::<L>(&mut self.in_contact, l, from.in_contact);
        self.touching_corners = (0..N)
            .filter(|&c| L::bits(self.state.corner_depths[c].gt(L::zero())) != 0)
            .fold(0, |bits, c| bits | 1 << c);
        self.c.set_lane(l, &from.c);
        self.bodies.as_mut()[l] = from.bodies[0];
    }

    /// Lane `l`'s roll written into `to`, whose kernel it was loaded from.
    #[inline(always)]
    pub(crate) fn lane_into(&self, l: usize, to: &mut Kernel<f64, W, N, B>) {
        let (from, s) = (&self.state, &mut to.state);
        s.position = lane3(&from.position, l);
        s.velocity = lane3(&from.velocity, l);
        s.angular_momentum = lane3(&from.angular_momentum, l);
        for c in 0..N {
            s.corner_offsets[c] = lane3(&from.corner_offsets[c], l);
            s.corner_forces[c] = lane3(&from.corner_forces[c], l);
            s.corner_depths[c] = from.corner_depths[c].lane(l);
            to.points[c] = W::point_lane(&self.points[c], l);
        }
        s.time_s = from.time_s.lane(l);
        s.step = L::count_lane(from.step, l);
        to.angular_velocity = lane3(&self.angular_velocity, l);
        to.rotation = self.rotation.map(|e| e.lane(l));
        to.rotating = L::bits(self.rotating) & (1 << l) != 0;
        to.in_contact = L::bits(self.in_contact) & (1 << l) != 0;
        to.touching_corners = (0..N)
            .filter(|&c| s.corner_depths[c] > 0.0)
            .fold(0, |bits, c| bits | 1 << c);
    }

    /// Empties lane `l` for good: a still fair die high above the ground without weight, so
    /// it never touches nor spins and costs the other lanes nothing (it turns by the
    /// identity).
    #[inline(always)]
    pub(crate) fn park(&mut self, l: usize) {
        put_mask::<L>(&mut self.in_contact, l, false);
        put_mask::<L>(&mut self.rotating, l, true);
        for (e, entry) in self.rotation.iter_mut().enumerate() {
            put(entry, l, if e % 4 == 0 { 1.0 } else { 0.0 });
        }
        put3(&mut self.state.position, l, &Vector3::new(0.0, 0.0, 1e9));
        put3(&mut self.state.velocity, l, &Vector3::zeros());
        self.c.park(l);
        let neighbour = (l + 1) % L::WIDTH;
        self.bodies.as_mut()[l] = self.bodies.as_ref()[neighbour];
        for c in 0..N {
            put3(&mut self.state.corner_forces[c], l, &Vector3::zeros());
            put(&mut self.state.corner_depths[c], l, 0.0);
            W::set_point_lane(&mut self.points[c], l, &W::free_point());
        }
    }
}

impl<L: Lane, W: Law, const N: usize, B: Faces<N>> Kernel<L, W, N, B> {
    /// One step of Δt in every lane: kick → drift → L → ω → rotate → forces (docs/model.md,
    /// "One time step"), the law `W`'s kick and forces.
    #[inline(always)]
    pub(crate) fn step(&mut self, hook: &mut impl StepHook<L, W, N, B>) {
        // The constants this stage reads, copied out one by one: a copy of them all costs a
        // memcpy call per step.
        let c = &self.c;
        let b = &c.body;
        let (dt, mass, weight_z, flight_kick, turning) = (c.dt, b.mass, b.weight_z, b.flight_kick, b.turning);
        let rounded = b.rounded != 0;
        let contact_bits = L::bits(self.in_contact);
        let touching = self.touching_corners;
        hook.before_kick(self);
        let s = &mut self.state;
        // 1. kick: v ← v + ((ΣF + M·g)/M)·Δt, forces summed in corner order. Out of contact
        // every force is +0.0 and each lane's kick is its flight constant. Skipping corners
        // whose force is +0.0 in every lane keeps the corner-order sum bit for bit: adding
        // +0.0 only turns a −0.0 into +0.0, and doing that once at the end gives the same as
        // anywhere in between.
        if contact_bits != 0 {
            let mut f: Option<Vector3<L>> = None;
            for k in corners::<N>(touching) {
                f = Some(f.map_or(s.corner_forces[k], |f| add3(&f, &s.corner_forces[k])));
            }
            let f = f.unwrap_or_else(zero3);
            let force = if touching != every_point::<N>() {
                add3(&f, &zero3())
            } else {
                f
            };
            // A lane in flight among them gets its flight constant this way too: its
            // forces are +0.0, so these are the very quotients the constant holds.
            W::kick(&self.c.law, &mut s.velocity, &force, weight_z, mass, dt);
        } else {
            s.velocity = add3(&s.velocity, &flight_kick);
        }
        // 2. drift with the new velocity (semi-implicit Euler).
        s.position = add3(&s.position, &scale3(&s.velocity, dt));
        // 3. angular momentum from the torque of the forces at the old corner offsets. The
        // sum starts from +0.0, so a skipped corner's ±0.0 term changes nothing (the
        // offsets are finite: a roll ends as soon as they are not). A rounded body's force
        // acts at its contact sphere's lowest point.
        if contact_bits != 0 {
            let torque = if rounded {
                torque::<true, L, N>(&s.corner_offsets, &s.corner_forces, touching, &b.corner_radii)
            } else {
                torque::<false, L, N>(&s.corner_offsets, &s.corner_forces, touching, &b.corner_radii)
            };
            let l_new = add3(&s.angular_momentum, &scale3(&torque, dt));
            s.angular_momentum = if contact_bits == all_lanes::<L>() {
                l_new
            } else {
                select3(self.in_contact, &l_new, &s.angular_momentum)
            };
        }
        // 4. ω = I⁻¹·L and the rotation it implies, where L changed, and for a loaded die or
        // a general body every step: its inertia turns with it, so ω changes in flight too.
        let spinning = contact_bits | L::bits(turning);
        if spinning != 0 {
            self.respin(spinning);
        }
        hook.after_spin(self);
        // 5. rotate every corner row by |ω|·Δt about ω, each entry (a₁b₁ + a₂b₂) + a₃b₃ as
        // reference BLAS. A lane whose ω = 0 keeps its rows; where every lane turns the
        // rows are stored whole (a per-lane select against memory compiles to slow masked
        // stores).
        let rotating = L::bits(self.rotating);
        if rotating != 0 {
            let all = rotating == all_lanes::<L>();
            // The rotation copied out: read through `self`, the compiler reloaded its nine
            // entries for every row written (about a third more loads per step).
            let m = self.rotation;
            for r in &mut self.state.corner_offsets {
                let turned = v3(
                    (r.x * m[0] + r.y * m[3]) + r.z * m[6],
                    (r.x * m[1] + r.y * m[4]) + r.z * m[7],
                    (r.x * m[2] + r.y * m[5]) + r.z * m[8],
                );
                *r = if all {
                    turned
                } else {
                    select3(self.rotating, &turned, r)
                };
            }
        }
        // A body turned by the splitting: its corners along its turned principal axes, and
        // the ω of its new orientation.
        let split = L::bits(self.c.body.split);
        if split != 0 {
            let all = split == all_lanes::<L>();
            let [a, b, c] = self.turned_axes;
            for (r, p) in self
                .state
                .corner_offsets
                .iter_mut()
                .zip(&self.c.body.principal_corners)
            {
                let placed = v3(
                    (a.x * p.x + b.x * p.y) + c.x * p.z,
                    (a.y * p.x + b.y * p.y) + c.y * p.z,
                    (a.z * p.x + b.z * p.y) + c.z * p.z,
                );
                *r = if all {
                    placed
                } else {
                    select3(self.c.body.split, &placed, r)
                };
            }
            self.angular_velocity = if all {
                self.turned_angular_velocity
            } else {
                select3(
                    self.c.body.split,
                    &self.turned_angular_velocity,
                    &self.angular_velocity,
                )
            };
        }
        // 6. forces at the new state.
        self.update_forces();
        // 7. the clock.
        self.state.time_s = self.state.time_s + dt;
        self.state.step = L::count_up(self.state.step);
    }

    /// ω and the step rotation rebuilt in the lanes of `lanes`.
    ///
    /// A loaded die's ω = I(t)⁻¹·L (its tensor built from the current corner offsets and
    /// inverted) is computed in every lane at once, and so is the rotation but for its `sin`
    /// and `cos`: only libm's scalar calls give the bits the reference data and the scalar
    /// engine have (no vector sin/cos is correctly rounded, so a vector one would differ in
    /// the last bit), so those are taken per lane ([`spin_lanes`]).
    #[inline(always)]
    pub(crate) fn respin(&mut self, lanes: u32) {
        let split = L::bits(self.c.body.split) & lanes;
        if split != 0 {
            self.turn_freely(split);
        }
        let lanes = lanes & !split;
        if lanes == 0 {
            return;
        }
        let (c, dt) = (&self.c.body, self.c.dt);
        let loaded = L::bits(c.loaded) & lanes;
        let shaped = L::bits(c.shaped) & lanes;
        let mut spin_input = self.state.angular_momentum;
        // Only a cube is loaded or shaped (N = 8): its corners are the first 8 points.
        let cube = self.state.corner_offsets.first_chunk::<8>();
        if loaded != 0
            && let Some(corners) = cube
        {
            let tensor = InertiaTensor::new(c.uniform_inertia, c.uniform_mass, &c.extra_masses, corners);
            let w = tensor.angular_velocity(&self.state.angular_momentum);
            spin_input = select3(c.loaded, &w, &spin_input);
        }
        if shaped != 0
            && let Some(corners) = cube
        {
            let w = shape::angular_velocity(
                &c.inverse_inertia,
                &c.axis_scale,
                corners,
                &self.state.angular_momentum,
            );
            spin_input = select3(c.shaped, &w, &spin_input);
        }
        let loaded = loaded | shaped;
        if L::WIDTH == 1 {
            // One lane: the scalar spin, its branches taken rather than selected, and ω and
            // the rotation straight into place.
            let (w, rotation) = scalar_spin(
                &lane3(&spin_input, 0),
                c.uniform_inertia.lane(0),
                dt.lane(0),
                loaded != 0,
            );
            self.angular_velocity = v3(L::splat(w.x), L::splat(w.y), L::splat(w.z));
            if let Some(r) = &rotation {
                for i in 0..3 {
                    for j in 0..3 {
                        self.rotation[3 * i + j] = L::splat(r[(i, j)]);
                    }
                }
            }
            self.rotating = L::mask_from_bits(rotation.is_some() as u32);
            return;
        }
        // Several lanes: ω = L/I (a loaded or general body's ω is its tensor's already) and
        // the rotation in vector operations, only `sin` and `cos` per lane ([`spin_lanes`]).
        let (inertia, turning_lanes) = (c.uniform_inertia, c.turning);
        let divided = v3(
            spin_input.x / inertia,
            spin_input.y / inertia,
            spin_input.z / inertia,
        );
        let w = if loaded == 0 {
            divided
        } else {
            select3(turning_lanes, &spin_input, &divided)
        };
        let (nonzero, rotation) = spin_lanes(&w, dt, lanes);
        let update = L::mask_from_bits(lanes);
        let turn = update & nonzero;
        self.angular_velocity = select3(update, &w, &self.angular_velocity);
        for (old, new) in self.rotation.iter_mut().zip(rotation) {
            *old = L::select(turn, new, *old);
        }
        self.rotating = (self.rotating & !update) | turn;
    }

    /// ω and the step rotation in the lanes of `lanes`, all of [`Constants::split`]: the
    /// splitting's turn ([`free_turn`]) with this step's `L`, its ω before the turn now and
    /// the turned body's once the corners have turned ([`Kernel::step`]).
    #[inline(always)]
    fn turn_freely(&mut self, lanes: u32) {
        let c = &self.c.body;
        let turn = free_turn(
            &self.state.corner_offsets,
            (c.frame, &c.axis_scale),
            &c.principal_axes,
            &c.inverse_moments,
            &self.state.angular_momentum,
            self.c.dt,
            lanes,
        );
        let mask = L::mask_from_bits(lanes);
        if lanes == all_lanes::<L>() {
            self.angular_velocity = turn.before;
            self.turned_angular_velocity = turn.after;
            self.turned_axes = turn.axes;
        } else {
            self.angular_velocity = select3(mask, &turn.before, &self.angular_velocity);
            self.turned_angular_velocity = select3(mask, &turn.after, &self.turned_angular_velocity);
            for (old, new) in self.turned_axes.iter_mut().zip(&turn.axes) {
                *old = select3(mask, new, old);
            }
        }
        // Its corners are placed, not rotated.
        self.rotating = self.rotating & !mask;
    }

    /// Velocity of a corner, `u_k = v + ω × r_k`, cm/s, in the authors' operation order.
    #[inline(always)]
    pub(crate) fn corner_velocity(&self, r: &Vector3<L>) -> Vector3<L> {
        point_velocity(&self.state.velocity, &self.angular_velocity, r)
    }

    /// Recomputes every contact point's depth, force and memory at the current state, under
    /// the law `W`.
    #[inline(always)]
    pub(crate) fn update_forces(&mut self) {
        let (dt, rounded) = (self.c.dt, self.c.body.rounded != 0);
        W::forces(
            &self.c.law,
            dt,
            rounded,
            Touch {
                state: &mut self.state,
                angular_velocity: &self.angular_velocity,
                points: &mut self.points,
                in_contact: &mut self.in_contact,
                touching_corners: &mut self.touching_corners,
                radii: &self.c.body.corner_radii,
            },
        );
    }

    /// The rigid-body energy terms at the current state, erg: the weight's potential
    /// `M·g·(x.z − a)` as the law `W` has it (a tilted table's adds its downhill part).
    #[inline(always)]
    pub(crate) fn energy(&self) -> EnergyTerms<L> {
        let c = &self.c;
        let b = &c.body;
        let s = &self.state;
        let (v, w, l) = (&s.velocity, &self.angular_velocity, &s.angular_momentum);
        let mut elastic = L::zero();
        let half_stiffness = W::half_stiffness(&c.law);
        // Terms are ≥ +0.0, so leaving out the +0.0 of corners that touch nowhere is exact.
        if L::bits(self.in_contact) != 0 {
            for k in corners::<N>(self.touching_corners) {
                let d = s.corner_depths[k];
                elastic = elastic + (half_stiffness * d) * d;
            }
        }
        let normal = b.mass_gravity * (s.position.z - b.half_size);
        EnergyTerms {
            translational: b.half_mass * ((v.x * v.x + v.y * v.y) + v.z * v.z),
            // ω·L summed from +0.0 as nalgebra's dot product does (a −0.0 product first
            // becomes +0.0).
            rotational: L::splat(0.5) * (((L::zero() + w.x * l.x) + w.y * l.y) + w.z * l.z),
            gravitational: W::potential(&c.law, normal, &s.position),
            elastic: elastic.or_zero(self.in_contact),
        }
    }

    /// erg, the authors' point-mass energy as `(kinetic, total)`: the corners as 8 point
    /// masses and the ground term `½·Σ d_k·P_k` with the damped force (reference §2). The
    /// fair die sums column-major as the authors did (every x component, then y, then z);
    /// a loaded die weighs each corner's `|u_k|²` and height by its own mass.
    #[inline(always)]
    pub(crate) fn point_mass_parts(&self) -> (L, L) {
        let c = &self.c.body;
        let s = &self.state;
        let u: [Vector3<L>; N] = std::array::from_fn(|k| self.corner_velocity(&s.corner_offsets[k]));
        let mut ground = L::zero();
        for k in 0..N {
            ground = ground + s.corner_depths[k] * s.corner_forces[k].z;
        }
        let loaded = L::bits(c.loaded);
        let fair = if loaded != all_lanes::<L>() {
            let mut kinetic = L::zero();
            for uk in &u {
                kinetic = kinetic + uk.x * uk.x;
            }
            for uk in &u {
                kinetic = kinetic + uk.y * uk.y;
            }
            for uk in &u {
                kinetic = kinetic + uk.z * uk.z;
            }
            let mut heights = L::zero();
            for r in &s.corner_offsets {
                heights = heights + (r.z + s.position.z);
            }
            let kinetic = c.half_corner_mass * kinetic;
            let total =
                kinetic + c.corner_mass_gravity * heights + L::splat(0.5) * ground - c.mass_gravity_half_size;
            (kinetic, total)
        } else {
            (L::zero(), L::zero())
        };
        if loaded == 0 {
            return fair;
        }
        let (mut kinetic, mut heights) = (L::zero(), L::zero());
        for ((uk, r), &m) in u.iter().zip(&s.corner_offsets).zip(&c.corner_masses) {
            kinetic = kinetic + m * ((uk.x * uk.x + uk.y * uk.y) + uk.z * uk.z);
            heights = heights + m * (r.z + s.position.z);
        }
        let kinetic = L::splat(0.5) * kinetic;
        let total = kinetic + c.gravity * heights + L::splat(0.5) * ground - c.loaded_mass_gravity_half_size;
        (
            L::select(c.loaded, kinetic, fair.0),
            L::select(c.loaded, total, fair.1),
        )
    }

    /// How the roll in each lane ends at this state (docs/model.md, "Stopping rule" and
    /// "Stability"): unstable (not finite, or the energy ran away), settled, or out of time,
    /// in that precedence.
    ///
    /// The stopping rule is a conjunction of comparisons, so the cheap rigid-body potential
    /// is compared first: where no lane is below the threshold, the point-mass energy need
    /// not be summed nor a loaded die's face looked up.
    #[inline(always)]
    pub(crate) fn ends(&self) -> Ends<L::Mask> {
        let c = &self.c.stop;
        let e = self.energy();
        let kinetic = e.translational + e.rotational;
        let potential = e.gravitational + e.elastic;
        let rigid = (kinetic + e.gravitational) + e.elastic;
        let unstable = !(rigid.finite()
            & L::all_finite(
                &self.state.position,
                &self.state.velocity,
                &self.state.corner_offsets,
            ))
            | rigid.gt(c.runaway);
        let faced = self.c.body.faced;
        let low = potential.le(c.energy_threshold);
        let settled = if L::bits(low) == 0 {
            L::mask_from_bits(0)
        } else {
            let (stop, stop_kinetic) = if L::bits(c.point_masses) != 0 {
                let (point_kinetic, point_total) = self.point_mass_parts();
                (
                    L::select(c.point_masses, point_total, rigid),
                    L::select(c.point_masses, point_kinetic, kinetic),
                )
            } else {
                (rigid, kinetic)
            };
            let screened = settles(
                stop,
                stop_kinetic,
                potential,
                c.energy_threshold,
                c.kinetic_threshold,
            );
            let by_face = L::bits(screened & faced);
            if by_face == 0 {
                screened
            } else {
                // A loaded die's, a general body's or an uneven die's rule depends on the face
                // it lies on. Looking the face up is a per-roll table search, done only where
                // the widest rule passed.
                let (mut et, mut kt) = (c.energy_threshold.to_lanes(), c.kinetic_threshold.to_lanes());
                for lane in set_bits(by_face) {
                    let offsets = self.state.corner_offsets.each_ref().map(|r| lane3(r, lane));
                    let rule = self.bodies.as_ref()[lane].stop_rule_at(&offsets);
                    et.as_mut()[lane] = rule.energy_threshold;
                    kt.as_mut()[lane] = rule.kinetic_threshold;
                }
                settles(
                    stop,
                    stop_kinetic,
                    potential,
                    L::from_lanes(et),
                    L::from_lanes(kt),
                )
            }
        };
        let settled = W::settles(&self.c.law, settled & !unstable, kinetic);
        let timeout = L::count_reached(self.state.step, c.max_steps) & !unstable & !settled;
        Ends {
            unstable,
            settled,
            timeout,
        }
    }
}
