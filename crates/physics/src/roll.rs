//! One roll of any die a preset names, step by step, with everything a live view, a trace or
//! a report reads: the box by the paper's [`Simulation`] (it holds one, so its numbers are
//! the box's bit for bit), a polyhedral die (`die.kind`) by a [`PointRoll`](crate::PointRoll) of as many points
//! as its solid has vertices, the same trajectory `batch` rolls.
//!
//! The readouts are the box's and a die's alike, sized by the die's points (8 corners, or a
//! die's vertices); what only the box has (its point-mass energy, its pips) is read off
//! [`Roll::simulation`].

use super::energy::Energy;
use super::initial::InitialCondition;
use super::lanes::{DiceBody, DiceRoll, dice_body, on_points};
use super::model::check_setup;
use super::params::{Ground, ParamError, Params};
use super::sim::{ContactForce, EnergyLedger, Outcome, Simulation};
use super::stability_contact::BodyFigures;
use super::stopping::StopRule;
use nalgebra::{Matrix3, Rotation3, Vector2, Vector3};

/// One roll of any die from an initial condition (module docs).
#[derive(Debug, Clone)]
pub struct Roll {
    engine: Engine,
    /// The number the face most nearly up showed at t = 0.
    start_face: u8,
}

#[derive(Debug, Clone)]
// A roll is made once and stepped in place; boxing the larger die would add a pointer to
// every step for nothing.
#[allow(clippy::large_enum_variant)]
enum Engine {
    Box(Simulation),
    Die {
        params: Params,
        roll: DiceRoll,
        /// cm, each vertex's rounding radius (the body's points past them are the padding
        /// `lanes::dice_body` adds, at the centre of mass, never touching: no readout shows
        /// them); g, the mass one point carries; cm, how far a point may move in a step
        /// (docs/model.md, "A polyhedral die's readings").
        radii: Vec<f64>,
        point_mass: f64,
        travel_allowed: f64,
    },
}

/// `$body` with `$r` bound to the engine's roll, the box's [`Simulation`] or a die's
/// [`PointRoll`](crate::PointRoll), whatever its points (their methods share these names).
macro_rules! on_engine {
    ($engine:expr, $r:ident => $body:expr) => {
        match $engine {
            Engine::Box($r) => $body,
            Engine::Die { roll, .. } => on_points!(roll, $r => $body),
        }
    };
}

impl Roll {
    /// Validates the parameters and the initial condition (no point may start inside the
    /// table), then places the die.
    pub fn new(params: &Params, initial: &InitialCondition) -> Result<Roll, ParamError> {
        check_setup(params, initial)?;
        Ok(Roll::new_unchecked(params, initial))
    }

    /// [`Roll::new`] without the checks; any input still ends in a status, as
    /// [`Simulation::new_unchecked`]'s does. The energy ledger is kept.
    pub fn new_unchecked(params: &Params, initial: &InitialCondition) -> Roll {
        Roll::made(params, initial, true)
    }

    /// [`Roll::new_unchecked`] for a roll whose outcome alone is wanted: the same trajectory
    /// bit for bit, without the ledger ([`Roll::energy_ledger`] must not be asked).
    pub fn for_outcome(params: &Params, initial: &InitialCondition) -> Roll {
        Roll::made(params, initial, false)
    }

    fn made(params: &Params, initial: &InitialCondition, ledger: bool) -> Roll {
        let engine = if params.die.is_polyhedral() {
            let mut roll = dice_body(params).roll(params, initial);
            if ledger {
                on_points!(&mut roll, r => r.keep_ledger());
            }
            let figures = BodyFigures::of(params);
            let radii = figures.points.iter().flatten().map(|&(_, r)| r).collect();
            Engine::Die {
                params: *params,
                roll,
                radii,
                point_mass: figures.point_mass,
                travel_allowed: figures.travel_allowed,
            }
        } else if ledger {
            Engine::Box(Simulation::new_unchecked(params, initial))
        } else {
            Engine::Box(Simulation::for_outcome(params, initial))
        };
        let start_face = on_engine!(&engine, r => r.face_up());
        Roll { engine, start_face }
    }

    pub fn params(&self) -> &Params {
        match &self.engine {
            Engine::Box(sim) => sim.params(),
            Engine::Die { params, .. } => params,
        }
    }

