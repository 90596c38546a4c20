//! The state of a rolling die and the paper's semi-implicit Euler step (docs/model.md).
//!
//! The arithmetic follows the authors' program operation by operation (tests/data/reference/README.md §2
//! and §9: sums in corner order, divisions where they divided, Octave's scaled 2-norm and
//! `pow(x, 2)`), so the reference trajectories are reproduced to rounding, not merely in law.

use super::body::{body_corner_offsets, face_most_nearly_up, face_of_highest_corners};
use super::energy::Energy;
use super::initial::InitialCondition;
use super::mass::LoadedMass;
use super::params::{FrictionLaw, Ground, ParamError, Params, StopEnergy};
use super::stopping::{StopRule, settles};
use nalgebra::{Matrix3, Vector3};
use serde::Serialize;

/// A rigid-body energy above this multiple of `max(initial energy, edge energy)` means the
/// integrator is feeding energy in (docs/model.md, "Stability"): a stable roll stays within a
/// few percent of its start.
pub(crate) const RUNAWAY_ENERGY_FACTOR: f64 = 10.0;

/// The dynamic state of the die at one instant.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// cm, centre of mass.
    pub position: Vector3<f64>,
    /// cm/s, centre of mass.
    pub velocity: Vector3<f64>,
    /// g·cm²/s, about the centre of mass.
    pub angular_momentum: Vector3<f64>,
    /// cm, corners 1..8 relative to the centre of mass, world frame.
    pub corner_offsets: [Vector3<f64>; 8],
    /// dyn, the contact force on each corner at this state `(friction x, friction y, P)`.
    pub corner_forces: [Vector3<f64>; 8],
    /// cm, how far each corner is below the ground (0 above it).
    pub corner_depths: [f64; 8],
    /// s, simulated time.
    pub time_s: f64,
    /// Steps taken since the initial condition.
    pub step: u64,
}

/// One corner's contact force split into the paper's three parts (eq. 13–15), dyn.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ContactForce {
    /// cm below the ground (0 when not touching).
    pub(crate) depth: f64,
    /// Spring force `k·d`, up.
    pub(crate) normal: f64,
    /// Damping force `−k·d·γ·u_z` (the vertical force is normal + damping).
    pub(crate) damping: f64,
    /// Horizontal kinetic friction `(x, y)`.
    pub(crate) friction: [f64; 2],
}

/// Work done on the die since t = 0 by the ground's damping and by friction, erg.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct ContactWork {
    damping: f64,
    friction: f64,
}

/// Where the energy went since t = 0, erg (the energy ledger).
///
/// `initial = current + damping_loss + friction_loss + integrator_loss`: the first three are
/// measured, the last is the remainder, the energy semi-implicit Euler itself gains or loses
/// (½·M·g²·Δt² per step in free flight, docs/model.md).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyLedger {
    /// Rigid-body energy at t = 0.
    pub initial: f64,
    /// Rigid-body energy now.
    pub current: f64,
    /// Energy taken out by the ground's damping (the work it did, negated).
    pub damping_loss: f64,
    /// Energy taken out by kinetic friction.
    pub friction_loss: f64,
    /// The remainder: energy lost (positive) or gained by the integrator.
    pub integrator_loss: f64,
}

/// How a roll ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// The stopping rule held (docs/model.md, "Stopping rule"): the energy is too low to
    /// pass over an edge and the die is close to rest, so the face can no longer change.
    Settled,
    /// Simulated time passed `integrator.max_time` first: the die did not settle.
    Timeout,
    /// The state stopped being finite or the energy ran away: the integrator is unstable
    /// for these parameters (docs/model.md, "Stability").
    Unstable,
}

impl Status {
    pub fn name(self) -> &'static str {
        match self {
            Status::Settled => "settled",
            Status::Timeout => "timeout",
            Status::Unstable => "unstable",
        }
    }

    /// The status of a [`name`](Status::name), as result files write it.
    pub fn from_name(name: &str) -> Option<Status> {
        [Status::Settled, Status::Timeout, Status::Unstable]
            .into_iter()
            .find(|s| s.name() == name)
    }
}

