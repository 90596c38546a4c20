//! Where each panel of the main screen goes, which parameter row a screen position is, and
//! where the timeline's bar sits and which step a click on it means: shared by rendering
//! and by the mouse handling in `update`, so neither imports the other.

use crate::worker::TimelineSnapshot;
use ratatui::layout::{Constraint, Layout, Position, Rect};
use ratatui::widgets::Block;

/// The smallest terminal the explorer draws its panels in.
pub(crate) const MIN_WIDTH: u16 = 80;
pub(crate) const MIN_HEIGHT: u16 = 24;

/// Rows the outcome table keeps on the smallest screen, borders included.
const OUTCOME_ROWS: u16 = 11;

/// Where each panel goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Areas {
    pub(crate) header: Rect,
    pub(crate) params: Rect,
    pub(crate) outcomes: Rect,
    pub(crate) die: Rect,
    /// The timeline strip: the die panel's bottom border, between its corners.
    pub(crate) timeline: Rect,
    pub(crate) energy: Rect,
    /// The energy bar and ledger, beside the energy plot.
    pub(crate) ledger: Rect,
    pub(crate) footer: Rect,
}

/// The panel layout for a terminal of this size; `None` below [`MIN_WIDTH`]×[`MIN_HEIGHT`].
pub(crate) fn screen_layout(area: Rect) -> Option<Areas> {
    if area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        return None;
    }
    let [header, body, footer] = area.layout(&Layout::vertical([
        Constraint::Length(1),
        Constraint::Min(0),
        Constraint::Length(1),
    ]));
    let [left, right] = body.layout(&Layout::horizontal([
        Constraint::Length(left_width(area.width)),
        Constraint::Min(0),
    ]));
    // The paper's parameter rows when there is room (a loaded die's extra masses scroll
    // into view below them), and at least the table's rows a lesson reads: its six faces,
    // the fairness test and how many rolls show the bias (the list scrolls, the table can't).
    let params_height = (crate::tui::vocabulary::param::paper_rows() as u16 + 4)
        .min(body.height.saturating_sub(OUTCOME_ROWS));
    let [params, outcomes] = left.layout(&Layout::vertical([
        Constraint::Length(params_height),
        Constraint::Min(0),
    ]));
    let [die, energy_row] = right.layout(&Layout::vertical([
        Constraint::Percentage(50),
        Constraint::Percentage(50),
    ]));
    let timeline = Rect::new(
        die.x + 1,
        die.bottom().saturating_sub(1),
        die.width.saturating_sub(2),
        1,
    );
    let [energy, ledger] = energy_row.layout(&Layout::horizontal([
        Constraint::Min(0),
        Constraint::Length(ledger_width(area.width)),
    ]));
    Some(Areas {
        header,
        params,
        outcomes,
        die,
        timeline,
        energy,
        ledger,
        footer,
    })
}

/// Outer width of the left column (the parameters and the outcome table).
pub(crate) fn left_width(screen_width: u16) -> u16 {
    if screen_width >= 120 { 52 } else { 38 }
}

/// Inner area of a bordered panel.
pub(crate) fn inner(area: Rect) -> Rect {
    Block::bordered().inner(area)
}

/// How many parameter rows fit, and the first one shown (the selection stays in view).
pub(crate) fn param_window(selected: usize, params_area: Rect) -> (usize, usize) {
    let visible = inner(params_area).height.saturating_sub(2) as usize;
    let first = if visible > 0 && selected >= visible {
        selected + 1 - visible
    } else {
        0
    };
    (first, visible)
}

/// The parameter under a screen position, for mouse clicks and scrolls, on a list of `rows`.
pub(crate) fn param_row_at(selected: usize, rows: usize, areas: &Areas, at: Position) -> Option<usize> {
    let body = inner(areas.params);
    if !body.contains(at) || at.y < body.y + 1 {
        return None;
    }
    let (first, visible) = param_window(selected, areas.params);
    let row = (at.y - body.y - 1) as usize;
    (row < visible).then_some(first + row).filter(|&i| i < rows)
}

/// Outer width of the energy ledger panel: wide terminals get room for the unit, and from
/// 100 columns a six-digit loss keeps its label whole.
pub(crate) fn ledger_width(screen_width: u16) -> u16 {
    match screen_width {
        120.. => 24,
        100.. => 22,
        _ => 20,
    }
}

/// A time on the timeline strip: as many decimals as Δt has (at least the header's three),
/// so one step shows, and its unit.
pub(crate) fn strip_seconds(t_s: f64, dt: f64) -> String {
    let decimals = ((-dt.log10()).ceil().max(3.0)) as usize;
    format!("{t_s:.decimals$} s")
}

/// Columns of the timeline strip before its bar (`t 12.345 s `) and after it
/// (` end 12.345 s`), wide enough for the longest time of a roll of `max_time_s` at `dt`, so
/// neither label is cut (its unit included) and the bar stays put while the time grows.
pub(crate) fn timeline_margins(dt: f64, max_time_s: f64) -> (u16, u16) {
    let longest = strip_seconds(max_time_s, dt).chars().count() as u16;
    (longest + 4, longest + 6)
}

/// The timeline bar's columns inside its strip, given the strip's `margins`
/// ([`timeline_margins`]); `None` if the strip is too narrow for one.
pub(crate) fn timeline_bar(area: Rect, (left, right): (u16, u16)) -> Option<Rect> {
    let width = area.width.checked_sub(left + right).filter(|&w| w >= 8)?;
    Some(Rect::new(area.x + left, area.y, width, area.height.min(1)))
}

/// Steps the timeline bar spans: the whole roll once it has ended, else as far as it has got.
pub(crate) fn timeline_steps(t: &TimelineSnapshot) -> u64 {
    t.furthest.max(t.position).max(1)
}

/// The step a click on screen column `column` of the timeline bar `bar` asks for.
pub(crate) fn timeline_step_at(t: &TimelineSnapshot, bar: Rect, column: u16) -> u64 {
    let last = bar.width.saturating_sub(1).max(1) as u64;
    let x = column.saturating_sub(bar.x).min(bar.width.saturating_sub(1)) as u64;
    (x * timeline_steps(t) + last / 2) / last
}
