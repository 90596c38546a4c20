//! Simulated dice thrown the way a historical experiment threw real ones, held against its
//! counts ([`real_data`](crate::real_data)), and one setup value fitted to them.
//!
//! A throw of the experiment is [`Dataset::dice_per_throw`] consecutive rolls of one batch
//! ([`stream_batch`]), each drawn from the preset's random ranges, so the comparison is
//! parallel, the same for any thread count or engine, and a cancel keeps an exact prefix of
//! whole throws. A fit rolls every candidate value with the same seed: the same throws
//! (common random numbers), so the candidates differ by the value alone and the deviance
//! profile is smooth enough to read an interval from.

use crate::Error;
use crate::basin::Axis;
use crate::batch::{Rolls, RunOptions, stream_batch};
use crate::compare_stats::{
    FitInterval, GoodnessOfFit, TwoSample, deviance, fit_groups, goodness_of_fit, profile_interval,
    two_sample,
};
use crate::data_file::Column;
use crate::player_counts::PlayerCounts;
use crate::real_data::{CountData, Dataset, Experiment};
use crate::record::RollRecord;
use crate::stats::{FaceTally, wilson_interval};
use dicesim_physics::{InitialCondition, Params, Reading};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::number::{Real, fmt_exact};
use dicesim_setup::random::{RandomRanges, check_drawn_setup, worst_throw_reading};
use dicesim_setup::registry::Role;
use serde::Serialize;
use std::sync::atomic::AtomicBool;

/// The fewest candidates a fit rolls: enough to trace the deviance's valley.
pub const MIN_CANDIDATES: usize = 20;

/// The candidates a fit rolls unless told otherwise: 20 steps over the range.
pub const DEFAULT_CANDIDATES: usize = 21;

/// The least share of a candidate's throws that must end on a face for the candidate to take
/// part in a fit (docs/real-dice.md, "What a fit rests on"). Every candidate rolls the same
/// throws; one that counts `m` of its `N` measures each share with a σ √(N/m) times a whole
/// candidate's, and its deviance, which grows with the evidence `m·n/(m + n)` against the
/// data's `n`, falls for the throws it lost alone. Below half, that σ is more than √2 times
/// the whole candidate's and its evidence under half of it: such a candidate would win a fit
/// by what it did not measure. And a die that leaves most throws without a face is not the
/// die the experimenters threw, who threw a cocked die again.
pub const MIN_COUNTED_SHARE: f64 = 0.5;

/// Why a fit left a candidate out. Each reason is one variant, so every cause that takes a
/// candidate out of a fit is listed the same way.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum Exclusion {
    /// Fewer than [`MIN_COUNTED_SHARE`] of its throws (of one calibration ratio, for Budden)
    /// ended on a face: `counted` of `thrown`, where the fit needs `needed`.
    TooFewCounted { counted: u64, thrown: u64, needed: u64 },
    /// The stability check predicts the worst throw of the random ranges past a limit for
    /// one body thrown (`ratio`: Budden's cuboid of that ratio; `None`: the preset's die):
    /// its steps would not follow the physics, so its counts are not the model's.
    PastStabilityLimit { ratio: Option<f64>, reading: Reading },
}

/// A candidate a fit left out: its value and why.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Excluded {
    pub value: f64,
    #[serde(flatten)]
    pub why: Exclusion,
}

impl Exclusion {
    /// Whether `counted` of `thrown` throws ending on a face are too few for a fit.
    pub fn of_counts(counted: u64, thrown: u64) -> Option<Exclusion> {
        let needed = ((MIN_COUNTED_SHARE * thrown as f64).ceil() as u64).max(1);
        (counted < needed).then_some(Exclusion::TooFewCounted {
            counted,
            thrown,
            needed,
        })
    }
}

/// E.g. "3 of 200 throws ended on a face, fewer than the 100 a candidate needs (half of them)".
impl std::fmt::Display for Exclusion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Exclusion::TooFewCounted {
                counted,
                thrown,
                needed,
            } => write!(
                f,
                "{counted} of {thrown} throws ended on a face, fewer than the {needed} a candidate needs (half of them)"
            ),
            Exclusion::PastStabilityLimit { ratio, reading } => write!(
                f,
                "past the stability limit for {} at the worst throw of the random ranges ({} load {:.2}): {reading}",
                body_name(*ratio),
                reading.limit.name(),
                reading.load()
            ),
        }
    }
}

/// The body a comparison throws, in words.
fn body_name(ratio: Option<f64>) -> String {
    ratio.map_or("the die".to_string(), |r| format!("the cuboid of ratio {r}"))
}

/// Each body's setup with the fitted key at `value` (Budden: one per ratio; a cubic die:
/// one), as the stability check reads it.
pub(crate) type BodySetups<'a> = &'a dyn Fn(f64) -> Vec<(Option<f64>, Params, InitialCondition)>;

