//! The plot panel: the energy terms together (the energy plot, drawn by its own module),
//! any one quantity of [`QUANTITIES`] against time, or a phase plot of one quantity
//! against another, whichever the plot keys chose.

pub(crate) mod energy_chart;

use crate::tui::panels::chart::{
    edit_datasets, edit_marks, faded_run, fit_window, in_window, marker_colour, marker_dataset, nice_ticks,
    parameter_twin, previous_dataset, scaled_faded_run, thinned, time_axis, time_labels_for, time_marker,
};
use crate::tui::panels::quantity_plot::energy_chart::render_energy;
use crate::tui::state::app::App;
use crate::tui::state::die_screen::Drawing;
use crate::tui::vocabulary::format::fmt_num;
use crate::worker::EnergySample;
use dicesim_setup::quantity::QUANTITIES;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType};

/// The value axis of `data`: a floor and top that read well, with at most `most` labels,
/// each `width` characters wide; `fitted`, from the data's lowest to its highest rather
/// than from zero.
fn value_axis(data: &[(f64, f64)], most: usize, width: usize, fitted: bool) -> ([f64; 2], Vec<String>) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(_, v) in data {
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !lo.is_finite() {
        (lo, hi) = (0.0, 1.0);
    }
    // A quantity that stays near zero or positive starts at zero, so its size reads true
    // (unless the axis is fitted to it on demand).
    if !fitted && lo > 0.0 && lo < 0.5 * hi {
        lo = 0.0;
    }
    // A constant (a stability load before any edit, the force in flight): from zero to
    // half as much again, so the line sits at two thirds of the height.
    if hi - lo <= 1e-12 * hi.abs().max(lo.abs()) {
        (lo, hi) = match lo {
            v if v > 0.0 => (0.0, 1.5 * v),
            v if v < 0.0 => (1.5 * v, 0.0),
            _ => (0.0, 1.0),
        };
    }
    let (lo, hi, ticks) = nice_ticks(lo, hi, most);
    let labels = ticks.iter().map(|&v| format!("{:>width$}", fmt_num(v))).collect();
    ([lo, hi], labels)
}

/// The plot panel: the energy plot, or the quantity or phase plot chosen instead.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    match (app.die_screen.plot.quantity, app.die_screen.plot.phase) {
        (_, Some(j)) => render_phase(app, area, frame, app.die_screen.plot.first(), j),
        (Some(i), None) => render_quantity(app, area, frame, i),
        (None, None) => render_energy(app, area, frame),
    }
}

/// The panel's title: the plot's name and unit, and which curve is which.
fn title<'a>(app: &App, words: String) -> Line<'a> {
    let mut spans = vec![Span::styled(format!(" {words} "), app.theme.heading())];
    // Which curve is which, while die B's is drawn beside A's.
    if parameter_twin(app) {
        spans.push(Span::styled("━A ", Style::new().fg(app.theme.energy_series()[0])));
        spans.push(Span::styled("━B ", Style::new().fg(app.theme.ghost())));
    }
    Line::from(spans)
}

/// The colour of the second curve on a plot against time (`Y`).
fn second_colour(app: &App) -> ratatui::style::Color {
    app.theme.energy_series()[1]
}

/// The readout at the time marker: each plotted quantity's value at the state on screen,
/// with its unit, for the bottom border of a panel `border` columns wide inside its
/// corners (the time goes first where it is narrow).
fn readout(app: &App, quantities: &[usize], border: usize) -> Line<'static> {
    let live = &app.roll.live;
    let decimals = ((-live.params.integrator.dt.log10()).ceil().max(3.0)) as usize;
    let mut parts = vec![(1, vec![Span::raw(format!(" at {:.*} s:", decimals, live.time_s))])];
    for (k, &i) in quantities.iter().enumerate() {
        let q = &QUANTITIES[i];
        let sep = if k == 0 { " " } else { " · " };
        parts.push((
            0,
            vec![Span::raw(format!(
                "{sep}{} {} {}",
                q.short,
                fmt_num(live.readings[i]),
                q.unit
            ))],
        ));
    }
    // The space before the corner: `fit`'s gap column, kept whatever goes.
    let mut line = crate::tui::vocabulary::fit::line(parts, border.saturating_sub(1));
    line.spans.push(Span::raw(" "));
    line.right_aligned()
}

/// Characters the y labels take.
const LABEL_WIDTH: usize = 6;

/// A plot's frame, titled by the longest of `forms` that fits its border whole (never a
/// word cut), and the area inside it; `None`, the frame drawn alone, where it is too small
/// to plot in.
fn framed(
    app: &App,
    area: Rect,
    frame: &mut Frame,
    forms: &[String],
    shown: &[usize],
) -> Option<(Block<'static>, Rect)> {
    let border = area.width.saturating_sub(2) as usize;
    let words = forms
        .iter()
        .find(|w| w.chars().count() + 2 <= border)
        .cloned()
        .unwrap_or_default();
    let block = Block::bordered()
        .title(title(app, words))
        .title_bottom(readout(app, shown, border));
    let body = block.inner(area);
    if body.width < 12 || body.height < 4 {
        frame.render_widget(block, area);
        return None;
    }
    Some((block, body))
}

