//! The presentation view (`P`): for a projector and the back row. The die takes most of
//! the screen over a fixed height scale in cm (the camera follows the die across the table
//! but never up and down, so a drop or a bounce is seen as a change of height), with the
//! face up in large block digits, the time and one number the lesson is about beside it.

use crate::tui::panels::die::{self, Projection};
use crate::tui::panels::footer::{self, KeyHint, render_key_hints};
use crate::tui::state::app::{App, Mode};
use crate::tui::vocabulary::key_table::{Action, Scope, first_key, rows};
use nalgebra::Vector3;
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

/// Rows and columns of one block digit in [`GLYPHS`].
const GLYPH_ROWS: usize = 5;
const GLYPH_COLUMNS: usize = 5;

/// The faces' numbers as 5×5 block patterns (`#` filled), drawn scaled up; `?` for a die
/// with no face up (on an edge).
const GLYPHS: [(char, [&str; GLYPH_ROWS]); 7] = [
    ('1', ["  #  ", " ##  ", "  #  ", "  #  ", " ### "]),
    ('2', ["#### ", "    #", " ### ", "#    ", "#####"]),
    ('3', ["#### ", "    #", " ### ", "    #", "#### "]),
    ('4', ["#  # ", "#  # ", "#####", "   # ", "   # "]),
    ('5', ["#####", "#    ", "#### ", "    #", "#### "]),
    ('6', [" ### ", "#    ", "#### ", "#   #", " ### "]),
    ('?', [" ### ", "#   #", "  ## ", "     ", "  #  "]),
];

/// The block pattern of `c` (`?` for anything without one).
pub(crate) fn glyph(c: char) -> [&'static str; GLYPH_ROWS] {
    GLYPHS
        .iter()
        .find(|(g, _)| *g == c)
        .or_else(|| GLYPHS.iter().find(|(g, _)| *g == '?'))
        .map(|(_, rows)| *rows)
        .expect("the table has `?`")
}

/// `c` in block characters, each pattern cell `sx` columns by `sy` rows.
pub(crate) fn big_digit(c: char, sx: usize, sy: usize) -> Vec<String> {
    glyph(c)
        .iter()
        .flat_map(|row| {
            let line: String = row
                .chars()
                .flat_map(|p| std::iter::repeat_n(if p == '#' { '█' } else { ' ' }, sx))
                .collect();
            std::iter::repeat_n(line, sy)
        })
        .collect()
}

/// Columns of the height scale left of the die: `100 ┤`.
const SCALE_WIDTH: u16 = 6;

/// cm between the scale's ticks: the smallest of 1, 2, 5 × 10ⁿ that gives at most
/// `most` ticks over `span` cm.
pub(crate) fn tick_step(span: f64, most: usize) -> f64 {
    let most = most.max(1) as f64;
    let mut decade = 10f64.powi((span / most).max(1e-6).log10().floor() as i32);
    loop {
        for m in [1.0, 2.0, 5.0] {
            if span / (m * decade) <= most {
                return m * decade;
            }
        }
        decade *= 10.0;
    }
}

/// The die's view with a fixed vertical range: from just below the table to above the
/// highest the roll's centre can get (its start, or where an upward throw peaks, ½v²/g
/// higher), the same for every step of the roll; the zoom keys shrink it from the top, the
/// table staying at the bottom. Horizontally the camera follows the die, as on the main
/// screen, so the die stays in view as it travels.
pub(crate) fn fixed_view(app: &App, area: Rect) -> Projection {
    let live = &app.roll.live;
    let camera = app.die_screen.camera;
    let half = app.roll.shape.scale;
    let (sp, cp) = camera.pitch_deg.to_radians().sin_cos();
    let rise = live.initial.velocity[2].max(0.0);
    let peak = live.initial.height + rise * rise / (2.0 * live.params.world.gravity);
    // A corner reaches √3 half sizes from the centre; the table in front of the die shows
    // below its foot by the pitch.
    let reach = 3f64.sqrt() * half;
    let bottom = -(reach * sp.abs() + 0.5 * half);
    let top = ((peak + reach) * cp + reach * sp.abs()).max(bottom + 4.0 * reach);
    let height = (top - bottom) * 1.25f64.powi(-camera.zoom);
    let width = height * area.width.max(1) as f64 / (2.0 * area.height.max(1) as f64);
    let die = &live.die;
    Projection {
        camera,
        focus: Vector3::new(die.centre.x, die.centre.y, 0.0),
        x: (-width / 2.0, width / 2.0),
        y: (bottom, bottom + height),
        area,
    }
}

/// The row of `view.area` (from its top) where a height of `z_cm` above the table shows,
/// straight above the die's foot (where the die's centre is), if inside the area.
pub(crate) fn row_of_height(view: &Projection, z_cm: f64) -> Option<u16> {
    let y = z_cm * view.camera.pitch_deg.to_radians().cos();
    let f = (view.y.1 - y) / (view.y.1 - view.y.0);
    (0.0..1.0)
        .contains(&f)
        .then_some((f * view.area.height as f64) as u16)
}

