//! Several setup values fitted at once to two experiments together: Budden's calibration
//! ratios ([`compare_budden`](crate::compare_budden)) and the shaved die at the cut the
//! experiment measured ([`compare_shaved`](crate::compare_shaved)).
//!
//! The values form a grid, each key's evenly spaced over its range as a one-key fit's
//! candidates are; every grid point throws the same throws (common random numbers), so the
//! points differ by their values alone. The two experiments are independent samples, so
//! their likelihoods multiply and their deviances add: the joint deviance of a point is
//! Budden's deviance summed over his calibration ratios plus the shaved die's. The 95 %
//! region holds every point within the χ² quantile of `k` degrees of freedom (`k` keys
//! fitted) of the lowest (docs/real-dice.md, "A fit of several keys").

use crate::Error;
use crate::batch::RunOptions;
use crate::compare::{Exclusion, Progress, past_stability_limit};
use crate::compare_budden::{
    DEFAULT_CALIBRATE_ON, RatioThrows, body_at, hand_throw, ratio_deviance, throw_ratio,
    unapplied as budden_unapplied,
};
use crate::compare_shaved::{ShavedSpec, drop_throw, run_shaved, setups as shaved_setups};
use crate::data_file::Column;
use crate::limits::{CANDIDATES, EXPERIMENT_ROLLS};
use crate::real_data::{budden, shaved_die};
use dicesim_physics::{InitialCondition, Params};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::number::{Real, fmt_exact};
use dicesim_setup::random::{RandomRanges, check_drawn_setup};
use dicesim_setup::registry::Role;
use serde::Serialize;
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::sync::atomic::AtomicBool;

/// The fewest values a key of a grid takes: three, the fewest that can show a valley (a
/// lowest point with a higher one on each side).
pub const MIN_VALUES_PER_KEY: usize = 3;

/// The values a key of a grid takes unless told otherwise: five, so three keys make 125
/// points, each a whole rolling of both experiments.
pub const DEFAULT_VALUES_PER_KEY: usize = 5;

/// The cut the shaved-die experiment measured, the one the joint fit throws.
pub const MEASURED_CUT: f64 = 0.03;

/// One key of a grid: `values` values evenly spaced from `low` to `high`, exact at both ends.
#[derive(Debug, Clone, PartialEq)]
pub struct GridKey {
    pub key: ScanKey,
    pub low: f64,
    pub high: f64,
    pub values: usize,
}

