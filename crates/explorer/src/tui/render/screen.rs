//! Drawing: `render(&App, &mut Frame)` is a pure function of the app state. It never steps
//! the physics and never reads a clock.

use crate::tui::panels::die::render_die;
use crate::tui::panels::footer::{render_footer, render_help};
use crate::tui::panels::header::{render_header, render_too_small};
use crate::tui::panels::outcomes::render_outcomes;
use crate::tui::panels::params_panel::render_params;
use crate::tui::panels::quantity_plot::render_plot;
use crate::tui::state::app::{App, Page};
use crate::tui::vocabulary::layout::screen_layout;
use ratatui::Frame;

/// Draws the whole screen, then paints the theme over every cell of it, whichever screen.
pub fn render(app: &App, frame: &mut Frame) {
    match app.page {
        Page::Map => crate::tui::panels::basin_map::render_map_screen(app, frame),
        Page::Presentation if screen_layout(frame.area()).is_some() => {
            crate::tui::panels::presentation::render(app, frame)
        }
        _ => render_die_screen(app, frame),
    }
    app.theme.paint(frame.buffer_mut());
}

fn render_die_screen(app: &App, frame: &mut Frame) {
    let area = frame.area();
    let Some(areas) = screen_layout(area) else {
        render_too_small(area, frame);
        return;
    };
    render_header(app, areas.header, frame);
    render_params(app, areas.params, frame);
    render_die(app, areas.die, frame);
    crate::tui::panels::timeline_strip::render(app, areas.timeline, frame);
    // While a chaos twin rolls, its predictability curve takes the outcome table's place
    // and the separation of the two dice the plot's. A parameter twin's table of shared
    // throws takes the outcome table's place; the plot stays, with die B's curve in it.
    if let Some(twin) = &app.roll.live.twin {
        if twin.differs_by.is_empty() {
            crate::tui::panels::twins::predictability_curve::render_curve(app, areas.outcomes, frame);
            crate::tui::panels::twins::separation::render_separation(app, areas.energy, frame);
        } else {
            crate::tui::panels::twins::versus_table::render_table(app, areas.outcomes, frame);
            render_plot(app, areas.energy, frame);
        }
    } else {
        render_outcomes(app, areas.outcomes, frame);
        render_plot(app, areas.energy, frame);
    }
    crate::tui::panels::ledger::render_ledger(app, areas.ledger, frame);
    render_footer(app, areas.footer, frame);
    if app.help_scroll().is_some() {
        render_help(app, area, frame);
    }
    crate::tui::panels::overlays::dialogs::render(app, area, frame);
}
