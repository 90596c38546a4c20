//! Drawing: `render(&App, &mut Frame)` is a pure function of the app state. It never steps
//! the physics and never reads a clock.

use super::places::PLACES;
use crate::tui::panels::too_small;
use crate::tui::state::app::App;
use crate::tui::vocabulary::layout::screen_layout;
use ratatui::Frame;

/// Draws the panels `PLACES` puts on screen now, or the notice that the terminal is too
/// small, then paints the theme over every cell.
pub fn render(app: &App, frame: &mut Frame) {
    let area = frame.area();
    match screen_layout(area) {
        None => too_small::render(app, area, frame),
        Some(areas) => {
            for (place, when, panel) in PLACES {
                if when.holds(app) {
                    panel(app, place.rect(&areas, area), frame);
                }
            }
        }
    }
    app.theme.paint(frame.buffer_mut());
}
