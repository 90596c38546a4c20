//! The text tables of results, as the commands print them: beside each result's CSV
//! (`write_csv`), the same figures for a reader. Each writes whole lines to `out`. Only the
//! command line prints them, so they live beside it, not in the experiment crate.

use dicesim_experiment::basin::{BasinMap, Layer};
use dicesim_experiment::compare::{Comparison, Excluded, Fairness};
use dicesim_experiment::compare_budden::{BuddenComparison, RatioRole, seeds_text};
use dicesim_experiment::compare_joint::JointComparison;
use dicesim_experiment::compare_shaved::{Bias, ShavedComparison};
use dicesim_experiment::compare_stats::{FitInterval, FitMethod};
use dicesim_experiment::ending::Ending;
use dicesim_experiment::merge::{BatchMerge, MapMerge};
use dicesim_experiment::one_roll::{OneRoll, Verdict, why_it_cannot_settle_roll};
use dicesim_experiment::predict::Prediction;
use dicesim_experiment::versus::VersusRun;
use dicesim_experiment::{BatchRun, BatchSummary, FaceTally};
use dicesim_figures::animation::{Animated, speed_words};
use dicesim_physics::{InitialCondition, Outcome, Params, Solid, Status};
use dicesim_setup::number::{die_number, fmt_exact, fmt_num};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The summary's lines that depend on the rolls alone (not on threads or time), as `batch`
/// and `merge` print them.
pub fn batch_counts(out: &mut dyn Write, s: &BatchSummary) -> std::io::Result<()> {
    let faced = s.faces.total();
    writeln!(
        out,
        "face   count   share   95% interval   of the {faced} rolls that ended on a face; {} did not (status below)",
        s.rolls - faced
    )?;
    let rows = s.faces.by_number().zip(&s.face_shares).zip(&s.face_intervals);
    for (((number, count), share), interval) in rows {
        let [low, high] = interval.map(|x| 100.0 * x);
        writeln!(
            out,
            "{number:>4} {count:>7}  {:>5.1}%  {low:>5.1}–{high:.1}%",
            100.0 * share
        )?;
    }
    match (s.chi_square, s.p_value) {
        // p as the explorer prints it (three significant digits, 6.02e-28 rather than 0.0000).
        (Some(chi2), Some(p)) => writeln!(
            out,
            "χ² against a fair die  {chi2:.3} ({} dof), p = {}",
            s.faces.degrees_of_freedom(),
            fmt_num(p)
        )?,
        _ => writeln!(out, "χ² against a fair die  n/a (no faces)")?,
    }
    match s.rolls_to_detect {
        Some(n) => writeln!(
            out,
            "bias detectable in     {n} rolls (χ² at 5 %, 80 % power, for the bias measured here)"
        )?,
        None if s.chi_square.is_some() => {
            writeln!(out, "bias detectable in     — (no bias measured beyond chance)")?
        }
        None => {}
    }
    let [same, other, opposite] = s.start_face_shares.map(|x| 100.0 * x);
    // On the box every other face is next to the start face; on a die of more faces most
    // are not.
    let others = match Solid::showing(s.faces.numbers()) {
        Some(Solid::Box) => "adjacent",
        _ => "other",
    };
    writeln!(
        out,
        "from the start face    same {same:.1}%, {others} {other:.1}%, opposite {opposite:.1}%"
    )?;
    let st = &s.status;
    writeln!(
        out,
        "status                 settled {}, {} {}, {} {}, {} {}",
        st.settled,
        Ending::WithoutFace.name(),
        st.settled_without_face,
        Ending::DidNotSettle.name(),
        st.timeout,
        Ending::Unstable.name(),
        st.unstable
    )?;
    Ok(())
}

/// How many of `rolls` started past the stability limit (docs/model.md, "Stability"), as
/// the summaries of `batch` and `compare` say it.
pub fn stability_count(out: &mut dyn Write, past: u64, rolls: u64) -> std::io::Result<()> {
    if past == 0 {
        writeln!(out, "stability              every roll within the step's limits")
    } else {
        writeln!(
            out,
            "stability              {past} of {rolls} rolls past the stability limit: their endings are the \
             step's, not the model's (`dicesim roll --set …` on one names the limit; a smaller \
             integrator.dt helps where the step is the cause)"
        )
    }
}

/// A versus batch: the throws, setups, threads and engine, the table of A's ending against
/// B's, and the share of throws that agree.
pub fn versus(out: &mut dyn Write, run: &VersusRun, preset: &str, versus: &[String]) -> std::io::Result<()> {
    let t = &run.table;
    writeln!(
        out,
        "{} throws in A ({preset} as given) and B (A with {}), {} thread{}, {} engine",
        t.throws(),
        versus.join(" "),
        run.jobs,
        if run.jobs == 1 { "" } else { "s" },
        run.engine.name()
    )?;
    // A column per number B's die shows, then "none"; a row per A's number, then "none".
    let label = |faces: &[u8], k: usize| match faces.get(k) {
        Some(&n) => die_number(Solid::showing(faces).unwrap_or_default(), n),
        None => "none".to_string(),
    };
    write!(out, "A \\ B")?;
    for b in 0..=t.b_faces.len() {
        write!(out, " {:>6}", label(t.b_faces, b))?;
    }
    writeln!(out)?;
    for (a, row) in t.counts.iter().enumerate() {
        write!(out, "{:>5}", label(t.a_faces, a))?;
        for count in row {
            write!(out, " {count:>6}")?;
        }
        writeln!(out)?;
    }
    match t.agreement() {
        Some((share, [low, high])) => writeln!(
            out,
            "agreement  {:.1}% ({} of {}), 95% interval {:.1}–{:.1}%",
            100.0 * share,
            t.agreeing(),
            t.faced(),
            100.0 * low,
            100.0 * high
        )?,
        None => writeln!(out, "agreement  none: no throw ended on a face in both setups")?,
    }
    writeln!(
        out,
        "           over the throws ending on a face in both; {} ended on no face in A or B (\"none\")",
        t.throws() - t.faced()
    )?;
    Ok(())
}

