//! Outcome statistics: face counts, shares with their intervals, the χ² test against a fair
//! die, and how many rolls that test needs to see a measured bias.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF};
use statrs::function::gamma::ln_gamma;

/// The normal quantile of a two-sided 95 % interval.
const Z95: f64 = 1.959_963_984_540_054;

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

/// Counts of the numbers a die shows over a set of settled rolls, one per number of the
/// die's list ([`Die::face_numbers`](dicesim_physics::Die::face_numbers)) and in its order:
/// 1 to 6 for the paper's cube, 1 to 20 for a d20, 0 to 9 for a d10.
///
/// Files carry the counts alone (`{"counts": [..]}`, as they always have); counts read back
/// name no die until [`FaceTally::of_die`] checks them against the setup's.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct FaceTally {
    /// The die's numbers, as its setup lists them; empty for counts read from a file.
    #[serde(skip)]
    numbers: &'static [u8],
    pub counts: Vec<u64>,
}

impl FaceTally {
    /// No rolls yet of a die that shows `numbers` ([`Die::face_numbers`](dicesim_physics::Die::face_numbers)).
    pub fn new(numbers: &'static [u8]) -> FaceTally {
        FaceTally {
            numbers,
            counts: vec![0; numbers.len()],
        }
    }

    /// `counts` read from a file, as the counts of a die that shows `numbers`: refused
    /// (with what is wrong) unless there is one count per number.
    pub fn of_die(self, numbers: &'static [u8]) -> Result<FaceTally, String> {
        if self.counts.len() != numbers.len() {
            return Err(format!(
                "{} face counts, but its die shows {} numbers ({})",
                self.counts.len(),
                numbers.len(),
                numbers_words(numbers)
            ));
        }
        Ok(FaceTally { numbers, ..self })
    }

    /// The numbers counted, in the order of [`Self::counts`].
    pub fn numbers(&self) -> &'static [u8] {
        self.numbers
    }

    /// Counts a roll that shows `face`; a number the die does not show is not counted
    /// (a tally's sums then disagree with its settled rolls: [`Tally::check`](crate::tally::Tally::check)).
    pub fn add(&mut self, face: u8) {
        if let Some(i) = self.index(face) {
            self.counts[i] += 1;
        }
    }

    /// Where `face` is in the die's list, if it is a number the die shows.
    fn index(&self, face: u8) -> Option<usize> {
        self.numbers.iter().position(|&n| n == face)
    }

    /// Adds the counts of `other`, of the same die.
    pub fn merge(&mut self, other: &FaceTally) {
        debug_assert_eq!(self.numbers, other.numbers, "tallies of one die");
        for (c, o) in self.counts.iter_mut().zip(&other.counts) {
            *c += o;
        }
    }

    /// Rolls counted.
    pub fn total(&self) -> u64 {
        self.counts.iter().sum()
    }

    /// Degrees of freedom of the χ² test against a fair die: one fewer than its numbers.
    pub fn degrees_of_freedom(&self) -> usize {
        self.counts.len().saturating_sub(1)
    }

    /// Each number with its count, in the die's order.
    pub fn by_number(&self) -> impl Iterator<Item = (u8, u64)> + '_ {
        self.numbers.iter().copied().zip(self.counts.iter().copied())
    }

    /// Share of rolls showing `face`; 0 with no rolls or for a number the die does not show.
    pub fn share(&self, face: u8) -> f64 {
        let n = self.total();
        match self.index(face) {
            Some(i) if n > 0 => self.counts[i] as f64 / n as f64,
            _ => 0.0,
        }
    }

    /// Share of each number's rolls, in the die's order; zeros with no rolls.
    pub fn shares(&self) -> Vec<f64> {
        let n = self.total();
        (self.counts.iter())
            .map(|&c| if n == 0 { 0.0 } else { c as f64 / n as f64 })
            .collect()
    }

    /// Pearson's χ² against a fair die of `k` numbers: `Σ (c − n/k)² / (n/k)`; `None` with
    /// no rolls.
    pub fn chi_square(&self) -> Option<f64> {
        let n = self.total();
        if n == 0 {
            return None;
        }
        let expected = n as f64 / self.counts.len() as f64;
        Some(
            self.counts
                .iter()
                .map(|&c| (c as f64 - expected).powi(2) / expected)
                .sum(),
        )
    }

    /// The probability of a χ² at least this large from a fair die (`k − 1` degrees of
    /// freedom); `None` with no rolls.
    pub fn p_value(&self) -> Option<f64> {
        let chi2 = self.chi_square()?;
        Some(chi_square_of(self.degrees_of_freedom()).sf(chi2))
    }

    /// The 95 % Wilson interval of each number's share, in the die's order.
    pub fn share_intervals(&self) -> Vec<[f64; 2]> {
        let n = self.total();
        self.counts.iter().map(|&c| wilson_interval(c, n)).collect()
    }

    /// Cohen's effect size `w² = Σ (p_f − 1/k)² / (1/k)` of the die these counts measure,
    /// unbiased: the raw shares' `χ²/n` less the `(k − 1)/n` a fair die shows by chance (the
    /// mean of χ² is `k − 1 + n·w²`). `None` without faces or when no bias stands out of the
    /// noise.
    pub(crate) fn effect_size_squared(&self) -> Option<f64> {
        let n = self.total() as f64;
        let w2 = (self.chi_square()? - self.degrees_of_freedom() as f64) / n;
        (w2 > 0.0).then_some(w2)
    }

    /// The number of rolls at which the χ² test at 5 % detects a die as biased as these
    /// counts measure with 80 % power: `λ / w²`, with `λ` the noncentrality at which a
    /// noncentral χ² of `k − 1` degrees of freedom exceeds the test's critical value 80 % of
    /// the time (12.83 for six faces). `None` when no bias is measured (see
    /// [`Self::effect_size_squared`]).
    pub fn rolls_to_detect(&self) -> Option<u64> {
        let w2 = self.effect_size_squared()?;
        Some((detecting_noncentrality(self.degrees_of_freedom()) / w2).ceil() as u64)
    }
}

