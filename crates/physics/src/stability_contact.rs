//! The spring-friction contact law's own stability modes (docs/model.md, "The
//! spring-friction contact", its "Stability"): its normal mode against the limit its damping
//! sets, and the modes its tangential springs add. [`super::stability`] reads them in place of
//! the paper's table-stiffness reading; the paper's readings the law does not meet — γ's
//! damping and the kinetic friction's chatter — do not apply to it, and the corner-speed and
//! impact-depth readings apply to both laws.

use super::contact::spring_friction::SpringFrictionConstants;
use super::model::Body;
use super::params::{ContactLaw, Params};
use nalgebra::Vector3;

/// The share of semi-implicit Euler's limit for a damped mode that is allowed: contact
/// switching on and off between steps pumps energy in below the lone mode's limit (the paper's
/// stiffness reading allows 1.25 of 2 for the same reason).
pub const SWITCHING_MARGIN: f64 = 0.7;

/// One mode of the law's springs: its frequency and the largest `ω·Δt` that still steps
/// stably at its damping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringMode {
    /// rad/s.
    pub frequency: f64,
    /// The `ω·Δt` above which the roll is predicted unstable.
    pub allowed: f64,
}

/// What the stability readings ask of a die's body, worked out once: the box's from its
/// [`Body`], a polyhedral die's from its points and mass (docs/model.md, "Stability of a die
/// of any shape").
#[derive(Debug, Clone)]
pub(crate) struct BodyFigures {
    /// g.
    pub(crate) mass: f64,
    /// g·cm², the mean principal moment and the least one.
    pub(crate) mean_inertia: f64,
    pub(crate) least_inertia: f64,
    /// rad/s, the fastest contact mode on the paper's springs: the box rocking on its face,
    /// a polyhedral die on one point (`√(k·(1/M + r²/I_min))`, the mode its step is refused
    /// past).
    pub(crate) rocking_frequency: f64,
    /// g, the mass one point carries on its own spring: the box's corner mass, a die's `M/N`.
    pub(crate) point_mass: f64,
    /// cm, how far a point may move in one step: the box's smallest half size, a die's
    /// nearest face from its centre of mass.
    pub(crate) travel_allowed: f64,
    /// cm, how far the farthest contact point reaches from the centre of mass (its sphere's
    /// edge for a rounded one): what a spin moves it by, and the lever of a sideways push.
    pub(crate) reach: f64,
    /// cm, how deep a point may press the table before the centre of mass could reach it:
    /// the box's `2·a_min − r`, a die's thinnest width across a face pair of points, less a
    /// radius.
    pub(crate) depth_allowed: f64,
    /// cm, the centre of mass's height resting on its lowest face, and erg, the energy to
    /// tip it over an edge.
    pub(crate) reference_height: f64,
    pub(crate) edge_energy: f64,
    /// A polyhedral die's contact points (sphere centre from the centre of mass, die frame,
    /// and radius); `None` for the box, whose [`Body`] places its corners.
    pub(crate) points: Option<Vec<(Vector3<f64>, f64)>>,
    pub(crate) body: Body,
}

