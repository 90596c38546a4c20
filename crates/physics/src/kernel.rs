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

use super::contact::{self, SpringFriction};
use super::initial::InitialCondition;
use super::lane::{Lane, set_bits};
use super::mass::InertiaTensor;
use super::model::Body;
use super::params::{ContactLaw, FrictionLaw, Params, StopEnergy};
use super::shape;
use super::spin::{free_turn, spin, spin_lanes, step_rotation};
use super::stopping::settles;
use nalgebra::{Matrix3, Vector2, Vector3};

/// Where a corner's contact force acts, relative to the centre of mass: a rounded body's
/// contact sphere's lowest point, the radius below its centre (lanes of a sharp body among
/// rounded ones have radius +0.0, and `z − 0` is `z`). `ROUNDED` is decided once per call of
/// the stage, so a sharp die's step compiles without it.
#[inline(always)]
pub(crate) fn contact_point<const ROUNDED: bool, L: Lane>(r: &Vector3<L>, radius: L) -> Vector3<L> {
    if ROUNDED { v3(r.x, r.y, r.z - radius) } else { *r }
}

/// `Σ ρ_k × F_k` over the touching corners, in corner order from +0.0.
#[inline(always)]
fn torque<const ROUNDED: bool, L: Lane>(
    offsets: &[Vector3<L>; 8],
    forces: &[Vector3<L>; 8],
    touching: u8,
    radius: L,
) -> Vector3<L> {
    let mut torque = zero3();
    for k in set_bits(touching.into()) {
        let arm = contact_point::<ROUNDED, L>(&offsets[k], radius);
        torque = add3(&torque, &cross3(&arm, &forces[k]));
    }
    torque
}

/// The bits of every lane.
#[inline(always)]
fn all_lanes<L: Lane>() -> u32 {
    (1 << L::WIDTH) - 1
}

#[inline(always)]
fn v3<L: Lane>(x: L, y: L, z: L) -> Vector3<L> {
    Vector3::new(x, y, z)
}

#[inline(always)]
fn zero3<L: Lane>() -> Vector3<L> {
    v3(L::zero(), L::zero(), L::zero())
}

#[inline(always)]
fn add3<L: Lane>(a: &Vector3<L>, b: &Vector3<L>) -> Vector3<L> {
    v3(a.x + b.x, a.y + b.y, a.z + b.z)
}

#[inline(always)]
fn scale3<L: Lane>(a: &Vector3<L>, s: L) -> Vector3<L> {
    v3(a.x * s, a.y * s, a.z * s)
}

