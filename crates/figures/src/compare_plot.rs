//! A comparison with real dice as a PNG image: the data's share of each category beside
//! the simulation's, both with their 95 % intervals; with a fit, the deviance of every
//! candidate beside it, the 3.84 line and the interval it cuts.

use crate::figure::setup_value;
use crate::figure::{Ticks, resolved};
use crate::plot::random_starts;
use crate::plot::{Record, Scale, TICKS, plot_error, png_bytes, register_fonts, with_caption};
use dicesim_experiment::Error;
use dicesim_experiment::compare::{CompareSpec, Comparison, CountsSpec, FitSpec};
use dicesim_experiment::compare_budden::{BuddenComparison, BuddenSpec, RatioRole, hand_throw, seeds_text};
use dicesim_experiment::compare_shaved::{Bias, CutResult, ShavedComparison, ShavedSpec, drop_throw};
use dicesim_experiment::compare_stats::{FitInterval, deviance_rise_95};
use dicesim_setup::keys::ScanKey;
use dicesim_setup::preset::Preset;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// Image size in pixels.
pub(crate) const SIZE: (u32, u32) = (1400, 760);

/// Okabe–Ito: blue for the real dice, vermilion for the simulation.
const DATA: RGBColor = RGBColor(0, 114, 178);
const SIMULATED: RGBColor = RGBColor(213, 94, 0);

/// The comparison as the bytes of a PNG file; `record` is captioned and written into it.
pub fn comparison_png(comparison: &Comparison, record: &Record) -> Result<Vec<u8>, Error> {
    register_fonts()?;
    png_bytes(SIZE, record, |root| {
        root.fill(&WHITE).map_err(plot_error)?;
        let picture = with_caption(&root, record, Scale::ONE)?;
        if comparison.fit.is_some() {
            let (left, right) = picture.split_horizontally(SIZE.0 * 3 / 5);
            draw_shares(&left, comparison)?;
            draw_comparison_deviance(&right, comparison)?;
        } else {
            draw_shares(&picture, comparison)?;
        }
        root.present().map_err(plot_error)
    })
}

/// The PNG's caption: the throws (drawn from the random ranges: those define the figure)
/// and the fit, and the setup whose throws are drawn: a fit's shown value.
pub fn comparison_record(
    c: &Comparison,
    preset: &Preset,
    spec: &CompareSpec,
    fit_text: Option<&str>,
    provenance: &serde_json::Value,
) -> Record {
    let thrown = format!("{} throws as {} threw them", spec.throws, spec.dataset.name());
    let title = format!("{} against real dice", preset.name);
    record(
        c,
        preset,
        (spec.fit.as_ref(), fit_text),
        spec.seed,
        &thrown,
        &title,
        provenance,
    )
}

/// The PNG's caption of a player's counts against the simulated die: as
/// [`comparison_record`]'s, with the counts' origin and the die.
pub fn counts_record(
    c: &Comparison,
    preset: &Preset,
    spec: &CountsSpec,
    fit_text: Option<&str>,
    provenance: &serde_json::Value,
) -> Record {
    let thrown = format!(
        "{} simulated rolls against {} counted rolls of a {} ({})",
        spec.throws,
        spec.counts.total(),
        spec.counts.die,
        spec.counts.origin
    );
    let title = format!("{}: is the {} fair?", preset.name, spec.counts.die);
    record(
        c,
        preset,
        (spec.fit.as_ref(), fit_text),
        spec.seed,
        &thrown,
        &title,
        provenance,
    )
}

