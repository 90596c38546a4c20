//! The spin stage of the step: ω from L and the rotation it turns the die by in one Δt.
//!
//! It calls libm's `sin` and `cos`, which have no exactly rounded vector twin: the lane
//! engine ([`spin_lanes`]) does everything else in vector operations and calls them once
//! per lane, rather than a vector approximation that would differ in the last bit.

use super::lane::{Lane, set_bits};
use nalgebra::{Matrix3, Vector3};

/// ω = L / I and the step rotation by |ω|·Δt about ω (`None` while ω = 0), as the authors
/// built it: see [`step_rotation`].
#[inline(always)]
pub(crate) fn spin(
    angular_momentum: &Vector3<f64>,
    inertia: f64,
    dt: f64,
) -> (Vector3<f64>, Option<Matrix3<f64>>) {
    let w = angular_momentum / inertia;
    (w, step_rotation(&w, dt))
}

/// The step rotation by |ω|·Δt about ω (`None` while ω = 0), as the authors built it from
/// their `w = −ω` for row vectors: entry (i, j) is `(p + cos·(δᵢⱼ − p)) + (sin·[w]×ᵢⱼ)/|ω|`
/// with `p = (ωᵢ·ωⱼ)/|ω|²`.
///
/// The scalar engine calls it out of line: inlined, it crowds the step's loop. Its divisions
/// are the fewest that keep every entry bitwise: `p` is symmetric (`ωᵢ·ωⱼ = ωⱼ·ωᵢ` exactly)
/// and the cross term antisymmetric (a quotient's sign follows its dividend's), so 6 + 3
/// quotients serve 9 + 9 entries, and the diagonal's `(sin·0)/|ω|` needs no division at all.
#[inline(never)]
pub(crate) fn step_rotation(w: &Vector3<f64>, dt: f64) -> Option<Matrix3<f64>> {
    let norm = scaled_norm(w);
    if norm == 0.0 {
        return None;
    }
    let theta = norm * dt;
    let norm_sq = norm.powf(2.0);
    let (sin, cos) = (theta.sin(), theta.cos());
    let p = |i: usize, j: usize| (w[i] * w[j]) / norm_sq;
    let (pxx, pyy, pzz) = (p(0, 0), p(1, 1), p(2, 2));
    let (pxy, pxz, pyz) = (p(0, 1), p(0, 2), p(1, 2));
    // [w_code]× with w_code = −ω has (0,1) = ω_z, (0,2) = −ω_y, (1,2) = ω_x.
    let (sz, sy, sx) = ((sin * w.z) / norm, (sin * -w.y) / norm, (sin * w.x) / norm);
    // `(sin·0)/|ω|` is `sin·0` itself: ±0 keeps its sign over a positive |ω| (finite or
    // ∞), and a NaN (sin of ∞ or NaN) passes through the division unchanged.
    let diagonal = sin * 0.0;
    let on = |p: f64| (p + cos * (1.0 - p)) + diagonal;
    let off = |p: f64| p + cos * (0.0 - p);
    #[rustfmt::skip]
    let m = Matrix3::new(
        on(pxx),        off(pxy) + sz,  off(pxz) + sy,
        off(pxy) + -sz, on(pyy),        off(pyz) + sx,
        off(pxz) + -sy, off(pyz) + -sx, on(pzz),
    );
    Some(m)
}

/// [`spin`] in several lanes at once, from ω (the quotient `L/I` already taken): where ω ≠ 0,
/// and the row-major step rotation, meaningful in those lanes of `lanes` (the others'
/// entries are whatever their values gave, to be discarded).
///
/// The same operations on the same operands lane by lane, so every entry has [`spin`]'s
/// bits: the branches of the scaled norm become selects between their values (a lane
/// computes every branch's value and keeps the one its branch would have taken; the
/// others may divide by zero, harmlessly), and `sin` and `cos` come from libm per lane.
#[inline(always)]
pub(crate) fn spin_lanes<L: Lane>(w: &Vector3<L>, dt: L, lanes: u32) -> (L::Mask, [L; 9]) {
    let (zero, one) = (L::zero(), L::splat(1.0));
    let (mut scale, mut sum) = (zero, one);
    for t in [w.x.abs(), w.y.abs(), w.z.abs()] {
        // `scaled_norm`'s three branches, in its order of precedence.
        let equal = !scale.ne(t);
        let grows = scale.lt(t);
        let counts = t.ne(zero);
        let q = scale / t;
        let grown = L::select(!scale.ne(zero), one, sum * (q * q) + one);
        let r = t / scale;
        let added = sum + r * r;
        sum = L::select(
            equal,
            sum + one,
            L::select(grows, grown, L::select(counts, added, sum)),
        );
        scale = L::select(grows, t, scale);
    }
    let norm = scale * sum.sqrt();
    let nonzero = norm.ne(zero);
    let theta = (norm * dt).to_lanes();
    let (mut sin, mut cos) = (zero.to_lanes(), zero.to_lanes());
    for lane in set_bits(lanes & L::bits(nonzero)) {
        let t = theta.as_ref()[lane];
        sin.as_mut()[lane] = t.sin();
        cos.as_mut()[lane] = t.cos();
    }
    let (sin, cos) = (L::from_lanes(sin), L::from_lanes(cos));
    // `norm.powf(2.0)` in `spin` compiles to this product (LLVM folds pow(x, 2) to x·x,
    // exact in both).
    let norm_sq = norm * norm;
    let p = |a: L, b: L| (a * b) / norm_sq;
    let (pxx, pyy, pzz) = (p(w.x, w.x), p(w.y, w.y), p(w.z, w.z));
    let (pxy, pxz, pyz) = (p(w.x, w.y), p(w.x, w.z), p(w.y, w.z));
    let (sz, sy, sx) = ((sin * w.z) / norm, (sin * -w.y) / norm, (sin * w.x) / norm);
    let diagonal = sin * zero;
    let on = |p: L| (p + cos * (one - p)) + diagonal;
    let off = |p: L| p + cos * (zero - p);
    #[rustfmt::skip]
    let m = [
        on(pxx),        off(pxy) + sz,  off(pxz) + sy,
        off(pxy) + -sz, on(pyy),        off(pyz) + sx,
        off(pxz) + -sy, off(pyz) + -sx, on(pzz),
    ];
    (nonzero, m)
}