/// The end of a roll.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Outcome {
    pub status: Status,
    /// The face up (4 highest corners) for a settled roll; `None` otherwise, or when the 4
    /// highest corners do not form a face.
    pub face: Option<u8>,
    /// Steps taken when the roll ended.
    pub steps: u64,
    /// s of simulated time when the roll ended.
    pub time_s: f64,
}

/// Constants of one run, derived once from the parameters.
#[derive(Debug, Clone, Copy)]
struct Constants {
    dt: f64,
    mass: f64,
    corner_mass: f64,
    inertia: f64,
    half_size: f64,
    gravity: f64,
    /// dyn, `M·g` as a (negative) z force.
    weight_z: f64,
    /// cm/s, the kick of a step in flight: the contact kick's quotients with every force
    /// +0.0, `((0 + M·g_z)/M)·Δt` and `(0/M)·Δt`, the same for every flight step of a run.
    flight_kick: Vector3<f64>,
    stiffness: f64,
    damping: f64,
    friction: f64,
    friction_law: FrictionLaw,
    stop_energy: StopEnergy,
    stop_rule: StopRule,
    max_steps: u64,
}

impl Constants {
    fn new(p: &Params) -> Self {
        let mass = p.total_mass();
        let weight_z = mass * -p.world.gravity;
        let (dt, zero) = (p.integrator.dt, 0.0);
        Constants {
            dt: p.integrator.dt,
            mass,
            corner_mass: p.die.corner_mass,
            inertia: p.inertia(),
            half_size: p.die.half_size,
            gravity: p.world.gravity,
            weight_z,
            flight_kick: Vector3::new(
                (zero / mass) * dt,
                (zero / mass) * dt,
                ((zero + weight_z) / mass) * dt,
            ),
            stiffness: p.ground.stiffness,
            damping: p.ground.damping,
            friction: p.ground.friction,
            friction_law: p.ground.friction_law,
            stop_energy: p.integrator.stop_energy,
            stop_rule: StopRule::new(p),
            max_steps: p.max_steps(),
        }
    }
}

/// Steps between two looks at a stop request in [`Simulation::run_until_stopped`]: a few
/// tenths of a millisecond of stepping, so a cancel is answered well within 0.2 s.
pub const STEPS_BETWEEN_STOP_CHECKS: u64 = 4096;

/// A die rolling from an initial condition: the state plus everything the step needs.
///
/// The fields are visible to the lane engine ([`super::lanes`]), which loads rolls from
/// and stores them back into this struct so that both engines start and end alike.
#[derive(Debug, Clone)]
pub struct Simulation {
    params: Params,
    c: Constants,
    pub(super) state: State,
    /// rad/s, `L / I`, kept in step with the angular momentum.
    pub(super) angular_velocity: Vector3<f64>,
    /// The rotation applied to the corner rows each step; `None` while ω = 0. It depends on
    /// ω alone, so it is rebuilt only when a contact torque changed L.
    pub(super) step_rotation: Option<Matrix3<f64>>,
    /// Whether any corner is below the ground at the current state.
    pub(super) in_contact: bool,
    /// Whether the energy ledger is kept (its work sums cost a second pass over the
    /// corners per contact step, which a batch that only wants outcomes skips).
    track_ledger: bool,
    /// cm/s, the corner velocities the current contact forces were computed from (kept
    /// while in contact): the ledger's velocities before the next kick.
    contact_velocities: [Vector3<f64>; 8],
    /// erg, work done on the die by damping and by friction since t = 0 (negative: lost).
    work: ContactWork,
    /// erg, rigid-body energy at t = 0.
    initial_energy: f64,
    /// erg, a rigid-body energy above this is a runaway: `RUNAWAY_ENERGY_FACTOR ·
    /// max(initial energy, edge energy)`, fixed at t = 0.
    pub(super) runaway_energy: f64,
    outcome: Option<Outcome>,
    /// A loaded die's mass model; `None` for the fair die, whose path it never touches.
    loaded: Option<LoadedMass>,
}