impl BodyFigures {
    pub(crate) fn of(p: &Params) -> BodyFigures {
        let body = Body::new(p);
        let Some(die) = p.polyhedral_die() else {
            let offsets = body.start_offsets(&super::initial::InitialCondition::default());
            let reach = offsets.iter().map(|k| k.norm()).fold(0.0, f64::max) + p.die.corner_radius;
            return BodyFigures {
                mass: body.mass(),
                mean_inertia: body.mean_inertia(),
                least_inertia: body.least_inertia(&offsets),
                rocking_frequency: body.rocking_frequency(),
                point_mass: p.die.corner_mass,
                travel_allowed: p.die.smallest_half_size(),
                reach,
                depth_allowed: 2.0 * p.die.smallest_half_size() - p.die.corner_radius,
                reference_height: body.reference_height(),
                edge_energy: body.edge_energy(),
                points: None,
                body,
            };
        };
        let props = die.mass_properties();
        let points: Vec<(Vector3<f64>, f64)> = die
            .contact_points()
            .iter()
            .map(|c| (c.offset, c.radius))
            .collect();
        let largest_radius = points.iter().map(|&(_, r)| r).fold(0.0, f64::max);
        let reach = points.iter().map(|(c, r)| c.norm() + r).fold(0.0, f64::max);
        // Along each face's normal: the points' extent (their spheres' edges), and how far the
        // farthest reaches toward the face, the centre's height resting on it.
        let along = |n: &Vector3<f64>| {
            let high = points
                .iter()
                .map(|(c, r)| n.dot(c) + r)
                .fold(f64::NEG_INFINITY, f64::max);
            let low = points
                .iter()
                .map(|(c, r)| n.dot(c) - r)
                .fold(f64::INFINITY, f64::min);
            (high, high - low)
        };
        let faces = die.shape().faces();
        let rest_height = faces
            .iter()
            .map(|f| along(&f.normal).0)
            .fold(f64::INFINITY, f64::min);
        let width = faces
            .iter()
            .map(|f| along(&f.normal).1)
            .fold(f64::INFINITY, f64::min);
        let eigen = props.inertia.symmetric_eigen().eigenvalues;
        BodyFigures {
            mass: props.mass,
            mean_inertia: props.inertia.trace() / 3.0,
            least_inertia: eigen.min(),
            rocking_frequency: p.stability_number() / p.integrator.dt,
            point_mass: props.mass / points.len() as f64,
            travel_allowed: rest_height,
            reach,
            depth_allowed: width - largest_radius,
            reference_height: rest_height,
            edge_energy: p.edge_energy(),
            points: Some(points),
            body,
        }
    }

    /// cm, the lowest point's height below the centre of mass at the start of `initial`.
    pub(crate) fn lowest_point_at_start(&self, initial: &super::initial::InitialCondition) -> f64 {
        match &self.points {
            None => self.body.lowest_point_at_start(initial),
            Some(points) => {
                let rotation = initial.rotation();
                points
                    .iter()
                    .map(|(c, r)| (rotation * c).z - r)
                    .fold(f64::INFINITY, f64::min)
            }
        }
    }

    /// cm/s, the fastest point's speed from a spin of `spin_rate` rad/s.
    pub(crate) fn point_speed_of_spin(&self, spin_rate: f64) -> f64 {
        match self.points {
            None => self.body.corner_speed_of_spin(spin_rate),
            Some(_) => spin_rate * self.reach,
        }
    }
}

/// The law's two modes for `p`: the die rocking on a face on its normal springs, and the
/// faster of a stuck face's rock-and-slide and twist modes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringModes {
    pub normal: SpringMode,
    pub tangential: SpringMode,
}

/// `ω·Δt` below which semi-implicit Euler steps the mode `x'' = −ω²·x − 2ζω·x'` stably,
/// `2·(√(1 + ζ²) − ζ)`, times [`SWITCHING_MARGIN`].
pub fn damped_mode_limit(zeta: f64) -> f64 {
    SWITCHING_MARGIN * 2.0 * ((1.0 + zeta * zeta).sqrt() - zeta)
}

/// The spring-friction law's modes for `p`; `None` under the paper's law.
pub fn spring_friction_modes(p: &Params) -> Option<SpringModes> {
    spring_friction_modes_of(p, &BodyFigures::of(p))
}

