//! Contrast on the painted themes: every screen state of `screen_tests`, rendered in the
//! light and projector palettes at the classroom sizes, read back cell by cell. A cell with
//! a printable symbol must stand out from the colour it is drawn on by WCAG 2's contrast
//! ratio: 4.5 for text, 3 for a marker (Braille dots, line and block characters, the
//! contact and heavy-corner marks).

use crate::tui::state::app::App;
use crate::tui::tests::fixtures::map_scene;
use crate::tui::tests::screen_tests::{SIZES, draw, states};
use crate::tui::vocabulary::theme::{Palette, Theme};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::KeyCode;
use ratatui::style::{Color, Modifier};

/// WCAG 2's minimum contrast of text, and of graphical objects.
const TEXT: f64 = 4.5;
const MARKER: f64 = 3.0;

/// WCAG 2 relative luminance of an sRGB colour.
fn luminance((r, g, b): (u8, u8, u8)) -> f64 {
    let lin = |c: u8| {
        let c = c as f64 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b)
}

fn contrast(a: (u8, u8, u8), b: (u8, u8, u8)) -> f64 {
    let (la, lb) = (luminance(a), luminance(b));
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}

#[test]
fn the_contrast_formula_gives_wcags_reference_ratios() {
    assert!((contrast((0, 0, 0), (255, 255, 255)) - 21.0).abs() < 1e-9);
    assert!((contrast((7, 7, 7), (7, 7, 7)) - 1.0).abs() < 1e-12);
    // #767676 on white is the classic lightest grey that passes AA (4.54:1).
    let grey = contrast((0x76, 0x76, 0x76), (255, 255, 255));
    assert!((4.5..4.6).contains(&grey), "{grey}");
}

/// Whether a symbol is a marker (a line, dot or block drawn as graphics) rather than text.
fn is_marker(symbol: &str) -> bool {
    symbol.chars().all(|c| {
        matches!(c as u32,
            0x2500..=0x259F // box drawing, block elements
            | 0x25A0..=0x25FF // geometric shapes: ● ◆ ▲
            | 0x2800..=0x28FF) // Braille
    })
}

/// Block cells are area fills (map cells, legend swatches): a half block's two halves are
/// two neighbouring cells, or a cell and the page, not a mark on its background. The map
/// cursor's notch, the one mark among them, has a test of its own below.
fn is_fill(symbol: &str) -> bool {
    matches!(symbol, "▀" | "▄" | "█")
}

fn rgb(c: Color) -> Option<(u8, u8, u8)> {
    match c {
        Color::Rgb(r, g, b) => Some((r, g, b)),
        _ => None,
    }
}

/// One failing cell, for the report.
#[derive(Debug)]
struct Poor {
    ratio: f64,
    need: f64,
    state: &'static str,
    palette: &'static str,
    size: (u16, u16),
    at: (u16, u16),
    symbol: String,
    fg: Color,
    bg: Color,
}

fn check(buf: &Buffer, state: &'static str, theme: Theme, out: &mut Vec<Poor>) {
    let area = buf.area;
    for y in area.top()..area.bottom() {
        for x in area.left()..area.right() {
            let cell = &buf[(x, y)];
            let (mut fg, mut bg) = (cell.fg, cell.bg);
            if cell.modifier.contains(Modifier::REVERSED) {
                std::mem::swap(&mut fg, &mut bg);
            }
            let symbol = cell.symbol();
            let printable = symbol.chars().any(|c| !c.is_whitespace() && c != '\u{2800}');
            let poor = |ratio: f64, need: f64| Poor {
                ratio,
                need,
                state,
                palette: theme.palette.name(),
                size: (area.width, area.height),
                at: (x, y),
                symbol: symbol.to_string(),
                fg,
                bg,
            };
            // Every colour is the palette's own RGB: a terminal's named colours are its
            // theme's choice, so their contrast is nobody's promise.
            let (Some(f), Some(b)) = (rgb(fg), rgb(bg)) else {
                out.push(poor(0.0, TEXT));
                continue;
            };
            if !printable || is_fill(symbol) {
                continue;
            }
            let need = if is_marker(symbol) { MARKER } else { TEXT };
            let ratio = contrast(f, b);
            if ratio < need {
                out.push(poor(ratio, need));
            }
        }
    }
}

fn painted() -> [Theme; 2] {
    [Palette::Light, Palette::Projector].map(|palette| Theme {
        colour: true,
        palette,
    })
}

