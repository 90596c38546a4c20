//! The timeline strip, drawn in the die panel's bottom border: where the roll on screen is, how far it has been
//! computed, where its impacts began and where a table value was changed mid-roll (▼); a
//! click seeks there (`,` `.` `Home` `End` step
//! and jump by key).

use super::app::App;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

/// Characters before the bar: the time now (`t 12.345 s `).
const LEFT: u16 = 12;
/// Characters after it: the end, or how far the roll has got (` end 12.345 s`).
const RIGHT: u16 = 14;

/// The bar's columns inside the strip; `None` if the strip is too narrow for one.
pub(crate) fn bar(area: Rect) -> Option<Rect> {
    let width = area.width.checked_sub(LEFT + RIGHT).filter(|&w| w >= 8)?;
    Some(Rect::new(area.x + LEFT, area.y, width, area.height.min(1)))
}

/// Steps the bar spans: the whole roll once it has ended, else as far as it has got.
fn span_steps(app: &App) -> u64 {
    let t = &app.roll.live.timeline;
    t.furthest.max(t.position).max(1)
}

/// The bar column that step `n` falls in.
fn column_of(n: u64, steps: u64, width: u16) -> u16 {
    let last = width.saturating_sub(1) as u64;
    ((n.min(steps) * last + steps / 2) / steps) as u16
}

/// The step a click on bar column `column` asks for.
pub(crate) fn step_at(app: &App, bar: Rect, column: u16) -> u64 {
    let last = bar.width.saturating_sub(1).max(1) as u64;
    let x = column.saturating_sub(bar.x).min(bar.width.saturating_sub(1)) as u64;
    (x * span_steps(app) + last / 2) / last
}

pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let timeline = &app.roll.live.timeline;
    let dt = app.roll.live.params.integrator.dt;
    // As many decimals as Δt has (at least the header's three), so one step shows.
    let decimals = ((-dt.log10()).ceil().max(3.0)) as usize;
    let seconds = |n: u64| format!("{:.*} s", decimals, n as f64 * dt);
    let now = format!("t {}", seconds(timeline.position));
    let end = if timeline.ended {
        format!("end {}", seconds(timeline.furthest))
    } else {
        format!("… {}", seconds(timeline.furthest))
    };
    let Some(bar) = bar(area) else {
        frame.render_widget(Paragraph::new(format!("{now} · {end}")), area);
        return;
    };
    let steps = span_steps(app);
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
    for &edit in &app.roll.edits {
        let i = column_of(edit, steps, bar.width) as usize;
        cells[i] = ('▼', Style::new().fg(super::plot::marker_colour(app)));
    }
    let i = column_of(timeline.position, steps, bar.width) as usize;
    cells[i] = ('◆', t.selected());
    let mut spans = vec![Span::styled(
        format!("{now:<width$}", width = LEFT as usize),
        t.heading(),
    )];
    spans.extend(
        cells
            .into_iter()
            .map(|(c, style)| Span::styled(c.to_string(), style)),
    );
    spans.push(Span::raw(format!(" {end:<width$}", width = RIGHT as usize - 1)));
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}
