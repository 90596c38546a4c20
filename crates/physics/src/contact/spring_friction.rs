//! The spring-friction contact law (docs/model.md, "The spring-friction contact"): at each
//! point below the table a damped normal spring that never pulls,
//! `N = max(0, k·d − c·u_z)`, and a damped tangential spring `ξ` — the slip the point made
//! since it touched the table — that holds it stuck while `|F*| ≤ μ_s·N` and lets it slide at
//! `μ_k·N` beyond. Its numbers: the normal damping that gives the set restitution, the
//! tangential spring and its damping; and its table may be tilted: gravity in the table's
//! frame, and what the tilt does to the stopping rule.
//!
//! It knows the body only by the numbers it is handed (mass, edge energy), so the body
//! model may ask it why a tilted table cannot hold a die.

use super::law::{Law, Touch, corners, touching_bits};
use crate::lane::{Lane, put, v3, zero3};
use crate::params::{ContactLaw, Params};
use crate::stopping::StopRule;
use nalgebra::{Vector2, Vector3};

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

/// The spring-friction law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpringFriction;

/// The spring-friction law's numbers for one roll (per lane, CGS).
#[derive(Debug, Clone, Copy)]
pub struct SpringFrictionConstants<L: Lane> {
    /// dyn/cm, the normal stiffness `k`, and `½·k`.
    pub(crate) stiffness: L,
    pub(crate) half_stiffness: L,
    /// dyn·s/cm, `c = 2·ζ·√(k·M/4)`.
    pub(crate) normal_damping: L,
    /// dyn/cm, `k_t = (k_t/k)·k`.
    pub(crate) tangential_stiffness: L,
    /// dyn·s/cm, `c_t = (k_t/k)·c`.
    pub(crate) tangential_damping: L,
    /// cm/dyn, `1/k_t`: a multiplication where the spring is reset, in both widths alike.
    pub(crate) tangential_compliance: L,
    /// `μ_k` and `μ_s`.
    pub(crate) friction: L,
    pub(crate) static_friction: L,
    /// dyn, the weight's components in a tilted table's plane (+0.0 on a level table).
    pub(crate) weight_x: L,
    pub(crate) weight_y: L,
    /// erg, a tilted table's cap on a settled die's kinetic energy (+∞: none).
    pub(crate) kinetic_cap: L,
}

impl SpringFrictionConstants<f64> {
    /// The constants for a body of `mass` (g) whose edge energy is `edge_energy` (erg) on
    /// `p`'s table.
    pub(crate) fn new(p: &Params, mass: f64, edge_energy: f64) -> Self {
        let g = &p.ground;
        let zeta = damping_ratio(g.restitution);
        let normal_damping = 2.0 * zeta * (g.stiffness * mass / POINTS_OF_A_FACE).sqrt();
        let ratio = g.tangential_stiffness_ratio;
        let tangential_stiffness = ratio * g.stiffness;
        let [gx, gy, _] = gravity_in_table_frame(p);
        SpringFrictionConstants {
            stiffness: g.stiffness,
            half_stiffness: 0.5 * g.stiffness,
            normal_damping,
            tangential_stiffness,
            tangential_damping: ratio * normal_damping,
            tangential_compliance: 1.0 / tangential_stiffness,
            friction: g.friction,
            static_friction: g.static_friction,
            weight_x: mass * gx,
            weight_y: mass * gy,
            kinetic_cap: kinetic_cap(p, edge_energy),
        }
    }
}

impl Law for SpringFriction {
    type Constants<L: Lane> = SpringFrictionConstants<L>;
    /// cm, the tangential spring `ξ` in the table's plane: the slip the point made since it
    /// touched the table (0 off it).
    type Point<L: Lane> = Vector2<L>;

    fn constants(p: &Params, mass: f64, edge_energy: f64) -> SpringFrictionConstants<f64> {
        SpringFrictionConstants::new(p, mass, edge_energy)
    }

