//! The spring-friction contact law (docs/model.md, "The spring-friction contact"): at each
//! point below the table a damped normal spring that never pulls,
//! `N = max(0, k·d − c·u_z)`, and a damped tangential spring `ξ` — the slip the point made
//! since it touched the table — that holds it stuck while `|F*| ≤ μ_s·N` and lets it slide at
//! `μ_k·N` beyond. Its numbers: the normal damping that gives the set restitution, the
//! tangential spring and its damping, and the damping of a point that strikes while the body
//! leans on the table (the face restitution); its table may be compliant (a top of its own
//! mass on a damped spring, moving along the normal under every point at once) and tilted:
//! gravity in the table's frame, and what the tilt does to the stopping rule.
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

/// s, how long a flat drop's four points touch the table on springs `k` under a body of
/// `mass` (g) at damping ratio `zeta`: `(π − 2·asin ζ)/ω_d`, `ω_d = √(k/(M/4))·√(1 − ζ²)`,
/// the clamped dashpot's contact (docs/model.md, "The spring-friction contact"). A point that
/// first touches after another has touched this long strikes a body leaning on the table,
/// not one landing from flight.
pub fn flat_drop_contact_time(stiffness: f64, mass: f64, zeta: f64) -> f64 {
    let damped = (stiffness * POINTS_OF_A_FACE / mass).sqrt() * (1.0 - zeta * zeta).sqrt();
    (std::f64::consts::PI - 2.0 * zeta.asin()) / damped
}

/// The spring-friction law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpringFriction;