impl Simulation {
    /// Validates the parameters and the initial condition (no corner may start inside the
    /// table), then places the die.
    pub fn new(params: &Params, initial: &InitialCondition) -> Result<Self, ParamError> {
        params.validate()?;
        initial.validate()?;
        initial.check_clear_of_table(params)?;
        Ok(Self::new_unchecked(params, initial))
    }

    /// Like [`Simulation::new`] without the range checks. Any input still ends in a status:
    /// non-finite or absurd values end the first step as [`Status::Unstable`].
    pub fn new_unchecked(params: &Params, initial: &InitialCondition) -> Self {
        let c = Constants::new(params);
        let loaded = LoadedMass::new(params);
        let rotation = initial.rotation();
        let corner_offsets = if let Some(m) = &loaded {
            m.initial_corner_offsets(c.half_size, initial)
        } else if initial.orientation == [0.0; 3] {
            body_corner_offsets(c.half_size)
        } else {
            body_corner_offsets(c.half_size).map(|r| rotation * r)
        };
        let angular_momentum = match &loaded {
            Some(m) => m.initial_angular_momentum(initial, &corner_offsets),
            None => initial.angular_momentum_for(c.inertia),
        };
        let state = State {
            position: Vector3::new(0.0, 0.0, initial.height),
            velocity: Vector3::from(initial.velocity),
            angular_momentum,
            corner_offsets,
            corner_forces: [Vector3::zeros(); 8],
            corner_depths: [0.0; 8],
            time_s: 0.0,
            step: 0,
        };
        let mut sim = Simulation {
            params: *params,
            c,
            state,
            angular_velocity: Vector3::zeros(),
            step_rotation: None,
            in_contact: false,
            track_ledger: true,
            contact_velocities: [Vector3::zeros(); 8],
            work: ContactWork::default(),
            initial_energy: 0.0,
            runaway_energy: 0.0,
            outcome: None,
            loaded,
        };
        sim.update_spin();
        sim.update_forces();
        sim.initial_energy = sim.energy().total();
        sim.runaway_energy = RUNAWAY_ENERGY_FACTOR * sim.initial_energy.max(params.edge_energy());
        sim
    }

    /// Like [`Simulation::new_unchecked`] for a roll whose outcome alone is wanted (batches,
    /// maps): the same trajectory bit for bit, without the energy ledger's bookkeeping. Crate
    /// internal, as its [`energy_ledger`](Simulation::energy_ledger) would miss the contact work.
    pub(crate) fn for_outcome(params: &Params, initial: &InitialCondition) -> Self {
        let mut sim = Self::new_unchecked(params, initial);
        sim.track_ledger = false;
        sim
    }

    pub(crate) fn params(&self) -> &Params {
        &self.params
    }

    pub fn state(&self) -> &State {
        &self.state
    }

    /// rad/s, world frame.
    pub fn angular_velocity(&self) -> Vector3<f64> {
        self.angular_velocity
    }

    /// The end of the roll, once it has ended (later steps do not change it).
    pub fn outcome(&self) -> Option<Outcome> {
        self.outcome
    }

    /// Where the energy has gone since t = 0.
    pub fn energy_ledger(&self) -> EnergyLedger {
        debug_assert!(self.track_ledger, "a roll built for its outcome keeps no ledger");
        let current = self.energy().total();
        let (damping_loss, friction_loss) = (-self.work.damping, -self.work.friction);
        EnergyLedger {
            initial: self.initial_energy,
            current,
            damping_loss,
            friction_loss,
            integrator_loss: self.initial_energy - current - damping_loss - friction_loss,
        }
    }

    /// Whether any corner is below the ground now.
    pub fn in_contact(&self) -> bool {
        self.in_contact
    }

    /// Changes the ground mid-roll; the new law acts from the next step on.
    pub(crate) fn set_ground(&mut self, ground: Ground) -> Result<(), ParamError> {
        let mut params = self.params;
        params.ground = ground;
        params.validate()?;
        self.params = params;
        self.c = Constants::new(&params);
        self.update_forces();
        Ok(())
    }

    /// World positions of corners 1..8, cm.
    pub fn corner_positions(&self) -> [Vector3<f64>; 8] {
        self.state.corner_offsets.map(|r| self.state.position + r)
    }

