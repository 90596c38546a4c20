//! The spring-friction contact law's numbers, derived once from the parameters
//! (docs/model.md, "The spring-friction contact"): the normal damping that gives the set
//! restitution, the tangential spring and its damping, gravity in the tilted table's frame,
//! and what the tilt does to the stopping rule. The step itself is in kernel.rs.
//!
//! It knows the body only by the numbers it is handed (mass, edge energy), so the body
//! model may ask it why a tilted table cannot hold a die.

use super::params::{ContactLaw, Params};
use super::stopping::StopRule;

/// How many of a body's contact points the set restitution is exact for: a flat face's 4,
/// each carrying a quarter of the mass (`m_eff = M/4`, docs/model.md).
pub(crate) const POINTS_OF_A_FACE: f64 = 4.0;

/// The restitution of a linear spring-dashpot whose force is clamped at zero (the table
/// never pulls), at damping ratio `zeta` in [0, 1): `exp(−ζ·(π − 2·asin ζ)/√(1 − ζ²))`.
/// The point leaves the table where the force reaches zero, before it is back at depth 0
/// (docs/model.md derives it); 1 at ζ = 0, falling to e⁻² as ζ → 1.
pub fn clamped_restitution(zeta: f64) -> f64 {
    (-zeta * (std::f64::consts::PI - 2.0 * zeta.asin()) / (1.0 - zeta * zeta).sqrt()).exp()
}

/// The damping ratio ζ at which [`clamped_restitution`] is `e` (e in [0.2, 1]); 0 for
/// e = 1. Newton's method on `ln e(ζ) = ln e`, whose derivative is
/// `2ζ/(1 − ζ²) − (π − 2·asin ζ)/(1 − ζ²)^(3/2)`, from the unclamped dashpot's
/// `−ln e/√(π² + ln² e)` (below the answer, where the curve is convex: it converges from there
/// without overshooting); a fixed number of steps, so the answer is the same every time. It runs
/// once per roll, so it is kept to a few calls of `asin`.
pub fn damping_ratio(e: f64) -> f64 {
    if e >= 1.0 {
        return 0.0;
    }
    let target = e.ln();
    let pi = std::f64::consts::PI;
    let mut zeta = -target / (pi * pi + target * target).sqrt();
    for _ in 0..8 {
        let (arc, s2) = (pi - 2.0 * zeta.asin(), 1.0 - zeta * zeta);
        let s = s2.sqrt();
        let value = -zeta * arc / s - target;
        let slope = 2.0 * zeta / s2 - arc / (s2 * s);
        zeta = (zeta - value / slope).clamp(0.0, 1.0 - 1e-12);
    }
    zeta
}

/// cm/s², gravity in the table's frame: `g·(sin θ·cos φ, sin θ·sin φ, −cos θ)` for a table
/// tilted by θ (`ground.tilt`) sloping down toward φ (`ground.tilt_direction`); exactly
/// `(0, 0, −g)` on a level table and under the paper's law.
pub fn gravity_in_table_frame(p: &Params) -> [f64; 3] {
    let g = p.world.gravity;
    let ground = &p.ground;
    if ground.contact == ContactLaw::Paper || ground.tilt == 0.0 {
        return [0.0, 0.0, -g];
    }
    let (theta, phi) = (ground.tilt.to_radians(), ground.tilt_direction.to_radians());
    let along = g * theta.sin();
    [along * phi.cos(), along * phi.sin(), -(g * theta.cos())]
}

/// The spring-friction law's constants for one die (CGS).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SpringFriction {
    /// dyn·s/cm, `c = 2·ζ·√(k·M/4)`.
    pub(crate) normal_damping: f64,
    /// dyn/cm, `k_t = (k_t/k)·k`.
    pub(crate) tangential_stiffness: f64,
    /// dyn·s/cm, `c_t = (k_t/k)·c`.
    pub(crate) tangential_damping: f64,
    /// cm/dyn, `1/k_t`.
    pub(crate) tangential_compliance: f64,
}

impl SpringFriction {
    /// The constants for a die of `mass` (g) on `p`'s table; all zero under the paper's law,
    /// which reads none of them (and should not pay for the restitution's Newton steps).
    pub(crate) fn new(p: &Params, mass: f64) -> SpringFriction {
        let g = &p.ground;
        if g.contact == ContactLaw::Paper {
            return SpringFriction {
                normal_damping: 0.0,
                tangential_stiffness: 0.0,
                tangential_damping: 0.0,
                tangential_compliance: 0.0,
            };
        }
        let zeta = damping_ratio(g.restitution);
        let normal_damping = 2.0 * zeta * (g.stiffness * mass / POINTS_OF_A_FACE).sqrt();
        let ratio = g.tangential_stiffness_ratio;
        let tangential_stiffness = ratio * g.stiffness;
        SpringFriction {
            normal_damping,
            tangential_stiffness,
            tangential_damping: ratio * normal_damping,
            tangential_compliance: 1.0 / tangential_stiffness,
        }
    }
}