/// Why `value` is left out for stability: the first body whose worst throw is past a limit.
pub(crate) fn past_stability_limit(
    setups: BodySetups,
    ranges: &RandomRanges,
    value: f64,
) -> Option<Exclusion> {
    setups(value).into_iter().find_map(|(ratio, p, ic)| {
        let reading = worst_throw_reading(&p, ranges, &ic);
        reading
            .exceeded()
            .then_some(Exclusion::PastStabilityLimit { ratio, reading })
    })
}

/// Refuses a fit whose every candidate is past the stability limit, before any roll,
/// naming the first candidate's reason and the key's value where the limit lies: the
/// stable value nearest the range, found over the key's allowed range (a scan of 256
/// values, then 60 halvings toward the range).
pub(crate) fn refuse_all_unstable(
    fit: &FitSpec,
    setups: BodySetups,
    ranges: &RandomRanges,
) -> Result<(), Error> {
    // Every candidate's reason, or None at the first stable one (the fit then goes on).
    let reasons: Option<Vec<Exclusion>> = fit
        .values()
        .into_iter()
        .map(|v| past_stability_limit(setups, ranges, v))
        .collect();
    let Some(first) = reasons.and_then(|r| r.into_iter().next()) else {
        return Ok(());
    };
    let stable = |v: f64| past_stability_limit(setups, ranges, v).is_none();
    let limits = fit.key.limits();
    let distance = |v: f64| (fit.low - v).max(v - fit.high).max(0.0);
    let scan: Vec<f64> = (0..=255)
        .map(|i| limits.min + (limits.max - limits.min) * f64::from(i) / 255.0)
        .collect();
    let nearest = scan
        .iter()
        .copied()
        .filter(|&v| stable(v))
        .min_by(|a, b| distance(*a).total_cmp(&distance(*b)));
    let edge = nearest.map(|good| {
        // Toward the range from the stable scan value: the last stable value before it.
        let toward = if good < fit.low { fit.low } else { fit.high };
        let (mut good, mut bad) = (good, toward);
        for _ in 0..60 {
            let mid = 0.5 * (good + bad);
            if stable(mid) {
                good = mid;
            } else {
                bad = mid;
            }
        }
        good
    });
    let unit = fit.key.unit();
    let limit = match edge {
        Some(v) => format!(
            "the stability limit is at {} = {} {unit}{}: fit a range on the stable side of it",
            fit.key.key,
            fmt_exact(round_significant(v, 4)),
            if v < fit.low {
                " (stable below it)"
            } else {
                " (stable above it)"
            }
        ),
        None => format!(
            "no value of {} from {} to {} {unit} is stable for every body thrown",
            fit.key.key,
            fmt_exact(limits.min),
            fmt_exact(limits.max)
        ),
    };
    Err(Error::Compare(format!(
        "every candidate of the fit, {} from {} to {} {unit}, is past the stability limit \
         ({} = {}: {first}); {limit}",
        fit.key.key,
        fmt_exact(fit.low),
        fmt_exact(fit.high),
        fit.key.key,
        fmt_exact(fit.low)
    )))
}

/// `x` to `digits` significant digits, so a limit found by halving reads 0.01234, not
/// 0.012340000000000001.
fn round_significant(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

/// The fit over the candidates no exclusion took out: `values` and `deviances` of every
/// candidate in order, `excluded` the left-out ones' values; the interval's `best_index`
/// points into the whole list. A fit with no candidate left is refused, naming each reason.
pub(crate) fn fit_over_kept(
    key: &str,
    values: &[f64],
    deviances: &[f64],
    excluded: &[Excluded],
) -> Result<Option<FitInterval>, Error> {
    let kept: Vec<usize> = (0..values.len())
        .filter(|&i| !excluded.iter().any(|e| e.value == values[i]))
        .collect();
    if kept.is_empty() && !values.is_empty() {
        let reasons: Vec<String> = excluded
            .iter()
            .take(3)
            .map(|e| format!("{key} = {}: {}", fmt_exact(e.value), e.why))
            .collect();
        let more = excluded.len().saturating_sub(3);
        return Err(Error::Compare(format!(
            "no candidate of the fit rests on enough throws within the model's limits, so it has \
             no best value: {}{}; throw more (--throws) or fit a range where the die settles on \
             a face and steps stably",
            reasons.join("; "),
            if more > 0 {
                format!("; and {more} more")
            } else {
                String::new()
            }
        )));
    }
    let pick = |v: &[f64]| kept.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    Ok(
        profile_interval(&pick(values), &pick(deviances)).map(|f| FitInterval {
            best_index: kept[f.best_index],
            ..f
        }),
    )
}

/// One setup value fitted to the data: `candidates` values evenly spaced over `[low, high]`.
#[derive(Debug, Clone, PartialEq)]
pub struct FitSpec {
    pub key: ScanKey,
    pub low: f64,
    pub high: f64,
    pub candidates: usize,
}

impl FitSpec {
    /// `KEY:LO:HI` (as a basin map's axis), e.g. `ground.friction:0.2:1.2`, with the
    /// number of candidates.
    pub fn parse(text: &str, candidates: usize) -> Result<FitSpec, Error> {
        let axis = Axis::parse(text, candidates.max(2))?;
        Ok(FitSpec {
            key: axis.key,
            low: axis.min,
            high: axis.max,
            candidates,
        })
    }

    /// Checks the fit: a key of the setup (not of the throw), a range inside the key's
    /// limits and increasing, and enough candidates.
    pub fn validate(&self) -> Result<(), Error> {
        let refuse = |m: String| Err(Error::Compare(m));
        if matches!(self.key.spec.role, Role::Initial | Role::Random) {
            return refuse(format!(
                "`{}` is part of the throw, which is drawn from the random ranges; fit a die, \
                 ground, world or integrator key",
                self.key.key
            ));
        }
        self.key.check(self.low)?;
        self.key.check(self.high)?;
        if self.low >= self.high {
            return refuse(format!(
                "`{}`: the range's low end {} is not below its high end {}",
                self.key.key,
                fmt_exact(self.low),
                fmt_exact(self.high)
            ));
        }
        if self.candidates < MIN_CANDIDATES {
            return refuse(format!(
                "a fit rolls at least {MIN_CANDIDATES} candidates, not {}",
                self.candidates
            ));
        }
        crate::limits::CANDIDATES.check(self.candidates as u64)
    }

    /// The candidate values, from `low` to `high`, exact at both ends (a range that ends
    /// at the preset's own value rolls that value itself).
    pub fn values(&self) -> Vec<f64> {
        let steps = (self.candidates - 1) as f64;
        (0..self.candidates)
            .map(|i| {
                if i + 1 == self.candidates {
                    self.high
                } else {
                    self.low + (self.high - self.low) * i as f64 / steps
                }
            })
            .collect()
    }
}

/// What to throw: `throws` throws of the dataset's protocol (with the setup as it is, or
/// once per candidate of a fit), drawn from the random ranges with `seed`.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareSpec {
    pub dataset: Dataset,
    pub throws: u64,
    pub seed: u64,
    pub fit: Option<FitSpec>,
}