/// What `basin` and `merge` print about a map: its grid, method, axes and the face shares
/// over its `known` cells (those `faces` counts: a summary-only merge reads no cell, but its
/// complete parts know every one).
pub fn map_summary(
    out: &mut dyn Write,
    map: &BasinMap,
    layer: Layer,
    faces: &FaceTally,
    known: u64,
) -> std::io::Result<()> {
    let (x, y) = (&map.x, &map.y);
    let (w, h) = (map.width(), map.height());
    writeln!(out, "{w}×{h} {} map, {}", layer.name(), map.method_report())?;
    writeln!(out, "x  {} from {} to {}", x.key.label(), x.min, x.max)?;
    if h == 1 {
        writeln!(out, "y  {} = {}", y.key.label(), y.value(0))?;
    } else {
        writeln!(out, "y  {} from {} to {}", y.key.label(), y.min, y.max)?;
    }
    let shares: Vec<String> = (faces.numbers().iter().zip(faces.shares()))
        .map(|(f, share)| format!("{f}: {:.1}%", 100.0 * share))
        .collect();
    for line in wrapped("faces over the map  ", &shares, LINE_WIDTH) {
        writeln!(out, "{line}")?;
    }
    writeln!(
        out,
        "cells               {} of {known} with a face (the shares above), {} without; {} of them rolled, the rest filled",
        faces.total(),
        known.saturating_sub(faces.total()),
        map.sampled
    )?;
    Ok(())
}

/// Columns a list is wrapped to: a terminal's 80.
const LINE_WIDTH: usize = 80;

/// `items` after `lead`, joined by ", " and wrapped at `width` columns (characters) onto
/// lines indented as far as `lead`; a line holds at least one item.
fn wrapped(lead: &str, items: &[String], width: usize) -> Vec<String> {
    let indent = " ".repeat(lead.chars().count());
    let mut lines = vec![lead.to_string()];
    for (k, item) in items.iter().enumerate() {
        let last = k + 1 == items.len();
        let piece = if last { item.clone() } else { format!("{item},") };
        let line = lines.last_mut().expect("one line at least");
        let fresh = line.chars().count() == indent.chars().count();
        let room = line.chars().count() + usize::from(!fresh) + piece.chars().count();
        if fresh {
            line.push_str(&piece);
        } else if room <= width {
            line.push(' ');
            line.push_str(&piece);
        } else {
            lines.push(format!("{indent}{piece}"));
        }
    }
    lines
}

/// The table: one column of P(same face) per curve, then chance, ε½ and the start face.
pub fn prediction(out: &mut dyn Write, p: &Prediction) -> std::io::Result<()> {
    let name = |v: Option<f64>| match (&p.key, v) {
        (Some(k), Some(v)) => format!("{k} = {v}"),
        _ => "this setup".to_string(),
    };
    writeln!(
        out,
        "{} random starts per curve, each beside its ε-twin (height, velocity and spin × (1 + ε)), seed {}",
        p.count, p.seed
    )?;
    for c in &p.curves {
        let faced = c.faces.total();
        writeln!(
            out,
            "\n{} ({} starts: {faced} ended on a face, {} did not)",
            name(c.value),
            c.starts,
            c.starts - faced
        )?;
        writeln!(
            out,
            "     ε      P(same face)   95% interval   pairs counted (both on a face)"
        )?;
        for pt in &c.points {
            writeln!(
                out,
                "{:>8}   {:>8.3}      {:.3}–{:.3}    {:>6} of {}",
                // ε as given (1.5e-3, never rounded to 2e-3): the twins were rolled at it.
                format!("{:e}", pt.epsilon),
                pt.same_share,
                pt.interval[0],
                pt.interval[1],
                pt.pairs,
                c.starts
            )?;
        }
        writeln!(
            out,
            "chance Σpᶠ²  {:.3}; halfway {:.3}; ε½ {}",
            c.chance,
            c.half,
            c.threshold.map_or("n/a (no faces)".to_string(), |t| t.text())
        )?;
        writeln!(
            out,
            "start face kept  {:.1}% ({:.1}–{:.1}%)",
            100.0 * c.start_face_share,
            100.0 * c.start_face_interval[0],
            100.0 * c.start_face_interval[1]
        )?;
    }
    Ok(())
}

/// A comparison with real dice: the data against a fair die, a fit's candidates if any, and
/// the real counts beside those simulated with `preset` (at a fit's value nearest its best).
pub fn comparison(out: &mut dyn Write, c: &Comparison, preset: &str) -> std::io::Result<()> {
    if let Some(fairness) = &c.fairness {
        return player_counts(out, c, fairness, preset);
    }
    writeln!(out, "{} ({})", c.dataset.name(), c.data.source)?;
    let fair = &c.data_against_fair;
    writeln!(
        out,
        "the real dice against a fair die: χ² {:.2} on {} dof, p = {}",
        fair.chi_square,
        fair.dof,
        p_text(fair.p_value)
    )?;
    writeln!(out, "{}", c.headline)?;
    if let (Some(fit), Some(key)) = (&c.fit, &c.key) {
        candidates(out, c, key, fit)?;
    }
    comparison_counts(out, c, preset, None)
}

