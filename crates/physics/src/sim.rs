//! The state of a rolling die and the paper's semi-implicit Euler step (docs/model.md).
//!
//! The arithmetic follows the authors' program operation by operation
//! (crates/physics/tests/data/reference/README.md §2 and §9: sums in corner order, divisions
//! where they divided, Octave's scaled 2-norm and `pow(x, 2)`), so the reference
//! trajectories are reproduced to rounding, not merely in law.

use super::body::face_most_nearly_up;
use super::contact::{Law, Paper, PerCornerSlip, SpringFriction, WholeDieSlip};
use super::energy::Energy;
use super::impact::Impacts;
use super::initial::InitialCondition;
use super::kernel::{Constants, Ends, Faces, Kernel, NoHook, StepHook};
use super::model::{Body, check_setup};
use super::params::{ContactLaw, Detail, FrictionLaw, Ground, KIND_KEY, ParamError, Params, StopEnergy};
use super::state::contact_point;
use super::stopping::StopRule;
use nalgebra::{Vector2, Vector3};
use serde::Serialize;

pub use super::state::State;

/// A rigid-body energy above this multiple of `max(initial energy, edge energy)` means the
/// integrator is feeding energy in (docs/model.md, "Stability"): a stable roll stays within a
/// few percent of its start.
pub(crate) const RUNAWAY_ENERGY_FACTOR: f64 = 10.0;

/// One corner's contact force split into the paper's three parts (eq. 13–15), dyn.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ContactForce {
    /// cm below the ground (0 when not touching).
    pub depth: f64,
    /// Spring force `k·d`, up.
    pub normal: f64,
    /// Damping force `−k·d·γ·u_z` (the vertical force is normal + damping).
    pub damping: f64,
    /// Horizontal kinetic friction `(x, y)`.
    pub friction: [f64; 2],
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
    /// Impacts in the roll (docs/model.md, "Impacts": a contact after at least one state
    /// with the whole body clear of the table).
    pub impacts: u64,
    /// The first of them; `None` when there was none (a die placed on the table that never
    /// left it).
    pub first_impact: Option<FirstImpact>,
}

/// The state at which a roll's first impact begins.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FirstImpact {
    /// Steps taken when it began.
    pub step: u64,
    /// s of simulated time when it began.
    pub time_s: f64,
    /// The face most nearly down then, by the number printed on it (the box's 1..6: the one
    /// opposite the face most nearly up; a polyhedral die's, [`crate::PointBody::face_down`]:
    /// the number on the face opposite the face most nearly up, which on the d4, whose
    /// faces have no opposites, is the number at the vertex most nearly down).
    pub face_down: u8,
}

/// A roll's impacts as its states are seen, by the one definition ([`Impacts`]), with the
/// first one's state: both engines keep one per roll and fill it alike.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ImpactLog {
    pub(crate) impacts: Impacts,
    pub(crate) first: Option<FirstImpact>,
}

impl ImpactLog {
    /// A roll whose first state is in contact or not.
    pub(crate) fn new(in_contact: bool) -> ImpactLog {
        ImpactLog {
            impacts: Impacts::new(in_contact),
            first: None,
        }
    }

    /// The next state's contact; `state` (the face most nearly down, the step and the time)
    /// is asked only when the first impact begins at it.
    #[inline(always)]
    pub(crate) fn observe(&mut self, in_contact: bool, state: impl FnOnce() -> (u8, u64, f64)) {
        if self.impacts.observe(in_contact) && self.first.is_none() {
            self.first = Some(first_impact(state()));
        }
    }
}

#[cold]
fn first_impact((face_down, step, time_s): (u8, u64, f64)) -> FirstImpact {
    FirstImpact {
        step,
        time_s,
        face_down,
    }
}

/// The box's face most nearly down with its corners at `corner_offsets`: opposite faces sum
/// to 7 (face i's normal is face 7 − i's, reversed).
#[cold]
pub(crate) fn box_face_down(corner_offsets: &[Vector3<f64>; 8]) -> u8 {
    7 - face_most_nearly_up(corner_offsets)
}

