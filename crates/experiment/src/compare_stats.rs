//! The statistics of holding simulated throws against counted ones: the χ² test of a
//! die's counts against known probabilities, the two-sample (contingency) χ² test of the
//! data's counts against the simulation's — so the simulation's own finite size is
//! accounted for — with categories pooled until every expected count is at least 5, its
//! residuals and power, the deviance profile of a fitted parameter, and the comparison of
//! two shares (Budden's cuboids).

use crate::stats::{TEST_LEVEL, TEST_POWER, noncentral_chi_square_cdf, wilson_interval};
use serde::Serialize;
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::ops::Range;

/// The smallest expected count a category of a χ² test keeps on its own (the usual rule:
/// below it the χ² approximation of the statistic's distribution fails).
pub(crate) const MIN_EXPECTED: f64 = 5.0;

/// The rise of the deviance above its minimum that bounds a 95 % profile interval: the χ²
/// of one degree of freedom's 95 % quantile, 3.84.
pub fn deviance_rise_95() -> f64 {
    ChiSquared::new(1.0)
        .expect("one degree of freedom is a valid χ² distribution")
        .inverse_cdf(0.95)
}

/// Groups of neighbouring categories whose `weights` (expected counts) reach `min`: from
/// the first category on, each group closes once its weight reaches `min`; a last group
/// short of it joins the one before. Categories are ordered (a count of dice, a face), so
/// a sparse tail pools into its neighbour — Weldon's 10, 11 and 12 into "10 or more".
pub(crate) fn pool(weights: &[f64], min: f64) -> Vec<Range<usize>> {
    let mut groups: Vec<Range<usize>> = Vec::new();
    let (mut start, mut sum) = (0, 0.0);
    for (i, &w) in weights.iter().enumerate() {
        sum += w;
        if sum >= min {
            groups.push(start..i + 1);
            (start, sum) = (i + 1, 0.0);
        }
    }
    if start < weights.len() {
        match groups.last_mut() {
            Some(last) => last.end = weights.len(),
            None => groups.push(0..weights.len()),
        }
    }
    groups
}

/// `counts` summed over each group.
pub(crate) fn pooled(counts: &[u64], groups: &[Range<usize>]) -> Vec<u64> {
    groups.iter().map(|g| counts[g.clone()].iter().sum()).collect()
}

/// The upper tail of a χ² of `dof` degrees of freedom at `x` (1 with no degrees of freedom).
fn chi_square_tail(x: f64, dof: usize) -> f64 {
    if dof == 0 {
        return 1.0;
    }
    ChiSquared::new(dof as f64)
        .expect("positive degrees of freedom")
        .sf(x)
}

/// A χ² test of counts against known probabilities.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GoodnessOfFit {
    /// The categories pooled into each term (indices into the categories).
    pub groups: Vec<Range<usize>>,
    pub chi_square: f64,
    pub dof: usize,
    pub p_value: f64,
}

/// Pearson's χ² of `observed` against `probabilities` (one per category, summing to 1),
/// categories with expected counts below 5 pooled.
pub(crate) fn goodness_of_fit(observed: &[u64], probabilities: &[f64]) -> GoodnessOfFit {
    let n = observed.iter().sum::<u64>() as f64;
    let expected: Vec<f64> = probabilities.iter().map(|p| n * p).collect();
    let groups = pool(&expected, MIN_EXPECTED);
    let chi_square = groups
        .iter()
        .map(|g| {
            let o = observed[g.clone()].iter().sum::<u64>() as f64;
            let e: f64 = expected[g.clone()].iter().sum();
            (o - e).powi(2) / e
        })
        .sum();
    let dof = groups.len().saturating_sub(1);
    GoodnessOfFit {
        p_value: chi_square_tail(chi_square, dof),
        groups,
        chi_square,
        dof,
    }
}

/// The two-sample χ² test of a real die's counts against a simulation's, over the same
/// categories: a 2 × k contingency table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TwoSample {
    /// The categories pooled into each column, so that every expected count is at least 5.
    pub groups: Vec<Range<usize>>,
    /// The data's and the simulation's counts per group.
    pub data: Vec<u64>,
    pub simulated: Vec<u64>,
    pub chi_square: f64,
    pub dof: usize,
    pub p_value: f64,
    /// The adjusted (standardised) residual of the data's count in each group: about
    /// normal with unit variance where the model is right, so beyond ±2 is a real excess.
    pub residuals: Vec<f64>,
    /// The noncentrality the table measures beyond chance, `max(χ² − dof, 0)` (the mean
    /// of χ² is `dof + λ`).
    pub noncentrality: f64,
    /// The chance a test of this size detects a difference as large as the one measured
    /// (at 5 %): the power of this comparison.
    pub power: f64,
    /// How many real throws a test against the model (its probabilities taken as exact)
    /// needs to tell the two apart at 80 % power and 5 %, for the difference measured;
    /// `None` when no difference stands out of the noise.
    pub throws_to_detect: Option<u64>,
}