/// The numbers of a die as words: `1–6`, `0–9` for a run of consecutive numbers, else them
/// all (`0, 10, …, 90` in full).
pub(crate) fn numbers_words(numbers: &[u8]) -> String {
    let consecutive = numbers.windows(2).all(|w| w[1] == w[0].wrapping_add(1));
    match numbers {
        [first, .., last] if consecutive => format!("{first}–{last}"),
        _ => numbers.iter().map(u8::to_string).collect::<Vec<_>>().join(", "),
    }
}

/// The central χ² distribution of `dof` degrees of freedom (at least one).
fn chi_square_of(dof: usize) -> ChiSquared {
    ChiSquared::new(dof.max(1) as f64).expect("a positive number of degrees of freedom")
}

/// The noncentrality `λ` at which the 5 % χ² test of `dof` degrees of freedom has 80 %
/// power, by bisection on the noncentral distribution's tail (computed once per `dof`).
fn detecting_noncentrality(dof: usize) -> f64 {
    static LAMBDAS: std::sync::Mutex<Vec<(usize, f64)>> = std::sync::Mutex::new(Vec::new());
    let mut known = LAMBDAS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(&(_, lambda)) = known.iter().find(|(d, _)| *d == dof) {
        return lambda;
    }
    let k = dof.max(1) as f64;
    let critical = chi_square_of(dof).inverse_cdf(1.0 - TEST_LEVEL);
    let (mut low, mut high) = (0.0, 200.0);
    for _ in 0..100 {
        let mid = 0.5 * (low + high);
        if 1.0 - noncentral_chi_square_cdf(critical, k, mid) < TEST_POWER {
            low = mid;
        } else {
            high = mid;
        }
    }
    let lambda = 0.5 * (low + high);
    known.push((dof, lambda));
    lambda
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

#[cfg(test)]
mod tests {
    use super::*;

    const D6: &[u8] = &[1, 2, 3, 4, 5, 6];
    const D20: &[u8] = &[
        1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
    ];
    /// The d10 as players read it, and the d% (a d10 labelled in tens).
    const D10: &[u8] = &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9];
    const PERCENTILE: &[u8] = &[0, 10, 20, 30, 40, 50, 60, 70, 80, 90];

    /// A tally of a die that shows `numbers` with these counts, in the die's order.
    fn counted(numbers: &'static [u8], counts: &[u64]) -> FaceTally {
        assert_eq!(counts.len(), numbers.len());
        FaceTally {
            numbers,
            counts: counts.to_vec(),
        }
    }

    /// `P(χ²_k ≥ x)` for odd `k` by the closed form
    /// `erfc(√(x/2)) + √(2/π)·e^(−x/2)·Σ_{j=1}^{(k−1)/2} x^(j−½) / (1·3·…·(2j−1))`,
    /// independent of the distribution the code asks statrs for.
    fn tail_odd(x: f64, k: u32) -> f64 {
        let mut sum = 0.0;
        let mut odd_product = 1.0;
        for j in 1..=(k - 1) / 2 {
            odd_product *= f64::from(2 * j - 1);
            sum += x.powf(f64::from(j) - 0.5) / odd_product;
        }
        statrs::function::erf::erfc((x / 2.0).sqrt())
            + (2.0 / std::f64::consts::PI).sqrt() * (-x / 2.0).exp() * sum
    }

    #[test]
    fn chi_square_and_p_value_by_hand() {
        // Σ(c−100)²/100 over [101,102,94,97,94,112] = (1+4+36+9+36+144)/100 = 2.30.
        let t = counted(D6, &[101, 102, 94, 97, 94, 112]);
        assert!((t.chi_square().unwrap() - 2.30).abs() < 1e-12);
        // 5-dof closed form: erfc(√(x/2)) + √(2/π)·e^(−x/2)·(√x + x^1.5/3) at x = 2.3.
        assert!((t.p_value().unwrap() - 0.8062669).abs() < 1e-6);
        assert!((tail_odd(2.3, 5) - 0.8062669).abs() < 1e-6);
        let fair = counted(D6, &[10; 6]);
        assert_eq!(fair.chi_square(), Some(0.0));
        assert_eq!(fair.p_value(), Some(1.0));
        assert_eq!(FaceTally::new(D6).p_value(), None);
        assert_eq!(FaceTally::new(D20).chi_square(), None);
    }

    #[test]
    fn a_d20_is_tested_on_19_degrees_of_freedom() {
        // 200 rolls of a d20 expect 10 a face. Deviations +5 −5 +4 −4 +3 −3 +2 −2 +1 −1 on
        // faces 1..10 and none on 11..20: χ² = 2·(25 + 16 + 9 + 4 + 1)/10 = 11.0, on
        // 20 − 1 = 19 degrees of freedom (not the six-faced 5).
        let mut counts = [10u64; 20];
        for (k, d) in [5i64, -5, 4, -4, 3, -3, 2, -2, 1, -1].into_iter().enumerate() {
            counts[k] = (10 + d) as u64;
        }
        let t = counted(D20, &counts);
        assert_eq!((t.total(), t.degrees_of_freedom()), (200, 19));
        assert!((t.chi_square().unwrap() - 11.0).abs() < 1e-12);
        // The odd-dof closed form (tail_odd) at x = 11, k = 19: erfc(√5.5) + √(2/π)·e^(−5.5)·
        // Σ_{j=1}^{9} 11^(j−½)/(2j−1)!! = 0.92384 (a χ² of 11 is well below its mean of 19:
        // a fair-looking die). On 5 dof the same χ² would give p = 0.051.
        assert!(
            (t.p_value().unwrap() - 0.923_838_4).abs() < 1e-6,
            "{:?}",
            t.p_value()
        );
        assert!((tail_odd(11.0, 19) - 0.923_838_4).abs() < 1e-6);
        assert!((tail_odd(11.0, 5) - t.p_value().unwrap()).abs() > 0.8);
        // No bias measured beyond chance: χ² below its fair mean of 19.
        assert_eq!(t.rolls_to_detect(), None);
        // Shares and intervals, one per number, in the die's order.
        assert_eq!(t.share(1), 15.0 / 200.0);
        assert_eq!(t.share(20), 10.0 / 200.0);
        assert_eq!(t.shares().len(), 20);
        assert_eq!(t.share_intervals()[1], wilson_interval(5, 200));
    }

    #[test]
    fn a_d4_by_hand() {
        // 100 rolls, 25 expected a face: χ² = (25 + 25 + 0 + 0)/25 = 2 on 3 dof;
        // p = erfc(1) + √(2/π)·e^(−1)·√2 = 0.15730 + 0.41511 = 0.57241.
        let t = counted(&[1, 2, 3, 4], &[30, 20, 25, 25]);
        assert_eq!(t.degrees_of_freedom(), 3);
        assert!((t.chi_square().unwrap() - 2.0).abs() < 1e-12);
        assert!((t.p_value().unwrap() - 0.572_406_7).abs() < 1e-6);
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
            (detecting_noncentrality(5) - 12.825).abs() < 0.005,
            "{}",
            detecting_noncentrality(5)
        );
        // One degree of freedom is the two-sided z test: power 0.8 at δ = 1.95996 + 0.84162,
        // λ = δ² = 7.849; Cohen's table gives 10.91 for 3 (a d4) and λ grows with the dof.
        assert!((detecting_noncentrality(1) - 7.849).abs() < 0.005);
        assert!((detecting_noncentrality(3) - 10.91).abs() < 0.01);
        assert!(detecting_noncentrality(19) > detecting_noncentrality(5));
        // Counts whose unbiased w² is exactly 0.01 (w = 0.1): χ² = 5 + n·0.01.
        let n = 60_000u64;
        let t = counted(D6, &[10_000 + 245, 10_000 - 245, 10_000, 10_000, 10_000, 10_000]);
        let w2 = t.effect_size_squared().unwrap();
        let expected = (t.chi_square().unwrap() - 5.0) / n as f64;
        assert_eq!(w2, expected);
        assert_eq!(
            t.rolls_to_detect(),
            Some((detecting_noncentrality(5) / w2).ceil() as u64)
        );
        // Cohen's w = 0.1 and 0.3 cases by this formula.
        assert_eq!((detecting_noncentrality(5) / 0.01).ceil(), 1283.0);
        assert_eq!((detecting_noncentrality(5) / 0.09).ceil(), 143.0);
        // A die as fair as chance allows measures no bias at all.
        assert_eq!(counted(D6, &[100; 6]).rolls_to_detect(), None);
        // A d20's bias is measured beyond its 19 dof of chance: 2 000 rolls with face 20 at
        // 200 and face 1 at 0, the rest at 100: χ² = (100² + 100²)/100 = 200, w² =
        // (200 − 19)/2000 = 0.0905.
        let mut counts = [100u64; 20];
        (counts[0], counts[19]) = (0, 200);
        let t = counted(D20, &counts);
        assert!((t.effect_size_squared().unwrap() - 0.0905).abs() < 1e-12);
        assert_eq!(
            t.rolls_to_detect(),
            Some((detecting_noncentrality(19) / 0.0905).ceil() as u64)
        );
    }

    #[test]
    fn counts_follow_the_dies_numbers() {
        let mut t = FaceTally::new(D6);
        [1u8, 1, 6, 3, 0, 7].into_iter().for_each(|f| t.add(f));
        assert_eq!(t.counts, [2, 0, 1, 0, 0, 1]);
        assert_eq!(t.total(), 4);
        assert_eq!(t.share(1), 0.5);
        // A d10 reads 0 to 9: 0 is a face, 10 is not.
        let mut d10 = FaceTally::new(D10);
        [0u8, 0, 9, 10, 5].into_iter().for_each(|f| d10.add(f));
        assert_eq!(d10.counts, [2, 0, 0, 0, 0, 1, 0, 0, 0, 1]);
        assert_eq!((d10.share(0), d10.share(10)), (0.5, 0.0));
        // The d% reads tens: 30 is its fourth number, 3 none of them.
        let mut tens = FaceTally::new(PERCENTILE);
        [30u8, 90, 3, 0].into_iter().for_each(|f| tens.add(f));
        assert_eq!(tens.counts, [1, 0, 0, 1, 0, 0, 0, 0, 0, 1]);
        assert_eq!(tens.by_number().nth(3), Some((30, 1)));
        assert_eq!(tens.degrees_of_freedom(), 9);
        // Tallies of one die merge count by count.
        let mut both = d10.clone();
        both.merge(&d10);
        assert_eq!(both.counts, [4, 0, 0, 0, 0, 2, 0, 0, 0, 2]);
    }

    #[test]
    fn counts_read_back_must_be_one_per_number_of_the_die() {
        // As files carry them: the counts alone.
        let mut d20 = FaceTally::new(D20);
        d20.add(20);
        let json = serde_json::to_string(&d20).unwrap();
        assert_eq!(json, format!("{{\"counts\":[{}1]}}", "0,".repeat(19)));
        let read: FaceTally = serde_json::from_str(&json).unwrap();
        assert_eq!(read.clone().of_die(D20), Ok(d20));
        assert_eq!(
            read.clone().of_die(D6).unwrap_err(),
            "20 face counts, but its die shows 6 numbers (1–6)"
        );
        let six: FaceTally = serde_json::from_str("{\"counts\":[1,2,3,4,5,6]}").unwrap();
        assert_eq!(
            six.of_die(PERCENTILE).unwrap_err(),
            "6 face counts, but its die shows 10 numbers (0, 10, 20, 30, 40, 50, 60, 70, 80, 90)"
        );
        assert_eq!(numbers_words(D10), "0–9");
    }
}
