//! How precisely a throw must be known to predict it: random starts rolled beside their
//! ε-twins ([`twin::perturbed`]) for a list of ε, the share of pairs that end on the same
//! face, and the ε at which that share has fallen halfway from certainty to chance.
//!
//! The rolls go through the batch machinery ([`stream_batch`]): each start and its twins are
//! consecutive rolls of one batch, so the experiment is parallel, the same for any thread
//! count or engine, and a cancel keeps an exact prefix of whole groups.

use crate::Error;
use crate::batch::{Rolls, RunOptions, stream_batch};
use crate::data_file::Column;
use crate::record::RollRecord;
use crate::stats::{FaceTally, wilson_interval};
use dicesim_physics::{InitialCondition, Params};
use dicesim_setup::chaos::{EPSILON, perturbed};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::number::Real;
use dicesim_setup::number::fmt_exact;
use dicesim_setup::random::{RandomDraws, RandomRanges, check_drawn_setup};
use dicesim_setup::registry::{HEIGHT, Role};
use serde::Serialize;
use std::sync::atomic::AtomicBool;

/// The default list of ε: one per decade from 10⁻¹⁵ to 10⁻¹.
pub fn default_epsilons() -> Vec<f64> {
    (-15..=-1)
        .map(|e| format!("1e{e}").parse().expect("a literal"))
        .collect()
}

/// What to roll: `count` random starts (drawn by `ranges` from `seed`) each beside one twin
/// per ε, for each value of the swept key (or once, for the setup as it is).
#[derive(Debug, Clone)]
pub struct PredictSpec {
    pub epsilons: Vec<f64>,
    pub count: u64,
    pub seed: u64,
    /// One setup key and its values; `None`: the setup as given.
    pub sweep: Option<(ScanKey, Vec<f64>)>,
}

/// The share of pairs that ended on the same face at one ε.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PredictPoint {
    pub epsilon: f64,
    /// Pairs whose start and twin both ended with a face.
    pub pairs: u64,
    /// Of those, pairs that ended on the same face.
    pub same: u64,
    /// `same / pairs`.
    pub same_share: f64,
    /// Its 95 % (Wilson) interval.
    pub interval: [f64; 2],
}

/// Where P(same face) crosses halfway between 1 and chance, on the list of ε.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Threshold {
    /// Between two listed ε, interpolated linearly in P against log₁₀ ε.
    At(f64),
    /// Already below halfway at the smallest ε listed.
    Below(f64),
    /// Still above halfway at the largest ε listed.
    Above(f64),
}

impl Threshold {
    /// The ε itself, or the bound it lies beyond.
    pub fn value(self) -> f64 {
        match self {
            Threshold::At(e) | Threshold::Below(e) | Threshold::Above(e) => e,
        }
    }

    /// As a person reads it: `3.2e-9`, `< 1e-15`, `> 0.1`.
    pub fn text(self) -> String {
        match self {
            Threshold::At(e) => format!("{e:.2e}"),
            Threshold::Below(e) => format!("< {e:e}"),
            Threshold::Above(e) => format!("> {e:e}"),
        }
    }
}

/// The curve of one setup: P(same face) against ε, chance, and the threshold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PredictCurve {
    /// The swept key's value (`None` without a sweep).
    pub value: Option<f64>,
    /// Starts whose groups were rolled whole.
    pub starts: u64,
    pub points: Vec<PredictPoint>,
    /// The starts' own faces.
    pub faces: FaceTally,
    /// `Σ pᶠ²` over the starts' face shares: P(same face) of two unrelated throws.
    pub chance: f64,
    /// The share halfway between certainty and chance, `(1 + chance) / 2`.
    pub half: f64,
    /// ε½: where P(same face) falls to `half` (`None` without pairs).
    pub threshold: Option<Threshold>,
    /// Share of the starts that ended on the face that started up, with its 95 % interval.
    pub start_face_share: f64,
    pub start_face_interval: [f64; 2],
}

/// The whole experiment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Prediction {
    /// The swept key (`None` without a sweep).
    pub key: Option<String>,
    pub epsilons: Vec<f64>,
    /// Starts asked for per curve.
    pub count: u64,
    pub seed: u64,
    pub curves: Vec<PredictCurve>,
    /// Whether a cancel stopped it before the end (the curves then hold whole groups only).
    pub cancelled: bool,
}

