//! Every quantity of a roll a person may plot or export: its name, its unit and how it is
//! read from the die's state. The roll CSV's columns and the explorer's plot both come from
//! [`QUANTITIES`], so a quantity added here appears in both.
//!
//! The box is read off its [`Simulation`] as it always was (the same bits); a polyhedral
//! die off its [`Roll`], each reading taken over its `N` points as the box's over its 8
//! corners (docs/commands.md, `trace`).

use dicesim_physics::stability::{
    CONTACT_MODE_LIMIT, CORNER_TRAVEL_LIMIT, DAMPING_LIMIT, FRICTION_CHATTER_LIMIT,
};
use dicesim_physics::{Params, Roll, Simulation};
use nalgebra::Vector3;
use std::cell::RefCell;

/// A roll as the quantities read it: the box by its engine, a polyhedral die by its
/// [`Roll`]. A box's `Roll` reads as its `Simulation`.
#[derive(Debug, Clone, Copy)]
pub enum Rolled<'a> {
    Box(&'a Simulation),
    Die(&'a Roll),
}

impl<'a> From<&'a Simulation> for Rolled<'a> {
    fn from(sim: &'a Simulation) -> Self {
        Rolled::Box(sim)
    }
}

impl<'a> From<&'a Roll> for Rolled<'a> {
    fn from(roll: &'a Roll) -> Self {
        match roll.simulation() {
            Some(sim) => Rolled::Box(sim),
            None => Rolled::Die(roll),
        }
    }
}

impl Rolled<'_> {
    pub fn params(&self) -> &Params {
        match self {
            Rolled::Box(sim) => sim.params(),
            Rolled::Die(roll) => roll.params(),
        }
    }

    /// Steps of Δt taken.
    pub fn steps(&self) -> u64 {
        match self {
            Rolled::Box(sim) => sim.state().step,
            Rolled::Die(roll) => roll.steps(),
        }
    }

    /// cm, the centre of mass.
    pub fn position(&self) -> Vector3<f64> {
        match self {
            Rolled::Box(sim) => sim.state().position,
            Rolled::Die(roll) => roll.position(),
        }
    }

    /// cm/s.
    pub fn velocity(&self) -> Vector3<f64> {
        match self {
            Rolled::Box(sim) => sim.state().velocity,
            Rolled::Die(roll) => roll.velocity(),
        }
    }

    /// g·cm²/s.
    pub fn angular_momentum(&self) -> Vector3<f64> {
        match self {
            Rolled::Box(sim) => sim.state().angular_momentum,
            Rolled::Die(roll) => roll.angular_momentum(),
        }
    }

    /// rad/s.
    pub fn angular_velocity(&self) -> Vector3<f64> {
        match self {
            Rolled::Box(sim) => sim.angular_velocity(),
            Rolled::Die(roll) => roll.angular_velocity(),
        }
    }

    /// cm, the contact points (the box's corners 1..8, a die's vertices) from the centre.
    pub fn point_offsets(&self) -> Vec<Vector3<f64>> {
        match self {
            Rolled::Box(sim) => sim.state().corner_offsets.to_vec(),
            Rolled::Die(roll) => roll.point_offsets(),
        }
    }

    /// cm, the contact points' world positions.
    pub fn point_positions(&self) -> Vec<Vector3<f64>> {
        match self {
            Rolled::Box(sim) => sim.corner_positions().to_vec(),
            Rolled::Die(roll) => roll.point_positions(),
        }
    }

    /// The energy terms, erg.
    pub fn energy(&self) -> dicesim_physics::Energy {
        match self {
            Rolled::Box(sim) => sim.energy(),
            Rolled::Die(roll) => roll.energy(),
        }
    }

    /// dyn, the table's whole force on the die: the sum over its points of each one's
    /// friction (across) and spring and damping (up).
    fn contact_force(&self) -> Vector3<f64> {
        match self {
            Rolled::Box(sim) => sim.state().corner_forces.iter().sum::<Vector3<f64>>(),
            Rolled::Die(roll) => roll
                .contact_forces()
                .iter()
                .map(|f| Vector3::new(f.friction[0], f.friction[1], f.normal + f.damping))
                .sum(),
        }
    }
}

/// What the die's readings need of its solid beyond its state, built once per setup.
#[derive(Debug, Clone, PartialEq)]
struct DieGeometry {
    /// cm, each point's rounding radius, in the points' order.
    radii: Vec<f64>,
    /// cm, the least distance from the centre of mass to a face's plane: what the box's
    /// smallest half size is to a cube.
    least_reach: f64,
}

