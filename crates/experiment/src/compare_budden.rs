//! Budden's steel cuboids ([`real_data::budden`](crate::real_data::budden)) thrown as
//! Budden threw them: one cuboid per ratio x/y, each throw drawn from the preset's random
//! ranges, counted by whether a square face ended up (or, the same, down).
//!
//! A hand does not hold a cuboid the same way up twice, so every throw starts from a
//! uniformly random orientation, with the preset's ranges for height, velocity and spin.
//!
//! One setup value is fitted on a few ratios (`calibrate_on`) with common random numbers,
//! as [`compare`](crate::compare) fits a cubic die; every ratio is then thrown once more
//! with the best value, so the other ratios are predictions out of sample: the fit never
//! saw them.
//!
//! The source gives only the ratio, not the cuboids' size: the square faces are taken as
//! 2 cm across and the cuboids as solid steel (both stated in every output).

use crate::Error;
use crate::batch::{Rolls, RunOptions, stream_batch};
use crate::compare::{
    Excluded, Exclusion, FitSpec, Progress, fit_over_kept, past_stability_limit, refuse_all_unstable,
};
use crate::compare_stats::{FitInterval, SharePair, SharesSummary, deviance, shares_summary};
use crate::data_file::Column;
use crate::real_data::{BuddenRow, budden};
use dicesim_physics::{Die, InitialCondition, Params};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::number::Real;
use dicesim_setup::random::{RandomRanges, check_drawn_setup};
use serde::Serialize;
use std::sync::atomic::AtomicBool;

/// cm, the side of the cuboids' square faces (not in the source: an assumption).
pub const SQUARE_SIDE_CM: f64 = 2.0;

/// g/cm³, the density of the cuboids' steel (an assumption: the source says "steel").
pub const STEEL_DENSITY_G_PER_CM3: f64 = 7.8;

/// The ratios a fit uses unless told otherwise: one where square faces win, one near the
/// even split and one where they are rare, so the fit sees the whole curve's shape.
pub const DEFAULT_CALIBRATE_ON: [f64; 3] = [0.63, 1.16, 1.87];

/// The fit unless told otherwise: the table's damping γ (s/cm), which sets how much of a
/// landing's energy a bounce keeps and so how long a cuboid tumbles before it settles
/// (docs/real-dice.md, "Budden's cuboids", says why this key and not the friction). Its
/// range is where the paper's table steps every cuboid stably at the worst throw of the
/// paper's ranges: below about 0.0086 s/cm the 2.65 cuboid lands too deep into the table,
/// above about 0.0164 s/cm the damping pulls on the 0.47 cuboid's corners.
pub const DEFAULT_FIT: &str = "ground.damping:0.009:0.016";

/// Throws of different ratios are drawn from disjoint parts of the seed's stream: ratio
/// `i`'s throw `j` is roll `i·RATIO_STREAM + j`.
const RATIO_STREAM: u64 = 1 << 32;

/// The sentences every output states about the body and the throw.
pub fn assumptions() -> Vec<String> {
    vec![
        format!("square faces {SQUARE_SIDE_CM} cm across (the source gives only the ratio x/y)"),
        format!(
            "solid steel of {STEEL_DENSITY_G_PER_CM3} g/cm³, corners as the preset's die.corner_radius (0 = sharp): mass {STEEL_DENSITY_G_PER_CM3} g/cm³ × \
             x·{SQUARE_SIDE_CM}·{SQUARE_SIDE_CM} cm³, spread evenly through the body"
        ),
        "a hand throw: each throw drawn from the preset's random ranges (height, velocity, spin) \
         from a uniformly random orientation, whatever the preset says; the preset's die is \
         replaced by the cuboid, its table, world and integrator are kept"
            .to_string(),
    ]
}

