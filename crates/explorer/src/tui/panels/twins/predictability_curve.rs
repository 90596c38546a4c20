//! The twin screen's predictability curve: P(same face) of random throws and their ε-twins
//! against log₁₀ ε, with 95 % intervals, the chance and halfway levels, ε½, and where the
//! twin's own ε lies on it. The worker computes it (`worker::curve`); this draws it.

use crate::tui::state::app::App;
use crate::tui::state::die_screen::Drawing;
use crate::tui::vocabulary::format::fmt_num;
use crate::worker::{CurveState, CurveUpdate};
use dicesim_experiment::predict::PredictCurve;
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph, Wrap};

/// log₁₀ ε at the plot's edges: the worker's list of ε, one per decade.
const X_RANGE: [f64; 2] = [-15.0, -1.0];

/// The characters that tell the plot's lines apart without colour.
struct Glyphs {
    curve: Marker,
    point: char,
    interval: char,
    chance: char,
    half: char,
    ours: char,
    our_point: char,
}

impl Glyphs {
    fn of(drawing: Drawing) -> Glyphs {
        match drawing {
            Drawing::Braille => Glyphs {
                curve: Marker::Braille,
                point: '●',
                interval: '│',
                chance: '┄',
                half: '·',
                ours: '┆',
                our_point: '◆',
            },
            Drawing::Ascii => Glyphs {
                curve: Marker::Custom('.'),
                point: 'o',
                interval: '|',
                chance: '=',
                half: '-',
                ours: ':',
                our_point: '#',
            },
        }
    }
}

/// P(same face) at `epsilon`: the listed point's share and interval, or between two listed
/// points the share interpolated linearly in log₁₀ ε (as ε½ is), without an interval.
pub(crate) fn at_epsilon(curve: &PredictCurve, epsilon: f64) -> Option<(f64, Option<[f64; 2]>)> {
    let points: Vec<_> = curve.points.iter().filter(|p| p.pairs > 0).collect();
    let x = epsilon.log10();
    if let Some(p) = points.iter().find(|p| (p.epsilon.log10() - x).abs() < 1e-9) {
        return Some((p.same_share, Some(p.interval)));
    }
    points.windows(2).find_map(|w| {
        let (a, b) = (w[0].epsilon.log10(), w[1].epsilon.log10());
        (a < x && x < b).then(|| {
            let t = (x - a) / (b - a);
            (w[0].same_share + t * (w[1].same_share - w[0].same_share), None)
        })
    })
}

fn percent(share: f64) -> String {
    format!("{:.0} %", 100.0 * share)
}

/// What the curve says at the twin's ε, as the longest sentence that fits `width` columns.
fn our_epsilon_text(curve: &PredictCurve, epsilon: f64, width: usize) -> String {
    let eps = fmt_num(epsilon);
    let Some((share, interval)) = at_epsilon(curve, epsilon) else {
        return format!("our ε {eps}: no throw settled yet");
    };
    let approx = if interval.is_some() { "" } else { "≈ " };
    let share = percent(share);
    let sentence = format!("our ε {eps}: the faces agree in {approx}{share} of throws");
    let mut texts = Vec::new();
    if let Some([lo, hi]) = interval {
        texts.push(format!("{sentence} (95 %: {:.0}–{:.0})", 100.0 * lo, 100.0 * hi));
    }
    texts.push(sentence);
    texts.push(format!("our ε {eps}: {approx}{share} same face"));
    texts
        .iter()
        .find(|t| t.chars().count() <= crate::tui::vocabulary::fit::room(width))
        .cloned()
        .unwrap_or_else(|| {
            crate::tui::vocabulary::fit::cut_text(
                texts.last().expect("three texts"),
                crate::tui::vocabulary::fit::room(width),
            )
        })
}

/// ε½ and the levels it is measured between.
fn threshold_text(curve: &PredictCurve, width: usize) -> String {
    let eps = curve.threshold.map_or("–".to_string(), |t| t.text());
    let long = format!("ε½ {eps}: halfway from 1 to chance ({:.2})", curve.chance);
    crate::tui::vocabulary::fit::longest_fitting(
        &[
            long,
            format!("ε½ {eps} · chance {:.2}", curve.chance),
            format!("ε½ {eps}"),
        ],
        width,
    )
}

