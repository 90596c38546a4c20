//! The energy bar and the energy ledger beside the time plot: the rigid-body energy now,
//! stacked by form, and where the rest went since t = 0 (damping, friction, and the
//! integrator's own error), as the physics measured it step by step.

use crate::tui::state::app::App;
use crate::tui::vocabulary::fit;
use crate::tui::vocabulary::format::fmt_num;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

/// Columns the bar (and its total mark) take on the left of the panel.
const BAR_COLUMNS: u16 = 3;

/// The four stacked forms, bottom to top: name, short name, index into `energy_series`, value.
fn forms(app: &App) -> [(&'static str, &'static str, usize, f64); 4] {
    let e = &app.roll.live.energy;
    [
        ("grav", "g", 3, e.gravitational),
        ("transl", "tr", 1, e.translational),
        ("rot", "r", 2, e.rotational),
        ("elastic", "el", 4, e.elastic),
    ]
}

/// The glyph of each stacked form: one solid block in colour; without colour the forms are
/// told apart by shading alone.
fn glyph(app: &App, index: usize) -> char {
    if app.theme.colour {
        '█'
    } else {
        ['█', '▓', '▒', '░'][index]
    }
}

/// Which form fills the bar at each row, bottom row first (`None` above the stack), and the
/// row of the total (counted from the bottom; the total is the sum with gravity as it is,
/// while the stack shows a negative gravitational term, a die pressed into the ground, as 0).
pub(crate) fn bar_rows(app: &App, rows: u16) -> (Vec<Option<usize>>, Option<u16>) {
    let forms = forms(app);
    let stacked: f64 = forms.iter().map(|f| f.3.max(0.0)).sum();
    let total = app.roll.live.energy.total();
    let top = app.roll.live.ledger.initial.max(stacked).max(total);
    if rows == 0 || !(top.is_finite() && top > 0.0) {
        return (vec![None; rows as usize], None);
    }
    let per_row = top / rows as f64;
    let cells = (0..rows)
        .map(|r| {
            let middle = (r as f64 + 0.5) * per_row;
            let mut below = 0.0;
            for (i, f) in forms.iter().enumerate() {
                below += f.3.max(0.0);
                if middle < below {
                    return Some(i);
                }
            }
            None
        })
        .collect();
    let total_row = (total / per_row).floor().clamp(0.0, rows as f64 - 1.0) as u16;
    (cells, Some(total_row))
}

/// The energy bar, top row first: each cell in the colour of the form it stands for, the
/// total marked.
fn bar_lines(app: &App, height: u16) -> Vec<Line<'static>> {
    let t = &app.theme;
    let colours = t.energy_series();
    let forms = forms(app);
    let (cells, total_row) = bar_rows(app, height);
    (0..height)
        .rev()
        .map(|r| {
            let fill = match cells[r as usize] {
                Some(i) => Span::styled(
                    glyph(app, i).to_string().repeat(2),
                    Style::new().fg(colours[forms[i].2]),
                ),
                None => Span::raw("  "),
            };
            let mark = if total_row == Some(r) { "◀" } else { " " };
            Line::from(vec![fill, Span::styled(mark, t.heading())])
        })
        .collect()
}

/// A row of the books `text_width` wide: the label, the number right-aligned. A label too
/// long beside its number loses its glyph or indent, then takes its `short` form (never a
/// word cut mid-way): the number is what is read.
fn book_row(label: Span<'static>, short: &str, value: f64, text_width: usize) -> Line<'static> {
    let number = fmt_num(value);
    let room = fit::room(text_width);
    let label_room = room.saturating_sub(number.chars().count() + 1);
    let bare = label
        .content
        .trim_start_matches(['█', '▓', '▒', '░', '◀', ' '])
        .to_string();
    let text = [label.content.to_string(), bare, short.to_string()]
        .into_iter()
        .find(|l| l.chars().count() <= label_room)
        .unwrap_or_default();
    let label = Span::styled(text, label.style);
    let pad = room.saturating_sub(label.width() + number.chars().count());
    Line::from(vec![label, Span::raw(" ".repeat(pad)), Span::raw(number)])
}

/// The energy ledger: a bar of the energy now by form, the energy gone (damping, friction,
/// the integrator's share) and the start it all came from.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    // The energy at the state on screen: the energy plot's readout at its time marker.
    let title = fit::longest_fitting(
        &[
            " energy now, erg ".to_string(),
            " now, erg ".to_string(),
            " erg ".to_string(),
        ],
        area.width.saturating_sub(2) as usize,
    );
    let mut block = Block::bordered().title(Line::styled(title, t.heading()));
    let body = block.inner(area);
    if body.width < BAR_COLUMNS + 8 || body.height < 2 {
        frame.render_widget(block, area);
        return;
    }
    let colours = t.energy_series();
    let forms = forms(app);
    frame.render_widget(
        Paragraph::new(bar_lines(app, body.height)),
        Rect {
            width: BAR_COLUMNS,
            ..body
        },
    );
    let text_width = (body.width - BAR_COLUMNS) as usize;
    let l = &app.roll.live.ledger;
    // A term a billionth of the start or less is the arithmetic's rounding, not energy: 0.
    let noise = 1e-9 * l.initial.abs().max(1.0);
    let row = |label: Span<'static>, short: &str, value: f64| {
        let value = if value.abs() < noise { 0.0 } else { value };
        book_row(label, short, value, text_width)
    };
    // By importance, for a short panel: the total, the heading that says the numbers under
    // it are energy gone (not energy present) and the two losses a class asks about; the
    // start moves into the bottom border; then the integrator's share and the forms go.
    let mut lines: Vec<(u8, Line)> = forms
        .iter()
        .enumerate()
        .rev()
        .map(|(i, (name, short, colour, value))| {
            let rank = if i == 3 { 4 } else { 3 };
            let label = Span::styled(
                format!("{} {name}", glyph(app, i)),
                Style::new().fg(colours[*colour]),
            );
            (rank, row(label, short, *value))
        })
        .collect();
    lines.push((
        0,
        row(
            Span::styled("◀ total", t.heading()),
            "◀",
            app.roll.live.energy.total(),
        ),
    ));
    let heading = if text_width >= 20 {
        "lost since 0 s, erg"
    } else {
        "lost since 0 s"
    };
    lines.push((0, Line::styled(heading, t.heading())));
    // Indented under their heading where the numbers leave room.
    let indent = if text_width >= 17 { "  " } else { "" };
    lines.push((
        0,
        row(Span::raw(format!("{indent}damping")), "damp.", l.damping_loss),
    ));
    lines.push((
        0,
        row(Span::raw(format!("{indent}friction")), "fric.", l.friction_loss),
    ));
    // The remainder: what semi-implicit Euler itself took (negative: gave).
    lines.push((
        2,
        row(Span::raw(format!("{indent}integr.")), "int.", l.integrator_loss),
    ));
    let start = row(Span::styled("= start", t.heading()), "=", l.initial);
    let lines = if lines.len() < body.height as usize {
        lines.push((0, start));
        fit::rows(lines, body.height as usize)
    } else {
        // A space before the corner keeps the number in line with those above.
        let mut spans = vec![Span::raw(" ")];
        spans.extend(start.spans);
        spans.push(Span::raw(" "));
        block = block.title_bottom(Line::from(spans).right_aligned());
        fit::rows(lines, body.height as usize)
    };
    frame.render_widget(block, area);
    frame.render_widget(
        Paragraph::new(lines),
        Rect {
            x: body.x + BAR_COLUMNS,
            width: body.width - BAR_COLUMNS,
            ..body
        },
    );
}

#[cfg(test)]
mod ledger_tests;
