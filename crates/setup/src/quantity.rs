//! Every quantity of a roll a person may plot or export: its name, its unit and how it is
//! read from the die's state. The roll CSV's columns and the explorer's plot both come from
//! [`QUANTITIES`], so a quantity added here appears in both.

use dicesim_physics::RollingDie;
use dicesim_physics::stability::{
    CONTACT_MODE_LIMIT, CORNER_TRAVEL_LIMIT, DAMPING_LIMIT, FRICTION_CHATTER_LIMIT,
};
use nalgebra::Vector3;

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
    /// Reads the quantity from the die's current state (the box's `Simulation` or any die's
    /// `Roll`).
    pub read: fn(&dyn RollingDie) -> f64,
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
        read: |s| s.point_forces().iter().sum::<Vector3<f64>>().norm(),
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

/// Every quantity of the die's current state.
pub fn read_all(sim: &dyn RollingDie) -> Readings {
    QUANTITIES.map(|q| (q.read)(sim))
}

/// The axis label of a quantity: its name and unit, e.g. "speed (cm/s)".
pub fn label(q: &Quantity) -> String {
    format!("{} ({})", q.name, q.unit)
}

/// cm, the die's lowest point above the table (negative: pressed into it). A rounded
/// body's contact spheres reach their radius below their centres.
fn lowest_point(sim: &dyn RollingDie) -> f64 {
    let centre = sim.position();
    sim.point_offsets()
        .iter()
        .zip(sim.point_radii())
        .map(|(r, radius)| (centre + r).z - radius)
        .fold(f64::INFINITY, f64::min)
}

/// cm/s, each contact point's velocity `v + ω × r` now.
fn corner_velocities(sim: &dyn RollingDie) -> Vec<Vector3<f64>> {
    let (v, w) = (sim.velocity(), sim.angular_velocity());
    sim.point_offsets().iter().map(|r| v + w.cross(r)).collect()
}

/// rad/s, one point on its spring.
fn corner_frequency(sim: &dyn RollingDie) -> f64 {
    (sim.params().ground.stiffness / sim.point_mass()).sqrt()
}

/// `ω_rock·Δt` against its limit: a property of the table and Δt, changed by a mid-roll edit
/// (the prediction's stiffening by a striking corner, `√(1 + γ·u_z)`, is its first impact's).
fn contact_mode_load(sim: &dyn RollingDie) -> f64 {
    sim.params().stability_number() / CONTACT_MODE_LIMIT
}

/// How far the fastest point moves in one step now, against the distance it may.
fn corner_travel_load(sim: &dyn RollingDie) -> f64 {
    let p = sim.params();
    let fastest = corner_velocities(sim)
        .iter()
        .map(|u| u.norm())
        .fold(0.0, f64::max);
    fastest * p.integrator.dt / (CORNER_TRAVEL_LIMIT * sim.travel_allowed())
}

/// `γ·u_z` of the point falling fastest now, against `max(1, 2/(√(k/m)·Δt))`.
fn damping_load(sim: &dyn RollingDie) -> f64 {
    let p = sim.params();
    let falling = corner_velocities(sim).iter().map(|u| -u.z).fold(0.0, f64::max);
    let allowed = DAMPING_LIMIT.max(2.0 / (corner_frequency(sim) * p.integrator.dt));
    p.ground.damping * falling / allowed
}

/// `μ·√(k/m)·Δt` against its limit.
fn friction_load(sim: &dyn RollingDie) -> f64 {
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