    /// Velocity of a corner, `u_k = v + ω × r_k`, cm/s, in the authors' operation order.
    #[inline(always)]
    fn corner_velocity(&self, r: &Vector3<f64>) -> Vector3<f64> {
        let v = &self.state.velocity;
        let w = &self.angular_velocity;
        Vector3::new(
            v.x + (r.z * w.y - r.y * w.z),
            v.y + (r.x * w.z - r.z * w.x),
            v.z + (r.y * w.x - r.x * w.y),
        )
    }

    /// Velocities of corners 1..8, cm/s.
    pub(crate) fn corner_velocities(&self) -> [Vector3<f64>; 8] {
        self.state.corner_offsets.map(|r| self.corner_velocity(&r))
    }

    /// Each corner's contact force split into normal, damping and friction, at the current
    /// state (the forces the next step will apply).
    pub(crate) fn contact_forces(&self) -> [ContactForce; 8] {
        let s = &self.state;
        std::array::from_fn(|k| {
            let depth = s.corner_depths[k];
            let normal = depth * self.c.stiffness;
            ContactForce {
                depth,
                normal,
                damping: s.corner_forces[k].z - normal,
                friction: [s.corner_forces[k].x, s.corner_forces[k].y],
            }
        })
    }

    /// The energy terms at the current state (docs/model.md, "Energy"), erg.
    pub fn energy(&self) -> Energy {
        let s = &self.state;
        let c = &self.c;
        let elastic = if self.in_contact {
            s.corner_depths.iter().map(|d| 0.5 * c.stiffness * d * d).sum()
        } else {
            0.0
        };
        Energy {
            translational: 0.5 * c.mass * s.velocity.norm_squared(),
            rotational: 0.5 * self.angular_velocity.dot(&s.angular_momentum),
            gravitational: c.mass * c.gravity * (s.position.z - c.half_size),
            elastic,
        }
    }

    /// erg, the energy the authors' program compared with the threshold: the corners as 8
    /// point masses and the ground term `½·Σ d_k·P_k` with the damped force (reference §2).
    pub fn point_mass_energy(&self) -> f64 {
        self.point_mass_parts().1
    }

    /// erg, the authors' point-mass energy as `(kinetic ½·m·Σ|u_k|², total)`.
    fn point_mass_parts(&self) -> (f64, f64) {
        let s = &self.state;
        let c = &self.c;
        let u = self.corner_velocities();
        if let Some(m) = &self.loaded {
            let heights = s.corner_offsets.map(|r| r.z + s.position.z);
            let ground = (0..8).map(|k| s.corner_depths[k] * s.corner_forces[k].z).sum();
            return m.point_mass_parts(&u, &heights, ground, c.gravity, c.half_size);
        }
        // Column-major, as the authors summed: every x component, then y, then z.
        let mut kinetic = 0.0;
        for axis in 0..3 {
            for uk in &u {
                kinetic += uk[axis] * uk[axis];
            }
        }
        let mut heights = 0.0;
        let mut ground = 0.0;
        for k in 0..8 {
            heights += s.corner_offsets[k].z + s.position.z;
            ground += s.corner_depths[k] * s.corner_forces[k].z;
        }
        let kinetic = 0.5 * c.corner_mass * kinetic;
        let total =
            kinetic + c.corner_mass * c.gravity * heights + 0.5 * ground - c.mass * c.gravity * c.half_size;
        (kinetic, total)
    }

    /// erg, the energy the stopping rule uses (`integrator.stop_energy`).
    pub(crate) fn stop_energy(&self) -> f64 {
        self.stop_energy_from(&self.energy()).1
    }

    /// erg, the kinetic part of the stop energy.
    pub fn stop_kinetic_energy(&self) -> f64 {
        self.stop_energy_from(&self.energy()).0
    }

    /// erg, the stop energy's threshold (docs/model.md, "Stopping rule").
    pub(crate) fn stop_threshold(&self) -> f64 {
        self.c.stop_rule.energy_threshold
    }

    /// The stopping rule's thresholds for these parameters.
    pub fn stop_rule(&self) -> StopRule {
        self.c.stop_rule
    }

