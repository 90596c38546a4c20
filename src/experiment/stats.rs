//! Outcome statistics: face counts, shares and the χ² test against a fair die.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// Counts of faces 1..6 over a set of settled rolls.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct FaceTally {
    pub(crate) counts: [u64; 6],
}

impl FaceTally {
    pub(crate) fn add(&mut self, face: u8) {
        if (1..=6).contains(&face) {
            self.counts[face as usize - 1] += 1;
        }
    }

    pub(crate) fn total(&self) -> u64 {
        self.counts.iter().sum()
    }

    /// Share of rolls showing `face` (1..6); 0 with no rolls.
    pub(crate) fn share(&self, face: u8) -> f64 {
        let n = self.total();
        if n == 0 {
            0.0
        } else {
            self.counts[face as usize - 1] as f64 / n as f64
        }
    }

    /// Pearson's χ² against a fair die: `Σ (c − n/6)² / (n/6)`; `None` with no rolls.
    pub(crate) fn chi_square(&self) -> Option<f64> {
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
    pub(crate) fn p_value(&self) -> Option<f64> {
        let chi2 = self.chi_square()?;
        let dist = ChiSquared::new(5.0).expect("5 degrees of freedom is a valid χ² distribution");
        Some(dist.sf(chi2))
    }
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
    fn counts_and_shares() {
        let t: FaceTally = [1u8, 1, 6, 3, 0, 7].into_iter().collect();
        assert_eq!(t.counts, [2, 0, 1, 0, 0, 1]);
        assert_eq!(t.total(), 4);
        assert_eq!(t.share(1), 0.5);
    }
}
