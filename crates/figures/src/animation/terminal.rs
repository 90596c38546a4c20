//! A terminal's screen as a picture: each cell its background and its character, drawn
//! in DejaVu Sans Mono at a size the back row reads, so a view of the explorer (its
//! presentation view above all) goes on a slide as the class saw it.
//!
//! The characters a terminal draws as geometry rather than type (Braille dots, block
//! elements and shades, box-drawing lines) are drawn here as geometry too, as terminals
//! themselves do, so neighbouring cells join without seams whatever the font's metrics;
//! everything else is the font's glyph. Type is drawn with four steps of coverage between
//! a cell's background and its ink, so the whole screen needs a small fixed palette: its
//! colours and those steps, found before anything is drawn. The same screens give the
//! same pixels.

use super::render::{CLEAR, Frame};
use super::{Animated, AnimationProgress, AnimationSpec, Encoding, flat_palette};
use crate::plot::Record;
use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};
use dicesim_experiment::Error;
use dicesim_physics::Outcome;
use dicesim_setup::output::Output;
use dicesim_setup::preset::Preset;
use std::collections::HashMap;
use std::sync::OnceLock;
use std::sync::atomic::AtomicBool;

/// One character cell: its character (a space for none), ink and background as RGB, bold
/// and underlined.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cell {
    pub symbol: char,
    pub fg: [u8; 3],
    pub bg: [u8; 3],
    pub bold: bool,
    pub underline: bool,
}

/// A terminal's screen: `columns` × `rows` cells, row by row from the top.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Screen {
    pub columns: u16,
    pub rows: u16,
    pub cells: Vec<Cell>,
}

/// DejaVu Sans Mono 2.37, regular and bold, cut to the characters a terminal screen of the
/// explorer shows (`fonts/README.md` says which and how).
const DEJAVU_SANS_MONO: [&[u8]; 2] = [
    include_bytes!("../../fonts/DejaVuSansMono.ttf"),
    include_bytes!("../../fonts/DejaVuSansMono-Bold.ttf"),
];

fn mono(bold: bool) -> &'static FontRef<'static> {
    static FONTS: OnceLock<[FontRef<'static>; 2]> = OnceLock::new();
    &FONTS.get_or_init(|| {
        DEJAVU_SANS_MONO.map(|bytes| {
            FontRef::try_from_slice(bytes).expect("the embedded DejaVu Sans Mono is a valid font")
        })
    })[usize::from(bold)]
}

/// The font's cell, in ems: its advance across, and its ascent and descent down.
fn cell_ems() -> (f64, f64, f64) {
    let font = mono(false);
    let units = f64::from(font.units_per_em().unwrap_or(2048.0));
    let advance = f64::from(font.h_advance_unscaled(font.glyph_id('M'))) / units;
    let ascent = f64::from(font.ascent_unscaled()) / units;
    let descent = -f64::from(font.descent_unscaled()) / units;
    (advance, ascent, descent)
}

/// The fewest pixels a cell is high: a 10-pixel em, about the smallest type a screen shows
/// crisply; a frame too small for it is refused.
pub const LEAST_CELL_HEIGHT: u32 = 12;

/// Where the cells go in a frame: each `cell` pixels (across, down), the grid's top left
/// corner at `origin`, type at `em` pixels with its baseline `ascent` below a cell's top.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub cell: (u32, u32),
    pub origin: (u32, u32),
    pub em: f64,
    ascent: f64,
}

impl Grid {
    /// The largest cells of the font's shape that fit `columns` × `rows` into a `size`
    /// frame, the grid centred in it; `None` when they would be under
    /// [`LEAST_CELL_HEIGHT`] pixels high.
    pub fn fitting(size: (u32, u32), columns: u16, rows: u16) -> Option<Grid> {
        let (advance, ascent, descent) = cell_ems();
        let line = ascent + descent;
        let (columns, rows) = (u32::from(columns.max(1)), u32::from(rows.max(1)));
        let by_width = ((f64::from(size.0 / columns)) * line / advance).floor() as u32;
        let height = (size.1 / rows).min(by_width);
        if height < LEAST_CELL_HEIGHT {
            return None;
        }
        let em = f64::from(height) / line;
        let width = ((em * advance).round() as u32).clamp(1, size.0 / columns);
        Some(Grid {
            cell: (width, height),
            origin: ((size.0 - width * columns) / 2, (size.1 - height * rows) / 2),
            em,
            ascent: em * ascent,
        })
    }