impl CompareSpec {
    /// Checks the spec before anything is rolled.
    pub fn validate(&self) -> Result<(), Error> {
        let refuse = |m: String| Err(Error::Compare(m));
        if self.throws == 0 {
            return refuse("throw at least once".to_string());
        }
        if let Some(fit) = &self.fit {
            fit.validate()?;
        }
        Ok(())
    }

    /// Rolls in the whole experiment.
    pub fn total_rolls(&self) -> u64 {
        let candidates = self.fit.as_ref().map_or(1, |f| f.candidates as u64);
        self.throws
            .saturating_mul(self.dataset.dice_per_throw() as u64)
            .saturating_mul(candidates)
    }
}

/// The simulated throws of one setup.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Candidate {
    /// The fitted key's value (`None` without a fit).
    pub value: Option<f64>,
    /// Throws counted: every die of them settled on a face.
    pub throws: u64,
    /// Throws not counted because a die ended without a face (on an edge, not settled, or
    /// unstable), as a real experimenter would throw again.
    pub uncounted: u64,
    /// Counted throws by category.
    pub counts: Vec<u64>,
    /// The data against these throws (`None` with too few throws to test).
    pub test: Option<TwoSample>,
    /// Rolls whose start the stability check puts past its limit (their endings are the
    /// step's, not the model's).
    pub past_stability_limit: u64,
    /// The deviance over the fit's fixed groups (only when fitting).
    pub deviance: Option<f64>,
}

/// The whole comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    pub dataset: Experiment,
    /// The data as bundled, with its source.
    pub data: CountData,
    /// The data against a fair die's exact probabilities.
    pub data_against_fair: GoodnessOfFit,
    pub seed: u64,
    /// Throws asked for per candidate.
    pub throws: u64,
    /// The fitted key (`None` without a fit).
    pub key: Option<String>,
    pub candidates: Vec<Candidate>,
    /// The fit's best value and interval (`None` without a fit or its candidates).
    pub fit: Option<FitInterval>,
    /// The candidates the fit left out, each with its reason.
    pub excluded: Vec<Excluded>,
    /// The number the experiment is known for, real beside simulated (at the shown candidate).
    pub headline: Headline,
    /// Whether a cancel stopped it before the end.
    pub cancelled: bool,
    /// A player's counts: what a player asks of them ("Is my die fair?"); `None` for a
    /// historical experiment.
    pub fairness: Option<Fairness>,
}

/// The number an experiment is known for, the real dice's beside the simulated die's:
/// Weldon's share of 5s and 6s per die (0.33770, above a fair die's 1/3), Wolf's χ² of
/// his die against a fair one (270.96 and 94.19 on 5 dof).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Headline {
    /// What the number is, in words.
    pub name: String,
    pub real: f64,
    /// `None` when nothing simulated was counted.
    pub simulated: Option<f64>,
    /// A fair die's value, where it has one fixed number (Weldon's 1/3).
    pub fair: Option<f64>,
    /// Decimals the number is quoted with (a share to five, as Weldon's is; a χ² to two).
    #[serde(skip)]
    pub decimals: usize,
}

