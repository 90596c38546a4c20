//! The basin-map screen drawn: which face each start in a plane of two setup values ends
//! on, while the worker computes it, with the cursor's cell read out and the legend.
//!
//! Its state and rules (cursor, zoom stack, axes, the generation that keeps a map the user
//! has moved away from off the screen) are the state's [`MapView`](crate::tui::state::map_view::MapView).

use crate::tui::panels::{footer, header, too_small};
use crate::tui::state::app::App;
use crate::tui::state::map_view::{MapAreas, Side, Y_LABELS, ZOOM_FACTOR, map_layout};
use crate::tui::vocabulary::format::fmt_num;
use crate::tui::vocabulary::key_table::{Action, Scope, first_key, label};
use crate::tui::vocabulary::param::Param;
use crate::worker::MapAxis;
use dicesim_experiment::basin::node_setup;
use dicesim_experiment::ending::Ending;
use dicesim_experiment::{BasinMap, Cell, Layer};
use dicesim_figures::plot::{INFERRED_WORDS, cell_colour, time_range};
use dicesim_physics::Status;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

/// The terminal colour of a cell: the exported image's colour, or nothing without colour.
pub(crate) fn terminal_colour(app: &App, cell: Option<&Cell>, times: Option<(f64, f64)>) -> Color {
    match cell {
        Some(_) if app.theme.colour => {
            let c = cell_colour(app.setup.params.die.face_numbers(), cell, app.map.layer, times);
            Color::Rgb(c.0, c.1, c.2)
        }
        _ => Color::Reset,
    }
}

/// Without colour a character shows its upper cell: the face digit, or a shade of settle
/// time (`~` where the time was filled in, not rolled).
fn monochrome_symbol(layer: Layer, cell: Option<&Cell>, times: Option<(f64, f64)>) -> char {
    let Some(c) = cell else { return ' ' };
    match (c.outcome.status, c.outcome.face, layer) {
        (Status::Timeout, ..) => '?',
        (Status::Unstable, ..) => '!',
        (Status::Settled, _, Layer::SettleTime) if !c.sampled => '~',
        (Status::Settled, None, _) => '·',
        (Status::Settled, Some(f), Layer::Face) => char::from(b'0' + f),
        (Status::Settled, Some(_), Layer::SettleTime) => {
            let (lo, hi) = times.unwrap_or((0.0, 1.0));
            let t = ((c.outcome.time_s - lo) / (hi - lo).max(1e-12)).clamp(0.0, 1.0);
            [' ', '░', '▒', '▓', '█'][(t * 4.0).round() as usize]
        }
    }
}

/// Draws the map screen.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let Some(areas) = map_layout(area) else {
        too_small::render(app, area, frame);
        return;
    };
    header::render(app, areas.header, frame);
    render_side(app, areas.side, frame);
    render_panel(app, &areas, frame);
    footer::render(app, areas.footer, frame);
}

fn layer_name(layer: Layer) -> &'static str {
    match layer {
        Layer::Face => "face up",
        Layer::SettleTime => "settle time",
    }
}

fn render_panel(app: &App, areas: &MapAreas, frame: &mut Frame) {
    let t = &app.theme;
    let m = &app.map;
    // The axes in the parameter list's words, as the exported picture names them.
    let y_title = format!(" ↑ y: {} ", m.y.key.title());
    let x_title = format!(" x: {} → ", m.x.key.title());
    let layer = Span::styled(format!(" {} ", layer_name(m.layer)), t.heading());
    // Narrow panels drop the layer's name (the legend says it) before the axis key.
    let fits = layer.width() + y_title.chars().count() + 2 <= areas.panel.width as usize;
    let title = if fits {
        Line::from(vec![layer, Span::raw(y_title)])
    } else {
        Line::from(y_title)
    };
    let block = Block::bordered()
        .title(title)
        .title_bottom(Line::from(x_title).right_aligned());
    let inner = block.inner(areas.panel);
    frame.render_widget(block, areas.panel);
    let grid = areas.grid;
    let Some(map) = m.map() else {
        let text = if m.running {
            "computing the first cells…".to_string()
        } else {
            format!(
                "no map: {} back to the die, or {} / {} to choose axes",
                label(Scope::Map, Action::MapBack),
                label(Scope::Map, Action::NextXAxis),
                label(Scope::Map, Action::NextYAxis)
            )
        };
        frame.render_widget(Paragraph::new(text).wrap(Wrap { trim: true }), grid);
        return;
    };
    if grid.width == 0 || grid.height == 0 {
        return;
    }
    draw_cells(app, map, grid, frame);
    draw_labels(app, map, inner, grid, frame);
}

