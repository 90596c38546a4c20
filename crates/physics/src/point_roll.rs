//! The scalar engine for a body given as its contact points ([`PointBody`]): one roll of a
//! body of `N` points under the contact law its table names, stepped by the same kernel the
//! die's [`Simulation`](crate::Simulation) steps (the lane engine's twin is
//! [`crate::lanes::roll_points_in_lanes`]).

use super::contact::{Law, SpringFriction};
use super::energy::Energy;
use super::initial::InitialCondition;
use super::kernel::{Faces, Kernel, NoHook};
use super::params::{ContactLaw, FrictionLaw, ParamError, Params};
use super::points::PointBody;
use super::sim::{ContactForce, EnergyLedger, ImpactLog, Ledger, Outcome, STEPS_BETWEEN_STOP_CHECKS, Status};
use super::sim::{PaperPerCorner, PaperWholeDie, by_law, contact_forces_of, engine_law, on_law, status_of};
use super::state::State;
use super::stopping::StopRule;
use nalgebra::{Matrix3, Vector2, Vector3};

/// The end of a roll of a body of points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointOutcome {
    pub status: Status,
    /// The number of the face up, for a settled roll.
    pub face: Option<u8>,
    /// Steps taken when the roll ended.
    pub steps: u64,
    /// s of simulated time when the roll ended.
    pub time_s: f64,
}

/// The kernel under each law.
#[derive(Debug, Clone)]
pub(crate) enum PointKernel<const N: usize> {
    Paper(Kernel<f64, PaperPerCorner, N, PointBody<N>>),
    PaperWholeDie(Kernel<f64, PaperWholeDie, N, PointBody<N>>),
    SpringFriction(Kernel<f64, SpringFriction, N, PointBody<N>>),
}

/// A body of `N` points rolling from an initial condition.
#[derive(Debug, Clone)]
pub struct PointRoll<const N: usize> {
    pub(crate) k: PointKernel<N>,
    body: PointBody<N>,
    /// The number of the face up at t = 0 (the number read were it to rest as it starts).
    start_face: u8,
    /// Its impacts so far, by the box's definition (the lane engine carries a lane's and
    /// stores it back).
    pub(crate) impact_log: ImpactLog,
    outcome: Option<Outcome>,
    /// Whether the energy ledger is kept ([`PointRoll::keep_ledger`]): a batch that only
    /// wants outcomes skips its second pass over the points.
    track_ledger: bool,
    ledger: Ledger<N>,
    /// erg, rigid-body energy at t = 0.
    initial_energy: f64,
}

impl<const N: usize> PointRoll<N> {
    /// `body` placed at `initial` on `params`' table (its world, ground and integrator; its
    /// die is not read), after both are validated.
    pub fn new(params: &Params, body: &PointBody<N>, initial: &InitialCondition) -> Result<Self, ParamError> {
        params.validate()?;
        initial.validate()?;
        Ok(Self::new_unchecked(params, body, initial))
    }

    /// [`PointRoll::new`] without the range checks.
    pub(crate) fn new_unchecked(params: &Params, body: &PointBody<N>, initial: &InitialCondition) -> Self {
        let k = by_law!(PointKernel, params, body.kernel(params, initial));
        let (in_contact, offsets) = on_law!(PointKernel, &k, k => (k.in_contact, k.state.corner_offsets));
        let initial_energy = on_law!(PointKernel, &k, k => Energy::from(k.energy())).total();
        PointRoll {
            k,
            body: *body,
            start_face: body.face_up(&offsets),
            impact_log: ImpactLog::new(in_contact),
            outcome: None,
            track_ledger: false,
            ledger: Ledger::default(),
            initial_energy,
        }
    }

    /// This roll keeping the energy ledger from its start on (what a live view or a trace
    /// shows; the trajectory is the same bit for bit).
    pub fn keep_ledger(&mut self) {
        debug_assert_eq!(self.state().step, 0, "the ledger starts with the roll");
        self.track_ledger = true;
    }

