//! The presentation view (`P`) as a slide: the explorer opened on a preset, `P` pressed,
//! the roll stepped to each frame's time and the screen drawn as the terminal would show
//! it, then each screen rasterised into an animated GIF or PNG
//! ([`dicesim_figures::animation::terminal`]). No thread, clock or terminal: the same
//! preset gives the same screens, and the same bytes.

use crate::tui::input::update::update;
use crate::tui::render::screen::render;
use crate::tui::state::app::App;
use crate::tui::state::messages::Msg;
use crate::tui::vocabulary::theme::Theme;
use crate::worker::{Phase, Simulator};
use dicesim_experiment::Error;
use dicesim_figures::animation::terminal::{Cell, Grid, Screen, ScreenFilm, write_screens};
use dicesim_figures::animation::{Animated, AnimationProgress, AnimationSpec, frame_times};
use dicesim_setup::output::Output;
use dicesim_setup::preset::Preset;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::style::{Color, Modifier};
use std::sync::atomic::{AtomicBool, Ordering};

/// The terminal sizes a slide of the view may have, columns and rows: from the explorer's
/// smallest screen to a very large one.
pub const TERMINAL_COLUMNS: std::ops::RangeInclusive<u16> = 80..=400;
pub const TERMINAL_ROWS: std::ops::RangeInclusive<u16> = 24..=200;

/// Writes the presentation view of `preset`'s roll to `out` (`.gif` or `.png`), on a
/// `terminal` of columns × rows drawn into `spec.size` pixels at `spec.fps` frames per
/// second and `spec.speed`. The view opens as the explorer would (the preset's `[view]`:
/// its theme over `theme`, its camera, speed and readout), so a preset that names its
/// speed should have it as `spec.speed`, which the view's title then states.
pub fn write_presentation(
    preset: &Preset,
    spec: &AnimationSpec,
    terminal: (u16, u16),
    theme: Theme,
    out: &Output,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(AnimationProgress),
) -> Result<Animated, Error> {
    spec.validate()?;
    let (columns, rows) = terminal;
    if !TERMINAL_COLUMNS.contains(&columns) || !TERMINAL_ROWS.contains(&rows) {
        return Err(Error::Animation(format!(
            "a {columns}×{rows} terminal: from {}×{} to {}×{}",
            TERMINAL_COLUMNS.start(),
            TERMINAL_ROWS.start(),
            TERMINAL_COLUMNS.end(),
            TERMINAL_ROWS.end()
        )));
    }
    // Refused before anything is rolled or drawn.
    Grid::legible(spec.size, columns, rows).map_err(Error::Animation)?;
    let film = presentation_film(preset, spec, terminal, theme, cancel, progress)?;
    write_screens(preset, spec, &film, out, cancel, progress)
}

/// The view's screens at every frame's time of the roll, to its end (the die at rest).
pub(crate) fn presentation_film(
    preset: &Preset,
    spec: &AnimationSpec,
    terminal: (u16, u16),
    theme: Theme,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(AnimationProgress),
) -> Result<ScreenFilm, Error> {
    let dt = preset.params().integrator.dt;
    // The live roll's end (it runs past the outcome's stop until the die is at rest).
    let mut ahead = Simulator::new(preset)?;
    while ahead.advance_steps(1 << 14) > 0 {
        if cancel.load(Ordering::Relaxed) {
            return Err(Error::Cancelled);
        }
    }
    let end_s = ahead.snapshot().time_s;
    let times = frame_times(spec, end_s, dt)?;

    let mut simulator = Simulator::new(preset)?;
    let mut app = App::new(simulator.snapshot(), theme);
    // The view is drawn alone: a preset that opens on the map screen opens on the die's.
    app.map.open_asked = false;
    let (columns, rows) = terminal;
    let key = KeyEvent::new(KeyCode::Char('P'), KeyModifiers::NONE);
    for event in [Event::Resize(columns, rows), Event::Key(key)] {
        // The size and `P` only change the page: they ask nothing of the worker or the disk.
        let effects = update(&mut app, Msg::Input(event));
        debug_assert!(effects.is_empty(), "{effects:?}");
    }
    let mut drawn = Terminal::new(TestBackend::new(columns, rows)).expect("a test backend draws");
    let mut status = AnimationProgress {
        drawing: false,
        done: 0,
        total: times.len() as u64,
    };
    let mut screens = Vec::with_capacity(times.len());
    let mut now = 0.0;
    let mut outcome = None;
    for &t in &times {
        if cancel.load(Ordering::Relaxed) {
            return Err(Error::Cancelled);
        }
        simulator.advance_steps(((t - now) / dt).round().max(0.0) as u64);
        let snapshot = simulator.snapshot();
        now = snapshot.time_s;
        if let Phase::Ended(o) = snapshot.phase {
            outcome = Some(o);
        }
        update(&mut app, Msg::from(snapshot));
        drawn.draw(|f| render(&app, f)).expect("a test backend draws");
        screens.push(screen_of(drawn.backend().buffer(), app.theme));
        status.done += 1;
        progress(status);
    }
    let outcome = outcome.expect("the last frame is the live roll's end, after its outcome");
    Ok(ScreenFilm {
        view: "the presentation view".to_string(),
        times,
        screens,
        outcome,
    })
}

