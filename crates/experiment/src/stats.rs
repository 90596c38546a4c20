//! Outcome statistics: face counts, shares with their intervals, the χ² test against a fair
//! die, and how many rolls that test needs to see a measured bias.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF};
use statrs::function::gamma::ln_gamma;

/// The normal quantile of a two-sided 95 % interval.
const Z95: f64 = 1.959_963_984_540_054;

/// Degrees of freedom of the χ² test of six faces.
const DOF: f64 = 5.0;

/// The test's level and the power asked of it in [`FaceTally::rolls_to_detect`].
pub(crate) const TEST_LEVEL: f64 = 0.05;
pub(crate) const TEST_POWER: f64 = 0.8;

/// The 95 % Wilson score interval of a share of `count` in `n` (`[0, 1]` with `n = 0`):
/// unlike the normal approximation it stays inside `[0, 1]` and is honest for shares near 0.
pub(crate) fn wilson_interval(count: u64, n: u64) -> [f64; 2] {
    if n == 0 {
        return [0.0, 1.0];
    }
    let (n, p) = (n as f64, count as f64 / n as f64);
    let z2 = Z95 * Z95;
    let centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
    let half = Z95 / (1.0 + z2 / n) * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    [(centre - half).max(0.0), (centre + half).min(1.0)]
}

/// Counts of faces 1..6 over a set of settled rolls.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct FaceTally {
    pub counts: [u64; 6],
}

impl FaceTally {
    pub fn add(&mut self, face: u8) {
        if (1..=6).contains(&face) {
            self.counts[face as usize - 1] += 1;
        }
    }

    /// Rolls counted.
    pub fn total(&self) -> u64 {
        self.counts.iter().sum()
    }

    /// Counts of faces 1..6.
    pub fn counts(&self) -> [u64; 6] {
        self.counts
    }

    /// Share of rolls showing `face` (1..6); 0 with no rolls.
    pub fn share(&self, face: u8) -> f64 {
        let n = self.total();
        if n == 0 {
            0.0
        } else {
            self.counts[face as usize - 1] as f64 / n as f64
        }
    }

    /// Pearson's χ² against a fair die: `Σ (c − n/6)² / (n/6)`; `None` with no rolls.
    pub fn chi_square(&self) -> Option<f64> {
        let n = self.total();
        if n == 0 {
            return None;
        }
        let expected = n as f64 / 6.0;
        Some(
            self.counts
                .iter()
                .map(|&c| (c as f64 - expected).powi(2) / expected)
                .sum(),
        )
    }

    /// The probability of a χ² at least this large from a fair die (5 degrees of freedom).
    pub fn p_value(&self) -> Option<f64> {
        let chi2 = self.chi_square()?;
        let dist = ChiSquared::new(5.0).expect("5 degrees of freedom is a valid χ² distribution");
        Some(dist.sf(chi2))
    }
}

impl FaceTally {
    /// The 95 % Wilson interval of each face's share.
    pub fn share_intervals(&self) -> [[f64; 2]; 6] {
        let n = self.total();
        std::array::from_fn(|f| wilson_interval(self.counts[f], n))
    }

    /// Cohen's effect size `w² = Σ (p_f − 1/6)² / (1/6)` of the die these counts measure,
    /// unbiased: the raw shares' `χ²/n` less the `5/n` a fair die shows by chance (the mean
    /// of χ² is `5 + n·w²`). `None` without faces or when no bias stands out of the noise.
    pub(crate) fn effect_size_squared(&self) -> Option<f64> {
        let n = self.total() as f64;
        let w2 = (self.chi_square()? - DOF) / n;
        (w2 > 0.0).then_some(w2)
    }

    /// The number of rolls at which the χ² test at 5 % detects a die as biased as these
    /// counts measure with 80 % power: `λ / w²`, with `λ` the noncentrality at which a
    /// noncentral χ² of 5 degrees of freedom exceeds the test's critical value 80 % of the
    /// time (12.83). `None` when no bias is measured (see [`Self::effect_size_squared`]).
    pub fn rolls_to_detect(&self) -> Option<u64> {
        let w2 = self.effect_size_squared()?;
        Some((detecting_noncentrality() / w2).ceil() as u64)
    }
}

/// The noncentrality `λ` at which the 5 % χ² test (5 dof) has 80 % power, by bisection on
/// the noncentral distribution's tail (computed once).
fn detecting_noncentrality() -> f64 {
    static LAMBDA: std::sync::LazyLock<f64> = std::sync::LazyLock::new(|| {
        let central = ChiSquared::new(DOF).expect("5 degrees of freedom is a valid χ² distribution");
        let critical = central.inverse_cdf(1.0 - TEST_LEVEL);
        let (mut low, mut high) = (0.0, 200.0);
        for _ in 0..100 {
            let mid = 0.5 * (low + high);
            if 1.0 - noncentral_chi_square_cdf(critical, DOF, mid) < TEST_POWER {
                low = mid;
            } else {
                high = mid;
            }
        }
        0.5 * (low + high)
    });
    *LAMBDA
}