    /// [`Grid::fitting`], or why the frame is too small, with the least size that is not.
    pub fn legible(size: (u32, u32), columns: u16, rows: u16) -> Result<Grid, String> {
        Grid::fitting(size, columns, rows).ok_or_else(|| {
            let least = Grid::least_size(columns, rows);
            format!(
                "{}×{} pixels: {columns}×{rows} terminal cells need at least {}×{} to be read",
                size.0, size.1, least.0, least.1
            )
        })
    }

    /// The least frame size that gives `columns` × `rows` cells of [`LEAST_CELL_HEIGHT`].
    pub fn least_size(columns: u16, rows: u16) -> (u32, u32) {
        let (advance, ascent, descent) = cell_ems();
        let width = (f64::from(LEAST_CELL_HEIGHT) * advance / (ascent + descent)).round() as u32;
        (
            (width + 1) * u32::from(columns),
            LEAST_CELL_HEIGHT * u32::from(rows),
        )
    }
}

/// Steps of ink over a cell's background: 0 the background, `INK_STEPS` the ink.
const INK_STEPS: u8 = 4;

/// `bg` carried `step` of [`INK_STEPS`] of the way to `fg`.
fn mix(fg: [u8; 3], bg: [u8; 3], step: u8) -> [u8; 3] {
    let (k, n) = (u32::from(step), u32::from(INK_STEPS));
    std::array::from_fn(|i| ((u32::from(bg[i]) * (n - k) + u32::from(fg[i]) * k + n / 2) / n) as u8)
}

/// The colours of a set of screens, as palette indices: every background and ink, then
/// the steps between each ink and the background it is drawn on, as long as there is
/// room (a step left out is drawn as the nearest colour there is). Index 0 is [`CLEAR`].
#[derive(Debug, Clone, PartialEq)]
pub struct ScreenPalette {
    colours: Vec<[u8; 3]>,
    index: HashMap<[u8; 3], u8>,
}

impl ScreenPalette {
    pub fn of(screens: &[Screen]) -> ScreenPalette {
        let mut p = ScreenPalette {
            // Never drawn: a delta frame's unchanged pixel.
            colours: vec![super::render::PALETTE[usize::from(CLEAR)]],
            index: HashMap::new(),
        };
        let cells = || screens.iter().flat_map(|s| &s.cells);
        for c in cells() {
            p.add(c.bg);
            p.add(c.fg);
        }
        for c in cells().filter(|c| c.symbol != ' ') {
            for step in 1..INK_STEPS {
                p.add(mix(c.fg, c.bg, step));
            }
        }
        p
    }

    fn add(&mut self, c: [u8; 3]) {
        if self.colours.len() < 256 && !self.index.contains_key(&c) {
            self.index.insert(c, self.colours.len() as u8);
            self.colours.push(c);
        }
    }

    /// The index of `c`, or of the nearest colour in the palette.
    fn of_colour(&self, c: [u8; 3]) -> u8 {
        if let Some(&i) = self.index.get(&c) {
            return i;
        }
        let distance = |p: &[u8; 3]| -> u32 {
            (0..3)
                .map(|i| (i32::from(p[i]) - i32::from(c[i])).pow(2) as u32)
                .sum()
        };
        (1..self.colours.len())
            .min_by_key(|&i| distance(&self.colours[i]))
            .unwrap_or(0) as u8
    }

    /// The palette as 256 RGB colours (the unused ones black).
    pub(crate) fn rgb(&self) -> Vec<[u8; 3]> {
        let mut all = self.colours.clone();
        all.resize(256, [0, 0, 0]);
        all
    }
}

