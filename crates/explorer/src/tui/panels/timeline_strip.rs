//! The timeline strip, drawn in the die panel's bottom border: where the roll on screen is
//! (◆), how far it has been computed, where its impacts began (┃), where the face was
//! decided (✓) and where a table value was changed mid-roll (▼); a click seeks there, and the
//! keys step (`,` `.`), jump to the ends (`Home` `End`) and to the marks (`i` `I` `F`).

use crate::tui::panels::chart::marker_colour;
use crate::tui::state::app::App;
use crate::tui::vocabulary::layout::{strip_seconds, timeline_bar, timeline_margins, timeline_steps};
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

/// The bar column that step `n` falls in.
fn column_of(n: u64, steps: u64, width: u16) -> u16 {
    let last = width.saturating_sub(1) as u64;
    ((n.min(steps) * last + steps / 2) / steps) as u16
}

/// The strip: the time now, the bar with its marks, the end (or how far the roll has got).
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let timeline = &app.roll.live.timeline;
    let integrator = &app.roll.live.params.integrator;
    let dt = integrator.dt;
    let seconds = |n: u64| strip_seconds(n as f64 * dt, dt);
    let margins = timeline_margins(dt, integrator.max_time);
    let now = format!("t {}", seconds(timeline.position));
    let end = if timeline.ended {
        format!("end {}", seconds(timeline.furthest))
    } else {
        format!("… {}", seconds(timeline.furthest))
    };
    let Some(bar) = timeline_bar(area, margins) else {
        frame.render_widget(Paragraph::new(format!("{now} · {end}")), area);
        return;
    };
    let steps = timeline_steps(timeline);
    let mut cells: Vec<(char, Style)> = vec![('─', Style::new().fg(t.shadow())); bar.width as usize];
    for (i, cell) in cells.iter_mut().enumerate() {
        if column_of(timeline.furthest, steps, bar.width) >= i as u16 {
            *cell = ('━', Style::new().fg(t.ground()));
        }
    }
    for &impact in &app.roll.impacts {
        let i = column_of(impact, steps, bar.width) as usize;
        cells[i] = ('┃', t.contact());
    }
    // Where the stopping rule decided the face: the event key jumps there.
    if let Some(decided) = timeline.decided {
        let i = column_of(decided, steps, bar.width) as usize;
        cells[i] = ('✓', t.good());
    }
    for &edit in &app.roll.edits {
        let i = column_of(edit, steps, bar.width) as usize;
        cells[i] = ('▼', Style::new().fg(marker_colour(app)));
    }
    let i = column_of(timeline.position, steps, bar.width) as usize;
    cells[i] = ('◆', t.selected());
    let mut spans = vec![Span::styled(
        format!("{now:<width$}", width = margins.0 as usize),
        t.heading(),
    )];
    spans.extend(
        cells
            .into_iter()
            .map(|(c, style)| Span::styled(c.to_string(), style)),
    );
    spans.push(Span::raw(format!(
        " {end:<width$}",
        width = margins.1 as usize - 1
    )));
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

#[cfg(test)]
mod timeline_strip_tests;