    /// The box's engine, for what only the box has; `None` for a polyhedral die.
    pub fn simulation(&self) -> Option<&Simulation> {
        match &self.engine {
            Engine::Box(sim) => Some(sim),
            Engine::Die { .. } => None,
        }
    }

    /// Whether it is a polyhedral die (not the box).
    pub fn is_polyhedral(&self) -> bool {
        matches!(self.engine, Engine::Die { .. })
    }

    /// The numbers it can show, in the order its tables list them.
    pub fn face_numbers(&self) -> &'static [u8] {
        self.params().die.face_numbers()
    }

    /// s, simulated time.
    pub fn time_s(&self) -> f64 {
        on_engine!(&self.engine, r => r.state().time_s)
    }

    /// Steps of Δt taken since the start.
    pub fn steps(&self) -> u64 {
        on_engine!(&self.engine, r => r.state().step)
    }

    /// cm, the centre of mass (world frame).
    pub fn position(&self) -> Vector3<f64> {
        on_engine!(&self.engine, r => r.state().position)
    }

    /// cm/s, the centre of mass's velocity.
    pub fn velocity(&self) -> Vector3<f64> {
        on_engine!(&self.engine, r => r.state().velocity)
    }

    /// g·cm²/s, about the centre of mass.
    pub fn angular_momentum(&self) -> Vector3<f64> {
        on_engine!(&self.engine, r => r.state().angular_momentum)
    }

    /// rad/s, world frame.
    pub fn angular_velocity(&self) -> Vector3<f64> {
        on_engine!(&self.engine, r => r.angular_velocity())
    }

    /// The body frame's turn into the world: a point `p` of the body's frame, about its
    /// centre of mass, lies at `orientation · p` from the centre. The box's columns are
    /// [`Simulation::body_axes`]; a polyhedral die's frame is that of its solid's vertices
    /// (`params.polyhedral_die()`), taken about its centre of mass.
    pub fn orientation(&self) -> Rotation3<f64> {
        let matrix = match &self.engine {
            Engine::Box(sim) => Matrix3::from_columns(&sim.body_axes()),
            Engine::Die { roll, .. } => on_points!(roll, r => r.orientation()),
        };
        Rotation3::from_matrix_unchecked(matrix)
    }

    /// How many contact points it has: the box's 8 corners, a die's vertices.
    pub fn point_count(&self) -> usize {
        match &self.engine {
            Engine::Box(_) => 8,
            Engine::Die { radii, .. } => radii.len(),
        }
    }

    /// cm, the contact points about the centre of mass, world frame: the box's corners 1..8,
    /// a die's vertices (a rounded one's sphere centres) in its solid's order.
    pub fn point_offsets(&self) -> Vec<Vector3<f64>> {
        let count = self.point_count();
        on_engine!(&self.engine, r => r.state().corner_offsets[..count].to_vec())
    }

    /// cm, the contact points' world positions.
    pub fn point_positions(&self) -> Vec<Vector3<f64>> {
        let centre = self.position();
        self.point_offsets().into_iter().map(|r| centre + r).collect()
    }

    /// Each point's contact force split into normal, damping and friction, at the current
    /// state (the forces the next step applies).
    pub fn contact_forces(&self) -> Vec<ContactForce> {
        let count = self.point_count();
        on_engine!(&self.engine, r => r.contact_forces()[..count].to_vec())
    }

    /// cm, each point's tangential spring in the table's plane (0 under the paper's law).
    pub fn tangential_springs(&self) -> Vec<Vector2<f64>> {
        let count = self.point_count();
        on_engine!(&self.engine, r => r.tangential_springs()[..count].to_vec())
    }

    /// Whether any point is below the table now.
    pub fn in_contact(&self) -> bool {
        on_engine!(&self.engine, r => r.in_contact())
    }

    /// The energy terms now, erg.
    pub fn energy(&self) -> Energy {
        on_engine!(&self.engine, r => r.energy())
    }

    /// Where the energy has gone since t = 0 (not for a roll made [`Roll::for_outcome`]).
    pub fn energy_ledger(&self) -> EnergyLedger {
        on_engine!(&self.engine, r => r.energy_ledger())
    }

    /// The number the face most nearly up shows now: the box's face, a die's number as a
    /// player reads it (docs/dice.md; the d4's as printed).
    pub fn face_up(&self) -> u8 {
        on_engine!(&self.engine, r => r.face_up())
    }

    /// The same at t = 0.
    pub fn start_face(&self) -> u8 {
        self.start_face
    }

    /// The end of the roll, once it has ended (later steps do not change it).
    pub fn outcome(&self) -> Option<Outcome> {
        match &self.engine {
            Engine::Box(sim) => sim.outcome(),
            Engine::Die { roll, .. } => on_points!(roll, r => r.full_outcome()),
        }
    }

    /// One step of Δt; steps on past the end if asked, the outcome staying the first end.
    pub fn step(&mut self) {
        on_engine!(&mut self.engine, r => r.step())
    }

    /// One step, then the end-of-roll test: the outcome on the step that ends the roll.
    pub fn advance(&mut self) -> Option<Outcome> {
        match &mut self.engine {
            Engine::Box(sim) => sim.advance(),
            Engine::Die { roll, .. } => on_points!(roll, r => r.advance().and_then(|_| r.full_outcome())),
        }
    }

    /// Steps until the roll ends.
    pub fn run_to_end(&mut self) -> Outcome {
        self.run_until_stopped(&|| false)
            .expect("a roll that is never stopped ends")
    }

    /// Steps until the roll ends, or until `stop()` answers true (asked every
    /// [`crate::STEPS_BETWEEN_STOP_CHECKS`] steps): `None` then, and the roll can go on.
    pub fn run_until_stopped(&mut self, stop: &dyn Fn() -> bool) -> Option<Outcome> {
        on_engine!(&mut self.engine, r => r.run_until_stopped(stop))
    }

    /// erg, the energy the stopping rule reads (`integrator.stop_energy` for the box; a die's
    /// rigid-body energy).
    pub fn stop_energy(&self) -> f64 {
        match &self.engine {
            Engine::Box(sim) => sim.stop_energy(),
            Engine::Die { .. } => self.energy().total(),
        }
    }

    /// erg, the kinetic part of the stop energy.
    pub fn stop_kinetic_energy(&self) -> f64 {
        match &self.engine {
            Engine::Box(sim) => sim.stop_kinetic_energy(),
            Engine::Die { .. } => self.energy().kinetic(),
        }
    }

    /// erg, the stop energy's threshold (the widest over a die's faces where they differ).
    pub fn stop_threshold(&self) -> f64 {
        self.stop_rule().energy_threshold
    }

    /// The stopping rule on this table (the widest over the faces where they differ).
    pub fn stop_rule(&self) -> StopRule {
        on_engine!(&self.engine, r => r.stop_rule())
    }

    /// The stopping rule of the face it lies on now.
    pub fn stop_rule_now(&self) -> StopRule {
        on_engine!(&self.engine, r => r.stop_rule_now())
    }

    /// Changes the table mid-roll; the new law acts from the next step on, and a die's
    /// stopping rules are derived anew for it.
    pub fn set_ground(&mut self, ground: Ground) -> Result<(), ParamError> {
        match &mut self.engine {
            Engine::Box(sim) => sim.set_ground(ground),
            Engine::Die { params, roll, .. } => {
                let mut changed = *params;
                changed.ground = ground;
                changed.validate()?;
                match (roll, dice_body(&changed)) {
                    (DiceRoll::P4(r), DiceBody::P4(b)) => r.set_table(&changed, &b)?,
                    (DiceRoll::P6(r), DiceBody::P6(b)) => r.set_table(&changed, &b)?,
                    (DiceRoll::P12(r), DiceBody::P12(b)) => r.set_table(&changed, &b)?,
                    (DiceRoll::P20(r), DiceBody::P20(b)) => r.set_table(&changed, &b)?,
                    _ => unreachable!("the table does not change the die's points"),
                }
                *params = changed;
                Ok(())
            }
        }
    }
}

