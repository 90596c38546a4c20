//! The basin-map screen's state: its axes, zoom steps, cursor and range editor, and the
//! map on screen, and the rules that change them (a request fitted to the terminal, the
//! zoom stack, the range editor). Keys reach it through the map screen's keys; the map
//! screen's panel draws it.

use super::editor::{Editor, Typed};
use crate::tui::vocabulary::format::fmt_num;
use crate::tui::vocabulary::key_table::Input;
use crate::tui::vocabulary::param::{Param, all};
use crate::worker::{MapAxis, MapExport, MapRequest, MapUpdate};
use dicesim_experiment::basin::{check_nodes, node_setup};
use dicesim_experiment::{Axis, BasinMap, Layer};
use dicesim_figures::plot::SIZE;
use dicesim_physics::{InitialCondition, Params, check_setup};
use dicesim_setup::registry;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::widgets::Block;

/// Most cells along each axis: a 200×100 map takes about half a second on two cores, so
/// a full panel stays near a second even where borders are long.
pub(crate) const MAX_CELLS: (usize, usize) = (200, 100);
/// Grid nodes while the terminal is too small to show the map.
pub(crate) const FALLBACK_CELLS: (usize, usize) = (64, 48);
/// Each zoom shows a quarter of the range on each axis.
pub(crate) const ZOOM_FACTOR: f64 = 4.0;
/// Characters for the y-axis labels.
pub(crate) const Y_LABELS: u16 = 8;

/// The map's x or y axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    X,
    Y,
}

/// The ranges before a zoom, to go back out to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ZoomStep {
    pub(crate) x: (f64, f64),
    pub(crate) y: (f64, f64),
    pub(crate) cursor: (usize, usize),
}

/// A range being typed in for one axis.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RangeEditor {
    pub(crate) side: Side,
    pub(crate) editor: Editor,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MapView {
    /// The axes the user chose (their `cells` are set when a map is requested).
    pub(crate) x: MapAxis,
    pub(crate) y: MapAxis,
    /// Ranges before each zoom, innermost last.
    pub(crate) zooms: Vec<ZoomStep>,
    /// The generation of the current request; updates of any other are stale.
    pub(crate) generation: u64,
    /// The setup and grid of the current request.
    pub(crate) requested: Option<(MapRequest, Params, InitialCondition)>,
    /// Whether the worker is still computing the current request.
    pub(crate) running: bool,
    /// The newest map of the current generation.
    pub(crate) shown: Option<MapUpdate>,
    /// Cell under the cursor: x node, y node (0 = bottom row).
    pub(crate) cursor: (usize, usize),
    pub(crate) layer: Layer,
    pub(crate) editing: Option<RangeEditor>,
    /// Which of [`EXPORT_SIZES`] the image is written at.
    pub(crate) export_size: usize,
    /// The preset's view asks for the map screen: opened by the first `update`, once the
    /// event loop has told the app its terminal size.
    pub(crate) open_asked: bool,
}

/// The sizes of the map's PNG (`E` picks one, `e` writes it), each with what it is for; all
/// 3:2, the shape the image is designed at, its text scaled with its height.
pub(crate) const EXPORT_SIZES: [((u32, u32), &str); 4] = [
    (SIZE, "screen"),
    ((1920, 1280), "slide"),
    ((3000, 2000), "print"),
    ((6000, 4000), "poster"),
];

impl MapView {
    /// Spin about x against spin about y, each over the preset's default random range
    /// around its current value.
    pub(crate) fn new(params: &Params, initial: &InitialCondition) -> MapView {
        let axis = |param| {
            let (min, max) = default_range(param, params, initial);
            MapAxis {
                key: param.scan_key(),
                min,
                max,
                cells: 0,
            }
        };
        MapView {
            x: axis(Param::named("initial.angular_velocity.x")),
            y: axis(Param::named("initial.angular_velocity.y")),
            zooms: Vec::new(),
            generation: 0,
            requested: None,
            running: false,
            shown: None,
            cursor: (0, 0),
            layer: Layer::Face,
            editing: None,
            export_size: 0,
            open_asked: false,
        }
    }

    /// Another preset opened: the default axes around its own values, no zoom and no map
    /// yet (a map of the old preset's ranges would answer a question nobody asked); the
    /// layer and the PNG size stay, being the user's choice rather than the setup's.
    /// Updates of a map still computing for the old preset are dropped.
    pub(crate) fn reopen(&mut self, params: &Params, initial: &InitialCondition) {
        *self = MapView {
            generation: self.generation + 1,
            layer: self.layer,
            export_size: self.export_size,
            open_asked: self.open_asked,
            ..MapView::new(params, initial)
        };
    }