impl PredictSpec {
    /// Checks the list of ε and the sweep before anything is rolled.
    pub fn validate(&self) -> Result<(), Error> {
        if self.epsilons.is_empty() {
            return Err(Error::Predict("give at least one ε".to_string()));
        }
        for &e in &self.epsilons {
            EPSILON.check(e)?;
        }
        if !self.epsilons.is_sorted_by(|a, b| a < b) {
            return Err(Error::Predict(
                "list the ε in increasing order, each once".to_string(),
            ));
        }
        if self.count == 0 {
            return Err(Error::Predict("roll at least one start".to_string()));
        }
        if let Some((key, values)) = &self.sweep {
            let drawn = key.spec.role == Role::Initial && key.spec != &HEIGHT;
            if drawn || key.spec.role == Role::Random {
                return Err(Error::Predict(format!(
                    "`{}` is drawn at random for every start; sweep `initial.height` or a die, \
                     ground, world or integrator key",
                    key.key
                )));
            }
            if values.is_empty() {
                return Err(Error::Predict(format!(
                    "give at least one value of `{}`",
                    key.key
                )));
            }
            for (i, &v) in values.iter().enumerate() {
                key.check(v)?;
                // Two curves of one value are one curve drawn twice: a typo, not a result.
                if values[..i].contains(&v) {
                    return Err(Error::Predict(format!(
                        "`{}` = {} is given twice; each curve needs a value of its own",
                        key.key,
                        fmt_exact(v)
                    )));
                }
            }
        }
        Ok(())
    }
}

/// The setup of one curve: the swept value set in the parameters, or, for the drop height,
/// as the random starts' height.
fn curve_setup(
    params: &Params,
    ranges: &RandomRanges,
    base: &InitialCondition,
    sweep: Option<(&ScanKey, f64)>,
) -> (Params, RandomRanges, InitialCondition) {
    let (mut params, mut ranges, mut base) = (*params, *ranges, *base);
    if let Some((key, value)) = sweep {
        key.set(&mut params, &mut base, value);
        if key.spec == &HEIGHT {
            ranges.height = [value, value];
        }
    }
    (params, ranges, base)
}

/// How far [`run_prediction`] has got, after a chunk of rolls.
#[derive(Debug, Clone, Copy)]
pub struct Progress<'a> {
    /// Rolls done so far, over every curve.
    pub done: u64,
    /// Rolls in the whole experiment.
    pub total: u64,
    /// The curve being rolled, of its whole groups so far: what a screen can show filling in.
    pub curve: &'a PredictCurve,
}