/// `P(X ≤ x)` for a noncentral χ² of `k` degrees of freedom and noncentrality `lambda`, as the
/// Poisson mixture `Σ_j e^(−λ/2)·(λ/2)^j / j! · P(χ²_(k+2j) ≤ x)` (statrs has no noncentral
/// χ²), summed until the Poisson weights left are below 10⁻¹⁶.
pub(crate) fn noncentral_chi_square_cdf(x: f64, k: f64, lambda: f64) -> f64 {
    let half = lambda / 2.0;
    let mut total = 0.0;
    let mut weight_left = 1.0;
    for j in 0..10_000u32 {
        let j = f64::from(j);
        let weight = if half == 0.0 {
            if j == 0.0 { 1.0 } else { 0.0 }
        } else {
            (-half + j * half.ln() - ln_gamma(j + 1.0)).exp()
        };
        let dist = ChiSquared::new(k + 2.0 * j).expect("positive degrees of freedom");
        total += weight * dist.cdf(x);
        weight_left -= weight;
        if j > half && weight_left < 1e-16 {
            break;
        }
    }
    total
}

impl FromIterator<u8> for FaceTally {
    fn from_iter<I: IntoIterator<Item = u8>>(iter: I) -> Self {
        let mut t = FaceTally::default();
        for f in iter {
            t.add(f);
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chi_square_and_p_value_by_hand() {
        // Σ(c−100)²/100 over [101,102,94,97,94,112] = (1+4+36+9+36+144)/100 = 2.30.
        let t = FaceTally {
            counts: [101, 102, 94, 97, 94, 112],
        };
        assert!((t.chi_square().unwrap() - 2.30).abs() < 1e-12);
        // 5-dof closed form: erfc(√(x/2)) + √(2/π)·e^(−x/2)·(√x + x^1.5/3) at x = 2.3.
        assert!((t.p_value().unwrap() - 0.8062669).abs() < 1e-6);
        let fair = FaceTally { counts: [10; 6] };
        assert_eq!(fair.chi_square(), Some(0.0));
        assert_eq!(fair.p_value(), Some(1.0));
        assert_eq!(FaceTally::default().p_value(), None);
    }

    #[test]
    fn wilson_interval_by_hand() {
        // 20 of 100 at z = 1.96: centre (0.2 + 0.0192)/1.0384, half 0.0784…: [0.1333, 0.2888].
        let [low, high] = wilson_interval(20, 100);
        assert!(
            (low - 0.13332).abs() < 1e-4 && (high - 0.28883).abs() < 1e-4,
            "{low} {high}"
        );
        // None of 10 still has room above zero; all of them room below one.
        assert_eq!(wilson_interval(0, 10)[0], 0.0);
        assert!(wilson_interval(0, 10)[1] > 0.25);
        assert!(wilson_interval(10, 10)[0] < 0.75);
        assert_eq!(wilson_interval(0, 0), [0.0, 1.0]);
    }

    #[test]
    fn noncentral_tail_and_the_rolls_a_test_needs() {
        // λ = 0 is the central distribution.
        let central = ChiSquared::new(5.0).unwrap();
        assert!((noncentral_chi_square_cdf(7.0, 5.0, 0.0) - central.cdf(7.0)).abs() < 1e-14);
        // The tail grows with λ.
        assert!(noncentral_chi_square_cdf(11.07, 5.0, 20.0) < noncentral_chi_square_cdf(11.07, 5.0, 5.0));
        // Cohen's power tables (5 dof, α = 0.05, power 0.80): w = 0.1 needs 1 283 rolls and
        // w = 0.3 needs 143; λ = 12.83.
        assert!(
            (detecting_noncentrality() - 12.825).abs() < 0.005,
            "{}",
            detecting_noncentrality()
        );
        // Counts whose unbiased w² is exactly 0.01 (w = 0.1): χ² = 5 + n·0.01.
        let n = 60_000u64;
        let t = FaceTally {
            counts: [10_000 + 245, 10_000 - 245, 10_000, 10_000, 10_000, 10_000],
        };
        let w2 = t.effect_size_squared().unwrap();
        let expected = (t.chi_square().unwrap() - 5.0) / n as f64;
        assert_eq!(w2, expected);
        assert_eq!(
            t.rolls_to_detect(),
            Some((detecting_noncentrality() / w2).ceil() as u64)
        );
        // Cohen's w = 0.1 and 0.3 cases by this formula.
        assert_eq!((detecting_noncentrality() / 0.01).ceil(), 1283.0);
        assert_eq!((detecting_noncentrality() / 0.09).ceil(), 143.0);
        // A die as fair as chance allows measures no bias at all.
        assert_eq!(FaceTally { counts: [100; 6] }.rolls_to_detect(), None);
    }

    #[test]
    fn counts_and_shares() {
        let t: FaceTally = [1u8, 1, 6, 3, 0, 7].into_iter().collect();
        assert_eq!(t.counts, [2, 0, 1, 0, 0, 1]);
        assert_eq!(t.total(), 4);
        assert_eq!(t.share(1), 0.5);
    }
}
