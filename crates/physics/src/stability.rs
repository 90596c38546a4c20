//! Whether semi-implicit Euler can follow a roll with these parameters, before it is rolled
//! (docs/model.md, "Stability"): one reading per cause the allowed ranges make possible.

use super::initial::InitialCondition;
use super::params::{ContactLaw, Params};
use super::stability_contact::{BodyFigures, SpringModes, spring_friction_modes_of};
use serde::Serialize;
use std::fmt;

/// ω_rock·Δt above this lets the rocking mode gain energy. A lone undamped spring allows 2;
/// contact switching on and off between steps pumps energy in well below it.
pub const CONTACT_MODE_LIMIT: f64 = 1.25;

/// A corner may move at most this many half sizes in one step: faster, the step jumps it
/// deep into the table (or through it) before any force acts, and a spin turns the die
/// by so much per step that its contacts are sampled at random.
pub const CORNER_TRAVEL_LIMIT: f64 = 1.0;

/// `γ·u_z` above this turns the press force `k·d·(1 − γ·u_z)` into a pull on a corner
/// leaving the table, and multiplies the push on one striking it. On a finely resolved
/// contact that only kills the bounce; it feeds energy in once one step of that force
/// changes the corner's speed by about twice its own speed, `γ·u_z·√(k/m)·Δt ≳ 2`. So the
/// allowed `γ·u_z` is `max(1, 2/(√(k/m)·Δt))`.
pub const DAMPING_LIMIT: f64 = 1.0;

/// One step's friction impulse `μ·|P|·Δt`, per unit of the sideways momentum of the corner
/// it pushes, above this reverses the slip faster than it was: friction then feeds energy
/// in (or, on a light or flat body, spins it up at an impact). A corner striking at speed
/// `u` presses with a spring stiffened by the damping to `k·(1 + γ·u)`, its force peaking at
/// `u·√(k·(1 + γ·u)·m_s)`, where `m_s = (1/M + ℓ²/I_min)⁻¹` is the least mass a sideways push
/// at a corner moves (ℓ its reach from the centre of mass, `I_min` the least moment of
/// inertia); so the number is `μ·√(k·(1 + γ·u)/m_s)·Δt`, whatever the speed.
pub const FRICTION_CHATTER_LIMIT: f64 = 2.0;

/// A landing may press a corner at most this share of the die's reach into the table
/// ([`Limit::ImpactDepth`]): one spring, stiffened by the damping to `k·(1 + γ·v)`, under a
/// corner that took the whole landing at `v`, `½·k·(1 + γ·v)·d² = ½·M·v²`, gives the depth
/// `d = v·√(M/(k·(1 + γ·v)))`; past the reach the centre of mass comes down to the table
/// top, and the springs hold the die nowhere.
pub const IMPACT_DEPTH_LIMIT: f64 = 1.0;

/// A cause of instability.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Limit {
    /// The table's fastest mode, a die rocking on a face: `ω_rock·Δt` (under the paper's law
    /// stiffened by the damping while a corner strikes; under spring-friction against the limit
    /// the mode's own damping sets).
    ContactMode,
    /// How far the fastest corner moves in one step at the first impact, cm.
    CornerTravel,
    /// `γ·u_z` of the fastest corner at the first impact, against `max(1, 2/(√(k/m)·Δt))`.
    Damping,
    /// `μ·√(k·(1 + γ·u)/m_s)·Δt`: one step's friction against a corner's slip.
    FrictionChatter,
    /// cm, how deep a landing at `v` would press one corner's spring (stiffened by the
    /// damping) taking it alone, `v·√(M/(k·(1 + γ·v)))`, against the die's reach `2·a_min − r`
    /// (a landing on the thinnest face, shared between its corners).
    ImpactDepth,
    /// Spring-friction only: `ω_t·Δt` of the faster of a stuck face's rock-and-slide and
    /// twist modes on the tangential springs, against the limit their damping sets.
    TangentialMode,
}

/// How many kinds of reading there are, one slot each in [`Stability`].
const LIMITS: usize = 6;

impl Limit {
    /// A short name for the readout.
    pub fn name(self) -> &'static str {
        match self {
            Limit::ContactMode => "table stiffness",
            Limit::CornerTravel => "corner speed",
            Limit::Damping => "damping",
            Limit::FrictionChatter => "friction",
            Limit::ImpactDepth => "impact depth",
            Limit::TangentialMode => "tangential spring",
        }
    }
}

/// One cause: its value for a roll and the largest value that still steps stably.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Reading {
    pub limit: Limit,
    pub value: f64,
    /// The value above which the roll is predicted unstable.
    pub allowed: f64,
    /// For [`Limit::CornerTravel`] and [`Limit::Damping`]: whether spin, rather than the
    /// die's speed, gives the corner most of its speed.
    #[serde(skip)]
    spin_dominated: bool,
    /// cm/s, the speed the words quote: the fastest corner's at the first impact, or for
    /// [`Limit::ImpactDepth`] the centre's as it lands.
    #[serde(skip)]
    speed: f64,
}

