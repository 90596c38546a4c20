//! The energy plot: the roll's energy by form against time, on a linear or log scale, the
//! time on screen marked; the plot panel shows it unless another plot was chosen.

use crate::tui::panels::chart::{
    edit_datasets, edit_marks, faded_run, fit_window, in_window, marker_dataset, nice_ticks, parameter_twin,
    previous_dataset, scaled_faded_run, thinned, time_axis, time_marker,
};
use crate::tui::state::app::App;
use crate::tui::state::die_screen::Drawing;
use crate::tui::vocabulary::fit;
use crate::tui::vocabulary::format::fmt_num;
use crate::worker::EnergySample;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph};

/// Short names of the energy terms: total, translational, rotational, gravitational, elastic
/// (the order of [`crate::tui::vocabulary::theme::Theme::energy_series`], and the ledger's words).
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
    if parameter_twin(app) {
        let sample = if app.theme.colour { '━' } else { '.' };
        items.push(Span::styled(
            format!("{sample}B total"),
            Style::new().fg(app.theme.ghost()),
        ));
    }
    let dots = if app.die_screen.drawing == Drawing::Ascii {
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

/// The energy plot's frame, its heading and legend: the legend rides in the title or the
/// bottom border when it fits there whole; else it takes the plot's top rows (the lines
/// returned), and the y range grows so that no line runs under it.
fn framed(app: &App, area: Rect) -> (Block<'static>, Vec<Line<'static>>) {
    let t = &app.theme;
    let scale = if app.die_screen.log_scale { "log" } else { "linear" };
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
    let block = Block::bordered();
    if heading_width + legend_width < fit::room(border) {
        let mut title = heading;
        title.extend(pack(legend, border).into_iter().flat_map(|l| l.spans));
        return (block.title(Line::from(title)), Vec::new());
    }
    let block = block.title(fit::abbreviate(Line::from(heading), border));
    if legend_width < border {
        // A space before the corner: `fit`'s gap column.
        let mut spans = pack(legend, border).remove(0).spans;
        spans.push(Span::raw(" "));
        return (block.title_bottom(Line::from(spans).right_aligned()), Vec::new());
    }
    // Over the whole width, the y labels under it left out; the threshold's item only
    // if it needs no line of its own (it is no energy term).
    let all = pack(legend.clone(), fit::room(border));
    let terms = pack(legend[..legend.len() - 1].to_vec(), fit::room(border));
    (block, if all.len() > terms.len() { terms } else { all })
}

/// The y axis's bounds and ticks for curves from `lo` to `hi` (log10 of erg on the log
/// scale): whole decades on the log scale, round numbers on the linear, and room on top
/// for the legend's `covered` rows of the plot's `rows`. `fitted`: to the curves around the
/// time on screen (`y`), else from the floor.
fn y_ticks(log: bool, fitted: bool, (lo, hi): (f64, f64), rows: f64, covered: f64) -> (f64, f64, Vec<f64>) {
    let most_labels = (rows as usize).div_ceil(2).clamp(2, 5);
    if log {
        // Fitted on demand (`y`): from the decade of the curves' lowest.
        let floor = LOG_FLOOR.log10();
        let bottom = if fitted { lo.max(floor).floor() } else { floor };
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
        // Fitted on demand (`y`): from the curves' lowest.
        let floor = if fitted || lo < -0.05 * hi.max(1.0) {
            lo
        } else {
            0.0
        };
        let top = floor + (hi.max(1.0) * 1.05 - floor) * rows / (rows - covered);
        nice_ticks(floor, top, most_labels)
    }
}

/// The y axis's labels, evenly from the bottom row (first) to the top (last) of the plot's
/// `rows`; those under the legend's `legend_rows` are left blank.
fn y_labels(ticks: &[f64], log: bool, rows: f64, legend_rows: usize) -> Vec<String> {
    let label = |v: f64| {
        let s = if log { fmt_num(10f64.powf(v)) } else { fmt_num(v) };
        format!("{s:>width$}", width = Y_LABEL_WIDTH as usize - 1)
    };
    let plot_rows = rows as usize;
    let n = ticks.len();
    ticks
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let from_top = (plot_rows - 1) as f64 * (1.0 - i as f64 / (n - 1).max(1) as f64);
            if (from_top.round() as usize) < legend_rows {
                String::new()
            } else {
                label(v)
            }
        })
        .collect()
}

/// The energy terms' curves, each in its colour (or, without colour, its own character).
fn term_datasets<'a>(app: &App, series: &'a [Vec<(f64, f64)>]) -> Vec<Dataset<'a>> {
    let t = &app.theme;
    series
        .iter()
        .zip(LEGEND)
        .zip(t.energy_series())
        .zip(PATTERNS)
        .map(|(((data, name), colour), pattern)| {
            let marker = if t.colour {
                app.die_screen.drawing.line_marker()
            } else {
                Marker::Custom(pattern)
            };
            Dataset::default()
                .name(name)
                .marker(marker)
                .graph_type(GraphType::Line)
                .style(Style::new().fg(colour))
                .data(data)
        })
        .collect()
}

/// The stop threshold's line across the plot.
fn stop_dataset<'a>(app: &App, line: &'a [(f64, f64)]) -> Dataset<'a> {
    Dataset::default()
        .name("stop")
        .marker(if app.die_screen.drawing == Drawing::Ascii {
            Marker::Custom('-')
        } else {
            Marker::Dot
        })
        .graph_type(GraphType::Line)
        .style(Style::new().fg(app.theme.threshold()))
        .data(line)
}

/// The energy plot: each energy term and the total against time, the stop threshold across.
pub(crate) fn render_energy(app: &App, area: Rect, frame: &mut Frame) {
    let (block, inside) = framed(app, area);
    let body = block.inner(area);
    if body.width < 12 || body.height < 4 {
        frame.render_widget(block, area);
        return;
    }
    let log = app.die_screen.log_scale;
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
    let scaled = thinned(scaled_faded_run(app), buckets, |s| y_of(s.total));
    // Fitted on demand (`y`): to the curves around the time on screen.
    let window = fit_window(app, x_hi);
    if window.is_some() {
        (lo, hi) = (f64::INFINITY, f64::NEG_INFINITY);
    }
    for s in series.iter().chain([&scaled]) {
        for &(_, v) in &in_window(s, window) {
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
    let (y_lo, y_hi, ticks) = y_ticks(log, window.is_some(), (lo, hi), rows, covered);
    let stop_line = [(0.0, y_of(threshold)), (x_hi, y_of(threshold))];
    // The marker first, so the curves are drawn over it.
    // Below the legend's rows, as the curves are.
    let marker = time_marker(app, y_lo, y_hi - (y_hi - y_lo) * covered / rows);
    let edits = edit_marks(app, y_lo, y_hi - (y_hi - y_lo) * covered / rows);
    // The previous run's total (or die B's), faded, under everything.
    let mut datasets: Vec<Dataset> = vec![previous_dataset(app, &previous)];
    datasets.extend(edit_datasets(app, &edits));
    datasets.push(marker_dataset(app, &marker));
    datasets.extend(term_datasets(app, &series));
    if threshold.is_finite() {
        datasets.push(stop_dataset(app, &stop_line));
    }
    let labels = y_labels(&ticks, log, rows, inside.len());
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