/// Steps between two looks at a stop request in [`Simulation::run_until_stopped`]: a few
/// tenths of a millisecond of stepping, so a cancel is answered well within 0.2 s.
pub const STEPS_BETWEEN_STOP_CHECKS: u64 = 4096;

/// The paper's law with each point's own slip (its eq. 15), and with the authors' whole-die
/// norm.
pub(crate) type PaperPerCorner = Paper<PerCornerSlip>;
pub(crate) type PaperWholeDie = Paper<WholeDieSlip>;

/// The scalar kernel under the contact law the parameters name: each law's step is its own
/// code, and the engines pick it once per roll.
// The spring-friction kernel is the largest (its points remember more); a roll holds one and
// steps it in place, so a box would only put every step behind a pointer.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
pub(crate) enum Laws {
    Paper(Kernel<f64, PaperPerCorner>),
    PaperWholeDie(Kernel<f64, PaperWholeDie>),
    SpringFriction(Kernel<f64, SpringFriction>),
}

/// `$body` with `$k` bound to the kernel in `$laws`, a variant of `$enum` ([`Laws`], or
/// `PointKernel` for a body of points), whatever its law.
macro_rules! on_law {
    ($enum:ident, $laws:expr, $k:ident => $body:expr) => {
        match $laws {
            $enum::Paper($k) => $body,
            $enum::PaperWholeDie($k) => $body,
            $enum::SpringFriction($k) => $body,
        }
    };
}
pub(crate) use on_law;

/// `$make` for the law `$p`'s ground names, wrapped in its variant of `$enum`.
macro_rules! by_law {
    ($enum:ident, $p:expr, $make:expr) => {
        match ($p.ground.contact, $p.ground.friction_law) {
            (ContactLaw::Paper, FrictionLaw::PerCorner) => $enum::Paper($make),
            (ContactLaw::Paper, FrictionLaw::WholeDieNorm) => $enum::PaperWholeDie($make),
            (ContactLaw::SpringFriction, _) => $enum::SpringFriction($make),
        }
    };
}
pub(crate) use by_law;

impl Laws {
    /// The kernel of `params`' law, the die placed at `initial`.
    fn new(params: &Params, initial: &InitialCondition) -> Laws {
        by_law!(Laws, params, Kernel::new(params, initial))
    }
}

/// A contact law as the engines hold it: which variant of [`Laws`] is its kernel.
pub(crate) trait EngineLaw: Law {
    fn of(k: &Laws) -> Option<&Kernel<f64, Self>>;
    fn of_mut(k: &mut Laws) -> Option<&mut Kernel<f64, Self>>;
}

/// [`EngineLaw`] for the law `$law`, the variant `$variant` of `$enum`.
macro_rules! engine_law {
    ($trait:ident, $enum:ident, $law:ty, $variant:ident $(, $n:ident)?) => {
        impl $trait for $law {
            #[inline(always)]
            fn of$(<const $n: usize>)?(k: &$enum$(<$n>)?) -> Option<&Kernel<f64, Self $(, $n, PointBody<$n>)?>> {
                match k {
                    $enum::$variant(k) => Some(k),
                    _ => None,
                }
            }
            #[inline(always)]
            fn of_mut$(<const $n: usize>)?(k: &mut $enum$(<$n>)?) -> Option<&mut Kernel<f64, Self $(, $n, PointBody<$n>)?>> {
                match k {
                    $enum::$variant(k) => Some(k),
                    _ => None,
                }
            }
        }
    };
}
pub(crate) use engine_law;

engine_law!(EngineLaw, Laws, PaperPerCorner, Paper);
engine_law!(EngineLaw, Laws, PaperWholeDie, PaperWholeDie);
engine_law!(EngineLaw, Laws, SpringFriction, SpringFriction);