/// The panel's title: what is plotted and how many throws it rests on, in `width` columns.
fn title(app: &App, update: Option<&CurveUpdate>, width: u16) -> Line<'static> {
    let t = &app.theme;
    let (text, style) = match update.map(|u| (&u.state, u.count)) {
        Some((CurveState::Complete(c), _)) => (format!("· {} throws ", c.starts), Style::new()),
        Some((CurveState::Computing(c), count)) => {
            let done = c.as_ref().map_or(0, |c| c.starts);
            let long = format!("· computing {done} of {count} throws ");
            let fits = long.chars().count() + 16 <= width as usize;
            (
                if fits {
                    long
                } else {
                    format!("· computing {done}/{count} ")
                },
                t.caution(),
            )
        }
        Some((CurveState::Failed(_), _)) => ("· no curve ".to_string(), t.danger()),
        None => ("· waiting for the worker ".to_string(), Style::new()),
    };
    crate::tui::vocabulary::fit::abbreviate(
        Line::from(vec![
            Span::styled(" P(same face) ", t.heading()),
            Span::styled(text, style),
        ]),
        width as usize,
    )
}

/// The legend on the bottom border: each line's glyph and what it is.
fn legend(app: &App, width: u16) -> Line<'static> {
    let g = Glyphs::of(app.die_screen.drawing);
    let c = colours(app);
    let curve_glyph = match app.die_screen.drawing {
        Drawing::Braille => '━',
        Drawing::Ascii => g.point,
    };
    // Each line's glyph, its name, the name when space is short, and its colour.
    let items = [
        (curve_glyph, "P", "P", c.curve),
        (g.interval, "95 %", "95%", c.curve),
        (g.chance, "chance Σp²", "chance", c.chance),
        (g.half, "halfway", "½", c.half),
        (g.our_point, "our ε", "ε", c.ours),
    ];
    let long_width: usize = items.iter().map(|(_, name, ..)| name.chars().count() + 3).sum();
    let long = long_width + 2 <= width as usize;
    let mut spans = vec![Span::raw(" ")];
    for (glyph, name, short, colour) in items {
        spans.push(Span::styled(glyph.to_string(), Style::new().fg(colour)));
        spans.push(Span::raw(format!("{} ", if long { name } else { short })));
    }
    Line::from(spans)
}

struct Colours {
    curve: Color,
    chance: Color,
    half: Color,
    ours: Color,
}

fn colours(app: &App) -> Colours {
    let t = &app.theme;
    Colours {
        curve: t.ink(Color::Blue),
        chance: t.ink(Color::Red),
        half: t.ink(Color::DarkGray),
        ours: t.ink(Color::Magenta),
    }
}

/// The curve panel (while a twin rolls): the plot, ε½ and what our ε means, or why there is
/// no curve.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let update = app.twin.curve.as_ref();
    let failed = matches!(update.map(|u| &u.state), Some(CurveState::Failed(_)));
    let mut block = Block::bordered().title(title(app, update, area.width.saturating_sub(2)));
    if !failed {
        block = block.title_bottom(legend(app, area.width.saturating_sub(2)));
    }
    let body = block.inner(area);
    frame.render_widget(block, area);
    if body.height < 3 || body.width < 16 {
        return;
    }
    let epsilon = app
        .roll
        .live
        .twin
        .as_ref()
        .map_or(app.twin.epsilon, |tw| tw.epsilon);
    let (curve, computing) = match update.map(|u| &u.state) {
        Some(CurveState::Complete(c)) => (Some(c), false),
        Some(CurveState::Computing(c)) => (c.as_ref(), true),
        Some(CurveState::Failed(why)) => {
            let text = Paragraph::new(vec![
                Line::styled("The curve cannot be computed:", t.danger()),
                Line::raw(why.clone()),
            ])
            .wrap(Wrap { trim: true });
            frame.render_widget(text, crate::tui::panels::overlays::popup::text_area(body));
            return;
        }
        None => (None, true),
    };
    let width = body.width as usize;
    let mut text = Vec::new();
    match curve {
        Some(c) if c.faces.total() > 0 => {
            text.push(Line::from(vec![Span::styled(
                our_epsilon_text(c, epsilon, width),
                Style::new().fg(colours(app).ours),
            )]));
            if computing {
                text.push(crate::tui::vocabulary::fit::abbreviate(
                    Line::styled("computing: the intervals narrow as throws come in", t.caution()),
                    width,
                ));
            } else {
                text.push(Line::raw(threshold_text(c, width)));
            }
        }
        _ => text.push(crate::tui::vocabulary::fit::abbreviate(
            Line::styled("computing: each throw beside 15 twins, ε 1e-15…0.1", t.caution()),
            width,
        )),
    }
    // Two lines of text where there is room, else the first only.
    let rows = if body.height >= 8 { text.len() as u16 } else { 1 };
    text.truncate(rows as usize);
    let [words, plot] = body.layout(&Layout::vertical([Constraint::Length(rows), Constraint::Min(0)]));
    frame.render_widget(Paragraph::new(text), words);
    let series = Series::of(curve, epsilon);
    frame.render_widget(chart(app, &series), plot);
}