/// Character columns and rows the map takes in `grid`: a cell a column, two cells a row.
fn grid_size(map: &BasinMap, grid: Rect) -> (u16, u16) {
    let cols = (map.width() as u16).min(grid.width);
    let rows = (map.height().div_ceil(2) as u16).min(grid.height);
    (cols, rows)
}

/// The map's cells, two to a character (upper and lower half), the cursor's marked.
fn draw_cells(app: &App, map: &BasinMap, grid: Rect, frame: &mut Frame) {
    let m = &app.map;
    let times = time_range(map);
    let h = map.height();
    let (cols, rows) = grid_size(map, grid);
    // Character row r (from the top) holds cells j = h-1-2r (upper half) and h-2-2r (lower).
    let cell_at = |i: usize, j: isize| (j >= 0).then(|| map.cell(i, j as usize)).flatten();
    let buf = frame.buffer_mut();
    for r in 0..rows {
        let upper = h as isize - 1 - 2 * r as isize;
        for c in 0..cols {
            let i = c as usize;
            let (top, bottom) = (cell_at(i, upper), cell_at(i, upper - 1));
            let cursor_here =
                m.cursor.0 == i && (m.cursor.1 as isize == upper || m.cursor.1 as isize == upper - 1);
            let cell = &mut buf[(grid.x + c, grid.y + r)];
            if app.theme.colour {
                cell.set_symbol("▀")
                    .set_fg(terminal_colour(app, top, times))
                    .set_bg(terminal_colour(app, bottom, times));
            } else {
                let mut s = [0u8; 4];
                cell.set_symbol(monochrome_symbol(m.layer, top, times).encode_utf8(&mut s));
            }
            if cursor_here {
                let on_upper = m.cursor.1 as isize == upper;
                let under = if on_upper { top } else { bottom };
                if app.theme.colour {
                    // The cursor's half keeps its colour, the other half is a notch that
                    // reads on any face.
                    let colour = terminal_colour(app, under, times);
                    cell.set_symbol(if on_upper { "▀" } else { "▄" })
                        .set_fg(colour)
                        .set_bg(app.theme.notch(colour));
                } else {
                    let mut s = [0u8; 4];
                    cell.set_symbol(monochrome_symbol(m.layer, under, times).encode_utf8(&mut s))
                        .set_style(Style::new().add_modifier(Modifier::REVERSED));
                }
            }
        }
    }
}

/// The axes' labels beside and under the map, and the cursor's ticks on both.
fn draw_labels(app: &App, map: &BasinMap, inner: Rect, grid: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let m = &app.map;
    let h = map.height();
    let (cols, rows) = grid_size(map, grid);
    // Axis labels: y max at the top row, min at the bottom row; x min left, max right.
    let labels = Rect {
        x: inner.x,
        width: Y_LABELS.min(inner.width),
        ..grid
    };
    let y_label = |row: u16, v: f64| {
        (
            Rect {
                y: grid.y + row,
                height: 1,
                ..labels
            },
            Line::from(format!("{} ", fmt_num(v))).right_aligned(),
        )
    };
    let mut y_labels = vec![y_label(0, map.y.max), y_label(rows - 1, map.y.min)];
    if rows >= 5 {
        let j = (h - 1).saturating_sub(2 * (rows as usize / 2));
        y_labels.push(y_label(rows / 2, map.y.value(j)));
    }
    for (rect, line) in y_labels {
        frame.render_widget(Paragraph::new(line), rect);
    }
    let x_row = grid.y + rows;
    if x_row < inner.bottom() {
        let row = Rect {
            x: grid.x,
            y: x_row,
            width: cols,
            height: 1,
        };
        let lo = fmt_num(map.x.min);
        let hi = fmt_num(map.x.max);
        frame.render_widget(Paragraph::new(lo.clone()), row);
        // The space is the panel's gap column (`fit`): a label never meets the border.
        frame.render_widget(Paragraph::new(Line::from(format!("{hi} ")).right_aligned()), row);
        // The cursor's column, unless that would cover an end label.
        let tick = m.cursor.0 as u16;
        if tick > lo.chars().count() as u16 && tick + (hi.chars().count() as u16) + 1 < cols {
            frame.render_widget(
                Paragraph::new(Span::styled("▲", t.key())),
                Rect {
                    x: grid.x + tick,
                    width: 1,
                    ..row
                },
            );
        }
    }
    let cursor_row = (h as isize - 1 - m.cursor.1 as isize) / 2;
    if cursor_row >= 0 && (cursor_row as u16) < rows && labels.width > 0 {
        frame.render_widget(
            Paragraph::new(Span::styled("▶", t.key())),
            Rect {
                x: labels.right() - 1,
                y: grid.y + cursor_row as u16,
                width: 1,
                height: 1,
            },
        );
    }
}

