//! The paper's contact law (docs/model.md, eq. 13–15): each point below the table is pushed
//! up by a spring stiffened by the damping, `P = k·d·(1 − γ·u_z)`, and dragged by kinetic
//! friction `μ·|P|` against its horizontal slip. The slip's direction is the point's own
//! (`FrictionLaw::PerCorner`), or, as the authors' program had it, every point's slip is
//! scaled by one whole-die norm (`FrictionLaw::WholeDieNorm`, reference §9). It remembers
//! nothing between steps, and it knows no tilted table: its weight is straight down.

use super::law::{Law, Touch, corners, touching_bits};
use crate::lane::{Lane, all_lanes, mask_of, put, put_mask, v3, zero3};
use crate::params::{FrictionLaw, Params};
use crate::stopping::StopRule;
use nalgebra::{Vector2, Vector3};

/// The paper's law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Paper;

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
    /// Lanes whose friction takes the authors' whole-die norm (`FrictionLaw::WholeDieNorm`):
    /// a setting of this law's friction, not a law of its own (both variants push alike).
    pub(crate) whole_die_norm: L::Mask,
}

/// No memory at a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct NoMemory;

impl Law for Paper {
    type Constants<L: Lane> = PaperConstants<L>;
    type Point<L: Lane> = NoMemory;

    fn constants(p: &Params, _mass: f64, _edge_energy: f64) -> PaperConstants<f64> {
        let g = &p.ground;
        PaperConstants {
            stiffness: g.stiffness,
            half_stiffness: 0.5 * g.stiffness,
            damping: g.damping,
            friction: g.friction,
            whole_die_norm: g.friction_law == FrictionLaw::WholeDieNorm,
        }
    }

    fn splat<L: Lane>(c: &PaperConstants<f64>) -> PaperConstants<L> {
        PaperConstants {
            stiffness: L::splat(c.stiffness),
            half_stiffness: L::splat(c.half_stiffness),
            damping: L::splat(c.damping),
            friction: L::splat(c.friction),
            whole_die_norm: mask_of::<L>(c.whole_die_norm),
        }
    }

    fn set_lane<L: Lane>(c: &mut PaperConstants<L>, l: usize, from: &PaperConstants<f64>) {
        put(&mut c.stiffness, l, from.stiffness);
        put(&mut c.half_stiffness, l, from.half_stiffness);
        put(&mut c.damping, l, from.damping);
        put(&mut c.friction, l, from.friction);
        put_mask::<L>(&mut c.whole_die_norm, l, from.whole_die_norm);
    }

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
    fn forces<L: Lane>(
        c: &PaperConstants<L>,
        _dt: L,
        radius: L,
        rounded: bool,
        touch: Touch<'_, L, NoMemory>,
    ) {
        if rounded {
            forces_at::<true, L>(c, radius, touch);
        } else {
            forces_at::<false, L>(c, radius, touch);
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
fn forces_at<const ROUNDED: bool, L: Lane>(
    c: &PaperConstants<L>,
    radius: L,
    mut touch: Touch<'_, L, NoMemory>,
) {
    // Copied out one by one, as in the kernel's step.
    let (stiffness, damping, friction, whole_die_norm) =
        (c.stiffness, c.damping, c.friction, c.whole_die_norm);
    let zero = L::zero();
    let (touching, any) = touch.press::<ROUNDED>(radius);
    // Lanes that neither touch now nor did before keep their +0.0 forces; a lane that
    // just left the ground gets +0.0 from the masks below.
    if L::bits(any | *touch.in_contact) == 0 {
        return;
    }
    *touch.in_contact = any;
    let laws = L::bits(whole_die_norm);
    let per_corner_lanes = laws != all_lanes::<L>();
    let whole_lanes = laws != 0;
    let touching_corners = touching_bits::<L>(&touching);
    let previous = std::mem::replace(touch.touching_corners, touching_corners);
    for k in corners(previous & !touching_corners) {
        touch.state.corner_forces[k] = zero3();
    }
    // The authors' law scales every corner's slip by one whole-die matrix norm: the
    // largest singular value of the 8×2 matrix of horizontal corner velocities, from the
    // largest eigenvalue of its 2×2 Gram matrix (within 5·10⁻¹⁶ of LAPACK's, reference
    // §9). It needs every corner's velocity, the per-corner law only those that touch.
    let norm = if whole_lanes {
        let (mut a, mut b, mut cc) = (zero, zero, zero);
        for k in 0..8 {
            let uk = touch.velocity_at::<ROUNDED>(k, radius);
            a = a + uk.x * uk.x;
            b = b + uk.x * uk.y;
            cc = cc + uk.y * uk.y;
        }
        let half_diff = (a - cc) / L::splat(2.0);
        ((a + cc) / L::splat(2.0) + (half_diff * half_diff + b * b).sqrt()).sqrt()
    } else {
        zero
    };
    let norm_nonzero = norm.ne(zero);
    for k in corners(touching_corners) {
        let uk = touch.velocity_at::<ROUNDED>(k, radius);
        let normal = touch.state.corner_depths[k] * stiffness;
        let vertical = normal * (L::splat(1.0) - damping * uk.z);
        let (mut fx, mut fy) = (zero, zero);
        if per_corner_lanes {
            let slip = (uk.x * uk.x + uk.y * uk.y).sqrt();
            let sliding = slip.gt(zero);
            let scale = -(friction * vertical.abs());
            fx = (scale * (uk.x / slip)).or_zero(sliding);
            fy = (scale * (uk.y / slip)).or_zero(sliding);
        }
        if whole_lanes {
            let wx = (-((uk.x / norm) * vertical) * friction).or_zero(norm_nonzero);
            let wy = (-((uk.y / norm) * vertical) * friction).or_zero(norm_nonzero);
            fx = L::select(whole_die_norm, wx, fx);
            fy = L::select(whole_die_norm, wy, fy);
        }
        touch.state.corner_forces[k] = v3(
            fx.or_zero(touching[k]),
            fy.or_zero(touching[k]),
            vertical.or_zero(touching[k]),
        );
    }
}
