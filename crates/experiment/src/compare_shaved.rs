//! The shaved die ([`real_data::shaved_die`](crate::real_data::shaved_die)) thrown as
//! Murray's group threw it: the preset's cube cut short by a fraction `c` along the axis
//! between faces 1 and 6, dropped from 10 cm from any orientation, and counted by whether 1
//! or 6 came up.
//!
//! Every throw is rolled twice over, once with the uncut die and once with each cut one
//! (the same start: common random numbers, as `batch --versus` rolls two setups). A cube
//! that is fair by its symmetry has `b = 0` exactly, so the cut's bias is the paired
//! difference `b = 3·(P_cut(1 or 6) − P_uncut(1 or 6))`, whose variance is that of the
//! per-throw difference: the throws both dice end alike cancel, and the interval is
//! narrower than the cut die's own (docs/real-dice.md, "The shaved die").

use crate::Error;
use crate::batch::{Rolls, RunOptions, stream_setups};
use crate::compare::Progress;
use crate::data_file::Column;
use crate::real_data::{ShavedRow, shaved_die};
use crate::record::RollRecord;
use crate::stats::wilson_interval;
use dicesim_physics::{Die, InitialCondition, Params, StabilityCheck, Status};
use dicesim_setup::number::{Real, fmt_exact};
use dicesim_setup::random::{RandomRanges, check_drawn_setup};
use serde::Serialize;
use std::sync::atomic::AtomicBool;

/// The cuts thrown unless told otherwise: the published one (3 %) with half and twice it,
/// so the slope b/c is read at three points.
pub const DEFAULT_CUTS: [f64; 3] = [0.015, 0.03, 0.06];

/// The largest cut: past half the side the body is a slab (the `plate` preset is one),
/// no longer a die with two faces a little larger than the rest.
pub const MAX_CUT: f64 = 0.5;

/// cm, the height of the centre of mass at release: the experiment dropped the die from at
/// least 10 cm.
pub const DROP_HEIGHT_CM: f64 = 10.0;

/// cm/s, each component of the release velocity is uniform in ± this: a hand's drop.
pub const DROP_VELOCITY_CM_PER_S: f64 = 20.0;

/// rad/s, each component of the release spin is uniform in ± this.
pub const DROP_SPIN_RAD_PER_S: f64 = 20.0;

/// Throws unless told otherwise: as many as the experiment rolled at a cut.
pub fn default_throws() -> u64 {
    shaved_die().0.iter().map(|r| r.rolls).max().unwrap_or(1)
}

/// The normal quantile of a two-sided 95 % interval.
const Z95: f64 = 1.959_963_984_540_054;

/// The throw of the protocol, whatever the preset's ranges say: from [`DROP_HEIGHT_CM`],
/// velocity and spin uniform per component, orientation uniform over all rotations.
pub fn drop_throw(seed: u64) -> RandomRanges {
    RandomRanges {
        seed,
        height: [DROP_HEIGHT_CM; 2],
        velocity: [-DROP_VELOCITY_CM_PER_S, DROP_VELOCITY_CM_PER_S],
        angular_velocity: [-DROP_SPIN_RAD_PER_S, DROP_SPIN_RAD_PER_S],
        random_orientation: true,
        orientation_spread: 0.0,
    }
}

/// The sentences every output states about the body and the throw.
pub fn assumptions() -> Vec<String> {
    vec![
        "the preset's cube cut short by c along the 1–6 axis: half sizes [h·(1 − c), h, h], corner mass \
         × (1 − c) (the same density), its corners, table, world and integrator kept"
            .to_string(),
        format!(
            "a drop: centre of mass {DROP_HEIGHT_CM} cm up, each velocity component uniform in ±{DROP_VELOCITY_CM_PER_S} cm/s, \
             each spin component in ±{DROP_SPIN_RAD_PER_S} rad/s, orientation uniform, whatever the preset's ranges say"
        ),
        "each throw rolled with the uncut die and with every cut one from the same start; a throw counts for a \
         cut when both dice end on a face"
            .to_string(),
    ]
}

