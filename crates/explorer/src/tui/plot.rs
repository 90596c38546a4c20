//! What the plot panel draws: the energy terms together (the energy plot), any one quantity
//! of [`QUANTITIES`] against time, or a phase plot of one quantity against another; and the
//! parts every plot against time shares (the time axis fitted to the roll, the marker of
//! the time on screen).

use super::app::{App, Drawing};
use super::energy::{nice_ticks, thinned};
use super::format::fmt_num;
use crate::worker::EnergySample;
use dicesim_setup::quantity::{QUANTITIES, QUANTITY_COUNT, TOTAL_ENERGY};
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType};

/// Index of the height of the centre and of the speed in [`QUANTITIES`].
const HEIGHT: usize = 0;
const SPEED: usize = 2;

/// What the plot panel draws, chosen with the plot keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct PlotChoice {
    /// `None`: the energy terms together; `Some(i)`: `QUANTITIES[i]` against time.
    pub(crate) quantity: Option<usize>,
    /// `Some(j)`: the phase plot, `QUANTITIES[j]` up against the first quantity across.
    pub(crate) phase: Option<usize>,
}

impl PlotChoice {
    /// The quantity plotted against time, or across in the phase plot (the energy plot's
    /// is its total).
    pub(crate) fn first(&self) -> usize {
        self.quantity.unwrap_or(TOTAL_ENERGY)
    }

    /// The next quantity: against time, the energy terms, then each quantity in turn; in
    /// the phase plot, the next quantity up (never the one across).
    pub(crate) fn next(&mut self) {
        match self.phase {
            Some(j) => {
                let mut k = (j + 1) % QUANTITY_COUNT;
                if k == self.first() {
                    k = (k + 1) % QUANTITY_COUNT;
                }
                self.phase = Some(k);
            }
            None => {
                self.quantity = match self.quantity {
                    None => Some(0),
                    Some(i) if i + 1 < QUANTITY_COUNT => Some(i + 1),
                    Some(_) => None,
                }
            }
        }
    }

    /// The phase plot on (up: the height, or the speed when the height is across) or off.
    pub(crate) fn toggle_phase(&mut self) {
        self.phase = match self.phase {
            Some(_) => None,
            None if self.first() == HEIGHT => Some(SPEED),
            None => Some(HEIGHT),
        };
    }
}

/// The time axis of a plot against time, `width` columns wide, fitted to the roll computed so
/// far: from 0 to its end rounded up on a fine grid (1.096 s → 1.2 s), labelled evenly on a
/// round step where one divides the axis (0, 0.4, 0.8, 1.2 s), else at its two ends.
pub(crate) fn time_axis(app: &App, width: u16) -> (f64, Vec<String>) {
    let t_end = app
        .roll
        .history
        .last()
        .map_or(0.0, |s| s.time_s)
        .max(app.roll.live.time_s);
    time_axis_to(t_end, width)
}

/// [`time_axis`] for a roll computed to `t_end` seconds (the twin's plot reads its own).
pub(crate) fn time_axis_to(t_end: f64, width: u16) -> (f64, Vec<String>) {
    let most = time_labels_for(width);
    // A chart gives its last label a share of the plot (less the value labels, about 7
    // columns): a longer one loses its first digits (0.35 s read ".35 s"). A coarser end
    // keeps the label short enough.
    let plot = (width as usize).saturating_sub(7);
    let fits =
        |labels: &[String]| labels.last().map_or(0, |l| l.chars().count()) < plot / labels.len().max(1);
    let (hi, mut labels) = FINE_TIME_TICKS
        .iter()
        .map(|&fine| time_ticks(t_end, most, fine))
        .find(|(_, labels)| fits(labels))
        .unwrap_or_else(|| time_ticks(t_end, most, 2));
    // The last label ends in a space: a panel's gap column (`fit`), never text.
    if let Some(last) = labels.last_mut() {
        last.push(' ');
    }
    (hi, labels)
}