/// The two-sample test of `data` against `simulated` (counts per category, same length);
/// `None` when either has no throws or everything pools into one group.
pub(crate) fn two_sample(data: &[u64], simulated: &[u64]) -> Option<TwoSample> {
    let (n, m) = (data.iter().sum::<u64>(), simulated.iter().sum::<u64>());
    if n == 0 || m == 0 {
        return None;
    }
    let total = (n + m) as f64;
    // The smaller row's expected count in each category decides its pooling.
    let smallest = n.min(m) as f64;
    let weights: Vec<f64> = data
        .iter()
        .zip(simulated)
        .map(|(a, b)| smallest * (a + b) as f64 / total)
        .collect();
    let groups = pool(&weights, MIN_EXPECTED);
    if groups.len() < 2 {
        return None;
    }
    let (d, s) = (pooled(data, &groups), pooled(simulated, &groups));
    let (n, m) = (n as f64, m as f64);
    let mut chi_square = 0.0;
    let mut residuals = Vec::with_capacity(groups.len());
    for (&a, &b) in d.iter().zip(&s) {
        let column = (a + b) as f64;
        let (ea, eb) = (n * column / total, m * column / total);
        chi_square += (a as f64 - ea).powi(2) / ea + (b as f64 - eb).powi(2) / eb;
        let variance = ea * (1.0 - n / total) * (1.0 - column / total);
        residuals.push((a as f64 - ea) / variance.sqrt());
    }
    let dof = groups.len() - 1;
    let noncentrality = (chi_square - dof as f64).max(0.0);
    let throws_to_detect = (noncentrality > 0.0).then(|| {
        // λ = w²·nm/(n + m) for a table of n and m throws; a test against exact model
        // probabilities has λ = w²·n.
        let effect = noncentrality / (n * m / (n + m));
        (detecting_noncentrality(dof) / effect).ceil() as u64
    });
    Some(TwoSample {
        groups,
        data: d,
        simulated: s,
        chi_square,
        dof,
        p_value: chi_square_tail(chi_square, dof),
        residuals,
        noncentrality,
        power: power(noncentrality, dof),
        throws_to_detect,
    })
}

/// The noncentrality of the two-sample test of `n` throws from `real` against `m` from
/// `model` (exact probabilities per group): `nm/(n + m) · Σ (q − p)² / p̄`, with `p̄` the
/// two samples' pooled probability.
pub fn noncentrality(real: &[f64], model: &[f64], n: f64, m: f64) -> f64 {
    let scale = n * m / (n + m);
    scale
        * real
            .iter()
            .zip(model)
            .map(|(q, p)| {
                let mean = (n * q + m * p) / (n + m);
                if mean > 0.0 { (q - p).powi(2) / mean } else { 0.0 }
            })
            .sum::<f64>()
}

/// The power of the 5 % χ² test of `dof` degrees of freedom against a noncentrality λ:
/// the noncentral χ²'s tail beyond the central one's 95 % quantile.
pub(crate) fn power(lambda: f64, dof: usize) -> f64 {
    if dof == 0 {
        return 0.0;
    }
    let critical = ChiSquared::new(dof as f64)
        .expect("positive degrees of freedom")
        .inverse_cdf(1.0 - TEST_LEVEL);
    1.0 - noncentral_chi_square_cdf(critical, dof as f64, lambda)
}

/// The noncentrality at which the 5 % test of `dof` degrees of freedom has 80 % power, by
/// bisection of [`power`].
pub(crate) fn detecting_noncentrality(dof: usize) -> f64 {
    let (mut low, mut high) = (0.0, 1000.0);
    for _ in 0..80 {
        let mid = 0.5 * (low + high);
        if power(mid, dof) < TEST_POWER {
            low = mid;
        } else {
            high = mid;
        }
    }
    0.5 * (low + high)
}

/// The deviance (G², the likelihood-ratio statistic) of the 2 × k table of `data` against
/// `simulated` over fixed `groups`: `2 Σ O ln(O / E)`. With the groups fixed it compares
/// candidates of a fit on one footing; `−2 ln` of the profile likelihood up to a constant.
pub(crate) fn deviance(data: &[u64], simulated: &[u64], groups: &[Range<usize>]) -> f64 {
    let (d, s) = (pooled(data, groups), pooled(simulated, groups));
    let (n, m) = (d.iter().sum::<u64>() as f64, s.iter().sum::<u64>() as f64);
    let total = n + m;
    let term = |o: u64, e: f64| {
        if o == 0 {
            0.0
        } else {
            o as f64 * (o as f64 / e).ln()
        }
    };
    2.0 * d
        .iter()
        .zip(&s)
        .map(|(&a, &b)| {
            let column = (a + b) as f64;
            term(a, n * column / total) + term(b, m * column / total)
        })
        .sum::<f64>()
}

/// The fixed groups a fit compares its candidates over: the data's own categories pooled
/// until each holds 5 throws (the simulation's counts change from candidate to candidate,
/// the data's do not).
pub(crate) fn fit_groups(data: &[u64]) -> Vec<Range<usize>> {
    let weights: Vec<f64> = data.iter().map(|&c| c as f64).collect();
    pool(&weights, MIN_EXPECTED)
}

/// How a fit's best value and interval were read from the candidates' deviances.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FitMethod {
    /// From a parabola fitted to every candidate's deviance by least squares. Each
    /// deviance carries the simulation's own noise (a roll is chaotic, so even with the same
    /// throws a small change of the value changes many outcomes); the parabola reads the
    /// trend instead of the noise, as one reads a profile likelihood from noisy points.
    Parabola,
    /// From the candidates themselves, interpolated between them: the deviances did not
    /// follow an upward parabola.
    Candidates,
}

/// The best value of a fit and its 95 % interval (docs/real-dice.md, "The fit's interval"):
/// the smallest interval that holds every candidate whose deviance is within 3.84 of the
/// lowest candidate's, each end reaching out to where the deviance crosses that line toward
/// the next candidate beyond it (or to the range's end), and, when the deviances follow an
/// upward parabola, where the parabola stays within 3.84 of its own minimum. Candidates
/// inside it whose own deviance is beyond the line are listed (`beyond`): then the
/// candidates within 3.84 are not one connected set, and every reading says so.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitInterval {
    pub method: FitMethod,
    /// The best value and its deviance (the parabola's, or the best candidate's).
    pub best: f64,
    pub best_deviance: f64,
    /// The candidate nearest to the best value, whose throws are shown.
    pub best_index: usize,
    /// The lowest deviance of any candidate; every candidate within 3.84 of it is inside.
    pub lowest_deviance: f64,
    /// The interval's ends.
    pub low: f64,
    pub high: f64,
    /// Whether the interval reached the range's own end on that side (it then reaches at
    /// least that far: the data allow values beyond the range).
    pub low_open: bool,
    pub high_open: bool,
    /// The candidates between the interval's ends whose deviance is more than 3.84 above
    /// the lowest, in increasing order: empty when the candidates within 3.84 are one
    /// connected run.
    pub beyond: Vec<f64>,
    /// The parabola `a·x² + b·x + c` (`None` for [`FitMethod::Candidates`]).
    pub parabola: Option<[f64; 3]>,
}