    /// The face whose outward normal points most nearly up (the live display's face).
    pub fn face_up(&self) -> u8 {
        face_most_nearly_up(&self.state.corner_offsets)
    }

    /// The face whose 4 corners are highest (the outcome rule).
    pub(crate) fn face_of_highest_corners(&self) -> Option<u8> {
        face_of_highest_corners(&self.state.corner_offsets.map(|r| r.z))
    }

    /// One step of Δt: kick → drift → L → rotate → forces (docs/model.md, "One time step").
    ///
    /// Steps on past the end of a roll if asked; the recorded outcome stays the first end.
    #[inline]
    pub fn step(&mut self) {
        let c = self.c;
        // Corner velocities before the kick, for the energy ledger.
        let before = (self.in_contact && self.track_ledger).then_some(self.contact_velocities);
        let s = &mut self.state;
        // 1. kick: v ← v + ((ΣF + M·g)/M)·Δt, forces summed in corner order; in flight
        // (ΣF = +0) the quotients are the run's constants.
        if self.in_contact {
            let mut force = s.corner_forces[0];
            for fk in &s.corner_forces[1..] {
                force += fk;
            }
            s.velocity.x += (force.x / c.mass) * c.dt;
            s.velocity.y += (force.y / c.mass) * c.dt;
            s.velocity.z += ((force.z + c.weight_z) / c.mass) * c.dt;
        } else {
            s.velocity += c.flight_kick;
        }
        // 2. drift with the new velocity (semi-implicit Euler).
        s.position += s.velocity * c.dt;
        // 3. angular momentum from the torque of the forces at the old corner offsets.
        if self.in_contact {
            let mut torque = Vector3::zeros();
            for (r, f) in s.corner_offsets.iter().zip(&s.corner_forces) {
                torque += r.cross(f);
            }
            s.angular_momentum += torque * c.dt;
            // 4. ω = I⁻¹·L (and the rotation it implies).
            self.update_spin();
        } else if self.loaded.is_some() {
            // A loaded die's inertia turns with it: ω changes in flight too.
            self.update_spin();
        }
        if let Some(before) = before {
            self.record_contact_work(&before);
        }
        // 5. rotate every corner offset by |ω|·Δt about ω.
        if let Some(m) = self.step_rotation {
            // The entries as locals: the compiler then keeps them in registers across the
            // 8 corners instead of reloading them after every store.
            let column = |j: usize| (m[(0, j)], m[(1, j)], m[(2, j)]);
            let (cx, cy, cz) = (column(0), column(1), column(2));
            for r in &mut self.state.corner_offsets {
                // Row vector times matrix, each entry (a₁b₁ + a₂b₂) + a₃b₃ as reference BLAS.
                let (x, y, z) = (r.x, r.y, r.z);
                *r = Vector3::new(
                    (x * cx.0 + y * cx.1) + z * cx.2,
                    (x * cy.0 + y * cy.1) + z * cy.2,
                    (x * cz.0 + y * cz.1) + z * cz.2,
                );
            }
        }
        // 6. forces at the new state.
        self.update_forces();
        // 7. the clock.
        self.state.time_s += c.dt;
        self.state.step += 1;
    }

    /// One step, then the end-of-roll checks; returns the outcome on the step that ends it.
    #[inline]
    pub fn advance(&mut self) -> Option<Outcome> {
        self.step();
        if self.outcome.is_some() {
            return None;
        }
        let outcome = self.check_end()?;
        self.outcome = Some(outcome);
        Some(outcome)
    }

    /// Steps until the roll ends (settled, did not settle, or unstable).
    pub fn run_to_end(&mut self) -> Outcome {
        if let Some(o) = self.outcome {
            return o;
        }
        loop {
            if let Some(o) = self.advance() {
                return o;
            }
        }
    }

    /// Steps until the roll ends, or until `stop()` answers true (asked every
    /// [`STEPS_BETWEEN_STOP_CHECKS`] steps): `None` then, and the roll can be continued.
    pub fn run_until_stopped(&mut self, stop: &dyn Fn() -> bool) -> Option<Outcome> {
        if let Some(o) = self.outcome {
            return Some(o);
        }
        loop {
            for _ in 0..STEPS_BETWEEN_STOP_CHECKS {
                if let Some(o) = self.advance() {
                    return Some(o);
                }
            }
            if stop() {
                return None;
            }
        }
    }