/// The steel cuboid of `ratio` = x/y: faces 1 and 6 (the body's x axis) are the square
/// ones, `x = ratio·y` apart; half sizes `[ratio·y/2, y/2, y/2]`, sharp, no pips, and a
/// body mass of density × volume (`8·corner_mass`, spread evenly through a body that is not
/// a cube; Budden's ratios never are 1).
pub fn cuboid(ratio: f64) -> Die {
    let half = 0.5 * SQUARE_SIDE_CM;
    let half_sizes = [ratio * half, half, half];
    let volume = 8.0 * half_sizes.iter().product::<f64>();
    Die {
        half_sizes,
        corner_radius: 0.0,
        pip_diameter: 0.0,
        pip_depth: 0.0,
        corner_mass: STEEL_DENSITY_G_PER_CM3 * volume / 8.0,
        extra_corner_mass: [0.0; 8],
        ..Params::DEFAULT.die
    }
}

/// Why a `--set` of `key` does not reach Budden's throws (`None` where it does): the
/// cuboid's size, mass and bare faces are the protocol's, so of the die's keys only its
/// corner rounding applies (to every ratio's cuboid); the hand throw always starts from a
/// uniformly random orientation.
pub fn unapplied(key: &str) -> Option<String> {
    if key == "random.random_orientation" {
        return Some("Budden's hand throws always start from a uniformly random orientation".to_string());
    }
    (key.starts_with("die.") && key != "die.corner_radius").then(|| {
        format!(
            "`compare budden` throws Budden's solid steel cuboids (square faces {SQUARE_SIDE_CM} cm \
             across, no pips) in place of the preset's die; of the die's keys only \
             `die.corner_radius` applies, to every cuboid"
        )
    })
}

/// Why a comparison would not apply a change of `key` to its preset (a `--set`), as
/// [`dicesim_setup::preset::refuse_unapplied`] asks: a start value the throws draw from
/// `ranges`, a seed a given seed replaces (`seed_given`), the value `fit` sets on every
/// candidate, and for Budden (`budden`) the die the cuboids replace
/// ([`unapplied`]).
pub fn unapplied_by_comparison(
    key: &str,
    budden: bool,
    ranges: &RandomRanges,
    fit: Option<&FitSpec>,
    seed_given: bool,
) -> Option<String> {
    let command = if budden { "compare budden" } else { "compare" };
    budden
        .then(|| unapplied(key))
        .flatten()
        .or_else(|| dicesim_setup::random::unapplied_when_drawn(key, ranges, command))
        .or_else(|| dicesim_setup::random::seed_given(key, seed_given))
        .or_else(|| {
            fit.filter(|f| f.key.overlaps(key))
                .map(|f| format!("--fit sets `{}` on every candidate", f.key.key))
        })
}

/// Whether the face up (1..6) is a square one: the cuboid's square faces are 1 and 6,
/// opposite each other, so a square face up is a square face down.
pub fn is_square_face(face: u8) -> bool {
    face == 1 || face == 6
}

/// What a ratio is for in a comparison.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RatioRole {
    /// The fit used it.
    Calibrate,
    /// Thrown with the fitted value only: a prediction out of sample.
    Predict,
}

/// What to throw: each ratio `throws` times (Budden's own count when `None`) once per seed
/// of `seeds`, the counts pooled; `fit` calibrated on the ratios `calibrate_on` (`None`:
/// the preset's table as it stands, every ratio keeping its role, so a table fitted on
/// those ratios elsewhere is judged out of sample on the others).
#[derive(Debug, Clone, PartialEq)]
pub struct BuddenSpec {
    pub throws: Option<u64>,
    pub seeds: Vec<u64>,
    pub fit: Option<FitSpec>,
    pub calibrate_on: Vec<f64>,
}