/// What a point of the spring-friction law remembers while it touches the table (zero off it),
/// and the table top's motion, which every point holds alike whether it touches or not (zero on
/// a rigid table).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringPoint<L: Lane> {
    /// cm, the tangential spring `ξ` in the table's plane: the slip the point made since it
    /// touched the table.
    pub(crate) spring: Vector2<L>,
    /// s, how long the point has touched the table.
    pub(crate) held: L,
    /// 1 when the point struck while another point of the body had touched for at least the
    /// flat drop's contact time (it takes the face dashpot until it leaves), else 0.
    pub(crate) leaning: L,
    /// cm, how far the table top has sunk below its rest level, and cm/s, how fast it sinks.
    pub(crate) table_depth: L,
    pub(crate) table_speed: L,
}

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
    /// dyn·s/cm, the dashpots of a point that struck leaning: `c_f = 2·ζ(e_f)·√(k·M/4)` and
    /// `(k_t/k)·c_f`; `c` and `c_t` themselves when no face restitution is set.
    pub(crate) face_damping: L,
    pub(crate) face_tangential_damping: L,
    /// s, the flat drop's contact time: a point striking after another has touched this long
    /// strikes leaning.
    pub(crate) leaning_after: L,
    /// 1/g, dyn/cm and dyn·s/cm: the table top's `1/m_T`, `K_T` and `C_T`; all +0.0 on a
    /// rigid table, whose top then never moves.
    pub(crate) table_inverse_mass: L,
    pub(crate) table_stiffness: L,
    pub(crate) table_damping: L,
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
        let point_mass = (g.stiffness * mass / POINTS_OF_A_FACE).sqrt();
        let normal_damping = 2.0 * zeta * point_mass;
        // Absent, the face dashpot is `c` itself, so every step's arithmetic is the law's
        // without the key.
        let face_damping = g
            .face_restitution
            .map_or(normal_damping, |e_f| 2.0 * damping_ratio(e_f) * point_mass);
        let ratio = g.tangential_stiffness_ratio;
        let tangential_stiffness = ratio * g.stiffness;
        let [gx, gy, _] = gravity_in_table_frame(p);
        SpringFrictionConstants {
            stiffness: g.stiffness,
            half_stiffness: 0.5 * g.stiffness,
            normal_damping,
            tangential_stiffness,
            tangential_damping: ratio * normal_damping,
            face_damping,
            face_tangential_damping: ratio * face_damping,
            leaning_after: flat_drop_contact_time(g.stiffness, mass, zeta),
            table_inverse_mass: g.table_mass.map_or(0.0, |m| 1.0 / m),
            table_stiffness: g.table_mass.and(g.table_stiffness).unwrap_or(0.0),
            table_damping: g.table_mass.and(g.table_damping).unwrap_or(0.0),
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
    type Point<L: Lane> = SpringPoint<L>;

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
            face_damping: L::splat(c.face_damping),
            face_tangential_damping: L::splat(c.face_tangential_damping),
            leaning_after: L::splat(c.leaning_after),
            table_inverse_mass: L::splat(c.table_inverse_mass),
            table_stiffness: L::splat(c.table_stiffness),
            table_damping: L::splat(c.table_damping),
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
        put(&mut c.face_damping, l, from.face_damping);
        put(&mut c.face_tangential_damping, l, from.face_tangential_damping);
        put(&mut c.leaning_after, l, from.leaning_after);
        put(&mut c.table_inverse_mass, l, from.table_inverse_mass);
        put(&mut c.table_stiffness, l, from.table_stiffness);
        put(&mut c.table_damping, l, from.table_damping);
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
    fn free_point<L: Lane>() -> SpringPoint<L> {
        SpringPoint {
            spring: Vector2::new(L::zero(), L::zero()),
            held: L::zero(),
            leaning: L::zero(),
            table_depth: L::zero(),
            table_speed: L::zero(),
        }
    }

    fn point_lane<L: Lane>(point: &SpringPoint<L>, l: usize) -> SpringPoint<f64> {
        SpringPoint {
            spring: Vector2::new(point.spring.x.lane(l), point.spring.y.lane(l)),
            held: point.held.lane(l),
            leaning: point.leaning.lane(l),
            table_depth: point.table_depth.lane(l),
            table_speed: point.table_speed.lane(l),
        }
    }

    fn set_point_lane<L: Lane>(point: &mut SpringPoint<L>, l: usize, from: &SpringPoint<f64>) {
        put(&mut point.spring.x, l, from.spring.x);
        put(&mut point.spring.y, l, from.spring.y);
        put(&mut point.held, l, from.held);
        put(&mut point.leaning, l, from.leaning);
        put(&mut point.table_depth, l, from.table_depth);
        put(&mut point.table_speed, l, from.table_speed);
    }

    fn tangential_spring(point: &SpringPoint<f64>) -> Vector2<f64> {
        point.spring
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
        rounded: bool,
        touch: Touch<'_, L, SpringPoint<L>, N>,
    ) {
        if rounded {
            forces_at::<true, L, N>(c, dt, touch);
        } else {
            forces_at::<false, L, N>(c, dt, touch);
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
/// force. A point that struck while another had touched for the flat drop's contact time
/// takes `c_f` and `(k_t/k)·c_f` for `c` and `c_t` until it leaves. A point off the table has
/// no force and no memory. Depths and the normal velocity are taken against the table top,
/// which then moves under the points' summed normal force and its own spring and damper
/// (semi-implicit Euler, as the body).
#[inline(always)]
fn forces_at<const ROUNDED: bool, L: Lane, const N: usize>(
    c: &SpringFrictionConstants<L>,
    dt: L,
    mut touch: Touch<'_, L, SpringPoint<L>, N>,
) {
    let (stiffness, kinetic) = (c.stiffness, c.friction);
    let (k_t, stuck_up_to) = (c.tangential_stiffness, c.static_friction);
    let compliance = c.tangential_compliance;
    let zero = L::zero();
    let previous = *touch.touching_corners;
    // The top sunk by `z_T` is the table the points meet: pressed against it, as if the body
    // stood `z_T` higher above a table at rest.
    let (table_depth, table_speed) = (touch.points[0].table_depth, touch.points[0].table_speed);
    let centre = touch.state.position.z;
    touch.state.position.z = centre + table_depth;
    let (touching, any) = touch.press::<ROUNDED>();
    touch.state.position.z = centre;
    let table_moves = table_depth.ne(zero) | table_speed.ne(zero);
    if L::bits(any) == 0 && previous == 0 && L::bits(table_moves) == 0 {
        return;
    }
    *touch.in_contact = any;
    // Per lane: the body leans on the table when a point has touched for the contact time
    // (a point off the table holds 0).
    let mut leaning = L::mask_from_bits(0);
    for k in corners::<N>(previous) {
        leaning = leaning | c.leaning_after.le(touch.points[k].held);
    }
    let touching_corners = touching_bits::<L, N>(&touching);
    *touch.touching_corners = touching_corners;
    for k in corners::<N>(previous & !touching_corners) {
        touch.state.corner_forces[k] = zero3();
        touch.points[k] = SpringFriction::free_point();
    }
    for k in corners::<N>(touching_corners) {
        let t = touching[k];
        let u = touch.velocity_at::<ROUNDED>(k);
        let point = touch.points[k];
        // A point keeps the dashpot it struck with; one striking now takes the face dashpot
        // where the body leans.
        let struck_before = point.held.gt(zero);
        let face = (struck_before & point.leaning.gt(zero)) | (!struck_before & leaning);
        let damping = L::select(face, c.face_damping, c.normal_damping);
        let c_t = L::select(face, c.face_tangential_damping, c.tangential_damping);
        let xi = point.spring;
        let (sx, sy) = (xi.x + u.x * dt, xi.y + u.y * dt);
        // The table pushes, never pulls; its top sinks at `table_speed`.
        let pressed = touch.state.corner_depths[k] * stiffness - damping * (u.z + table_speed);
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
        touch.points[k] = SpringPoint {
            spring: Vector2::new(sx.or_zero(t), sy.or_zero(t)),
            held: (point.held + dt).or_zero(t),
            leaning: L::select(face, L::splat(1.0), zero).or_zero(t),
            table_depth: zero,
            table_speed: zero,
        };
    }
    // The top: pushed down by the points' normal forces, held by its spring and damper. On a
    // rigid table `1/m_T` is +0.0 and it stays at +0.0.
    let mut load = zero;
    for k in corners::<N>(touching_corners) {
        load = load + touch.state.corner_forces[k].z;
    }
    let support = c.table_stiffness * table_depth + c.table_damping * table_speed;
    let table_speed = table_speed + ((load - support) * c.table_inverse_mass) * dt;
    let table_depth = table_depth + table_speed * dt;
    for point in touch.points.iter_mut() {
        point.table_depth = table_depth;
        point.table_speed = table_speed;
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
