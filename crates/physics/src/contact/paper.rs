//! The paper's contact law (docs/model.md, eq. 13–15): each point below the table is pushed
//! up by a spring stiffened by the damping, `P = k·d·(1 − γ·u_z)`, and dragged by kinetic
//! friction `μ·|P|` against its horizontal slip. The slip's direction is the point's own
//! (`FrictionLaw::PerCorner`, [`PerCornerSlip`]), or, as the authors' program had it, every
//! point's slip is scaled by one whole-die norm (`FrictionLaw::WholeDieNorm`,
//! [`WholeDieSlip`], reference §9): two laws, `Paper<PerCornerSlip>` and
//! `Paper<WholeDieSlip>`, that share everything but the slip. It remembers nothing between
//! steps, and it knows no tilted table: its weight is straight down.

use super::law::{Law, Touch, corners, touching_bits};
use crate::lane::{Lane, put, v3, zero3};
use crate::params::Params;
use crate::stopping::StopRule;
use nalgebra::{Vector2, Vector3};
use std::fmt::Debug;
use std::marker::PhantomData;

/// The paper's law, its friction's slip by `S`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Paper<S: Slip>(PhantomData<S>);

/// How the paper's law scales a point's horizontal slip into its friction.
pub trait Slip: Copy + Debug + Send + Sync + 'static {
    /// What every point's friction at this state shares (the whole-die norm), from all `N`
    /// points' velocities; nothing for a slip of a point's own.
    fn shared<const ROUNDED: bool, L: Lane, P, const N: usize>(touch: &Touch<'_, L, P, N>) -> L;
    /// The friction `(x, y)`, dyn, at a point of velocity `u` pressed by `vertical` (dyn).
    fn friction<L: Lane>(u: &Vector3<L>, vertical: L, friction: L, shared: L) -> (L, L);
}

/// The paper's eq. 15: `−μ·|P|·û`, `û` the point's own horizontal slip direction; none
/// without slip.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PerCornerSlip;

impl Slip for PerCornerSlip {
    #[inline(always)]
    fn shared<const ROUNDED: bool, L: Lane, P, const N: usize>(_: &Touch<'_, L, P, N>) -> L {
        L::zero()
    }

    #[inline(always)]
    fn friction<L: Lane>(u: &Vector3<L>, vertical: L, friction: L, _: L) -> (L, L) {
        let zero = L::zero();
        let slip = (u.x * u.x + u.y * u.y).sqrt();
        let sliding = slip.gt(zero);
        let scale = -(friction * vertical.abs());
        (
            (scale * (u.x / slip)).or_zero(sliding),
            (scale * (u.y / slip)).or_zero(sliding),
        )
    }
}

/// The authors' program: every point's slip divided by one whole-die matrix norm, the
/// largest singular value of the N×2 matrix of horizontal point velocities, from the largest
/// eigenvalue of its 2×2 Gram matrix (within 5·10⁻¹⁶ of LAPACK's, reference §9), times
/// `−μ·P` (signed).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WholeDieSlip;

impl Slip for WholeDieSlip {
    #[inline(always)]
    fn shared<const ROUNDED: bool, L: Lane, P, const N: usize>(touch: &Touch<'_, L, P, N>) -> L {
        let zero = L::zero();
        let (mut a, mut b, mut cc) = (zero, zero, zero);
        for k in 0..N {
            let uk = touch.velocity_at::<ROUNDED>(k);
            a = a + uk.x * uk.x;
            b = b + uk.x * uk.y;
            cc = cc + uk.y * uk.y;
        }
        let half_diff = (a - cc) / L::splat(2.0);
        ((a + cc) / L::splat(2.0) + (half_diff * half_diff + b * b).sqrt()).sqrt()
    }

    #[inline(always)]
    fn friction<L: Lane>(u: &Vector3<L>, vertical: L, friction: L, norm: L) -> (L, L) {
        let nonzero = norm.ne(L::zero());
        (
            (-((u.x / norm) * vertical) * friction).or_zero(nonzero),
            (-((u.y / norm) * vertical) * friction).or_zero(nonzero),
        )
    }
}

/// The paper's law's numbers for one roll (per lane).
#[derive(Debug, Clone, Copy)]
pub struct PaperConstants<L: Lane> {
    /// dyn/cm, `k`, and `½·k`.
    pub(crate) stiffness: L,
    pub(crate) half_stiffness: L,
    /// s/cm, `γ`.
    pub(crate) damping: L,
    /// `μ`, kinetic.
    pub(crate) friction: L,
}

/// No memory at a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct NoMemory;

impl<S: Slip> Law for Paper<S> {
    type Constants<L: Lane> = PaperConstants<L>;
    type Point<L: Lane> = NoMemory;