/// Draws the presentation view over the whole terminal.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let [header, body, footer] = area.layout(&Layout::vertical([
        Constraint::Length(1),
        Constraint::Min(0),
        Constraint::Length(1),
    ]));
    let side = (area.width * 2 / 7).clamp(24, 36);
    let [stage, panel] = body.layout(&Layout::horizontal([
        Constraint::Min(0),
        Constraint::Length(side),
    ]));
    let live = &app.roll.live;
    let at_end = live.timeline.ended && live.timeline.position >= live.timeline.furthest;
    // Between the stop and rest the face is known but the die still moves: not "settled" yet.
    let phase = match (die::decided_at(app), live.phase) {
        (Some(_), crate::worker::Phase::Ended(o)) if !at_end => match o.face {
            Some(f) => format!("face {f} decided, coming to rest"),
            None => "decided, coming to rest".to_string(),
        },
        _ => live.phase.label(),
    };
    let title = Line::from(vec![
        Span::styled(" dicesim ", t.heading()),
        // The speed too: `]` and `[` change it here, and a class should see that they did.
        Span::raw(format!(
            "· {} · speed {} · {phase} ",
            app.setup.preset.name,
            app.setup.speed.label()
        )),
    ]);
    frame.render_widget(Paragraph::new(title), header);

    let block = Block::bordered().title(Line::styled(" die · height scale in cm ", t.heading()));
    let inner = block.inner(stage);
    frame.render_widget(block, stage);
    if inner.width > SCALE_WIDTH + 4 && inner.height > 4 {
        let [scale, canvas] = inner.layout(&Layout::horizontal([
            Constraint::Length(SCALE_WIDTH),
            Constraint::Min(0),
        ]));
        let view = fixed_view(app, canvas);
        die::draw(app, &view, frame);
        draw_scale(app, &view, scale, frame);
    }
    draw_panel(app, panel, frame);

    if app.mode() == Mode::Normal {
        render_key_hints(app, hints(), footer, frame);
    } else {
        footer::render(app, footer, frame);
    }
}

/// The footer's hints: the view's own rows of the key table, then the few main-screen keys
/// a lesson uses here (play, replay, a random roll, the start and end, help and quit).
fn hints() -> Vec<KeyHint> {
    let wanted = [
        Action::TogglePlay,
        Action::Replay,
        Action::RandomRoll,
        Action::ToStart,
        Action::Help,
        Action::Quit,
    ];
    let own = rows(Scope::Show).filter(|b| b.screen == Scope::Show || b.action == Action::Presentation);
    let shared = rows(Scope::Show).filter(|b| wanted.contains(&b.action));
    own.chain(shared)
        .filter_map(|b| {
            let h = b.hint?;
            let words = if b.action == Action::Presentation {
                "back"
            } else {
                h.words
            };
            Some((h.keys.to_string(), words.to_string(), h.priority))
        })
        .collect()
}

/// The height scale: a tick at each whole step of cm, labelled, the table at 0.
fn draw_scale(app: &App, view: &Projection, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let cp = view.camera.pitch_deg.to_radians().cos();
    if cp <= 0.05 {
        // Looking almost straight down, heights do not show on screen.
        return;
    }
    let span = view.y.1 / cp;
    let step = tick_step(span, (area.height as usize / 3).max(2));
    let buf = frame.buffer_mut();
    let mut z = 0.0;
    let style = Style::new().fg(t.ground());
    while z <= span {
        if let Some(row) = row_of_height(view, z) {
            let label = format!("{:>4} ┤", crate::tui::vocabulary::format::fmt_num(z));
            buf.set_string(area.x, area.y + row, &label, Style::new());
            buf.set_string(area.x + SCALE_WIDTH - 1, area.y + row, "┤", style);
        }
        z += step;
    }
}

/// The panel beside the die: the face up in large digits, the time and the chosen number.
fn draw_panel(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let live = &app.roll.live;
    let block = Block::bordered().title(Line::styled(" face up ", t.heading()));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let readout = app.die_screen.readout;
    // The number as printed: one digit on the box, up to two on the d8 … d20 and the d%.
    let face: Vec<char> = match live.phase {
        crate::worker::Phase::Ended(o) if o.face.is_none() => vec!['?'],
        _ => crate::tui::vocabulary::format::face_text(live.params.die.kind, live.die.face_up.into())
            .chars()
            .collect(),
    };
    // Text below the digits: the time, the number's name and value, the key that changes it.
    let text_rows = 7;
    let sy = ((inner.height.saturating_sub(text_rows) as usize) / GLYPH_ROWS).clamp(1, 3);
    // The digits side by side, a column of one dot between them.
    let digits = face.len();
    let sx = (2 * sy)
        .min((inner.width as usize).saturating_sub(2 + digits - 1) / (digits * GLYPH_COLUMNS))
        .max(1);
    let glyphs: Vec<Vec<String>> = face.iter().map(|&c| big_digit(c, sx, sy)).collect();
    let mut lines: Vec<Line> = (0..glyphs[0].len())
        .map(|row| {
            let joined: Vec<&str> = glyphs.iter().map(|g| g[row].as_str()).collect();
            Line::styled(joined.join(" ".repeat(sx).as_str()), t.heading()).centered()
        })
        .collect();
    lines.push(Line::raw(""));
    lines.push(Line::from(vec![Span::styled(format!("t {:.3} s", live.time_s), t.heading())]).centered());
    if let Some(t_s) = die::decided_at(app) {
        lines.push(Line::raw(format!("face decided {t_s:.3} s")).centered());
    }
    for text in crate::tui::state::die_screen::readout_texts(app.die_screen.readouts, live) {
        for part in text.split("  ") {
            lines.push(Line::styled(part.to_string(), t.heading()).centered());
        }
    }
    lines.push(Line::raw(""));
    lines.push(Line::raw(readout.name()).centered());
    lines.push(Line::styled(readout.text(&app.roll.live), t.heading()).centered());
    lines.push(
        Line::from(vec![
            Span::styled(first_key(Scope::Show, Action::NextReadout), t.key()),
            Span::raw(format!(" {}", readout.next().name())),
        ])
        .centered(),
    );
    frame.render_widget(Paragraph::new(lines), inner);
}

#[cfg(test)]
mod presentation_tests;