/// One quantity against time, with the marker of the time on screen.
pub(crate) fn render_quantity(app: &App, area: Rect, frame: &mut Frame, i: usize) {
    let q = &QUANTITIES[i];
    let second = app.die_screen.plot.second;
    let forms = match second.map(|j| &QUANTITIES[j]) {
        // Two curves on the axis of their one unit.
        Some(r) => vec![
            format!("━{} ━{} · {}", q.name, r.name, q.unit),
            format!("━{} ━{} · {}", q.short, r.short, q.unit),
            format!("━{} ━{}", q.short, r.short),
        ],
        None => vec![
            format!("{} · {}", q.name, q.unit),
            format!("{} · {}", q.short, q.unit),
            q.short.to_string(),
        ],
    };
    let shown: Vec<usize> = std::iter::once(i).chain(second).collect();
    let Some((block, body)) = framed(app, area, frame, &forms, &shown) else {
        return;
    };
    let data = thinned(&app.roll.history, body.width as usize * 2, |s| s.quantities[i]);
    let previous = thinned(faded_run(app), body.width as usize * 2, |s| s.quantities[i]);
    let rows = body.height.saturating_sub(2).max(1) as usize;
    let scaled = thinned(scaled_faded_run(app), body.width as usize * 2, |s| {
        s.quantities[i]
    });
    let other = second
        .map(|j| thinned(&app.roll.history, body.width as usize * 2, |s| s.quantities[j]))
        .unwrap_or_default();
    let both: Vec<(f64, f64)> = data.iter().chain(&scaled).chain(&other).copied().collect();
    let (x_hi, x_labels) = time_axis(app, body.width);
    let window = fit_window(app, x_hi);
    let ([y_lo, y_hi], labels) = value_axis(
        &in_window(&both, window),
        rows.div_ceil(2).clamp(2, 5),
        LABEL_WIDTH,
        window.is_some(),
    );
    let marker = time_marker(app, y_lo, y_hi);
    let edits = edit_marks(app, y_lo, y_hi);
    let colour = app.theme.energy_series()[0];
    let line = Dataset::default()
        .name(q.short)
        .marker(if app.theme.colour {
            app.die_screen.drawing.line_marker()
        } else {
            Marker::Custom('#')
        })
        .graph_type(GraphType::Line)
        .style(Style::new().fg(colour))
        .data(&data);
    let second_line = Dataset::default()
        .name("second")
        .marker(if app.theme.colour {
            app.die_screen.drawing.line_marker()
        } else {
            Marker::Custom('+')
        })
        .graph_type(GraphType::Line)
        .style(Style::new().fg(second_colour(app)))
        .data(&other);
    let mut datasets = vec![previous_dataset(app, &previous)];
    datasets.extend(edit_datasets(app, &edits));
    datasets.extend([marker_dataset(app, &marker), second_line, line]);
    let chart = Chart::new(datasets)
        .block(block)
        .x_axis(Axis::default().bounds([0.0, x_hi]).labels(x_labels))
        .y_axis(Axis::default().bounds([y_lo, y_hi]).labels(labels))
        .legend_position(None);
    frame.render_widget(chart, area);
}

/// The sample of the time on screen: the last at or before it.
fn sample_now(history: &[EnergySample], t: f64) -> Option<&EnergySample> {
    let after = history.partition_point(|s| s.time_s <= t);
    history.get(after.saturating_sub(1))
}

/// Most points of a phase plot's curve: more only cost time, the cells are full by then.
const PHASE_POINTS: usize = 4000;