    /// Records `outcome` as the end of the roll (the lane engine, which decided it with
    /// [`Simulation::check_end`] on a state stored back here).
    pub(super) fn set_outcome(&mut self, outcome: Outcome) {
        self.outcome = Some(outcome);
    }

    /// Whether the current state ends the roll, and how.
    ///
    /// Asked after every step, so the usual answer (finite, no runaway, not settled, time
    /// left) is reached with one energy sum, one branch-free finiteness test and a few
    /// comparisons; the outcome is only built on the step that ends the roll.
    #[inline]
    pub(super) fn check_end(&self) -> Option<Outcome> {
        let energy = self.energy();
        let rigid = energy.total();
        let status = if !rigid.is_finite() || !self.state_is_finite() || rigid > self.runaway_energy {
            Status::Unstable
        } else if self.settled(&energy, rigid) {
            Status::Settled
        } else if self.state.step >= self.c.max_steps {
            Status::Timeout
        } else {
            return None;
        };
        Some(self.outcome_of(status))
    }

    #[cold]
    fn outcome_of(&self, status: Status) -> Outcome {
        Outcome {
            status,
            face: match status {
                Status::Settled => self.face_of_highest_corners(),
                _ => None,
            },
            steps: self.state.step,
            time_s: self.state.time_s,
        }
    }

    /// The stopping rule on this state, given its rigid-body energy and that energy's total.
    ///
    /// The rule is a conjunction of comparisons, so the cheap rigid-body potential is
    /// compared first: above the threshold, the point-mass energy need not be summed.
    #[inline]
    fn settled(&self, energy: &Energy, rigid: f64) -> bool {
        let rule = &self.stop_rule_now();
        let potential = energy.potential();
        potential <= rule.energy_threshold
            && match self.c.stop_energy {
                StopEnergy::RigidBody => settles(rigid, energy.kinetic(), potential, rule),
                StopEnergy::PointMasses => {
                    let (kinetic, total) = self.point_mass_parts();
                    settles(total, kinetic, potential, rule)
                }
            }
    }

    /// `(kinetic, total)` of the stop energy, given the rigid-body energy of this state.
    fn stop_energy_from(&self, energy: &Energy) -> (f64, f64) {
        match self.c.stop_energy {
            StopEnergy::RigidBody => (energy.kinetic(), energy.total()),
            StopEnergy::PointMasses => self.point_mass_parts(),
        }
    }

    /// The stopping rule for the current state: a loaded die's depends on the face down
    /// (what a report of a finished roll prints; [`Simulation::stop_rule`] is the fair die's).
    #[inline(always)]
    pub(crate) fn stop_rule_now(&self) -> StopRule {
        match &self.loaded {
            None => self.c.stop_rule,
            Some(m) => m.stop_rule(&self.state.corner_offsets),
        }
    }

    /// Whether the position, velocity and every corner offset are finite.
    ///
    /// A value is not finite exactly when its 11 exponent bits are all set; adding one at
    /// the exponent's lowest bit then carries into the sign bit. OR-ing that over the 30
    /// values needs no branch per value, and integer ORs may be regrouped, so the compiler
    /// vectorises it.
    #[inline]
    fn state_is_finite(&self) -> bool {
        const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
        const EXPONENT_ONE: u64 = 1 << 52;
        let flags = |v: &Vector3<f64>| {
            let flag = |x: f64| (x.to_bits() & EXPONENT) + EXPONENT_ONE;
            flag(v.x) | flag(v.y) | flag(v.z)
        };
        let s = &self.state;
        let mut any = flags(&s.position) | flags(&s.velocity);
        for r in &s.corner_offsets {
            any |= flags(r);
        }
        any >> 63 == 0
    }