/// The caption both comparisons of counts by face share: `thrown` says what was thrown.
fn record(
    c: &Comparison,
    preset: &Preset,
    (fit_spec, fit_text): (Option<&FitSpec>, Option<&str>),
    seed: u64,
    thrown: &str,
    title: &str,
    provenance: &serde_json::Value,
) -> Record {
    let (mut shown, mut initial) = (preset.params(), preset.initial);
    let value = c.shown().and_then(|k| k.value);
    if let (Some(fit), Some(value)) = (fit_spec, value) {
        fit.key.set(&mut shown, &mut initial, value);
    }
    let fit = match (fit_text, fit_spec, value, &c.key, &c.fit) {
        (Some(f), Some(fit), Some(v), Some(k), Some(i)) => format!(
            "; --fit {f} over {} candidates, drawn at the best, {k} = {}; 95 % interval {} to {}{}",
            fit.candidates,
            setup_value(v),
            setup_value(i.low),
            setup_value(i.high),
            if i.connected() {
                ""
            } else {
                " (the candidates within 3.84 are not one connected set)"
            }
        ),
        _ => String::new(),
    };
    // What the figure rests on: the throws counted (every die on a face) and those not.
    let counted = c.shown().map_or(String::new(), |k| {
        format!(
            "; {} of {} throws counted, {} ended with a die on no face{}",
            k.throws,
            k.throws + k.uncounted,
            k.uncounted,
            match c.excluded.len() {
                0 => String::new(),
                n => format!(", {n} candidates left out of the fit for too few"),
            }
        )
    });
    let experiment = format!(
        "{}: {thrown}, each die {}{fit}{counted}; {}",
        preset.name,
        random_starts(&preset.random, seed, &[]),
        c.headline,
    );
    Record::of_experiment(title, experiment, &shown, &[], provenance)
}

/// The PNG's caption: the throw, the fit, and the table and body assumptions.
pub fn budden_record(
    c: &BuddenComparison,
    preset: &Preset,
    spec: &BuddenSpec,
    fit_text: Option<&str>,
    provenance: &serde_json::Value,
) -> Record {
    let n = setup_value;
    let throws = spec
        .throws
        .map_or("Budden's own throws per ratio".to_string(), |t| {
            format!("{t} throws per ratio")
        });
    let best = match (&c.fit, &c.key) {
        (Some(f), Some(key)) => format!(", drawn at the best, {key} = {}", n(f.best)),
        _ => String::new(),
    };
    let thrown: u64 = c
        .ratios
        .iter()
        .map(|r| r.simulated.throws + r.simulated.uncounted)
        .sum();
    let uncounted: u64 = c.ratios.iter().map(|r| r.simulated.uncounted).sum();
    let at = if spec.fit.is_some() { " at the best" } else { "" };
    let best = format!(
        "{best}; {} of {thrown} throws{at} counted, {uncounted} ended on no face",
        thrown - uncounted
    );
    // The table and world as the throws were drawn: with the fitted value at its best.
    let (mut p, mut initial) = (preset.params(), preset.initial);
    if let (Some(f), Some(fit)) = (&c.fit, &spec.fit) {
        fit.key.set(&mut p, &mut initial, f.best);
    }
    let ratios = spec
        .calibrate_on
        .iter()
        .map(|r| n(*r))
        .collect::<Vec<_>>()
        .join(", ");
    let fitted = match (fit_text, &spec.fit) {
        (Some(text), Some(fit)) => format!(
            "--fit {text} over {} candidates on ratios {ratios}",
            fit.candidates
        ),
        _ => format!("--no-fit: the preset's table as it stands, ratios {ratios} in sample"),
    };
    // The caption's throws name the first seed; several are pooled.
    let pooled = match spec.seeds.as_slice() {
        [_] => String::new(),
        seeds => format!(" ({})", seeds_text(seeds)),
    };
    let caption = vec![
        format!(
            "{}: {throws}{pooled}, each {}; {fitted}{best}",
            preset.name,
            random_starts(&hand_throw(&preset.random), spec.seeds[0], &[]),
        ),
        format!(
            "{}; table k {} dyn/cm, γ {} s/cm, μ {}; g {} cm/s², Δt {} s (every value in the file's dicesim-provenance text)",
            c.assumptions[..2].join("; "),
            n(p.ground.stiffness),
            n(p.ground.damping),
            n(p.ground.friction),
            n(p.world.gravity),
            n(p.integrator.dt),
        ),
    ];
    let title = format!("{}: Budden's cuboids", preset.name);
    Record::captioned(title, caption, dicesim_experiment::PROGRAM).with_provenance(provenance)
}

/// How far apart a fit's candidates are (what its best value is known to), or a
/// ten-thousandth where there is no fit.
fn candidate_spacing(comparison: &Comparison) -> f64 {
    let values: Vec<f64> = comparison.candidates.iter().filter_map(|c| c.value).collect();
    match values.as_slice() {
        [first, .., last] if values.len() > 1 => (last - first).abs() / (values.len() - 1) as f64,
        _ => 1e-4,
    }
}