impl GridKey {
    /// `KEY:LO:HI` (the key's values `default_values`) or `KEY:LO:HI:N`, e.g.
    /// `ground.restitution:0.2:0.6:5`. The key, both ends and the count are checked by
    /// [`JointSpec::validate`], which names the key.
    pub fn parse(text: &str, default_values: usize) -> Result<GridKey, Error> {
        let parts: Vec<&str> = text.split(':').collect();
        let bad = |m: String| Error::Compare(format!("--fit {text}: {m}"));
        let (key, low, high, values) = match parts[..] {
            [key, low, high] => (key, low, high, None),
            [key, low, high, n] => (key, low, high, Some(n)),
            _ => return Err(bad("expected KEY:LO:HI or KEY:LO:HI:N".to_string())),
        };
        let key = ScanKey::parse(key.trim()).map_err(|e| bad(e.to_string()))?;
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| bad(format!("`{s}` is not a number")))
        };
        let values = match values {
            Some(n) => n
                .trim()
                .parse::<usize>()
                .map_err(|_| bad(format!("`{n}` is not a count of values")))?,
            None => default_values,
        };
        Ok(GridKey {
            key,
            low: number(low)?,
            high: number(high)?,
            values,
        })
    }

    /// The key's values, from `low` to `high`, exact at both ends.
    pub fn grid_values(&self) -> Vec<f64> {
        let steps = (self.values.max(2) - 1) as f64;
        (0..self.values)
            .map(|i| {
                if i + 1 == self.values {
                    self.high
                } else {
                    self.low + (self.high - self.low) * i as f64 / steps
                }
            })
            .collect()
    }

    /// The key as typed back: `ground.restitution:0.2:0.6:5`.
    pub fn text(&self) -> String {
        format!(
            "{}:{}:{}:{}",
            self.key.key,
            fmt_exact(self.low),
            fmt_exact(self.high),
            self.values
        )
    }

    /// Why this key cannot be one of a joint fit's (`None` where it can): a key of the
    /// setup both experiments apply, a range inside its limits, increasing, and at least
    /// [`MIN_VALUES_PER_KEY`] values.
    fn refusal(&self) -> Option<String> {
        let key = &self.key.key;
        if matches!(self.key.spec.role, Role::Initial | Role::Random) {
            return Some(format!(
                "`{key}` is part of the throw, which each experiment draws by its own protocol; \
                 fit a ground, world or integrator key, or die.corner_radius"
            ));
        }
        if let Some(why) = budden_unapplied(key) {
            return Some(format!("`{key}` does not reach Budden's throws: {why}"));
        }
        for v in [self.low, self.high] {
            if let Err(e) = self.key.check(v) {
                return Some(e.to_string());
            }
        }
        if self.values < 2 || self.low == self.high {
            return Some(format!(
                "`{key}` takes one value ({}): a fitted key needs at least {MIN_VALUES_PER_KEY} \
                 values over a range; set a fixed value with --set {key}=…",
                fmt_exact(self.low)
            ));
        }
        if self.low > self.high {
            return Some(format!(
                "`{key}`: the range's low end {} is not below its high end {}",
                fmt_exact(self.low),
                fmt_exact(self.high)
            ));
        }
        if self.values < MIN_VALUES_PER_KEY {
            return Some(format!(
                "`{key}` takes {} values; a key of a grid takes at least {MIN_VALUES_PER_KEY}, \
                 the fewest that can show a valley",
                self.values
            ));
        }
        None
    }
}

/// What a joint fit throws: at every point of the grid of `keys`, Budden's calibration
/// ratios `calibrate_on` as often as he threw each, and the shaved die at
/// [`MEASURED_CUT`] `shaved_throws` times paired with the uncut die, all from `seed`.
#[derive(Debug, Clone, PartialEq)]
pub struct JointSpec {
    pub keys: Vec<GridKey>,
    pub seed: u64,
    pub shaved_throws: u64,
    pub calibrate_on: Vec<f64>,
}

impl JointSpec {
    /// Checks the fit before anything is rolled; every refusal names the key or option.
    pub fn validate(&self) -> Result<(), Error> {
        let refuse = |m: String| Err(Error::Compare(m));
        if self.keys.len() < 2 {
            return refuse(format!(
                "a joint fit takes two or more keys (--fit KEY:LO:HI, once per key), not {}; \
                 one key is fitted by `compare budden --fit` or `compare weldon --fit`",
                self.keys.len()
            ));
        }
        for (i, k) in self.keys.iter().enumerate() {
            if let Some(why) = k.refusal() {
                return refuse(format!("--fit {}: {why}", k.text()));
            }
            if let Some(other) = self.keys[..i].iter().find(|o| o.key.overlaps(&k.key.key)) {
                return refuse(format!(
                    "--fit {}: `{}` is fitted twice (also as `{}`)",
                    k.text(),
                    k.key.key,
                    other.key.key
                ));
            }
        }
        let points = self
            .keys
            .iter()
            .fold(1u64, |n, k| n.saturating_mul(k.values as u64));
        if points > CANDIDATES.max {
            let sizes: Vec<String> = self
                .keys
                .iter()
                .map(|k| format!("{} ({})", k.values, k.key.key))
                .collect();
            return Err(CANDIDATES.refuse(format!("a grid of {points} points ({})", sizes.join(" × "))));
        }
        if self.shaved_throws == 0 {
            return refuse("throw at least once".to_string());
        }
        let rows = budden().0;
        if self.calibrate_on.is_empty() {
            return refuse("--calibrate-on: name at least one ratio to fit on".to_string());
        }
        for (i, &r) in self.calibrate_on.iter().enumerate() {
            if !rows.iter().any(|row| row.ratio == r) || self.calibrate_on[..i].contains(&r) {
                return refuse(format!(
                    "--calibrate-on: {r} is not one of Budden's ratios x/y, or is named twice"
                ));
            }
        }
        EXPERIMENT_ROLLS.check(self.total_rolls())
    }

