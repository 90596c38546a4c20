//! The chaos twin (`T`) on screen: the separation of the ghost die from the die on a log
//! scale, ε's meaning above it (or ε being typed), and both outcomes below. The worker
//! steps both dice.

use crate::tui::panels::chart::time_axis_to;
use crate::tui::state::app::App;
use crate::tui::state::twins::DEFINITION;
use crate::tui::vocabulary::format::fmt_num;
use crate::worker::Phase;
use dicesim_physics::Status;
use dicesim_setup::chaos::EPSILON;
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph};

/// log₁₀ of the smallest separation the plot shows (below it: rounding of doubles).
const FLOOR: f64 = -16.0;

/// The separation plot with ε's meaning above and both outcomes below.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let Some(twin) = &app.roll.live.twin else { return };
    let colours = t.separation_colours();
    let epsilon = fmt_num(twin.epsilon);
    let title = Line::from(vec![
        Span::styled(" chaos twin ", t.heading()),
        Span::raw(format!("ε = {epsilon} ")),
        Span::styled("━centre cm ", Style::new().fg(colours[0])),
        Span::styled("━angle rad ", Style::new().fg(colours[1])),
    ]);
    // A cut title would show another ε (1e-11 as 1e-1): narrow, ε keeps the top border and
    // the legend goes to the bottom one.
    let block = if title.to_string().trim_end().chars().count() + 2 < area.width as usize {
        Block::bordered().title(title)
    } else {
        Block::bordered()
            .title(Line::from(vec![
                Span::styled(" twin ", t.heading()),
                Span::raw(format!("ε = {epsilon} ")),
            ]))
            .title_bottom(Line::from(vec![
                Span::styled("━cm ", Style::new().fg(colours[0])),
                Span::styled("━rad ", Style::new().fg(colours[1])),
            ]))
    };
    let body = block.inner(area);
    frame.render_widget(block, area);
    if body.height < 4 || body.width < 16 {
        return;
    }
    let verdict = outcome_lines(app, body.width);
    let [definition, plot, outcomes] = body.layout(&Layout::vertical([
        Constraint::Length(1),
        Constraint::Min(0),
        Constraint::Length(verdict.len() as u16),
    ]));
    let definition_text = match app.epsilon_editor() {
        Some(editor) => match &editor.error {
            Some(e) => Line::styled(e.clone(), t.danger()),
            None => Line::from(vec![
                Span::styled("ε = ", t.heading()),
                Span::styled(format!("{}▏", editor.text), t.selected()),
                Span::raw(format!("  {}…{}", fmt_num(EPSILON.min), fmt_num(EPSILON.max))),
            ]),
        },
        None if crate::tui::vocabulary::fit::room(definition.width as usize)
            >= DEFINITION.chars().count() =>
        {
            Line::raw(DEFINITION)
        }
        None => Line::raw("h, v, ω × (1+ε)"),
    };
    frame.render_widget(Paragraph::new(definition_text), definition);
    let y_of = |v: f64| if v > 0.0 { v.log10().max(FLOOR) } else { FLOOR };
    let centre: Vec<(f64, f64)> = app
        .twin
        .history
        .iter()
        .map(|s| (s.time_s, y_of(s.separation.centre)))
        .collect();
    let angle: Vec<(f64, f64)> = app
        .twin
        .history
        .iter()
        .map(|s| (s.time_s, y_of(s.separation.angle)))
        .collect();
    let t_end = app
        .twin
        .history
        .last()
        .map_or(0.0, |s| s.time_s)
        .max(app.roll.live.time_s);
    let (x_hi, x_labels) = time_axis_to(t_end, body.width);
    let marker = app.die_screen.drawing.line_marker();
    let datasets = vec![
        Dataset::default()
            .marker(marker)
            .graph_type(GraphType::Line)
            .style(Style::new().fg(colours[0]))
            .data(&centre),
        Dataset::default()
            .marker(marker)
            .graph_type(GraphType::Line)
            .style(Style::new().fg(colours[1]))
            .data(&angle),
    ];
    let chart = Chart::new(datasets)
        .x_axis(Axis::default().bounds([0.0, x_hi]).labels(x_labels))
        .y_axis(
            Axis::default()
                .bounds([FLOOR, 1.0])
                .labels(["1e-16", "1e-8", "10"]),
        )
        .legend_position(None);
    frame.render_widget(chart, plot);
    frame.render_widget(Paragraph::new(verdict), outcomes);
}

/// The plot's time axis end: whole seconds past one, tenths below.
fn face_of(phase: &Phase) -> Option<u8> {
    match phase {
        Phase::Ended(o) if o.status == Status::Settled => o.face,
        _ => None,
    }
}

/// "die settled: face 3 · twin settled: face 5 · faces differ"; narrower "die 3 · twin 5 ·
/// faces differ"; narrower still, the verdict on a line of its own (the lesson's point, so
/// it is never cut).
pub(crate) fn outcome_lines(app: &App, width: u16) -> Vec<Line<'static>> {
    let t = &app.theme;
    let Some(twin) = &app.roll.live.twin else {
        return Vec::new();
    };
    let room = crate::tui::vocabulary::fit::room(width as usize);
    let faces = (face_of(&app.roll.live.phase), face_of(&twin.phase));
    let verdict = match faces {
        (Some(a), Some(b)) if a == b => Some(Span::styled("same face", t.good())),
        (Some(_), Some(_)) => Some(Span::styled("faces differ", t.caution())),
        _ => None,
    };
    let verdict_width = verdict.as_ref().map_or(0, |v| v.width() + 3);
    let full = format!(
        "die {} · twin {}",
        app.roll.live.phase.label(),
        twin.phase.label()
    );
    let short = |f: Option<u8>| f.map_or("…".to_string(), |f| f.to_string());
    let brief = format!("die {} · twin {}", short(faces.0), short(faces.1));
    let text = if full.chars().count() + verdict_width <= room {
        full
    } else {
        brief
    };
    let together = text.chars().count() + verdict_width <= room;
    let mut lines = vec![Line::from(crate::tui::vocabulary::fit::cut_text(&text, room))];
    if let Some(v) = verdict {
        if together {
            lines[0].spans.push(Span::raw(" · "));
            lines[0].spans.push(v);
        } else {
            lines.push(Line::from(v));
        }
    }
    lines
}

#[cfg(test)]
mod separation_tests;