impl Reading {
    /// `value / allowed`: below 1 the roll is predicted to step stably.
    pub fn load(&self) -> f64 {
        self.value / self.allowed
    }

    pub fn exceeded(&self) -> bool {
        let load = self.load();
        load > 1.0 || load.is_nan()
    }
}

/// A reading in words a student understands, e.g. "spin too fast for Δt: a corner moves
/// 17.3 cm per step (stable below 0.50 cm)".
impl fmt::Display for Reading {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (v, allowed) = (self.value, self.allowed);
        match self.limit {
            Limit::ContactMode => write!(
                f,
                "table too stiff for Δt: the die rocks on it with ω_rock·Δt = {v:.2}, \
                 only {:.1} steps per swing (stable below {allowed:.2}, {:.1} steps)",
                std::f64::consts::TAU / v,
                std::f64::consts::TAU / allowed
            ),
            Limit::CornerTravel if self.spin_dominated => write!(
                f,
                "spin too fast for Δt: a corner moves {v:.3} cm per step (stable below {allowed:.3} cm)"
            ),
            Limit::CornerTravel => write!(
                f,
                "die too fast for Δt: a corner hits the table at {:.0} cm/s and moves {v:.3} cm per \
                 step (stable below {allowed:.3} cm)",
                self.speed
            ),
            Limit::Damping => write!(
                f,
                "damping too strong for a corner at {:.0} cm/s: γ·u_z = {v:.2} turns the table's \
                 push into a pull on a buried corner (stable below {allowed:.2} at this Δt)",
                self.speed
            ),
            Limit::FrictionChatter => write!(
                f,
                "friction too strong for Δt: one step of friction reverses a sliding corner {v:.2} \
                 times as fast as it slid (μ·√(k·(1 + γ·u)/m_s)·Δt, stable below {allowed:.0})"
            ),
            Limit::ImpactDepth => write!(
                f,
                "landing too hard for the table: the die lands at {:.0} cm/s and presses up to {v:.3} cm \
                 into it, so deep its centre of mass nears the table top (stable below {allowed:.3} cm)",
                self.speed
            ),
            Limit::TangentialMode => write!(
                f,
                "tangential spring too stiff for Δt: a stuck die rocks and slides on it with \
                 ω·Δt = {v:.2}, only {:.1} steps per swing (stable below {allowed:.2} at its damping)",
                std::f64::consts::TAU / v
            ),
        }
    }
}

/// Every reading that applies to one roll under its contact law, one slot per [`Limit`]
/// (`None` where the law does not meet that cause: γ's damping and the kinetic friction's
/// chatter under spring-friction, the tangential springs under the paper's law).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stability {
    readings: [Option<Reading>; LIMITS],
}

impl Stability {
    /// Reads every cause for these parameters and this initial condition.
    pub fn predict(p: &Params, initial: &InitialCondition) -> Stability {
        StabilityCheck::new(p).predict(initial)
    }

    /// The reading of one cause, if it applies under the roll's contact law.
    pub fn reading(&self, limit: Limit) -> Option<Reading> {
        self.readings[limit as usize]
    }

    /// The readings that apply, in the order of [`Stability::verdict`].
    pub fn readings(&self) -> impl Iterator<Item = Reading> + '_ {
        CAUSAL_ORDER.iter().filter_map(|&limit| self.reading(limit))
    }

    /// The reading to report: the first past its limit in the order corner travel, contact
    /// mode, tangential mode, damping, friction chatter, impact depth (a cause before its
    /// symptoms: a corner moving too far per step also strikes fast, which stiffens the
    /// contact mode, is too fast for the damping and presses deep); when none is past, the
    /// one with the largest `value / allowed`.
    pub fn verdict(&self) -> Reading {
        if let Some(r) = self.readings().find(Reading::exceeded) {
            return r;
        }
        self.readings()
            .reduce(|closest, r| if r.load() > closest.load() { r } else { closest })
            .expect("the corner-speed reading applies under every law")
    }

    /// Whether every reading is within its limit.
    pub fn is_stable(&self) -> bool {
        !self.verdict().exceeded()
    }
}

/// Causes before their symptoms (see [`Stability::verdict`]).
const CAUSAL_ORDER: [Limit; LIMITS] = [
    Limit::CornerTravel,
    Limit::ContactMode,
    Limit::TangentialMode,
    Limit::Damping,
    Limit::FrictionChatter,
    Limit::ImpactDepth,
];

/// The readings of one setup for any start: what depends on the body alone, worked out once
/// (a batch asks it of every roll).
#[derive(Debug, Clone)]
pub struct StabilityCheck {
    params: Params,
    body: BodyFigures,
    /// g, the least mass a sideways push at a corner moves, `(1/M + ℓ²/I_min)⁻¹`: ℓ the
    /// farthest contact point's reach from the centre of mass, pushed across the axis of
    /// least inertia.
    sideways_mass: f64,
    /// The spring-friction law's modes; `None` under the paper's law.
    spring_modes: Option<SpringModes>,
}