fn draw_shares(area: &DrawingArea<BitMapBackend<'_>, Shift>, comparison: &Comparison) -> Result<(), Error> {
    let Some(candidate) = comparison.shown() else {
        return Ok(());
    };
    let rows = comparison.rows(candidate);
    let top = rows
        .iter()
        .map(|r| r.data_interval[1].max(r.simulated_interval[1]))
        .fold(0.0, f64::max)
        * 1.1;
    let n = rows.len().max(1) as f64;
    let value = match (&comparison.key, candidate.value) {
        (Some(k), Some(v)) => format!(", {k} = {}", resolved(v, candidate_spacing(comparison))),
        _ => String::new(),
    };
    // A player's counts are "yours", a fair die's share drawn across them.
    let player = comparison.fairness.as_ref();
    let title = match player {
        Some(f) => format!(
            "your {}: {} counted rolls against {} simulated{value}",
            f.die,
            comparison.data.total(),
            candidate.throws
        ),
        None => format!(
            "{}: {} real throws against {} simulated{value}",
            comparison.dataset.name(),
            comparison.data.total(),
            candidate.throws
        ),
    };
    let yt = Ticks::new(0.0, top.max(1e-3), TICKS);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 22))
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(80)
        .build_cartesian_2d(-0.5..n - 0.5, 0.0..top.max(1e-3))
        .map_err(plot_error)?;
    let names: Vec<String> = rows.iter().map(|r| r.category.clone()).collect();
    let label = |x: &f64| {
        let i = x.round();
        if (x - i).abs() < 1e-9 && i >= 0.0 {
            names.get(i as usize).cloned().unwrap_or_default()
        } else {
            String::new()
        }
    };
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(rows.len())
        .x_label_formatter(&label)
        .x_desc(comparison.dataset.category_words())
        .y_desc("share of throws, with 95 % intervals")
        .y_labels(TICKS)
        .y_label_formatter(&|v| yt.label(*v))
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 19))
        .draw()
        .map_err(plot_error)?;
    let offset = 0.15;
    let pairs: Vec<(f64, [[f64; 3]; 2])> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let (d, m) = (r.data_interval, r.simulated_interval);
            (
                i as f64,
                [[d[0], r.data_share, d[1]], [m[0], r.simulated_share, m[1]]],
            )
        })
        .collect();
    if player.is_some() {
        let fair = 1.0 / n;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(-0.5, fair), (n - 0.5, fair)],
                BLACK.mix(0.5),
            )))
            .map_err(plot_error)?
            .label(format!("a fair die: 1/{n}"))
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLACK.mix(0.5)));
    }
    let names = if player.is_some() {
        ["your counts", "simulated"]
    } else {
        ["real dice", "simulated"]
    };
    // Caps a tenth of a category wide.
    draw_share_pairs(&mut chart, &pairs, names, offset, 0.05)?;
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 18))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(plot_error)?;
    Ok(())
}

fn draw_comparison_deviance(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    comparison: &Comparison,
) -> Result<(), Error> {
    let (Some(fit), Some(key)) = (&comparison.fit, &comparison.key) else {
        return Ok(());
    };
    let points: Vec<(f64, f64)> = comparison
        .candidates
        .iter()
        .filter_map(|c| Some((c.value?, c.deviance?)))
        .collect();
    draw_deviance(area, key, fit, &points, candidate_spacing(comparison))
}