/// Why the preset's die cannot be cut as the experiment cut its die (`None` where it can):
/// a cube (three equal half sizes), fair by its symmetry (no pips, no loads), so that the
/// cut is its only asymmetry and the uncut die's bias is zero.
pub fn uncuttable(die: &Die) -> Option<String> {
    let [x, y, z] = die.half_sizes;
    if x != y || y != z {
        return Some(format!(
            "`compare shaved-die` cuts a cube along its 1–6 axis, and the preset's die is not one \
             (half sizes {}, {}, {} cm); use a cubic die, e.g. --preset paper or --set die.half_size=1",
            fmt_exact(x),
            fmt_exact(y),
            fmt_exact(z)
        ));
    }
    if die.is_loaded() {
        return Some(
            "`compare shaved-die` needs a die that is fair uncut, and the preset's carries extra corner \
             masses (a loaded die); set them to 0"
                .to_string(),
        );
    }
    if die.is_drilled() {
        return Some(
            "`compare shaved-die` needs a die that is fair uncut, and the preset's has drilled pips \
             (each face a different mass); set die.pip_depth=0"
                .to_string(),
        );
    }
    None
}

/// The die cut short by `cut` along its x axis (faces 1 and 6), its density kept.
pub fn cut_die(die: &Die, cut: f64) -> Die {
    let [x, y, z] = die.half_sizes;
    Die {
        half_sizes: [x * (1.0 - cut), y, z],
        corner_mass: die.corner_mass * (1.0 - cut),
        ..*die
    }
}

/// Why a `--set` of `key` does not reach the experiment's throws (`None` where it does):
/// the throw is the protocol's, so every `random.*` key but the seed and every start value
/// the throws draw.
pub fn unapplied(key: &str) -> Option<String> {
    let drawn = [
        "initial.height",
        "initial.velocity",
        "initial.angular_velocity",
        "initial.angular_momentum",
        "initial.orientation",
    ];
    let is = |name: &str| key == name || key.strip_prefix(name).is_some_and(|c| c.starts_with('.'));
    ((key.starts_with("random.") && key != "random.seed") || drawn.iter().any(|d| is(d))).then(|| {
        format!(
            "`compare shaved-die` drops the die as the experiment did ({DROP_HEIGHT_CM} cm, ±{DROP_VELOCITY_CM_PER_S} cm/s, \
             ±{DROP_SPIN_RAD_PER_S} rad/s, any orientation), whatever the preset's throw says"
        )
    })
}

/// What to throw: each throw once uncut and once with every cut of `cuts`.
#[derive(Debug, Clone, PartialEq)]
pub struct ShavedSpec {
    pub cuts: Vec<f64>,
    pub throws: u64,
    pub seed: u64,
}

impl ShavedSpec {
    /// Checks the spec before anything is rolled: at least one throw, every cut inside
    /// `(0, MAX_CUT]` and named once.
    pub fn validate(&self) -> Result<(), Error> {
        let refuse = |m: String| Err(Error::Compare(m));
        if self.throws == 0 {
            return refuse("throw at least once".to_string());
        }
        if self.cuts.is_empty() {
            return refuse("--cuts: name at least one cut".to_string());
        }
        for (i, &c) in self.cuts.iter().enumerate() {
            if !(c > 0.0 && c <= MAX_CUT) {
                return refuse(format!(
                    "--cuts: {} is outside the cuts a shaved die takes, more than 0 and at most {} of the side \
                     (past half, the body is a slab, not a die with two faces a little larger)",
                    fmt_exact(c),
                    fmt_exact(MAX_CUT)
                ));
            }
            if self.cuts[..i].contains(&c) {
                return refuse(format!("--cuts: cut {} is named twice", fmt_exact(c)));
            }
        }
        Ok(())
    }

    /// Rolls in the whole comparison: every throw uncut and with each cut.
    pub fn total_rolls(&self) -> u64 {
        self.throws.saturating_mul(self.cuts.len() as u64 + 1)
    }
}