    /// Where the energy has gone since t = 0 (a roll made [`PointRoll::keep_ledger`]).
    pub fn energy_ledger(&self) -> EnergyLedger {
        debug_assert!(self.track_ledger, "a roll built for its outcome keeps no ledger");
        self.ledger
            .energy_ledger(self.initial_energy, self.energy().total())
    }

    /// Each point's contact force split into normal, damping and friction, at the current
    /// state (the forces the next step will apply).
    pub fn contact_forces(&self) -> [ContactForce; N] {
        on_law!(PointKernel, &self.k, k => contact_forces_of(k))
    }

    /// rad/s, world frame.
    pub fn angular_velocity(&self) -> Vector3<f64> {
        on_law!(PointKernel, &self.k, k => k.angular_velocity)
    }

    /// The body-to-world rotation now: a point `p` of the body's frame (about its centre of
    /// mass) lies at `orientation · p` from the centre.
    pub fn orientation(&self) -> Matrix3<f64> {
        self.body.orientation(&self.state().corner_offsets)
    }

    /// The stopping rule on this table, erg: the one the step screens with (the widest of
    /// the faces' where they differ).
    pub fn stop_rule(&self) -> StopRule {
        on_law!(PointKernel, &self.k, k => StopRule {
            energy_threshold: k.c.stop.energy_threshold,
            kinetic_threshold: k.c.stop.kinetic_threshold,
        })
    }

    /// The stopping rule of the face it shows now, on this table.
    pub fn stop_rule_now(&self) -> StopRule {
        let faced = on_law!(PointKernel, &self.k, k => k.bodies[0].stop_rule_at(&k.state.corner_offsets));
        if self.body.has_face_rules() {
            faced
        } else {
            self.stop_rule()
        }
    }

    /// This roll on `params`' table from now on (the ground changed mid-roll), `body` its
    /// body as made for that table (its stopping rules depend on it): the same state and
    /// motion, each point's memory kept where the law stays, forgotten where it changes.
    pub fn set_table(&mut self, params: &Params, body: &PointBody<N>) -> Result<(), ParamError> {
        params.validate()?;
        let runaway = on_law!(PointKernel, &self.k, k => k.c.stop.runaway);
        self.k = by_law!(PointKernel, params, under_law(&self.k, params, body, runaway));
        self.body = *body;
        Ok(())
    }

    /// The number of the face up at t = 0.
    pub fn start_face(&self) -> u8 {
        self.start_face
    }

    /// The body it rolls.
    pub fn body(&self) -> &PointBody<N> {
        &self.body
    }

    pub fn state(&self) -> &State<f64, N> {
        on_law!(PointKernel, &self.k, k => &k.state)
    }

    /// cm, each point's tangential spring (0 under the paper's law).
    pub fn tangential_springs(&self) -> [Vector2<f64>; N] {
        on_law!(PointKernel, &self.k, k => springs(k))
    }

    /// The energy terms at the current state, erg.
    pub fn energy(&self) -> Energy {
        on_law!(PointKernel, &self.k, k => k.energy()).into()
    }

    /// Whether any point is below the table now.
    pub fn in_contact(&self) -> bool {
        on_law!(PointKernel, &self.k, k => k.in_contact)
    }

    /// The number of the face most nearly down, and up, now.
    pub fn face_down(&self) -> u8 {
        self.body.face_down(&self.state().corner_offsets)
    }

    pub fn face_up(&self) -> u8 {
        self.body.face_up(&self.state().corner_offsets)
    }

    /// The end, once the roll has ended.
    pub fn outcome(&self) -> Option<PointOutcome> {
        self.outcome.map(|o| PointOutcome {
            status: o.status,
            face: o.face,
            steps: o.steps,
            time_s: o.time_s,
        })
    }