/// The lines of a box-drawing character: its arms' weights left, right, up and down (0
/// none, 1 light, 2 heavy) and, for a dashed line, its dashes; read off the characters'
/// Unicode names. The double lines and diagonals are left to the font.
#[rustfmt::skip]
const BOX_LINES: [(char, [u8; 4], u8); 96] = [
    ('─', [1, 1, 0, 0], 0), ('━', [2, 2, 0, 0], 0), ('│', [0, 0, 1, 1], 0), ('┃', [0, 0, 2, 2], 0),
    ('┄', [1, 1, 0, 0], 3), ('┅', [2, 2, 0, 0], 3), ('┆', [0, 0, 1, 1], 3), ('┇', [0, 0, 2, 2], 3),
    ('┈', [1, 1, 0, 0], 4), ('┉', [2, 2, 0, 0], 4), ('┊', [0, 0, 1, 1], 4), ('┋', [0, 0, 2, 2], 4),
    ('┌', [0, 1, 0, 1], 0), ('┍', [0, 2, 0, 1], 0), ('┎', [0, 1, 0, 2], 0), ('┏', [0, 2, 0, 2], 0),
    ('┐', [1, 0, 0, 1], 0), ('┑', [2, 0, 0, 1], 0), ('┒', [1, 0, 0, 2], 0), ('┓', [2, 0, 0, 2], 0),
    ('└', [0, 1, 1, 0], 0), ('┕', [0, 2, 1, 0], 0), ('┖', [0, 1, 2, 0], 0), ('┗', [0, 2, 2, 0], 0),
    ('┘', [1, 0, 1, 0], 0), ('┙', [2, 0, 1, 0], 0), ('┚', [1, 0, 2, 0], 0), ('┛', [2, 0, 2, 0], 0),
    ('├', [0, 1, 1, 1], 0), ('┝', [0, 2, 1, 1], 0), ('┞', [0, 1, 2, 1], 0), ('┟', [0, 1, 1, 2], 0),
    ('┠', [0, 1, 2, 2], 0), ('┡', [0, 2, 2, 1], 0), ('┢', [0, 2, 1, 2], 0), ('┣', [0, 2, 2, 2], 0),
    ('┤', [1, 0, 1, 1], 0), ('┥', [2, 0, 1, 1], 0), ('┦', [1, 0, 2, 1], 0), ('┧', [1, 0, 1, 2], 0),
    ('┨', [1, 0, 2, 2], 0), ('┩', [2, 0, 2, 1], 0), ('┪', [2, 0, 1, 2], 0), ('┫', [2, 0, 2, 2], 0),
    ('┬', [1, 1, 0, 1], 0), ('┭', [2, 1, 0, 1], 0), ('┮', [1, 2, 0, 1], 0), ('┯', [2, 2, 0, 1], 0),
    ('┰', [1, 1, 0, 2], 0), ('┱', [2, 1, 0, 2], 0), ('┲', [1, 2, 0, 2], 0), ('┳', [2, 2, 0, 2], 0),
    ('┴', [1, 1, 1, 0], 0), ('┵', [2, 1, 1, 0], 0), ('┶', [1, 2, 1, 0], 0), ('┷', [2, 2, 1, 0], 0),
    ('┸', [1, 1, 2, 0], 0), ('┹', [2, 1, 2, 0], 0), ('┺', [1, 2, 2, 0], 0), ('┻', [2, 2, 2, 0], 0),
    ('┼', [1, 1, 1, 1], 0), ('┽', [2, 1, 1, 1], 0), ('┾', [1, 2, 1, 1], 0), ('┿', [2, 2, 1, 1], 0),
    ('╀', [1, 1, 2, 1], 0), ('╁', [1, 1, 1, 2], 0), ('╂', [1, 1, 2, 2], 0), ('╃', [2, 1, 2, 1], 0),
    ('╄', [1, 2, 2, 1], 0), ('╅', [2, 1, 1, 2], 0), ('╆', [1, 2, 1, 2], 0), ('╇', [2, 2, 2, 1], 0),
    ('╈', [2, 2, 1, 2], 0), ('╉', [2, 1, 2, 2], 0), ('╊', [1, 2, 2, 2], 0), ('╋', [2, 2, 2, 2], 0),
    ('╌', [1, 1, 0, 0], 2), ('╍', [2, 2, 0, 0], 2), ('╎', [0, 0, 1, 1], 2), ('╏', [0, 0, 2, 2], 2),
    ('╭', [0, 1, 0, 1], 0), ('╮', [1, 0, 0, 1], 0), ('╯', [1, 0, 1, 0], 0), ('╰', [0, 1, 1, 0], 0),
    ('╴', [1, 0, 0, 0], 0), ('╵', [0, 0, 1, 0], 0), ('╶', [0, 1, 0, 0], 0), ('╷', [0, 0, 0, 1], 0),
    ('╸', [2, 0, 0, 0], 0), ('╹', [0, 0, 2, 0], 0), ('╺', [0, 2, 0, 0], 0), ('╻', [0, 0, 0, 2], 0),
    ('╼', [1, 2, 0, 0], 0), ('╽', [0, 0, 1, 2], 0), ('╾', [2, 1, 0, 0], 0), ('╿', [0, 0, 2, 1], 0),
];