/// The setups of a comparison, checked: the uncut die first, then one per cut. A die that
/// cannot be cut, a cut its corners have no room for, or a drop that would start inside
/// the table is refused with the reason.
pub fn setups(params: &Params, base: &InitialCondition, spec: &ShavedSpec) -> Result<Vec<Params>, Error> {
    spec.validate()?;
    if let Some(why) = uncuttable(&params.die) {
        return Err(Error::Compare(why));
    }
    let ranges = drop_throw(spec.seed);
    let mut all = vec![*params];
    for &cut in &spec.cuts {
        let p = Params {
            die: cut_die(&params.die, cut),
            ..*params
        };
        check_drawn_setup(&p, &ranges, base)
            .map_err(|e| Error::Compare(format!("the die cut by {}: {e}", fmt_exact(cut))))?;
        all.push(p);
    }
    check_drawn_setup(params, &ranges, base)?;
    Ok(all)
}

/// A bias with its 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Bias {
    pub bias: f64,
    pub interval: [f64; 2],
}

impl Bias {
    /// `b = 3·k/n − 1` of one die alone, its interval the Wilson interval of `k/n` mapped.
    pub fn alone(one_or_six: u64, throws: u64) -> Bias {
        let [low, high] = wilson_interval(one_or_six, throws);
        Bias {
            bias: 3.0 * one_or_six as f64 / throws.max(1) as f64 - 1.0,
            interval: [3.0 * low - 1.0, 3.0 * high - 1.0],
        }
    }
}

/// One cut's throws, each beside the uncut die's from the same start.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CutThrows {
    pub cut: f64,
    /// Throws in which both the uncut and the cut die ended on a face.
    pub throws: u64,
    /// Throws not counted: either die ended without a face.
    pub uncounted: u64,
    /// Of the counted throws, those the cut die ended on 1 or 6, and the uncut die.
    pub cut_one_or_six: u64,
    pub uncut_one_or_six: u64,
    /// Counted throws the cut die ended on 1 or 6 and the uncut not, and the other way.
    pub cut_only: u64,
    pub uncut_only: u64,
    /// Throws whose start the stability check puts past its limit for the cut die.
    pub past_stability_limit: u64,
}

impl CutThrows {
    fn new(cut: f64) -> CutThrows {
        CutThrows {
            cut,
            throws: 0,
            uncounted: 0,
            cut_one_or_six: 0,
            uncut_one_or_six: 0,
            cut_only: 0,
            uncut_only: 0,
            past_stability_limit: 0,
        }
    }

    /// Counts one throw: the uncut die's ending and the cut die's.
    fn add(&mut self, uncut: &RollRecord, cut: &RollRecord) {
        let (Some(u), Some(c)) = (one_or_six(uncut), one_or_six(cut)) else {
            self.uncounted += 1;
            return;
        };
        self.throws += 1;
        self.cut_one_or_six += u64::from(c);
        self.uncut_one_or_six += u64::from(u);
        self.cut_only += u64::from(c && !u);
        self.uncut_only += u64::from(u && !c);
    }

    /// The paired bias `b = 3·(d₁₀ − d₀₁)/n` with `d₁₀` the throws only the cut die ended
    /// on 1 or 6 and `d₀₁` those only the uncut did, and its 95 % interval `b ± 1.96·3·s/√n`,
    /// `s²` the sample variance of the per-throw difference (each −1, 0 or 1):
    /// `(d₁₀ + d₀₁ − n·d̄²)/(n − 1)`, `d̄ = (d₁₀ − d₀₁)/n`. Under two throws nothing is
    /// known: 0 in the whole range a paired bias can take, −3 to 3.
    pub fn paired_bias(&self) -> Bias {
        let n = self.throws as f64;
        if self.throws < 2 {
            return Bias {
                bias: 0.0,
                interval: [-3.0, 3.0],
            };
        }
        let mean = (self.cut_only as f64 - self.uncut_only as f64) / n;
        let variance = ((self.cut_only + self.uncut_only) as f64 - n * mean * mean) / (n - 1.0);
        let half = Z95 * 3.0 * (variance / n).sqrt();
        let bias = 3.0 * mean;
        Bias {
            bias,
            interval: [bias - half, bias + half],
        }
    }
}

