//! The notice shown instead of a screen when the terminal is too small for it.

use crate::tui::state::app::App;
use crate::tui::vocabulary::key_table::{Action, Scope, label};
use crate::tui::vocabulary::layout::{MIN_HEIGHT, MIN_WIDTH};
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Paragraph, Wrap};

pub(crate) fn render(_app: &App, area: Rect, frame: &mut Frame) {
    let text = vec![
        Line::styled(
            format!("Enlarge the terminal to at least {MIN_WIDTH}×{MIN_HEIGHT}"),
            Style::new().add_modifier(Modifier::BOLD),
        ),
        Line::from(format!(
            "(it is {}×{} now) · {} quits",
            area.width,
            area.height,
            label(Scope::Die, Action::Quit)
        )),
    ];
    let top = area.height.saturating_sub(2) / 2;
    let [_, middle] = area.layout(&Layout::vertical([Constraint::Length(top), Constraint::Min(0)]));
    frame.render_widget(Paragraph::new(text).centered().wrap(Wrap { trim: true }), middle);
}

#[cfg(test)]
mod too_small_tests;
