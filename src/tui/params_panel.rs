//! The parameter panel: every value of the setup, the one selected, the value being
//! typed, and the step's stability readout under them.

use super::app::App;
use super::format::{fmt_num, fmt_range};
use super::layout::param_window;
use super::param::all;
use crate::physics::Stability;
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

pub(crate) fn render_params(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let (first, visible) = param_window(app.selected, area);
    // Rows scrolled out of view, above and below: ↑↓ (or a click and the wheel) reach them.
    let below = all().len().saturating_sub(first + visible);
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
    let wide = body.width >= 49;
    let mut lines = Vec::with_capacity(body.height as usize);
    let mut head = format!(" {:<13} {:>8} {:<6}", "parameter", "value", "unit");
    if wide {
        head.push_str(&format!(" {:<11}", "range"));
    }
    lines.push(Line::styled(head, t.heading()));
    for (i, &p) in all().iter().enumerate().skip(first).take(visible) {
        let value = fmt_num(p.get(&app.setup.params, &app.setup.initial));
        let mut spans = vec![Span::raw(format!(
            "{}{:<13} {:>8} {:<6}",
            if i == app.selected { "▶" } else { " " },
            p.label(),
            value,
            p.limits().unit
        ))];
        if wide {
            spans.push(Span::raw(format!(" {:<11}", fmt_range(p))));
        }
        let mut line = Line::from(spans);
        if i == app.selected {
            line = line.style(t.selected());
        }
        lines.push(line);
    }
    let p = app.selected_param();
    let detail = match app.value_editor() {
        Some(editor) => match &editor.error {
            Some(e) => Line::styled(format!(" {e}"), t.danger()),
            None => Line::from(vec![
                Span::styled(format!(" {} = ", p.label()), t.heading()),
                Span::styled(format!("{}▏", editor.text), t.selected()),
                Span::raw(format!("  {} {}", fmt_range(p), p.limits().unit)),
            ]),
        },
        None => {
            let when = if p.acts_mid_roll() {
                "acts now"
            } else {
                "restarts the roll"
            };
            let mut s = vec![Span::raw(format!(" {} ", p.key()))];
            if !wide {
                s.push(Span::raw(format!("{} ", fmt_range(p))));
            }
            s.push(Span::raw(format!("· {when}")));
            Line::from(s)
        }
    };
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