/// A player's counts ("Is my die fair?"): the verdict against a fair die first, in a
/// player's words, then the simulated die's flaw and the rolls it takes to see it, the fit,
/// and each face beside the simulated die's.
fn player_counts(out: &mut dyn Write, c: &Comparison, f: &Fairness, preset: &str) -> std::io::Result<()> {
    let fair = &c.data_against_fair;
    writeln!(out, "Is my die fair? {}", c.data.source)?;
    let verdict = if f.consistent_with_fair {
        "consistent with a fair die"
    } else {
        "unlikely for a fair die"
    };
    writeln!(
        out,
        "your counts: {verdict} (p = {}; χ² {:.2} on {} dof against equal shares, test at 5 %)",
        p_text(fair.p_value),
        fair.chi_square,
        fair.dof
    )?;
    let standing_out: Vec<String> = c
        .data
        .categories
        .iter()
        .zip(&f.residuals_against_fair)
        .filter(|(_, r)| r.abs() > 2.0)
        .map(|(face, r)| format!("{face} ({r:+.1})"))
        .collect();
    match standing_out.as_slice() {
        [] => writeln!(
            out,
            "no face stands out of a fair die's chance (every adjusted residual within ±2)"
        )?,
        faces => writeln!(
            out,
            "faces beyond ±2 of a fair die's chance (adjusted residual): {} (one face in twenty does so by chance)",
            faces.join(", ")
        )?,
    }
    if let Some(shown) = c.shown() {
        let value = match (&c.key, shown.value) {
            (Some(k), Some(v)) => format!(", {k} = {}", fmt_exact(v)),
            _ => String::new(),
        };
        match &f.simulated_against_fair {
            Some(sim) => writeln!(
                out,
                "the simulated {} ({preset}{value}, {} rolls): χ² {:.2} on {} dof against a fair die, p = {}",
                f.die,
                shown.throws,
                sim.chi_square,
                sim.dof,
                p_text(sim.p_value)
            )?,
            None => writeln!(out, "the simulated {}: no roll ended on a face", f.die)?,
        }
        match f.rolls_to_detect {
            Some(n) => writeln!(
                out,
                "rolls a player needs to detect the simulated die's flaw: {n} (χ² against a fair die at 5 %, 80 % power)"
            )?,
            None => writeln!(
                out,
                "rolls a player needs to detect the simulated die's flaw: — (it shows none beyond its own rolls' chance)"
            )?,
        }
    }
    if let (Some(fit), Some(key)) = (&c.fit, &c.key) {
        candidates(out, c, key, fit)?;
        match f.no_flaw_inside {
            Some(true) => writeln!(
                out,
                "no flaw ({key} = 0) is inside the 95 % interval: a fair die explains your counts as well"
            )?,
            Some(false) => writeln!(
                out,
                "no flaw ({key} = 0) is outside the 95 % interval: your counts need the flaw"
            )?,
            None => writeln!(
                out,
                "the fit's range does not hold 0: start it at 0 (no flaw) to ask whether a fair die explains the counts"
            )?,
        }
    }
    comparison_counts(out, c, preset, Some(&f.residuals_against_fair))
}

/// A fit's candidates, one line each with its deviance and test, and the best value.
fn candidates(out: &mut dyn Write, c: &Comparison, key: &str, fit: &FitInterval) -> std::io::Result<()> {
    writeln!(
        out,
        "\nfit of {key}: {} candidates, each with the same {} throws (seed {})",
        c.candidates.len(),
        c.throws,
        c.seed
    )?;
    writeln!(
        out,
        "{:>12}  {:>10}  {:>8}  {:>4}  {:>9}  {:>9}",
        key.rsplit('.').next().unwrap_or(key),
        "deviance",
        "χ²",
        "dof",
        "p",
        "counted"
    )?;
    for k in &c.candidates {
        let (Some(value), Some(deviance)) = (k.value, k.deviance) else {
            continue;
        };
        let counted = format!("{}/{}", k.throws, k.throws + k.uncounted);
        if c.excluded.iter().any(|e| e.value == value) {
            writeln!(
                out,
                "{:>12}  {:>10}  {:>8}  {:>4}  {:>9}  {counted:>9}  excluded",
                candidate_value(value),
                "—",
                "",
                "",
                ""
            )?;
            continue;
        }
        let (chi2, dof, p) = k
            .test
            .as_ref()
            .map_or(("n/a".to_string(), String::new(), String::new()), |t| {
                (
                    format!("{:.2}", t.chi_square),
                    t.dof.to_string(),
                    p_text(t.p_value),
                )
            });
        let mark = if Some(k) == c.shown() {
            " ← nearest the best"
        } else {
            ""
        };
        writeln!(
            out,
            "{:>12}  {deviance:>10.2}  {chi2:>8}  {dof:>4}  {p:>9}  {counted:>9}{mark}",
            candidate_value(value)
        )?;
    }
    exclusions(out, key, &c.excluded)?;
    fit_line(out, key, fit)
}

/// The candidates a fit left out, one line each with its reason (none: nothing printed).
fn exclusions(out: &mut dyn Write, key: &str, excluded: &[Excluded]) -> std::io::Result<()> {
    if excluded.is_empty() {
        return Ok(());
    }
    writeln!(
        out,
        "left out of the fit: {} candidate{} (a candidate counts when every body it throws is within the stability limit at the worst throw, and at least half its throws end on a face)",
        excluded.len(),
        if excluded.len() == 1 { "" } else { "s" }
    )?;
    for e in excluded {
        writeln!(out, "  {key} = {}: {}", fmt_exact(e.value), e.why)?;
    }
    Ok(())
}

/// A candidate's value in its table column: six decimals, or the exact value where those
/// would hide it (`1e-200`, not `0.000000`).
fn candidate_value(v: f64) -> String {
    if v == 0.0 || (1e-3..1e9).contains(&v.abs()) {
        format!("{v:.6}")
    } else {
        fmt_exact(v)
    }
}

/// The real counts beside the simulated ones of the value shown, and their test.
/// `against_fair`: each category's adjusted residual against a fair die, a column of its own
/// (a player's counts).
fn comparison_counts(
    out: &mut dyn Write,
    c: &Comparison,
    preset: &str,
    against_fair: Option<&[f64]>,
) -> std::io::Result<()> {
    let Some(shown) = c.shown() else {
        return writeln!(out, "no simulated throws completed");
    };
    let value = match (&c.key, shown.value) {
        (Some(k), Some(v)) => format!(", {k} = {}", fmt_exact(v)),
        _ => String::new(),
    };
    writeln!(
        out,
        "\n{} real throws against {} simulated ({preset}{value}, seed {}); {} simulated throws not counted (a die ended without a face)",
        c.data.total(),
        shown.throws,
        c.seed,
        shown.uncounted
    )?;
    stability_count(out, shown.past_stability_limit, shown.throws + shown.uncounted)?;
    let rows = c.rows(shown);
    let Some(test) = &shown.test else {
        return writeln!(out, "too few simulated throws to test");
    };
    // The column against a fair die, where every category is a row of its own.
    let against_fair = against_fair.filter(|r| r.len() == rows.len());
    writeln!(
        out,
        "{:>10}  {:>7}  {:>6}  {:>13}{}  {:>9}  {:>6}  {:>13}  {:>8}",
        if against_fair.is_some() {
            "face"
        } else {
            "category"
        },
        "real",
        "share",
        "95% interval",
        if against_fair.is_some() { "  vs fair" } else { "" },
        "simulated",
        "share",
        "95% interval",
        "residual"
    )?;
    let pc = |x: f64| 100.0 * x;
    let interval = |i: [f64; 2]| format!("{:.2}–{:.2}%", pc(i[0]), pc(i[1]));
    for (i, r) in rows.iter().enumerate() {
        writeln!(
            out,
            "{:>10}  {:>7}  {:>5.2}%  {:>13}{}  {:>9}  {:>5.2}%  {:>13}  {:>+8.2}",
            r.category,
            r.data_count,
            pc(r.data_share),
            interval(r.data_interval),
            against_fair.map_or(String::new(), |f| format!("  {:>+7.2}", f[i])),
            r.simulated_count,
            pc(r.simulated_share),
            interval(r.simulated_interval),
            r.residual
        )?;
    }
    writeln!(
        out,
        "χ² of the real against the simulated counts: {:.2} on {} dof, p = {}",
        test.chi_square,
        test.dof,
        p_text(test.p_value)
    )?;
    writeln!(
        out,
        "power of this comparison: {:.0}% for the difference measured (test at 5 %)",
        100.0 * test.power
    )?;
    match test.throws_to_detect {
        Some(n) => writeln!(
            out,
            "real throws that tell this model from the real die: {n} (80 % power, 5 %)"
        ),
        None => writeln!(
            out,
            "real throws that tell this model from the real die: — (no difference measured beyond chance)"
        ),
    }
}