/// The axis end and labels of [`time_axis_to`], without the gap column: the end rounded up
/// to one of about `fine` steps, at most `most` labels.
fn time_ticks(t_end: f64, most: usize, fine: usize) -> (f64, Vec<String>) {
    // Before the roll has moved, a tenth of a second, not a zero-width axis. The end is
    // chosen on a grid finer than the labels' so that the curve fills the plot: labels
    // alone would round a 1.1 s roll up to a 2 s axis, half of it empty.
    let (_, hi, _) = nice_ticks(0.0, t_end.max(0.1), fine);
    let n = (2..=most.max(2))
        .rev()
        .find(|&n| is_round_step(hi / (n - 1) as f64))
        .unwrap_or(2);
    let labels = (0..n)
        .map(|i| {
            let v = fmt_num(hi * i as f64 / (n - 1) as f64);
            if i + 1 == n { format!("{v} s") } else { v }
        })
        .collect();
    (hi, labels)
}

/// How finely the time axis's end is rounded up, finest first: to one of about this many
/// steps, or fewer where the plot is too narrow for the finer end's label.
const FINE_TIME_TICKS: [usize; 3] = [8, 4, 2];

/// Whether `step` is 2.5 × 10ⁿ or has one significant digit (0.4, 20), a step whose
/// multiples read as round numbers (0.6, 1.2 do; 0.35, 0.7 do not).
fn is_round_step(step: f64) -> bool {
    let decade = 10f64.powf(step.log10().floor());
    let digits = step / decade;
    (digits - digits.round()).abs() < 1e-9 || (digits - 2.5).abs() < 1e-9
}

/// At most this many time labels for a plot `width` columns wide ("0.25" and room around).
pub(crate) fn time_labels_for(width: u16) -> usize {
    (width as usize / 12).clamp(2, 6)
}

/// The colour of the marker of the time on screen: a hue no curve of the plots uses.
pub(crate) fn marker_colour(app: &App) -> Color {
    app.theme.ink(Color::Cyan)
}

/// The vertical line of the time on screen, from `y_lo` to `y_hi`, as points. None at
/// t = 0, where the y axis itself marks it, nor at the end of a roll that has ended, where
/// the curves end: a line beside the axis or the border would read as a double one.
pub(crate) fn time_marker(app: &App, y_lo: f64, y_hi: f64) -> Vec<(f64, f64)> {
    let live = &app.roll.live;
    let t = live.time_s;
    let at_end = live.timeline.ended && live.timeline.position >= live.timeline.furthest;
    if t > 0.0 && !at_end {
        vec![(t, y_lo), (t, y_hi)]
    } else {
        Vec::new()
    }
}

/// The dataset drawing [`time_marker`]: a line of `│` (of `|` in ASCII).
pub(crate) fn marker_dataset<'a>(app: &App, points: &'a [(f64, f64)]) -> Dataset<'a> {
    let symbol = if app.drawing == Drawing::Ascii { '|' } else { '│' };
    Dataset::default()
        .name("now")
        .marker(Marker::Custom(symbol))
        .graph_type(GraphType::Line)
        .style(Style::new().fg(marker_colour(app)))
        .data(points)
}

/// The vertical lines of the mid-roll edits ([`super::roll_view::RollView::edits`]) from
/// `y_lo` to `y_hi`, one pair of points each.
pub(crate) fn edit_marks(app: &App, y_lo: f64, y_hi: f64) -> Vec<[(f64, f64); 2]> {
    let dt = app.roll.live.params.integrator.dt;
    app.roll
        .edits
        .iter()
        .map(|&n| {
            let t = n as f64 * dt;
            [(t, y_lo), (t, y_hi)]
        })
        .collect()
}

/// The datasets drawing [`edit_marks`]: each a line of `┊` (`:` in ASCII).
pub(crate) fn edit_datasets<'a>(app: &App, marks: &'a [[(f64, f64); 2]]) -> Vec<Dataset<'a>> {
    let symbol = if app.drawing == Drawing::Ascii { ':' } else { '┊' };
    marks
        .iter()
        .map(|m| {
            Dataset::default()
                .name("edit")
                .marker(Marker::Custom(symbol))
                .graph_type(GraphType::Line)
                .style(Style::new().fg(marker_colour(app)))
                .data(m)
        })
        .collect()
}

/// Whether a parameter twin rolls: its die B's curve then takes the faded curve's place.
pub(crate) fn parameter_twin(app: &App) -> bool {
    app.roll
        .live
        .twin
        .as_ref()
        .is_some_and(|t| !t.differs_by.is_empty())
}