/// Whether a roll ended on 1 or 6 (`None`: it ended without a face).
fn one_or_six(r: &RollRecord) -> Option<bool> {
    match (r.outcome.status, r.outcome.face) {
        (Status::Settled, Some(face @ 1..=6)) => Some(face == 1 || face == 6),
        _ => None,
    }
}

/// One cut's result: the paired bias, its slope, the cut die's own bias, and the data
/// where the experiment measured this cut.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CutResult {
    pub cut: f64,
    pub simulated: CutThrows,
    /// The paired bias and its interval.
    pub bias: Bias,
    /// `b/c` and its interval (the bias's, over the exact cut).
    pub slope: Bias,
    /// The cut die's bias from its own throws alone (the interval the pairing narrows).
    pub cut_alone: Bias,
    /// The experiment's row at this cut, if it measured one.
    pub data: Option<DataAgainst>,
}

/// The experiment's bias at a cut beside the simulation's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DataAgainst {
    pub rolls: u64,
    /// Rolls on 1 or 6: the whole number behind the reported bias.
    pub one_or_six: u64,
    pub bias: Bias,
    /// The standard deviation of the reported bias from its rolls alone, `3·√(p(1 − p)/N)`.
    pub sigma: f64,
    /// `(b_data − b_sim)/√(σ_data² + σ_sim²)`, σ_sim from the paired interval.
    pub z: f64,
}

impl DataAgainst {
    fn new(row: &ShavedRow, simulated: &Bias) -> DataAgainst {
        let k = row.one_or_six();
        let p = k as f64 / row.rolls as f64;
        let sigma = 3.0 * (p * (1.0 - p) / row.rolls as f64).sqrt();
        let sigma_sim = (simulated.interval[1] - simulated.interval[0]) / (2.0 * Z95);
        DataAgainst {
            rolls: row.rolls,
            one_or_six: k,
            // The reported bias, with the interval of the count behind it.
            bias: Bias {
                bias: row.bias,
                ..Bias::alone(k, row.rolls)
            },
            sigma,
            z: (row.bias - simulated.bias) / (sigma * sigma + sigma_sim * sigma_sim).sqrt(),
        }
    }

    pub fn within_two_sigma(&self) -> bool {
        self.z.abs() <= 2.0
    }
}

/// The whole comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShavedComparison {
    /// `"shaved-die"`.
    pub dataset: &'static str,
    pub source: String,
    pub assumptions: Vec<String>,
    pub seed: u64,
    /// Throws asked for.
    pub throws: u64,
    /// The uncut die's own throws that ended on a face, those on 1 or 6, and its bias
    /// (zero for a fair die, within its noise).
    pub uncut_throws: u64,
    pub uncut_one_or_six: u64,
    pub uncut: Bias,
    pub cuts: Vec<CutResult>,
    /// Stopped before the last throw: the counts are those of the throws completed.
    pub cancelled: bool,
}

impl ShavedComparison {
    /// The CSV's columns: the cut, the simulated counts, the paired bias and its slope with
    /// intervals, the cut die's own bias, and the data's bias and z where it has one.
    pub fn csv_columns(&self) -> Vec<Column> {
        vec![
            Column::real("cut"),
            Column::integer("simulated_throws"),
            Column::integer("simulated_uncounted"),
            Column::integer("cut_one_or_six"),
            Column::integer("uncut_one_or_six"),
            Column::real("bias"),
            Column::real("bias_low"),
            Column::real("bias_high"),
            Column::real("slope"),
            Column::real("slope_low"),
            Column::real("slope_high"),
            Column::real("cut_alone_bias"),
            Column::real("cut_alone_low"),
            Column::real("cut_alone_high"),
            Column::integer("data_rolls"),
            Column::real("data_bias"),
            Column::real("data_sigma"),
            Column::real("z"),
            Column::boolean("within_two_sigma"),
        ]
    }