    fn constants(p: &Params, _mass: f64, _edge_energy: f64) -> PaperConstants<f64> {
        let g = &p.ground;
        PaperConstants {
            stiffness: g.stiffness,
            half_stiffness: 0.5 * g.stiffness,
            damping: g.damping,
            friction: g.friction,
        }
    }

    fn splat<L: Lane>(c: &PaperConstants<f64>) -> PaperConstants<L> {
        PaperConstants {
            stiffness: L::splat(c.stiffness),
            half_stiffness: L::splat(c.half_stiffness),
            damping: L::splat(c.damping),
            friction: L::splat(c.friction),
        }
    }

    #[inline(always)]
    fn set_lane<L: Lane>(c: &mut PaperConstants<L>, l: usize, from: &PaperConstants<f64>) {
        put(&mut c.stiffness, l, from.stiffness);
        put(&mut c.half_stiffness, l, from.half_stiffness);
        put(&mut c.damping, l, from.damping);
        put(&mut c.friction, l, from.friction);
    }

    #[inline(always)]
    fn park<L: Lane>(_: &mut PaperConstants<L>, _: usize) {}

    #[inline(always)]
    fn free_point<L: Lane>() -> NoMemory {
        NoMemory
    }

    fn point_lane<L: Lane>(_: &NoMemory, _: usize) -> NoMemory {
        NoMemory
    }

    fn set_point_lane<L: Lane>(_: &mut NoMemory, _: usize, _: &NoMemory) {}

    fn tangential_spring(_: &NoMemory) -> Vector2<f64> {
        Vector2::zeros()
    }

    #[inline(always)]
    fn stiffness<L: Lane>(c: &PaperConstants<L>) -> L {
        c.stiffness
    }

    #[inline(always)]
    fn half_stiffness<L: Lane>(c: &PaperConstants<L>) -> L {
        c.half_stiffness
    }

    fn gravity(p: &Params) -> [f64; 3] {
        [0.0, 0.0, -p.world.gravity]
    }

    #[inline(always)]
    fn kick<L: Lane>(
        _: &PaperConstants<L>,
        v: &mut Vector3<L>,
        force: &Vector3<L>,
        weight_z: L,
        mass: L,
        dt: L,
    ) {
        v.x = v.x + (force.x / mass) * dt;
        v.y = v.y + (force.y / mass) * dt;
        v.z = v.z + ((force.z + weight_z) / mass) * dt;
    }

    #[inline(always)]
    fn potential<L: Lane>(_: &PaperConstants<L>, normal: L, _: &Vector3<L>) -> L {
        normal
    }

    #[inline(always)]
    fn forces<L: Lane, const N: usize>(
        c: &PaperConstants<L>,
        _dt: L,
        rounded: bool,
        touch: Touch<'_, L, NoMemory, N>,
    ) {
        if rounded {
            forces_at::<true, L, N, S>(c, touch);
        } else {
            forces_at::<false, L, N, S>(c, touch);
        }
    }

    #[inline(always)]
    fn settles<L: Lane>(_: &PaperConstants<L>, settled: L::Mask, _: L) -> L::Mask {
        settled
    }

    fn stop_rule(rule: StopRule, _: &Params, _: f64) -> StopRule {
        rule
    }
}

/// [`Paper::forces`] for sharp (`ROUNDED` false) or rounded lanes.
#[inline(always)]
fn forces_at<const ROUNDED: bool, L: Lane, const N: usize, S: Slip>(
    c: &PaperConstants<L>,
    mut touch: Touch<'_, L, NoMemory, N>,
) {
    // Copied out one by one, as in the kernel's step.
    let (stiffness, damping, friction) = (c.stiffness, c.damping, c.friction);
    let (touching, any) = touch.press::<ROUNDED>();
    // Lanes that neither touch now nor did before keep their +0.0 forces; a lane that
    // just left the ground gets +0.0 from the masks below.
    if L::bits(any | *touch.in_contact) == 0 {
        return;
    }
    *touch.in_contact = any;
    let touching_corners = touching_bits::<L, N>(&touching);
    let previous = std::mem::replace(touch.touching_corners, touching_corners);
    for k in corners::<N>(previous & !touching_corners) {
        touch.state.corner_forces[k] = zero3();
    }
    // The authors' whole-die norm needs every point's velocity, a point's own slip only
    // those that touch.
    let shared = S::shared::<ROUNDED, L, NoMemory, N>(&touch);
    for k in corners::<N>(touching_corners) {
        let uk = touch.velocity_at::<ROUNDED>(k);
        let normal = touch.state.corner_depths[k] * stiffness;
        let vertical = normal * (L::splat(1.0) - damping * uk.z);
        let (fx, fy) = S::friction(&uk, vertical, friction, shared);
        touch.state.corner_forces[k] = v3(
            fx.or_zero(touching[k]),
            fy.or_zero(touching[k]),
            vertical.or_zero(touching[k]),
        );
    }
}