fn range_line(a: &MapAxis) -> String {
    format!(
        "{} … {} {}",
        fmt_num(a.min),
        fmt_num(a.max),
        Param::of(a.key).limits().unit
    )
}

fn render_side(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let m = &app.map;
    let block = Block::bordered().title(Line::styled(" basin map of the current setup ", t.heading()));
    // Ranked (0 matters most): on a short panel the cursor's details go first, and the colour
    // key, without which a class cannot tell the faces apart, stays.
    let mut lines: Vec<(u8, Line<'static>)> = Vec::new();
    let keys = |axis, range| format!("{} · {}", label(Scope::Map, axis), label(Scope::Map, range));
    for (side, a, keys) in [
        (Side::X, &m.x, keys(Action::NextXAxis, Action::TypeXRange)),
        (Side::Y, &m.y, keys(Action::NextYAxis, Action::TypeYRange)),
    ] {
        let name = if side == Side::X { "x" } else { "y" };
        lines.push((
            0,
            Line::from(vec![
                Span::styled(format!(" {name} "), t.heading()),
                Span::raw(format!("{:<14}", Param::of(a.key).label())),
                Span::styled(format!(" {keys}"), t.key()),
            ]),
        ));
        match &m.editing {
            Some(r) if r.side == side => {
                lines.push((
                    0,
                    Line::from(vec![
                        Span::raw("   range "),
                        Span::styled(format!("{}▏", r.editor.text), t.selected()),
                    ]),
                ));
                if let Some(e) = &r.editor.error {
                    lines.push((0, Line::styled(format!("   {e}"), t.danger())));
                }
            }
            _ => lines.push((1, Line::raw(format!("   {}", range_line(a))))),
        }
    }
    let zoom = ZOOM_FACTOR.powi(m.zooms.len() as i32);
    let progress = match (m.map(), m.running) {
        (Some(map), running) => {
            let state = if running {
                "computing"
            } else if map.complete {
                "complete"
            } else {
                "stopped"
            };
            Line::from(vec![
                Span::styled(format!(" {state} "), if running { t.caution() } else { t.good() }),
                Span::raw(format!(
                    " {}×{} · {} rolled",
                    map.width(),
                    map.height(),
                    map.sampled
                )),
            ])
        }
        (None, true) => Line::styled(" computing… ", t.caution()),
        (None, false) => Line::raw(" not computed"),
    };
    lines.push((0, progress));
    lines.push((
        2,
        Line::raw(format!(
            " zoom ×{} ({} in, {} out)",
            fmt_num(zoom),
            first_key(Scope::Map, Action::MapZoomIn),
            first_key(Scope::Map, Action::MapZoomOut)
        )),
    ));
    lines.push((5, Line::raw("")));
    lines.extend(cursor_lines(app));
    lines.extend(legend_lines(app).into_iter().map(|l| (0, l)));
    let body = crate::tui::panels::overlays::popup::text_area(block.inner(area));
    frame.render_widget(block, area);
    // Each line wrapped on its own, and kept or dropped whole.
    let wrapped: Vec<(u8, Vec<Line<'static>>)> = lines
        .into_iter()
        .map(|(rank, line)| {
            (
                rank,
                crate::tui::vocabulary::fit::hanging(vec![line], body.width as usize),
            )
        })
        .collect();
    let height = body.height as usize;
    let kept = crate::tui::vocabulary::fit::by_rank(wrapped, |kept| {
        kept.iter().map(|l| l.len()).sum::<usize>() <= height
    });
    frame.render_widget(Paragraph::new(kept.concat()), body);
}

/// The cursor cell's lines, ranked: its heading and outcome first, then its start's values.
fn cursor_lines(app: &App) -> Vec<(u8, Line<'static>)> {
    let t = &app.theme;
    let m = &app.map;
    let (i, j) = m.cursor;
    let rolled = match m.map().and_then(|map| map.cell(i, j)) {
        Some(c) if c.sampled => " · rolled",
        Some(_) => " · inferred",
        None => "",
    };
    let mut lines = vec![(
        1,
        Line::styled(format!(" cursor cell ({i}, {j}){rolled}"), t.heading()),
    )];
    let (Some(update), Some(map)) = (&m.shown, m.map()) else {
        lines.push((1, Line::raw("   waiting for the map")));
        return lines;
    };
    let (params, ic) = node_setup(&update.params, &update.initial, &map.x, &map.y, i, j);
    let w = ic.angular_velocity_for(params.inertia());
    let v = ic.velocity;
    let o = ic.orientation;
    let n = |x: f64| fmt_num(x);
    lines.push((
        2,
        Line::raw(format!(
            "   {} {} · {} {}",
            Param::of(m.x.key).label(),
            n(map.x.value(i)),
            Param::of(m.y.key).label(),
            n(map.y.value(j))
        )),
    ));
    match map.cell(i, j) {
        Some(c) => {
            let ending = Ending::of(&c.outcome);
            let style = match ending {
                Ending::Face(_) => t.good(),
                Ending::Unstable => t.danger(),
                _ => t.caution(),
            };
            let how = if c.sampled {
                format!(" after {:.3} s (from {})", c.outcome.time_s, c.start_face)
            } else {
                // Filled in from its block's corners, which all ended so: the time of a
                // roll nobody ran is not known.
                " like its block's rolled corners; time not known".to_string()
            };
            lines.push((
                1,
                Line::from(vec![
                    Span::raw("   "),
                    Span::styled(ending.words(), style),
                    Span::raw(how),
                ]),
            ));
        }
        None => lines.push((1, Line::raw("   not computed yet"))),
    }
    lines.push((
        3,
        Line::raw(format!(
            "   h {} cm · v ({}, {}, {}) cm/s",
            n(ic.height),
            n(v[0]),
            n(v[1]),
            n(v[2])
        )),
    ));
    lines.push((
        3,
        Line::raw(format!("   ω ({}, {}, {}) rad/s", n(w[0]), n(w[1]), n(w[2]))),
    ));
    lines.push((
        4,
        Line::raw(format!(
            "   yaw pitch roll ({}, {}, {})°",
            n(o[0]),
            n(o[1]),
            n(o[2])
        )),
    ));
    lines
}

fn legend_lines(app: &App) -> Vec<Line<'static>> {
    let t = &app.theme;
    let m = &app.map;
    let mut lines = vec![Line::styled(
        format!(
            " legend: {} ({})",
            layer_name(m.layer),
            label(Scope::Map, Action::MapLayer)
        ),
        t.heading(),
    )];
    let swatch = |cell: Option<Cell>, times| {
        Span::styled("██", Style::new().fg(terminal_colour(app, cell.as_ref(), times)))
    };
    let cell = |status, face, time_s| Cell {
        outcome: dicesim_physics::Outcome {
            status,
            face,
            steps: 0,
            time_s,
            impacts: 0,
            first_impact: None,
        },
        start_face: 1,
        sampled: true,
    };
    let (without, unsettled, unstable) = (
        Ending::WithoutFace.name(),
        Ending::DidNotSettle.name(),
        Ending::Unstable.name(),
    );
    if !app.theme.colour {
        lines.push(Line::raw(match m.layer {
            Layer::Face => "   no colour: digits 1-6 show the face up".to_string(),
            Layer::SettleTime => format!("   no colour: ░▒▓█ longer settle times, ~ {INFERRED_WORDS}"),
        }));
        lines.push(Line::raw(format!("   · {without}")));
        lines.push(Line::raw(format!("   ? {unsettled}  ! {unstable}")));
        return lines;
    }
    match m.layer {
        Layer::Face => {
            let mut faces = vec![Span::raw("  ")];
            for &f in app.setup.params.die.face_numbers() {
                faces.push(swatch(Some(cell(Status::Settled, Some(f), 0.0)), None));
                faces.push(Span::raw(format!("{f} ")));
            }
            lines.push(Line::from(faces));
        }
        Layer::SettleTime => {
            let (lo, hi) = m.map().and_then(time_range).unwrap_or((0.0, 0.0));
            let mut bar = vec![Span::raw(format!("   {:.2} s ", lo))];
            for k in 0..8 {
                let time = lo + (hi - lo) * k as f64 / 7.0;
                bar.push(Span::styled(
                    "█",
                    Style::new().fg(terminal_colour(
                        app,
                        Some(&cell(Status::Settled, Some(1), time)),
                        Some((lo, hi)),
                    )),
                ));
            }
            bar.push(Span::raw(format!(" {:.2} s", hi)));
            lines.push(Line::from(bar));
        }
    }
    if m.layer == Layer::SettleTime {
        let filled = Cell {
            sampled: false,
            ..cell(Status::Settled, Some(1), 0.0)
        };
        lines.push(Line::from(vec![
            Span::raw("  "),
            swatch(Some(filled), None),
            Span::raw(INFERRED_WORDS),
        ]));
    } else {
        lines.push(Line::from(vec![
            Span::raw("  "),
            swatch(Some(cell(Status::Settled, None, 0.0)), None),
            Span::raw(without),
        ]));
    }
    lines.push(Line::from(vec![
        Span::raw("  "),
        swatch(Some(cell(Status::Timeout, None, 0.0)), None),
        Span::raw(format!("{unsettled} ")),
        swatch(Some(cell(Status::Unstable, None, 0.0)), None),
        Span::raw(unstable),
    ]));
    lines
}

#[cfg(test)]
mod basin_map_tests;