    /// ω from L, and the step rotation from ω (reference §2 step 5, built as the authors
    /// built it from their `w = −ω` and applied to row vectors).
    fn update_spin(&mut self) {
        let (w, rotation) = match &self.loaded {
            None => spin(&self.state.angular_momentum, self.c.inertia, self.c.dt),
            Some(m) => m.spin(
                &self.state.angular_momentum,
                &self.state.corner_offsets,
                self.c.dt,
            ),
        };
        self.angular_velocity = w;
        self.step_rotation = rotation;
    }

    /// Recomputes every corner's depth and contact force at the current state (eq. 13–15).
    #[inline]
    fn update_forces(&mut self) {
        let c = self.c;
        let z0 = self.state.position.z;
        if !self.in_contact {
            // Out of contact every depth is already +0.0: look before writing them.
            let offsets = &self.state.corner_offsets;
            if !offsets.iter().fold(false, |any, r| any | (r.z + z0 < 0.0)) {
                return;
            }
        }
        let mut any = false;
        for k in 0..8 {
            let z = self.state.corner_offsets[k].z + z0;
            let depth = if z < 0.0 { -z } else { 0.0 };
            self.state.corner_depths[k] = depth;
            any |= z < 0.0;
        }
        self.in_contact = any;
        if !any {
            self.state.corner_forces = [Vector3::zeros(); 8];
            return;
        }
        let u = self.corner_velocities();
        // The authors' law scales every corner's slip by one whole-die matrix norm.
        let whole_die_norm = match c.friction_law {
            FrictionLaw::PerCorner => None,
            FrictionLaw::WholeDieNorm => Some(horizontal_matrix_norm(&u)),
        };
        self.contact_velocities = u;
        let s = &mut self.state;
        for ((force, &depth), uk) in s.corner_forces.iter_mut().zip(&s.corner_depths).zip(&u) {
            if depth <= 0.0 {
                *force = Vector3::zeros();
                continue;
            }
            let normal = depth * c.stiffness;
            let vertical = normal * (1.0 - c.damping * uk.z);
            let (fx, fy) = match whole_die_norm {
                None => {
                    let slip = (uk.x * uk.x + uk.y * uk.y).sqrt();
                    if slip > 0.0 {
                        let scale = -(c.friction * vertical.abs());
                        (scale * (uk.x / slip), scale * (uk.y / slip))
                    } else {
                        (0.0, 0.0)
                    }
                }
                Some(norm) if norm != 0.0 => (
                    -((uk.x / norm) * vertical) * c.friction,
                    -((uk.y / norm) * vertical) * c.friction,
                ),
                Some(_) => (0.0, 0.0),
            };
            *force = Vector3::new(fx, fy, vertical);
        }
    }

    /// Adds this step's work of damping and friction to the ledger.
    ///
    /// Over the kick, the kinetic energy changes by exactly `Σ F_k·Δt·ū_k`, where `ū_k` is
    /// the mean of corner k's velocity before and after the kick (at the unrotated offsets):
    /// `½M|v|²` and `½|L|²/I` are quadratic. So this is the work each force really does in
    /// the discrete step, chatter included, not a sampled power.
    fn record_contact_work(&mut self, before: &[Vector3<f64>; 8]) {
        let after = self.corner_velocities();
        let s = &self.state;
        for k in 0..8 {
            if s.corner_depths[k] > 0.0 {
                let mean = (before[k] + after[k]) * 0.5;
                let f = &s.corner_forces[k];
                let damping = f.z - s.corner_depths[k] * self.c.stiffness;
                self.work.damping += damping * mean.z * self.c.dt;
                self.work.friction += (f.x * mean.x + f.y * mean.y) * self.c.dt;
            }
        }
    }
}

