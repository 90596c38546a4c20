//! The spin stage of the step: ω from L and the rotation it turns the die by in one Δt.
//!
//! The one stage both engines run per roll in scalar code (docs/model.md, "One time step"):
//! it calls libm's `sin` and `cos`, which have no exactly rounded vector twin, so a lane
//! engine calls this function once per lane rather than a vector approximation that would
//! differ in the last bit.

use nalgebra::{Matrix3, Vector3};

/// ω = L / I and the step rotation by |ω|·Δt about ω (`None` while ω = 0), as the authors
/// built it from their `w = −ω` for row vectors: entry (i, j) is
/// `(p + cos·(δᵢⱼ − p)) + (sin·[w]×ᵢⱼ)/|ω|` with `p = (ωᵢ·ωⱼ)/|ω|²`.
///
/// Both engines call this one function (never inlined, so the two see the same libm calls
/// in the same order). Its divisions are the fewest that keep every entry bitwise: `p` is
/// symmetric (`ωᵢ·ωⱼ = ωⱼ·ωᵢ` exactly) and the cross term antisymmetric (a quotient's sign
/// follows its dividend's), so 6 + 3 quotients serve 9 + 9 entries, and the diagonal's
/// `(sin·0)/|ω|` needs no division at all.
#[inline(never)]
pub(crate) fn spin(
    angular_momentum: &Vector3<f64>,
    inertia: f64,
    dt: f64,
) -> (Vector3<f64>, Option<Matrix3<f64>>) {
    let w = angular_momentum / inertia;
    let norm = scaled_norm(&w);
    if norm == 0.0 {
        return (w, None);
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
    (w, Some(m))
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