/// A die rolling from an initial condition: the scalar engine, the step kernel on `f64`.
#[derive(Debug, Clone)]
pub struct Simulation {
    params: Params,
    /// The state and everything the step needs; visible to the lane engine (lanes.rs),
    /// which loads rolls from it and stores them back, so that both engines start and end
    /// alike.
    pub(super) k: Laws,
    /// The roll's impacts so far (the lane engine carries a lane's and stores it back).
    pub(super) impact_log: ImpactLog,
    /// Whether the energy ledger is kept (its work sums cost a second pass over the
    /// corners per contact step, which a batch that only wants outcomes skips).
    track_ledger: bool,
    ledger: Ledger,
    /// erg, rigid-body energy at t = 0.
    initial_energy: f64,
    /// The stopping rule of these parameters (a loaded die's depends on the face down).
    stop_rule: StopRule,
    outcome: Option<Outcome>,
}

/// The energy ledger's bookkeeping for a body of `N` contact points, a hook the step calls
/// while the ledger is kept (the box's and a polyhedral die's alike).
#[derive(Debug, Clone)]
pub(crate) struct Ledger<const N: usize = 8> {
    /// cm/s, the contact points' velocities before the kick, taken while in contact.
    before: Option<[Vector3<f64>; N]>,
    /// erg, work done on the die by damping and by friction since t = 0 (negative: lost).
    work: ContactWork,
}

impl<const N: usize> Default for Ledger<N> {
    fn default() -> Self {
        Ledger {
            before: None,
            work: ContactWork::default(),
        }
    }
}

impl<const N: usize> Ledger<N> {
    /// Where the energy went between `initial` and `current` (erg) by this ledger's work.
    pub(crate) fn energy_ledger(&self, initial: f64, current: f64) -> EnergyLedger {
        let (damping_loss, friction_loss) = (-self.work.damping, -self.work.friction);
        EnergyLedger {
            initial,
            current,
            damping_loss,
            friction_loss,
            integrator_loss: initial - current - damping_loss - friction_loss,
        }
    }
}

impl<W: Law, const N: usize, B: Faces<N>> StepHook<f64, W, N, B> for Ledger<N> {
    #[inline]
    fn before_kick(&mut self, k: &Kernel<f64, W, N, B>) {
        self.before = k.in_contact.then(|| corner_velocities(k));
    }

    /// Adds this step's work of damping and friction to the ledger.
    ///
    /// Over the kick, the kinetic energy changes by exactly `Σ F_k·Δt·ū_k`, where `ū_k` is
    /// the mean of corner k's velocity before and after the kick (at the unrotated offsets):
    /// `½M|v|²` and `½|L|²/I` are quadratic. So this is the work each force really does in
    /// the discrete step, chatter included, not a sampled power.
    #[inline]
    fn after_spin(&mut self, k: &Kernel<f64, W, N, B>) {
        let Some(before) = self.before.take() else { return };
        let after = corner_velocities(k);
        let s = &k.state;
        for k_ in 0..N {
            if s.corner_depths[k_] > 0.0 {
                let mean = (before[k_] + after[k_]) * 0.5;
                let f = &s.corner_forces[k_];
                let damping = f.z - s.corner_depths[k_] * W::stiffness(&k.c.law);
                self.work.damping += damping * mean.z * k.c.dt;
                self.work.friction += (f.x * mean.x + f.y * mean.y) * k.c.dt;
            }
        }
    }
}

/// Velocities of the contact points (corners 1..8 of a box; a rounded body's contact
/// points), cm/s.
fn corner_velocities<W: Law, const N: usize, B: Faces<N>>(k: &Kernel<f64, W, N, B>) -> [Vector3<f64>; N] {
    let radii = &k.c.body.corner_radii;
    std::array::from_fn(|c| {
        k.corner_velocity(&contact_point::<true, f64>(&k.state.corner_offsets[c], radii[c]))
    })
}

/// Each contact point's force split into normal, damping and friction at `k`'s state.
pub(crate) fn contact_forces_of<W: Law, const N: usize, B: Faces<N>>(
    k: &Kernel<f64, W, N, B>,
) -> [ContactForce; N] {
    let s = &k.state;
    let stiffness = W::stiffness(&k.c.law);
    std::array::from_fn(|p| {
        let depth = s.corner_depths[p];
        let normal = depth * stiffness;
        ContactForce {
            depth,
            normal,
            damping: s.corner_forces[p].z - normal,
            friction: [s.corner_forces[p].x, s.corner_forces[p].y],
        }
    })
}