thread_local! {
    /// The last setup's die geometry: a trace reads it at every row.
    static GEOMETRY: RefCell<Option<(Params, DieGeometry)>> = const { RefCell::new(None) };
}

/// `params`' polyhedral die's [`DieGeometry`].
fn die_geometry(params: &Params) -> DieGeometry {
    GEOMETRY.with(|cell| {
        let mut cached = cell.borrow_mut();
        if let Some((p, g)) = cached.as_ref()
            && p == params
        {
            return g.clone();
        }
        let die = params.polyhedral_die().expect("a polyhedral die");
        let centre = die.mass_properties().centre_of_mass;
        let geometry = DieGeometry {
            radii: die.radii().to_vec(),
            least_reach: die
                .shape()
                .faces()
                .iter()
                .map(|f| f.offset - f.normal.dot(&centre))
                .fold(f64::INFINITY, f64::min),
        };
        *cached = Some((*params, geometry.clone()));
        geometry
    })
}

/// One quantity of a roll.
#[derive(Debug, Clone, Copy)]
pub struct Quantity {
    /// The words a plot's axis and the help use, e.g. "height of the centre".
    pub name: &'static str,
    /// Short name for narrow places (a plot title at 80 columns).
    pub short: &'static str,
    /// The unit as a person reads it, e.g. "cm/s"; "× limit" for a stability load.
    pub unit: &'static str,
    /// The roll CSV's column: a name with the unit in it, e.g. `speed_cm_per_s`.
    pub column: &'static str,
    /// Reads the quantity from the roll's current state.
    pub read: fn(Rolled<'_>) -> f64,
}

/// How many quantities [`QUANTITIES`] has.
pub const QUANTITY_COUNT: usize = 14;

/// Every quantity of one state, in the order of [`QUANTITIES`].
pub type Readings = [f64; QUANTITY_COUNT];

/// Index of the total energy in [`QUANTITIES`] (the plot's first choice).
pub const TOTAL_ENERGY: usize = 9;

/// Every quantity of a roll. The stability loads are the readings of docs/model.md's
/// "Stability" taken at the current state (value / allowed: below 1 the step is stable),
/// so a tuner sees which one a change of the table pushes up, and when in the roll.
pub const QUANTITIES: [Quantity; QUANTITY_COUNT] = [
    Quantity {
        name: "height of the centre",
        short: "height",
        unit: "cm",
        column: "height_cm",
        read: |s| s.position().z,
    },
    Quantity {
        name: "lowest corner",
        short: "lowest",
        unit: "cm",
        column: "lowest_corner_cm",
        read: lowest_point,
    },
    Quantity {
        name: "speed",
        short: "speed",
        unit: "cm/s",
        column: "speed_cm_per_s",
        read: |s| s.velocity().norm(),
    },
    Quantity {
        name: "spin rate",
        short: "spin",
        unit: "rad/s",
        column: "spin_rate_rad_per_s",
        read: |s| s.angular_velocity().norm(),
    },
    Quantity {
        name: "contact force",
        short: "force",
        unit: "dyn",
        column: "contact_force_dyn",
        read: |s| s.contact_force().norm(),
    },
    Quantity {
        name: "translational energy",
        short: "E transl",
        unit: "erg",
        column: "e_trans_erg",
        read: |s| s.energy().translational,
    },
    Quantity {
        name: "rotational energy",
        short: "E rot",
        unit: "erg",
        column: "e_rot_erg",
        read: |s| s.energy().rotational,
    },
    Quantity {
        name: "potential energy",
        short: "E grav",
        unit: "erg",
        column: "e_grav_erg",
        read: |s| s.energy().gravitational,
    },
    Quantity {
        name: "spring energy",
        short: "E elastic",
        unit: "erg",
        column: "e_elastic_erg",
        read: |s| s.energy().elastic,
    },
    Quantity {
        name: "total energy",
        short: "E total",
        unit: "erg",
        column: "e_total_erg",
        read: |s| s.energy().total(),
    },
    Quantity {
        name: "stability: table stiffness",
        short: "stiff load",
        unit: "× limit",
        column: "contact_mode_load",
        read: contact_mode_load,
    },
    Quantity {
        name: "stability: corner speed",
        short: "travel load",
        unit: "× limit",
        column: "corner_travel_load",
        read: corner_travel_load,
    },
    Quantity {
        name: "stability: damping",
        short: "damp load",
        unit: "× limit",
        column: "damping_load",
        read: damping_load,
    },
    Quantity {
        name: "stability: friction",
        short: "fric load",
        unit: "× limit",
        column: "friction_load",
        read: friction_load,
    },
];

/// Every quantity of the roll's current state (a [`Simulation`] or a [`Roll`]).
pub fn read_all<'a>(roll: impl Into<Rolled<'a>>) -> Readings {
    let roll = roll.into();
    QUANTITIES.map(|q| (q.read)(roll))
}