/// One step's free rotation of a body whose inertia is not isotropic, by the symmetric
/// splitting about its principal axes (docs/model.md, "Rotation of an anisotropic body"):
/// the body turns about its principal axis 1 by `(m₁/I₁)·Δt/2`, then about axis 2 by
/// `(m₂/I₂)·Δt/2`, about axis 3 by `(m₃/I₃)·Δt`, about axis 2 and axis 1 by half steps
/// again, each `m_i` the component of `L` along the axis as it stands at that turn. Each
/// turn is the exact flow of one term `m_i²/(2I_i)` of the energy, so it keeps `m_i`, `L`
/// and `|L|`; the composition is symplectic and keeps the energy to `O(Δt²)` without drift
/// (Dullweber, Leimkuhler & McLachlan 1997).
#[derive(Debug, Clone, Copy)]
pub(crate) struct FreeTurn<L> {
    /// rad/s, `I(t)⁻¹·L` at the orientation the step starts from (what the kick's work is
    /// measured against, as for every other body).
    pub(crate) before: Vector3<L>,
    /// The principal axes in the world frame once the body has turned (orthonormal to
    /// rounding): the step places the corners along them ([`Kernel::step`]), so the body
    /// stays rigid to rounding however many steps it turns.
    ///
    /// [`Kernel::step`]: crate::kernel::Kernel::step
    pub(crate) axes: [Vector3<L>; 3],
    /// rad/s, `I(t + Δt)⁻¹·L`, the turned body's.
    pub(crate) after: Vector3<L>,
}

/// The turns of [`free_turn`]: the principal axis (0-based) and whether it turns for the
/// whole `Δt` (else for half of it).
const SPLITTING: [(usize, bool); 5] = [(0, false), (1, false), (2, true), (1, false), (0, false)];

/// [`FreeTurn`] from the corner (contact-sphere) offsets `offsets` (cm, world frame), which
/// give the body axes, read at the frame points `[o, x, y]` (a cube's corners 1, 5 and 3), as
/// `(r_x − r_o)·s₀` and `(r_y − r_o)·s₁` (`axis_scale`, 1/cm),
/// orthonormalised (Gram–Schmidt, so that the step's rotation is orthogonal to rounding
/// however the corners have drifted); the principal axes in the body frame,
/// `principal_axes[3j + i]` the body component `j` of axis `i`; `1/I_i` (1/(g·cm²)); `L`
/// (g·cm²/s) and `Δt` (s). `sin` and `cos` are libm's, taken per lane for the lanes of
/// `lanes` (the others' values are to be discarded), so every width has the same bits.
#[inline(always)]
pub(crate) fn free_turn<L: Lane, const N: usize>(
    offsets: &[Vector3<L>; N],
    ([o, x, y], axis_scale): ([usize; 3], &[L; 3]),
    principal_axes: &[L; 9],
    inverse_moments: &[L; 3],
    l: &Vector3<L>,
    dt: L,
    lanes: u32,
) -> FreeTurn<L> {
    // No closures and no `array::from_fn` here: they would be functions of their own, built
    // without the lane engine's AVX2, and every vector operation in them a call.
    let ex = unit(&column(offsets, o, x, axis_scale[0]));
    let y = column(offsets, o, y, axis_scale[1]);
    let along = dot(&ex, &y);
    let ey = unit(&Vector3::new(
        y.x - ex.x * along,
        y.y - ex.y * along,
        y.z - ex.z * along,
    ));
    let ez = Vector3::new(
        ex.y * ey.z - ex.z * ey.y,
        ex.z * ey.x - ex.x * ey.z,
        ex.x * ey.y - ex.y * ey.x,
    );
    // The principal axes in the world frame, and L's components along them.
    let e = principal_axes;
    let axes = [
        combine(&ex, &ey, &ez, e[0], e[3], e[6]),
        combine(&ex, &ey, &ez, e[1], e[4], e[7]),
        combine(&ex, &ey, &ez, e[2], e[5], e[8]),
    ];
    let start = [dot(&axes[0], l), dot(&axes[1], l), dot(&axes[2], l)];
    let mut m = start;
    let mut turned = axes;
    let half = L::splat(0.5) * dt;
    for (i, whole) in SPLITTING {
        let h = if whole { dt } else { half };
        let angle = (m[i] * inverse_moments[i]) * h;
        let (sin, cos) = sin_cos(angle, lanes);
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        // The body turns by +angle about axis i: its axes j and k turn with it, and L,
        // which stands still, turns the other way in the body's frame.
        let (mj, mk) = (m[j], m[k]);
        m[j] = cos * mj + sin * mk;
        m[k] = cos * mk - sin * mj;
        let (bj, bk) = (turned[j], turned[k]);
        turned[j] = Vector3::new(
            bj.x * cos + bk.x * sin,
            bj.y * cos + bk.y * sin,
            bj.z * cos + bk.z * sin,
        );
        turned[k] = Vector3::new(
            bk.x * cos - bj.x * sin,
            bk.y * cos - bj.y * sin,
            bk.z * cos - bj.z * sin,
        );
    }
    let r = inverse_moments;
    let before = [start[0] * r[0], start[1] * r[1], start[2] * r[2]];
    let after = [m[0] * r[0], m[1] * r[1], m[2] * r[2]];
    FreeTurn {
        before: combine(&axes[0], &axes[1], &axes[2], before[0], before[1], before[2]),
        after: combine(&turned[0], &turned[1], &turned[2], after[0], after[1], after[2]),
        axes: turned,
    }
}