/// E.g. "share of 5s and 6s per die: real 0.33770, simulated 0.33206 (a fair die: 0.33333)".
impl std::fmt::Display for Headline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let d = self.decimals;
        write!(f, "{}: real {:.d$}, simulated ", self.name, self.real)?;
        match self.simulated {
            Some(s) => write!(f, "{s:.d$}")?,
            None => write!(f, "— (nothing counted)")?,
        }
        if let Some(fair) = self.fair {
            write!(f, " (a fair die: {fair:.d$})")?;
        }
        Ok(())
    }
}

impl Headline {
    /// The headline of `dataset` for the real `data` counts and the simulated `simulated`.
    pub fn of(experiment: Experiment, data: &[u64], simulated: Option<&[u64]>) -> Headline {
        let counted = |c: &&[u64]| c.iter().sum::<u64>() > 0;
        match experiment {
            Experiment::Historical(Dataset::Weldon) => {
                // Category k: k of the 12 dice showed a 5 or a 6.
                let share = |c: &[u64]| {
                    let fives_and_sixes: u64 = c.iter().enumerate().map(|(k, n)| k as u64 * n).sum();
                    fives_and_sixes as f64 / (12 * c.iter().sum::<u64>()) as f64
                };
                Headline {
                    name: "share of 5s and 6s per die".to_string(),
                    real: share(data),
                    simulated: simulated.filter(counted).map(share),
                    fair: Some(1.0 / 3.0),
                    decimals: 5,
                }
            }
            Experiment::Historical(Dataset::WolfRed | Dataset::WolfWhite) | Experiment::Player { .. } => {
                let fair = experiment.fair_probabilities();
                let against_fair = |c: &[u64]| goodness_of_fit(c, &fair).chi_square;
                Headline {
                    name: format!(
                        "χ² of the die's faces against a fair die ({} dof)",
                        fair.len() - 1
                    ),
                    real: against_fair(data),
                    simulated: simulated.filter(counted).map(against_fair),
                    fair: None,
                    decimals: 2,
                }
            }
        }
    }
}

/// The candidate a comparison shows: the fit's best, or without a fit the one rolled.
fn shown<'a>(fit: Option<&FitInterval>, candidates: &'a [Candidate]) -> Option<&'a Candidate> {
    match fit {
        Some(f) => candidates.get(f.best_index),
        None => candidates.first(),
    }
}

/// One row of the side-by-side table: a group of categories (pooled as the test pooled
/// them) in the data and in the simulation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// `"3"`, or `"10–12"` for a pooled group.
    pub category: String,
    pub data_count: u64,
    pub data_share: f64,
    pub data_interval: [f64; 2],
    pub simulated_count: u64,
    pub simulated_share: f64,
    pub simulated_interval: [f64; 2],
    /// The data's adjusted residual against the simulation.
    pub residual: f64,
}

impl Comparison {
    /// The candidate shown: the fit's best, or the one setup rolled.
    pub fn shown(&self) -> Option<&Candidate> {
        shown(self.fit.as_ref(), &self.candidates)
    }

    /// The rows of `candidate`'s table (none without a test).
    pub fn rows(&self, candidate: &Candidate) -> Vec<Row> {
        let Some(test) = &candidate.test else {
            return Vec::new();
        };
        let (n, m) = (test.data.iter().sum::<u64>(), test.simulated.iter().sum::<u64>());
        let share = |k: u64, n: u64| k as f64 / n as f64;
        test.groups
            .iter()
            .enumerate()
            .map(|(g, range)| {
                let names = &self.data.categories[range.clone()];
                let category = match names {
                    [one] => one.clone(),
                    [first, .., last] => format!("{first}–{last}"),
                    [] => String::new(),
                };
                let (a, b) = (test.data[g], test.simulated[g]);
                Row {
                    category,
                    data_count: a,
                    data_share: share(a, n),
                    data_interval: wilson_interval(a, n),
                    simulated_count: b,
                    simulated_share: share(b, m),
                    simulated_interval: wilson_interval(b, m),
                    residual: test.residuals[g],
                }
            })
            .collect()
    }

    /// The CSV's columns: the fitted key's value (named with its unit, when fitting), the
    /// group of categories as its first and last (whole numbers: counts of faces, or faces;
    /// a group of names that are not numbers as its text), both counts with their shares and
    /// intervals, the residual, the candidate's test, and its deviance (when fitting).
    pub fn csv_columns(&self) -> Vec<Column> {
        let mut columns = Vec::new();
        if let Some(key) = &self.key {
            let name = ScanKey::named(key).map_or_else(|_| key.replace('.', "_"), |k| k.column());
            columns.push(Column::real(name));
        }
        if self.numbered_categories() {
            columns.extend([
                Column::integer("category_first"),
                Column::integer("category_last"),
            ]);
        } else {
            columns.push(Column::text("category"));
        }
        columns.extend([
            Column::integer("data_count"),
            Column::real("data_share"),
            Column::real("data_low"),
            Column::real("data_high"),
            Column::integer("simulated_count"),
            Column::real("simulated_share"),
            Column::real("simulated_low"),
            Column::real("simulated_high"),
            Column::real("residual"),
            Column::real("chi_square"),
            Column::integer("dof"),
            Column::real("p_value"),
        ]);
        if self.candidates.iter().any(|c| c.deviance.is_some()) {
            columns.push(Column::real("deviance"));
        }
        if self.fit.is_some() {
            // The fit's 95 % interval on every row, and whether this candidate's own deviance
            // is within 3.84 of the lowest (docs/real-dice.md, "The fit's interval").
            columns.extend([
                Column::real("interval_low"),
                Column::real("interval_high"),
                Column::boolean("within_interval"),
            ]);
        }
        columns
    }