/// nalgebra's cross product, operation for operation.
#[inline(always)]
fn cross3<L: Lane>(a: &Vector3<L>, b: &Vector3<L>) -> Vector3<L> {
    v3(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

#[inline(always)]
fn select3<L: Lane>(mask: L::Mask, yes: &Vector3<L>, no: &Vector3<L>) -> Vector3<L> {
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

/// The dynamic state of the die at one instant (one per lane in a lane type).
#[derive(Debug, Clone, PartialEq)]
pub struct State<L: Lane = f64> {
    /// cm, centre of mass.
    pub position: Vector3<L>,
    /// cm/s, centre of mass.
    pub velocity: Vector3<L>,
    /// g·cm²/s, about the centre of mass.
    pub angular_momentum: Vector3<L>,
    /// cm, corners 1..8 relative to the centre of mass, world frame.
    pub corner_offsets: [Vector3<L>; 8],
    /// dyn, the contact force on each corner at this state `(friction x, friction y, P)`.
    pub corner_forces: [Vector3<L>; 8],
    /// cm, how far each corner is below the ground (0 above it).
    pub corner_depths: [L; 8],
    /// cm, each contact point's tangential spring `ξ` in the table's plane: the slip it made
    /// since it touched the table, as the spring-friction law holds it (reset to 0 when the
    /// point leaves the table; always 0 under the paper's law).
    pub tangential_springs: [Vector2<L>; 8],
    /// s, simulated time.
    pub time_s: L,
    /// Steps taken since the initial condition.
    pub step: L::Count,
}

/// The rigid-body energy terms, erg (docs/model.md, "Energy"), per lane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EnergyTerms<L> {
    pub(crate) translational: L,
    pub(crate) rotational: L,
    pub(crate) gravitational: L,
    pub(crate) elastic: L,
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

/// Constants of one run per lane, derived once from the parameters (each lane may come from
/// different parameters, e.g. in a map over the stiffness).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Constants<L: Lane> {
    pub(crate) dt: L,
    /// g, the total mass `M`.
    pub(crate) mass: L,
    /// dyn, `M·g` as a (negative) z force.
    pub(crate) weight_z: L,
    /// cm/s, the kick of a step in flight: the contact kick's quotients with every force
    /// +0.0, `((0 + M·g_z)/M)·Δt` and `(0/M)·Δt`, the same for every flight step of a run.
    pub(crate) flight_kick: Vector3<L>,
    pub(crate) stiffness: L,
    pub(crate) damping: L,
    pub(crate) friction: L,
    /// dyn, the weight's components in a tilted table's plane (+0.0 on a level table and
    /// under the paper's law); `weight_z` is then the normal part, `−M·g·cos θ`.
    pub(crate) weight_x: L,
    pub(crate) weight_y: L,
    /// The spring-friction law's normal damping `c` (dyn·s/cm), tangential stiffness `k_t`
    /// (dyn/cm) and damping `c_t` (dyn·s/cm), and static friction `μ_s` (`friction` is
    /// its `μ_k`).
    pub(crate) normal_damping: L,
    pub(crate) tangential_stiffness: L,
    pub(crate) tangential_damping: L,
    /// cm/dyn, `1/k_t`: a multiplication where the spring is reset, in both widths alike.
    pub(crate) tangential_compliance: L,
    pub(crate) static_friction: L,
    /// erg, a tilted table's cap on a settled die's kinetic energy (+∞: none).
    pub(crate) kinetic_cap: L,
    /// `0.5·M`, `M·g`, `0.5·k`: the energy's leading products, grouped as the scalar
    /// formulas group them (left to right).
    pub(crate) half_mass: L,
    pub(crate) mass_gravity: L,
    pub(crate) half_stiffness: L,
    /// cm, `a`.
    pub(crate) half_size: L,
    /// The fair die's point-mass energy: `0.5·m`, `m·g`, `M·g·a`.
    pub(crate) half_corner_mass: L,
    pub(crate) corner_mass_gravity: L,
    pub(crate) mass_gravity_half_size: L,
    /// A loaded die's point-mass energy: each corner's mass `m + Δm_k`, `g`, `M·g·a`.
    pub(crate) corner_masses: [L; 8],
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
    /// cm, each corner (contact-sphere centre) relative to the centre of mass along the
    /// principal axes: where the step places it once the axes have turned.
    pub(crate) principal_corners: [Vector3<L>; 8],
    pub(crate) split: L::Mask,
    /// cm, the corner radius: a contact sphere's lowest point is this far below its centre.
    pub(crate) corner_radius: L,
    /// erg, the stopping rule's thresholds; for a loaded die the largest over its faces,
    /// which only screens (the rule of the face down decides).
    pub(crate) energy_threshold: L,
    pub(crate) kinetic_threshold: L,
    /// erg, a rigid-body energy above this is a runaway (fixed at t = 0).
    pub(crate) runaway: L,
    pub(crate) max_steps: L::Count,
    /// Lanes on the whole-die-norm friction law, on the point-mass stop energy, with a
    /// loaded die.
    pub(crate) whole_die_norm: L::Mask,
    pub(crate) point_masses: L::Mask,
    pub(crate) loaded: L::Mask,
    /// Lanes with a general body; whose inertia turns with the body (loaded or general: ω
    /// changes in flight too); whose stopping rule depends on the face down (the same lanes).
    pub(crate) shaped: L::Mask,
    pub(crate) turning: L::Mask,
    /// Bit l: lane l's body has rounded corners. Plain bits, not a mask: the step asks
    /// only whether any lane has, and a sharp die's step should not pay for asking.
    pub(crate) rounded: u32,
    /// Lanes on the spring-friction contact law, as a mask and as plain bits: the engines
    /// pick the step of the paper's law alone where no lane has it ([`Kernel::step`]).
    pub(crate) spring: L::Mask,
    pub(crate) spring_lanes: u32,
}

impl Constants<f64> {
    /// The constants of `p`, with `runaway` still +∞ (it needs the initial energy).
    pub(crate) fn new(p: &Params, body: &Body) -> Self {
        let shape = body.shape();
        let mass = body.mass();
        let gravity = p.world.gravity;
        let spring = p.ground.contact == ContactLaw::SpringFriction;
        // The paper's weight as the authors' program had it; a tilted table's in its frame.
        let [gx, gy, gz] = contact::gravity_in_table_frame(p);
        let (weight_x, weight_y, weight_z) = if spring {
            (mass * gx, mass * gy, mass * gz)
        } else {
            (0.0, 0.0, mass * -gravity)
        };
        let (dt, zero) = (p.integrator.dt, 0.0);
        // A general body's potential is measured from its lowest rest height.
        let a = body.reference_height();
        let m = p.die.corner_mass;
        let rule = contact::on_the_table(body.widest_stop_rule(), p, body.edge_energy());
        let law = SpringFriction::new(p, mass);
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
        Constants {
            dt,
            mass,
            weight_z,
            // `0 + 0` is the paper's `0`, so its kick keeps its bits.
            flight_kick: Vector3::new(
                ((zero + weight_x) / mass) * dt,
                ((zero + weight_y) / mass) * dt,
                ((zero + weight_z) / mass) * dt,
            ),
            stiffness: p.ground.stiffness,
            damping: p.ground.damping,
            friction: p.ground.friction,
            weight_x,
            weight_y,
            normal_damping: law.normal_damping,
            tangential_stiffness: law.tangential_stiffness,
            tangential_damping: law.tangential_damping,
            tangential_compliance: law.tangential_compliance,
            static_friction: p.ground.static_friction,
            kinetic_cap: contact::kinetic_cap(p, body.edge_energy()),
            half_mass: 0.5 * mass,
            // The potential of the normal weight; a tilted table's downhill part is added
            // in `energy`.
            mass_gravity: if spring { mass * -gz } else { mass * gravity },
            half_stiffness: 0.5 * p.ground.stiffness,
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
            split: principal.is_some(),
            corner_radius: shape.map_or(0.0, |s| s.radius),
            energy_threshold: rule.energy_threshold,
            kinetic_threshold: rule.kinetic_threshold,
            runaway: f64::INFINITY,
            max_steps: p.max_steps(),
            whole_die_norm: p.ground.friction_law == FrictionLaw::WholeDieNorm,
            point_masses: p.integrator.stop_energy == StopEnergy::PointMasses,
            loaded,
            shaped: shape.is_some(),
            rounded: shape.is_some_and(|s| s.radius > 0.0) as u32,
            turning: loaded || shape.is_some(),
            spring,
            spring_lanes: spring as u32,
        }
    }
}

/// Calls the kernel makes into an engine's bookkeeping during a step; the energy ledger is
/// the one user, and a run that does not keep it passes [`NoHook`].
pub(crate) trait StepHook<L: Lane> {
    /// Before the kick, at the state the contact forces were computed from.
    fn before_kick(&mut self, kernel: &Kernel<L>);
    /// After the kick and the new ω, before the corners turn.
    fn after_spin(&mut self, kernel: &Kernel<L>);
}

/// No bookkeeping.
pub(crate) struct NoHook;

impl<L: Lane> StepHook<L> for NoHook {
    #[inline(always)]
    fn before_kick(&mut self, _: &Kernel<L>) {}
    #[inline(always)]
    fn after_spin(&mut self, _: &Kernel<L>) {}
}

/// One roll per lane: the state plus everything the step needs.
#[derive(Debug, Clone)]
pub(crate) struct Kernel<L: Lane> {
    pub(crate) state: State<L>,
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
    pub(crate) touching_corners: u8,
    pub(crate) c: Constants<L>,
    /// Each lane's body: what the end-of-step test asks for the stopping rule of the face
    /// down, and the outcome rule asks at the end.
    pub(crate) bodies: L::PerLane<Body>,
}

impl Kernel<f64> {
    /// The die placed at `initial`, its spin and its forces computed (no range checks).
    pub(crate) fn new(params: &Params, initial: &InitialCondition) -> Self {
        let body = Body::new(params);
        let c = Constants::new(params, &body);
        let corner_offsets = body.start_offsets(initial);
        let angular_momentum = body.initial_angular_momentum(initial, &corner_offsets);
        let state = State {
            position: Vector3::new(0.0, 0.0, initial.height),
            velocity: Vector3::from(initial.velocity),
            angular_momentum,
            corner_offsets,
            corner_forces: [Vector3::zeros(); 8],
            corner_depths: [0.0; 8],
            tangential_springs: [Vector2::zeros(); 8],
            time_s: 0.0,
            step: 0,
        };
        let mut kernel = Kernel {
            state,
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

impl<L: Lane> Kernel<L> {
    /// One step under the laws the lanes have: [`Kernel::step`] of the paper's law alone
    /// where no lane has the spring-friction law.
    #[inline(always)]
    pub(crate) fn step_by_law(&mut self, hook: &mut impl StepHook<L>) {
        if self.c.spring_lanes != 0 {
            self.step::<true>(hook);
        } else {
            self.step::<false>(hook);
        }
    }

    /// One step of Δt in every lane: kick → drift → L → ω → rotate → forces (docs/model.md,
    /// "One time step").
    ///
    /// `SPRING` false is the paper's law in every lane, its arithmetic untouched by the other
    /// law; true steps lanes on the spring-friction law (and any paper lanes beside them).
    /// The engines pick it once per step from [`Constants::spring_lanes`], so the paper's
    /// step compiles without a trace of the other law.
    #[inline(always)]
    pub(crate) fn step<const SPRING: bool>(&mut self, hook: &mut impl StepHook<L>) {
        // The constants this stage reads, copied out one by one: a copy of them all costs a
        // memcpy call per step.
        let c = &self.c;
        let (dt, mass, weight_z, flight_kick, turning) = (c.dt, c.mass, c.weight_z, c.flight_kick, c.turning);
        let (rounded, radius) = (c.rounded != 0, c.corner_radius);
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
            for k in set_bits(touching.into()) {
                f = Some(f.map_or(s.corner_forces[k], |f| add3(&f, &s.corner_forces[k])));
            }
            let f = f.unwrap_or_else(zero3);
            let force = if touching != 0xff { add3(&f, &zero3()) } else { f };
            // A lane in flight among them gets its flight constant this way too: its
            // forces are +0.0, so these are the very quotients the constant holds.
            let v = &mut s.velocity;
            if SPRING {
                // A tilted table's weight has a part in its plane.
                let c = &self.c;
                let tilted = v3(
                    v.x + ((force.x + c.weight_x) / mass) * dt,
                    v.y + ((force.y + c.weight_y) / mass) * dt,
                    v.z + ((force.z + weight_z) / mass) * dt,
                );
                *v = if c.spring_lanes == all_lanes::<L>() {
                    tilted
                } else {
                    let paper = v3(v.x + (force.x / mass) * dt, v.y + (force.y / mass) * dt, tilted.z);
                    select3(c.spring, &tilted, &paper)
                };
            } else {
                v.x = v.x + (force.x / mass) * dt;
                v.y = v.y + (force.y / mass) * dt;
                v.z = v.z + ((force.z + weight_z) / mass) * dt;
            }
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
                torque::<true, L>(&s.corner_offsets, &s.corner_forces, touching, radius)
            } else {
                torque::<false, L>(&s.corner_offsets, &s.corner_forces, touching, radius)
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
            let m = &self.rotation;
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
        let split = L::bits(self.c.split);
        if split != 0 {
            let all = split == all_lanes::<L>();
            let [a, b, c] = self.turned_axes;
            for (r, p) in self
                .state
                .corner_offsets
                .iter_mut()
                .zip(&self.c.principal_corners)
            {
                let placed = v3(
                    (a.x * p.x + b.x * p.y) + c.x * p.z,
                    (a.y * p.x + b.y * p.y) + c.y * p.z,
                    (a.z * p.x + b.z * p.y) + c.z * p.z,
                );
                *r = if all {
                    placed
                } else {
                    select3(self.c.split, &placed, r)
                };
            }
            self.angular_velocity = if all {
                self.turned_angular_velocity
            } else {
                select3(
                    self.c.split,
                    &self.turned_angular_velocity,
                    &self.angular_velocity,
                )
            };
        }
        // 6. forces at the new state.
        self.update_forces_by::<SPRING>();
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
        let split = L::bits(self.c.split) & lanes;
        if split != 0 {
            self.turn_freely(split);
        }
        let lanes = lanes & !split;
        if lanes == 0 {
            return;
        }
        let c = &self.c;
        let loaded = L::bits(c.loaded) & lanes;
        let shaped = L::bits(c.shaped) & lanes;
        let mut spin_input = self.state.angular_momentum;
        if loaded != 0 {
            let tensor = InertiaTensor::new(
                c.uniform_inertia,
                c.uniform_mass,
                &c.extra_masses,
                &self.state.corner_offsets,
            );
            let w = tensor.angular_velocity(&self.state.angular_momentum);
            spin_input = select3(c.loaded, &w, &spin_input);
        }
        if shaped != 0 {
            let w = shape::angular_velocity(
                &c.inverse_inertia,
                &c.axis_scale,
                &self.state.corner_offsets,
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
                c.dt.lane(0),
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
        let (dt, inertia, turning_lanes) = (c.dt, c.uniform_inertia, c.turning);
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
        let c = &self.c;
        let turn = free_turn(
            &self.state.corner_offsets,
            &c.axis_scale,
            &c.principal_axes,
            &c.inverse_moments,
            &self.state.angular_momentum,
            c.dt,
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
        let (v, w) = (&self.state.velocity, &self.angular_velocity);
        v3(
            v.x + (r.z * w.y - r.y * w.z),
            v.y + (r.x * w.z - r.z * w.x),
            v.z + (r.y * w.x - r.x * w.y),
        )
    }

    /// Recomputes every corner's depth and contact force at the current state, under each
    /// lane's contact and friction law.
    #[inline(always)]
    pub(crate) fn update_forces(&mut self) {
        if self.c.spring_lanes != 0 {
            self.update_forces_by::<true>();
        } else {
            self.update_forces_by::<false>();
        }
    }

    /// [`Kernel::update_forces`] with the laws known: the paper's alone (`SPRING` false,
    /// eq. 13–15), or lanes on the spring-friction law, with the paper's in any lane beside
    /// them computed as before and kept by a select.
    #[inline(always)]
    fn update_forces_by<const SPRING: bool>(&mut self) {
        // A rounded body touches the table with the lowest points of its corner spheres, the
        // radius below their centres (docs/model.md, "Real dice"); a sharp one skips this.
        let rounded = self.c.rounded != 0;
        if !SPRING {
            if rounded {
                self.update_forces_at::<true>();
            } else {
                self.update_forces_at::<false>();
            }
            return;
        }
        let previous = self.touching_corners;
        let paper = (self.c.spring_lanes != all_lanes::<L>()).then(|| {
            if rounded {
                self.update_forces_at::<true>();
            } else {
                self.update_forces_at::<false>();
            }
            self.state.corner_forces
        });
        if rounded {
            self.spring_forces_at::<true>(previous);
        } else {
            self.spring_forces_at::<false>(previous);
        }
        if let Some(paper) = paper {
            let spring = self.c.spring;
            for (force, paper) in self.state.corner_forces.iter_mut().zip(&paper) {
                *force = select3(spring, force, paper);
            }
        }
    }

    /// The spring-friction law's forces for sharp (`ROUNDED` false) or rounded lanes, with
    /// `previous` the corners that touched in some lane before (docs/model.md, "The
    /// spring-friction contact"): per point, the normal `N = max(0, k·d − c·u_z)`; the trial
    /// tangential force `F* = −k_t·ξ − c_t·u_t` on the spring `ξ` (the slip since the point
    /// touched, this step's included); stuck while `|F*| ≤ μ_s·N`, else sliding at
    /// `μ_k·N` along `F*` with the spring set to hold that force. A point off the table has
    /// no force and no spring.
    #[inline(always)]
    fn spring_forces_at<const ROUNDED: bool>(&mut self, previous: u8) {
        let c = &self.c;
        let (stiffness, damping, kinetic, dt) = (c.stiffness, c.normal_damping, c.friction, c.dt);
        let (k_t, c_t, stuck_up_to, spring) = (
            c.tangential_stiffness,
            c.tangential_damping,
            c.static_friction,
            c.spring,
        );
        let compliance = c.tangential_compliance;
        let radius = c.corner_radius;
        let zero = L::zero();
        let (touching, any) = self.press_corners::<ROUNDED>(radius);
        if L::bits(any) == 0 && previous == 0 {
            return;
        }
        self.in_contact = any;
        let mut touching_corners = 0u8;
        for (k, t) in touching.iter().enumerate() {
            if L::bits(*t) != 0 {
                touching_corners |= 1 << k;
            }
        }
        self.touching_corners = touching_corners;
        for k in set_bits((previous & !touching_corners).into()) {
            self.state.corner_forces[k] = zero3();
            self.state.tangential_springs[k] = Vector2::new(zero, zero);
        }
        for k in set_bits(touching_corners.into()) {
            let t = touching[k];
            let u = self.corner_velocity(&contact_point::<ROUNDED, L>(
                &self.state.corner_offsets[k],
                radius,
            ));
            let xi = self.state.tangential_springs[k];
            let (sx, sy) = (xi.x + u.x * dt, xi.y + u.y * dt);
            // The table pushes, never pulls.
            let pressed = self.state.corner_depths[k] * stiffness - damping * u.z;
            let normal = pressed.or_zero(pressed.gt(zero));
            let (mut fx, mut fy) = (-(k_t * sx) - c_t * u.x, -(k_t * sy) - c_t * u.y);
            let (mut sx, mut sy) = (sx, sy);
            // |F*| > μ_s·N, compared squared (both sides ≥ 0): a point stuck in every lane
            // needs no square root and no quotient.
            let limit = stuck_up_to * normal;
            let slipping = (fx * fx + fy * fy).gt(limit * limit);
            if L::bits(slipping) != 0 {
                // Where it slips |F*| is above μ_s·N ≥ 0, so the quotient is finite there.
                let scale = (kinetic * normal) / (fx * fx + fy * fy).sqrt();
                fx = L::select(slipping, fx * scale, fx);
                fy = L::select(slipping, fy * scale, fy);
                // Sliding, the spring holds the kinetic force: ξ = −(F_t + c_t·u_t)/k_t.
                sx = L::select(slipping, -(fx + c_t * u.x) * compliance, sx);
                sy = L::select(slipping, -(fy + c_t * u.y) * compliance, sy);
            }
            let kept = t & spring;
            self.state.corner_forces[k] = v3(fx.or_zero(t), fy.or_zero(t), normal.or_zero(t));
            self.state.tangential_springs[k] = Vector2::new(sx.or_zero(kept), sy.or_zero(kept));
        }
    }

    /// Which corners (or corner spheres, `ROUNDED`) are in the table, per lane, and their
    /// depths into it, cm: the same for both contact laws. Returns the masks and their union.
    #[inline(always)]
    fn press_corners<const ROUNDED: bool>(&mut self, radius: L) -> ([L::Mask; 8], L::Mask) {
        let z0 = self.state.position.z;
        let zero = L::zero();
        let mut touching = [L::mask_from_bits(0); 8];
        let mut any = L::mask_from_bits(0);
        for (k, t) in touching.iter_mut().enumerate() {
            let z = self.state.corner_offsets[k].z + z0;
            let z = if ROUNDED { z - radius } else { z };
            *t = z.lt(zero);
            self.state.corner_depths[k] = (-z).or_zero(*t);
            any = any | *t;
        }
        (touching, any)
    }

    /// [`Kernel::update_forces`] for sharp (`ROUNDED` false) or rounded lanes.
    #[inline(always)]
    fn update_forces_at<const ROUNDED: bool>(&mut self) {
        // Copied out one by one, as in `step`.
        let c = &self.c;
        let (stiffness, damping, friction, whole_die_norm) =
            (c.stiffness, c.damping, c.friction, c.whole_die_norm);
        let radius = c.corner_radius;
        let zero = L::zero();
        let (touching, any) = self.press_corners::<ROUNDED>(radius);
        // Lanes that neither touch now nor did before keep their +0.0 forces; a lane that
        // just left the ground gets +0.0 from the masks below.
        if L::bits(any | self.in_contact) == 0 {
            return;
        }
        self.in_contact = any;
        let laws = L::bits(whole_die_norm);
        let per_corner_lanes = laws != all_lanes::<L>();
        let whole_lanes = laws != 0;
        let mut touching_corners = 0u8;
        for (k, t) in touching.iter().enumerate() {
            if L::bits(*t) != 0 {
                touching_corners |= 1 << k;
            }
        }
        let previous = std::mem::replace(&mut self.touching_corners, touching_corners);
        for k in set_bits((previous & !touching_corners).into()) {
            self.state.corner_forces[k] = zero3();
        }
        // The authors' law scales every corner's slip by one whole-die matrix norm: the
        // largest singular value of the 8×2 matrix of horizontal corner velocities, from the
        // largest eigenvalue of its 2×2 Gram matrix (within 5·10⁻¹⁶ of LAPACK's, reference
        // §9). It needs every corner's velocity, the per-corner law only those that touch.
        let norm = if whole_lanes {
            let (mut a, mut b, mut cc) = (zero, zero, zero);
            for r in &self.state.corner_offsets {
                let uk = self.corner_velocity(&contact_point::<ROUNDED, L>(r, radius));
                a = a + uk.x * uk.x;
                b = b + uk.x * uk.y;
                cc = cc + uk.y * uk.y;
            }
            let half_diff = (a - cc) / L::splat(2.0);
            ((a + cc) / L::splat(2.0) + (half_diff * half_diff + b * b).sqrt()).sqrt()
        } else {
            zero
        };
        let norm_nonzero = norm.ne(zero);
        for k in set_bits(touching_corners.into()) {
            let uk = self.corner_velocity(&contact_point::<ROUNDED, L>(
                &self.state.corner_offsets[k],
                radius,
            ));
            let normal = self.state.corner_depths[k] * stiffness;
            let vertical = normal * (L::splat(1.0) - damping * uk.z);
            let (mut fx, mut fy) = (zero, zero);
            if per_corner_lanes {
                let slip = (uk.x * uk.x + uk.y * uk.y).sqrt();
                let sliding = slip.gt(zero);
                let scale = -(friction * vertical.abs());
                fx = (scale * (uk.x / slip)).or_zero(sliding);
                fy = (scale * (uk.y / slip)).or_zero(sliding);
            }
            if whole_lanes {
                let wx = (-((uk.x / norm) * vertical) * friction).or_zero(norm_nonzero);
                let wy = (-((uk.y / norm) * vertical) * friction).or_zero(norm_nonzero);
                fx = L::select(whole_die_norm, wx, fx);
                fy = L::select(whole_die_norm, wy, fy);
            }
            self.state.corner_forces[k] = v3(
                fx.or_zero(touching[k]),
                fy.or_zero(touching[k]),
                vertical.or_zero(touching[k]),
            );
        }
    }

    /// erg, the weight's potential: `M·g·(x.z − a)`; on a spring-friction lane
    /// `−M·g⃗·x` measured from the same height, the normal part `M·g·cos θ·(x.z − a)` less
    /// the downhill part `M·g_t·x` of a tilted table (zero on a level one).
    #[inline(always)]
    fn gravitational<const SPRING: bool>(&self) -> L {
        let c = &self.c;
        let x = &self.state.position;
        let normal = c.mass_gravity * (x.z - c.half_size);
        if !SPRING {
            return normal;
        }
        let tilted = normal - (c.weight_x * x.x + c.weight_y * x.y);
        if c.spring_lanes == all_lanes::<L>() {
            tilted
        } else {
            L::select(c.spring, tilted, normal)
        }
    }

    /// The rigid-body energy terms at the current state, erg, under the lanes' laws.
    #[inline(always)]
    pub(crate) fn energy(&self) -> EnergyTerms<L> {
        if self.c.spring_lanes != 0 {
            self.energy_by::<true>()
        } else {
            self.energy_by::<false>()
        }
    }

    /// [`Kernel::energy`] with the laws known, as [`Kernel::step`] takes them.
    #[inline(always)]
    pub(crate) fn energy_by<const SPRING: bool>(&self) -> EnergyTerms<L> {
        let c = &self.c;
        let s = &self.state;
        let (v, w, l) = (&s.velocity, &self.angular_velocity, &s.angular_momentum);
        let mut elastic = L::zero();
        // Terms are ≥ +0.0, so leaving out the +0.0 of corners that touch nowhere is exact.
        if L::bits(self.in_contact) != 0 {
            for k in set_bits(self.touching_corners.into()) {
                let d = s.corner_depths[k];
                elastic = elastic + (c.half_stiffness * d) * d;
            }
        }
        EnergyTerms {
            translational: c.half_mass * ((v.x * v.x + v.y * v.y) + v.z * v.z),
            // ω·L summed from +0.0 as nalgebra's dot product does (a −0.0 product first
            // becomes +0.0).
            rotational: L::splat(0.5) * (((L::zero() + w.x * l.x) + w.y * l.y) + w.z * l.z),
            gravitational: self.gravitational::<SPRING>(),
            elastic: elastic.or_zero(self.in_contact),
        }
    }

    /// erg, the authors' point-mass energy as `(kinetic, total)`: the corners as 8 point
    /// masses and the ground term `½·Σ d_k·P_k` with the damped force (reference §2). The
    /// fair die sums column-major as the authors did (every x component, then y, then z);
    /// a loaded die weighs each corner's `|u_k|²` and height by its own mass.
    #[inline(always)]
    pub(crate) fn point_mass_parts(&self) -> (L, L) {
        let c = &self.c;
        let s = &self.state;
        let u: [Vector3<L>; 8] = std::array::from_fn(|k| self.corner_velocity(&s.corner_offsets[k]));
        let mut ground = L::zero();
        for k in 0..8 {
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
    pub(crate) fn ends_by<const SPRING: bool>(&self) -> Ends<L::Mask> {
        let c = &self.c;
        let e = self.energy_by::<SPRING>();
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
            let loaded = L::bits(screened & c.turning);
            if loaded == 0 {
                screened
            } else {
                // A loaded die's or a general body's rule depends on the face it lies on.
                // Looking the face up is a per-roll table search, done only where the widest
                // rule passed.
                let (mut et, mut kt) = (c.energy_threshold.to_lanes(), c.kinetic_threshold.to_lanes());
                for lane in set_bits(loaded) {
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
        let settled = settled & !unstable;
        // A tilted table's cap on the kinetic energy (docs/model.md, "The spring-friction
        // contact"): it settles only what its downhill edge can hold.
        let settled = if SPRING && L::bits(settled) != 0 {
            settled & kinetic.le(c.kinetic_cap)
        } else {
            settled
        };
        let timeout = L::count_reached(self.state.step, c.max_steps) & !unstable & !settled;
        Ends {
            unstable,
            settled,
            timeout,
        }
    }
}