    /// Every point of the grid, the first key's values varying slowest.
    pub fn points(&self) -> Vec<Vec<f64>> {
        self.keys.iter().fold(vec![Vec::new()], |points, k| {
            points
                .iter()
                .flat_map(|p| {
                    k.grid_values().into_iter().map(move |v| {
                        let mut q = p.clone();
                        q.push(v);
                        q
                    })
                })
                .collect()
        })
    }

    /// Rolls of one point: Budden's throws of each calibration ratio, and every shaved-die
    /// throw twice (uncut and cut).
    fn rolls_per_point(&self) -> u64 {
        let budden: u64 = budden()
            .0
            .iter()
            .filter(|r| self.calibrate_on.contains(&r.ratio))
            .map(|r| r.throws)
            .sum();
        budden.saturating_add(self.shaved_throws.saturating_mul(2))
    }

    /// Rolls in the whole fit.
    pub fn total_rolls(&self) -> u64 {
        let points = self
            .keys
            .iter()
            .fold(1u64, |n, k| n.saturating_mul(k.values as u64));
        points.saturating_mul(self.rolls_per_point())
    }

    /// The deviance rise that bounds the 95 % region: the χ² quantile of `k` degrees of
    /// freedom, `k` the keys fitted (5.99 for two, 7.81 for three).
    pub fn region_rise(&self) -> f64 {
        region_rise(self.keys.len())
    }

    /// `params` and `base` with every key at its value at `point`.
    fn at(&self, params: &Params, base: &InitialCondition, point: &[f64]) -> (Params, InitialCondition) {
        let (mut p, mut ic) = (*params, *base);
        for (k, &v) in self.keys.iter().zip(point) {
            k.key.set(&mut p, &mut ic, v);
        }
        (p, ic)
    }

    /// The point in words: `ground.restitution = 0.4, ground.table_mass = 300`.
    pub fn point_text(&self, point: &[f64]) -> String {
        self.keys
            .iter()
            .zip(point)
            .map(|(k, v)| format!("{} = {}", k.key.key, fmt_exact(*v)))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// The 95 % quantile of χ² with `k` degrees of freedom: the deviance rise of a 95 % region
/// of `k` fitted values (Wilks).
pub fn region_rise(k: usize) -> f64 {
    ChiSquared::new(k as f64)
        .expect("at least one degree of freedom")
        .inverse_cdf(0.95)
}

/// The shaved die at the measured cut at one point: the paired bias, its interval and the
/// data's against it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ShavedAtPoint {
    /// Pairs counted (both dice on a face) and not.
    pub throws: u64,
    pub uncounted: u64,
    pub bias: f64,
    pub interval: [f64; 2],
    /// `(b_data − b_sim)/√(σ_data² + σ_sim²)`: its square is this experiment's deviance.
    pub z: f64,
    /// Throws whose start the stability check puts past its limit for the cut die.
    pub past_stability_limit: u64,
}

/// One grid point: its values, what each experiment measured there and the deviances.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridPoint {
    pub values: Vec<f64>,
    /// Budden's calibration ratios thrown here (empty when left out before rolling).
    pub ratios: Vec<RatioThrows>,
    pub shaved: Option<ShavedAtPoint>,
    /// Budden's deviance summed over the calibration ratios.
    pub budden_deviance: Option<f64>,
    /// The shaved die's deviance, z².
    pub shaved_deviance: Option<f64>,
    /// Their sum: the joint deviance.
    pub deviance: Option<f64>,
    /// Why the fit left the point out, if it did.
    pub excluded: Option<Exclusion>,
}

impl GridPoint {
    fn kept_deviance(&self) -> Option<f64> {
        self.deviance.filter(|_| self.excluded.is_none())
    }
}

