//! The energy plot: the roll's energy by form against time, on a linear or log scale, the
//! time on screen marked; the plot panel's other plots are [`super::plot`]'s.

use super::app::{App, Drawing};
use super::format::fmt_num;
use super::plot::{
    edit_datasets, edit_marks, faded_run, marker_dataset, previous_dataset, render_phase, render_quantity,
    time_axis, time_marker,
};
use crate::worker::EnergySample;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph};

/// Each series thinned to at most two points (its low and its high) per bucket, so a frame
/// costs the same for any roll length and impact spikes stay visible.
pub(crate) fn thinned(
    history: &[EnergySample],
    buckets: usize,
    value: impl Fn(&EnergySample) -> f64,
) -> Vec<(f64, f64)> {
    let n = history.len();
    if n <= 2 * buckets.max(1) {
        return history.iter().map(|s| (s.time_s, value(s))).collect();
    }
    let mut out = Vec::with_capacity(2 * buckets);
    for b in 0..buckets {
        let slice = &history[b * n / buckets..((b + 1) * n / buckets).max(b * n / buckets + 1).min(n)];
        let (mut lo, mut hi) = (slice[0], slice[0]);
        for s in slice {
            if value(s) < value(&lo) {
                lo = *s;
            }
            if value(s) > value(&hi) {
                hi = *s;
            }
        }
        let (first, second) = if lo.time_s <= hi.time_s {
            (lo, hi)
        } else {
            (hi, lo)
        };
        out.push((first.time_s, value(&first)));
        out.push((second.time_s, value(&second)));
    }
    out
}

/// Short names of the energy terms: total, translational, rotational, gravitational, elastic
/// (the order of [`super::theme::Theme::energy_series`], and the ledger's words).
const LEGEND: [&str; 5] = ["total", "transl", "rot", "grav", "elastic"];

/// Without colour each line is drawn with its own character, so the five stay apart.
const PATTERNS: [char; 5] = ['#', '+', 'x', 'o', '*'];

/// One energy term of a sample, erg.
type Term = fn(&EnergySample) -> f64;

/// erg: the floor of the log plot (energies below, including negative gravity, sit on it).
const LOG_FLOOR: f64 = 1.0;

/// The energy plot's legend: each term's line sample and name (and die B's total), then
/// the stop threshold's.
fn energy_legend(app: &App) -> Vec<Span<'static>> {
    let colours = app.theme.energy_series();
    let mut items: Vec<Span<'static>> = LEGEND
        .iter()
        .zip(colours)
        .zip(PATTERNS)
        .map(|((name, colour), pattern)| {
            let sample = if app.theme.colour { '━' } else { pattern };
            Span::styled(format!("{sample}{name}"), Style::new().fg(colour))
        })
        .collect();
    // Die B's total, faded, while a parameter twin rolls (`.` marks it without colour).
    if super::plot::parameter_twin(app) {
        let sample = if app.theme.colour { '━' } else { '.' };
        items.push(Span::styled(
            format!("{sample}B total"),
            Style::new().fg(app.theme.ghost()),
        ));
    }
    let dots = if app.drawing == Drawing::Ascii {
        "--"
    } else {
        "••"
    };
    items.push(Span::raw(format!("{dots}stop")));
    items
}

