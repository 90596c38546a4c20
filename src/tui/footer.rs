//! The footer's key hints and the help overlay's frame.

use super::app::App;
use super::help::help_lines;
use ratatui::Frame;
use ratatui::layout::{Constraint, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Wrap};

pub(crate) fn render_footer(app: &App, area: Rect, frame: &mut Frame) {
    // (key, what it does, priority): on a narrow terminal the highest numbers go first, so
    // the keys that matter most, help and quit among them, always stay in view.
    let keys: Vec<(&str, &str, u8)> = if app.editing.is_some() || app.epsilon_editor.is_some() {
        typing_hints("0-9 . - e")
    } else if app.help {
        help_hints()
    } else {
        vec![
            ("space", if app.live.playing { "pause" } else { "play" }, 0),
            ("n", "step", 1),
            ("r", "replay", 1),
            ("R", "random", 2),
            (
                "b",
                if app.batch.is_some() {
                    "cancel batch"
                } else {
                    "batch"
                },
                2,
            ),
            ("[ ]", "speed", 1),
            ("↑↓←→", "values", 2),
            ("v", "arrows", 3),
            if app.twin {
                ("T < > E", "twin, ε", 3)
            } else {
                ("T", "twin", 3)
            },
            ("Tab", "map", 3),
            ("o s", "presets", 4),
            ("e", "export", 4),
            ("?", "help", 0),
            ("q", "quit", 0),
        ]
    };
    render_key_hints(app, keys, area, frame);
}

/// The footer while a value is typed: `typing` says what may be typed.
pub(crate) fn typing_hints(typing: &'static str) -> Vec<(&'static str, &'static str, u8)> {
    vec![
        (typing, "type", 0),
        ("Enter", "apply", 0),
        ("Esc", "cancel", 0),
        ("Ctrl-C", "quit", 0),
    ]
}

/// The footer while the help overlay is open.
pub(crate) fn help_hints() -> Vec<(&'static str, &'static str, u8)> {
    vec![("↑↓", "scroll", 0), ("? Esc", "close help", 0), ("q", "quit", 0)]
}

/// A footer line of `(key, what it does, priority)` hints after any notice. On a narrow
/// terminal the highest priority numbers are dropped first; priority 0 always stays.
pub(crate) fn render_key_hints(app: &App, keys: Vec<(&str, &str, u8)>, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let notice = app
        .export_status()
        .or_else(|| app.notice.clone())
        // Notices quote names and errors from files: an escape sequence in one is shown,
        // not obeyed (ratatui alone would drop the control character and show the rest).
        .map(|n| format!(" {} ", crate::output::printable(&n)));
    let width = |ks: &[(&str, &str, u8)]| -> usize {
        ks.iter()
            .map(|(k, w, _)| 2 + k.chars().count() + w.chars().count())
            .sum::<usize>()
            + notice.as_ref().map_or(0, |n| n.chars().count())
    };
    let mut shown = keys;
    while width(&shown) > area.width as usize {
        let droppable = shown.iter().enumerate().filter(|(_, e)| e.2 > 0);
        let Some((i, _)) = droppable.max_by_key(|(i, e)| (e.2, *i)) else {
            break;
        };
        shown.remove(i);
    }
    let mut spans = Vec::new();
    if let Some(n) = notice {
        spans.push(Span::styled(n, t.caution()));
    }
    for (k, what, _) in shown {
        spans.push(Span::raw(" "));
        spans.push(Span::styled(k, t.key()));
        spans.push(Span::raw(format!(" {what}")));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

pub(crate) fn render_help(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let popup = area.centered(Constraint::Max(100), Constraint::Percentage(90));
    frame.render_widget(Clear, popup);
    let block = Block::bordered()
        .title(Line::styled(" help · the model in a nutshell ", t.heading()))
        .title_bottom(Line::from(" ↑↓ scroll · ? or Esc closes ").right_aligned());
    let para = Paragraph::new(help_lines(t))
        .block(block)
        .wrap(Wrap { trim: false })
        .scroll((app.help_scroll, 0));
    frame.render_widget(para, popup);
}