/// A fit's best value and its 95 % interval (an end that reached the range's edge said so).
fn fit_line(out: &mut dyn Write, key: &str, fit: &FitInterval) -> std::io::Result<()> {
    let side = |v: f64, open: bool, words: &str| {
        if open {
            // The range's own end, as typed: the shortest digits (1e-200 as 1e-200).
            format!("{words} {}", fmt_exact(v))
        } else {
            candidate_value(v)
        }
    };
    let how = match fit.method {
        FitMethod::Parabola => "on the least-squares parabola through the candidates' deviances",
        FitMethod::Candidates => "the best candidate; the deviances follow no upward parabola",
    };
    let parabola = if fit.parabola.is_some() {
        ", and where the parabola stays within 3.84 of its minimum"
    } else {
        ""
    };
    let beyond: Vec<String> = fit.beyond.iter().map(|&v| candidate_value(v)).collect();
    let connected = match beyond.as_slice() {
        [] => String::new(),
        [one] => format!("; not one connected set: the candidate {one} inside it lies more than 3.84 above"),
        many => format!(
            "; not one connected set: the candidates {} inside it lie more than 3.84 above",
            many.join(", ")
        ),
    };
    writeln!(
        out,
        "best {key} = {} (deviance {:.2}, {how}); 95 % interval {} to {} (it holds every candidate \
         within 3.84 of the lowest deviance, {:.2}{parabola}){connected}",
        candidate_value(fit.best),
        fit.best_deviance,
        side(fit.low, fit.low_open, "the range's low end,"),
        side(fit.high, fit.high_open, "the range's high end,"),
        fit.lowest_deviance,
    )
}

