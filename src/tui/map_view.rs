//! The basin-map screen's state: its axes, zoom steps, cursor and range editor, and the
//! map on screen. Its keys are in [`super::map_keys`], its drawing in [`super::map`].

use super::editor::Editor;
use super::param::Param;
use crate::experiment::plot::SIZE;
use crate::experiment::registry;
use crate::experiment::{BasinMap, Layer};
use crate::physics::{InitialCondition, Params};
use crate::worker::{MapAxis, MapRequest, MapUpdate};
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

/// Which screen is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum View {
    #[default]
    Die,
    Map,
}

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

    /// The chosen size of the map's PNG, in pixels, and what it is for.
    pub(crate) fn png_size(&self) -> ((u32, u32), &'static str) {
        EXPORT_SIZES[self.export_size]
    }

    /// The map on screen, if one has arrived for the current request.
    pub(crate) fn map(&self) -> Option<&BasinMap> {
        self.shown.as_ref().and_then(|u| u.map.as_ref().ok())
    }

    pub(super) fn axis_mut(&mut self, side: Side) -> &mut MapAxis {
        match side {
            Side::X => &mut self.x,
            Side::Y => &mut self.y,
        }
    }

    pub(super) fn clamp_cursor(&mut self) {
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
/// velocity (±50 cm/s), a few coarse steps for the rest, inside the allowed range.
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
    let (lo, hi) = (p.nudged(now, -steps, true), p.nudged(now, steps, true));
    if lo < hi {
        (lo, hi)
    } else {
        let l = p.limits();
        (l.min, l.max)
    }
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
    super::layout::screen_layout(area)?;
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
