//! The spring-friction contact law's own stability readings (docs/model.md, "The
//! spring-friction contact", its "Stability"): its normal mode against the limit its damping
//! sets, and the modes its tangential springs add. The paper's readings (stability.rs) that
//! the law does not meet — γ's damping and the kinetic friction's chatter — do not apply to it;
//! the corner-speed reading applies to both laws.

use super::contact::SpringFriction;
use super::model::Body;
use super::params::{ContactLaw, Params};
use serde::Serialize;
use std::fmt;

/// The share of semi-implicit Euler's limit for a damped mode that is allowed: contact
/// switching on and off between steps pumps energy in below the lone mode's limit (the paper's
/// stiffness reading allows 1.4 of 2 for the same reason).
pub const SWITCHING_MARGIN: f64 = 0.7;

/// What a spring-friction reading measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SpringLimit {
    /// `ω_rock·Δt`: the die rocking on a face on its normal springs.
    NormalMode,
    /// `ω_t·Δt`: the faster of a stuck face's rock-and-slide and twist modes.
    TangentialMode,
}

impl SpringLimit {
    /// A short name for the readout.
    pub fn name(self) -> &'static str {
        match self {
            SpringLimit::NormalMode => "table stiffness",
            SpringLimit::TangentialMode => "tangential spring",
        }
    }
}

/// One mode: `ω·Δt` and the largest value that still steps stably at its damping.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpringReading {
    pub limit: SpringLimit,
    /// rad/s, the mode's frequency.
    pub frequency: f64,
    /// `ω·Δt`.
    pub value: f64,
    /// The value above which the roll is predicted unstable.
    pub allowed: f64,
}

impl SpringReading {
    /// `value / allowed`: below 1 the roll is predicted to step stably.
    pub fn load(&self) -> f64 {
        self.value / self.allowed
    }

    pub fn exceeded(&self) -> bool {
        let load = self.load();
        load > 1.0 || load.is_nan()
    }
}

impl fmt::Display for SpringReading {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (v, allowed) = (self.value, self.allowed);
        let what = match self.limit {
            SpringLimit::NormalMode => "table too stiff for Δt: the die rocks on it",
            SpringLimit::TangentialMode => {
                "tangential spring too stiff for Δt: a stuck die rocks and slides on it"
            }
        };
        write!(
            f,
            "{what} with ω·Δt = {v:.2}, {:.1} steps per swing (stable below {allowed:.2} at this damping)",
            std::f64::consts::TAU / v
        )
    }
}

/// `ω·Δt` below which semi-implicit Euler steps the mode `x'' = −ω²·x − 2ζω·x'` stably,
/// `2·(√(1 + ζ²) − ζ)`, times [`SWITCHING_MARGIN`].
pub fn damped_mode_limit(zeta: f64) -> f64 {
    SWITCHING_MARGIN * 2.0 * ((1.0 + zeta * zeta).sqrt() - zeta)
}

/// The spring-friction law's readings for `p`; `None` under the paper's law.
pub fn spring_friction_readings(p: &Params) -> Option<[SpringReading; 2]> {
    if p.ground.contact != ContactLaw::SpringFriction {
        return None;
    }
    let body = Body::new(p);
    let (k, dt, mass) = (p.ground.stiffness, p.integrator.dt, body.mass());
    let law = SpringFriction::new(p, mass);
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
    let reading = |limit, frequency: f64| SpringReading {
        limit,
        frequency,
        value: frequency * dt,
        allowed: damped_mode_limit(frequency * law.normal_damping / (2.0 * k)),
    };
    Some([
        reading(SpringLimit::NormalMode, rock),
        reading(SpringLimit::TangentialMode, slide.max(twist)),
    ])
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
        assert!(spring_friction_readings(&p).is_none());
        p.ground.contact = ContactLaw::SpringFriction;
        let [normal, tangential] = spring_friction_readings(&p).unwrap();
        // √(6k/M) = 612.4 rad/s. The stuck face's matrix has trace (6k + 10k_t)/M and
        // determinant 24·k·k_t/M²; at k_t = 2k/7 its larger eigenvalue is 8k/M: 707.1 rad/s.
        assert!((normal.frequency - (6.0 * 500_000.0f64 / 8.0).sqrt()).abs() < 1e-9);
        assert!(
            (tangential.frequency - (8.0 * 500_000.0f64 / 8.0).sqrt()).abs() < 1e-6,
            "{tangential:?}"
        );
        assert!(!normal.exceeded() && !tangential.exceeded());
        p.integrator.dt = 0.0015;
        let [_, tangential] = spring_friction_readings(&p).unwrap();
        assert!(tangential.exceeded(), "{tangential}");
    }
}
