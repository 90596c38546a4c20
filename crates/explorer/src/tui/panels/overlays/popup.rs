//! What the popups (the dialogs, the question, the help) and the panels of wrapped text
//! (the map's side panel, the twin's curve) share: a popup's cells cleared with a margin,
//! and wrapped text kept off a box's last column.

use crate::tui::vocabulary::fit;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::widgets::Clear;

/// Clears a popup and a column either side of it, so the text it covers ends in a blank
/// column instead of running into its border as if cut.
pub(crate) fn clear_around(popup: Rect, screen: Rect, frame: &mut Frame) {
    let x = popup.x.saturating_sub(1).max(screen.x);
    let right = (popup.right() + 1).min(screen.right());
    frame.render_widget(
        Clear,
        Rect {
            x,
            width: right - x,
            ..popup
        },
    );
}

/// The part of a popup's inside its text wraps in: the last column stays free (`fit`).
pub(crate) fn text_area(inside: Rect) -> Rect {
    Rect {
        width: fit::room(inside.width as usize) as u16,
        ..inside
    }
}
