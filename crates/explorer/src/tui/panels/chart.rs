//! What the plots share (the energy plot, the quantity and phase plots, the twin's
//! separation, and the timeline's marks): the time axis fitted to the roll, ticks that read
//! well, long histories thinned to the cells, the marker of the time on screen and of
//! mid-roll edits, and the faded curve drawn under the roll's (the previous run's, or die B's).

use crate::tui::state::app::App;
use crate::tui::state::die_screen::Drawing;
use crate::tui::vocabulary::format::fmt_num;
use crate::worker::EnergySample;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::widgets::{Dataset, GraphType};

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

/// s: the span of time the value axis is fitted to on demand (`y`): a quarter of the time
/// axis (to `x_hi` s), centred on the time on screen, so what the die does now fills the
/// plot's height and the rest of the roll runs off it; `None` while the axis spans the roll.
pub(crate) fn fit_window(app: &App, x_hi: f64) -> Option<(f64, f64)> {
    let t = app.roll.live.time_s;
    app.die_screen
        .plot
        .fitted
        .then(|| (t - x_hi / 8.0, t + x_hi / 8.0))
}

/// The points of `data` within `window` (every point without one, or where none fall in it).
pub(crate) fn in_window(data: &[(f64, f64)], window: Option<(f64, f64)>) -> Vec<(f64, f64)> {
    let Some((from, to)) = window else {
        return data.to_vec();
    };
    let inside: Vec<(f64, f64)> = data
        .iter()
        .copied()
        .filter(|p| (from..=to).contains(&p.0))
        .collect();
    if inside.is_empty() { data.to_vec() } else { inside }
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
    let symbol = if app.die_screen.drawing == Drawing::Ascii {
        '|'
    } else {
        '│'
    };
    Dataset::default()
        .name("now")
        .marker(Marker::Custom(symbol))
        .graph_type(GraphType::Line)
        .style(Style::new().fg(marker_colour(app)))
        .data(points)
}

/// The vertical lines of the mid-roll edits ([`RollView::edits`](crate::tui::state::roll_view::RollView::edits)) from
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
    let symbol = if app.die_screen.drawing == Drawing::Ascii {
        ':'
    } else {
        '┊'
    };
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

/// The faded samples that share the value axis's range: die B's (a roll on screen beside
/// A's), never a previous run's ghost, whose scale may be another preset's (its points past
/// the axis are clipped, not fitted).
pub(crate) fn scaled_faded_run(app: &App) -> &[EnergySample] {
    if parameter_twin(app) { faded_run(app) } else { &[] }
}

/// The dataset of the faded curve (the previous run's, or die B's): the twin's ghost
/// grey; `.` without colour.
pub(crate) fn previous_dataset<'a>(app: &App, data: &'a [(f64, f64)]) -> Dataset<'a> {
    Dataset::default()
        .name(if parameter_twin(app) { "B" } else { "previous" })
        .marker(if app.theme.colour {
            app.die_screen.drawing.line_marker()
        } else {
            Marker::Custom('.')
        })
        .graph_type(GraphType::Line)
        .style(Style::new().fg(app.theme.ghost()))
        .data(data)
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
}