/// A fit's deviance at each candidate (`points`: value, deviance), the parabola through
/// them, the 3.84 line and the interval it cuts; `spacing` is the candidates' step.
fn draw_deviance(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    key: &str,
    fit: &FitInterval,
    points: &[(f64, f64)],
    spacing: f64,
) -> Result<(), Error> {
    let (x0, x1) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let top = points.iter().map(|p| p.1).fold(0.0, f64::max) * 1.05;
    // The candidates' line (the lowest candidate's deviance + 3.84), and the parabola's own
    // (its minimum + 3.84): the interval holds what lies under either.
    let limit = fit.candidate_limit();
    let parabola_limit = fit.best_deviance + deviance_rise_95();
    let x_hi = x1.max(x0 + 1e-12);
    let y_hi = top.max(limit.max(parabola_limit) * 1.05);
    let (xt, yt) = (Ticks::new(x0, x_hi, TICKS), Ticks::new(0.0, y_hi, TICKS));
    // The fitted key's unit, on the axis and after the best value (none if dimensionless).
    let unit = ScanKey::named(key)
        .map(|k| k.unit())
        .ok()
        .filter(|u| !u.is_empty())
        .map_or(String::new(), |u| format!(" {u}"));
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "deviance against {key}: best {}{unit}",
                resolved(fit.best, spacing)
            ),
            ("sans-serif", 22),
        )
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(80)
        .build_cartesian_2d(x0..x_hi, 0.0..y_hi)
        .map_err(plot_error)?;
    draw_axes(
        &mut chart,
        match unit.as_str() {
            "" => key.to_string(),
            u => format!("{key} ({})", u.trim()),
        },
        "deviance G²",
        &xt,
        &yt,
    )?;
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(fit.low, 0.0), (fit.high, limit)],
            DATA.mix(0.15).filled(),
        )))
        .map_err(plot_error)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(x0, limit), (x1, limit)],
            ShapeStyle::from(BLACK.mix(0.6)).stroke_width(1),
        )))
        .map_err(plot_error)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            points.to_vec(),
            SIMULATED.mix(0.5).stroke_width(1),
        )))
        .map_err(plot_error)?;
    if let Some([a, b, c]) = fit.parabola {
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(x0, parabola_limit), (x1, parabola_limit)],
                ShapeStyle::from(DATA.mix(0.6)).stroke_width(1),
            )))
            .map_err(plot_error)?;
        let curve = (0..=200).map(|i| {
            let x = x0 + (x1 - x0) * f64::from(i) / 200.0;
            (x, (a * x + b) * x + c)
        });
        chart
            .draw_series(std::iter::once(PathElement::new(
                curve.collect::<Vec<_>>(),
                DATA.stroke_width(2),
            )))
            .map_err(plot_error)?;
    }
    chart
        .draw_series(points.iter().map(|&p| Circle::new(p, 4, SIMULATED.filled())))
        .map_err(plot_error)?;
    // A candidate inside the interval but beyond the line: ringed, the set's gap (the
    // caption says the set is not connected).
    chart
        .draw_series(
            points
                .iter()
                .filter(|p| fit.beyond.contains(&p.0))
                .map(|&p| Circle::new(p, 8, BLACK.stroke_width(2))),
        )
        .map_err(plot_error)?;
    Ok(())
}

/// The axes of a chart of two numbers: each described, labelled at `TICKS` round values.
fn draw_axes(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    x_desc: impl Into<String>,
    y_desc: &str,
    xt: &Ticks,
    yt: &Ticks,
) -> Result<(), Error> {
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_labels(TICKS)
        .y_labels(TICKS)
        .x_label_formatter(&|v| xt.label(*v))
        .y_label_formatter(&|v| yt.label(*v))
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 19))
        .draw()
        .map_err(plot_error)
}

/// The data's and the simulation's share at each `x` (each as low end, share, high end),
/// side by side `offset` apart, as dots with their 95 % intervals (caps `cap` wide), named in
/// the legend by `names`.
fn draw_share_pairs(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    pairs: &[(f64, [[f64; 3]; 2])],
    names: [&str; 2],
    offset: f64,
    cap: f64,
) -> Result<(), Error> {
    for (k, (colour, side)) in [(DATA, -offset), (SIMULATED, offset)].into_iter().enumerate() {
        let points: Vec<(f64, [f64; 3])> = pairs.iter().map(|&(x, both)| (x + side, both[k])).collect();
        draw_intervals(chart, &points, colour, cap, Some(names[k]))?;
    }
    Ok(())
}

/// Dots at each `x` with their 95 % intervals (each as low end, share, high end; caps `cap`
/// wide) in `colour`, named in the legend by `name` where one is given.
fn draw_intervals(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    points: &[(f64, [f64; 3])],
    colour: RGBColor,
    cap: f64,
    name: Option<&str>,
) -> Result<(), Error> {
    chart
        .draw_series(points.iter().flat_map(|&(x, [lo, _, hi])| {
            [
                vec![(x, lo), (x, hi)],
                vec![(x - cap, lo), (x + cap, lo)],
                vec![(x - cap, hi), (x + cap, hi)],
            ]
            .map(|line| PathElement::new(line, colour.stroke_width(2)))
        }))
        .map_err(plot_error)?;
    let dots = chart
        .draw_series(
            points
                .iter()
                .map(|&(x, [_, mid, _])| Circle::new((x, mid), 5, colour.filled())),
        )
        .map_err(plot_error)?;
    if let Some(name) = name {
        dots.label(name)
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, colour.filled()));
    }
    Ok(())
}