/// A drawn buffer as the cells of a screen: the terminal's own colours (where the theme
/// leaves them, the dark and colourless themes) as a dark terminal shows them, named ones
/// as xterm's, reversed cells swapped.
pub(crate) fn screen_of(buffer: &Buffer, theme: Theme) -> Screen {
    let (own_fg, own_bg) = match theme.base().bg {
        Some(Color::Rgb(r, g, b)) => ([0, 0, 0], [r, g, b]),
        _ => ([229, 229, 229], [0, 0, 0]),
    };
    let area = buffer.area;
    let cells = buffer
        .content
        .iter()
        .map(|c| {
            let mut fg = rgb(c.fg, own_fg);
            let mut bg = rgb(c.bg, own_bg);
            if c.modifier.contains(Modifier::REVERSED) {
                std::mem::swap(&mut fg, &mut bg);
            }
            Cell {
                symbol: c.symbol().chars().next().unwrap_or(' '),
                fg,
                bg,
                bold: c.modifier.contains(Modifier::BOLD),
                underline: c.modifier.contains(Modifier::UNDERLINED),
            }
        })
        .collect();
    Screen {
        columns: area.width,
        rows: area.height,
        cells,
    }
}

/// xterm's shades of the 16 named colours, in ANSI order.
const ANSI: [[u8; 3]; 16] = [
    [0, 0, 0],
    [205, 0, 0],
    [0, 205, 0],
    [205, 205, 0],
    [0, 0, 238],
    [205, 0, 205],
    [0, 205, 205],
    [229, 229, 229],
    [127, 127, 127],
    [255, 0, 0],
    [0, 255, 0],
    [255, 255, 0],
    [92, 92, 255],
    [255, 0, 255],
    [0, 255, 255],
    [255, 255, 255],
];

