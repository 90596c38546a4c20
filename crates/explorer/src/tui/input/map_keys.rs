//! What reaches the basin-map screen: its keys (rows of [`crate::tui::vocabulary::key_table::BINDINGS`]), the
//! maps the worker sends, the terminal's size. The screen's own rules live with its state
//! ([`MapView`]); this file only hands them the app's setup and terminal and sends the
//! requests they make.

use crate::tui::state::app::{App, Page};
use crate::tui::state::map_view::{MapView, Side};
use crate::tui::vocabulary::key_table::{Action, Input, Scope, label};
use crate::worker::{Command, MapRequest, MapUpdate};

/// Cells one Shift-arrow moves the cursor.
const BIG_STEP: usize = 8;

/// Asks the worker for `request`, if one was made.
fn send(app: &mut App, request: Option<MapRequest>) {
    if let Some(r) = request {
        app.send(Command::MapStart(r));
    }
}

/// Asks for a fresh map of the chosen axes, fitted to the terminal, around the setup.
fn start(app: &mut App) {
    let r = app.map.request(app.screen, &app.setup.params, &app.setup.initial);
    send(app, Some(r));
}

/// Switches to the map screen; computes the map unless the one there still fits the setup
/// and the terminal.
pub(crate) fn open(app: &mut App) {
    app.page = Page::Map;
    if !app
        .map
        .still_fits(app.screen, &app.setup.params, &app.setup.initial)
    {
        start(app);
    }
}

/// Back to the die. A map still being computed is cancelled so the live roll gets the cores;
/// coming back computes it again.
pub(crate) fn close(app: &mut App) -> Option<MapRequest> {
    app.page = Page::Die;
    if app.map.leave() {
        app.send(Command::MapCancel);
    }
    None
}

/// Takes a map from the worker (one of an older request is dropped).
pub(crate) fn absorb(app: &mut App, update: MapUpdate) {
    if let Err(e) = app.map.take(update) {
        app.notice = Some(format!("the map cannot be computed: {e}"));
    }
}

/// The terminal was resized: a map on screen is recomputed to fill the new panel.
pub(crate) fn resized(app: &mut App) {
    if app.page == Page::Map && app.map.stale(app.screen) {
        start(app);
    }
}

/// What a key of the map screen's table does (see [`crate::tui::vocabulary::key_table`]); `coarse` (Shift)
/// moves the cursor by [`BIG_STEP`] cells. A key that asks for another map (zoom, axis)
/// gets its request from the map's state and sends it once, here.
pub(crate) fn act(app: &mut App, action: Action, coarse: bool) {
    let step = if coarse { BIG_STEP } else { 1 } as isize;
    let big = BIG_STEP as isize;
    let (screen, params, initial) = (app.screen, app.setup.params, app.setup.initial);
    let m: &mut MapView = &mut app.map;
    let request = match action {
        Action::CursorLeft => cursor(m, -step, 0),
        Action::CursorRight => cursor(m, step, 0),
        Action::CursorUp => cursor(m, 0, step),
        Action::CursorDown => cursor(m, 0, -step),
        Action::CursorLeftBig => cursor(m, -big, 0),
        Action::CursorRightBig => cursor(m, big, 0),
        Action::CursorUpBig => cursor(m, 0, big),
        Action::CursorDownBig => cursor(m, 0, -big),
        Action::MapZoomIn => m.zoom_in(screen, &params, &initial),
        Action::MapZoomOut => {
            let r = m.zoom_out(screen, &params, &initial);
            if r.is_none() {
                app.notice = Some("already at the full range".to_string());
            }
            r
        }
        Action::NextXAxis => Some(m.next_axis(Side::X, screen, &params, &initial)),
        Action::NextYAxis => Some(m.next_axis(Side::Y, screen, &params, &initial)),
        Action::TypeXRange => m.edit_range(Side::X),
        Action::TypeYRange => m.edit_range(Side::Y),
        Action::MapLayer => m.next_layer(),
        Action::MapExportSize => {
            let ((w, h), what) = m.next_export_size();
            app.notice = Some(format!(
                "PNG size {w}×{h} ({what}) · {} exports, {} the next size",
                label(Scope::Map, Action::ExportMap),
                label(Scope::Map, Action::MapExportSize)
            ));
            None
        }
        Action::MapBack => close(app),
        Action::ReplayCell => replay(app),
        Action::ExportMap => export(app),
        _ => None,
    };
    send(app, request);
}

fn cursor(m: &mut MapView, dx: isize, dy: isize) -> Option<MapRequest> {
    m.move_cursor(dx, dy);
    None
}

/// Plays the cell under the cursor in the die view: exactly the setup the map rolled there.
fn replay(app: &mut App) -> Option<MapRequest> {
    match app.map.cell_setup() {
        Some((params, initial, cell)) => {
            let c = app.setup.play(params, initial);
            app.send(c);
            close(app);
            app.notice = Some(format!("replaying {cell}"));
        }
        None => app.notice = Some("no map yet: wait for the first cells".to_string()),
    }
    None
}

/// The export key: the map on screen written into the current folder (its cells and its
/// picture at the chosen size, by the worker's export job), or the running export cancelled.
fn export(app: &mut App) -> Option<MapRequest> {
    if app.roll.export.is_some() {
        app.send(Command::ExportCancel);
        return None;
    }
    match app.map.export() {
        Some(m) => app.send(Command::ExportMap(Box::new(m))),
        None => app.notice = Some("no map to export yet".to_string()),
    }
    None
}

/// A key typed into an axis's range editor.
pub(crate) fn on_range_key(app: &mut App, input: &Input) {
    let r = app
        .map
        .type_range(input, app.screen, &app.setup.params, &app.setup.initial);
    send(app, r);
}