/// One cell being drawn: its rectangle in the frame and its colours' indices by ink step.
struct Pen<'a> {
    frame: &'a mut Frame,
    x: i64,
    y: i64,
    w: i64,
    h: i64,
    steps: [u8; INK_STEPS as usize + 1],
}

impl Pen<'_> {
    /// Fills the cell's pixels from `(x0, y0)` to before `(x1, y1)`, relative to its
    /// corner, with ink step `step`.
    fn rect(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, step: u8) {
        for y in y0.max(0)..y1.min(self.h) {
            for x in x0.max(0)..x1.min(self.w) {
                self.frame
                    .set(self.x + x, self.y + y, self.steps[usize::from(step)]);
            }
        }
    }

    /// The 2 × 4 dots of a Braille pattern, bit k of `bits` dot k + 1 of the standard
    /// numbering (1–3 and 7 down the left, 4–6 and 8 down the right).
    fn braille(&mut self, bits: u8) {
        const DOTS: [(i64, i64); 8] = [(0, 0), (0, 1), (0, 2), (1, 0), (1, 1), (1, 2), (0, 3), (1, 3)];
        let (w, h) = (self.w as f64, self.h as f64);
        let r = (w / 4.0).min(h / 8.0) * 0.8;
        for (k, &(col, row)) in DOTS.iter().enumerate() {
            if bits & (1 << k) == 0 {
                continue;
            }
            let (cx, cy) = (
                w * (col as f64 * 2.0 + 1.0) / 4.0,
                h * (row as f64 * 2.0 + 1.0) / 8.0,
            );
            for y in (cy - r).floor() as i64..=(cy + r).ceil() as i64 {
                for x in (cx - r).floor() as i64..=(cx + r).ceil() as i64 {
                    let (dx, dy) = (x as f64 + 0.5 - cx, y as f64 + 0.5 - cy);
                    if dx * dx + dy * dy <= r * r && (0..self.w).contains(&x) && (0..self.h).contains(&y) {
                        self.frame
                            .set(self.x + x, self.y + y, self.steps[usize::from(INK_STEPS)]);
                    }
                }
            }
        }
    }

    /// A block element (U+2580–259F): parts of the cell filled, or a shade.
    fn block(&mut self, c: char) {
        let (w, h) = (self.w, self.h);
        let ink = INK_STEPS;
        let eighths = |n: i64, of: i64| (of * n + 4) / 8;
        match c as u32 {
            0x2580 => self.rect(0, 0, w, h / 2, ink),
            k @ 0x2581..=0x2588 => self.rect(0, h - eighths(k as i64 - 0x2580, h), w, h, ink),
            k @ 0x2589..=0x258F => self.rect(0, 0, eighths(0x2590 - k as i64, w), h, ink),
            0x2590 => self.rect(w / 2, 0, w, h, ink),
            k @ 0x2591..=0x2593 => self.rect(0, 0, w, h, (k - 0x2590) as u8),
            0x2594 => self.rect(0, 0, w, eighths(1, h), ink),
            0x2595 => self.rect(w - eighths(1, w), 0, w, h, ink),
            k => {
                // Quadrants: upper left, upper right, lower left, lower right.
                const QUADRANTS: [u8; 10] = [
                    0b0010, 0b0001, 0b1000, 0b1011, 0b1001, 0b1110, 0b1101, 0b0100, 0b0110, 0b0111,
                ];
                let q = QUADRANTS[(k - 0x2596) as usize];
                let (mx, my) = (w / 2, h / 2);
                for (bit, (x0, y0, x1, y1)) in [
                    (0b1000, (0, 0, mx, my)),
                    (0b0100, (mx, 0, w, my)),
                    (0b0010, (0, my, mx, h)),
                    (0b0001, (mx, my, w, h)),
                ] {
                    if q & bit != 0 {
                        self.rect(x0, y0, x1, y1, ink);
                    }
                }
            }
        }
    }

    /// A box-drawing character's arms from the cell's middle to its edges, `light` pixels
    /// thick (twice as heavy), dashed in `dashes` if not 0.
    fn box_lines(&mut self, arms: [u8; 4], dashes: u8, light: i64) {
        let heaviest = i64::from(*arms.iter().max().unwrap_or(&1));
        // Each arm reaches past the middle by half the thickest line, so corners close.
        let reach = (light * heaviest + 1) / 2;
        let [left, right, up, down] = arms;
        // Across the cell, then down it: (along, across) lengths and the two arms.
        for (across_the_cell, (along, across), (first, second)) in [
            (true, (self.w, self.h), (left, right)),
            (false, (self.h, self.w), (up, down)),
        ] {
            let middle = along / 2;
            let line = |weight: u8| {
                let thick = light * i64::from(weight);
                (across / 2 - thick / 2, across / 2 - thick / 2 + thick)
            };
            // A piece of the line, from `a` to `b` along it.
            let bar = |pen: &mut Pen, a: i64, b: i64, weight: u8| {
                let (c0, c1) = line(weight);
                if across_the_cell {
                    pen.rect(a, c0, b, c1, INK_STEPS);
                } else {
                    pen.rect(c0, a, c1, b, INK_STEPS);
                }
            };
            if dashes > 0 && first == second && first > 0 {
                let n = i64::from(dashes);
                for k in 0..n {
                    let start = along * k / n;
                    bar(self, start, start + (along * 3 / (5 * n)).max(1), first);
                }
                continue;
            }
            if first > 0 {
                bar(self, 0, middle + reach, first);
            }
            if second > 0 {
                bar(self, middle - reach, along, second);
            }
        }
    }
}