/// Rolls the experiment: for each curve, `count` starts and their twins as one batch.
/// `progress` is called after each chunk of rolls; setting `cancel` stops it, keeping the
/// whole groups rolled so far.
pub fn run_prediction(
    params: &Params,
    ranges: &RandomRanges,
    base: &InitialCondition,
    spec: &PredictSpec,
    options: &RunOptions,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(Progress<'_>),
) -> Result<Prediction, Error> {
    spec.validate()?;
    let values: Vec<Option<f64>> = match &spec.sweep {
        Some((_, values)) => values.iter().copied().map(Some).collect(),
        None => vec![None],
    };
    let group = 1 + spec.epsilons.len() as u64;
    let total = group * spec.count * values.len() as u64;
    let setups: Vec<_> = values
        .iter()
        .map(|value| {
            let sweep = spec.sweep.as_ref().zip(*value).map(|((k, _), v)| (k, v));
            curve_setup(params, ranges, base, sweep)
        })
        .collect();
    // Every curve's setup is checked before the first is rolled: no start of any of them
    // may put a corner into the table.
    for (params, ranges, base) in &setups {
        check_drawn_setup(params, ranges, base)?;
    }
    let mut curves = Vec::new();
    let mut cancelled = false;
    for (i, ((params, ranges, base), value)) in setups.into_iter().zip(&values).enumerate() {
        let starts: Vec<(u64, InitialCondition)> = (0..spec.count)
            .flat_map(|s| {
                let start = ranges.draw(&base, spec.seed, s);
                std::iter::once(start)
                    .chain(spec.epsilons.iter().map(move |&e| perturbed(&start, e)))
                    .enumerate()
                    .map(move |(j, ic)| (s * group + j as u64, ic))
            })
            .collect();
        let done_before = i as u64 * group * spec.count;
        let mut curve = CurveTally::new(spec.epsilons.len(), params.die.face_numbers());
        let mut done = 0u64;
        let run = stream_batch(&params, &Rolls::Given(&starts), options, cancel, &mut |records| {
            done += records.len() as u64;
            curve.add(records);
            progress(Progress {
                done: done_before + done,
                total,
                curve: &curve.curve(*value, &spec.epsilons),
            });
            Ok(())
        })?;
        curves.push(curve.curve(*value, &spec.epsilons));
        if run.cancelled {
            cancelled = true;
            break;
        }
    }
    Ok(Prediction {
        key: spec.sweep.as_ref().map(|(k, _)| k.key.clone()),
        epsilons: spec.epsilons.clone(),
        count: spec.count,
        seed: spec.seed,
        curves,
        cancelled,
    })
}

/// The counts of one curve, fed with records in roll order; a group counts once whole.
struct CurveTally {
    /// The records of the group being filled (a start, then its twins).
    open: Vec<RollRecord>,
    group: usize,
    starts: u64,
    faces: FaceTally,
    kept_start_face: u64,
    pairs: Vec<u64>,
    same: Vec<u64>,
}

impl CurveTally {
    fn new(epsilons: usize, numbers: &'static [u8]) -> CurveTally {
        CurveTally {
            open: Vec::with_capacity(epsilons + 1),
            group: epsilons + 1,
            starts: 0,
            faces: FaceTally::new(numbers),
            kept_start_face: 0,
            pairs: vec![0; epsilons],
            same: vec![0; epsilons],
        }
    }

    fn add(&mut self, records: &[RollRecord]) {
        for r in records {
            self.open.push(*r);
            if self.open.len() == self.group {
                self.close();
            }
        }
    }

    fn close(&mut self) {
        let start = self.open[0];
        self.starts += 1;
        if let Some(face) = start.outcome.face {
            self.faces.add(face);
            if face == start.start_face {
                self.kept_start_face += 1;
            }
            for (j, twin) in self.open[1..].iter().enumerate() {
                if let Some(other) = twin.outcome.face {
                    self.pairs[j] += 1;
                    if other == face {
                        self.same[j] += 1;
                    }
                }
            }
        }
        self.open.clear();
    }

    fn curve(&self, value: Option<f64>, epsilons: &[f64]) -> PredictCurve {
        let points: Vec<PredictPoint> = epsilons
            .iter()
            .enumerate()
            .map(|(j, &epsilon)| PredictPoint {
                epsilon,
                pairs: self.pairs[j],
                same: self.same[j],
                same_share: if self.pairs[j] == 0 {
                    0.0
                } else {
                    self.same[j] as f64 / self.pairs[j] as f64
                },
                interval: wilson_interval(self.same[j], self.pairs[j]),
            })
            .collect();
        let chance: f64 = self.faces.shares().iter().map(|s| s.powi(2)).sum();
        let half = 0.5 * (1.0 + chance);
        let with_face = self.faces.total();
        PredictCurve {
            value,
            starts: self.starts,
            threshold: threshold(&points, half),
            points,
            faces: self.faces.clone(),
            chance,
            half,
            start_face_share: if with_face == 0 {
                0.0
            } else {
                self.kept_start_face as f64 / with_face as f64
            },
            start_face_interval: wilson_interval(self.kept_start_face, with_face),
        }
    }
}

/// ε½: the first ε (in increasing order) where the curve falls below `half`, interpolated
/// linearly against log₁₀ ε from the point before it.
fn threshold(points: &[PredictPoint], half: f64) -> Option<Threshold> {
    let points: Vec<&PredictPoint> = points.iter().filter(|p| p.pairs > 0).collect();
    let first = points.first()?;
    if first.same_share < half {
        return Some(Threshold::Below(first.epsilon));
    }
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if b.same_share < half {
            let t = (a.same_share - half) / (a.same_share - b.same_share);
            let log = a.epsilon.log10() + t * (b.epsilon.log10() - a.epsilon.log10());
            return Some(Threshold::At(10f64.powf(log)));
        }
    }
    Some(Threshold::Above(points.last()?.epsilon))
}

impl Prediction {
    /// The CSV's columns: the swept key's value (named with its unit, where a key was
    /// swept), ε, pairs, same, the share and its interval, the curve's chance level and
    /// halfway share, and its threshold (where a curve has one).
    pub fn csv_columns(&self) -> Vec<Column> {
        let mut columns = Vec::new();
        if let Some(key) = &self.key {
            let name = ScanKey::named(key).map_or_else(|_| key.replace('.', "_"), |k| k.column());
            columns.push(Column::real(name));
        }
        columns.extend([
            Column::real("epsilon"),
            Column::integer("pairs"),
            Column::integer("same"),
            Column::real("same_share"),
            Column::real("same_low"),
            Column::real("same_high"),
            Column::real("chance"),
            Column::real("half"),
        ]);
        if self.has_threshold() {
            columns.extend([Column::real("threshold"), Column::text("threshold_bound")]);
        }
        columns
    }