    /// Whether every category is named by a whole number (Weldon's counts, Wolf's faces).
    fn numbered_categories(&self) -> bool {
        self.data.categories.iter().all(|c| c.parse::<u64>().is_ok())
    }

    /// One row per candidate and group, in [`Comparison::csv_columns`]; reals with their point.
    pub fn write_csv(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        let columns = self.csv_columns();
        let mut csv = csv::Writer::from_writer(w);
        csv.write_record(columns.iter().map(|c| c.name.as_str()))
            .map_err(crate::csv_io)?;
        let real = |x: f64| Real(x).to_string();
        let with_deviance = columns.iter().any(|c| c.name == "deviance");
        for c in &self.candidates {
            let Some(test) = &c.test else { continue };
            for r in self.rows(c) {
                let mut cells: Vec<String> = Vec::with_capacity(columns.len());
                if self.key.is_some() {
                    cells.push(c.value.map_or(String::new(), real));
                }
                if self.numbered_categories() {
                    // `3`, or `10–12` for a group pooled by the test.
                    let (first, last) = r.category.split_once('–').unwrap_or((&r.category, &r.category));
                    cells.extend([first.to_string(), last.to_string()]);
                } else {
                    cells.push(r.category.clone());
                }
                cells.extend([
                    r.data_count.to_string(),
                    real(r.data_share),
                    real(r.data_interval[0]),
                    real(r.data_interval[1]),
                    r.simulated_count.to_string(),
                    real(r.simulated_share),
                    real(r.simulated_interval[0]),
                    real(r.simulated_interval[1]),
                    real(r.residual),
                    real(test.chi_square),
                    test.dof.to_string(),
                    real(test.p_value),
                ]);
                if with_deviance {
                    cells.push(c.deviance.map_or(String::new(), real));
                }
                if let Some(fit) = &self.fit {
                    let within = c.deviance.is_some_and(|d| d <= fit.candidate_limit())
                        && !self.excluded.iter().any(|e| Some(e.value) == c.value);
                    cells.extend([real(fit.low), real(fit.high), within.to_string()]);
                }
                csv.write_record(&cells).map_err(crate::csv_io)?;
            }
        }
        csv.flush()
    }
}

/// The throws of one candidate, fed with records in roll order; a throw counts once all
/// its dice are in.
struct ThrowTally {
    dataset: Experiment,
    faces: Vec<u8>,
    whole: bool,
    counted: u64,
    uncounted: u64,
    counts: Vec<u64>,
}

impl ThrowTally {
    fn new(dataset: Experiment, categories: usize) -> ThrowTally {
        ThrowTally {
            dataset,
            faces: Vec::with_capacity(dataset.dice_per_throw()),
            whole: true,
            counted: 0,
            uncounted: 0,
            counts: vec![0; categories],
        }
    }

    fn add(&mut self, records: &[RollRecord]) {
        for r in records {
            match r.outcome.face {
                Some(face) => self.faces.push(face),
                None => self.whole = false,
            }
            let dice = self.dataset.dice_per_throw() as u64;
            if r.id % dice == dice - 1 {
                if self.whole {
                    self.counts[self.dataset.category(&self.faces)] += 1;
                    self.counted += 1;
                } else {
                    self.uncounted += 1;
                }
                self.faces.clear();
                self.whole = true;
            }
        }
    }
}

/// How far [`run_comparison`] has got, after a chunk of rolls.
#[derive(Debug, Clone, Copy)]
pub struct Progress {
    /// Rolls done so far, over every candidate.
    pub done: u64,
    /// Rolls in the whole experiment.
    pub total: u64,
}

/// Throws the dataset's protocol with `params` (once, or once per candidate of the fit,
/// each with the same throws), tests each against the data and, when fitting, finds the
/// best value and its interval. `progress` is called after each chunk of rolls; setting
/// `cancel` stops it: without a fit the whole throws so far are kept, with a fit the
/// candidates rolled whole.
pub fn run_comparison(
    params: &Params,
    ranges: &RandomRanges,
    base: &InitialCondition,
    spec: &CompareSpec,
    options: &RunOptions,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(Progress),
) -> Result<Comparison, Error> {
    spec.validate()?;
    let thrown = Thrown {
        data: spec.dataset.data(),
        throws: spec.throws,
        seed: spec.seed,
        fit: spec.fit.as_ref(),
    };
    compare_thrown(params, ranges, base, &thrown, options, cancel, progress)
}