/// What every readout of a rolling die reads, whatever engine rolls it: the box's
/// [`Simulation`] (a batch's, a test's) or any die's [`Roll`]. The quantities a plot or a trace
/// shows (`dicesim_setup::quantity`) and the separation of two throws read a die through it.
pub trait RollingDie {
    fn params(&self) -> &Params;
    /// Steps of Δt taken since the start.
    fn steps(&self) -> u64;
    /// cm, the centre of mass; cm/s, its velocity; g·cm²/s, L about the centre of mass;
    /// rad/s, ω (world frame).
    fn position(&self) -> Vector3<f64>;
    fn velocity(&self) -> Vector3<f64>;
    fn angular_momentum(&self) -> Vector3<f64>;
    fn angular_velocity(&self) -> Vector3<f64>;
    /// cm, the contact points (sphere centres) about the centre of mass, world frame.
    fn point_offsets(&self) -> Vec<Vector3<f64>>;
    /// cm, their world positions.
    fn point_positions(&self) -> Vec<Vector3<f64>> {
        let centre = self.position();
        self.point_offsets().iter().map(|r| centre + r).collect()
    }
    /// cm, each point's rounding radius: its sphere reaches this far below its centre.
    fn point_radii(&self) -> Vec<f64>;
    /// dyn, the contact force on each point `(friction x, friction y, P)`.
    fn point_forces(&self) -> Vec<Vector3<f64>>;
    /// The energy terms now, erg.
    fn energy(&self) -> Energy;
    /// The body frame's turn into the world ([`Roll::orientation`]).
    fn orientation(&self) -> Rotation3<f64>;
    /// g, the mass one point carries on its own spring (the box's corner mass, a die's
    /// `M/N`), and cm, how far a point may move in one step (the box's smallest half size, a
    /// die's resting height): the readings' own (docs/model.md, "Stability").
    fn point_mass(&self) -> f64;
    fn travel_allowed(&self) -> f64;
}