    /// The chosen size of the map's PNG, in pixels, and what it is for.
    pub(crate) fn png_size(&self) -> ((u32, u32), &'static str) {
        EXPORT_SIZES[self.export_size]
    }

    /// The map on screen, if one has arrived for the current request.
    pub(crate) fn map(&self) -> Option<&BasinMap> {
        self.shown.as_ref().and_then(|u| u.map.as_ref().ok())
    }

    fn axis_mut(&mut self, side: Side) -> &mut MapAxis {
        match side {
            Side::X => &mut self.x,
            Side::Y => &mut self.y,
        }
    }

    /// A new map of the chosen axes at the resolution that fits `screen`, around this
    /// setup: the request to send (older maps' updates are dropped from now on).
    pub(crate) fn request(
        &mut self,
        screen: Rect,
        params: &Params,
        initial: &InitialCondition,
    ) -> MapRequest {
        let (nx, ny) = fitted_cells(screen);
        if self.requested.is_none() {
            // The first map opens with the cursor in the middle.
            self.cursor = (nx / 2, ny / 2);
        }
        self.generation += 1;
        self.x.cells = nx;
        self.y.cells = ny;
        let request = MapRequest {
            generation: self.generation,
            x: self.x,
            y: self.y,
        };
        self.requested = Some((request, *params, *initial));
        self.running = true;
        self.shown = None;
        self.clamp_cursor();
        request
    }

    /// Whether the map there still serves: requested for this setup and this terminal,
    /// and computing or complete.
    pub(crate) fn still_fits(&self, screen: Rect, params: &Params, initial: &InitialCondition) -> bool {
        let fits = self.requested.as_ref().is_some_and(|(r, p, ic)| {
            (r.x.cells, r.y.cells) == fitted_cells(screen) && p == params && ic == initial
        });
        fits && (self.running || self.map().is_some_and(|m| m.complete))
    }

    /// Whether a map was requested for another terminal size than `screen`.
    pub(crate) fn stale(&self, screen: Rect) -> bool {
        self.requested
            .as_ref()
            .is_some_and(|(r, ..)| (r.x.cells, r.y.cells) != fitted_cells(screen))
    }

    /// Leaving the screen: the range editor closes; true if a map was still computing
    /// (the caller cancels it, so the live roll gets the cores).
    pub(crate) fn leave(&mut self) -> bool {
        self.editing = None;
        std::mem::take(&mut self.running)
    }

    /// Takes a map from the worker, unless it belongs to a request the user has moved away
    /// from; why it could not be computed, if so.
    pub(crate) fn take(&mut self, update: MapUpdate) -> Result<(), String> {
        if update.generation != self.generation || !self.running {
            return Ok(());
        }
        match &update.map {
            Ok(map) => {
                self.running = !map.complete;
                self.shown = Some(update);
                self.clamp_cursor();
                Ok(())
            }
            Err(e) => {
                self.running = false;
                Err(e.clone())
            }
        }
    }

    /// Moves the cursor by whole cells, inside the map.
    pub(crate) fn move_cursor(&mut self, dx: isize, dy: isize) {
        let (i, j) = self.cursor;
        self.cursor = (i.saturating_add_signed(dx), j.saturating_add_signed(dy));
        self.clamp_cursor();
    }

    /// Shrinks both ranges by [`ZOOM_FACTOR`] around the cursor (kept inside the old
    /// ranges) and asks for that map, the cursor in its middle; `None` before any map.
    pub(crate) fn zoom_in(
        &mut self,
        screen: Rect,
        params: &Params,
        initial: &InitialCondition,
    ) -> Option<MapRequest> {
        let map = self.map()?;
        let (i, j) = self.cursor;
        let inside = |a: &Axis, at: f64| {
            let half = (a.max - a.min) / ZOOM_FACTOR / 2.0;
            let centre = at.clamp(a.min + half, a.max - half);
            (centre - half, centre + half)
        };
        let (x, y) = (inside(&map.x, map.x.value(i)), inside(&map.y, map.y.value(j)));
        self.zooms.push(ZoomStep {
            x: (self.x.min, self.x.max),
            y: (self.y.min, self.y.max),
            cursor: self.cursor,
        });
        (self.x.min, self.x.max) = x;
        (self.y.min, self.y.max) = y;
        let r = self.request(screen, params, initial);
        self.cursor = (r.x.cells / 2, r.y.cells / 2);
        Some(r)
    }