    /// The end as the box's rolls report it, with its impacts, once the roll has ended.
    pub fn full_outcome(&self) -> Option<Outcome> {
        self.outcome
    }

    /// One step of Δt, its contact seen by the impact log.
    pub fn step(&mut self) {
        let body = &self.body;
        let log = &mut self.impact_log;
        let ledger = self.track_ledger.then_some(&mut self.ledger);
        on_law!(PointKernel, &mut self.k, k => {
            match ledger {
                Some(ledger) => k.step(ledger),
                None => k.step(&mut NoHook),
            }
            let s = &k.state;
            log.observe(k.in_contact, || (body.face_down(&s.corner_offsets), s.step, s.time_s));
        });
    }

    /// Steps until the roll ends, or until `stop()` answers true (asked every
    /// [`STEPS_BETWEEN_STOP_CHECKS`] steps): `None` then, and the roll can be continued.
    pub fn run_until_stopped(&mut self, stop: &dyn Fn() -> bool) -> Option<Outcome> {
        loop {
            for _ in 0..STEPS_BETWEEN_STOP_CHECKS {
                if self.outcome.is_some() {
                    return self.outcome;
                }
                self.advance();
            }
            if stop() {
                return None;
            }
        }
    }

    /// One step, then the end-of-roll test; the outcome on the step that ends it.
    pub fn advance(&mut self) -> Option<PointOutcome> {
        self.step();
        if self.outcome.is_some() {
            return None;
        }
        let status = status_of(&on_law!(PointKernel, &self.k, k => k.ends()))?;
        let outcome = self.finish(status);
        Some(outcome)
    }

    /// Steps until the roll ends.
    pub fn run_to_end(&mut self) -> PointOutcome {
        loop {
            if let Some(o) = self.outcome() {
                return o;
            }
            self.advance();
        }
    }

    /// Ends the roll as `status` at the current state.
    pub(crate) fn finish(&mut self, status: Status) -> PointOutcome {
        let s = self.state();
        let outcome = Outcome {
            status,
            face: match status {
                Status::Settled => Faces::face_up_at_rest(&self.body, &s.corner_offsets),
                _ => None,
            },
            steps: s.step,
            time_s: s.time_s,
            impacts: self.impact_log.impacts.count(),
            first_impact: self.impact_log.first,
        };
        self.outcome = Some(outcome);
        self.outcome().expect("just ended")
    }
}

/// The roll in `k` under `params`' law `V` with `body` (the ground changed), the runaway
/// bound kept, a point's memory kept where the law stays.
fn under_law<V: PointLaw, const N: usize>(
    k: &PointKernel<N>,
    params: &Params,
    body: &PointBody<N>,
    runaway: f64,
) -> Kernel<f64, V, N, PointBody<N>> {
    let (mut c, on_table) = body.on_table::<V>(params);
    c.stop.runaway = runaway;
    let mut kernel = on_law!(PointKernel, k, k => k.under::<V>(c, on_table));
    if let Some(same) = V::of(k) {
        kernel.points = same.points;
    }
    kernel.update_forces();
    kernel
}

fn springs<W: Law, const N: usize>(k: &Kernel<f64, W, N, PointBody<N>>) -> [Vector2<f64>; N] {
    k.points.each_ref().map(W::tangential_spring)
}

/// A contact law as [`PointRoll`] holds it.
pub(crate) trait PointLaw: Law {
    fn of<const N: usize>(k: &PointKernel<N>) -> Option<&Kernel<f64, Self, N, PointBody<N>>>;
    fn of_mut<const N: usize>(k: &mut PointKernel<N>) -> Option<&mut Kernel<f64, Self, N, PointBody<N>>>;
}

engine_law!(PointLaw, PointKernel, PaperPerCorner, Paper, N);
engine_law!(PointLaw, PointKernel, PaperWholeDie, PaperWholeDie, N);
engine_law!(PointLaw, PointKernel, SpringFriction, SpringFriction, N);