/// `QUANTITIES[j]` up against `QUANTITIES[i]` across, the state on screen marked.
pub(crate) fn render_phase(app: &App, area: Rect, frame: &mut Frame, i: usize, j: usize) {
    let (x, y) = (&QUANTITIES[i], &QUANTITIES[j]);
    let forms = [
        format!("{} ({}) against {} ({})", y.name, y.unit, x.name, x.unit),
        format!("{} ({}) vs {} ({})", y.short, y.unit, x.short, x.unit),
        format!("{} vs {}", y.short, x.short),
        y.short.to_string(),
    ];
    let Some((block, body)) = framed(app, area, frame, &forms, &[i, j]) else {
        return;
    };
    let curve_of = |history: &[EnergySample]| -> Vec<(f64, f64)> {
        let every = history.len().div_ceil(PHASE_POINTS).max(1);
        history
            .iter()
            .step_by(every)
            .chain(history.last())
            .map(|s| (s.quantities[i], s.quantities[j]))
            .collect()
    };
    let history = &app.roll.history;
    let data = curve_of(history);
    let previous = curve_of(faded_run(app));
    let scaled = curve_of(scaled_faded_run(app));
    let both: Vec<(f64, f64)> = data.iter().chain(&scaled).copied().collect();
    let rows = body.height.saturating_sub(2).max(1) as usize;
    let fitted = app.die_screen.plot.fitted;
    let ([y_lo, y_hi], y_labels) = value_axis(&both, rows.div_ceil(2).clamp(2, 5), LABEL_WIDTH, fitted);
    let across: Vec<(f64, f64)> = both.iter().map(|&(a, b)| (b, a)).collect();
    let ([x_lo, x_hi], mut x_labels) = value_axis(&across, time_labels_for(body.width), 0, fitted);
    // The unit after the last number where the two fit the label's share of the width
    // (else the title carries it, or the panel is too narrow for it).
    let share = body.width as usize / x_labels.len().max(2);
    if let Some(last) = x_labels.last_mut()
        && last.chars().count() + 1 + x.unit.chars().count() < share
    {
        *last = format!("{last} {}", x.unit);
    }
    let now: Vec<(f64, f64)> = sample_now(history, app.roll.live.time_s)
        .map(|s| (s.quantities[i], s.quantities[j]))
        .into_iter()
        .collect();
    let curve = Dataset::default()
        .name("roll")
        .marker(if app.theme.colour {
            app.die_screen.drawing.line_marker()
        } else {
            Marker::Custom('#')
        })
        .graph_type(GraphType::Line)
        .style(Style::new().fg(app.theme.energy_series()[0]))
        .data(&data);
    let symbol = if app.die_screen.drawing == Drawing::Ascii {
        '@'
    } else {
        '●'
    };
    let here = Dataset::default()
        .name("now")
        .marker(Marker::Custom(symbol))
        .graph_type(GraphType::Scatter)
        .style(Style::new().fg(marker_colour(app)))
        .data(&now);
    let chart = Chart::new(vec![previous_dataset(app, &previous), curve, here])
        .block(block)
        .x_axis(Axis::default().bounds([x_lo, x_hi]).labels(x_labels))
        .y_axis(Axis::default().bounds([y_lo, y_hi]).labels(y_labels))
        .legend_position(None);
    frame.render_widget(chart, area);
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_setup::quantity::QUANTITY_COUNT;

    #[test]
    fn a_value_axis_holds_its_data_and_a_constant_sits_inside_it() {
        let ([lo, hi], labels) = value_axis(&[(0.0, 3.0), (1.0, 17.0)], 5, 4, false);
        assert!(lo <= 3.0 && hi >= 17.0 && lo == 0.0, "{lo} {hi}");
        assert!(labels.iter().all(|l| l.len() >= 4), "{labels:?}");
        // A constant 0.42 (a stability load) and a constant 0 (the force in flight).
        let ([lo, hi], _) = value_axis(&[(0.0, 0.42), (1.0, 0.42)], 5, 0, false);
        assert!(lo == 0.0 && hi > 0.42, "{lo} {hi}");
        let ([lo, hi], _) = value_axis(&[(0.0, 0.0), (1.0, 0.0)], 5, 0, false);
        assert_eq!([lo, hi], [0.0, 1.0]);
        // Negative data (the lowest corner pressed in) keeps its sign below zero.
        let ([lo, hi], _) = value_axis(&[(0.0, -0.2), (1.0, 14.0)], 5, 0, false);
        assert!(lo <= -0.2 && hi >= 14.0, "{lo} {hi}");
        // Fitted on demand: from near the data's lowest (12) rather than from zero.
        let ([lo, hi], _) = value_axis(&[(0.0, 12.0), (1.0, 30.0)], 5, 0, true);
        assert!(lo > 0.0 && lo <= 12.0 && hi >= 30.0, "{lo} {hi}");
        let ([lo, _], _) = value_axis(&[(0.0, 12.0), (1.0, 30.0)], 5, 0, false);
        assert_eq!(lo, 0.0);
    }

    #[test]
    fn the_state_on_screen_is_the_last_sample_not_after_it() {
        let sample = |t| EnergySample {
            time_s: t,
            energy: Default::default(),
            total: 0.0,
            quantities: [t; QUANTITY_COUNT],
        };
        let h: Vec<_> = [0.0, 0.1, 0.2, 0.3].map(sample).to_vec();
        assert_eq!(sample_now(&h, 0.25).unwrap().time_s, 0.2);
        assert_eq!(sample_now(&h, 0.2).unwrap().time_s, 0.2);
        assert_eq!(sample_now(&h, 9.0).unwrap().time_s, 0.3);
        assert_eq!(sample_now(&h, -1.0).unwrap().time_s, 0.0);
    }
}

#[cfg(test)]
mod quantity_plot_tests;