    /// Back to the ranges before the last zoom; `None` at the full range.
    pub(crate) fn zoom_out(
        &mut self,
        screen: Rect,
        params: &Params,
        initial: &InitialCondition,
    ) -> Option<MapRequest> {
        let z = self.zooms.pop()?;
        (self.x.min, self.x.max) = z.x;
        (self.y.min, self.y.max) = z.y;
        self.cursor = z.cursor;
        Some(self.request(screen, params, initial))
    }

    /// The next value of the parameter list on this axis (never the other axis's), over
    /// its default range, and its map.
    pub(crate) fn next_axis(
        &mut self,
        side: Side,
        screen: Rect,
        params: &Params,
        initial: &InitialCondition,
    ) -> MapRequest {
        let other = match side {
            Side::X => Param::of(self.y.key),
            Side::Y => Param::of(self.x.key),
        };
        let now = Param::of(self.axis_mut(side).key);
        let list = all();
        let at = list.iter().position(|&p| p == now).unwrap_or(0);
        let next = (1..list.len())
            .map(|k| list[(at + k) % list.len()])
            .find(|&p| p != other)
            .unwrap_or(now);
        let (min, max) = default_range(next, params, initial);
        *self.axis_mut(side) = MapAxis {
            key: next.scan_key(),
            min,
            max,
            cells: 0,
        };
        self.zooms.clear();
        self.request(screen, params, initial)
    }

    /// Opens the range editor of one axis on its range now (its map comes on Enter).
    pub(crate) fn edit_range(&mut self, side: Side) -> Option<MapRequest> {
        let a = *self.axis_mut(side);
        self.editing = Some(RangeEditor {
            side,
            editor: Editor {
                text: format!("{} {}", fmt_num(a.min), fmt_num(a.max)),
                error: None,
            },
        });
        None
    }

    /// A key typed into the range editor; on Enter a valid range replaces the axis's and
    /// its map is asked for (a refused one says why in the editor).
    pub(crate) fn type_range(
        &mut self,
        input: &Input,
        screen: Rect,
        params: &Params,
        initial: &InitialCondition,
    ) -> Option<MapRequest> {
        let r = self.editing.as_mut()?;
        match r.editor.input(input, RANGE_CHARS) {
            Typed::Cancelled => self.editing = None,
            Typed::Editing => {}
            // Two numbers, not one: the text is read as a range.
            Typed::Submitted(_) => {
                let side = r.side;
                let param = match side {
                    Side::X => Param::of(self.x.key),
                    Side::Y => Param::of(self.y.key),
                };
                let (mut x, mut y) = (self.x, self.y);
                let parsed = parse_range(param, &r.editor.text).and_then(|(min, max)| {
                    let a = match side {
                        Side::X => &mut x,
                        Side::Y => &mut y,
                    };
                    (a.min, a.max) = (min, max);
                    check_map(&x, &y, fitted_cells(screen), params, initial)
                });
                // Re-borrowed: the check above read the other axis.
                let r = self.editing.as_mut()?;
                match parsed {
                    Ok(()) => {
                        (self.x, self.y) = (x, y);
                        self.editing = None;
                        self.zooms.clear();
                        return Some(self.request(screen, params, initial));
                    }
                    Err(e) => r.editor.error = Some(e),
                }
            }
        }
        None
    }

    /// The other layer (face up, settle time): the same map, drawn otherwise.
    pub(crate) fn next_layer(&mut self) -> Option<MapRequest> {
        self.layer = match self.layer {
            Layer::Face => Layer::SettleTime,
            Layer::SettleTime => Layer::Face,
        };
        None
    }

    /// The next of [`EXPORT_SIZES`] (after the last, the first).
    pub(crate) fn next_export_size(&mut self) -> ((u32, u32), &'static str) {
        self.export_size = (self.export_size + 1) % EXPORT_SIZES.len();
        self.png_size()
    }

    /// The exact setup the map rolled under the cursor, and the words that say which cell.
    pub(crate) fn cell_setup(&self) -> Option<(Params, InitialCondition, String)> {
        let update = self.shown.as_ref()?;
        let map = update.map.as_ref().ok()?;
        let (i, j) = self.cursor;
        let (params, initial) = node_setup(&update.params, &update.initial, &map.x, &map.y, i, j);
        let words = format!(
            "map cell ({i}, {j}): {} {}, {} {}",
            Param::of(self.x.key).label(),
            fmt_num(map.x.value(i)),
            Param::of(self.y.key).label(),
            fmt_num(map.y.value(j)),
        );
        Some((params, initial, words))
    }