/// The axis label of a quantity: its name and unit, e.g. "speed (cm/s)".
pub fn label(q: &Quantity) -> String {
    format!("{} ({})", q.name, q.unit)
}

/// cm, the die's lowest point above the table (negative: pressed into it). A rounded
/// body's corner spheres reach `corner_radius` below their centres; a die's each its own
/// radius below.
fn lowest_point(sim: Rolled<'_>) -> f64 {
    match sim {
        Rolled::Box(sim) => {
            let lowest = sim
                .corner_positions()
                .iter()
                .map(|c| c.z)
                .fold(f64::INFINITY, f64::min);
            lowest - sim.params().die.corner_radius
        }
        Rolled::Die(roll) => {
            let radii = die_geometry(roll.params()).radii;
            roll.point_positions()
                .iter()
                .zip(radii)
                .map(|(p, r)| p.z - r)
                .fold(f64::INFINITY, f64::min)
        }
    }
}

/// cm/s, each point's velocity `v + ω × r` now.
fn corner_velocities(sim: Rolled<'_>) -> Vec<Vector3<f64>> {
    let (v, w) = (sim.velocity(), sim.angular_velocity());
    sim.point_offsets().into_iter().map(|r| v + w.cross(&r)).collect()
}

/// rad/s, one point on its spring: the box's corner mass on it; a die's point moves the
/// least mass a push there moves, the frequency its step is checked on
/// (`Params::stability_number` over Δt).
fn corner_frequency(sim: Rolled<'_>) -> f64 {
    let p = sim.params();
    match sim {
        Rolled::Box(_) => (p.ground.stiffness / p.die.corner_mass).sqrt(),
        Rolled::Die(_) => p.stability_number() / p.integrator.dt,
    }
}

/// cm, how far a point may move in one step: the box's smallest half size, a die's least
/// distance from its centre to a face.
fn travel_scale(sim: Rolled<'_>) -> f64 {
    match sim {
        Rolled::Box(sim) => sim.params().die.smallest_half_size(),
        Rolled::Die(roll) => die_geometry(roll.params()).least_reach,
    }
}

/// `ω_rock·Δt` against its limit: a property of the table and Δt, changed by a mid-roll edit
/// (the prediction's stiffening by a striking corner, `√(1 + γ·u_z)`, is its first impact's).
fn contact_mode_load(sim: Rolled<'_>) -> f64 {
    sim.params().stability_number() / CONTACT_MODE_LIMIT
}

/// How far the fastest corner moves in one step now, against the smallest half size.
fn corner_travel_load(sim: Rolled<'_>) -> f64 {
    let p = sim.params();
    let fastest = corner_velocities(sim)
        .iter()
        .map(|u| u.norm())
        .fold(0.0, f64::max);
    fastest * p.integrator.dt / (CORNER_TRAVEL_LIMIT * travel_scale(sim))
}

/// `γ·u_z` of the corner falling fastest now, against `max(1, 2/(√(k/m)·Δt))`.
fn damping_load(sim: Rolled<'_>) -> f64 {
    let p = sim.params();
    let falling = corner_velocities(sim).iter().map(|u| -u.z).fold(0.0, f64::max);
    let allowed = DAMPING_LIMIT.max(2.0 / (corner_frequency(sim) * p.integrator.dt));
    p.ground.damping * falling / allowed
}

/// `μ·√(k/m)·Δt` against its limit.
fn friction_load(sim: Rolled<'_>) -> f64 {
    let p = sim.params();
    p.ground.friction * corner_frequency(sim) * p.integrator.dt / FRICTION_CHATTER_LIMIT
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_are_distinct_and_carry_their_units() {
        for (i, q) in QUANTITIES.iter().enumerate() {
            assert!(
                QUANTITIES[..i].iter().all(|o| o.column != q.column),
                "{}",
                q.column
            );
            let suffix = match q.unit {
                "× limit" => "_load".to_string(),
                u => format!("_{}", u.replace("/", "_per_")),
            };
            assert!(q.column.ends_with(&suffix), "{} lacks {suffix}", q.column);
        }
        assert_eq!(QUANTITIES[TOTAL_ENERGY].name, "total energy");
    }
}