impl RollingDie for Simulation {
    fn params(&self) -> &Params {
        Simulation::params(self)
    }
    fn steps(&self) -> u64 {
        self.state().step
    }
    fn angular_momentum(&self) -> Vector3<f64> {
        self.state().angular_momentum
    }
    fn position(&self) -> Vector3<f64> {
        self.state().position
    }
    fn velocity(&self) -> Vector3<f64> {
        self.state().velocity
    }
    fn angular_velocity(&self) -> Vector3<f64> {
        Simulation::angular_velocity(self)
    }
    fn point_offsets(&self) -> Vec<Vector3<f64>> {
        self.state().corner_offsets.to_vec()
    }
    fn point_radii(&self) -> Vec<f64> {
        vec![Simulation::params(self).die.corner_radius; 8]
    }
    fn point_forces(&self) -> Vec<Vector3<f64>> {
        self.state().corner_forces.to_vec()
    }
    fn energy(&self) -> Energy {
        Simulation::energy(self)
    }
    fn orientation(&self) -> Rotation3<f64> {
        Rotation3::from_matrix_unchecked(Matrix3::from_columns(&self.body_axes()))
    }
    fn point_mass(&self) -> f64 {
        Simulation::params(self).die.corner_mass
    }
    fn travel_allowed(&self) -> f64 {
        Simulation::params(self).die.smallest_half_size()
    }
}

impl RollingDie for Roll {
    fn params(&self) -> &Params {
        Roll::params(self)
    }
    fn steps(&self) -> u64 {
        Roll::steps(self)
    }
    fn angular_momentum(&self) -> Vector3<f64> {
        Roll::angular_momentum(self)
    }
    fn point_positions(&self) -> Vec<Vector3<f64>> {
        Roll::point_positions(self)
    }
    fn position(&self) -> Vector3<f64> {
        Roll::position(self)
    }
    fn velocity(&self) -> Vector3<f64> {
        Roll::velocity(self)
    }
    fn angular_velocity(&self) -> Vector3<f64> {
        Roll::angular_velocity(self)
    }
    fn point_offsets(&self) -> Vec<Vector3<f64>> {
        Roll::point_offsets(self)
    }
    fn point_radii(&self) -> Vec<f64> {
        match &self.engine {
            Engine::Box(sim) => sim.point_radii(),
            Engine::Die { radii, .. } => radii.clone(),
        }
    }
    fn point_forces(&self) -> Vec<Vector3<f64>> {
        let count = self.point_count();
        on_engine!(&self.engine, r => r.state().corner_forces[..count].to_vec())
    }
    fn energy(&self) -> Energy {
        Roll::energy(self)
    }
    fn orientation(&self) -> Rotation3<f64> {
        Roll::orientation(self)
    }
    fn point_mass(&self) -> f64 {
        match &self.engine {
            Engine::Box(sim) => sim.point_mass(),
            Engine::Die { point_mass, .. } => *point_mass,
        }
    }
    fn travel_allowed(&self) -> f64 {
        match &self.engine {
            Engine::Box(sim) => sim.travel_allowed(),
            Engine::Die { travel_allowed, .. } => *travel_allowed,
        }
    }
}