/// Draws `screen` as a frame of `size` pixels on `grid` in `palette`'s colours; the margin
/// round the grid takes the colour of the screen's first cell's background.
pub(crate) fn draw_screen(screen: &Screen, size: (u32, u32), grid: &Grid, palette: &ScreenPalette) -> Frame {
    let margin = screen.cells.first().map_or(1, |c| palette.of_colour(c.bg));
    let mut frame = Frame::new(size.0, size.1, margin);
    let columns = usize::from(screen.columns);
    let (cw, ch) = (i64::from(grid.cell.0), i64::from(grid.cell.1));
    let corner = |k: usize| {
        (
            i64::from(grid.origin.0) + (k % columns) as i64 * cw,
            i64::from(grid.origin.1) + (k / columns) as i64 * ch,
        )
    };
    // Every background first: type may reach over its cell's edge into the next one.
    for (k, cell) in screen.cells.iter().enumerate() {
        let (x, y) = corner(k);
        let bg = palette.of_colour(cell.bg);
        for row in y..y + ch {
            for col in x..x + cw {
                frame.set(col, row, bg);
            }
        }
    }
    let light = (cw / 8).max(1);
    for (k, cell) in screen.cells.iter().enumerate() {
        let (x, y) = corner(k);
        let steps: [u8; INK_STEPS as usize + 1] =
            std::array::from_fn(|s| palette.of_colour(mix(cell.fg, cell.bg, s as u8)));
        let mut pen = Pen {
            frame: &mut frame,
            x,
            y,
            w: cw,
            h: ch,
            steps,
        };
        let c = cell.symbol;
        match c as u32 {
            0x20 => {}
            0x2800..=0x28FF => pen.braille((c as u32 - 0x2800) as u8),
            0x2580..=0x259F => pen.block(c),
            _ => match BOX_LINES.iter().find(|(b, ..)| *b == c) {
                Some(&(_, arms, dashes)) => pen.box_lines(arms, dashes, light),
                None => glyph(&mut pen, c, cell.bold, grid),
            },
        }
        if cell.underline {
            let under = (grid.ascent + grid.em * 0.12).round() as i64;
            let thick = ((grid.em / 14.0).round() as i64).max(1);
            pen.rect(0, under, cw, under + thick, INK_STEPS);
        }
    }
    frame
}