impl StabilityCheck {
    pub fn new(p: &Params) -> StabilityCheck {
        let body = BodyFigures::of(p);
        let reach = body.reach;
        StabilityCheck {
            params: *p,
            sideways_mass: 1.0 / (1.0 / body.mass + reach * reach / body.least_inertia),
            spring_modes: spring_friction_modes_of(p, &body),
            body,
        }
    }

    /// Every reading for a roll from `initial`.
    pub fn predict(&self, initial: &InitialCondition) -> Stability {
        let (p, body) = (&self.params, &self.body);
        let dt = p.integrator.dt;
        // How far a corner may move per step: the smallest half size (a cube's half size).
        let a = body.travel_allowed;
        // rad/s, one corner on its spring.
        let corner_frequency = (p.ground.stiffness / body.point_mass).sqrt();
        // The centre's speed when the lowest corner first reaches the table.
        let drop = (initial.height + body.lowest_point_at_start(initial)).max(0.0);
        let v = initial.velocity;
        let vz_impact = (v[2] * v[2] + 2.0 * p.world.gravity * drop).sqrt();
        let translation = (v[0] * v[0] + v[1] * v[1] + vz_impact * vz_impact).sqrt();
        let spin_rate = initial.angular_velocity_for(body.mean_inertia).norm();
        let spin = body.point_speed_of_spin(spin_rate);
        let spin_dominated = spin > translation;
        let corner_speed = translation + spin;
        // A corner pressing in at u_z feels k·d·(1 + γ·u_z): while it strikes, the damping
        // stiffens its spring by that factor, and every mode of the contact with it.
        let striking = (1.0 + p.ground.damping * (vz_impact + spin)).sqrt();
        let reading = |limit, value, allowed, speed| Reading {
            limit,
            value,
            allowed,
            spin_dominated,
            speed,
        };
        let k = p.ground.stiffness;
        let corner_travel = reading(
            Limit::CornerTravel,
            corner_speed * dt,
            CORNER_TRAVEL_LIMIT * a,
            corner_speed,
        );
        let mut readings = [None; LIMITS];
        readings[Limit::CornerTravel as usize] = Some(corner_travel);
        match (p.ground.contact, self.spring_modes) {
            (ContactLaw::SpringFriction, Some(modes)) => {
                // Its dashpot damps the normal mode rather than stiffening its spring, so
                // the landing's depth is the undamped spring's, an upper bound.
                for (limit, mode) in [
                    (Limit::ContactMode, modes.normal),
                    (Limit::TangentialMode, modes.tangential),
                ] {
                    readings[limit as usize] =
                        Some(reading(limit, mode.frequency * dt, mode.allowed, corner_speed));
                }
                readings[Limit::ImpactDepth as usize] = Some(reading(
                    Limit::ImpactDepth,
                    vz_impact * (body.mass / k).sqrt(),
                    IMPACT_DEPTH_LIMIT * body.depth_allowed,
                    vz_impact,
                ));
            }
            _ => {
                readings[Limit::ContactMode as usize] = Some(reading(
                    Limit::ContactMode,
                    body.rocking_frequency * striking * dt,
                    CONTACT_MODE_LIMIT,
                    corner_speed,
                ));
                readings[Limit::Damping as usize] = Some(reading(
                    Limit::Damping,
                    p.ground.damping * (vz_impact + spin),
                    DAMPING_LIMIT.max(2.0 / (corner_frequency * dt)),
                    corner_speed,
                ));
                readings[Limit::FrictionChatter as usize] = Some(reading(
                    Limit::FrictionChatter,
                    p.ground.friction * (k / self.sideways_mass).sqrt() * striking * dt,
                    FRICTION_CHATTER_LIMIT,
                    corner_speed,
                ));
                readings[Limit::ImpactDepth as usize] = Some(reading(
                    Limit::ImpactDepth,
                    vz_impact * (body.mass / (k * (1.0 + p.ground.damping * vz_impact))).sqrt(),
                    IMPACT_DEPTH_LIMIT * body.depth_allowed,
                    vz_impact,
                ));
            }
        }
        Stability { readings }
    }
}

/// Why a roll ended unstable: [`Stability::verdict`] of its parameters and start. When
/// no reading is past its limit the words say so and name the closest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnstableReason(pub Reading);

impl UnstableReason {
    pub fn new(p: &Params, initial: &InitialCondition) -> UnstableReason {
        UnstableReason(Stability::predict(p, initial).verdict())
    }
}

/// E.g. "spin too fast for Δt: a corner moves 17.321 cm per step (stable below 1.000 cm)".
impl fmt::Display for UnstableReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.exceeded() {
            write!(f, "{}", self.0)
        } else {
            write!(
                f,
                "the energy ran away although no known limit was passed; closest: {}",
                self.0
            )
        }
    }
}