#[test]
fn every_cell_of_every_screen_reads_on_the_painted_themes() {
    let mut poor = Vec::new();
    let mut cells = 0usize;
    for theme in painted() {
        for s in states(theme) {
            for size in SIZES {
                check(&draw(&s.app, size), s.name, theme, &mut poor);
                cells += size.0 as usize * size.1 as usize;
            }
        }
    }
    assert!(cells > 0);
    poor.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    // The worst cell of each colour pair: one line per thing to fix.
    let mut seen = std::collections::HashSet::new();
    let report: Vec<String> = poor
        .iter()
        .filter(|p| seen.insert((p.palette, format!("{:?}{:?}", p.fg, p.bg), p.need.to_bits())))
        .take(60)
        .map(|p| {
            format!(
                "{:5.2} < {} {} {} {}x{} at ({},{}) {:?} fg {:?} on bg {:?}",
                p.ratio, p.need, p.palette, p.state, p.size.0, p.size.1, p.at.0, p.at.1, p.symbol, p.fg, p.bg
            )
        })
        .collect();
    assert!(
        poor.is_empty(),
        "{} cells below WCAG contrast, worst first:\n{}",
        poor.len(),
        report.join("\n")
    );
}

/// The check itself can fail: grey on white text, and a named colour, are caught.
#[test]
fn the_check_catches_faint_text_and_named_colours() {
    let theme = painted()[1];
    let mut buf = Buffer::empty(ratatui::layout::Rect::new(0, 0, 3, 1));
    buf[(0, 0)]
        .set_symbol("a")
        .set_fg(Color::Rgb(150, 150, 150))
        .set_bg(Color::Rgb(255, 255, 255));
    buf[(1, 0)]
        .set_symbol("⣿")
        .set_fg(Color::Rgb(150, 150, 150))
        .set_bg(Color::Rgb(255, 255, 255));
    buf[(2, 0)]
        .set_symbol("b")
        .set_fg(Color::Yellow)
        .set_bg(Color::Rgb(0, 0, 0));
    let mut poor = Vec::new();
    check(&buf, "made up", theme, &mut poor);
    let at: Vec<_> = poor.iter().map(|p| (p.at.0, p.need)).collect();
    // 150-grey on white is 2.96:1: below both text's 4.5 and a marker's 3.
    assert_eq!(at, vec![(0, TEXT), (1, MARKER), (2, TEXT)]);
}

/// The map cursor is a notch beside its cell's colour, and stands out from it by a marker's
/// 3:1: for every face colour and every colour the settle-time layer draws, and on screen,
/// where the cursor is the cell that changes when it moves.
#[test]
fn the_map_cursor_stands_out_from_every_map_colour() {
    use dicesim_figures::plot::FACE_COLOURS;
    let draw = |app: &App| {
        let mut t = Terminal::new(TestBackend::new(120, 36)).expect("test backend");
        t.draw(|f| crate::tui::render(app, f)).expect("draw");
        t.backend().buffer().clone()
    };
    for theme in painted() {
        let mut colours: Vec<(u8, u8, u8)> = FACE_COLOURS.iter().map(|c| (c.0, c.1, c.2)).collect();
        for layer_keys in [&[][..], &[KeyCode::Char('v')][..]] {
            let mut s = map_scene(theme);
            for &k in layer_keys {
                s.key(k);
            }
            let here = draw(&s.app);
            s.key(KeyCode::Right);
            let moved = draw(&s.app);
            let blocks = |b: &Buffer| {
                b.content()
                    .iter()
                    .filter(|c| matches!(c.symbol(), "▀" | "▄"))
                    .flat_map(|c| [c.fg, c.bg])
                    .filter_map(rgb)
                    .collect::<Vec<_>>()
            };
            colours.extend(blocks(&here));
            // The cursor's cell: a half block that changed when the cursor moved away, its
            // other half the notch.
            let cursor = here
                .content()
                .iter()
                .zip(moved.content())
                .filter(|(a, b)| a != b && matches!(a.symbol(), "▀" | "▄"))
                .map(|(a, _)| a)
                .find(|a| a.bg == theme.notch(a.fg))
                .unwrap_or_else(|| panic!("a cursor in the {} theme", theme.palette.name()));
            let ratio = contrast(rgb(cursor.fg).expect("RGB"), rgb(cursor.bg).expect("RGB"));
            assert!(
                ratio >= MARKER,
                "the cursor: {:?} on {:?}, {ratio:.2}",
                cursor.fg,
                cursor.bg
            );
        }
        colours.sort();
        colours.dedup();
        assert!(colours.len() > 10, "{} map colours", colours.len());
        for c in colours {
            let notch = rgb(theme.notch(Color::Rgb(c.0, c.1, c.2))).expect("an RGB notch");
            let ratio = contrast(c, notch);
            assert!(
                ratio >= MARKER,
                "map colour {c:?} beside the notch {notch:?}: {ratio:.2}"
            );
        }
    }
}
