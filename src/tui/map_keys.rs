//! The basin-map screen's keys: moving the cursor, zooming, choosing axes and ranges,
//! and the footer and help rows that name them.

use super::app::{App, Editor};
use super::format::fmt_num;
use super::map::{RangeEditor, Side, ZOOM_FACTOR, ZoomStep, close, default_range, start};
use super::param::{Param, all};
use crate::experiment::basin::node_setup;
use crate::experiment::{Axis, Layer};
use crate::worker::{Command, MapAxis};
use ratatui::Frame;
use ratatui::crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::layout::Rect;

/// Cells one Shift-arrow moves the cursor.
const BIG_STEP: usize = 8;

/// Keys of the map screen; false for the keys the explorer handles the same on every
/// screen (quit and help).
pub(crate) fn on_key(app: &mut App, key: KeyEvent, out: &mut Vec<Command>) -> bool {
    if app.map.editing.is_some() {
        on_range_key(app, key, out);
        return true;
    }
    let big = key.modifiers.contains(KeyModifiers::SHIFT);
    let step = if big { BIG_STEP } else { 1 };
    match key.code {
        KeyCode::Char('q') | KeyCode::Esc | KeyCode::Char('?') => return false,
        KeyCode::Tab | KeyCode::BackTab | KeyCode::Char('1') => close(app, out),
        KeyCode::Left | KeyCode::Char('h') => move_cursor(app, -(step as isize), 0),
        KeyCode::Right | KeyCode::Char('l') => move_cursor(app, step as isize, 0),
        KeyCode::Up | KeyCode::Char('k') => move_cursor(app, 0, step as isize),
        KeyCode::Down | KeyCode::Char('j') => move_cursor(app, 0, -(step as isize)),
        KeyCode::Char('H') => move_cursor(app, -(BIG_STEP as isize), 0),
        KeyCode::Char('L') => move_cursor(app, BIG_STEP as isize, 0),
        KeyCode::Char('K') => move_cursor(app, 0, BIG_STEP as isize),
        KeyCode::Char('J') => move_cursor(app, 0, -(BIG_STEP as isize)),
        KeyCode::Enter => replay(app, out),
        KeyCode::Char('z') => zoom_in(app, out),
        KeyCode::Char('Z') | KeyCode::Backspace => zoom_out(app, out),
        KeyCode::Char('x') => next_axis(app, Side::X, out),
        KeyCode::Char('y') => next_axis(app, Side::Y, out),
        KeyCode::Char('X') => edit_range(app, Side::X),
        KeyCode::Char('Y') => edit_range(app, Side::Y),
        KeyCode::Char('v') => {
            app.map.layer = match app.map.layer {
                Layer::Face => Layer::SettleTime,
                Layer::SettleTime => Layer::Face,
            }
        }
        KeyCode::Char('e') => app.map.export_asked = true,
        _ => {}
    }
    true
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
    app.send(out, Command::PlaySetup(params, initial));
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

fn on_range_key(app: &mut App, key: KeyEvent, out: &mut Vec<Command>) {
    let Some(r) = app.map.editing.as_mut() else {
        return;
    };
    match key.code {
        KeyCode::Esc => app.map.editing = None,
        KeyCode::Backspace => {
            r.editor.text.pop();
            r.editor.error = None;
        }
        KeyCode::Char(c) if c.is_ascii_digit() || ".-+eE :,".contains(c) => {
            if r.editor.text.len() < 40 {
                r.editor.text.push(c);
            }
            r.editor.error = None;
        }
        KeyCode::Enter => {
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
        _ => {}
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

pub(crate) fn render_footer(app: &App, area: Rect, frame: &mut Frame) {
    let keys = if app.map.editing.is_some() {
        super::footer::typing_hints("MIN MAX")
    } else if app.help {
        super::footer::help_hints()
    } else {
        vec![
            ("Tab", "die", 0),
            ("←↓↑→", "cursor", 1),
            ("Enter", "replay", 1),
            ("z Z", "zoom in/out", 1),
            ("x y", "axis", 2),
            ("X Y", "range", 2),
            ("v", "face/time", 3),
            ("e", "export PNG", 3),
            ("?", "help", 0),
            ("q", "quit", 0),
        ]
    };
    super::footer::render_key_hints(app, keys, area, frame);
}

/// The map screen's keys, for the `?` overlay.
pub(crate) const MAP_KEYS: &[(&str, &str)] = &[
    ("Tab 2 / Tab 1", "basin-map screen / back to the die"),
    (
        "←↓↑→ h j k l",
        "move the cursor over the map (Shift or H J K L: 8 cells)",
    ),
    ("Enter", "replay the cell under the cursor in the die view"),
    ("z  Z", "zoom in ×4 around the cursor / back out"),
    ("x  y", "next value of the list on the x / y axis"),
    ("X  Y", "type the x / y range as MIN MAX"),
    ("v", "colour by face up / by settle time (borders light up)"),
    ("e", "save the map as a PNG in the current folder"),
];