/// ω = L / I and the step rotation by |ω|·Δt about ω (`None` while ω = 0), as the authors
/// built it from their `w = −ω` for row vectors: entry (i, j) is
/// `(p + cos·(δᵢⱼ − p)) + (sin·[w]×ᵢⱼ)/|ω|` with `p = (ωᵢ·ωⱼ)/|ω|²`.
///
/// Both engines call this one function (never inlined, so the two see the same libm calls
/// in the same order). Its divisions are the fewest that keep every entry bitwise: `p` is
/// symmetric (`ωᵢ·ωⱼ = ωⱼ·ωᵢ` exactly) and the cross term antisymmetric (a quotient's sign
/// follows its dividend's), so 6 + 3 quotients serve 9 + 9 entries, and the diagonal's
/// `(sin·0)/|ω|` needs no division at all.
#[inline(never)]
pub(super) fn spin(
    angular_momentum: &Vector3<f64>,
    inertia: f64,
    dt: f64,
) -> (Vector3<f64>, Option<Matrix3<f64>>) {
    let w = angular_momentum / inertia;
    let norm = scaled_norm(&w);
    if norm == 0.0 {
        return (w, None);
    }
    let theta = norm * dt;
    let norm_sq = norm.powf(2.0);
    let (sin, cos) = (theta.sin(), theta.cos());
    let p = |i: usize, j: usize| (w[i] * w[j]) / norm_sq;
    let (pxx, pyy, pzz) = (p(0, 0), p(1, 1), p(2, 2));
    let (pxy, pxz, pyz) = (p(0, 1), p(0, 2), p(1, 2));
    // [w_code]× with w_code = −ω has (0,1) = ω_z, (0,2) = −ω_y, (1,2) = ω_x.
    let (sz, sy, sx) = ((sin * w.z) / norm, (sin * -w.y) / norm, (sin * w.x) / norm);
    // `(sin·0)/|ω|` is `sin·0` itself: ±0 keeps its sign over a positive |ω| (finite or
    // ∞), and a NaN (sin of ∞ or NaN) passes through the division unchanged.
    let diagonal = sin * 0.0;
    let on = |p: f64| (p + cos * (1.0 - p)) + diagonal;
    let off = |p: f64| p + cos * (0.0 - p);
    #[rustfmt::skip]
    let m = Matrix3::new(
        on(pxx),        off(pxy) + sz,  off(pxz) + sy,
        off(pxy) + -sz, on(pyy),        off(pyz) + sx,
        off(pxz) + -sy, off(pyz) + -sx, on(pzz),
    );
    (w, Some(m))
}

/// Octave's overflow-safe 2-norm of a 3-vector (reference §9), bitwise.
fn scaled_norm(w: &Vector3<f64>) -> f64 {
    let mut scale: f64 = 0.0;
    let mut sum: f64 = 1.0;
    for t in w.iter().map(|c| c.abs()) {
        if scale == t {
            sum += 1.0;
        } else if scale < t {
            // The first nonzero component: `1·(0/t)² + 1` is exactly 1, no division needed.
            sum = if scale == 0.0 {
                1.0
            } else {
                sum * ((scale / t) * (scale / t)) + 1.0
            };
            scale = t;
        } else if t != 0.0 {
            sum += (t / scale) * (t / scale);
        }
    }
    scale * sum.sqrt()
}

/// The largest singular value of the 8×2 matrix of horizontal corner velocities, from the
/// largest eigenvalue of its 2×2 Gram matrix (within 5·10⁻¹⁶ of LAPACK's, reference §9).
fn horizontal_matrix_norm(u: &[Vector3<f64>; 8]) -> f64 {
    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
    for uk in u {
        a += uk.x * uk.x;
        b += uk.x * uk.y;
        c += uk.y * uk.y;
    }
    let half_diff = (a - c) / 2.0;
    ((a + c) / 2.0 + (half_diff * half_diff + b * b).sqrt()).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaled_norm_matches_plain_norm_closely() {
        for w in [
            [3.0, 4.0, 0.0],
            [0.0, 0.0, 0.0],
            [1e-3, -2.0, 7.5],
            [0.0, 5.0, 0.0],
        ] {
            let v = Vector3::from(w);
            assert!((scaled_norm(&v) - v.norm()).abs() <= 1e-15 * v.norm().max(1.0));
        }
        assert_eq!(scaled_norm(&Vector3::new(0.0, 5.0, 0.0)), 5.0);
    }

    #[test]
    fn matrix_norm_of_pure_slide_is_sqrt8_speed() {
        let u = [Vector3::new(3.0, 4.0, 0.0); 8];
        assert!((horizontal_matrix_norm(&u) - 5.0 * 8f64.sqrt()).abs() < 1e-12);
    }
}