/// A comparison with Budden's cuboids: the assumptions, the fit on the calibration ratios,
/// and every ratio thrown with `preset` at the best value.
pub fn budden(out: &mut dyn Write, c: &BuddenComparison, preset: &str) -> std::io::Result<()> {
    writeln!(out, "budden ({})", c.source)?;
    for a in &c.assumptions {
        writeln!(out, "assumed: {a}")?;
    }
    let ratios = |rs: &[f64]| {
        rs.iter()
            .map(|r| format!("{r:.2}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let seeds = seeds_text(&c.seeds);
    let Some(key) = &c.key else {
        writeln!(
            out,
            "\nno fit (--no-fit): every ratio thrown with the preset's table as it stands; ratios {} keep the role \
             \"calibrate\" (in sample, if the table was fitted on them), the others are predictions out of sample",
            ratios(&c.calibrate_on)
        )?;
        return budden_ratios(out, c, None, preset);
    };
    writeln!(
        out,
        "\nfit of {} on ratios {}: {} candidates, each with the same throws ({seeds})",
        key,
        ratios(&c.calibrate_on),
        c.candidates.len(),
    )?;
    let short = key.rsplit('.').next().unwrap_or(key);
    writeln!(out, "{short:>12}  {:>10}  square share by ratio", "deviance")?;
    for k in &c.candidates {
        let shares: Vec<String> = k
            .ratios
            .iter()
            .map(|t| {
                format!(
                    "{:.2}: {:.3} ({} of {})",
                    t.ratio,
                    t.square as f64 / t.throws.max(1) as f64,
                    t.throws,
                    t.throws + t.uncounted
                )
            })
            .collect();
        let left_out = c.excluded.iter().any(|e| e.value == k.value);
        writeln!(
            out,
            "{:>12}  {:>10}  {}{}",
            candidate_value(k.value),
            if left_out {
                "—".to_string()
            } else {
                format!("{:.2}", k.deviance)
            },
            shares.join("  "),
            if left_out { "  excluded" } else { "" }
        )?;
    }
    exclusions(out, key, &c.excluded)?;
    let Some(fit) = &c.fit else {
        return writeln!(out, "no fit: too few candidates completed");
    };
    fit_line(out, key, fit)?;
    budden_ratios(out, c, Some(fit.best), preset)
}

/// Every ratio thrown with the best value: Budden's share of square-face landings beside
/// the simulation's, and how many lie within 2σ.
fn budden_ratios(
    out: &mut dyn Write,
    c: &BuddenComparison,
    best: Option<f64>,
    preset: &str,
) -> std::io::Result<()> {
    let with = match (&c.key, best) {
        (Some(key), Some(best)) => format!("{key} = {}", candidate_value(best)),
        _ => "the table as it stands".to_string(),
    };
    writeln!(
        out,
        "\nevery ratio thrown with {with} ({preset}, {}): Budden's share of square-face landings beside the simulation's",
        seeds_text(&c.seeds)
    )?;
    writeln!(
        out,
        "{:>5}  {:>9}  {:>6}  {:>6}  {:>11}  {:>6}  {:>6}  {:>11}  {:>6}  within 2σ",
        "x/y", "role", "real n", "share", "95% interval", "sim n", "share", "95% interval", "z (σ)"
    )?;
    let interval = |i: [f64; 2]| format!("{:.3}–{:.3}", i[0], i[1]);
    for r in &c.ratios {
        let s = &r.shares;
        writeln!(
            out,
            "{:>5.2}  {:>9}  {:>6}  {:>6.3}  {:>11}  {:>6}  {:>6.3}  {:>11}  {:>+6.2}  {}",
            r.ratio,
            match r.role {
                RatioRole::Calibrate => "calibrate",
                RatioRole::Predict => "predict",
            },
            r.data_throws,
            s.data_share,
            interval(s.data_interval),
            r.simulated.throws,
            s.simulated_share,
            interval(s.simulated_interval),
            s.z,
            match (r.excluded, s.within_two_sigma()) {
                (Some(_), _) => "left out",
                (None, true) => "yes",
                (None, false) => "no",
            }
        )?;
    }
    let uncounted: u64 = c.ratios.iter().map(|r| r.simulated.uncounted).sum();
    let thrown: u64 = c
        .ratios
        .iter()
        .map(|r| r.simulated.throws + r.simulated.uncounted)
        .sum();
    writeln!(
        out,
        "{} of {thrown} simulated throws counted, {uncounted} not (the cuboid ended without a face)",
        thrown - uncounted
    )?;
    let past: u64 = c.ratios.iter().map(|r| r.simulated.past_stability_limit).sum();
    stability_count(out, past, thrown)?;
    for r in c.ratios.iter().filter(|r| r.excluded.is_some()) {
        if let Some(why) = r.excluded {
            writeln!(
                out,
                "ratio {:.2} left out of the counts below: {why} (its share rests on too little)",
                r.ratio
            )?;
        }
    }
    for (words, summary) in [
        ("calibration ratios (in sample)", &c.calibrated),
        ("predicted ratios (out of sample)", &c.predicted),
        ("all ratios", &c.all),
    ] {
        if let Some(s) = summary {
            let pooled = if s.pooled.is_empty() {
                String::new()
            } else {
                format!(
                    " (ratios {} pooled: an expected count under 5)",
                    s.pooled
                        .iter()
                        .map(|g| g
                            .iter()
                            .map(|r| format!("{r:.2}"))
                            .collect::<Vec<_>>()
                            .join(" + "))
                        .collect::<Vec<_>>()
                        .join("; ")
                )
            };
            writeln!(
                out,
                "{words}: {} of {} within 2σ; χ² {:.2} on {} dof{pooled}, p = {}",
                s.within_two_sigma,
                s.shares,
                s.chi_square,
                s.dof,
                p_text(s.p_value)
            )?;
        }
    }
    Ok(())
}

/// The shaved die: the uncut die's own bias (zero within its noise for a fair die), then
/// per cut the paired bias and its slope with their intervals, the cut die's own bias
/// beside them, and the experiment's bias where it measured that cut.
pub fn shaved_die(out: &mut dyn Write, c: &ShavedComparison, preset: &str) -> std::io::Result<()> {
    writeln!(out, "shaved-die ({})", c.source)?;
    for a in &c.assumptions {
        writeln!(out, "assumed: {a}")?;
    }
    let interval = |b: &Bias| format!("{:+.4} to {:+.4}", b.interval[0], b.interval[1]);
    writeln!(
        out,
        "\nevery throw with the uncut die and each cut one ({preset}, seed {}, {} throws)",
        c.seed, c.throws
    )?;
    writeln!(
        out,
        "uncut die: 1 or 6 in {} of {} throws, b = {:+.4} ({})",
        c.uncut_one_or_six,
        c.uncut_throws,
        c.uncut.bias,
        interval(&c.uncut)
    )?;
    writeln!(
        out,
        "{:>6}  {:>7}  {:>7}  {:>7}  {:>8}  {:>20}  {:>6}  {:>16}  {:>8}  {:>20}",
        "cut",
        "sim n",
        "cut 1|6",
        "uncut",
        "b paired",
        "95% interval",
        "b/c",
        "95% interval",
        "cut alone",
        "95% interval"
    )?;
    for r in &c.cuts {
        let s = &r.simulated;
        writeln!(
            out,
            "{:>6}  {:>7}  {:>7}  {:>7}  {:>+8.4}  {:>20}  {:>6.2}  {:>16}  {:>+8.4}  {:>20}",
            fmt_exact(r.cut),
            s.throws,
            s.cut_one_or_six,
            s.uncut_one_or_six,
            r.bias.bias,
            interval(&r.bias),
            r.slope.bias,
            format!("{:.2} to {:.2}", r.slope.interval[0], r.slope.interval[1]),
            r.cut_alone.bias,
            interval(&r.cut_alone)
        )?;
    }
    let thrown: u64 = c
        .cuts
        .iter()
        .map(|r| r.simulated.throws + r.simulated.uncounted)
        .sum();
    let uncounted: u64 = c.cuts.iter().map(|r| r.simulated.uncounted).sum();
    writeln!(
        out,
        "{} of {thrown} paired throws counted, {uncounted} not (a die ended without a face)",
        thrown - uncounted
    )?;
    let past: u64 = c.cuts.iter().map(|r| r.simulated.past_stability_limit).sum();
    stability_count(out, past, thrown)?;
    for r in &c.cuts {
        if let Some(d) = &r.data {
            writeln!(
                out,
                "measured at c = {}: b = {:+.4} ± {:.4} ({} of {} rolls on 1 or 6), slope {:.2}; simulated {:+.4}: \
                 z = {:+.2}, {}",
                fmt_exact(r.cut),
                d.bias.bias,
                d.sigma,
                d.one_or_six,
                d.rolls,
                d.bias.bias / r.cut,
                r.bias.bias,
                d.z,
                if d.within_two_sigma() {
                    "within 2σ"
                } else {
                    "not within 2σ"
                }
            )?;
        }
    }
    if c.cuts.iter().all(|r| r.data.is_none()) {
        writeln!(
            out,
            "no cut thrown is one the experiment measured (it measured c = {}): the slopes are to read against its \
             b/c near 2",
            dicesim_experiment::real_data::shaved_die()
                .0
                .iter()
                .map(|r| fmt_exact(r.cut))
                .collect::<Vec<_>>()
                .join(", ")
        )?;
    }
    Ok(())
}

/// A joint fit: the assumptions, the deviance at every grid point (each experiment's and
/// their sum, `*` marking the 95 % region), the points left out, the best point with what
/// each experiment measured there, and the region's extent along each key.
pub fn joint(out: &mut dyn Write, c: &JointComparison, preset: &str) -> std::io::Result<()> {
    writeln!(
        out,
        "joint: Budden's calibration ratios and the shaved die at {} together",
        fmt_exact(c.cut)
    )?;
    for s in &c.sources {
        writeln!(out, "source: {s}")?;
    }
    for a in &c.assumptions {
        writeln!(out, "assumed: {a}")?;
    }
    let ratios: Vec<String> = c.calibrate_on.iter().map(|r| format!("{r:.2}")).collect();
    writeln!(
        out,
        "\njoint fit of {} keys on {preset}: {} grid points, each with the same throws (seed {}): Budden's ratios {} as often as he threw each, the shaved die {} times paired with the uncut die",
        c.keys.len(),
        c.points.len(),
        c.seed,
        ratios.join(", "),
        c.shaved_throws
    )?;
    let heads: Vec<String> = c
        .keys
        .iter()
        .map(|k| format!("{:>12}", k.rsplit('.').next().unwrap_or(k)))
        .collect();
    writeln!(
        out,
        "{}  {:>9}  {:>8}  {:>6}  {:>9}  {:>9}",
        heads.join(" "),
        "Budden G²",
        "shaved b",
        "z",
        "shaved z²",
        "deviance"
    )?;
    for (i, p) in c.points.iter().enumerate() {
        let values: Vec<String> = p
            .values
            .iter()
            .map(|&v| format!("{:>12}", candidate_value(v)))
            .collect();
        let cell = |x: Option<f64>, w: usize, d: usize| {
            x.map_or(format!("{:>w$}", "—"), |x| format!("{x:>w$.d$}"))
        };
        let mark = if c.best == Some(i) {
            "  * best"
        } else if c.in_region(i) {
            "  *"
        } else if p.excluded.is_some() {
            "  left out"
        } else {
            ""
        };
        writeln!(
            out,
            "{}  {}  {}  {}  {}  {}{mark}",
            values.join(" "),
            cell(p.budden_deviance, 9, 2),
            cell(p.shaved.map(|s| s.bias), 8, 4),
            cell(p.shaved.map(|s| s.z), 6, 2),
            cell(p.shaved_deviance, 9, 2),
            cell(p.deviance, 9, 2),
        )?;
    }
    let left_out: Vec<_> = c.points.iter().filter(|p| p.excluded.is_some()).collect();
    if !left_out.is_empty() {
        writeln!(
            out,
            "left out of the fit: {} point{} (a point counts when every body it throws is within the stability limit at the worst throw, and at least half its throws of each ratio, and of the shaved die's pairs, end on a face)",
            left_out.len(),
            if left_out.len() == 1 { "" } else { "s" }
        )?;
        for p in left_out {
            let at: Vec<String> = c
                .keys
                .iter()
                .zip(&p.values)
                .map(|(k, v)| format!("{k} = {}", fmt_exact(*v)))
                .collect();
            writeln!(
                out,
                "  {}: {}",
                at.join(", "),
                p.excluded.map_or(String::new(), |e| e.to_string())
            )?;
        }
    }
    let (Some(best), Some(lowest)) = (c.best_point(), c.lowest_deviance) else {
        return writeln!(out, "no fit: no grid point completed");
    };
    let at: Vec<String> = c
        .keys
        .iter()
        .zip(&best.values)
        .map(|(k, v)| format!("{k} = {}", fmt_exact(*v)))
        .collect();
    writeln!(
        out,
        "best point: {} (deviance {lowest:.2}: Budden {:.2} over {} ratios, shaved die {:.2})",
        at.join(", "),
        best.budden_deviance.unwrap_or(f64::NAN),
        best.ratios.len(),
        best.shaved_deviance.unwrap_or(f64::NAN),
    )?;
    for t in &best.ratios {
        writeln!(
            out,
            "  ratio {:.2}: {} of {} simulated on a square face ({:.3}), {} not counted",
            t.ratio,
            t.square,
            t.throws,
            t.square as f64 / t.throws.max(1) as f64,
            t.uncounted
        )?;
    }
    if let Some(s) = best.shaved {
        writeln!(
            out,
            "  shaved die at {}: b = {:+.4} ({:+.4} to {:+.4}), against the measured 0.06: z = {:+.2}; {} of {} pairs counted",
            fmt_exact(c.cut),
            s.bias,
            s.interval[0],
            s.interval[1],
            s.z,
            s.throws,
            s.throws + s.uncounted
        )?;
    }
    writeln!(
        out,
        "95 % region: the {} point{} within {:.2} of the lowest (χ² of {} degrees of freedom, one per key; marked *)",
        c.region.len(),
        if c.region.len() == 1 { "" } else { "s" },
        c.region_rise,
        c.keys.len()
    )?;
    for r in &c.region_ranges {
        writeln!(
            out,
            "  {}: {}{} to {}{}",
            r.key,
            fmt_exact(r.low),
            if r.low_open {
                " (the range's low end: open)"
            } else {
                ""
            },
            fmt_exact(r.high),
            if r.high_open {
                " (the range's high end: open)"
            } else {
                ""
            },
        )?;
    }
    Ok(())
}

/// A p-value as a person reads it: four decimals, or scientific notation when tiny.
fn p_text(p: f64) -> String {
    if p >= 1e-4 {
        format!("{p:.4}")
    } else {
        format!("{p:.2e}")
    }
}

/// The roll as text: its ending in words (a die's number as a player reads it: 0 to 9 on
/// the d10, 00 to 90 on the d%), then its steps, time, stopping energy and final state.
pub fn one_roll(
    out: &mut dyn Write,
    (params, initial): (&Params, &InitialCondition),
    rolled: &OneRoll,
) -> std::io::Result<()> {
    let OneRoll {
        roll,
        outcome,
        reason,
    } = rolled;
    let rule = roll.stop_rule_now();
    let verdict = match (outcome.status, outcome.face) {
        (Status::Settled, Some(f)) => format!("face {} (settled)", die_number(params.die.kind, f)),
        (Status::Settled, None) if roll.is_polyhedral() => {
            "settled, but on an edge or a vertex: no face is down".to_string()
        }
        (Status::Settled, None) => "settled, but the 4 highest corners form no face".to_string(),
        (Status::Timeout, _) => match why_it_cannot_settle_roll(roll) {
            Some(why) => format!("did not settle within {} s: {why}", params.integrator.max_time),
            None => format!("did not settle within {} s", params.integrator.max_time),
        },
        (Status::Unstable, _) => match reason {
            Some(reason) => format!("unstable: {reason}"),
            None => format!(
                "unstable: the energy ran away; {}",
                Verdict::of(params, initial).words
            ),
        },
    };
    let v3 = |v: &nalgebra::Vector3<f64>| format!("({:.6}, {:.6}, {:.6})", v.x, v.y, v.z);
    writeln!(out, "{verdict}")?;
    // An unstable roll's verdict names the limit already; any other ending past one is not
    // what the model gives, however plain it looks.
    let stability = Verdict::of(params, initial);
    if stability.exceeded() && outcome.status != Status::Unstable {
        writeln!(
            out,
            "stability         past its limit, so this ending is the step's, not the model's: {}",
            stability.words
        )?;
    }
    writeln!(out, "steps             {}", outcome.steps)?;
    writeln!(out, "simulated time    {:.3} s", outcome.time_s)?;
    if rule.can_settle() {
        writeln!(
            out,
            "stop energy       {:.1} erg (threshold {:.1} erg, {}); kinetic {:.1} erg (threshold {:.1} erg)",
            roll.stop_energy(),
            rule.energy_threshold,
            params.integrator.stop_energy.name(),
            roll.stop_kinetic_energy(),
            rule.kinetic_threshold
        )?;
    } else {
        writeln!(
            out,
            "stop energy       {:.1} erg ({}; no threshold: this table cannot hold a face)",
            roll.stop_energy(),
            params.integrator.stop_energy.name()
        )?;
    }
    writeln!(out, "position          {} cm", v3(&roll.position()))?;
    writeln!(out, "velocity          {} cm/s", v3(&roll.velocity()))?;
    writeln!(out, "angular momentum  {} g·cm²/s", v3(&roll.angular_momentum()))?;
    Ok(())
}

/// A batch's summary: its rolls and how they ran, the counts, and the speed.
pub fn batch_run(out: &mut dyn Write, batch: &BatchRun) -> std::io::Result<()> {
    let s = &batch.summary;
    writeln!(
        out,
        "{} rolls on {} thread{}, {} engine",
        s.rolls,
        batch.jobs,
        if batch.jobs == 1 { "" } else { "s" },
        batch.engine.name()
    )?;
    batch_counts(out, s)?;
    stability_count(out, batch.past_stability_limit, s.rolls)?;
    writeln!(
        out,
        "speed                  {:.0} rolls/s, {:.1} M steps/s ({} steps in {:.2} s)",
        s.rolls_per_s,
        s.steps_per_s / 1e6,
        s.steps,
        s.elapsed_s
    )?;
    Ok(())
}

/// A merged batch's summary: the counts, the shards' speed, the records rolled again and
/// the files written.
pub fn merged_batch(stdout: &mut dyn Write, m: &BatchMerge, wrote: &[PathBuf]) -> std::io::Result<()> {
    let summary = &m.summary;
    writeln!(stdout, "{} rolls in {} shards", summary.rolls, m.shards)?;
    batch_counts(stdout, summary)?;
    if let Some(past) = m.past_stability_limit {
        stability_count(stdout, past, summary.rolls)?;
    }
    writeln!(
        stdout,
        "speed                  {:.0} rolls per shard-second ({} steps; the shards took {:.2} s together, the longest {:.2} s)",
        summary.rolls_per_s, summary.steps, m.shard_s, m.longest_s
    )?;
    if m.verified > 0 {
        writeln!(
            stdout,
            "verified               {} records chosen at random, rolled again: identical bit for bit",
            m.verified
        )?;
    }
    for path in wrote {
        writeln!(stdout, "wrote                  {}", path.display())?;
    }
    Ok(())
}

/// A merged map's summary: its faces, the cells rolled again, the shards' time and the files
/// written.
pub fn merged_map(stdout: &mut dyn Write, m: &MapMerge, wrote: &[PathBuf]) -> std::io::Result<()> {
    map_summary(stdout, &m.map, m.layer, &m.faces, m.known_cells())?;
    if m.verified > 0 {
        writeln!(
            stdout,
            "verified            {} cells chosen at random, rolled again: identical bit for bit",
            m.verified
        )?;
    }
    writeln!(
        stdout,
        "time                {:.2} s over {} shards (the longest {:.2} s)",
        m.shard_s, m.shards, m.longest_s
    )?;
    for path in wrote {
        writeln!(stdout, "wrote               {}", path.display())?;
    }
    Ok(())
}

/// What the animation holds: its frames and time, each die's ending, where it went.
pub fn animation(
    out: &mut dyn Write,
    animated: &Animated,
    twin: Option<f64>,
    speed: f64,
    (fps, size): (u32, (u32, u32)),
    wrote: &Path,
) -> std::io::Result<()> {
    let face = |o: &Outcome| match o.face {
        Some(f) => format!("face {f} ({})", o.status.name()),
        None => o.status.name().to_string(),
    };
    writeln!(
        out,
        "{} frames, {:.2} s of roll at {} frames/s and {}, {}×{} pixels",
        animated.frames,
        animated.duration_s,
        fps,
        speed_words(speed),
        size.0,
        size.1
    )?;
    // Names padded by characters, not bytes (ε is two bytes), so the values line up.
    let line = |name: &str, value: &str| format!("{name:<18}{value}");
    writeln!(out, "{}", line("die", &face(&animated.outcome)))?;
    if let (Some(t), Some(e)) = (&animated.twin, twin) {
        writeln!(out, "{}", line(&format!("twin (ε {e:e})"), &face(t)))?;
    }
    writeln!(out, "{}", line("wrote", &wrote.display().to_string()))?;
    out.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> String {
        let mut out = Vec::new();
        write(&mut out).unwrap();
        String::from_utf8(out).unwrap()
    }

    /// 200 settled rolls of a d20: faces 1..10 off their expected 10 by +5 −5 +4 −4 +3 −3
    /// +2 −2 +1 −1, faces 11..20 on it.
    fn d20_summary() -> BatchSummary {
        use dicesim_experiment::tally::Tally;
        use dicesim_physics::Status;
        let numbers: &[u8] = &[
            1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
        ];
        let mut counts = [10u64; 20];
        for (k, d) in [5i64, -5, 4, -4, 3, -3, 2, -2, 1, -1].into_iter().enumerate() {
            counts[k] = (10 + d) as u64;
        }
        let mut records = Vec::new();
        for (&face, &count) in numbers.iter().zip(&counts) {
            for _ in 0..count {
                records.push(dicesim_experiment::RollRecord {
                    id: records.len() as u64,
                    initial: InitialCondition::default(),
                    outcome: Outcome {
                        status: Status::Settled,
                        face: Some(face),
                        steps: 1,
                        time_s: 0.001,
                        impacts: 0,
                        first_impact: None,
                    },
                    start_face: face,
                });
            }
        }
        Tally::of_records(numbers, &records).summary(std::time::Duration::ZERO)
    }

    #[test]
    fn a_d20s_summary_lists_its_twenty_faces_within_80_columns() {
        let table = text(|out| batch_counts(out, &d20_summary()));
        let lines: Vec<&str> = table.lines().collect();
        // The header, then one row per face in the die's order.
        let rows = &lines[1..21];
        for (k, row) in rows.iter().enumerate() {
            assert!(row.starts_with(&format!("{:>4} ", k + 1)), "{row}");
            assert!(row.chars().count() <= 80, "{row}");
        }
        // 15 of 200 = 7.5 %, its Wilson interval (0.075 + 0.0096)/1.0192 ∓ 0.0370 =
        // 4.6–12.0 %; face 20 on its expected 10, 5.0 %.
        assert_eq!(rows[0], "   1      15    7.5%    4.6–12.0%");
        assert!(rows[19].starts_with("  20      10    5.0%"), "{}", rows[19]);
        // χ² = 2·(25 + 16 + 9 + 4 + 1)/10 = 11 on 19 dof; p = 0.92384 (the odd-dof closed
        // form, stats.rs), printed to four decimals.
        assert_eq!(lines[21], "χ² against a fair die  11.000 (19 dof), p = 0.9238");
        assert!(lines[21].chars().count() <= 80);
        assert_eq!(
            lines[22],
            "bias detectable in     — (no bias measured beyond chance)"
        );
    }

    #[test]
    fn a_long_list_wraps_at_80_columns_under_its_lead() {
        let lead = "faces over the map  ";
        let d20: Vec<String> = (1..=20).map(|f| format!("{f}: 5.0%")).collect();
        // 20 columns of lead, then "n: 5.0%," (8) or "nn: 5.0%," (9) with a space between:
        // 1–6 end at column 73 (7 would end at 82), 7–12 at 76, 13–18 at 79, then 19–20.
        let lines = wrapped(lead, &d20, 80);
        let pad = " ".repeat(20);
        assert_eq!(
            lines,
            [
                format!("{lead}1: 5.0%, 2: 5.0%, 3: 5.0%, 4: 5.0%, 5: 5.0%, 6: 5.0%,"),
                format!("{pad}7: 5.0%, 8: 5.0%, 9: 5.0%, 10: 5.0%, 11: 5.0%, 12: 5.0%,"),
                format!("{pad}13: 5.0%, 14: 5.0%, 15: 5.0%, 16: 5.0%, 17: 5.0%, 18: 5.0%,"),
                format!("{pad}19: 5.0%, 20: 5.0%"),
            ]
        );
        // Six faces stay on the one line they always had.
        let d6: Vec<String> = (1..=6).map(|f| format!("{f}: 16.7%")).collect();
        assert_eq!(wrapped(lead, &d6, 80), [format!("{lead}{}", d6.join(", "))]);
    }

    #[test]
    fn p_values_read_as_four_decimals_until_tiny() {
        assert_eq!(p_text(0.5), "0.5000");
        assert_eq!(p_text(1e-4), "0.0001");
        assert_eq!(p_text(0.000012345), "1.23e-5");
    }

    #[test]
    fn extreme_fit_values_read_as_numbers_not_as_hundreds_of_digits() {
        // A fit bound of 1e-200 printed as a 202-character decimal (issue 36, item 6).
        let fit = FitInterval {
            best: 1e-200,
            best_deviance: 0.5,
            best_index: 0,
            low: 1e-200,
            low_open: true,
            high: 2.5e-7,
            high_open: false,
            method: FitMethod::Candidates,
            lowest_deviance: 0.5,
            beyond: Vec::new(),
            parabola: None,
        };
        let line = text(|out| fit_line(out, "ground.damping", &fit));
        assert!(
            line.starts_with("best ground.damping = 1e-200 (deviance 0.50"),
            "{line}"
        );
        assert!(line.contains("the range's low end, 1e-200 to 2.5e-7 "), "{line}");
        assert!(line.len() < 250, "{line}");
        assert_eq!(candidate_value(0.0), "0.000000");
        assert_eq!(candidate_value(12040.0), "12040.000000");
    }

    #[test]
    fn a_fits_interval_says_where_it_reached_the_range() {
        let fit = FitInterval {
            best: 0.5,
            best_deviance: 1.234,
            best_index: 3,
            low: 0.2,
            low_open: true,
            high: 0.75,
            high_open: false,
            method: FitMethod::Parabola,
            lowest_deviance: 0.987,
            beyond: Vec::new(),
            parabola: Some([1.0, -1.0, 1.5]),
        };
        assert_eq!(
            text(|out| fit_line(out, "ground.friction", &fit)),
            "best ground.friction = 0.500000 (deviance 1.23, on the least-squares parabola through the \
             candidates' deviances); 95 % interval the range's low end, 0.2 to 0.750000 (it holds every \
             candidate within 3.84 of the lowest deviance, 0.99, and where the parabola stays within 3.84 \
             of its minimum)\n"
        );
        // Candidates inside the interval beyond the line: the set is not connected, and said so.
        let split = FitInterval {
            beyond: vec![0.4, 0.6],
            ..fit
        };
        assert!(text(|out| fit_line(out, "ground.friction", &split)).ends_with(
            "; not one connected set: the candidates 0.400000, 0.600000 inside it lie more than \
                 3.84 above\n"
        ));
    }
}