    fn splat<L: Lane>(c: &SpringFrictionConstants<f64>) -> SpringFrictionConstants<L> {
        SpringFrictionConstants {
            stiffness: L::splat(c.stiffness),
            half_stiffness: L::splat(c.half_stiffness),
            normal_damping: L::splat(c.normal_damping),
            tangential_stiffness: L::splat(c.tangential_stiffness),
            tangential_damping: L::splat(c.tangential_damping),
            tangential_compliance: L::splat(c.tangential_compliance),
            friction: L::splat(c.friction),
            static_friction: L::splat(c.static_friction),
            weight_x: L::splat(c.weight_x),
            weight_y: L::splat(c.weight_y),
            kinetic_cap: L::splat(c.kinetic_cap),
        }
    }

    #[inline(always)]
    fn set_lane<L: Lane>(c: &mut SpringFrictionConstants<L>, l: usize, from: &SpringFrictionConstants<f64>) {
        put(&mut c.stiffness, l, from.stiffness);
        put(&mut c.half_stiffness, l, from.half_stiffness);
        put(&mut c.normal_damping, l, from.normal_damping);
        put(&mut c.tangential_stiffness, l, from.tangential_stiffness);
        put(&mut c.tangential_damping, l, from.tangential_damping);
        put(&mut c.tangential_compliance, l, from.tangential_compliance);
        put(&mut c.friction, l, from.friction);
        put(&mut c.static_friction, l, from.static_friction);
        put(&mut c.weight_x, l, from.weight_x);
        put(&mut c.weight_y, l, from.weight_y);
        put(&mut c.kinetic_cap, l, from.kinetic_cap);
    }

    #[inline(always)]
    fn park<L: Lane>(c: &mut SpringFrictionConstants<L>, l: usize) {
        put(&mut c.weight_x, l, 0.0);
        put(&mut c.weight_y, l, 0.0);
    }

    #[inline(always)]
    fn free_point<L: Lane>() -> Vector2<L> {
        Vector2::new(L::zero(), L::zero())
    }

    fn point_lane<L: Lane>(xi: &Vector2<L>, l: usize) -> Vector2<f64> {
        Vector2::new(xi.x.lane(l), xi.y.lane(l))
    }

    fn set_point_lane<L: Lane>(xi: &mut Vector2<L>, l: usize, from: &Vector2<f64>) {
        put(&mut xi.x, l, from.x);
        put(&mut xi.y, l, from.y);
    }

    fn tangential_spring(xi: &Vector2<f64>) -> Vector2<f64> {
        *xi
    }

    #[inline(always)]
    fn stiffness<L: Lane>(c: &SpringFrictionConstants<L>) -> L {
        c.stiffness
    }

    #[inline(always)]
    fn half_stiffness<L: Lane>(c: &SpringFrictionConstants<L>) -> L {
        c.half_stiffness
    }

    fn gravity(p: &Params) -> [f64; 3] {
        gravity_in_table_frame(p)
    }

    /// A tilted table's weight has a part in its plane.
    #[inline(always)]
    fn kick<L: Lane>(
        c: &SpringFrictionConstants<L>,
        v: &mut Vector3<L>,
        force: &Vector3<L>,
        weight_z: L,
        mass: L,
        dt: L,
    ) {
        *v = v3(
            v.x + ((force.x + c.weight_x) / mass) * dt,
            v.y + ((force.y + c.weight_y) / mass) * dt,
            v.z + ((force.z + weight_z) / mass) * dt,
        );
    }

    /// `−M·g⃗·x` measured from the rest height: the normal part less the downhill part
    /// `M·g_t·x` of a tilted table (zero on a level one).
    #[inline(always)]
    fn potential<L: Lane>(c: &SpringFrictionConstants<L>, normal: L, x: &Vector3<L>) -> L {
        normal - (c.weight_x * x.x + c.weight_y * x.y)
    }