/// [`spring_friction_modes`] of the body `body`.
pub(crate) fn spring_friction_modes_of(p: &Params, body: &BodyFigures) -> Option<SpringModes> {
    if p.ground.contact != ContactLaw::SpringFriction {
        return None;
    }
    let (k, mass) = (p.ground.stiffness, body.mass);
    let law = SpringFrictionConstants::new(p, mass, body.edge_energy);
    let k_t = law.tangential_stiffness;
    let rock = body.rocking_frequency;
    let (h, inertia) = (body.reference_height, body.mean_inertia);
    // The rock-and-slide pair: the larger eigenvalue of the 2×2 matrix in docs/model.md.
    let (a11, a12) = (4.0 * k_t / mass, -4.0 * k_t * h / mass);
    let (a21, a22) = (
        -4.0 * k_t * h / inertia,
        rock * rock + 4.0 * k_t * h * h / inertia,
    );
    let (trace, det) = (a11 + a22, a11 * a22 - a12 * a21);
    let slide = (0.5 * (trace + (trace * trace - 4.0 * det).max(0.0).sqrt())).sqrt();
    let twist = rock * (2.0 * k_t / k).sqrt();
    // The damping ratio of a mode of frequency ω on springs damped by c per k: ζ = ω·c/(2k);
    // a face may rest on points that struck leaning, so the stronger of the two dashpots
    // (`c` itself when no face restitution is set) sets the limit.
    let damping = law.normal_damping.max(law.face_damping);
    let mode = |frequency: f64| SpringMode {
        frequency,
        allowed: damped_mode_limit(frequency * damping / (2.0 * k)),
    };
    // On a compliant table the springs act on the relative motion of body and top, whose
    // reduced mass is smaller by 1 + M/m_T, so each mode is faster by its square root (1 on a
    // rigid table); the top's own mode on its spring, √(K_T/m_T), steps on the same Δt.
    let lighter = (1.0 + mass * law.table_inverse_mass).sqrt();
    let table = (law.table_stiffness * law.table_inverse_mass).sqrt();
    Some(SpringModes {
        normal: mode((rock * lighter).max(table)),
        tangential: mode(slide.max(twist) * lighter),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_damped_limit_is_the_characteristic_polynomials() {
        // Undamped: 2; the roots of λ² − (2 − h² − 2ζh)·λ + 1 − 2ζh leave the unit circle at
        // λ = −1 exactly where 4 − h² − 4ζh = 0.
        assert!((damped_mode_limit(0.0) - 2.0 * SWITCHING_MARGIN).abs() < 1e-15);
        for zeta in [0.1, 0.3, 0.7] {
            let h = damped_mode_limit(zeta) / SWITCHING_MARGIN;
            assert!((4.0 - h * h - 4.0 * zeta * h).abs() < 1e-12, "ζ = {zeta}");
        }
    }

    #[test]
    fn the_defaults_rock_and_slide_faster_than_they_rock() {
        let mut p = Params::default();
        assert!(spring_friction_modes(&p).is_none());
        p.ground.contact = ContactLaw::SpringFriction;
        let SpringModes { normal, tangential } = spring_friction_modes(&p).unwrap();
        // √(6k/M) = 612.4 rad/s. The stuck face's matrix has trace (6k + 10k_t)/M and
        // determinant 24·k·k_t/M²; at k_t = 2k/7 its larger eigenvalue is 8k/M: 707.1 rad/s.
        assert!((normal.frequency - (6.0 * 500_000.0f64 / 8.0).sqrt()).abs() < 1e-9);
        assert!(
            (tangential.frequency - (8.0 * 500_000.0f64 / 8.0).sqrt()).abs() < 1e-6,
            "{tangential:?}"
        );
        // At the default 1 ms both modes step within their limits; at 1.5 ms the rock-and-slide
        // mode's ω·Δt of 1.06 is past the 0.98 its damping allows, the rock's 0.92 within its 1.03.
        let dt = p.integrator.dt;
        assert!(normal.frequency * dt < normal.allowed && tangential.frequency * dt < tangential.allowed);
        let dt = 0.0015;
        assert!(tangential.frequency * dt > tangential.allowed, "{tangential:?}");
        assert!(normal.frequency * dt < normal.allowed, "{normal:?}");
    }
}