impl BuddenSpec {
    /// Checks the spec before anything is rolled: the fit, and every calibration ratio one
    /// of Budden's (the error names those).
    pub fn validate(&self) -> Result<(), Error> {
        if self.throws == Some(0) {
            return Err(Error::Compare("throw at least once".to_string()));
        }
        if let Some(fit) = &self.fit {
            fit.validate()?;
        }
        if self.seeds.is_empty() {
            return Err(Error::Compare("--seed: name at least one seed".to_string()));
        }
        if let Some(i) = (1..self.seeds.len()).find(|&i| self.seeds[..i].contains(&self.seeds[i])) {
            return Err(Error::Compare(format!(
                "--seed: seed {} is named twice (its throws would be counted twice)",
                self.seeds[i]
            )));
        }
        let rows = budden().0;
        if self.calibrate_on.is_empty() {
            return Err(Error::Compare(
                "--calibrate-on: name at least one ratio to fit on".to_string(),
            ));
        }
        for (i, &r) in self.calibrate_on.iter().enumerate() {
            if !rows.iter().any(|row| row.ratio == r) {
                return Err(Error::Compare(format!(
                    "--calibrate-on: {r} is not one of Budden's ratios x/y; they are {}",
                    ratio_list(&rows)
                )));
            }
            if self.calibrate_on[..i].contains(&r) {
                return Err(Error::Compare(format!(
                    "--calibrate-on: ratio {r} is named twice"
                )));
            }
        }
        Ok(())
    }

    /// Throws of `row`'s ratio with each seed.
    fn throws_of(&self, row: &BuddenRow) -> u64 {
        self.throws.unwrap_or(row.throws)
    }

    fn role(&self, row: &BuddenRow) -> RatioRole {
        if self.calibrate_on.contains(&row.ratio) {
            RatioRole::Calibrate
        } else {
            RatioRole::Predict
        }
    }

    /// Rolls in the whole comparison: every candidate on the calibration ratios, then every
    /// ratio once with the best value.
    pub fn total_rolls(&self) -> u64 {
        let rows = budden().0;
        let calibrating: u64 = rows
            .iter()
            .filter(|r| self.role(r) == RatioRole::Calibrate)
            .map(|r| self.throws_of(r))
            .sum();
        let all: u64 = rows.iter().map(|r| self.throws_of(r)).sum();
        calibrating
            .saturating_mul(self.fit.as_ref().map_or(0, |f| f.candidates as u64))
            .saturating_add(all)
            .saturating_mul(self.seeds.len() as u64)
    }
}

/// Budden's ratios as a list for messages: `0.47, 0.63, …, 2.65`.
fn ratio_list(rows: &[BuddenRow]) -> String {
    rows.iter()
        .map(|r| format!("{:.2}", r.ratio))
        .collect::<Vec<_>>()
        .join(", ")
}

/// One ratio thrown with one setup.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RatioThrows {
    pub ratio: f64,
    /// Throws that ended on a face.
    pub throws: u64,
    /// Throws not counted: the cuboid ended without a face (on an edge, not settled).
    pub uncounted: u64,
    /// Counted throws that ended on a square face.
    pub square: u64,
    /// Throws whose start the stability check puts past its limit.
    pub past_stability_limit: u64,
}

/// One candidate of the fit: its value, its throws of the calibration ratios and the
/// deviance summed over them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BuddenCandidate {
    pub value: f64,
    pub ratios: Vec<RatioThrows>,
    pub deviance: f64,
}

/// One ratio of the final table: Budden's count beside the simulation's with the best
/// value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RatioResult {
    pub ratio: f64,
    pub role: RatioRole,
    /// Budden's throws and those on a square face.
    pub data_throws: u64,
    pub data_square: u64,
    pub simulated: RatioThrows,
    /// The two shares with their intervals, and their difference in σ.
    pub shares: SharePair,
    /// Why this ratio is held against nothing (too few of its simulated throws counted), if
    /// so: it is left out of the within-2σ counts and their χ².
    pub excluded: Option<Exclusion>,
}

/// The whole comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BuddenComparison {
    /// `"budden"`.
    pub dataset: &'static str,
    pub source: String,
    pub assumptions: Vec<String>,
    /// The seeds thrown, each ratio's counts pooled over them.
    pub seeds: Vec<u64>,
    /// Throws per ratio and seed asked for (`None`: Budden's own count for each).
    pub throws: Option<u64>,
    /// The fitted key (`None`: no fit, the preset's table as it stands).
    pub key: Option<String>,
    pub calibrate_on: Vec<f64>,
    pub candidates: Vec<BuddenCandidate>,
    pub fit: Option<FitInterval>,
    /// The candidates the fit left out, each with its reason.
    pub excluded: Vec<Excluded>,
    /// Every ratio thrown with the fit's best value (empty if cancelled before).
    pub ratios: Vec<RatioResult>,
    /// The calibration ratios, the predicted ones and all of them against the data.
    pub calibrated: Option<SharesSummary>,
    pub predicted: Option<SharesSummary>,
    pub all: Option<SharesSummary>,
    pub cancelled: bool,
}