impl FitInterval {
    /// Whether the candidates within 3.84 of the lowest deviance form one connected run.
    pub fn connected(&self) -> bool {
        self.beyond.is_empty()
    }

    /// The deviance below which a candidate is inside: the lowest candidate's + 3.84.
    pub fn candidate_limit(&self) -> f64 {
        self.lowest_deviance + deviance_rise_95()
    }
}

/// The least-squares parabola `[a, b, c]` through the points, or `None` for fewer than three
/// distinct values. Solved in centred and scaled coordinates, then converted back.
pub(crate) fn least_squares_parabola(values: &[f64], deviances: &[f64]) -> Option<[f64; 3]> {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let scale = values.iter().map(|v| (v - mean).abs()).fold(0.0, f64::max);
    if values.len() < 3 || scale == 0.0 {
        return None;
    }
    // Normal equations for u = (x − mean)/scale: Σ [u⁴ u³ u²; u³ u² u; u² u 1]·[A B C] = Σ [u²y uy y].
    let mut m = [[0.0f64; 4]; 3];
    for (&x, &y) in values.iter().zip(deviances) {
        let u = (x - mean) / scale;
        let powers = [u * u, u, 1.0];
        for r in 0..3 {
            for c in 0..3 {
                m[r][c] += powers[r] * powers[c];
            }
            m[r][3] += powers[r] * y;
        }
    }
    // Gaussian elimination with partial pivoting.
    for col in 0..3 {
        let pivot = (col..3).max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))?;
        m.swap(col, pivot);
        if m[col][col].abs() < 1e-12 {
            return None;
        }
        let pivot_row = m[col];
        for (r, row) in m.iter_mut().enumerate() {
            if r != col {
                let f = row[col] / pivot_row[col];
                for (x, p) in row.iter_mut().zip(pivot_row).skip(col) {
                    *x -= f * p;
                }
            }
        }
    }
    let [a, b, c] = [0, 1, 2].map(|r| m[r][3] / m[r][r]);
    // A·u² + B·u + C with u = (x − mean)/scale, expanded in x.
    let (a2, b2) = (a / (scale * scale), b / scale);
    Some([a2, b2 - 2.0 * a2 * mean, a2 * mean * mean - b2 * mean + c])
}

/// The best of `values` (increasing) by `deviances` and its 95 % interval ([`FitInterval`]):
/// the best from the least-squares parabola through all of them when it opens upward, else
/// the best candidate; the interval holds the candidates' own reading and the parabola's.
/// `None` without candidates.
pub(crate) fn profile_interval(values: &[f64], deviances: &[f64]) -> Option<FitInterval> {
    let (lo, hi) = (*values.first()?, *values.last()?);
    let from_candidates = candidate_interval(values, deviances)?;
    let nearest = |x: f64| {
        (0..values.len())
            .min_by(|&a, &b| (values[a] - x).abs().total_cmp(&(values[b] - x).abs()))
            .unwrap_or(0)
    };
    if let Some([a, b, c]) = least_squares_parabola(values, deviances)
        && a > 0.0
    {
        let best = (-b / (2.0 * a)).clamp(lo, hi);
        let best_deviance = (a * best + b) * best + c;
        // a·x² + b·x + c = best_deviance + 3.84, on each side of the vertex.
        let vertex = -b / (2.0 * a);
        let reach = ((best_deviance + deviance_rise_95() - c) / a + vertex * vertex).sqrt();
        let (low, high) = (vertex - reach, vertex + reach);
        let (low, high) = (low.min(from_candidates.low), high.max(from_candidates.high));
        let (shown_low, shown_high) = (low.max(lo), high.min(hi));
        return Some(FitInterval {
            method: FitMethod::Parabola,
            best,
            best_deviance,
            best_index: nearest(best),
            low: shown_low,
            high: shown_high,
            low_open: low <= lo,
            high_open: high >= hi,
            beyond: beyond(
                values,
                deviances,
                from_candidates.lowest_deviance,
                shown_low,
                shown_high,
            ),
            parabola: Some([a, b, c]),
            ..from_candidates
        });
    }
    Some(from_candidates)
}

/// The candidates in `[low, high]` (its ends included) whose deviance is more than 3.84
/// above `lowest`.
fn beyond(values: &[f64], deviances: &[f64], lowest: f64, low: f64, high: f64) -> Vec<f64> {
    let limit = lowest + deviance_rise_95();
    values
        .iter()
        .zip(deviances)
        .filter(|&(&v, &d)| v >= low && v <= high && d > limit)
        .map(|(&v, _)| v)
        .collect()
}

/// The best candidate and the interval read from the candidates themselves: from the first
/// to the last candidate within 3.84 of the lowest deviance, each end interpolated linearly
/// to where the deviance crosses that line toward the next candidate beyond it, or open at
/// the range's end.
fn candidate_interval(values: &[f64], deviances: &[f64]) -> Option<FitInterval> {
    let (best_index, &best_deviance) = deviances.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1))?;
    let limit = best_deviance + deviance_rise_95();
    let inside: Vec<usize> = (0..values.len()).filter(|&i| deviances[i] <= limit).collect();
    let (&first, &last) = (inside.first()?, inside.last()?);
    // From an inside candidate `a` toward the one beyond it, `b`, to where the line is crossed.
    let crossing = |a: usize, b: usize| {
        let t = (limit - deviances[a]) / (deviances[b] - deviances[a]);
        values[a] + t * (values[b] - values[a])
    };
    let (low, low_open) = match first.checked_sub(1) {
        Some(b) => (crossing(first, b), false),
        None => (values[0], true),
    };
    let (high, high_open) = match last + 1 < values.len() {
        true => (crossing(last, last + 1), false),
        false => (values[last], true),
    };
    Some(FitInterval {
        method: FitMethod::Candidates,
        best: values[best_index],
        best_deviance,
        best_index,
        lowest_deviance: best_deviance,
        low,
        high,
        low_open,
        high_open,
        beyond: beyond(values, deviances, best_deviance, low, high),
        parabola: None,
    })
}

