//! What the basin-map screen's keys do: moving the cursor, zooming, choosing axes and
//! ranges (the keys themselves are rows of [`super::keys::BINDINGS`]).

use super::app::{App, Editor, Effect, Typed};
use super::format::fmt_num;
use super::keys::{Action, Input};
use super::map::{close, start};
use super::map_view::{EXPORT_SIZES, RangeEditor, Side, ZOOM_FACTOR, ZoomStep, default_range};
use super::param::{Param, all};
use crate::experiment::basin::node_setup;
use crate::experiment::{Axis, Layer};
use crate::worker::{Command, MapAxis};

/// Cells one Shift-arrow moves the cursor.
const BIG_STEP: usize = 8;

/// What a key of the map screen's table does (see [`super::keys`]); `coarse` (Shift)
/// moves the cursor by [`BIG_STEP`] cells.
pub(crate) fn act(app: &mut App, action: Action, coarse: bool, out: &mut Vec<Command>) {
    let step = if coarse { BIG_STEP } else { 1 } as isize;
    let big = BIG_STEP as isize;
    match action {
        Action::MapBack => close(app, out),
        Action::CursorLeft => move_cursor(app, -step, 0),
        Action::CursorRight => move_cursor(app, step, 0),
        Action::CursorUp => move_cursor(app, 0, step),
        Action::CursorDown => move_cursor(app, 0, -step),
        Action::CursorLeftBig => move_cursor(app, -big, 0),
        Action::CursorRightBig => move_cursor(app, big, 0),
        Action::CursorUpBig => move_cursor(app, 0, big),
        Action::CursorDownBig => move_cursor(app, 0, -big),
        Action::ReplayCell => replay(app, out),
        Action::MapZoomIn => zoom_in(app, out),
        Action::MapZoomOut => zoom_out(app, out),
        Action::NextXAxis => next_axis(app, Side::X, out),
        Action::NextYAxis => next_axis(app, Side::Y, out),
        Action::TypeXRange => edit_range(app, Side::X),
        Action::TypeYRange => edit_range(app, Side::Y),
        Action::MapLayer => {
            app.map.layer = match app.map.layer {
                Layer::Face => Layer::SettleTime,
                Layer::SettleTime => Layer::Face,
            }
        }
        Action::ExportMap => {
            app.map.export_asked = true;
            app.ask(Effect::ExportMap);
        }
        Action::MapExportSize => {
            let m = &mut app.map;
            m.export_size = (m.export_size + 1) % EXPORT_SIZES.len();
            let ((w, h), what) = m.png_size();
            app.notice = Some(format!("PNG size {w}×{h} ({what}) · e exports, E the next size"));
        }
        _ => {}
    }
}

fn move_cursor(app: &mut App, dx: isize, dy: isize) {
    let m = &mut app.map;
    let (i, j) = m.cursor;
    m.cursor = (i.saturating_add_signed(dx), j.saturating_add_signed(dy));
    m.clamp_cursor();
}

/// Plays the cell under the cursor in the die view: exactly the setup the map rolled there.
fn replay(app: &mut App, out: &mut Vec<Command>) {
    let Some(update) = &app.map.shown else {
        app.notice = Some("no map yet: wait for the first cells".to_string());
        return;
    };
    let Ok(map) = &update.map else { return };
    let (i, j) = app.map.cursor;
    let (params, initial) = node_setup(&update.params, &update.initial, &map.x, &map.y, i, j);
    let notice = format!(
        "replaying map cell ({i}, {j}): {} {}, {} {}",
        Param::of(app.map.x.key).label(),
        fmt_num(map.x.value(i)),
        Param::of(app.map.y.key).label(),
        fmt_num(map.y.value(j)),
    );
    app.params = params;
    app.initial = initial;
    app.send(out, Command::PlaySetup(Box::new(params), initial));
    close(app, out);
    app.notice = Some(notice);
}