impl BuddenComparison {
    /// The CSV's columns: the ratio and its role, the fitted key's best value (named with
    /// its unit, once the fit has one), Budden's and the simulated throws and their shares,
    /// σ, z and whether they agree within 2σ.
    pub fn csv_columns(&self) -> Vec<Column> {
        let mut columns = vec![Column::real("ratio"), Column::text("role")];
        if let (Some(_), Some(key)) = (&self.fit, &self.key) {
            let name = ScanKey::named(key).map_or_else(|_| key.replace('.', "_"), |k| k.column());
            // The best value, then the fit's 95 % interval (docs/real-dice.md, "The fit's interval").
            columns.extend([
                Column::real(name),
                Column::real("interval_low"),
                Column::real("interval_high"),
            ]);
        }
        columns.extend([
            Column::integer("data_throws"),
            Column::integer("data_square"),
            Column::real("data_share"),
            Column::real("data_low"),
            Column::real("data_high"),
            Column::integer("simulated_throws"),
            Column::integer("simulated_uncounted"),
            Column::integer("simulated_square"),
            Column::real("simulated_share"),
            Column::real("simulated_low"),
            Column::real("simulated_high"),
            Column::real("sigma"),
            Column::real("z"),
            Column::boolean("within_two_sigma"),
        ]);
        columns
    }

    /// One row per ratio of the final table, in [`BuddenComparison::csv_columns`].
    pub fn write_csv(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        writeln!(w, "{}", crate::data_file::header(&self.csv_columns()))?;
        let real = |x: f64| Real(x).to_string();
        for r in &self.ratios {
            let s = &r.shares;
            let mut cells = vec![
                real(r.ratio),
                match r.role {
                    RatioRole::Calibrate => "calibrate",
                    RatioRole::Predict => "predict",
                }
                .to_string(),
            ];
            if let Some(f) = &self.fit {
                cells.extend([real(f.best), real(f.low), real(f.high)]);
            }
            cells.extend([
                r.data_throws.to_string(),
                r.data_square.to_string(),
                real(s.data_share),
                real(s.data_interval[0]),
                real(s.data_interval[1]),
                r.simulated.throws.to_string(),
                r.simulated.uncounted.to_string(),
                r.simulated.square.to_string(),
                real(s.simulated_share),
                real(s.simulated_interval[0]),
                real(s.simulated_interval[1]),
                real(s.sigma),
                real(s.z),
                s.within_two_sigma().to_string(),
            ]);
            writeln!(w, "{}", cells.join(","))?;
        }
        Ok(())
    }
}

/// The throw of Budden's protocol: `ranges` from a uniformly random orientation.
pub fn hand_throw(ranges: &RandomRanges) -> RandomRanges {
    RandomRanges {
        random_orientation: true,
        ..*ranges
    }
}

/// `params` with the cuboid of `ratio` as its die and the fitted key at `value`.
pub(crate) fn body_at(
    params: &Params,
    base: &InitialCondition,
    fit: Option<&FitSpec>,
    ratio: f64,
    value: f64,
) -> (Params, InitialCondition) {
    let (mut p, mut ic) = (*params, *base);
    // The preset's corner rounding is the one body key a steel cuboid can take.
    p.die = Die {
        corner_radius: params.die.corner_radius,
        ..cuboid(ratio)
    };
    if let Some(fit) = fit {
        fit.key.set(&mut p, &mut ic, value);
    }
    (p, ic)
}