/// The share of a level table's edge energy that tips a cube resting on a table tilted by
/// `tilt` (degrees) over its downhill edge: the centre, `a·√2` from the edge, starts
/// `a·(cos θ + sin θ)` above it, so the pass is `M·g·a·(√2 − sin θ − cos θ)` against the
/// level `M·g·a·(√2 − 1)`; zero at 45°, where the cube tips by itself.
pub fn downhill_pass_share(tilt: f64) -> f64 {
    let theta = tilt.to_radians();
    (std::f64::consts::SQRT_2 - theta.sin() - theta.cos()) / (std::f64::consts::SQRT_2 - 1.0)
}

/// Why `p`'s tilted table cannot hold a die at rest, in words; `None` when it can (a level
/// table, or the paper's law).
pub fn why_a_tilt_cannot_hold(p: &Params) -> Option<String> {
    let g = &p.ground;
    if g.contact == ContactLaw::Paper || g.tilt == 0.0 {
        return None;
    }
    let slope = g.tilt.to_radians().tan();
    if slope > g.static_friction {
        return Some(format!(
            "the table is tilted {}° and tan {}° = {slope:.3} is above the static friction {}: \
             the die cannot rest, it slides",
            g.tilt, g.tilt, g.static_friction
        ));
    }
    if downhill_pass_share(g.tilt) <= 0.0 {
        return Some(format!(
            "the table is tilted {}°, at or past 45°: a cube tips over its downhill edge by itself",
            g.tilt
        ));
    }
    None
}

/// The stopping rule `rule` (a level table's, for a body whose edge energy is
/// `edge_energy`, erg) on `p`'s table: unchanged on a level one; on a tilted one, the
/// kinetic energy must also stay below `f` times the downhill pass, and a tilt that cannot
/// hold the die leaves no rule ([`StopRule::NEVER`]).
pub(crate) fn on_the_table(rule: StopRule, p: &Params, edge_energy: f64) -> StopRule {
    let g = &p.ground;
    if g.contact == ContactLaw::Paper || g.tilt == 0.0 {
        return rule;
    }
    if why_a_tilt_cannot_hold(p).is_some() {
        return StopRule::NEVER;
    }
    StopRule {
        kinetic_threshold: rule.kinetic_threshold.min(kinetic_cap(p, edge_energy)),
        ..rule
    }
}

/// erg, the tilted table's cap on the kinetic energy of a settled die, `f·share·E_edge`;
/// +∞ on a level table (no cap).
pub(crate) fn kinetic_cap(p: &Params, edge_energy: f64) -> f64 {
    let g = &p.ground;
    if g.contact == ContactLaw::Paper || g.tilt == 0.0 {
        return f64::INFINITY;
    }
    p.integrator.stop_energy_fraction * downhill_pass_share(g.tilt) * edge_energy
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_damping_ratio_gives_back_its_restitution() {
        for e in [0.2, 0.35, 0.5, 0.8, 0.95, 0.999] {
            let zeta = damping_ratio(e);
            assert!(
                (clamped_restitution(zeta) - e).abs() < 1e-12,
                "e = {e}: ζ = {zeta}"
            );
        }
        assert_eq!(damping_ratio(1.0), 0.0);
        // The clamped dashpot needs more damping than the unclamped `−ln e/√(π² + ln² e)`,
        // which would rebound at 0.550 where 0.5 is asked.
        let unclamped = -(0.5f64.ln()) / (std::f64::consts::PI.powi(2) + 0.5f64.ln().powi(2)).sqrt();
        assert!(damping_ratio(0.5) > unclamped + 0.03);
        assert!((clamped_restitution(unclamped) - 0.550).abs() < 5e-4);
    }

    #[test]
    fn a_level_table_keeps_gravity_down_and_the_rule() {
        let mut p = Params::default();
        p.ground.contact = ContactLaw::SpringFriction;
        assert_eq!(gravity_in_table_frame(&p), [0.0, 0.0, -980.0]);
        assert_eq!(kinetic_cap(&p, 3000.0), f64::INFINITY);
        p.ground.tilt = 30.0;
        p.ground.tilt_direction = 90.0;
        let [x, y, z] = gravity_in_table_frame(&p);
        assert!(x.abs() < 1e-12 && (y - 490.0).abs() < 1e-9 && (z + 980.0 * 0.75f64.sqrt()).abs() < 1e-9);
        assert!((downhill_pass_share(0.0) - 1.0).abs() < 1e-15);
        assert!(downhill_pass_share(45.0).abs() < 1e-15);
        // tan 30° = 0.577 is below μ_s = 1.2: it holds; at μ_s = 0.5 it cannot.
        assert_eq!(why_a_tilt_cannot_hold(&p), None);
        p.ground.static_friction = 0.5;
        p.ground.friction = 0.5;
        assert!(why_a_tilt_cannot_hold(&p).unwrap().contains("slides"));
        assert_eq!(
            on_the_table(
                StopRule {
                    energy_threshold: 1.0,
                    kinetic_threshold: 1.0
                },
                &p,
                1.0
            ),
            StopRule::NEVER
        );
    }
}