/// The legend's items packed into lines of at most `width` characters, one space apart.
fn pack(items: Vec<Span<'static>>, width: usize) -> Vec<Line<'static>> {
    let mut lines: Vec<Vec<Span<'static>>> = vec![Vec::new()];
    let mut used = 0;
    for item in items {
        let w = item.width();
        let line = lines.last_mut().expect("one line at least");
        if !line.is_empty() && used + 1 + w > width {
            lines.push(vec![item]);
            used = w;
        } else {
            if !line.is_empty() {
                line.push(Span::raw(" "));
                used += 1;
            }
            used += w;
            line.push(item);
        }
    }
    lines.into_iter().map(Line::from).collect()
}

/// Axis ticks that read well: bounds and every tick a multiple of one step of 1, 2 or 5 × 10ⁿ,
/// at most `most` labels, and the top at least `top`.
pub(crate) fn nice_ticks(bottom: f64, top: f64, most: usize) -> (f64, f64, Vec<f64>) {
    let most = most.max(2);
    let span = (top - bottom).max(f64::MIN_POSITIVE);
    let mut step = 10f64.powf((span / (most - 1) as f64).log10().floor());
    loop {
        for m in [1.0, 2.0, 5.0] {
            let s = step * m;
            let (lo, hi) = ((bottom / s).floor() * s, (top / s - 1e-9).ceil() * s);
            let n = ((hi - lo) / s).round() as usize + 1;
            if n <= most {
                let ticks = (0..n)
                    .map(|k| lo + k as f64 * s)
                    .map(|v| if v.abs() < s * 1e-9 { 0.0 } else { v })
                    .collect();
                return (lo, hi, ticks);
            }
        }
        step *= 10.0;
    }
}

/// The plot panel: the energy plot, or the quantity or phase plot chosen instead.
pub(crate) fn render_energy(app: &App, area: Rect, frame: &mut Frame) {
    match (app.plot.quantity, app.plot.phase) {
        (_, Some(j)) => render_phase(app, area, frame, app.plot.first(), j),
        (Some(i), None) => render_quantity(app, area, frame, i),
        (None, None) => render_energy_terms(app, area, frame),
    }
}

fn render_energy_terms(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let scale = if app.log_scale { "log" } else { "linear" };
    let colours = t.energy_series();
    let border = area.width.saturating_sub(2) as usize;
    // "(y)": the axis the scale applies to, where the title has room for it.
    let axis = if 25 <= border { " (y)" } else { "" };
    let heading = vec![
        Span::styled(" energy ", t.heading()),
        Span::raw(format!("erg · {scale}{axis} ")),
    ];
    let legend = energy_legend(app);
    let legend_width: usize = legend.iter().map(Span::width).sum::<usize>() + legend.len() - 1;
    let heading_width: usize = heading.iter().map(Span::width).sum();
    // The legend rides in the title or the bottom border when it fits there whole; else it
    // takes the plot's top rows, and the y range grows so that no line runs under it.
    let mut block = Block::bordered();
    let mut inside: Vec<Line<'static>> = Vec::new();
    if heading_width + legend_width < super::fit::room(border) {
        let mut title = heading;
        title.extend(pack(legend, border).into_iter().flat_map(|l| l.spans));
        block = block.title(Line::from(title));
    } else if legend_width < border {
        block = block
            .title(super::fit::abbreviate(Line::from(heading), border))
            .title_bottom({
                // A space before the corner: `fit`'s gap column.
                let mut spans = pack(legend, border).remove(0).spans;
                spans.push(Span::raw(" "));
                Line::from(spans).right_aligned()
            });
    } else {
        block = block.title(super::fit::abbreviate(Line::from(heading), border));
        // Over the whole width, the y labels under it left out; the threshold's item only
        // if it needs no line of its own (it is no energy term).
        inside = pack(legend.clone(), super::fit::room(border));
        if inside.len() > pack(legend[..legend.len() - 1].to_vec(), super::fit::room(border)).len() {
            inside = pack(legend[..legend.len() - 1].to_vec(), super::fit::room(border));
        }
    }
    let body = block.inner(area);
    if body.width < 12 || body.height < 4 {
        frame.render_widget(block, area);
        return;
    }
    let log = app.log_scale;
    let y_of = |v: f64| if log { v.max(LOG_FLOOR).log10() } else { v };
    let buckets = (body.width as usize).saturating_mul(2);
    let terms: [Term; 5] = [
        |s| s.total,
        |s| s.energy.translational,
        |s| s.energy.rotational,
        |s| s.energy.gravitational,
        |s| s.energy.elastic,
    ];
    let previous = thinned(faded_run(app), buckets, |s| y_of(s.total));
    let series: Vec<Vec<(f64, f64)>> = terms
        .iter()
        .map(|f| thinned(&app.roll.history, buckets, |s| y_of(f(s))))
        .collect();
    let (x_hi, x_labels) = time_axis(app, body.width);
    let threshold = app.roll.live.stop_threshold;
    let (mut lo, mut hi) = if threshold.is_finite() {
        (y_of(threshold), y_of(threshold))
    } else {
        (y_of(LOG_FLOOR), y_of(LOG_FLOOR))
    };
    for s in series.iter().chain([&previous]) {
        for &(_, v) in s {
            if v.is_finite() {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
    }
    // Rows of the plot itself (the x axis and its labels take two), and how many of the
    // top ones the legend covers.
    let rows = body.height.saturating_sub(2).max(1) as f64;
    let covered = (inside.len() as f64).min(rows - 1.0);
    let most_labels = (rows as usize).div_ceil(2).clamp(2, 5);
    let (y_lo, y_hi, ticks) = if log {
        let bottom = y_of(LOG_FLOOR);
        let top = bottom + (hi.max(bottom + 1.0) - bottom) * rows / (rows - covered);
        // Whole decades, every one labelled or every second, third, …
        let decades = (top - bottom).ceil().max(1.0) as usize;
        let every = (1..=decades)
            .find(|d| decades.div_ceil(*d) < most_labels)
            .unwrap_or(decades);
        let n = decades.div_ceil(every);
        let top = bottom + (n * every) as f64;
        (
            bottom,
            top,
            (0..=n).map(|k| bottom + (k * every) as f64).collect::<Vec<_>>(),
        )
    } else {
        // A die pressed into the table has a slightly negative potential energy: a floor
        // below zero only when that is a visible share of the plot.
        let floor = if lo < -0.05 * hi.max(1.0) { lo } else { 0.0 };
        let top = floor + (hi.max(1.0) * 1.05 - floor) * rows / (rows - covered);
        nice_ticks(floor, top, most_labels)
    };
    let stop_line = [(0.0, y_of(threshold)), (x_hi, y_of(threshold))];
    // The marker first, so the curves are drawn over it.
    // Below the legend's rows, as the curves are.
    let marker = time_marker(app, y_lo, y_hi - (y_hi - y_lo) * covered / rows);
    let edits = edit_marks(app, y_lo, y_hi - (y_hi - y_lo) * covered / rows);
    // The previous run's total (or die B's), faded, under everything.
    let mut datasets: Vec<Dataset> = vec![previous_dataset(app, &previous)];
    datasets.extend(edit_datasets(app, &edits));
    datasets.push(marker_dataset(app, &marker));
    datasets.extend(series.iter().zip(LEGEND).zip(colours).zip(PATTERNS).map(
        |(((data, name), colour), pattern)| {
            let marker = if t.colour {
                app.drawing.line_marker()
            } else {
                Marker::Custom(pattern)
            };
            Dataset::default()
                .name(name)
                .marker(marker)
                .graph_type(GraphType::Line)
                .style(Style::new().fg(colour))
                .data(data)
        },
    ));
    if threshold.is_finite() {
        datasets.push(
            Dataset::default()
                .name("stop")
                .marker(if app.drawing == Drawing::Ascii {
                    Marker::Custom('-')
                } else {
                    Marker::Dot
                })
                .graph_type(GraphType::Line)
                .style(Style::new().fg(t.threshold()))
                .data(&stop_line),
        );
    }
    let label = |v: f64| {
        let s = if log { fmt_num(10f64.powf(v)) } else { fmt_num(v) };
        format!("{s:>width$}", width = Y_LABEL_WIDTH as usize - 1)
    };
    // Labels sit evenly from the bottom row (first) to the top (last); those under the
    // legend are left blank.
    let plot_rows = rows as usize;
    let n = ticks.len();
    let labels: Vec<String> = ticks
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let from_top = (plot_rows - 1) as f64 * (1.0 - i as f64 / (n - 1).max(1) as f64);
            if (from_top.round() as usize) < inside.len() {
                String::new()
            } else {
                label(v)
            }
        })
        .collect();
    let chart = Chart::new(datasets)
        .block(block)
        .x_axis(Axis::default().bounds([0.0, x_hi]).labels(x_labels))
        .y_axis(Axis::default().bounds([y_lo, y_hi]).labels(labels))
        .legend_position(None);
    frame.render_widget(chart, area);
    if !inside.is_empty() {
        let legend_area = Rect {
            height: (inside.len() as u16).min(body.height),
            ..body
        };
        frame.render_widget(Paragraph::new(inside), legend_area);
    }
}

/// Characters the y axis's labels take ("200000" and a space).
const Y_LABEL_WIDTH: u16 = 7;