    /// Whether any curve found its threshold (else the columns would be empty in every row).
    fn has_threshold(&self) -> bool {
        self.curves.iter().any(|c| c.threshold.is_some())
    }

    /// One row per curve and ε, in [`Prediction::csv_columns`]; reals with their point.
    pub fn write_csv(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        writeln!(w, "{}", crate::data_file::header(&self.csv_columns()))?;
        for c in &self.curves {
            let (threshold, bound) = match c.threshold {
                Some(Threshold::At(e)) => (Real(e).to_string(), "at"),
                Some(Threshold::Below(e)) => (Real(e).to_string(), "below"),
                Some(Threshold::Above(e)) => (Real(e).to_string(), "above"),
                None => (String::new(), ""),
            };
            for p in &c.points {
                let mut cells: Vec<String> = Vec::with_capacity(11);
                if self.key.is_some() {
                    cells.push(c.value.map_or(String::new(), |v| Real(v).to_string()));
                }
                cells.extend([
                    Real(p.epsilon).to_string(),
                    p.pairs.to_string(),
                    p.same.to_string(),
                    Real(p.same_share).to_string(),
                    Real(p.interval[0]).to_string(),
                    Real(p.interval[1]).to_string(),
                    Real(c.chance).to_string(),
                    Real(c.half).to_string(),
                ]);
                if self.has_threshold() {
                    cells.extend([threshold.clone(), bound.to_string()]);
                }
                writeln!(w, "{}", cells.join(","))?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(epsilon: f64, same_share: f64) -> PredictPoint {
        PredictPoint {
            epsilon,
            pairs: 100,
            same: (same_share * 100.0) as u64,
            same_share,
            interval: [0.0, 1.0],
        }
    }

    #[test]
    fn the_threshold_is_interpolated_in_log_epsilon() {
        let points = [
            point(1e-9, 1.0),
            point(1e-8, 0.9),
            point(1e-7, 0.5),
            point(1e-6, 0.2),
        ];
        // half = 0.7: between 1e-8 (0.9) and 1e-7 (0.5), halfway in log ε.
        let t = threshold(&points, 0.7).unwrap();
        let Threshold::At(e) = t else { panic!("{t:?}") };
        assert!((e.log10() + 7.5).abs() < 1e-12, "{e}");
        assert_eq!(threshold(&points, 0.1), Some(Threshold::Above(1e-6)));
        assert_eq!(threshold(&points, 1.01), Some(Threshold::Below(1e-9)));
        assert_eq!(threshold(&[], 0.5), None);
    }

    #[test]
    fn default_epsilons_are_one_per_decade() {
        let e = default_epsilons();
        assert_eq!(e.len(), 15);
        assert_eq!((e[0], e[14]), (1e-15, 1e-1));
        assert!(e.windows(2).all(|w| (w[1] / w[0] - 10.0).abs() < 1e-9));
    }

    #[test]
    fn bad_lists_and_sweeps_are_refused() {
        let spec = |epsilons: Vec<f64>, sweep: Option<(&str, Vec<f64>)>| PredictSpec {
            epsilons,
            count: 10,
            seed: 1,
            sweep: sweep.map(|(k, v)| (ScanKey::parse(k).unwrap(), v)),
        };
        assert!(spec(vec![1e-9, 1e-3], None).validate().is_ok());
        assert!(spec(vec![], None).validate().is_err());
        assert!(spec(vec![1e-3, 1e-9], None).validate().is_err());
        let e = spec(vec![0.5], None).validate().unwrap_err().to_string();
        assert!(e.contains("twin.epsilon"), "{e}");
        let e = spec(vec![1e-3], Some(("initial.velocity.x", vec![1.0])))
            .validate()
            .unwrap_err()
            .to_string();
        assert!(e.contains("drawn at random"), "{e}");
        assert!(
            spec(vec![1e-3], Some(("initial.height", vec![2.0, 15.0])))
                .validate()
                .is_ok()
        );
        let e = spec(vec![1e-3], Some(("ground.damping", vec![0.5])))
            .validate()
            .unwrap_err()
            .to_string();
        assert!(e.contains("ground.damping"), "{e}");
    }
}