    /// One row per cut, in [`ShavedComparison::csv_columns`]; the data's cells empty where
    /// the experiment did not measure that cut.
    pub fn write_csv(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        writeln!(w, "{}", crate::data_file::header(&self.csv_columns()))?;
        let real = |x: f64| Real(x).to_string();
        for r in &self.cuts {
            let s = &r.simulated;
            let mut cells = vec![
                real(r.cut),
                s.throws.to_string(),
                s.uncounted.to_string(),
                s.cut_one_or_six.to_string(),
                s.uncut_one_or_six.to_string(),
            ];
            for b in [r.bias, r.slope, r.cut_alone] {
                cells.extend([real(b.bias), real(b.interval[0]), real(b.interval[1])]);
            }
            match &r.data {
                Some(d) => cells.extend([
                    d.rolls.to_string(),
                    real(d.bias.bias),
                    real(d.sigma),
                    real(d.z),
                    d.within_two_sigma().to_string(),
                ]),
                None => cells.extend(std::iter::repeat_n(String::new(), 5)),
            }
            writeln!(w, "{}", cells.join(","))?;
        }
        Ok(())
    }
}

/// Throws the protocol `spec.throws` times, each with the uncut die and every cut one,
/// and holds each cut's paired bias against the experiment's where it measured that cut.
/// `progress` is called after each chunk; `cancel` keeps the whole throws so far.
pub fn run_shaved(
    params: &Params,
    base: &InitialCondition,
    spec: &ShavedSpec,
    options: &RunOptions,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(Progress),
) -> Result<ShavedComparison, Error> {
    let setups = setups(params, base, spec)?;
    let ranges = drop_throw(spec.seed);
    let (rows, source) = shaved_die();
    let rolls = Rolls::Random {
        ranges: &ranges,
        base,
        seed: spec.seed,
        first: 0,
        count: spec.throws,
    };
    let checks: Vec<_> = setups[1..].iter().map(StabilityCheck::new).collect();
    let mut cuts: Vec<CutThrows> = spec.cuts.iter().map(|&c| CutThrows::new(c)).collect();
    let (mut uncut_throws, mut uncut_one_or_six) = (0u64, 0u64);
    let total = spec.total_rolls();
    let mut done = 0;
    let per_throw = setups.len();
    let run = stream_setups(&setups, &rolls, options, cancel, &mut |chunk| {
        for throw in chunk.chunks_exact(per_throw) {
            let uncut = &throw[0];
            if let Some(u) = one_or_six(uncut) {
                uncut_throws += 1;
                uncut_one_or_six += u64::from(u);
            }
            for ((t, cut), check) in cuts.iter_mut().zip(&throw[1..]).zip(&checks) {
                t.add(uncut, cut);
                t.past_stability_limit += u64::from(!check.predict(&cut.initial).is_stable());
            }
        }
        done += chunk.len() as u64;
        progress(Progress { done, total });
        Ok(())
    })?;
    let results = cuts
        .into_iter()
        .map(|t| {
            let bias = t.paired_bias();
            CutResult {
                cut: t.cut,
                slope: Bias {
                    bias: bias.bias / t.cut,
                    interval: [bias.interval[0] / t.cut, bias.interval[1] / t.cut],
                },
                cut_alone: Bias::alone(t.cut_one_or_six, t.throws),
                data: rows
                    .iter()
                    .find(|row| row.cut == t.cut)
                    .map(|row| DataAgainst::new(row, &bias)),
                bias,
                simulated: t,
            }
        })
        .collect();
    Ok(ShavedComparison {
        dataset: "shaved-die",
        source,
        assumptions: assumptions(),
        seed: spec.seed,
        throws: spec.throws,
        uncut_throws,
        uncut_one_or_six,
        uncut: Bias::alone(uncut_one_or_six, uncut_throws),
        cuts: results,
        cancelled: run.completed < run.requested,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(face: Option<u8>) -> RollRecord {
        let status = if face.is_some() {
            Status::Settled
        } else {
            Status::Timeout
        };
        RollRecord::ended(0, status, face)
    }

    #[test]
    fn the_paired_bias_is_three_times_the_mean_difference_with_its_sample_spread() {
        let mut t = CutThrows::new(0.03);
        // 10 counted throws: 3 where only the cut die shows 1 or 6, 1 where only the uncut
        // one does, 2 where both do, 4 where neither; and one the cut die ends faceless.
        let pairs = [
            (Some(2), Some(1)),
            (Some(3), Some(6)),
            (Some(5), Some(6)),
            (Some(1), Some(4)),
            (Some(6), Some(1)),
            (Some(1), Some(1)),
            (Some(2), Some(3)),
            (Some(4), Some(4)),
            (Some(5), Some(2)),
            (Some(3), Some(5)),
            (Some(1), None),
        ];
        for (u, c) in pairs {
            t.add(&record(u), &record(c));
        }
        assert_eq!((t.throws, t.uncounted), (10, 1));
        assert_eq!(
            (t.cut_only, t.uncut_only, t.cut_one_or_six, t.uncut_one_or_six),
            (3, 1, 5, 3)
        );
        // d = (1, 1, 1, −1, 0, 0, 0, 0, 0, 0): mean 0.2, Σ(d − 0.2)² = 4 − 10·0.04 = 3.6, s² = 0.4.
        let b = t.paired_bias();
        assert!((b.bias - 0.6).abs() < 1e-15);
        let half = Z95 * 3.0 * (0.4f64 / 10.0).sqrt();
        assert!((b.interval[0] - (0.6 - half)).abs() < 1e-12 && (b.interval[1] - (0.6 + half)).abs() < 1e-12);
        // Alone, the cut die's 5 of 10 gives b = 3·0.5 − 1 = 0.5.
        assert!((Bias::alone(5, 10).bias - 0.5).abs() < 1e-15);
    }

    #[test]
    fn a_cut_shortens_the_one_six_axis_and_keeps_the_density() {
        let die = Params::default().die;
        let cut = cut_die(&die, 0.03);
        assert_eq!(cut.half_sizes, [0.97, 1.0, 1.0]);
        assert_eq!(cut.corner_mass, 0.97);
        // The body's mass over its volume, before and after: 8 g / 8 cm³.
        let density = |d: &Die| 8.0 * d.corner_mass / (8.0 * d.half_sizes.iter().product::<f64>());
        assert!((density(&cut) - density(&die)).abs() < 1e-15);
        assert_eq!(uncuttable(&die), None);
        assert!(uncuttable(&cut).unwrap().contains("half sizes 0.97, 1, 1 cm"));
    }

    #[test]
    fn cuts_out_of_range_are_refused_and_the_throw_is_the_protocols() {
        let spec = |cuts: &[f64]| ShavedSpec {
            cuts: cuts.to_vec(),
            throws: 10,
            seed: 1,
        };
        spec(&DEFAULT_CUTS).validate().unwrap();
        assert_eq!(spec(&DEFAULT_CUTS).total_rolls(), 40);
        spec(&[MAX_CUT]).validate().unwrap();
        for bad in [0.0, -0.01, 0.5000001, f64::NAN] {
            let e = spec(&[bad]).validate().unwrap_err().to_string();
            assert!(e.contains("outside the cuts a shaved die takes"), "{bad}: {e}");
        }
        assert!(spec(&[]).validate().is_err());
        assert!(unapplied("random.height").is_some());
        assert!(unapplied("initial.orientation").is_some());
        assert!(unapplied("random.seed").is_none());
        assert!(unapplied("ground.restitution").is_none());
        assert!(unapplied("die.corner_radius").is_none());
        let r = drop_throw(5);
        assert_eq!(
            (r.seed, r.height, r.velocity, r.random_orientation),
            (5, [10.0, 10.0], [-20.0, 20.0], true)
        );
    }
}