impl Simulation {
    /// Validates the parameters and the initial condition (no corner may start inside the
    /// table), then places the die.
    /// A polyhedral die (`die.kind`) is refused: this engine rolls the box; a polyhedral die
    /// rolls in [`crate::lanes::roll_in_lanes`] and [`crate::lanes::roll_one_by_one`].
    pub fn new(params: &Params, initial: &InitialCondition) -> Result<Self, ParamError> {
        check_setup(params, initial)?;
        refuse_polyhedral_die(params, "this command")?;
        Ok(Self::new_unchecked(params, initial))
    }

    /// Like [`Simulation::new`] without the range checks. Any input still ends in a status:
    /// non-finite or absurd values end the first step as [`Status::Unstable`].
    pub fn new_unchecked(params: &Params, initial: &InitialCondition) -> Self {
        let k = Laws::new(params, initial);
        let body = *sim_body(&k);
        let mut sim = Simulation {
            params: *params,
            k,
            track_ledger: true,
            ledger: Ledger::default(),
            initial_energy: 0.0,
            stop_rule: stop_rule_on_table(params, body.stop_rule(), body.edge_energy()),
            outcome: None,
            impact_log: ImpactLog::new(false),
        };
        sim.impact_log = ImpactLog::new(sim.in_contact());
        sim.initial_energy = sim.energy().total();
        let runaway = RUNAWAY_ENERGY_FACTOR * sim.initial_energy.max(body.edge_energy());
        on_law!(Laws, &mut sim.k, k => k.c.stop.runaway = runaway);
        sim
    }

    /// Like [`Simulation::new_unchecked`] for a roll whose outcome alone is wanted (batches,
    /// maps): the same trajectory bit for bit, without the energy ledger's bookkeeping, so
    /// its [`energy_ledger`](Simulation::energy_ledger) must not be asked for.
    pub fn for_outcome(params: &Params, initial: &InitialCondition) -> Self {
        let mut sim = Self::new_unchecked(params, initial);
        sim.track_ledger = false;
        sim
    }

    pub fn params(&self) -> &Params {
        &self.params
    }

    pub fn state(&self) -> &State {
        on_law!(Laws, &self.k, k => &k.state)
    }

    /// cm, each contact point's tangential spring `ξ` in the table's plane: the slip it made
    /// since it touched the table, as the spring-friction law holds it (0 off the table, and
    /// always 0 under the paper's law, which keeps none).
    pub fn tangential_springs(&self) -> [Vector2<f64>; 8] {
        on_law!(Laws, &self.k, k => tangential_springs(k))
    }

    /// rad/s, world frame.
    pub fn angular_velocity(&self) -> Vector3<f64> {
        on_law!(Laws, &self.k, k => k.angular_velocity)
    }

    /// The end of the roll, once it has ended (later steps do not change it).
    pub fn outcome(&self) -> Option<Outcome> {
        self.outcome
    }

    /// Where the energy has gone since t = 0.
    pub fn energy_ledger(&self) -> EnergyLedger {
        debug_assert!(self.track_ledger, "a roll built for its outcome keeps no ledger");
        self.ledger
            .energy_ledger(self.initial_energy, self.energy().total())
    }

    /// Whether any corner is below the ground now.
    pub fn in_contact(&self) -> bool {
        on_law!(Laws, &self.k, k => k.in_contact)
    }

    /// Changes the ground mid-roll; the new law acts from the next step on.
    pub fn set_ground(&mut self, ground: Ground) -> Result<(), ParamError> {
        let mut params = self.params;
        params.ground = ground;
        params.validate()?;
        self.params = params;
        // The stopping rules of every body depend on the table.
        let body = Body::new(&params);
        self.stop_rule = stop_rule_on_table(&params, body.stop_rule(), body.edge_energy());
        self.k = by_law!(Laws, params, under_law(&self.k, &params, body));
        Ok(())
    }

    /// World positions of corners 1..8, cm (a rounded body's: its corner spheres' centres,
    /// `die.corner_radius` inside the surface).
    pub fn corner_positions(&self) -> [Vector3<f64>; 8] {
        let s = self.state();
        s.corner_offsets.map(|r| s.position + r)
    }