/// The whole joint fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointComparison {
    /// `"joint"`.
    pub dataset: &'static str,
    pub sources: Vec<String>,
    pub assumptions: Vec<String>,
    pub seed: u64,
    pub keys: Vec<String>,
    pub calibrate_on: Vec<f64>,
    pub cut: f64,
    pub shaved_throws: u64,
    pub points: Vec<GridPoint>,
    /// The point of the lowest joint deviance among those kept (an index into `points`).
    pub best: Option<usize>,
    /// The lowest joint deviance, the rise that bounds the region, and the region's points.
    pub lowest_deviance: Option<f64>,
    pub region_rise: f64,
    pub region: Vec<usize>,
    /// Per key, the lowest and highest value of a point in the region, and whether the
    /// region reaches the key's range end there (the data allow values beyond it).
    pub region_ranges: Vec<KeyRange>,
    pub cancelled: bool,
}

/// A key's values over the 95 % region.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KeyRange {
    pub key: String,
    pub low: f64,
    pub high: f64,
    pub low_open: bool,
    pub high_open: bool,
}

impl JointComparison {
    pub fn best_point(&self) -> Option<&GridPoint> {
        self.best.map(|i| &self.points[i])
    }

    pub fn in_region(&self, index: usize) -> bool {
        self.region.contains(&index)
    }

    /// The CSV's columns: each key's value, the throws behind each experiment, both
    /// deviances and their sum, whether the point is in the 95 % region, and why it was left
    /// out.
    pub fn csv_columns(&self) -> Vec<Column> {
        let mut columns: Vec<Column> = self
            .keys
            .iter()
            .map(|k| Column::real(ScanKey::named(k).map_or_else(|_| k.replace('.', "_"), |s| s.column())))
            .collect();
        columns.extend([
            Column::integer("budden_throws"),
            Column::integer("budden_uncounted"),
            Column::real("budden_deviance"),
            Column::integer("shaved_throws"),
            Column::integer("shaved_uncounted"),
            Column::real("shaved_bias"),
            Column::real("shaved_bias_low"),
            Column::real("shaved_bias_high"),
            Column::real("shaved_z"),
            Column::real("shaved_deviance"),
            Column::real("deviance"),
            Column::boolean("in_region"),
            Column::boolean("best"),
            Column::text("left_out"),
        ]);
        columns
    }

    /// One row per grid point, in [`JointComparison::csv_columns`]; cells a point left out
    /// before rolling has no value for are empty.
    pub fn write_csv(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        let mut csv = csv::Writer::from_writer(w);
        csv.write_record(self.csv_columns().iter().map(|c| c.name.as_str()))
            .map_err(crate::csv_io)?;
        let real = |x: f64| Real(x).to_string();
        let opt = |x: Option<f64>| x.map_or(String::new(), real);
        for (i, p) in self.points.iter().enumerate() {
            let mut cells: Vec<String> = p.values.iter().map(|&v| real(v)).collect();
            let thrown = !p.ratios.is_empty();
            let (bt, bu) = p
                .ratios
                .iter()
                .fold((0, 0), |(t, u), r| (t + r.throws, u + r.uncounted));
            cells.extend([
                if thrown { bt.to_string() } else { String::new() },
                if thrown { bu.to_string() } else { String::new() },
                opt(p.budden_deviance),
            ]);
            match &p.shaved {
                Some(s) => cells.extend([
                    s.throws.to_string(),
                    s.uncounted.to_string(),
                    real(s.bias),
                    real(s.interval[0]),
                    real(s.interval[1]),
                    real(s.z),
                ]),
                None => cells.extend(std::iter::repeat_n(String::new(), 6)),
            }
            cells.extend([
                opt(p.shaved_deviance),
                opt(p.deviance),
                self.in_region(i).to_string(),
                (self.best == Some(i)).to_string(),
                p.excluded.map_or(String::new(), |e| e.to_string()),
            ]);
            csv.write_record(&cells).map_err(crate::csv_io)?;
        }
        csv.flush()
    }
}

/// The sentences every output states: each experiment's own, and how they are joined.
pub fn assumptions() -> Vec<String> {
    let mut all = crate::compare_budden::assumptions();
    all.extend(crate::compare_shaved::assumptions());
    all.push(
        "the joint deviance: Budden's G² summed over his calibration ratios plus the shaved die's z² at 3 % \
         (independent experiments: their likelihoods multiply, their deviances add)"
            .to_string(),
    );
    all
}