/// What a comparison holds against what: the counts (and the protocol they were thrown by),
/// the simulated throws per candidate, their seed and the fit.
struct Thrown<'a> {
    data: CountData,
    throws: u64,
    seed: u64,
    fit: Option<&'a FitSpec>,
}

impl Thrown<'_> {
    /// The values rolled: the fit's candidates, or the setup as it is.
    fn values(&self) -> Vec<Option<f64>> {
        match self.fit {
            Some(fit) => fit.values().into_iter().map(Some).collect(),
            None => vec![None],
        }
    }
}

/// The one comparison loop, for a historical experiment's counts and a player's alike.
fn compare_thrown(
    params: &Params,
    ranges: &RandomRanges,
    base: &InitialCondition,
    thrown: &Thrown,
    options: &RunOptions,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(Progress),
) -> Result<Comparison, Error> {
    let experiment = thrown.data.dataset;
    let data = &thrown.data;
    let dice = experiment.dice_per_throw() as u64;
    let rolls_each = thrown.throws * dice;
    let values = thrown.values();
    let total = rolls_each.saturating_mul(values.len() as u64);
    // Every candidate is checked before the first is rolled.
    let setups = values
        .into_iter()
        .map(|value| {
            let (mut p, mut ic) = (*params, *base);
            if let (Some(fit), Some(v)) = (thrown.fit, value) {
                fit.key.check(v)?;
                fit.key.set(&mut p, &mut ic, v);
            }
            // The check every drawn setup gets, so a candidate is refused in roll's words.
            check_drawn_setup(&p, ranges, &ic)?;
            Ok((value, p, ic))
        })
        .collect::<Result<Vec<_>, Error>>()?;
    let die_at = |v: f64| {
        let (mut p, mut ic) = (*params, *base);
        if let Some(fit) = thrown.fit {
            fit.key.set(&mut p, &mut ic, v);
        }
        vec![(None, p, ic)]
    };
    if let Some(fit) = thrown.fit {
        refuse_all_unstable(fit, &die_at, ranges)?;
    }
    let groups = fit_groups(&data.counts);
    let mut candidates = Vec::new();
    let mut cancelled = false;
    for (i, (value, params, base)) in setups.into_iter().enumerate() {
        let rolls = Rolls::Random {
            ranges,
            base: &base,
            seed: thrown.seed,
            first: 0,
            count: rolls_each,
        };
        let mut tally = ThrowTally::new(experiment, data.counts.len());
        let mut done = i as u64 * rolls_each;
        let run = stream_batch(&params, &rolls, options, cancel, &mut |records| {
            tally.add(records);
            done += records.len() as u64;
            progress(Progress { done, total });
            Ok(())
        })?;
        if run.cancelled {
            cancelled = true;
            if thrown.fit.is_some() {
                break;
            }
        }
        candidates.push(Candidate {
            value,
            throws: tally.counted,
            uncounted: tally.uncounted,
            test: two_sample(&data.counts, &tally.counts),
            past_stability_limit: run.past_stability_limit,
            deviance: thrown.fit.map(|_| deviance(&data.counts, &tally.counts, &groups)),
            counts: tally.counts,
        });
        if cancelled {
            break;
        }
    }
    // One list: past the stability limit first (its counts are not the model's), then too
    // few counted.
    let excluded: Vec<Excluded> = candidates
        .iter()
        .filter_map(|c| {
            let value = c.value?;
            let why = past_stability_limit(&die_at, ranges, value)
                .or_else(|| Exclusion::of_counts(c.throws, c.throws + c.uncounted))?;
            Some(Excluded { value, why })
        })
        .collect();
    let fit = match thrown.fit {
        Some(fit) => {
            let values: Vec<f64> = candidates.iter().filter_map(|c| c.value).collect();
            let deviances: Vec<f64> = candidates.iter().filter_map(|c| c.deviance).collect();
            match fit_over_kept(&fit.key.key, &values, &deviances, &excluded) {
                // A cancelled fit keeps what its whole candidates say, if anything.
                Err(_) if cancelled => None,
                result => result?,
            }
        }
        None => None,
    };
    let shown = shown(fit.as_ref(), &candidates);
    let headline = Headline::of(experiment, &data.counts, shown.map(|c| c.counts.as_slice()));
    Ok(Comparison {
        headline,
        dataset: experiment,
        data_against_fair: goodness_of_fit(&data.counts, &experiment.fair_probabilities()),
        data: data.clone(),
        seed: thrown.seed,
        throws: thrown.throws,
        key: thrown.fit.map(|f| f.key.key.clone()),
        candidates,
        fit,
        excluded,
        cancelled,
        fairness: None,
    })
}

/// A player's counts against the simulated die: `throws` simulated rolls (once, or once per
/// candidate of the fit, each with the same rolls), drawn from the random ranges with `seed`.
#[derive(Debug, Clone, PartialEq)]
pub struct CountsSpec {
    pub counts: PlayerCounts,
    pub throws: u64,
    pub seed: u64,
    pub fit: Option<FitSpec>,
}