/// Budden's comparison as the bytes of a PNG file: the shares by ratio on the left, the
/// fit's deviance on the right.
pub fn budden_png(comparison: &BuddenComparison, record: &Record) -> Result<Vec<u8>, Error> {
    register_fonts()?;
    png_bytes(SIZE, record, |root| {
        root.fill(&WHITE).map_err(plot_error)?;
        let picture = with_caption(&root, record, Scale::ONE)?;
        // Without a fit (--no-fit) the shares take the whole picture.
        let (Some(fit), Some(key)) = (&comparison.fit, &comparison.key) else {
            draw_budden_shares(&picture, comparison)?;
            return root.present().map_err(plot_error);
        };
        let (left, right) = picture.split_horizontally(SIZE.0 * 3 / 5);
        draw_budden_shares(&left, comparison)?;
        let points: Vec<(f64, f64)> = comparison
            .candidates
            .iter()
            .map(|c| (c.value, c.deviance))
            .collect();
        let spacing = match points.as_slice() {
            [first, .., last] => (last.0 - first.0) / (points.len() - 1) as f64,
            _ => 1e-4,
        };
        draw_deviance(&right, key, fit, &points, spacing)?;
        root.present().map_err(plot_error)
    })
}

fn draw_budden_shares(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    comparison: &BuddenComparison,
) -> Result<(), Error> {
    let rows = &comparison.ratios;
    let (x0, x1) = (0.3, 2.8);
    let (xt, yt) = (Ticks::new(x0, x1, TICKS), Ticks::new(0.0, 1.0, TICKS));
    let predicted = rows.iter().filter(|r| r.role == RatioRole::Predict);
    let (count, within) = (
        predicted.clone().count(),
        predicted.filter(|r| r.shares.within_two_sigma()).count(),
    );
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("Budden's cuboids: {within} of {count} predicted ratios within 2σ"),
            ("sans-serif", 22),
        )
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(80)
        .build_cartesian_2d(x0..x1, 0.0..1.0)
        .map_err(plot_error)?;
    draw_axes(
        &mut chart,
        "ratio x/y (length between the square faces over their side)",
        "share of throws on a square face, with 95 % intervals",
        &xt,
        &yt,
    )?;
    // The two series a little apart so their intervals do not hide each other.
    let offset = 0.012;
    let pairs: Vec<(f64, [[f64; 3]; 2])> = rows
        .iter()
        .map(|r| {
            let s = &r.shares;
            let (d, m) = (s.data_interval, s.simulated_interval);
            (
                r.ratio,
                [[d[0], s.data_share, d[1]], [m[0], s.simulated_share, m[1]]],
            )
        })
        .collect();
    draw_share_pairs(&mut chart, &pairs, ["Budden", "simulated"], offset, 0.01)?;
    // The calibration ratios ringed: the fit saw them, the others are predictions.
    chart
        .draw_series(
            rows.iter()
                .filter(|r| r.role == RatioRole::Calibrate)
                .map(|r| Circle::new((r.ratio - offset, r.shares.data_share), 11, BLACK.stroke_width(2))),
        )
        .map_err(plot_error)?
        .label("calibration ratio (fitted on)")
        .legend(|(x, y)| Circle::new((x + 10, y), 8, BLACK.stroke_width(2)));
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 18))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(plot_error)?;
    Ok(())
}

/// The shaved die's comparison as the bytes of a PNG file: the paired bias of every cut
/// thrown and the experiment's at the cut it measured, both with their 95 % intervals, and
/// the slope b/c = 2 the experiment reports at small cuts.
pub fn shaved_die_png(comparison: &ShavedComparison, record: &Record) -> Result<Vec<u8>, Error> {
    register_fonts()?;
    png_bytes(SIZE, record, |root| {
        root.fill(&WHITE).map_err(plot_error)?;
        let picture = with_caption(&root, record, Scale::ONE)?;
        draw_shaved_biases(&picture, comparison)?;
        root.present().map_err(plot_error)
    })
}