/// Whether `c` is drawn as itself: as geometry (Braille, blocks, box lines) or by the
/// font; anything else is drawn as the font's empty box.
pub fn draws(c: char) -> bool {
    matches!(c as u32, 0x2800..=0x28FF | 0x2580..=0x259F)
        || BOX_LINES.iter().any(|(b, ..)| *b == c)
        || [false, true].iter().all(|&bold| mono(bold).glyph_id(c).0 != 0)
}

/// `c` from the font, centred across its cell on the font's baseline, its coverage in ink
/// steps.
fn glyph(pen: &mut Pen, c: char, bold: bool, grid: &Grid) {
    let font = mono(bold);
    // ab_glyph's scale is the font's height, ascent to descent: the cell's.
    let scale = PxScale::from(pen.h as f32);
    let scaled = font.as_scaled(scale);
    let id = scaled.glyph_id(c);
    let left = (pen.w as f32 - scaled.h_advance(id)) / 2.0;
    let g = id.with_scale_and_position(scale, point(left, grid.ascent as f32));
    let Some(outline) = font.outline_glyph(g) else {
        return;
    };
    let bounds = outline.px_bounds();
    let (x0, y0) = (bounds.min.x as i64, bounds.min.y as i64);
    let (ox, oy, steps) = (pen.x, pen.y, pen.steps);
    let frame = &mut *pen.frame;
    outline.draw(|gx, gy, coverage| {
        let step = (coverage.clamp(0.0, 1.0) * f32::from(INK_STEPS)).round() as u8;
        if step > 0 {
            frame.set(
                ox + x0 + i64::from(gx),
                oy + y0 + i64::from(gy),
                steps[usize::from(step)],
            );
        }
    });
}

/// A roll as a terminal showed it: its screens at `times` (simulated s, as
/// [`super::frame_times`] gives them), what the view is called, and how the roll ended.
#[derive(Debug, Clone, PartialEq)]
pub struct ScreenFilm {
    pub view: String,
    pub times: Vec<f64>,
    pub screens: Vec<Screen>,
    pub outcome: Outcome,
}