/// The simulated rolls a player's counts are held against unless told otherwise: at least
/// ten thousand (a simulated share then carries an error of about 0.2 points on a d20, small
/// beside a player's hundreds of rolls), and never fewer than the player rolled.
pub const DEFAULT_COUNTS_THROWS: u64 = 10_000;

impl CountsSpec {
    /// The default simulated rolls for these counts ([`DEFAULT_COUNTS_THROWS`]).
    pub fn default_throws(counts: &PlayerCounts) -> u64 {
        counts.total().max(DEFAULT_COUNTS_THROWS)
    }

    /// Checks the spec before anything is rolled: the counts of the die `numbers` names.
    pub fn validate(&self, numbers: &[u8]) -> Result<(), Error> {
        if self.counts.numbers != numbers {
            return Err(Error::Compare(format!(
                "the counts are of a {} ({} numbers), the die rolled shows {}",
                self.counts.die,
                self.counts.numbers.len(),
                numbers.len()
            )));
        }
        if self.throws == 0 {
            return Err(Error::Compare("throw at least once".to_string()));
        }
        if let Some(fit) = &self.fit {
            fit.validate()?;
        }
        Ok(())
    }

    /// Rolls in the whole comparison.
    pub fn total_rolls(&self) -> u64 {
        let candidates = self.fit.as_ref().map_or(1, |f| f.candidates as u64);
        self.throws.saturating_mul(candidates)
    }
}

/// What a player asks of their counts ("Is my die fair?", docs/real-dice.md).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fairness {
    /// The die, as players name it (`d20`).
    pub die: String,
    /// Whether the counts are consistent with a fair die: the χ² test against equal shares
    /// ([`Comparison::data_against_fair`]) at 5 %.
    pub consistent_with_fair: bool,
    /// Each face's adjusted residual against a fair die, `(O − n/k)/√(n·(1/k)·(1 − 1/k))`:
    /// about standard normal for a fair die, so beyond ±2 a face stands out.
    pub residuals_against_fair: Vec<f64>,
    /// The simulated die (at the shown candidate) against a fair die: its χ² and p.
    pub simulated_against_fair: Option<GoodnessOfFit>,
    /// The rolls a player needs for the χ² test against a fair die to detect the simulated
    /// die's flaw at 80 % power and 5 % ([`FaceTally::rolls_to_detect`] of the simulated
    /// counts); `None` when the simulated die shows no flaw beyond its own noise.
    pub rolls_to_detect: Option<u64>,
    /// With a fit whose range holds 0 (a flaw's size of none): whether 0, "no flaw", lies
    /// inside the fit's 95 % interval: a fair die then explains the counts too.
    pub no_flaw_inside: Option<bool>,
}