    /// Each corner's contact force split into normal, damping and friction, at the current
    /// state (the forces the next step will apply).
    pub fn contact_forces(&self) -> [ContactForce; 8] {
        on_law!(Laws, &self.k, k => contact_forces_of(k))
    }

    /// The energy terms at the current state (docs/model.md, "Energy"), erg.
    pub fn energy(&self) -> Energy {
        on_law!(Laws, &self.k, k => k.energy()).into()
    }

    /// erg, the energy the authors' program compared with the threshold: the corners as 8
    /// point masses and the ground term `½·Σ d_k·P_k` with the damped force (reference §2).
    pub fn point_mass_energy(&self) -> f64 {
        on_law!(Laws, &self.k, k => k.point_mass_parts().1)
    }

    /// `(kinetic, total)` of the stop energy.
    fn stop_energy_parts(&self) -> (f64, f64) {
        match self.params.integrator.stop_energy {
            StopEnergy::RigidBody => {
                let energy = self.energy();
                (energy.kinetic(), energy.total())
            }
            StopEnergy::PointMasses => on_law!(Laws, &self.k, k => k.point_mass_parts()),
        }
    }

    /// erg, the energy the stopping rule uses (`integrator.stop_energy`).
    pub fn stop_energy(&self) -> f64 {
        self.stop_energy_parts().1
    }

    /// erg, the kinetic part of the stop energy.
    pub fn stop_kinetic_energy(&self) -> f64 {
        self.stop_energy_parts().0
    }

    /// erg, the stop energy's threshold (docs/model.md, "Stopping rule").
    pub fn stop_threshold(&self) -> f64 {
        self.stop_rule.energy_threshold
    }

    /// The stopping rule's thresholds for these parameters.
    pub fn stop_rule(&self) -> StopRule {
        self.stop_rule
    }

    /// The stopping rule for the current state: a loaded die's or a general body's depends
    /// on the face down (what a report of a finished roll prints; [`Simulation::stop_rule`]
    /// is the fair die's, or the widest over the faces).
    pub fn stop_rule_now(&self) -> StopRule {
        let body = sim_body(&self.k);
        let rule = body.stop_rule_at(&self.state().corner_offsets);
        stop_rule_on_table(&self.params, rule, body.edge_energy())
    }

    /// The face whose outward normal points most nearly up (the live display's face).
    pub fn face_up(&self) -> u8 {
        face_most_nearly_up(&self.state().corner_offsets)
    }

    /// The body's x, y and z axes in the world frame, unit vectors read off its corners
    /// (the orientation's columns).
    pub fn body_axes(&self) -> [Vector3<f64>; 3] {
        sim_body(&self.k).axes(&self.state().corner_offsets)
    }

    /// One step of Δt: kick → drift → L → rotate → forces (docs/model.md, "One time step").
    ///
    /// Steps on past the end of a roll if asked; the recorded outcome stays the first end.
    #[inline]
    pub fn step(&mut self) {
        match self.k {
            Laws::Paper(_) => self.step_by::<PaperPerCorner>(),
            Laws::PaperWholeDie(_) => self.step_by::<PaperWholeDie>(),
            Laws::SpringFriction(_) => self.step_by::<SpringFriction>(),
        }
    }

    /// [`Simulation::step`] with the law known.
    #[inline(always)]
    fn step_by<W: EngineLaw>(&mut self) {
        if self.track_ledger {
            self.step_with_ledger();
        } else {
            kernel_of::<W>(&mut self.k).step(&mut NoHook);
        }
        let k = kernel_of::<W>(&mut self.k);
        let s = &k.state;
        self.impact_log.observe(k.in_contact, || {
            (box_face_down(&s.corner_offsets), s.step, s.time_s)
        });
    }

    /// The step with the energy ledger's bookkeeping, kept out of line: inlined beside the
    /// plain step, its second copy of the kernel would crowd the batch loop's code.
    #[inline(never)]
    fn step_with_ledger(&mut self) {
        on_law!(Laws, &mut self.k, k => k.step(&mut self.ledger));
    }

