//! Which panel takes which place, and when: the one table the render follows. A screen that
//! is open (the basin map, the presentation view) takes the whole terminal; otherwise the die
//! screen's places are filled, a twin's panels taking the outcome table's and the plot's
//! places while it rolls; the overlays go over whichever screen is drawn.

use crate::tui::panels::overlays::{dialogs, help, lesson_card};
use crate::tui::panels::twins::{predictability_curve, separation, versus_table};
use crate::tui::panels::{
    basin_map, die, footer, header, ledger, outcomes, params_panel, presentation, quantity_plot,
    timeline_strip,
};
use crate::tui::state::app::{App, Page};
use crate::tui::vocabulary::layout::Areas;
use ratatui::Frame;
use ratatui::layout::Rect;

/// A panel's one entry point: it draws the app's state into `area` of the frame.
pub(crate) type Panel = fn(&App, Rect, &mut Frame);

/// Where a panel goes: the whole terminal or one of the die screen's [`Areas`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Place {
    Whole,
    Header,
    Params,
    Die,
    Timeline,
    Outcomes,
    Plot,
    Ledger,
    Footer,
}

impl Place {
    /// The rectangle this place is on a terminal of `whole` laid out as `areas`.
    pub(crate) fn rect(self, areas: &Areas, whole: Rect) -> Rect {
        match self {
            Place::Whole => whole,
            Place::Header => areas.header,
            Place::Params => areas.params,
            Place::Die => areas.die,
            Place::Timeline => areas.timeline,
            Place::Outcomes => areas.outcomes,
            Place::Plot => areas.energy,
            Place::Ledger => areas.ledger,
            Place::Footer => areas.footer,
        }
    }
}

/// When a row of [`PLACES`] is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum When {
    /// The basin map's screen is open.
    MapOpen,
    /// The presentation view is open.
    Presenting,
    /// The die screen is open, whatever rolls.
    DieScreen,
    /// The die screen, one die rolling.
    DieAlone,
    /// The die screen while a chaos twin rolls.
    ChaosTwin,
    /// The die screen while a parameter twin (die B, another setup) rolls.
    ParameterTwin,
    /// The die screen unless a chaos twin rolls: a parameter twin keeps the plot, die B's
    /// curve in it.
    NoChaosTwin,
    /// Any screen, a lesson step's card up.
    LessonCard,
    /// Any screen, the help open.
    HelpOpen,
    /// Any screen but the map's: its dialog, if one is open.
    OffMap,
}

impl When {
    pub(crate) fn holds(self, app: &App) -> bool {
        let die_screen = app.page == Page::Die;
        let twin = app.roll.live.twin.as_ref();
        let chaos = twin.is_some_and(|t| t.differs_by.is_empty());
        match self {
            When::MapOpen => app.page == Page::Map,
            When::Presenting => app.page == Page::Presentation,
            When::DieScreen => die_screen,
            When::DieAlone => die_screen && twin.is_none(),
            When::ChaosTwin => die_screen && chaos,
            When::ParameterTwin => die_screen && twin.is_some() && !chaos,
            When::NoChaosTwin => die_screen && !chaos,
            When::LessonCard => app.lesson.as_ref().is_some_and(|l| l.card && l.at.is_some()),
            When::HelpOpen => app.help_scroll().is_some(),
            When::OffMap => app.page != Page::Map,
        }
    }
}

/// Every panel, its place and when it is drawn, in the order they are drawn (later rows go
/// over earlier ones).
pub(crate) const PLACES: &[(Place, When, Panel)] = &[
    (Place::Whole, When::MapOpen, basin_map::render),
    (Place::Whole, When::Presenting, presentation::render),
    (Place::Header, When::DieScreen, header::render),
    (Place::Params, When::DieScreen, params_panel::render),
    (Place::Die, When::DieScreen, die::render),
    (Place::Timeline, When::DieScreen, timeline_strip::render),
    (Place::Outcomes, When::DieAlone, outcomes::render),
    (Place::Outcomes, When::ChaosTwin, predictability_curve::render),
    (Place::Outcomes, When::ParameterTwin, versus_table::render),
    (Place::Plot, When::NoChaosTwin, quantity_plot::render),
    (Place::Plot, When::ChaosTwin, separation::render),
    (Place::Ledger, When::DieScreen, ledger::render),
    (Place::Footer, When::DieScreen, footer::render),
    (Place::Whole, When::LessonCard, lesson_card::render),
    (Place::Whole, When::HelpOpen, help::render),
    (Place::Whole, When::OffMap, dialogs::render),
];