/// A share measured in the data beside the simulation's (Budden's square faces, one ratio).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SharePair {
    pub data_share: f64,
    pub data_interval: [f64; 2],
    pub simulated_share: f64,
    pub simulated_interval: [f64; 2],
    /// The standard deviation of the difference of the two shares where they are equal
    /// (their pooled share's), and the difference in units of it.
    pub sigma: f64,
    pub z: f64,
    /// The counts behind the shares: the data's `data_count` of `data_n`, the simulation's
    /// `simulated_count` of `simulated_n` (pooling neighbours adds them).
    pub data_count: u64,
    pub data_n: u64,
    pub simulated_count: u64,
    pub simulated_n: u64,
}

impl SharePair {
    /// `data_count` of `data_n` beside `simulated_count` of `simulated_n`.
    pub fn new(data_count: u64, data_n: u64, simulated_count: u64, simulated_n: u64) -> SharePair {
        let share = |k: u64, n: u64| if n == 0 { 0.0 } else { k as f64 / n as f64 };
        let (p1, p2) = (share(data_count, data_n), share(simulated_count, simulated_n));
        let both = share(data_count + simulated_count, data_n + simulated_n);
        let sigma = (both * (1.0 - both) * (1.0 / data_n as f64 + 1.0 / simulated_n as f64)).sqrt();
        SharePair {
            data_share: p1,
            data_interval: wilson_interval(data_count, data_n),
            simulated_share: p2,
            simulated_interval: wilson_interval(simulated_count, simulated_n),
            sigma,
            z: if sigma > 0.0 { (p1 - p2) / sigma } else { 0.0 },
            data_count,
            data_n,
            simulated_count,
            simulated_n,
        }
    }

    /// The pair of two pooled: the counts added.
    fn pooled(&self, other: &SharePair) -> SharePair {
        SharePair::new(
            self.data_count + other.data_count,
            self.data_n + other.data_n,
            self.simulated_count + other.simulated_count,
            self.simulated_n + other.simulated_n,
        )
    }

    /// The smaller of the data's expected counts (of the share and of the rest) were the
    /// two shares equal: `n·p̂` and `n·(1 − p̂)` with `p̂` the pooled share.
    fn least_expected(&self) -> f64 {
        let both =
            (self.data_count + self.simulated_count) as f64 / (self.data_n + self.simulated_n).max(1) as f64;
        self.data_n as f64 * both.min(1.0 - both)
    }

    /// Whether the simulation's share lies within 2σ of the data's.
    pub fn within_two_sigma(&self) -> bool {
        self.z.abs() <= 2.0
    }
}

/// Predictions of shares held against the data together: how many lie within 2σ (each
/// share on its own), and `Σ z²` over the groups [`pooled_groups`] forms, with its p (a χ²
/// of one degree of freedom per group).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SharesSummary {
    pub shares: usize,
    pub within_two_sigma: usize,
    pub chi_square: f64,
    /// Degrees of freedom: the groups, each share alone or pooled with neighbours.
    pub dof: usize,
    pub p_value: f64,
    /// The shares pooled for the χ², by their labels (Budden's ratios); only groups of two
    /// or more.
    pub pooled: Vec<Vec<f64>>,
}

/// Neighbouring shares (in the order given, e.g. by ratio) pooled until every group's
/// [`SharePair::least_expected`] is at least [`MIN_EXPECTED`] (the rule the cubic dice's faces are pooled by): the first group short of it
/// joins its neighbour — the only one at an end, else the one with the smaller expected
/// count, the next on a tie — and the rule runs again. One group is kept whatever it holds.
pub fn pooled_groups(pairs: &[SharePair]) -> Vec<Range<usize>> {
    let mut groups: Vec<Range<usize>> = (0..pairs.len()).map(|i| i..i + 1).collect();
    let pool = |g: &Range<usize>| pooled_pair(&pairs[g.clone()]);
    while groups.len() > 1 {
        let Some(i) = groups
            .iter()
            .position(|g| pool(g).least_expected() < MIN_EXPECTED)
        else {
            break;
        };
        let before_is_sparser =
            || pool(&groups[i - 1]).least_expected() < pool(&groups[i + 1]).least_expected();
        let other = if i > 0 && (i + 1 == groups.len() || before_is_sparser()) {
            i - 1
        } else {
            i + 1
        };
        let (a, b) = (i.min(other), i.max(other));
        groups[a] = groups[a].start..groups[b].end;
        groups.remove(b);
    }
    groups
}

/// The pair of a group of neighbours pooled: their counts added.
fn pooled_pair(group: &[SharePair]) -> SharePair {
    group[1..].iter().fold(group[0], |sum, p| sum.pooled(p))
}