fn draw_shaved_biases(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    comparison: &ShavedComparison,
) -> Result<(), Error> {
    let cuts = &comparison.cuts;
    let x1 = 1.15 * cuts.iter().map(|r| r.cut).fold(0.0, f64::max);
    let highs = cuts.iter().flat_map(|r| {
        let data = r.data.map_or(0.0, |d| d.bias.interval[1]);
        [r.bias.interval[1], data, PUBLISHED_SLOPE * r.cut]
    });
    let lows = cuts.iter().map(|r| r.bias.interval[0]);
    let y1 = 1.1 * highs.fold(0.0, f64::max);
    let y0 = lows.fold(0.0, f64::min).min(0.0) * 1.1;
    let (xt, yt) = (Ticks::new(0.0, x1, TICKS), Ticks::new(y0, y1, TICKS));
    let measured: Vec<&CutResult> = cuts.iter().filter(|r| r.data.is_some()).collect();
    let title = match measured.as_slice() {
        [r] => format!(
            "the shaved die: b = {:.3} at c = {} against the measured {:.3} (z = {:+.2})",
            r.bias.bias,
            setup_value(r.cut),
            r.data.map_or(0.0, |d| d.bias.bias),
            r.data.map_or(0.0, |d| d.z)
        ),
        _ => "the shaved die: the bias of each cut".to_string(),
    };
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 22))
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..x1, y0..y1)
        .map_err(plot_error)?;
    draw_axes(
        &mut chart,
        "cut c (the share of the side taken off along the 1–6 axis)",
        "bias b = 3·P(1 or 6) − 1, with 95 % intervals",
        &xt,
        &yt,
    )?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(0.0, 0.0), (x1, PUBLISHED_SLOPE * x1)],
            ShapeStyle::from(DATA.mix(0.5)).stroke_width(1),
        )))
        .map_err(plot_error)?
        .label("b/c = 2, the slope reported at small cuts")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], DATA.mix(0.5).stroke_width(1)));
    let interval = |b: &Bias| [b.interval[0], b.bias, b.interval[1]];
    let offset = 0.004 * x1;
    let pairs: Vec<(f64, [[f64; 3]; 2])> = measured
        .iter()
        .filter_map(|r| r.data.map(|d| (r.cut, [interval(&d.bias), interval(&r.bias)])))
        .collect();
    draw_share_pairs(
        &mut chart,
        &pairs,
        [
            "measured (Murray's group, 2001)",
            "simulated, paired with the uncut die",
        ],
        offset,
        0.006 * x1,
    )?;
    // The cuts the experiment did not measure: the simulation alone.
    let alone: Vec<(f64, [f64; 3])> = cuts
        .iter()
        .filter(|r| r.data.is_none())
        .map(|r| (r.cut, interval(&r.bias)))
        .collect();
    let cap = 0.006 * x1;
    draw_intervals(&mut chart, &alone, SIMULATED, cap, None)?;
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 18))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(plot_error)?;
    Ok(())
}

/// The slope b/c the shaved-die experiment reports at small cuts.
const PUBLISHED_SLOPE: f64 = 2.0;

/// The shaved die's PNG caption: the throws and the drop, the cuts, and the table.
pub fn shaved_die_record(
    c: &ShavedComparison,
    preset: &Preset,
    spec: &ShavedSpec,
    provenance: &serde_json::Value,
) -> Record {
    let n = setup_value;
    let p = preset.params();
    let cuts = spec.cuts.iter().map(|c| n(*c)).collect::<Vec<_>>().join(", ");
    let counted: u64 = c.cuts.iter().map(|r| r.simulated.throws).sum();
    let thrown: u64 = c
        .cuts
        .iter()
        .map(|r| r.simulated.throws + r.simulated.uncounted)
        .sum();
    let caption = vec![
        format!(
            "{}: {} throws, each {}, rolled with the uncut die and each cut ({cuts}); {counted} of {thrown} pairs counted",
            preset.name,
            spec.throws,
            random_starts(&drop_throw(spec.seed), spec.seed, &[]),
        ),
        format!(
            "{}; table {} law, k {} dyn/cm; g {} cm/s², Δt {} s (every value in the file's dicesim-provenance text)",
            c.assumptions[0],
            p.ground.contact.name(),
            n(p.ground.stiffness),
            n(p.world.gravity),
            n(p.integrator.dt),
        ),
    ];
    let title = format!("{}: the shaved die", preset.name);
    Record::captioned(title, caption, dicesim_experiment::PROGRAM).with_provenance(provenance)
}