/// Throws both experiments at every point of the grid, each point with the same throws,
/// and finds the point of the lowest joint deviance and the 95 % region. A point past the
/// stability limit for any body thrown is left out before it is rolled; one that counts
/// fewer than half its throws of any ratio, or pairs of the shaved die, after. `progress`
/// is called after each chunk; `cancel` keeps the points rolled whole.
pub fn run_joint(
    params: &Params,
    ranges: &RandomRanges,
    base: &InitialCondition,
    spec: &JointSpec,
    options: &RunOptions,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(Progress),
) -> Result<JointComparison, Error> {
    spec.validate()?;
    let hand = hand_throw(ranges);
    let (rows, budden_source) = budden();
    let calibration: Vec<(usize, f64, u64)> = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| spec.calibrate_on.contains(&r.ratio))
        .map(|(i, r)| (i, r.ratio, r.throws))
        .collect();
    let shaved = ShavedSpec {
        cuts: vec![MEASURED_CUT],
        throws: spec.shaved_throws,
        seed: spec.seed,
    };
    let drop = drop_throw(spec.seed);
    let points = spec.points();
    // Every point's bodies, checked before the first roll; the error names the point.
    let mut stable_from = Vec::with_capacity(points.len());
    for point in &points {
        let (p, ic) = spec.at(params, base, point);
        let context = |e: Error| Error::Compare(format!("at {}: {e}", spec.point_text(point)));
        let cuboids: Vec<(Option<f64>, Params, InitialCondition)> = calibration
            .iter()
            .map(|&(_, ratio, _)| {
                let (cp, cic) = body_at(&p, &ic, None, ratio, f64::NAN);
                (Some(ratio), cp, cic)
            })
            .collect();
        for (ratio, cp, cic) in &cuboids {
            check_drawn_setup(cp, &hand, cic).map_err(|e| {
                context(Error::Compare(format!(
                    "the cuboid of ratio {}: {e}",
                    ratio.unwrap_or(f64::NAN)
                )))
            })?;
        }
        let dice = shaved_setups(&p, &ic, &shaved).map_err(context)?;
        let die_bodies: Vec<(Option<f64>, Params, InitialCondition)> =
            dice.into_iter().map(|d| (None, d, ic)).collect();
        let why = past_stability_limit(&|_| cuboids.clone(), &hand, 0.0)
            .or_else(|| past_stability_limit(&|_| die_bodies.clone(), &drop, 0.0));
        stable_from.push(why);
    }
    if stable_from.iter().all(Option::is_some) {
        let first = stable_from[0].expect("every point has a reason");
        return Err(Error::Compare(format!(
            "every point of the grid is past the stability limit, so the fit has no best point; \
             at {}: {first}",
            spec.point_text(&points[0])
        )));
    }
    let total = spec.total_rolls();
    let mut done = 0u64;
    let mut results: Vec<GridPoint> = Vec::with_capacity(points.len());
    let mut cancelled = false;
    let (shaved_row, shaved_source) = {
        let (rows, source) = shaved_die();
        (rows.into_iter().find(|r| r.cut == MEASURED_CUT), source)
    };
    debug_assert!(shaved_row.is_some(), "the data measure the 3 % cut");
    'points: for (point, unstable) in points.iter().zip(stable_from) {
        if let Some(why) = unstable {
            done += spec.rolls_per_point();
            progress(Progress { done, total });
            results.push(GridPoint {
                values: point.clone(),
                ratios: Vec::new(),
                shaved: None,
                budden_deviance: None,
                shaved_deviance: None,
                deviance: None,
                excluded: Some(why),
            });
            continue;
        }
        let (p, ic) = spec.at(params, base, point);
        let mut ratios = Vec::with_capacity(calibration.len());
        for &(i, ratio, throws) in &calibration {
            let body = body_at(&p, &ic, None, ratio, f64::NAN);
            let thrown = throw_ratio(
                body,
                &hand,
                &[spec.seed],
                (i, ratio),
                throws,
                options,
                cancel,
                |n| {
                    done += n;
                    progress(Progress { done, total });
                },
            )?;
            match thrown {
                Some(t) => ratios.push(t),
                None => {
                    cancelled = true;
                    break 'points;
                }
            }
        }
        let start = done;
        let run = run_shaved(&p, &ic, &shaved, options, cancel, &mut |q| {
            progress(Progress {
                done: start + q.done,
                total,
            })
        })?;
        done = start + shaved.total_rolls();
        if run.cancelled {
            cancelled = true;
            break;
        }
        let cut = run.cuts[0];
        let against = cut.data.expect("the data measure the 3 % cut");
        let shaved_at = ShavedAtPoint {
            throws: cut.simulated.throws,
            uncounted: cut.simulated.uncounted,
            bias: cut.bias.bias,
            interval: cut.bias.interval,
            z: against.z,
            past_stability_limit: cut.simulated.past_stability_limit,
        };
        let budden_deviance: f64 = calibration
            .iter()
            .zip(&ratios)
            .map(|(&(i, _, _), t)| ratio_deviance(&rows[i], t))
            .sum();
        let shaved_deviance = against.z * against.z;
        let excluded = ratios
            .iter()
            .find_map(|t| Exclusion::of_counts(t.throws, t.throws + t.uncounted))
            .or_else(|| Exclusion::of_counts(shaved_at.throws, shaved_at.throws + shaved_at.uncounted));
        results.push(GridPoint {
            values: point.clone(),
            ratios,
            shaved: Some(shaved_at),
            budden_deviance: Some(budden_deviance),
            shaved_deviance: Some(shaved_deviance),
            deviance: Some(budden_deviance + shaved_deviance),
            excluded,
        });
    }
    let rise = spec.region_rise();
    let best = (0..results.len())
        .filter(|&i| results[i].kept_deviance().is_some())
        .min_by(|&a, &b| {
            let d = |i: usize| results[i].kept_deviance().unwrap_or(f64::INFINITY);
            d(a).total_cmp(&d(b))
        });
    if best.is_none() && !cancelled {
        let reasons: Vec<String> = results
            .iter()
            .filter_map(|p| Some(format!("{}: {}", spec.point_text(&p.values), p.excluded?)))
            .take(3)
            .collect();
        return Err(Error::Compare(format!(
            "no point of the grid rests on enough throws within the model's limits, so the fit \
             has no best point: {}; fit a range where the bodies settle on a face and step stably",
            reasons.join("; ")
        )));
    }
    let lowest = best.and_then(|i| results[i].kept_deviance());
    let region: Vec<usize> = match lowest {
        Some(d) => (0..results.len())
            .filter(|&i| results[i].kept_deviance().is_some_and(|x| x <= d + rise))
            .collect(),
        None => Vec::new(),
    };
    let region_ranges = if region.is_empty() {
        Vec::new()
    } else {
        spec.keys
            .iter()
            .enumerate()
            .map(|(k, key)| {
                let values = region.iter().map(|&i| results[i].values[k]);
                let low = values.clone().fold(f64::INFINITY, f64::min);
                let high = values.fold(f64::NEG_INFINITY, f64::max);
                KeyRange {
                    key: key.key.key.clone(),
                    low,
                    high,
                    low_open: low == key.low,
                    high_open: high == key.high,
                }
            })
            .collect()
    };
    Ok(JointComparison {
        dataset: "joint",
        sources: vec![budden_source, shaved_source],
        assumptions: assumptions(),
        seed: spec.seed,
        keys: spec.keys.iter().map(|k| k.key.key.clone()).collect(),
        calibrate_on: spec.calibrate_on.clone(),
        cut: MEASURED_CUT,
        shaved_throws: spec.shaved_throws,
        points: results,
        best,
        lowest_deviance: lowest,
        region_rise: rise,
        region,
        region_ranges,
        cancelled,
    })
}