/// The summary of `pairs`, each named by its `labels` entry (the pooled groups name them).
pub fn shares_summary(pairs: &[SharePair], labels: &[f64]) -> SharesSummary {
    let groups = pooled_groups(pairs);
    let chi_square = groups
        .iter()
        .map(|g| {
            let z = pooled_pair(&pairs[g.clone()]).z;
            z * z
        })
        .sum();
    SharesSummary {
        shares: pairs.len(),
        within_two_sigma: pairs.iter().filter(|p| p.within_two_sigma()).count(),
        chi_square,
        dof: groups.len(),
        p_value: chi_square_tail(chi_square, groups.len()),
        pooled: groups
            .into_iter()
            .filter(|g| g.len() > 1)
            .map(|g| labels[g].to_vec())
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real_data::{Dataset, budden};
    use rand::rngs::ChaCha8Rng;
    use rand::{RngExt, SeedableRng};

    #[test]
    fn weldon_reproduces_its_summaries() {
        let data = Dataset::Weldon.data();
        let fives_and_sixes: u64 = data.counts.iter().enumerate().map(|(k, c)| k as u64 * c).sum();
        assert_eq!((fives_and_sixes, 12 * data.total()), (106_602, 315_672));
        let share = fives_and_sixes as f64 / (12 * data.total()) as f64;
        assert_eq!((share * 1e5).round() / 1e5, 0.33770);
        let fit = goodness_of_fit(&data.counts, &Dataset::Weldon.fair_probabilities());
        // 10, 11 and 12 pooled: the expected 13.07, 1.19 and 0.05 of the last three.
        assert_eq!(fit.groups.len(), 11);
        assert_eq!(fit.groups[10], 10..13);
        assert_eq!(fit.dof, 10);
        // scipy: 35.494298591457…, p = 1.0279e-4.
        assert!(
            (fit.chi_square - 35.494_298_59).abs() < 1e-6,
            "{}",
            fit.chi_square
        );
        assert_eq!((fit.chi_square * 100.0).round() / 100.0, 35.49);
        assert!((fit.p_value - 1.027_88e-4).abs() < 1e-8, "{}", fit.p_value);
    }

    #[test]
    fn wolf_reproduces_its_summaries() {
        // Σ(c − 20000/6)²/(20000/6) over the faces, by exact rational arithmetic:
        // white 270.9568, red 94.189 (scipy agrees).
        for (d, expected) in [(Dataset::WolfWhite, 270.9568), (Dataset::WolfRed, 94.189)] {
            let data = d.data();
            let fit = goodness_of_fit(&data.counts, &d.fair_probabilities());
            assert_eq!(fit.dof, 5);
            assert!(
                (fit.chi_square - expected).abs() < 1e-9,
                "{d:?} {}",
                fit.chi_square
            );
            assert!(fit.p_value < 1e-17);
        }
    }

    #[test]
    fn pooling_closes_groups_at_five() {
        assert_eq!(pool(&[10.0, 3.0, 3.0, 9.0, 1.0], 5.0), [0..1, 1..3, 3..5]);
        let one = pool(&[1.0, 1.0], 5.0);
        assert_eq!((one.len(), one[0].clone()), (1, 0..2));
        assert_eq!(pool(&[6.0, 6.0, 0.0, 0.0], 5.0), [0..1, 1..4]);
        assert_eq!(pooled(&[1, 2, 3, 4, 5], &[0..2, 2..5]), [3, 12]);
    }

    #[test]
    fn two_sample_matches_a_table_by_hand() {
        // Rows [10, 20, 30, 40] and [15, 25, 20, 40]: expected [12.5, 22.5, 25, 40] in
        // both, χ² = 2·(6.25/12.5 + 6.25/22.5 + 25/25 + 0) = 3.5556 on 3 dof, p = 0.31363.
        let t = two_sample(&[10, 20, 30, 40], &[15, 25, 20, 40]).unwrap();
        assert!((t.chi_square - 32.0 / 9.0).abs() < 1e-12, "{}", t.chi_square);
        assert_eq!(t.dof, 3);
        assert!((t.p_value - 0.313_627_91).abs() < 1e-7, "{}", t.p_value);
        // Adjusted residual of the first cell: −2.5 / √(12.5 · ½ · (1 − 25/200)).
        assert!((t.residuals[0] + 2.5 / (12.5f64 * 0.5 * 0.875).sqrt()).abs() < 1e-12);
        assert!((t.noncentrality - (32.0 / 9.0 - 3.0)).abs() < 1e-12);
        assert!(two_sample(&[0, 0], &[1, 2]).is_none());
        // The sparse tail pools: 1 + 2 of the smaller row's expected counts is under 5.
        let t = two_sample(&[50, 50, 1, 1], &[50, 50, 2, 1]).unwrap();
        assert_eq!(t.groups, [0..1, 1..4]);
    }

    #[test]
    fn the_detecting_noncentrality_matches_tables() {
        // Cohen (5 dof): 12.83; scipy's ncx2 (10 dof): 16.2411.
        assert!((detecting_noncentrality(5) - 12.825).abs() < 0.005);
        assert!((detecting_noncentrality(10) - 16.2411).abs() < 0.001);
        assert!((power(0.0, 10) - 0.05).abs() < 1e-12);
        // scipy: ncx2.sf(chi2.ppf(.95, 10), 10, 13.4873) = 0.70334.
        assert!((power(13.487_275, 10) - 0.703_339).abs() < 1e-5);
    }

    #[test]
    fn the_profile_interval_is_read_from_the_parabola_or_the_candidates() {
        let rise = deviance_rise_95();
        assert!((rise - 3.841_458_8).abs() < 1e-6);
        // Deviances on an exact parabola 2 + 4(x − 1.25)²: the vertex and x* ± √(3.84/4).
        let values: Vec<f64> = (0..21).map(|i| f64::from(i) * 0.2).collect();
        let deviances: Vec<f64> = values
            .iter()
            .map(|x| 2.0 + 4.0 * (x - 1.25) * (x - 1.25))
            .collect();
        let f = profile_interval(&values, &deviances).unwrap();
        assert_eq!(f.method, FitMethod::Parabola);
        assert!(
            (f.best - 1.25).abs() < 1e-9 && (f.best_deviance - 2.0).abs() < 1e-9,
            "{f:?}"
        );
        let half = (rise / 4.0).sqrt();
        assert!((f.low - (1.25 - half)).abs() < 1e-9 && (f.high - (1.25 + half)).abs() < 1e-9);
        assert_eq!(f.best_index, 6); // 1.2 is the nearest candidate
        // Four points on 4(x − 1.5)² = 4x² − 12x + 9 (numpy's polyfit agrees).
        let [a, b, _] = least_squares_parabola(&[0.0, 1.0, 2.0, 3.0], &[9.0, 1.0, 1.0, 9.0]).unwrap();
        assert!((a - 4.0).abs() < 1e-9 && (-b / (2.0 * a) - 1.5).abs() < 1e-9);
        // A vertex outside the range: the best is the range's end, the interval open there.
        let rising: Vec<f64> = values.iter().map(|x| 1.0 + (x + 1.0) * (x + 1.0)).collect();
        let f = profile_interval(&values, &rising).unwrap();
        assert_eq!((f.best, f.low, f.low_open, f.high_open), (0.0, 0.0, true, false));
        assert!((f.best_deviance - 2.0).abs() < 1e-9);
        assert!((f.high - (-1.0 + (1.0 + rise).sqrt())).abs() < 1e-9, "{f:?}");
        // Deviances that do not open upward: read from the candidates.
        let values = [0.0, 1.0, 2.0, 3.0, 4.0];
        let deviances = [20.0, 4.0, 1.0, 1.0 + rise / 2.0, 1.0 + 2.0 * rise];
        let f = profile_interval(&values, &[-5.0, -1.0, -1.0, -1.0, -5.0]).unwrap();
        assert_eq!((f.method, f.parabola), (FitMethod::Candidates, None));
        let flat = profile_interval(&values, &[1.0; 5]).unwrap();
        assert_eq!(flat.method, FitMethod::Candidates);
        assert_eq!(
            (flat.low, flat.high, flat.low_open, flat.high_open),
            (0.0, 4.0, true, true)
        );
        // The candidates' own reading, interpolated where the deviance crosses: left from
        // 1.0 (4) to 0.0 (20), limit 4.84: t = 0.84/16; right a third of the way from 3 to 4.
        let f = candidate_interval(&values, &deviances).unwrap();
        assert_eq!((f.best, f.best_index, f.best_deviance), (2.0, 2, 1.0));
        assert!((f.low - (1.0 - (1.0 + rise - 4.0) / 16.0)).abs() < 1e-12);
        assert!((f.high - (3.0 + 1.0 / 3.0)).abs() < 1e-12);
        assert!(!f.low_open && !f.high_open);
        // The deviance of identical rows is zero; of different ones positive.
        let g = fit_groups(&[10, 10, 1]);
        assert_eq!(g, [0..1, 1..3]);
        assert_eq!(deviance(&[10, 10, 1], &[20, 20, 2], &g), 0.0);
        // 2·Σ O ln(O/E) for [[10, 11], [20, 10]] by hand: E = [[12, 9], [18, 12]]… no:
        // columns 30 and 21 of 51, rows 21 and 30.
        let e = |r: f64, c: f64| r * c / 51.0;
        let by_hand = 2.0
            * (10.0 * (10.0 / e(21.0, 30.0)).ln()
                + 11.0 * (11.0 / e(21.0, 21.0)).ln()
                + 20.0 * (20.0 / e(30.0, 30.0)).ln()
                + 10.0 * (10.0 / e(30.0, 21.0)).ln());
        assert!((deviance(&[10, 11], &[20, 10], &[0..1, 1..2]) - by_hand).abs() < 1e-12);
    }

    #[test]
    fn the_interval_holds_every_candidate_within_the_line_and_says_when_they_are_apart() {
        let rise = deviance_rise_95();
        // Issue 49: noisy deviances around a valley; the parabola's own interval is narrow,
        // but candidates far from it are within 3.84 of the lowest (0.5 at 4): 1 at 2, 2 at
        // 5, 3 at 7; those at 3 (7) and 6 (8) lie beyond the line 4.34 between them.
        let values: Vec<f64> = (0..=10).map(f64::from).collect();
        let deviances = [9.0, 6.0, 1.0, 7.0, 0.5, 2.0, 8.0, 3.0, 9.0, 12.0, 15.0];
        let limit = 0.5 + rise;
        let c = candidate_interval(&values, &deviances).unwrap();
        assert_eq!((c.best, c.lowest_deviance), (4.0, 0.5));
        // Left from 2 (1) toward 1 (6); right from 7 (3) toward 8 (9).
        assert!((c.low - (2.0 - (limit - 1.0) / 5.0)).abs() < 1e-12, "{c:?}");
        assert!((c.high - (7.0 + (limit - 3.0) / 6.0)).abs() < 1e-12, "{c:?}");
        assert_eq!(c.beyond, [3.0, 6.0]);
        assert!(!c.connected() && !c.low_open && !c.high_open);
        // Whatever the parabola says, every candidate under the line is inside.
        let f = profile_interval(&values, &deviances).unwrap();
        for (v, d) in values.iter().zip(deviances) {
            if d <= f.candidate_limit() {
                assert!(f.low <= *v && *v <= f.high, "{v} outside {f:?}");
            }
        }
        assert!(f.beyond.contains(&3.0) && f.beyond.contains(&6.0), "{f:?}");
        // A run that reaches the range's end is open there, at the end itself.
        let rising = [0.5, 1.0, 2.0, 9.0, 12.0];
        let f = candidate_interval(&values[..5], &rising).unwrap();
        assert_eq!((f.low, f.low_open, f.high_open), (0.0, true, false));
        assert!(f.connected());
        let e = profile_interval(&values[..5], &[3.0, 9.0, 9.0, 9.0, 0.5]).unwrap();
        assert!(e.high_open && e.high == 4.0 && e.low <= 3.0, "{e:?}");
    }

    #[test]
    fn shares_are_compared_in_units_of_their_sigma() {
        // 30 of 100 against 20 of 100: pooled 0.25, σ = √(0.25·0.75·0.02) = 0.061237.
        let s = SharePair::new(30, 100, 20, 100);
        assert!((s.sigma - 0.061_237_244).abs() < 1e-9);
        assert!((s.z - 0.1 / 0.061_237_244).abs() < 1e-6);
        assert!(s.within_two_sigma());
        assert!(!SharePair::new(40, 100, 20, 100).within_two_sigma());
        let summary = shares_summary(&[s, SharePair::new(40, 100, 20, 100)], &[1.0, 2.0]);
        assert_eq!((summary.shares, summary.within_two_sigma), (2, 1));
        // Budden's data against itself: every ratio within 2σ, χ² zero, p one.
        let pairs: Vec<SharePair> = budden()
            .0
            .iter()
            .map(|r| SharePair::new(r.square_count(), r.throws, r.square_count(), r.throws))
            .collect();
        let ratios: Vec<f64> = budden().0.iter().map(|r| r.ratio).collect();
        let all = shares_summary(&pairs, &ratios);
        assert_eq!(
            (all.shares, all.within_two_sigma, all.chi_square, all.p_value),
            (15, 15, 0.0, 1.0)
        );
    }

    /// `n` throws drawn from the categories' `probabilities`.
    fn multinomial(rng: &mut ChaCha8Rng, probabilities: &[f64], n: u64) -> Vec<u64> {
        let mut cumulative = probabilities.to_vec();
        for i in 1..cumulative.len() {
            cumulative[i] += cumulative[i - 1];
        }
        let mut counts = vec![0; probabilities.len()];
        for _ in 0..n {
            let u: f64 = rng.random_range(0.0..1.0);
            let k = cumulative.partition_point(|&c| c <= u).min(counts.len() - 1);
            counts[k] += 1;
        }
        counts
    }

    /// The Kolmogorov–Smirnov test's p of a sample against the uniform distribution on
    /// [0, 1]: Stephens' approximation of the statistic's law (Numerical Recipes §14.3).
    fn ks_uniform_p(mut sample: Vec<f64>) -> f64 {
        sample.sort_by(f64::total_cmp);
        let n = sample.len() as f64;
        let d = sample
            .iter()
            .enumerate()
            .map(|(i, &u)| ((i as f64 + 1.0) / n - u).max(u - i as f64 / n))
            .fold(0.0, f64::max);
        let lambda = (n.sqrt() + 0.12 + 0.11 / n.sqrt()) * d;
        let tail: f64 = (1..=100)
            .map(|k| {
                let k = f64::from(k);
                let sign = if k % 2.0 == 1.0 { 1.0 } else { -1.0 };
                2.0 * sign * (-2.0 * k * k * lambda * lambda).exp()
            })
            .sum();
        tail.clamp(0.0, 1.0)
    }

    /// Binomial(12, q) of Weldon's protocol.
    fn weldon_probabilities(q: f64) -> Vec<f64> {
        (0..=12)
            .map(|k| {
                let ways = (0..k).fold(1.0, |c, i| c * f64::from(12 - i) / f64::from(i + 1));
                ways * q.powi(k) * (1.0 - q).powi(12 - k)
            })
            .collect()
    }

    /// 200 replicates of Weldon's protocol, `n` throws of the "real" die with `real`
    /// probabilities against `n` simulated from `model`: the p-values and the share the 5 %
    /// test rejected.
    fn replicates(real: &[f64], model: &[f64], n: u64, seed: u64) -> (Vec<f64>, f64) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let ps: Vec<f64> = (0..200)
            .map(|_| {
                let data = multinomial(&mut rng, real, n);
                let simulated = multinomial(&mut rng, model, n);
                two_sample(&data, &simulated).unwrap().p_value
            })
            .collect();
        let rejected = ps.iter().filter(|&&p| p < TEST_LEVEL).count() as f64 / ps.len() as f64;
        (ps, rejected)
    }

    #[test]
    fn p_values_are_uniform_when_the_model_is_right() {
        let fair = weldon_probabilities(1.0 / 3.0);
        let (ps, rejected) = replicates(&fair, &fair, 2000, 21);
        let ks = ks_uniform_p(ps);
        assert!(ks > 0.01, "KS p = {ks}");
        assert!(rejected < 0.1, "{rejected}");
        // The KS test itself can fail: p-values piled at one end are not uniform.
        assert!(ks_uniform_p((0..200).map(|i| f64::from(i) / 1000.0).collect()) < 1e-6);
    }

    #[test]
    fn the_power_printed_is_the_share_rejected() {
        // Weldon's excess: 106 602 / 315 672 instead of 1/3 per die.
        let real = weldon_probabilities(106_602.0 / 315_672.0);
        let fair = weldon_probabilities(1.0 / 3.0);
        // At 2 000 throws a side the excess is nearly invisible (scipy, 9 dof once 9 to 12
        // pool: λ = 1.02519, power 0.08505); at 32 000 a side about four tests in five see it.
        for (n, seed) in [(2000u64, 5u64), (32_000, 6)] {
            // The groups the test itself forms from the expected counts.
            let weights: Vec<f64> = real
                .iter()
                .zip(&fair)
                .map(|(q, p)| n as f64 * (q + p) / 2.0)
                .collect();
            let groups = pool(&weights, MIN_EXPECTED);
            let grouped =
                |p: &[f64]| -> Vec<f64> { groups.iter().map(|g| p[g.clone()].iter().sum()).collect() };
            let lambda = noncentrality(&grouped(&real), &grouped(&fair), n as f64, n as f64);
            let printed = power(lambda, groups.len() - 1);
            if n == 2000 {
                assert_eq!(groups.len(), 10);
                assert!((lambda - 1.025_190).abs() < 1e-5, "{lambda}");
                assert!((printed - 0.085_047).abs() < 1e-4, "{printed}");
            }
            let (_, rejected) = replicates(&real, &fair, n, seed);
            assert!(
                (printed - rejected).abs() <= 0.05,
                "{n} throws: power {printed:.3}, rejected {rejected:.3}"
            );
        }
        let groups = fit_groups(&Dataset::Weldon.data().counts);
        let grouped = |p: &[f64]| -> Vec<f64> { groups.iter().map(|g| p[g.clone()].iter().sum()).collect() };
        let (q, p) = (grouped(&real), grouped(&fair));
        // The throws a test against the exact model needs: λ₈₀ / w² (scipy: 15 776.1).
        let w2: f64 = q.iter().zip(&p).map(|(q, p)| (q - p).powi(2) / p).sum();
        assert!((detecting_noncentrality(10) / w2 - 15_776.1).abs() < 1.0);
    }

    /// A fair d20's counts ("Is my die fair?"): the χ² p-values a player reads, against
    /// equal shares and against a simulated fair die of the default 10 000 rolls, are
    /// uniform over 200 seeded replicates at 100 (five expected a face, the fewest the
    /// counts are taken with), 1 000 and 10 000 rolls.
    #[test]
    fn a_fair_d20s_p_values_are_uniform() {
        let fair = vec![1.0 / 20.0; 20];
        for (n, seed) in [(100u64, 31u64), (1000, 32), (10_000, 33)] {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let (mut against_fair, mut against_simulated) = (Vec::new(), Vec::new());
            for _ in 0..200 {
                let counts = multinomial(&mut rng, &fair, n);
                let simulated = multinomial(&mut rng, &fair, 10_000);
                against_fair.push(goodness_of_fit(&counts, &fair).p_value);
                against_simulated.push(two_sample(&counts, &simulated).unwrap().p_value);
            }
            let ks = ks_uniform_p(against_fair);
            assert!(ks > 0.01, "{n} rolls, against equal shares: KS p = {ks}");
            let ks = ks_uniform_p(against_simulated);
            assert!(ks > 0.01, "{n} rolls, against the simulated die: KS p = {ks}");
        }
    }

    /// The rolls a player needs to see a flaw, read from a simulated flawed die's counts
    /// (its noncentrality beyond chance: [`crate::FaceTally::rolls_to_detect`]), are the
    /// rolls at which four tests in five of a die with those shares reject a fair die: 200
    /// seeded replicates at that size reject 80 % of the time, within 5 points. Two flaws: a
    /// bubble's (one face up more often, its opposite less) and a tumbled die's (every face
    /// a little off, alternately).
    #[test]
    fn the_rolls_to_detect_a_flaw_are_where_four_tests_in_five_see_it() {
        let fair = vec![1.0 / 20.0; 20];
        let mut bubble = fair.clone();
        (bubble[19], bubble[0]) = (0.05 + 0.008, 0.05 - 0.008);
        let tumbled: Vec<f64> = (0..20)
            .map(|i| if i % 2 == 0 { 0.05 + 0.003 } else { 0.05 - 0.003 })
            .collect();
        for (shares, seed) in [(bubble, 41u64), (tumbled, 42)] {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            // The simulated die: its shares measured over 200 000 rolls.
            let numbers: &'static [u8] = &[
                1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
            ];
            let mut simulated = crate::FaceTally::new(numbers);
            simulated.counts = multinomial(&mut rng, &shares, 200_000);
            let n = simulated.rolls_to_detect().unwrap();
            // Its own figure from the exact shares: λ₈₀(19) / w², w² = Σ (q − 1/20)²·20.
            let w2: f64 = shares.iter().map(|q| (q - 0.05).powi(2) / 0.05).sum();
            let exact = detecting_noncentrality(19) / w2;
            assert!(
                (n as f64 / exact - 1.0).abs() < 0.1,
                "{n} rolls from the simulated counts, {exact:.0} from the shares"
            );
            let rejected = (0..200)
                .filter(|_| {
                    let counts = multinomial(&mut rng, &shares, n);
                    goodness_of_fit(&counts, &fair).p_value < TEST_LEVEL
                })
                .count() as f64
                / 200.0;
            assert!(
                (rejected - TEST_POWER).abs() <= 0.05,
                "{n} rolls: {rejected:.3} of the replicates rejected a fair die, not 0.80 ± 0.05"
            );
        }
    }

    #[test]
    fn sparse_neighbouring_shares_are_pooled_for_the_chi_square() {
        // By hand: A's pooled share 110/200 = 0.55 expects 45 of its 100 — alone. B's
        // 3/600 = 0.005 expects 1.5 of 300 and C's 7/400 expects 3.5 of 200: B is short
        // first, and joins C, the neighbour expecting fewer than A; B + C, 10/1000, expects
        // 5.0 of 500: enough. A's z² = 0.1²/(0.55·0.45·2/100) = 2.020202…; B + C's shares
        // are equal (5/500 each), z = 0. χ² = 2.020202 on 2 dof; each share alone is
        // within 2σ (B: z = 0.58, C: z = −0.38).
        let pairs = [
            SharePair::new(50, 100, 60, 100),
            SharePair::new(2, 300, 1, 300),
            SharePair::new(3, 200, 4, 200),
        ];
        assert_eq!(pooled_groups(&pairs), vec![0..1, 1..3]);
        let s = shares_summary(&pairs, &[0.5, 1.5, 2.5]);
        assert_eq!((s.shares, s.dof, s.within_two_sigma), (3, 2, 3));
        assert!((s.chi_square - 0.01 / 0.00495).abs() < 1e-12, "{}", s.chi_square);
        assert_eq!(s.pooled, vec![vec![1.5, 2.5]]);
        // χ² of 2 dof: p = e^(−χ²/2).
        assert!((s.p_value - (-s.chi_square / 2.0).exp()).abs() < 1e-9);
        // Nothing short: nothing pooled, one dof a share.
        let plenty = [SharePair::new(50, 100, 60, 100), SharePair::new(30, 100, 25, 100)];
        assert_eq!(pooled_groups(&plenty), vec![0..1, 1..2]);
        // A short share at the end joins the one before it.
        let last = [SharePair::new(50, 100, 60, 100), SharePair::new(1, 100, 1, 100)];
        assert_eq!(pooled_groups(&last), vec![0..2]);
    }
}