    #[inline(always)]
    fn forces<L: Lane, const N: usize>(
        c: &SpringFrictionConstants<L>,
        dt: L,
        radius: L,
        rounded: bool,
        touch: Touch<'_, L, Vector2<L>, N>,
    ) {
        if rounded {
            forces_at::<true, L, N>(c, dt, radius, touch);
        } else {
            forces_at::<false, L, N>(c, dt, radius, touch);
        }
    }

    /// A tilted table settles only what its downhill edge can hold.
    #[inline(always)]
    fn settles<L: Lane>(c: &SpringFrictionConstants<L>, settled: L::Mask, kinetic: L) -> L::Mask {
        if L::bits(settled) != 0 {
            settled & kinetic.le(c.kinetic_cap)
        } else {
            settled
        }
    }

    fn stop_rule(rule: StopRule, p: &Params, edge_energy: f64) -> StopRule {
        on_the_table(rule, p, edge_energy)
    }
}

/// [`SpringFriction::forces`] for sharp (`ROUNDED` false) or rounded lanes: per point, the
/// normal `N = max(0, k·d − c·u_z)`; the trial tangential force `F* = −k_t·ξ − c_t·u_t` on
/// the spring `ξ` (the slip since the point touched, this step's included); stuck while
/// `|F*| ≤ μ_s·N`, else sliding at `μ_k·N` along `F*` with the spring set to hold that
/// force. A point off the table has no force and no spring.
#[inline(always)]
fn forces_at<const ROUNDED: bool, L: Lane, const N: usize>(
    c: &SpringFrictionConstants<L>,
    dt: L,
    radius: L,
    mut touch: Touch<'_, L, Vector2<L>, N>,
) {
    let (stiffness, damping, kinetic) = (c.stiffness, c.normal_damping, c.friction);
    let (k_t, c_t, stuck_up_to) = (c.tangential_stiffness, c.tangential_damping, c.static_friction);
    let compliance = c.tangential_compliance;
    let zero = L::zero();
    let previous = *touch.touching_corners;
    let (touching, any) = touch.press::<ROUNDED>(radius);
    if L::bits(any) == 0 && previous == 0 {
        return;
    }
    *touch.in_contact = any;
    let touching_corners = touching_bits::<L, N>(&touching);
    *touch.touching_corners = touching_corners;
    for k in corners::<N>(previous & !touching_corners) {
        touch.state.corner_forces[k] = zero3();
        touch.points[k] = Vector2::new(zero, zero);
    }
    for k in corners::<N>(touching_corners) {
        let t = touching[k];
        let u = touch.velocity_at::<ROUNDED>(k, radius);
        let xi = touch.points[k];
        let (sx, sy) = (xi.x + u.x * dt, xi.y + u.y * dt);
        // The table pushes, never pulls.
        let pressed = touch.state.corner_depths[k] * stiffness - damping * u.z;
        let normal = pressed.or_zero(pressed.gt(zero));
        let (mut fx, mut fy) = (-(k_t * sx) - c_t * u.x, -(k_t * sy) - c_t * u.y);
        let (mut sx, mut sy) = (sx, sy);
        // |F*| > μ_s·N, compared squared (both sides ≥ 0): a point stuck in every lane
        // needs no square root and no quotient.
        let limit = stuck_up_to * normal;
        let slipping = (fx * fx + fy * fy).gt(limit * limit);
        if L::bits(slipping) != 0 {
            // Where it slips |F*| is above μ_s·N ≥ 0, so the quotient is finite there.
            let scale = (kinetic * normal) / (fx * fx + fy * fy).sqrt();
            fx = L::select(slipping, fx * scale, fx);
            fy = L::select(slipping, fy * scale, fy);
            // Sliding, the spring holds the kinetic force: ξ = −(F_t + c_t·u_t)/k_t.
            sx = L::select(slipping, -(fx + c_t * u.x) * compliance, sx);
            sy = L::select(slipping, -(fy + c_t * u.y) * compliance, sy);
        }
        touch.state.corner_forces[k] = v3(fx.or_zero(t), fy.or_zero(t), normal.or_zero(t));
        touch.points[k] = Vector2::new(sx.or_zero(t), sy.or_zero(t));
    }
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