/// `params` with the cuboid of `ratio` as its die and the fitted key at `value`, checked.
fn setup(
    params: &Params,
    base: &InitialCondition,
    ranges: &RandomRanges,
    fit: Option<&FitSpec>,
    ratio: f64,
    value: f64,
) -> Result<(Params, InitialCondition), Error> {
    let (p, ic) = body_at(params, base, fit, ratio, value);
    // Which cuboid and candidate a refusal is about: the key alone does not say.
    let context = |e: Error| match fit {
        Some(fit) => Error::Compare(format!(
            "the cuboid of ratio {ratio} with {} = {value}: {e}",
            fit.key.key
        )),
        None => Error::Compare(format!("the cuboid of ratio {ratio}: {e}")),
    };
    if let Some(fit) = fit {
        fit.key.check(value).map_err(|e| context(e.into()))?;
    }
    check_drawn_setup(&p, ranges, &ic).map_err(|e| context(e.into()))?;
    Ok((p, ic))
}

/// Throws ratio `index` of Budden's table `throws` times; `None` when cancelled before
/// the last throw (a ratio counts whole or not at all).
#[allow(clippy::too_many_arguments)]
pub(crate) fn throw_ratio(
    (params, base): (Params, InitialCondition),
    ranges: &RandomRanges,
    seeds: &[u64],
    (index, ratio): (usize, f64),
    throws: u64,
    options: &RunOptions,
    cancel: &AtomicBool,
    mut advance: impl FnMut(u64),
) -> Result<Option<RatioThrows>, Error> {
    let mut t = RatioThrows {
        ratio,
        throws: 0,
        uncounted: 0,
        square: 0,
        past_stability_limit: 0,
    };
    // Each seed's throws of this ratio, from the same part of its own stream: seeds give
    // disjoint throws, and one seed alone gives the throws a single-seed run gives.
    for &seed in seeds {
        let rolls = Rolls::Random {
            ranges,
            base: &base,
            seed,
            first: index as u64 * RATIO_STREAM,
            count: throws,
        };
        let run = stream_batch(&params, &rolls, options, cancel, &mut |records| {
            for r in records {
                match r.outcome.face {
                    Some(face) => {
                        t.throws += 1;
                        t.square += u64::from(is_square_face(face));
                    }
                    None => t.uncounted += 1,
                }
            }
            advance(records.len() as u64);
            Ok(())
        })?;
        t.past_stability_limit += run.past_stability_limit;
        if run.cancelled {
            return Ok(None);
        }
    }
    Ok(Some(t))
}

/// The deviance of Budden's counts against the simulation's at one ratio: the 2 × 2 table
/// of square and other landings.
pub(crate) fn ratio_deviance(row: &BuddenRow, t: &RatioThrows) -> f64 {
    let data = [row.square_count(), row.throws - row.square_count()];
    let simulated = [t.square, t.throws - t.square];
    deviance(&data, &simulated, &[0..1, 1..2])
}