/// The calibration ratios a joint fit uses unless told otherwise: Budden's three.
pub fn default_calibrate_on() -> Vec<f64> {
    DEFAULT_CALIBRATE_ON.to_vec()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(keys: &[&str]) -> JointSpec {
        JointSpec {
            keys: keys
                .iter()
                .map(|k| GridKey::parse(k, DEFAULT_VALUES_PER_KEY).unwrap())
                .collect(),
            seed: 1,
            shaved_throws: 100,
            calibrate_on: default_calibrate_on(),
        }
    }

    #[test]
    fn the_grid_is_every_combination_first_key_slowest() {
        let s = spec(&["ground.restitution:0.2:0.6:3", "ground.friction:0.1:0.3:2"]);
        // Two values is one short of a valley.
        assert!(s.validate().unwrap_err().to_string().contains("at least 3"));
        let s = spec(&["ground.restitution:0.2:0.6:3", "ground.friction:0.1:0.3:3"]);
        s.validate().unwrap();
        let points = s.points();
        assert_eq!(points.len(), 9);
        assert_eq!(points[0], vec![0.2, 0.1]);
        assert_eq!(points[1][0], 0.2);
        assert_eq!(points[8], vec![0.6, 0.3]);
        assert!((points[4][0] - 0.4).abs() < 1e-15 && (points[4][1] - 0.2).abs() < 1e-15);
        // Per point: Budden's 840 + 1011 + 680 throws, and 100 shaved throws twice.
        assert_eq!(s.total_rolls(), 9 * (840 + 1011 + 680 + 200));
    }

    #[test]
    fn the_region_rise_is_the_chi_square_quantile_of_the_keys_fitted() {
        // χ² 95 % quantiles: −2 ln 0.05 = 5.9915 for two degrees of freedom (exact: the
        // χ²₂ is an exponential of mean 2), 7.8147 for three and 3.8415 for one (tables).
        assert!((region_rise(2) - (-2.0 * 0.05f64.ln())).abs() < 1e-9);
        assert!((region_rise(3) - 7.8147).abs() < 1e-4);
        assert!((region_rise(1) - 3.8415).abs() < 1e-4);
    }

    #[test]
    fn bad_grids_are_refused_naming_the_key() {
        let refused = |keys: &[&str]| spec(keys).validate().unwrap_err().to_string();
        let e = refused(&["ground.restitution:0.2:0.6"]);
        assert!(e.contains("two or more keys"), "{e}");
        let e = refused(&["ground.restitution:0.2:0.6", "ground.friction:0.3:0.3"]);
        assert!(e.contains("`ground.friction` takes one value (0.3)"), "{e}");
        let e = refused(&["ground.restitution:0.2:0.6", "ground.friction:0.1:0.5:1"]);
        assert!(e.contains("`ground.friction` takes one value"), "{e}");
        let e = refused(&["ground.restitution:0.2:0.6", "ground.friction:0.5:0.1"]);
        assert!(e.contains("`ground.friction`: the range's low end 0.5"), "{e}");
        let e = refused(&["ground.restitution:0.2:0.6", "ground.restitution:0.3:0.5"]);
        assert!(e.contains("fitted twice"), "{e}");
        let e = refused(&["ground.restitution:0.2:0.6", "die.corner_mass:0.5:1"]);
        assert!(e.contains("`die.corner_mass`"), "{e}");
        let e = refused(&["ground.restitution:0.2:0.6", "initial.height:5:10"]);
        assert!(e.contains("`initial.height` is part of the throw"), "{e}");
        let e = refused(&["ground.restitution:0.2:1.5", "ground.friction:0.1:0.5"]);
        assert!(e.contains("ground.restitution"), "{e}");
        // 11 × 10 × 10 = 1100 points: past the limit, each key's count named.
        let e = refused(&[
            "ground.restitution:0.2:0.6:11",
            "ground.friction:0.1:0.5:10",
            "ground.table_mass:100:1000:10",
        ]);
        assert!(e.contains("a grid of 1100 points"), "{e}");
        assert!(
            e.contains("11 (ground.restitution) × 10 (ground.friction)"),
            "{e}"
        );
        assert!(e.contains("at most 1000 candidates"), "{e}");
        let e = GridKey::parse("ground.bogus:0:1", 5).unwrap_err().to_string();
        assert!(e.contains("ground.bogus"), "{e}");
        let e = GridKey::parse("ground.friction:0:1:x", 5)
            .unwrap_err()
            .to_string();
        assert!(e.contains("`x` is not a count"), "{e}");
    }
}