/// The samples drawn faded under the roll's: die B's while a parameter twin rolls (the
/// same start in the other setup, side by side in time), else the previous run's.
pub(crate) fn faded_run(app: &App) -> &[EnergySample] {
    if parameter_twin(app) {
        &app.twin.samples
    } else {
        &app.roll.previous
    }
}

/// The dataset of the faded curve (the previous run's, or die B's): the twin's ghost
/// grey; `.` without colour.
pub(crate) fn previous_dataset<'a>(app: &App, data: &'a [(f64, f64)]) -> Dataset<'a> {
    Dataset::default()
        .name(if parameter_twin(app) { "B" } else { "previous" })
        .marker(if app.theme.colour {
            app.drawing.line_marker()
        } else {
            Marker::Custom('.')
        })
        .graph_type(GraphType::Line)
        .style(Style::new().fg(app.theme.ghost()))
        .data(data)
}

/// The value axis of `data`: a floor and top that read well, with at most `most` labels,
/// each `width` characters wide.
fn value_axis(data: &[(f64, f64)], most: usize, width: usize) -> ([f64; 2], Vec<String>) {
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
    // A quantity that stays near zero or positive starts at zero, so its size reads true.
    if lo > 0.0 && lo < 0.5 * hi {
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

/// The panel's title: the plot's name and unit, and the keys that change it.
fn title<'a>(app: &App, words: String) -> Line<'a> {
    let mut spans = vec![Span::styled(format!(" {words} "), app.theme.heading())];
    // Which curve is which, while die B's is drawn beside A's.
    if parameter_twin(app) {
        spans.push(Span::styled("━A ", Style::new().fg(app.theme.energy_series()[0])));
        spans.push(Span::styled("━B ", Style::new().fg(app.theme.ghost())));
    }
    Line::from(spans)
}

/// Characters the y labels take.
const LABEL_WIDTH: usize = 6;

/// A plot's frame, titled by the longest of `forms` that fits its border whole (never a
/// word cut), and the area inside it; `None`, the frame drawn alone, where it is too small
/// to plot in.
fn framed(app: &App, area: Rect, frame: &mut Frame, forms: &[String]) -> Option<(Block<'static>, Rect)> {
    let border = area.width.saturating_sub(2) as usize;
    let words = forms
        .iter()
        .find(|w| w.chars().count() + 2 <= border)
        .cloned()
        .unwrap_or_default();
    let block = Block::bordered().title(title(app, words));
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
    let forms = [
        format!("{} · {}", q.name, q.unit),
        format!("{} · {}", q.short, q.unit),
        q.short.to_string(),
    ];
    let Some((block, body)) = framed(app, area, frame, &forms) else {
        return;
    };
    let data = thinned(&app.roll.history, body.width as usize * 2, |s| s.quantities[i]);
    let previous = thinned(faded_run(app), body.width as usize * 2, |s| s.quantities[i]);
    let rows = body.height.saturating_sub(2).max(1) as usize;
    let both: Vec<(f64, f64)> = data.iter().chain(&previous).copied().collect();
    let ([y_lo, y_hi], labels) = value_axis(&both, rows.div_ceil(2).clamp(2, 5), LABEL_WIDTH);
    let (x_hi, x_labels) = time_axis(app, body.width);
    let marker = time_marker(app, y_lo, y_hi);
    let edits = edit_marks(app, y_lo, y_hi);
    let colour = app.theme.energy_series()[0];
    let line = Dataset::default()
        .name(q.short)
        .marker(if app.theme.colour {
            app.drawing.line_marker()
        } else {
            Marker::Custom('#')
        })
        .graph_type(GraphType::Line)
        .style(Style::new().fg(colour))
        .data(&data);
    let mut datasets = vec![previous_dataset(app, &previous)];
    datasets.extend(edit_datasets(app, &edits));
    datasets.extend([marker_dataset(app, &marker), line]);
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
    let Some((block, body)) = framed(app, area, frame, &forms) else {
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
    let both: Vec<(f64, f64)> = data.iter().chain(&previous).copied().collect();
    let rows = body.height.saturating_sub(2).max(1) as usize;
    let ([y_lo, y_hi], y_labels) = value_axis(&both, rows.div_ceil(2).clamp(2, 5), LABEL_WIDTH);
    let across: Vec<(f64, f64)> = both.iter().map(|&(a, b)| (b, a)).collect();
    let ([x_lo, x_hi], mut x_labels) = value_axis(&across, time_labels_for(body.width), 0);
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
            app.drawing.line_marker()
        } else {
            Marker::Custom('#')
        })
        .graph_type(GraphType::Line)
        .style(Style::new().fg(app.theme.energy_series()[0]))
        .data(&data);
    let symbol = if app.drawing == Drawing::Ascii { '@' } else { '●' };
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

    #[test]
    fn the_time_axis_ends_just_past_the_roll_with_round_labels() {
        let axis = |t_end: f64, most: usize| {
            let (hi, labels) = time_ticks(t_end, most, 8);
            ((hi * 1e6).round() / 1e6, labels.join(" "))
        };
        // The paper's roll played on to rest (1.096 s): a 1.2 s axis, not 2 s.
        assert_eq!(axis(1.096, 2), (1.2, "0 1.2 s".into()));
        assert_eq!(axis(1.096, 3), (1.2, "0 0.6 1.2 s".into()));
        assert_eq!(axis(1.096, 4), (1.2, "0 0.4 0.8 1.2 s".into()));
        // A half-second roll on a half-second axis; a roll not yet moving on a tenth.
        assert_eq!(axis(0.49, 3), (0.5, "0 0.25 0.5 s".into()));
        assert_eq!(axis(0.0, 2), (0.1, "0 0.1 s".into()));
        // On a plot too narrow for "0.35 s" (80×24's energy panel), a coarser end: 0.4 s.
        assert_eq!(time_axis_to(0.302, 20).1, ["0", "0.4 s "]);
        assert_eq!(
            time_axis_to(0.302, 60).1.last().map(String::as_str),
            Some("0.35 s ")
        );
        assert!(is_round_step(0.25) && is_round_step(20.0) && is_round_step(0.6));
        assert!(!is_round_step(0.35) && !is_round_step(1.2));
    }

    #[test]
    fn the_plot_key_walks_every_quantity_and_back_to_the_energy_plot() {
        let mut p = PlotChoice::default();
        let mut seen = Vec::new();
        for _ in 0..=QUANTITY_COUNT {
            p.next();
            seen.push(p.quantity);
        }
        assert_eq!(seen.last(), Some(&None));
        assert_eq!(
            seen[..QUANTITY_COUNT],
            (0..QUANTITY_COUNT).map(Some).collect::<Vec<_>>()
        );
        // The phase plot: up is never the quantity across.
        p.quantity = Some(HEIGHT);
        p.toggle_phase();
        assert_eq!(p.phase, Some(SPEED));
        for _ in 0..2 * QUANTITY_COUNT {
            p.next();
            assert_ne!(p.phase, Some(HEIGHT));
            assert_eq!(p.quantity, Some(HEIGHT));
        }
        p.toggle_phase();
        assert_eq!(p.phase, None);
    }

    #[test]
    fn a_value_axis_holds_its_data_and_a_constant_sits_inside_it() {
        let ([lo, hi], labels) = value_axis(&[(0.0, 3.0), (1.0, 17.0)], 5, 4);
        assert!(lo <= 3.0 && hi >= 17.0 && lo == 0.0, "{lo} {hi}");
        assert!(labels.iter().all(|l| l.len() >= 4), "{labels:?}");
        // A constant 0.42 (a stability load) and a constant 0 (the force in flight).
        let ([lo, hi], _) = value_axis(&[(0.0, 0.42), (1.0, 0.42)], 5, 0);
        assert!(lo == 0.0 && hi > 0.42, "{lo} {hi}");
        let ([lo, hi], _) = value_axis(&[(0.0, 0.0), (1.0, 0.0)], 5, 0);
        assert_eq!([lo, hi], [0.0, 1.0]);
        // Negative data (the lowest corner pressed in) keeps its sign below zero.
        let ([lo, hi], _) = value_axis(&[(0.0, -0.2), (1.0, 14.0)], 5, 0);
        assert!(lo <= -0.2 && hi >= 14.0, "{lo} {hi}");
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