    /// [`Simulation::advance`] on the spring-friction law, out of line for the same reason:
    /// the paper's step and end test stay the ones inlined into the batch loop.
    #[inline(never)]
    fn advance_spring_friction(&mut self) -> Option<Outcome> {
        self.advance_by::<SpringFriction>()
    }

    /// [`Simulation::advance`] on the authors' whole-die norm, out of line likewise.
    #[inline(never)]
    fn advance_whole_die(&mut self) -> Option<Outcome> {
        self.advance_by::<PaperWholeDie>()
    }

    /// One step, then the end-of-roll checks; returns the outcome on the step that ends it.
    #[inline]
    pub fn advance(&mut self) -> Option<Outcome> {
        match self.k {
            Laws::Paper(_) => self.advance_by::<PaperPerCorner>(),
            Laws::PaperWholeDie(_) => self.advance_whole_die(),
            Laws::SpringFriction(_) => self.advance_spring_friction(),
        }
    }

    /// [`Simulation::advance`] with the law known.
    #[inline(always)]
    fn advance_by<W: EngineLaw>(&mut self) -> Option<Outcome> {
        self.step_by::<W>();
        if self.outcome.is_some() {
            return None;
        }
        let outcome = self.check_end::<W>()?;
        self.outcome = Some(outcome);
        Some(outcome)
    }

    /// Steps until the roll ends (settled, did not settle, or unstable).
    pub fn run_to_end(&mut self) -> Outcome {
        self.run_until_stopped(&|| false)
            .expect("a roll that is never stopped ends")
    }

    /// Steps until the roll ends, or until `stop()` answers true (asked every
    /// [`STEPS_BETWEEN_STOP_CHECKS`] steps): `None` then, and the roll can be continued.
    pub fn run_until_stopped(&mut self, stop: &dyn Fn() -> bool) -> Option<Outcome> {
        if let Some(o) = self.outcome {
            return Some(o);
        }
        // The law is matched once per run, not per step.
        match self.k {
            Laws::Paper(_) => self.run_by::<PaperPerCorner>(stop),
            Laws::PaperWholeDie(_) => self.run_whole_die(stop),
            Laws::SpringFriction(_) => self.run_spring_friction(stop),
        }
    }

    /// [`Simulation::run_until_stopped`] on the authors' whole-die norm, out of line: the
    /// paper's step stays the one inlined into the batch loop.
    #[inline(never)]
    fn run_whole_die(&mut self, stop: &dyn Fn() -> bool) -> Option<Outcome> {
        self.run_by::<PaperWholeDie>(stop)
    }

    /// [`Simulation::run_until_stopped`] on the spring-friction law, out of line likewise.
    #[inline(never)]
    fn run_spring_friction(&mut self, stop: &dyn Fn() -> bool) -> Option<Outcome> {
        self.run_by::<SpringFriction>(stop)
    }

    /// [`Simulation::run_until_stopped`] with the law known: the kernel taken out of the
    /// enum once, then stepped and tested step by step.
    #[inline(always)]
    fn run_by<W: EngineLaw>(&mut self, stop: &dyn Fn() -> bool) -> Option<Outcome> {
        let Simulation {
            k,
            impact_log,
            track_ledger,
            ledger,
            outcome,
            ..
        } = self;
        let k = W::of_mut(k).expect("the law just matched");
        loop {
            for _ in 0..STEPS_BETWEEN_STOP_CHECKS {
                if *track_ledger {
                    step_with_ledger(k, ledger);
                } else {
                    k.step(&mut NoHook);
                }
                let s = &k.state;
                impact_log.observe(k.in_contact, || {
                    (box_face_down(&s.corner_offsets), s.step, s.time_s)
                });
                if let Some(status) = status_of(&k.ends()) {
                    let ended = outcome_of(k, impact_log, status);
                    *outcome = Some(ended);
                    return Some(ended);
                }
            }
            if stop() {
                return None;
            }
        }
    }

    /// Ends the roll as `status` at the current state (the lane engine, whose kernel
    /// decided it on the lane this roll's state was stored back from).
    pub(super) fn finish(&mut self, status: Status) -> Outcome {
        let outcome = self.outcome_of(status);
        self.outcome = Some(outcome);
        outcome
    }