/// Fits `spec.fit` on the calibration ratios (every candidate with the same throws), then
/// throws every ratio with the best value and holds each against Budden's share.
/// `progress` is called after each chunk of rolls; `cancel` keeps the candidates and
/// ratios thrown whole.
pub fn run_budden(
    params: &Params,
    ranges: &RandomRanges,
    base: &InitialCondition,
    spec: &BuddenSpec,
    options: &RunOptions,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(Progress),
) -> Result<BuddenComparison, Error> {
    spec.validate()?;
    let hand = hand_throw(ranges);
    let ranges = &hand;
    let (rows, source) = budden();
    let fit = spec.fit.as_ref();
    // Without a fit, one "value" that sets nothing: the preset's table as it stands.
    let values = fit.map_or(vec![f64::NAN], FitSpec::values);
    // Every setup is checked before the first roll.
    for row in &rows {
        for &v in &values {
            setup(params, base, ranges, fit, row.ratio, v)?;
        }
    }
    // Every cuboid is thrown with the best value: each one's limit holds for a candidate.
    let cuboids_at = |v: f64| {
        rows.iter()
            .map(|row| {
                let (p, ic) = body_at(params, base, fit, row.ratio, v);
                (Some(row.ratio), p, ic)
            })
            .collect()
    };
    if let Some(fit) = fit {
        refuse_all_unstable(fit, &cuboids_at, ranges)?;
    }
    let total = spec.total_rolls();
    let mut done = 0;
    let mut advance = |n: u64| {
        done += n;
        progress(Progress { done, total });
    };
    // Ratio `i`'s throws with the fitted key at `value` (None: stopped part way).
    let mut throw = |i: usize, row: &BuddenRow, value: f64| {
        let s = setup(params, base, ranges, fit, row.ratio, value)?;
        throw_ratio(
            s,
            ranges,
            &spec.seeds,
            (i, row.ratio),
            spec.throws_of(row),
            options,
            cancel,
            &mut advance,
        )
    };
    let calibration: Vec<(usize, &BuddenRow)> = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| spec.role(r) == RatioRole::Calibrate)
        .collect();
    let mut candidates = Vec::new();
    let mut cancelled = false;
    let fitted_values = if fit.is_some() { values.as_slice() } else { &[] };
    'candidates: for &value in fitted_values {
        let mut thrown = Vec::new();
        for &(i, row) in &calibration {
            match throw(i, row, value)? {
                Some(t) => thrown.push(t),
                None => {
                    cancelled = true;
                    break 'candidates;
                }
            }
        }
        let deviance = calibration
            .iter()
            .zip(&thrown)
            .map(|((_, row), t)| ratio_deviance(row, t))
            .sum();
        candidates.push(BuddenCandidate {
            value,
            ratios: thrown,
            deviance,
        });
    }
    // A candidate rests on every calibration ratio: too few counted at any one leaves it out.
    let excluded: Vec<Excluded> = candidates
        .iter()
        .filter_map(|c| {
            let why = past_stability_limit(&cuboids_at, ranges, c.value).or_else(|| {
                c.ratios
                    .iter()
                    .find_map(|t| Exclusion::of_counts(t.throws, t.throws + t.uncounted))
            })?;
            Some(Excluded { value: c.value, why })
        })
        .collect();
    let interval = match fit {
        Some(fit) if !cancelled => {
            let values: Vec<f64> = candidates.iter().map(|c| c.value).collect();
            let deviances: Vec<f64> = candidates.iter().map(|c| c.deviance).collect();
            fit_over_kept(&fit.key.key, &values, &deviances, &excluded)?
        }
        _ => None,
    };
    // Every ratio with the best value, or without a fit with the table as it stands.
    let thrown_with = match fit {
        Some(_) => interval.as_ref().map(|f| f.best),
        None => Some(f64::NAN),
    };
    let mut results = Vec::new();
    if let Some(best) = thrown_with {
        for (i, row) in rows.iter().enumerate() {
            let Some(t) = throw(i, row, best)? else {
                cancelled = true;
                break;
            };
            results.push(RatioResult {
                ratio: row.ratio,
                role: spec.role(row),
                data_throws: row.throws,
                data_square: row.square_count(),
                simulated: t,
                shares: SharePair::new(row.square_count(), row.throws, t.square, t.throws),
                excluded: Exclusion::of_counts(t.throws, t.throws + t.uncounted),
            });
        }
    }
    let complete = results.len() == rows.len();
    let summary = |role: Option<RatioRole>| {
        let kept: Vec<&RatioResult> = results
            .iter()
            .filter(|r| role.is_none_or(|role| r.role == role) && r.excluded.is_none())
            .collect();
        let pairs: Vec<SharePair> = kept.iter().map(|r| r.shares).collect();
        let labels: Vec<f64> = kept.iter().map(|r| r.ratio).collect();
        (complete && !pairs.is_empty()).then(|| shares_summary(&pairs, &labels))
    };
    Ok(BuddenComparison {
        dataset: "budden",
        source,
        assumptions: assumptions(),
        seeds: spec.seeds.clone(),
        throws: spec.throws,
        key: fit.map(|f| f.key.key.clone()),
        calibrate_on: spec.calibrate_on.clone(),
        candidates,
        fit: interval,
        excluded,
        calibrated: summary(Some(RatioRole::Calibrate)),
        predicted: summary(Some(RatioRole::Predict)),
        all: summary(None),
        ratios: results,
        cancelled,
    })
}

