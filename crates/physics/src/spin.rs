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