/// Shrinks both ranges by [`ZOOM_FACTOR`] around the cursor (kept inside the old ranges).
fn zoom_in(app: &mut App, out: &mut Vec<Command>) {
    let Some(map) = app.map.map() else { return };
    let (i, j) = app.map.cursor;
    let inside = |a: &Axis, at: f64| {
        let half = (a.max - a.min) / ZOOM_FACTOR / 2.0;
        let centre = at.clamp(a.min + half, a.max - half);
        (centre - half, centre + half)
    };
    let (x, y) = (inside(&map.x, map.x.value(i)), inside(&map.y, map.y.value(j)));
    let m = &mut app.map;
    m.zooms.push(ZoomStep {
        x: (m.x.min, m.x.max),
        y: (m.y.min, m.y.max),
        cursor: m.cursor,
    });
    (m.x.min, m.x.max) = x;
    (m.y.min, m.y.max) = y;
    start(app, out);
    let r = &app.map.requested.as_ref().expect("just requested").0;
    app.map.cursor = (r.x.cells / 2, r.y.cells / 2);
}

fn zoom_out(app: &mut App, out: &mut Vec<Command>) {
    let Some(z) = app.map.zooms.pop() else {
        app.notice = Some("already at the full range".to_string());
        return;
    };
    let m = &mut app.map;
    (m.x.min, m.x.max) = z.x;
    (m.y.min, m.y.max) = z.y;
    m.cursor = z.cursor;
    start(app, out);
}

/// The next value of the parameter list on this axis (never the other axis's), over its
/// default range.
fn next_axis(app: &mut App, side: Side, out: &mut Vec<Command>) {
    let other = match side {
        Side::X => Param::of(app.map.y.key),
        Side::Y => Param::of(app.map.x.key),
    };
    let now = Param::of(app.map.axis_mut(side).key);
    let at = all().iter().position(|&p| p == now).unwrap_or(0);
    let next = (1..all().len())
        .map(|k| all()[(at + k) % all().len()])
        .find(|&p| p != other)
        .unwrap_or(now);
    let (min, max) = default_range(next, &app.params, &app.initial);
    *app.map.axis_mut(side) = MapAxis {
        key: next.scan_key(),
        min,
        max,
        cells: 0,
    };
    app.map.zooms.clear();
    start(app, out);
}

fn edit_range(app: &mut App, side: Side) {
    let a = *app.map.axis_mut(side);
    app.map.editing = Some(RangeEditor {
        side,
        editor: Editor {
            text: format!("{} {}", fmt_num(a.min), fmt_num(a.max)),
            error: None,
        },
    });
}

/// Characters a typed range may hold: two numbers and what separates them.
const RANGE_CHARS: usize = 40;

pub(crate) fn on_range_key(app: &mut App, input: &Input, out: &mut Vec<Command>) {
    let Some(r) = app.map.editing.as_mut() else {
        return;
    };
    match r.editor.input(input, RANGE_CHARS) {
        Typed::Cancelled => app.map.editing = None,
        Typed::Editing => {}
        // Two numbers, not one: the text is read as a range.
        Typed::Submitted(_) => {
            let side = r.side;
            let param = match side {
                Side::X => Param::of(app.map.x.key),
                Side::Y => Param::of(app.map.y.key),
            };
            match parse_range(param, &r.editor.text) {
                Ok((min, max)) => {
                    let a = app.map.axis_mut(side);
                    (a.min, a.max) = (min, max);
                    app.map.editing = None;
                    app.map.zooms.clear();
                    start(app, out);
                }
                Err(e) => r.editor.error = Some(e),
            }
        }
    }
}

/// `MIN MAX` (or `MIN:MAX`, `MIN,MAX`), checked as a map axis is: both inside the value's
/// allowed range, MIN below MAX.
pub(crate) fn parse_range(param: Param, text: &str) -> Result<(f64, f64), String> {
    let parts: Vec<&str> = text
        .split(|c: char| c.is_whitespace() || c == ':' || c == ',')
        .filter(|s| !s.is_empty())
        .collect();
    let [min, max] = parts[..] else {
        return Err("type MIN MAX, e.g. -60 60".to_string());
    };
    let number = |s: &str| s.parse::<f64>().map_err(|_| format!("`{s}` is not a number"));
    let (min, max) = (number(min)?, number(max)?);
    Axis::new(param.scan_key().clone(), min, max, 2)
        .map(|a| (a.min, a.max))
        .map_err(|e| match e {
            crate::experiment::Error::Axis { message, .. } => message,
            e => e.to_string(),
        })
}
