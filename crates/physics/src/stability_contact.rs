//! The spring-friction contact law's own stability modes (docs/model.md, "The
//! spring-friction contact", its "Stability"): its normal mode against the limit its damping
//! sets, and the modes its tangential springs add. [`super::stability`] reads them in place of
//! the paper's table-stiffness reading; the paper's readings the law does not meet — γ's
//! damping and the kinetic friction's chatter — do not apply to it, and the corner-speed and
//! impact-depth readings apply to both laws.

use super::contact::spring_friction::SpringFrictionConstants;
use super::model::Body;
use super::params::{ContactLaw, Params};

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
    if p.ground.contact != ContactLaw::SpringFriction {
        return None;
    }
    let body = Body::new(p);
    let (k, mass) = (p.ground.stiffness, body.mass());
    let law = SpringFrictionConstants::new(p, mass, body.edge_energy());
    let k_t = law.tangential_stiffness;
    let rock = body.rocking_frequency();
    let (h, inertia) = (body.reference_height(), body.mean_inertia());
    // The rock-and-slide pair: the larger eigenvalue of the 2×2 matrix in docs/model.md.
    let (a11, a12) = (4.0 * k_t / mass, -4.0 * k_t * h / mass);
    let (a21, a22) = (
        -4.0 * k_t * h / inertia,
        rock * rock + 4.0 * k_t * h * h / inertia,
    );
    let (trace, det) = (a11 + a22, a11 * a22 - a12 * a21);
    let slide = (0.5 * (trace + (trace * trace - 4.0 * det).max(0.0).sqrt())).sqrt();
    let twist = rock * (2.0 * k_t / k).sqrt();
    // The damping ratio of a mode of frequency ω on springs damped by c per k: ζ = ω·c/(2k).
    let mode = |frequency: f64| SpringMode {
        frequency,
        allowed: damped_mode_limit(frequency * law.normal_damping / (2.0 * k)),
    };
    Some(SpringModes {
        normal: mode(rock),
        tangential: mode(slide.max(twist)),
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