    /// The map on screen as an export: its cells, its setup, the layer and size chosen,
    /// into the current folder; `None` before any map.
    pub(crate) fn export(&self) -> Option<MapExport> {
        let update = self.shown.as_ref()?;
        let map = update.map.as_ref().ok()?;
        Some(MapExport {
            dir: ".".into(),
            map: map.clone(),
            params: update.params,
            initial: update.initial,
            layer: self.layer,
            size: self.png_size().0,
        })
    }

    fn clamp_cursor(&mut self) {
        let (w, h) = match (self.map(), &self.requested) {
            (Some(m), _) => (m.width(), m.height()),
            (None, Some((r, ..))) => (r.x.cells, r.y.cells),
            (None, None) => return,
        };
        self.cursor = (
            self.cursor.0.min(w.saturating_sub(1)),
            self.cursor.1.min(h.saturating_sub(1)),
        );
    }
}

/// A range around the current value: the default random range for spin (±60 rad/s) and
/// velocity (±50 cm/s), a few coarse steps for the rest, inside the allowed range, and each
/// end a setup that can be rolled ([`check_setup`]): where a coarse step would make a body
/// that cannot exist (a corner radius of 1 on a half size of 1), the end comes in to a fine
/// step, and to the current value itself if that too is refused.
pub(crate) fn default_range(p: Param, params: &Params, initial: &InitialCondition) -> (f64, f64) {
    let row = p.scan_key().spec;
    let steps = if *row == registry::ANGULAR_VELOCITY {
        6
    } else if *row == registry::HEIGHT {
        2
    } else {
        1
    };
    let now = p.get(params, initial);
    let rolls = |v: f64| {
        let (mut pp, mut ic) = (*params, *initial);
        p.scan_key().set(&mut pp, &mut ic, v);
        check_setup(&pp, &ic).is_ok()
    };
    let end = |sign: i32| {
        [
            p.nudged(now, sign * steps, true),
            p.nudged(now, sign, true),
            p.nudged(now, sign, false),
        ]
        .into_iter()
        .find(|&v| rolls(v))
        .unwrap_or(now)
    };
    let (lo, hi) = (end(-1), end(1));
    if lo < hi {
        (lo, hi)
    } else {
        let l = p.limits();
        (l.min, l.max)
    }
}

/// Whether a map of axes `x` and `y` on a grid of `cells` can be rolled around this setup:
/// every node's setup passes the check `roll` makes of its own (the worker's map makes it
/// again), or the first node refused, in its words.
fn check_map(
    x: &MapAxis,
    y: &MapAxis,
    (nx, ny): (usize, usize),
    params: &Params,
    initial: &InitialCondition,
) -> Result<(), String> {
    let axis = |a: &MapAxis, cells| MapAxis { cells, ..*a }.axis().map_err(|e| e.to_string());
    check_nodes(params, initial, &axis(x, nx)?, &axis(y, ny)?).map_err(|e| e.to_string())
}

/// Panels of the map screen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct MapAreas {
    pub(crate) header: Rect,
    pub(crate) side: Rect,
    pub(crate) panel: Rect,
    /// Where the cells go: each character holds two cells, one above the other.
    pub(crate) grid: Rect,
    pub(crate) footer: Rect,
}

/// The map screen's layout; `None` below the explorer's minimum size.
pub(crate) fn map_layout(area: Rect) -> Option<MapAreas> {
    crate::tui::vocabulary::layout::screen_layout(area)?;
    let [header, body, footer] = area.layout(&Layout::vertical([
        Constraint::Length(1),
        Constraint::Min(0),
        Constraint::Length(1),
    ]));
    let side_width = if area.width >= 120 { 46 } else { 34 };
    let [side, panel] = body.layout(&Layout::horizontal([
        Constraint::Length(side_width),
        Constraint::Min(0),
    ]));
    let inner = Block::bordered().inner(panel);
    let grid = Rect {
        x: inner.x + Y_LABELS,
        width: inner.width.saturating_sub(Y_LABELS),
        height: inner.height.saturating_sub(1),
        ..inner
    };
    Some(MapAreas {
        header,
        side,
        panel,
        grid,
        footer,
    })
}

/// Grid nodes that fill the map panel of a terminal this size, two per character row.
pub(crate) fn fitted_cells(screen: Rect) -> (usize, usize) {
    match map_layout(screen) {
        Some(a) if a.grid.width >= 2 && a.grid.height >= 1 => (
            (a.grid.width as usize).min(MAX_CELLS.0),
            (2 * a.grid.height as usize).min(MAX_CELLS.1),
        ),
        _ => FALLBACK_CELLS,
    }
}

/// Characters a typed range may hold: two numbers and what separates them.
const RANGE_CHARS: usize = 40;

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
            dicesim_experiment::Error::Axis { message, .. } => message,
            e => e.to_string(),
        })
}