/// `c` as RGB, `own` for the terminal's own colour.
fn rgb(c: Color, own: [u8; 3]) -> [u8; 3] {
    let named = |k: usize| ANSI[k];
    match c {
        Color::Reset => own,
        Color::Rgb(r, g, b) => [r, g, b],
        Color::Black => named(0),
        Color::Red => named(1),
        Color::Green => named(2),
        Color::Yellow => named(3),
        Color::Blue => named(4),
        Color::Magenta => named(5),
        Color::Cyan => named(6),
        Color::Gray => named(7),
        Color::DarkGray => named(8),
        Color::LightRed => named(9),
        Color::LightGreen => named(10),
        Color::LightYellow => named(11),
        Color::LightBlue => named(12),
        Color::LightMagenta => named(13),
        Color::LightCyan => named(14),
        Color::White => named(15),
        Color::Indexed(k) if k < 16 => named(usize::from(k)),
        Color::Indexed(k) if k < 232 => {
            // The 6 × 6 × 6 cube.
            let level = |v: u8| if v == 0 { 0 } else { 55 + 40 * v };
            let k = k - 16;
            [level(k / 36), level(k / 6 % 6), level(k % 6)]
        }
        Color::Indexed(k) => {
            let grey = 8 + 10 * (k - 232);
            [grey; 3]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tui::state::app::Page;
    use crate::tui::vocabulary::theme::Palette;

    fn projector() -> Theme {
        Theme {
            palette: Palette::Projector,
            ..Theme::default()
        }
    }

    /// The paper's spun roll, as the presentation tests roll it.
    fn spun() -> Preset {
        Preset::default()
            .with_overrides(&["initial.angular_velocity=[12,-20,6]", "initial.velocity=[30,0,0]"])
            .expect("valid overrides")
    }

    /// Each screen of the film is the view as the explorer draws it at that frame's time:
    /// the page is the presentation's, its title's time and face are the roll's own, and
    /// the last screen is the roll at rest with the face it ended on.
    #[test]
    fn the_film_is_the_view_at_each_frame_time() {
        let preset = spun();
        let spec = AnimationSpec::new(10, (800, 600));
        let film = presentation_film(
            &preset,
            &spec,
            (80, 24),
            projector(),
            &AtomicBool::new(false),
            &mut |_| {},
        )
        .expect("a film");
        assert_eq!(film.screens.len(), film.times.len());
        let text = |s: &Screen| -> String {
            s.cells
                .chunks(usize::from(s.columns))
                .map(|row| row.iter().map(|c| c.symbol).collect::<String>() + "\n")
                .collect()
        };
        for (k, (screen, t)) in film.screens.iter().zip(&film.times).enumerate() {
            let words = text(screen);
            assert!(words.contains("die · height scale in cm"), "frame {k}:\n{words}");
            // The panel's time is the frame's, to the step.
            assert!(
                words.contains(&format!("t {t:.3} s")),
                "frame {k} at {t} s:\n{words}"
            );
            assert_eq!((screen.columns, screen.rows), (80, 24));
        }
        let face = film.outcome.face.expect("the roll settles on a face");
        let last = text(film.screens.last().unwrap());
        assert!(last.contains(&format!("settled: face {face}")), "{last}");
        // Every character on screen is drawn as itself.
        let unknown: String = film
            .screens
            .iter()
            .flat_map(|s| s.cells.iter().map(|c| c.symbol))
            .filter(|&c| !dicesim_figures::animation::terminal::draws(c))
            .collect();
        assert!(unknown.is_empty(), "no glyph for {unknown:?}");
        // The projector's white page and black ink.
        let first = &film.screens[0];
        assert_eq!(first.cells[0].bg, [255, 255, 255]);
        assert!(
            first
                .cells
                .iter()
                .any(|c| c.fg == [0, 0, 0] && c.symbol != ' ' && c.bold)
        );
        // Stepped the same way, the harness's app agrees on the page.
        let mut simulator = Simulator::new(&preset).expect("valid");
        let mut app = App::new(simulator.snapshot(), projector());
        update(
            &mut app,
            Msg::Input(Event::Key(KeyEvent::new(KeyCode::Char('P'), KeyModifiers::NONE))),
        );
        assert_eq!(app.page, Page::Presentation);
    }

    /// A preset that opens on the map screen is drawn in the presentation view all the same.
    #[test]
    fn a_preset_opening_on_the_map_is_drawn_in_the_view() {
        let mut preset = spun();
        preset.view.screen = Some(dicesim_setup::preset::Screen::Map);
        let spec = AnimationSpec::new(5, (800, 600));
        let film = presentation_film(
            &preset,
            &spec,
            (80, 24),
            projector(),
            &AtomicBool::new(false),
            &mut |_| {},
        )
        .expect("a film");
        let first: String = film.screens[0].cells.iter().map(|c| c.symbol).collect();
        assert!(first.contains("die · height scale in cm"), "{first}");
    }

    #[test]
    fn colours_are_the_themes_and_xterms() {
        assert_eq!(rgb(Color::Rgb(1, 2, 3), [9; 3]), [1, 2, 3]);
        assert_eq!(rgb(Color::Reset, [9; 3]), [9; 3]);
        assert_eq!(rgb(Color::Indexed(196), [0; 3]), [255, 0, 0]);
        assert_eq!(rgb(Color::Indexed(244), [0; 3]), [128; 3]);
        assert_eq!(rgb(Color::Indexed(9), [0; 3]), rgb(Color::LightRed, [0; 3]));
    }
}
