//! The parameter panel: every value of the setup, the one selected, the value being
//! typed, and the step's stability readout under them.

use crate::tui::state::app::App;
use crate::tui::vocabulary::fit;
use crate::tui::vocabulary::format::{fmt_num, fmt_range};
use crate::tui::vocabulary::layout::param_window;
use dicesim_physics::Stability;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

/// Share of the tightest stability limit from which the step is worth watching; past the
/// limit itself (1) a roll is predicted unstable (docs/model.md, "Stability").
pub(crate) const STABILITY_CAUTION: f64 = 0.8;
pub(crate) const STABILITY_DANGER: f64 = 1.0;

fn stability_style(app: &App, load: f64) -> Style {
    if load > STABILITY_DANGER || load.is_nan() {
        app.theme.danger()
    } else if load >= STABILITY_CAUTION {
        app.theme.caution()
    } else {
        Style::new()
    }
}

/// The one stability readout: the tightest of the predictor's limits for the setup on the
/// list, as a share of that limit, e.g. "Δt stability: table stiffness at 44 % of limit".
pub(crate) fn stability_readout(app: &App, width: u16) -> Line<'static> {
    let reading = Stability::predict(&app.setup.params, &app.setup.initial).verdict();
    let load = reading.load();
    let percent = if load.is_finite() {
        format!("{:.0} %", 100.0 * load)
    } else {
        "∞".to_string()
    };
    let name = reading.limit.name();
    let text = [
        format!(" Δt stability: {name} at {percent} of limit "),
        format!(" Δt: {name} at {percent} of limit "),
        format!(" Δt: {name} {percent} of limit "),
    ]
    .into_iter()
    .find(|t| t.chars().count() <= width as usize)
    .unwrap_or_else(|| format!(" Δt: {name} {percent} "));
    Line::styled(text, stability_style(app, load))
}

pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let (first, visible) = param_window(app.die_screen.selected, area);
    // Rows scrolled out of view, above and below: ↑↓ (or a click and the wheel) reach them.
    let listed = app.params_listed();
    let below = listed.len().saturating_sub(first + visible);
    let mut title = vec![Span::styled(" parameters ", t.heading())];
    if first > 0 {
        title.push(Span::raw(format!("↑{first} ")));
    }
    if below > 0 {
        title.push(Span::raw(format!("↓{below} more ")));
    }
    let block = Block::bordered()
        .title(Line::from(title))
        .title_bottom(stability_readout(app, area.width.saturating_sub(2)));
    let body = block.inner(area);
    frame.render_widget(block, area);
    if body.height == 0 {
        return;
    }
    let wide = body.width as usize >= WIDE;
    let mut lines = Vec::with_capacity(body.height as usize);
    let mut head = format!(" {:<13} {:>8} {:<6}", "parameter", "value", "unit");
    if wide {
        head.push_str(&format!(" {:<11}", "range"));
    }
    lines.push(Line::styled(head, t.heading()));
    for (i, &p) in listed.iter().enumerate().skip(first).take(visible) {
        let value = fmt_num(p.get(&app.setup.params, &app.setup.initial));
        let mut spans = vec![Span::raw(format!(
            "{}{:<13} {:>8} {:<6}",
            if i == app.die_screen.selected { "▶" } else { " " },
            p.label(),
            value,
            p.limits().unit
        ))];
        if wide {
            spans.push(Span::raw(format!(" {:<11}", fmt_range(p))));
        }
        let mut line = Line::from(spans);
        if i == app.die_screen.selected {
            line = line.style(t.selected());
        }
        lines.push(line);
    }
    let detail = detail_line(app, body.width as usize);
    let rows_area = Rect {
        height: body.height.saturating_sub(1),
        ..body
    };
    frame.render_widget(Paragraph::new(lines), rows_area);
    if body.height >= 2 {
        let detail_area = Rect {
            y: body.bottom() - 1,
            height: 1,
            ..body
        };
        frame.render_widget(Paragraph::new(detail), detail_area);
    }
}

/// The line under the list: the value being typed and its range, or why it was refused,
/// or the selected value's key and whether a change acts now or restarts the roll; its
/// parts ranked for a narrow panel. A refusal too long for the line is on the status line
/// instead ([`error_fits`]), whole.
fn detail_line(app: &App, width: usize) -> Line<'static> {
    let t = &app.theme;
    let p = app.selected_param();
    match app.value_editor() {
        Some(editor) => {
            let typed = vec![
                (0, vec![Span::styled(format!(" {} = ", p.label()), t.heading())]),
                (0, vec![Span::styled(format!("{}▏", editor.text), t.selected())]),
                (
                    1,
                    vec![Span::raw(format!("  {} {}", fmt_range(p), p.limits().unit))],
                ),
            ];
            match &editor.error {
                Some(e) if error_fits(e, width) => Line::styled(format!(" {e}"), t.danger()),
                Some(_) => fit::line(
                    vec![
                        typed[0].clone(),
                        typed[1].clone(),
                        (1, vec![Span::styled("  refused ↓", t.danger())]),
                    ],
                    width,
                ),
                None => fit::line(typed, width),
            }
        }
        None => {
            let when = if p.acts_mid_roll() {
                "acts now"
            } else {
                "restarts the roll"
            };
            let mut parts = vec![(0, vec![Span::raw(format!(" {} ", p.key()))])];
            if width < WIDE {
                parts.push((2, vec![Span::raw(format!("{} ", fmt_range(p)))]));
            }
            parts.push((1, vec![Span::raw(format!("· {when}"))]));
            fit::line(parts, width)
        }
    }
}

/// Inside width from which the list has a range column.
const WIDE: usize = 49;

/// Whether a refusal fits the line under the list of a panel `width` wide inside.
fn error_fits(error: &str, width: usize) -> bool {
    error.chars().count() < fit::room(width)
}

/// The refusal of the value being typed when the parameter panel of a screen this wide
/// has no room for it: the status line shows it.
pub(crate) fn refusal_for_status_line(app: &App, screen_width: u16) -> Option<String> {
    let inside = crate::tui::vocabulary::layout::left_width(screen_width).saturating_sub(2) as usize;
    let error = app.value_editor()?.error.as_ref()?;
    (!error_fits(error, inside)).then(|| error.clone())
}

#[cfg(test)]
mod params_panel_tests;
