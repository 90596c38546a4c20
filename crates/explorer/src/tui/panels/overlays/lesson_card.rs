//! A lesson step's card: its sentence in large type for the back row, over the screen the
//! step opened, between the header and the footer (which stay, so the class sees the preset
//! and the speed). Its frame says which step of how many, and which keys go on.

use crate::tui::panels::overlays::popup;
use crate::tui::state::app::App;
use crate::tui::vocabulary::big_type;
use crate::tui::vocabulary::key_table::{Action, Scope, first_key};
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

/// Draws the card of the step open, over everything but the top and bottom lines.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let Some(run) = app.lesson.as_ref() else { return };
    let (Some(step), Some(at)) = (run.step(), run.at) else {
        return;
    };
    let t = &app.theme;
    let card = Rect::new(area.x, area.y + 1, area.width, area.height.saturating_sub(2));
    popup::clear_around(card, area, frame);
    let block = Block::bordered()
        .border_style(t.heading())
        .title(Line::styled(
            format!(" lesson · step {} of {} ", at + 1, run.len()),
            t.heading(),
        ))
        .title_bottom(
            Line::from(vec![
                Span::raw(" "),
                Span::styled(first_key(Scope::Die, Action::NextStep), t.key()),
                Span::raw(" the screen · "),
                Span::styled(first_key(Scope::Die, Action::PreviousStep), t.key()),
                Span::raw(" back · any key works on it "),
            ])
            .centered(),
        );
    let inner = block.inner(card);
    frame.render_widget(block, card);
    let columns = inner.width.saturating_sub(2) as usize;
    let big = big_type::wrap(&step.say, columns).unwrap_or_default();
    let rows = big_type::height(big.len());
    // The title, a blank line, then the sentence, the whole centred up and down.
    let used = rows + 2;
    let top = inner.y + inner.height.saturating_sub(used) / 2;
    let mut lines = vec![
        Line::styled(step.title.replace('`', ""), t.heading()).centered(),
        Line::raw(""),
    ];
    for (i, line) in big.iter().enumerate() {
        if i > 0 {
            lines.extend((0..big_type::LEADING).map(|_| Line::raw("")));
        }
        lines.extend(
            big_type::render_line(line)
                .into_iter()
                .map(|row| Line::styled(row, t.heading()).centered()),
        );
    }
    let body = Rect::new(inner.x, top, inner.width, inner.bottom().saturating_sub(top));
    frame.render_widget(Paragraph::new(lines), body);
}