/// Writes `film` of `preset`'s roll to `out` as an animated GIF or PNG of `spec.size` pixels, at `spec.fps`
/// and `spec.speed` (the rest of `spec` is the die's picture's and unused), carrying the
/// setup and the outcome as [`super::write_animation`]'s files do; a frame too small for
/// legible cells is refused with the least size that is.
pub fn write_screens(
    preset: &Preset,
    spec: &AnimationSpec,
    film: &ScreenFilm,
    out: &Output,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(AnimationProgress),
) -> Result<Animated, Error> {
    spec.validate()?;
    let gif = Encoding::is_gif(out)?;
    let Some(first) = film.screens.first() else {
        return Err(Error::Animation("no screen to draw".to_string()));
    };
    let (columns, rows) = (first.columns, first.rows);
    let grid = Grid::legible(spec.size, columns, rows).map_err(Error::Animation)?;
    let name = &preset.name;
    let mut record = Record::of_setup(
        &format!("{name}: {}", film.view),
        name,
        &preset.params(),
        &preset.initial,
    );
    let json = serde_json::json!({
        "view": film.view,
        "frames": film.screens.len(),
        "fps": spec.fps,
        "speed": spec.speed,
        "width": spec.size.0,
        "height": spec.size.1,
        "terminal": { "columns": columns, "rows": rows, "cell": [grid.cell.0, grid.cell.1] },
        "die": super::outcome_json(&film.outcome),
    });
    record
        .text
        .push(("dicesim-outcome".to_string(), json.to_string()));
    let palette = ScreenPalette::of(&film.screens);
    let encoding = Encoding {
        gif,
        size: spec.size,
        palette: &flat_palette(&palette.rgb()),
        record: &record,
    };
    let mut frames = film
        .screens
        .iter()
        .map(|s| draw_screen(s, spec.size, &grid, &palette));
    encoding.write(out, &film.times, spec.speed, &mut frames, cancel, progress)?;
    Ok(Animated {
        frames: film.screens.len(),
        duration_s: film.times.last().copied().unwrap_or(0.0),
        outcome: film.outcome,
        twin: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const INK: [u8; 3] = [0, 0, 0];
    const PAPER: [u8; 3] = [255, 255, 255];

    fn screen_of(lines: &[&str], bold: bool) -> Screen {
        let columns = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0) as u16;
        let cells = lines
            .iter()
            .flat_map(|l| {
                let mut cs: Vec<char> = l.chars().collect();
                cs.resize(usize::from(columns), ' ');
                cs
            })
            .map(|symbol| Cell {
                symbol,
                fg: INK,
                bg: PAPER,
                bold,
                underline: false,
            })
            .collect();
        Screen {
            columns,
            rows: lines.len() as u16,
            cells,
        }
    }

    /// The rows and columns of cell `(column, row)` holding full ink.
    fn inked(frame: &Frame, grid: &Grid, palette: &ScreenPalette, column: u32, row: u32) -> Vec<(u32, u32)> {
        let ink = palette.of_colour(INK);
        let (x0, y0) = (
            grid.origin.0 + column * grid.cell.0,
            grid.origin.1 + row * grid.cell.1,
        );
        let mut out = Vec::new();
        for y in 0..grid.cell.1 {
            for x in 0..grid.cell.0 {
                if frame.pixels[((y0 + y) * frame.width + x0 + x) as usize] == ink {
                    out.push((x, y));
                }
            }
        }
        out
    }

    /// The grid fills the frame as far as the font's cell shape allows, centred, and a
    /// frame too small for legible type has no grid.
    #[test]
    fn the_grid_is_the_largest_that_fits_and_is_centred() {
        let (advance, ascent, descent) = cell_ems();
        // DejaVu Sans Mono: 1233 units across, 1901 up and 483 down, of 2048.
        assert!((advance - 1233.0 / 2048.0).abs() < 1e-9);
        assert!((ascent + descent - 2384.0 / 2048.0).abs() < 1e-9);
        // 80×24 in 1280×720: 16 × 30 cells, the width's limit (16 px across allows 30.9
        // high, and 720/24 is 30).
        let g = Grid::fitting((1280, 720), 80, 24).unwrap();
        assert_eq!(g.cell, (16, 30));
        assert_eq!(g.origin, (0, 0));
        // 80×24 in 800×600: 10 px across allows 19 high; the grid 800 × 456, centred.
        let g = Grid::fitting((800, 600), 80, 24).unwrap();
        assert_eq!(g.cell, (10, 19));
        assert_eq!(g.origin, (0, (600 - 19 * 24) / 2));
        assert!(
            Grid::fitting((320, 240), 80, 24).is_none(),
            "4 px across is unreadable"
        );
        let least = Grid::least_size(80, 24);
        assert!(Grid::fitting(least, 80, 24).is_some(), "{least:?}");
    }

    /// Box lines meet their neighbours across the cell's edges: a horizontal line is ink
    /// from the first column to the last at the same rows, a vertical from the top row to
    /// the bottom; a Braille cell with every dot has 8 separate dots; a full block fills its
    /// cell; a letter's ink stays near its cell.
    #[test]
    fn geometry_characters_join_and_letters_stay_in_their_cells() {
        let screen = screen_of(&["─┼─\u{28ff}█", " │ A "], false);
        let grid = Grid::fitting((400, 120), 5, 2).unwrap();
        let palette = ScreenPalette::of(std::slice::from_ref(&screen));
        let frame = draw_screen(&screen, (400, 120), &grid, &palette);
        let (w, h) = grid.cell;
        let rows_at = |cells: &[(u32, u32)], x: u32| -> Vec<u32> {
            cells.iter().filter(|p| p.0 == x).map(|p| p.1).collect()
        };
        let dash = inked(&frame, &grid, &palette, 0, 0);
        let cross = inked(&frame, &grid, &palette, 1, 0);
        assert!(!rows_at(&dash, 0).is_empty());
        assert_eq!(rows_at(&dash, 0), rows_at(&dash, w - 1), "level across the cell");
        assert_eq!(rows_at(&dash, w - 1), rows_at(&cross, 0), "joins the next cell");
        let bar = inked(&frame, &grid, &palette, 1, 1);
        let columns_at = |y: u32| -> Vec<u32> { bar.iter().filter(|p| p.1 == y).map(|p| p.0).collect() };
        assert!(!columns_at(0).is_empty());
        assert_eq!(columns_at(0), columns_at(h - 1), "top to bottom");
        assert_eq!(
            cross
                .iter()
                .filter(|p| p.1 == h - 1)
                .map(|p| p.0)
                .collect::<Vec<_>>(),
            columns_at(0),
            "the cross joins the bar below"
        );
        // The eight dots: connected regions of ink.
        let dots = inked(&frame, &grid, &palette, 3, 0);
        let mut seen = std::collections::HashSet::new();
        let mut regions = 0;
        for &p in &dots {
            if !seen.insert(p) {
                continue;
            }
            regions += 1;
            let mut stack = vec![p];
            while let Some((x, y)) = stack.pop() {
                for q in [
                    (x + 1, y),
                    (x.wrapping_sub(1), y),
                    (x, y + 1),
                    (x, y.wrapping_sub(1)),
                ] {
                    if dots.contains(&q) && seen.insert(q) {
                        stack.push(q);
                    }
                }
            }
        }
        assert_eq!(regions, 8);
        assert!(draws('\u{28ff}') && draws('ω') && draws('═'));
        assert!(!draws('\u{4e00}'), "a character the cut leaves out");
        assert_eq!(
            inked(&frame, &grid, &palette, 4, 0).len() as u32,
            w * h,
            "█ fills its cell"
        );
        let a = inked(&frame, &grid, &palette, 3, 1);
        assert!(!a.is_empty(), "A has ink");
        let top = a.iter().map(|p| p.1).min().unwrap();
        let bottom = a.iter().map(|p| p.1).max().unwrap();
        // A capital: from its cap height (0.73 em above the baseline) to the baseline, less
        // a pixel at either end where the ink is not whole.
        let cap = f64::from(bottom + 1 - top);
        assert!((cap - 0.73 * grid.em).abs() <= 2.0, "A {cap} px, em {}", grid.em);
        let baseline = grid.ascent.round() as u32;
        assert!(
            bottom < baseline + 1 && bottom + 2 >= baseline,
            "on the baseline: {bottom} {baseline}"
        );
    }

    /// The palette holds every background and ink and the steps between them, index 0
    /// for nothing drawn; a colour it has no room for is drawn as the nearest.
    #[test]
    fn the_palette_holds_the_screens_colours() {
        let mut screen = screen_of(&["ab"], true);
        screen.cells[1].fg = [200, 0, 0];
        let p = ScreenPalette::of(std::slice::from_ref(&screen));
        assert_eq!(p.colours[0], [255, 0, 255]);
        assert_eq!(p.colours.len(), 1 + 3 + 2 * 3, "paper, ink, red and 3 steps each");
        assert_eq!(
            p.colours[usize::from(p.of_colour(mix([200, 0, 0], PAPER, 2)))],
            [228, 128, 128]
        );
        assert_eq!(p.of_colour([250, 250, 250]), p.of_colour(PAPER));
        let many: Vec<Screen> = (0..300u32)
            .map(|k| {
                let mut s = screen_of(&[" "], false);
                s.cells[0].bg = [(k % 256) as u8, (k / 256) as u8, 7];
                s
            })
            .collect();
        assert_eq!(ScreenPalette::of(&many).rgb().len(), 256);
    }
}