/// The seeds of a run: `seed 1`, or `seeds 11, 12, 13 pooled`.
pub fn seeds_text(seeds: &[u64]) -> String {
    match seeds {
        [one] => format!("seed {one}"),
        _ => format!(
            "seeds {} pooled",
            seeds.iter().map(u64::to_string).collect::<Vec<_>>().join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(calibrate_on: &[f64]) -> BuddenSpec {
        BuddenSpec {
            throws: None,
            seeds: vec![1],
            fit: Some(FitSpec::parse(DEFAULT_FIT, 21).unwrap()),
            calibrate_on: calibrate_on.to_vec(),
        }
    }

    #[test]
    fn the_default_calibration_rolls_its_three_ratios_per_candidate_then_all_fifteen() {
        let s = spec(&DEFAULT_CALIBRATE_ON);
        s.validate().unwrap();
        // Budden's throws at 0.63, 1.16 and 1.87: 840 + 1011 + 680; all 15 ratios: 9 329.
        assert_eq!(s.total_rolls(), 21 * (840 + 1011 + 680) + 9329);
        let roles: Vec<RatioRole> = budden().0.iter().map(|r| s.role(r)).collect();
        assert_eq!(roles.iter().filter(|&&r| r == RatioRole::Predict).count(), 12);
        assert_eq!(roles[1], RatioRole::Calibrate);
    }

    #[test]
    fn calibration_ratios_outside_the_data_are_refused() {
        let e = spec(&[0.63, 1.0]).validate().unwrap_err().to_string();
        assert!(e.contains("1 is not one of Budden's ratios"), "{e}");
        assert!(e.contains("0.47, 0.63, 0.75"), "{e}");
        assert!(e.contains("2.12, 2.65"), "{e}");
        let e = spec(&[0.63, 0.63]).validate().unwrap_err().to_string();
        assert!(e.contains("named twice"), "{e}");
        let e = spec(&[]).validate().unwrap_err().to_string();
        assert!(e.contains("at least one ratio"), "{e}");
    }

    #[test]
    fn a_refused_cuboid_is_named_by_its_ratio_and_value() {
        let fit = FitSpec::parse("die.corner_radius:0:0.6", 21).unwrap();
        let (p, ic, r) = (
            Params::default(),
            InitialCondition::default(),
            RandomRanges::default(),
        );
        // Ratio 0.47: half sizes 0.47, 1, 1 cm, so a 0.6 cm rounding does not fit.
        let e = setup(&p, &ic, &r, Some(&fit), 0.47, 0.6).unwrap_err().to_string();
        assert!(
            e.contains("the cuboid of ratio 0.47 with die.corner_radius = 0.6"),
            "{e}"
        );
        assert!(e.contains("below the smallest half size, 0.47 cm"), "{e}");
        // The same cuboid with a rounding it has room for.
        assert!(setup(&p, &ic, &r, Some(&fit), 0.47, 0.2).is_ok());
    }

    #[test]
    fn a_ratio_deviance_is_the_two_by_two_g_squared() {
        // Ratio 0.63: 620 of 840 (0.738) square. Against 300 of 400 simulated, by hand:
        // E = 840·920/1240, 840·320/1240, 400·920/1240, 400·320/1240.
        let row = budden().0[1];
        assert_eq!(row.square_count(), 620);
        let t = RatioThrows {
            ratio: 0.63,
            throws: 400,
            uncounted: 7,
            square: 300,
            past_stability_limit: 0,
        };
        let g = |o: f64, e: f64| o * (o / e).ln();
        let n = 1240.0;
        let expected = 2.0
            * (g(620.0, 840.0 * 920.0 / n)
                + g(220.0, 840.0 * 320.0 / n)
                + g(300.0, 400.0 * 920.0 / n)
                + g(100.0, 400.0 * 320.0 / n));
        assert!((ratio_deviance(&row, &t) - expected).abs() < 1e-9);
    }
}