/// A player's counts thrown against the simulated die (fair, or with the flaw its setup
/// states), and with a fit, the flaw's size fitted to them: the comparison loop of the
/// historical experiments ([`run_comparison`]) with one die a throw, and what a player asks
/// of it ([`Fairness`]).
pub fn run_counts(
    params: &Params,
    ranges: &RandomRanges,
    base: &InitialCondition,
    spec: &CountsSpec,
    options: &RunOptions,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(Progress),
) -> Result<Comparison, Error> {
    let numbers = params.die.face_numbers();
    spec.validate(numbers)?;
    let counts = &spec.counts;
    let thrown = Thrown {
        data: CountData {
            dataset: Experiment::Player { numbers },
            source: match counts.notes.as_str() {
                "" => format!(
                    "{} rolls of a {} from {}",
                    counts.total(),
                    counts.die,
                    counts.origin
                ),
                notes => format!(
                    "{} rolls of a {} from {}: {notes}",
                    counts.total(),
                    counts.die,
                    counts.origin
                ),
            },
            categories: numbers.iter().map(u8::to_string).collect(),
            counts: counts.counts.clone(),
        },
        throws: spec.throws,
        seed: spec.seed,
        fit: spec.fit.as_ref(),
    };
    let mut comparison = compare_thrown(params, ranges, base, &thrown, options, cancel, progress)?;
    let n = counts.total() as f64;
    let share = 1.0 / numbers.len() as f64;
    let sd = (n * share * (1.0 - share)).sqrt();
    let simulated = comparison.shown().map(|c| {
        let mut tally = FaceTally::new(numbers);
        tally.counts.clone_from(&c.counts);
        tally
    });
    let no_flaw_inside = match (&spec.fit, &comparison.fit) {
        (Some(f), Some(interval)) if f.low <= 0.0 && 0.0 <= f.high => {
            Some(interval.low <= 0.0 && 0.0 <= interval.high)
        }
        _ => None,
    };
    comparison.fairness = Some(Fairness {
        die: counts.die.clone(),
        consistent_with_fair: comparison.data_against_fair.p_value >= crate::stats::TEST_LEVEL,
        residuals_against_fair: counts
            .counts
            .iter()
            .map(|&c| (c as f64 - n * share) / sd)
            .collect(),
        simulated_against_fair: simulated
            .as_ref()
            .filter(|t| t.total() > 0)
            .map(|t| goodness_of_fit(&t.counts, &thrown.data.dataset.fair_probabilities())),
        rolls_to_detect: simulated.and_then(|t| t.rolls_to_detect()),
        no_flaw_inside,
    });
    Ok(comparison)
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_physics::Status;

    fn record(id: u64, face: Option<u8>) -> RollRecord {
        let status = if face.is_some() {
            Status::Settled
        } else {
            Status::Timeout
        };
        RollRecord::ended(id, status, face)
    }

    #[test]
    fn a_throw_counts_when_all_its_dice_are_in() {
        let mut t = ThrowTally::new(Experiment::Historical(Dataset::Weldon), 13);
        // Throw 0: five 5s and 6s; throw 1: one die without a face.
        let first = [5, 6, 5, 6, 5, 1, 2, 3, 4, 1, 2, 3];
        let records: Vec<RollRecord> = (0..24)
            .map(|i| match i {
                i if i < 12 => record(i, Some(first[i as usize])),
                13 => record(i, None),
                _ => record(i, Some(6)),
            })
            .collect();
        // Fed in two uneven chunks, as a batch hands them on.
        t.add(&records[..7]);
        t.add(&records[7..]);
        assert_eq!((t.counted, t.uncounted), (1, 1));
        assert_eq!(t.counts[5], 1);
        assert_eq!(t.counts.iter().sum::<u64>(), 1);
        let mut wolf = ThrowTally::new(Experiment::Historical(Dataset::WolfRed), 6);
        wolf.add(&[record(0, Some(3)), record(1, None), record(2, Some(3))]);
        assert_eq!((wolf.counted, wolf.uncounted, wolf.counts[2]), (2, 1, 2));
    }

    #[test]
    fn a_candidate_needs_half_its_throws_on_a_face_and_a_fit_needs_a_candidate() {
        // The red team's corner-radius fit: 0.95 won with 9 of 300 throws counted.
        assert_eq!(
            Exclusion::of_counts(9, 300),
            Some(Exclusion::TooFewCounted {
                counted: 9,
                thrown: 300,
                needed: 150
            })
        );
        assert_eq!(Exclusion::of_counts(150, 300), None);
        assert_eq!(Exclusion::of_counts(0, 1).map(|_| ()), Some(()));
        assert_eq!(Exclusion::of_counts(1, 1), None);
        // Deviances that fall to 0 where nothing was counted: the fit keeps only what rests
        // on throws, and its best value is the kept minimum, indexed in the whole list.
        let values = [0.0, 0.25, 0.5, 0.75, 1.0];
        let deviances = [4.0, 1.0, 0.5, 1.0, 0.0];
        let left_out = |v: f64| Excluded {
            value: v,
            why: Exclusion::of_counts(3, 300).unwrap(),
        };
        let fit = fit_over_kept("k", &values, &deviances, &[left_out(1.0)])
            .unwrap()
            .unwrap();
        assert_eq!(fit.best_index, 2);
        assert!(
            (fit.best - 0.5).abs() < 0.05 && fit.best_deviance > 0.0,
            "{fit:?}"
        );
        let all: Vec<Excluded> = values.iter().map(|&v| left_out(v)).collect();
        let e = fit_over_kept("k", &values, &deviances, &all)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("no candidate of the fit rests on enough throws"),
            "{e}"
        );
        assert!(
            e.contains("k = 0.25: 3 of 300 throws ended on a face, fewer than the 150"),
            "{e}"
        );
        assert!(e.contains("and 2 more"), "{e}");
    }

    #[test]
    fn candidates_span_the_range_and_bad_fits_are_refused() {
        let fit = |key: &str, low: f64, high: f64, candidates: usize| CompareSpec {
            dataset: Dataset::Weldon,
            throws: 10,
            seed: 1,
            fit: Some(FitSpec {
                key: ScanKey::parse(key).unwrap(),
                low,
                high,
                candidates,
            }),
        };
        let spec = fit("ground.friction", 0.2, 1.2, 21);
        spec.validate().unwrap();
        let values = spec.fit.as_ref().unwrap().values();
        assert_eq!((values.len(), values[0], values[20]), (21, 0.2, 1.2));
        assert!((values[10] - 0.7).abs() < 1e-12);
        assert_eq!(spec.total_rolls(), 21 * 10 * 12);
        let e = fit("ground.friction", 0.2, 1.2, 19).validate().unwrap_err();
        assert!(e.to_string().contains("at least 20 candidates"), "{e}");
        let e = fit("ground.friction", 1.2, 0.2, 21).validate().unwrap_err();
        assert!(e.to_string().contains("not below"), "{e}");
        let e = fit("ground.friction", 0.2, 9.0, 21).validate().unwrap_err();
        assert!(e.to_string().contains("ground.friction"), "{e}");
        let e = fit("initial.height", 2.0, 9.0, 21).validate().unwrap_err();
        assert!(e.to_string().contains("drawn from the random ranges"), "{e}");
    }
}