    /// Whether the current state ends the roll, and how (the kernel's end-of-step test).
    #[inline]
    fn check_end<W: EngineLaw>(&self) -> Option<Outcome> {
        let status = status_of(&W::of(&self.k).expect("the law the step took").ends())?;
        Some(self.outcome_of(status))
    }

    #[cold]
    fn outcome_of(&self, status: Status) -> Outcome {
        on_law!(Laws, &self.k, k => outcome_of(k, &self.impact_log, status))
    }
}

/// The refusal of a polyhedral die by `what`, which rolls the box only: never a box rolled in
/// its place (a polyhedral die rolls as a [`crate::Roll`]).
pub(crate) fn refuse_polyhedral_die(params: &Params, what: &str) -> Result<(), ParamError> {
    if !params.die.is_polyhedral() {
        return Ok(());
    }
    Err(ParamError {
        key: KIND_KEY.key.to_string(),
        value: f64::NAN,
        limits: KIND_KEY,
        detail: Some(Box::new(Detail::Refused(format!(
            "a {} is a body of its points, which {what} does not roll: roll it as a `Roll`",
            params.die.kind.name()
        )))),
    })
}

/// The outcome of the roll in `k`, whose impacts `impact_log` saw, ending as `status`.
#[cold]
fn outcome_of<W: Law>(k: &Kernel<f64, W>, impact_log: &ImpactLog, status: Status) -> Outcome {
    Outcome {
        status,
        face: match status {
            Status::Settled => k.bodies[0].face_up_at_rest(&k.state.corner_offsets),
            _ => None,
        },
        steps: k.state.step,
        time_s: k.state.time_s,
        impacts: impact_log.impacts.count(),
        first_impact: impact_log.first,
    }
}

/// One step with the energy ledger's bookkeeping, kept out of line: inlined beside the
/// plain step, its second copy of the kernel would crowd the batch loop's code.
#[inline(never)]
fn step_with_ledger<W: Law>(k: &mut Kernel<f64, W>, ledger: &mut Ledger) {
    k.step(ledger);
}

/// How a roll ends at a state the end-of-step test says `ends` of (unstable before settled
/// before out of time), if it ends.
#[inline(always)]
pub(crate) fn status_of(ends: &Ends<bool>) -> Option<Status> {
    if ends.unstable {
        Some(Status::Unstable)
    } else if ends.settled {
        Some(Status::Settled)
    } else if ends.timeout {
        Some(Status::Timeout)
    } else {
        None
    }
}

/// The kernel of the law `W`, which the caller has matched.
#[inline(always)]
fn kernel_of<W: EngineLaw>(k: &mut Laws) -> &mut Kernel<f64, W> {
    W::of_mut(k).expect("the law the step took")
}

/// The roll's body.
fn sim_body(k: &Laws) -> &Body {
    on_law!(Laws, k, k => &k.bodies[0])
}

/// `rule` as `params`' law has it on its table.
fn stop_rule_on_table(params: &Params, rule: StopRule, edge_energy: f64) -> StopRule {
    match params.ground.contact {
        ContactLaw::Paper => PaperPerCorner::stop_rule(rule, params, edge_energy),
        ContactLaw::SpringFriction => SpringFriction::stop_rule(rule, params, edge_energy),
    }
}

/// The roll in `k` under `params`' law `V` (the ground changed): the runaway bound kept, a
/// point's memory kept where the law stays, forgotten where it changes.
fn under_law<V: EngineLaw>(k: &Laws, params: &Params, body: Body) -> Kernel<f64, V> {
    let mut c = Constants::<f64, V>::new(params, &body);
    c.stop.runaway = on_law!(Laws, k, k => k.c.stop.runaway);
    let mut kernel = on_law!(Laws, k, k => k.under::<V>(c, body));
    if let Some(same) = V::of(k) {
        kernel.points = same.points;
    }
    kernel.update_forces();
    kernel
}

/// [`Simulation::tangential_springs`] of a kernel.
fn tangential_springs<W: Law>(k: &Kernel<f64, W>) -> [Vector2<f64>; 8] {
    k.points.each_ref().map(W::tangential_spring)
}