/// `(r_to − r_from)·s`: a body axis read off the points.
#[inline(always)]
fn column<L: Lane, const N: usize>(offsets: &[Vector3<L>; N], from: usize, to: usize, s: L) -> Vector3<L> {
    let (a, b) = (&offsets[to], &offsets[from]);
    Vector3::new((a.x - b.x) * s, (a.y - b.y) * s, (a.z - b.z) * s)
}

#[inline(always)]
fn dot<L: Lane>(a: &Vector3<L>, b: &Vector3<L>) -> L {
    (a.x * b.x + a.y * b.y) + a.z * b.z
}

#[inline(always)]
fn unit<L: Lane>(a: &Vector3<L>) -> Vector3<L> {
    let norm = dot(a, a).sqrt();
    Vector3::new(a.x / norm, a.y / norm, a.z / norm)
}

/// `(a·p + b·q) + c·r`, component by component.
#[inline(always)]
fn combine<L: Lane>(a: &Vector3<L>, b: &Vector3<L>, c: &Vector3<L>, p: L, q: L, r: L) -> Vector3<L> {
    Vector3::new(
        (a.x * p + b.x * q) + c.x * r,
        (a.y * p + b.y * q) + c.y * r,
        (a.z * p + b.z * q) + c.z * r,
    )
}

/// libm's `sin` and `cos` of each lane of `lanes` (0 and 1 elsewhere).
#[inline(always)]
fn sin_cos<L: Lane>(angle: L, lanes: u32) -> (L, L) {
    let angles = angle.to_lanes();
    let (mut sin, mut cos) = (L::zero().to_lanes(), L::splat(1.0).to_lanes());
    for lane in set_bits(lanes) {
        let a = angles.as_ref()[lane];
        sin.as_mut()[lane] = a.sin();
        cos.as_mut()[lane] = a.cos();
    }
    (L::from_lanes(sin), L::from_lanes(cos))
}

/// Octave's overflow-safe 2-norm of a 3-vector (reference §9), bitwise.
fn scaled_norm(w: &Vector3<f64>) -> f64 {
    let mut scale: f64 = 0.0;
    let mut sum: f64 = 1.0;
    for t in w.iter().map(|c| c.abs()) {
        if scale == t {
            sum += 1.0;
        } else if scale < t {
            // The first nonzero component: `1·(0/t)² + 1` is exactly 1, no division needed.
            sum = if scale == 0.0 {
                1.0
            } else {
                sum * ((scale / t) * (scale / t)) + 1.0
            };
            scale = t;
        } else if t != 0.0 {
            sum += (t / scale) * (t / scale);
        }
    }
    scale * sum.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaled_norm_matches_plain_norm_closely() {
        for w in [
            [3.0, 4.0, 0.0],
            [0.0, 0.0, 0.0],
            [1e-3, -2.0, 7.5],
            [0.0, 5.0, 0.0],
        ] {
            let v = Vector3::from(w);
            assert!((scaled_norm(&v) - v.norm()).abs() <= 1e-15 * v.norm().max(1.0));
        }
        assert_eq!(scaled_norm(&Vector3::new(0.0, 5.0, 0.0)), 5.0);
    }
}