/// Evenly spaced x values across the plot, for lines drawn with a glyph per cell.
fn across(step: f64) -> impl Iterator<Item = f64> {
    let n = ((X_RANGE[1] - X_RANGE[0]) / step).round() as usize;
    (0..=n).map(move |i| X_RANGE[0] + i as f64 * step)
}

/// y values from `lo` to `hi`, dense enough to fill every cell between.
fn between(lo: f64, hi: f64) -> impl Iterator<Item = f64> {
    let n = ((hi - lo) / 0.005).ceil().max(1.0) as usize;
    (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64)
}

/// The plot's points, one list per dataset.
#[derive(Default)]
struct Series {
    ours_line: Vec<(f64, f64)>,
    chance: Vec<(f64, f64)>,
    half: Vec<(f64, f64)>,
    intervals: Vec<(f64, f64)>,
    curve: Vec<(f64, f64)>,
    ours_point: Vec<(f64, f64)>,
}

impl Series {
    /// Nothing before a throw has settled on a face: the empty axes say "no data yet".
    fn of(curve: Option<&PredictCurve>, epsilon: f64) -> Series {
        let Some(curve) = curve.filter(|c| c.faces.total() > 0) else {
            return Series::default();
        };
        let x_ours = epsilon.log10();
        let mut s = Series {
            ours_line: between(0.0, 1.0).map(|y| (x_ours, y)).collect(),
            chance: across(0.02).map(|x| (x, curve.chance)).collect(),
            half: across(0.02).map(|x| (x, curve.half)).collect(),
            ..Series::default()
        };
        for p in curve.points.iter().filter(|p| p.pairs > 0) {
            let x = p.epsilon.log10();
            s.intervals
                .extend(between(p.interval[0], p.interval[1]).map(|y| (x, y)));
            s.curve.push((x, p.same_share));
        }
        if let Some((share, _)) = at_epsilon(curve, epsilon) {
            s.ours_point.push((x_ours, share));
        }
        s
    }
}

/// The plot: later datasets are drawn over earlier ones, so the curve's points and our ε's
/// mark stay visible where lines cross them.
fn chart<'a>(app: &App, s: &'a Series) -> Chart<'a> {
    let g = Glyphs::of(app.die_screen.drawing);
    let c = colours(app);
    let scatter = |data: &'a [(f64, f64)], glyph: char, colour: Color| {
        Dataset::default()
            .marker(Marker::Custom(glyph))
            .graph_type(GraphType::Scatter)
            .style(Style::new().fg(colour))
            .data(data)
    };
    let datasets = vec![
        scatter(&s.ours_line, g.ours, c.ours),
        scatter(&s.half, g.half, c.half),
        scatter(&s.chance, g.chance, c.chance),
        scatter(&s.intervals, g.interval, c.curve),
        Dataset::default()
            .marker(g.curve)
            .graph_type(GraphType::Line)
            .style(Style::new().fg(c.curve))
            .data(&s.curve),
        scatter(&s.curve, g.point, c.curve),
        scatter(&s.ours_point, g.our_point, c.ours),
    ];
    Chart::new(datasets)
        .x_axis(Axis::default().bounds(X_RANGE).labels(["1e-15", "1e-8", "0.1 "]))
        .y_axis(Axis::default().bounds([0.0, 1.0]).labels(["0", "0.5", "1"]))
        .legend_position(None)
}

#[cfg(test)]
mod predictability_curve_tests;
