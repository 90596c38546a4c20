//! Styles that carry meaning, for colour terminals (dark, light, projector) and for
//! `NO_COLOR`, where bold, reverse and underline carry the same meaning.
//!
//! The dark theme draws on the terminal's own background. The light and projector themes
//! paint their own (white) background, so they read the same on any terminal: light with
//! darker inks, projector with the strongest inks and every character bold, for a washed-out
//! beamer at the back of a classroom.
//!
//! The dark theme uses only the standard ANSI colours whose hue the terminal's own theme
//! keeps readable on dark backgrounds (no white, grey or yellow text); warnings use a
//! background, which reads on any theme and on a projector.
//!
//! The painted themes give every colour as RGB, never a terminal's named colour (whose shade
//! is the terminal's choice), so their contrast can be promised: every ink is dark enough for
//! WCAG 2's 4.5:1 as text on the lightest and darkest background it is drawn on (the white
//! page, the die's grey faces, the blue-tinted face up, the shadow), and so more than the
//! 3:1 that lines and markers need. The faces stay light for the same reason.

use ratatui::style::{Color, Modifier, Style};

/// The light palettes' background and text, as exact RGB: terminals remap the 16 ANSI
/// colours (a "white" may be grey), which would cost contrast.
const PAPER: Color = Color::Rgb(255, 255, 255);
const INK: Color = Color::Rgb(0, 0, 0);

/// The painted themes' warning backgrounds: a yellow that black reads on at 14:1, and a red
/// that white reads on at 7:1.
const CAUTION: Color = Color::Rgb(255, 210, 0);
const DANGER: Color = Color::Rgb(180, 0, 0);

/// Which palette (`t` cycles them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Palette {
    #[default]
    Dark,
    Light,
    Projector,
}

impl Palette {
    pub(crate) fn name(self) -> &'static str {
        match self {
            Palette::Dark => "dark",
            Palette::Light => "light",
            Palette::Projector => "projector",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Theme {
    pub(crate) colour: bool,
    pub(crate) palette: Palette,
}

impl Default for Theme {
    fn default() -> Self {
        Theme {
            colour: true,
            palette: Palette::Dark,
        }
    }
}

impl Theme {
    /// Colour unless `NO_COLOR` is set to a non-empty value (no-color.org).
    pub fn from_env() -> Theme {
        Theme {
            colour: std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty()),
            ..Theme::default()
        }
    }

    pub fn monochrome() -> Theme {
        Theme {
            colour: false,
            ..Theme::default()
        }
    }

    /// The next palette: dark → light → projector → dark.
    pub(crate) fn next(self) -> Theme {
        let palette = match self.palette {
            Palette::Dark => Palette::Light,
            Palette::Light => Palette::Projector,
            Palette::Projector => Palette::Dark,
        };
        Theme { palette, ..self }
    }

    /// A colour for lines and text in this palette, or the terminal's own foreground
    /// without colour. The light palettes darken the hues that wash out on white.
    pub(crate) fn ink(&self, c: Color) -> Color {
        if !self.colour {
            return Color::Reset;
        }
        match (self.palette, c) {
            (Palette::Dark, c) => c,
            (_, Color::Reset) => INK,
            // Relative luminance at most 0.09 each: 4.5:1 on the darkest fill (the face up
            // turned away, 0.59).
            (Palette::Light, Color::Blue) => Color::Rgb(0, 70, 190),
            (Palette::Light, Color::Magenta) => Color::Rgb(130, 0, 140),
            (Palette::Light, Color::Green) => Color::Rgb(0, 90, 0),
            (Palette::Light, Color::Red) => Color::Rgb(160, 0, 0),
            (Palette::Light, Color::Cyan) => Color::Rgb(0, 80, 120),
            (Palette::Light, Color::DarkGray) => Color::Rgb(80, 80, 80),
            (Palette::Projector, Color::Blue) => Color::Rgb(0, 0, 230),
            (Palette::Projector, Color::Magenta) => Color::Rgb(140, 0, 140),
            (Palette::Projector, Color::Green) => Color::Rgb(0, 95, 0),
            (Palette::Projector, Color::Red) => Color::Rgb(170, 0, 0),
            (Palette::Projector, Color::Cyan) => Color::Rgb(0, 85, 130),
            (Palette::Projector, Color::DarkGray) => Color::Rgb(80, 80, 80),
            // Any other named colour has no promised shade: ink it.
            (_, _) => INK,
        }
    }

    /// What every cell starts from: the terminal's own colours (dark, or no colour), or
    /// the palette's ink on its painted background.
    pub(crate) fn base(&self) -> Style {
        match (self.colour, self.palette) {
            (false, _) | (true, Palette::Dark) => Style::new(),
            (true, Palette::Light) => Style::new().fg(INK).bg(PAPER),
            (true, Palette::Projector) => Style::new().fg(INK).bg(PAPER).add_modifier(Modifier::BOLD),
        }
    }

    /// Gives every cell the palette's background and ink where a widget left the
    /// terminal's own (`Reset`), and the projector's bold everywhere. Run once, after
    /// everything is drawn, so no widget needs to know the palette.
    pub(crate) fn paint(&self, buf: &mut ratatui::buffer::Buffer) {
        let base = self.base();
        if base == Style::new() {
            return;
        }
        let area = buf.area;
        for y in area.top()..area.bottom() {
            for x in area.left()..area.right() {
                let cell = &mut buf[(x, y)];
                if cell.bg == Color::Reset
                    && let Some(bg) = base.bg
                {
                    cell.bg = bg;
                }
                if cell.fg == Color::Reset
                    && let Some(fg) = base.fg
                {
                    cell.fg = fg;
                }
                cell.modifier |= base.add_modifier;
            }
        }
    }

    fn fg(&self, c: Color) -> Style {
        Style::new().fg(self.ink(c))
    }

    pub(crate) fn heading(&self) -> Style {
        Style::new().add_modifier(Modifier::BOLD)
    }

    pub(crate) fn key(&self) -> Style {
        self.fg(Color::Blue).add_modifier(Modifier::BOLD)
    }

    pub(crate) fn selected(&self) -> Style {
        Style::new().add_modifier(Modifier::REVERSED)
    }

    /// A corner touching the ground (the authors drew those edges red); no arrow is red, so
    /// the highlight is never mistaken for one.
    pub(crate) fn contact(&self) -> Style {
        if self.colour {
            Style::new().fg(self.ink(Color::Red)).add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::BOLD | Modifier::REVERSED)
        }
    }

    pub(crate) fn contact_colour(&self) -> Color {
        self.ink(Color::Red)
    }

    /// Worth a look: the stability number past 1, a p-value that doubts fairness.
    pub(crate) fn caution(&self) -> Style {
        match (self.colour, self.palette) {
            (true, Palette::Dark) => Style::new().fg(Color::Black).bg(Color::Yellow),
            (true, _) => Style::new().fg(INK).bg(CAUTION),
            (false, _) => Style::new().add_modifier(Modifier::BOLD | Modifier::UNDERLINED),
        }
    }

    /// Trouble: the stability number near 2, an unstable roll, a refused value.
    pub(crate) fn danger(&self) -> Style {
        let (fg, bg) = match self.palette {
            Palette::Dark => (Color::White, Color::Red),
            _ => (PAPER, DANGER),
        };
        if self.colour {
            Style::new().fg(fg).bg(bg).add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::BOLD | Modifier::REVERSED)
        }
    }

    pub(crate) fn good(&self) -> Style {
        self.fg(Color::Green).add_modifier(Modifier::BOLD)
    }

    pub(crate) fn bar(&self) -> Style {
        self.fg(Color::Blue)
    }

    /// The floor tiles: grey, so that the green contact-force arrows stand out on them.
    pub(crate) fn ground(&self) -> Color {
        self.ink(Color::DarkGray)
    }

    pub(crate) fn shadow(&self) -> Color {
        self.ink(Color::DarkGray)
    }

    pub(crate) fn die(&self) -> Color {
        Color::Reset
    }

    /// Line colours of total, translational, rotational, gravitational and elastic energy.
    pub(crate) fn energy_series(&self) -> [Color; 5] {
        [
            Color::Reset,
            Color::Blue,
            Color::Magenta,
            Color::Green,
            Color::Red,
        ]
        .map(|c| self.ink(c))
    }

    /// Arrow colours of ω, L, the centre-of-mass velocity and the contact forces: none of
    /// them the contact highlight's red.
    pub(crate) fn vector_colours(&self) -> [Color; 4] {
        [Color::Cyan, Color::Magenta, Color::Blue, Color::Green].map(|c| self.ink(c))
    }

    /// The background of a die face turned `facing` (0 edge-on … 1 head-on) to the viewer,
    /// lit from the front, or `None` without colour. The face up is tinted blue, so the
    /// class sees which face is winning from the back of the room.
    pub(crate) fn face_fill(&self, facing: f64, up: bool) -> Option<Color> {
        if !self.colour {
            return None;
        }
        let f = facing.clamp(0.0, 1.0);
        let rgb =
            |r: f64, g: f64, b: f64| Color::Rgb(r.round() as u8, g.round() as u8, b.round().min(255.0) as u8);
        // The painted faces stay light (luminance 0.59 and up) so every ink reads on them.
        let (dim, bright) = match self.palette {
            Palette::Dark => (55.0, 120.0),
            Palette::Light | Palette::Projector => (210.0, 250.0),
        };
        let g = dim + (bright - dim) * f;
        Some(match (up, self.palette) {
            (false, _) => rgb(g, g, g),
            (true, Palette::Dark) => rgb(0.7 * g, 0.85 * g, (1.35 * g).max(g + 30.0)),
            (true, _) => rgb(g - 30.0, g - 8.0, 255.0),
        })
    }

    /// The background of a face of the marked pair (`which` 0: the lower-numbered face, 1:
    /// its opposite) turned `facing` to the viewer: warm and cool tints as light as the
    /// other faces, so every ink still reads on them; `None` without colour.
    pub(crate) fn pair_fill(&self, facing: f64, which: usize) -> Option<Color> {
        if !self.colour {
            return None;
        }
        let f = facing.clamp(0.0, 1.0);
        let rgb = |r: f64, g: f64, b: f64| {
            Color::Rgb(
                r.round().min(255.0) as u8,
                g.round().min(255.0) as u8,
                b.round().min(255.0) as u8,
            )
        };
        Some(match (self.palette, which) {
            (Palette::Dark, 0) => {
                let g = 55.0 + 65.0 * f;
                rgb(1.5 * g, 0.9 * g, 0.45 * g)
            }
            (Palette::Dark, _) => {
                let g = 55.0 + 65.0 * f;
                rgb(0.5 * g, 1.3 * g, 0.9 * g)
            }
            (_, 0) => {
                let g = 215.0 + 40.0 * f;
                rgb(255.0, g - 40.0, g - 100.0)
            }
            (_, _) => {
                let g = 215.0 + 40.0 * f;
                rgb(g - 75.0, 255.0, g - 50.0)
            }
        })
    }

    /// The map cursor's notch, the half of its cell that shows no map, beside a map cell of
    /// colour `beside`: the terminal's own background on the dark theme; on the painted ones
    /// black or white, whichever stands out more (the page's white beside face 4's yellow
    /// would be 1.3:1, black beside the settle-time scale's dark blue 2.9:1).
    pub(crate) fn notch(&self, beside: Color) -> Color {
        match (self.colour, self.palette, beside) {
            (true, Palette::Light | Palette::Projector, Color::Rgb(r, g, b)) => {
                // Black and white contrast equally with a luminance of √(1.05·0.05) − 0.05.
                if relative_luminance(r, g, b) > 0.179 {
                    INK
                } else {
                    PAPER
                }
            }
            (true, Palette::Light | Palette::Projector, _) => INK,
            _ => Color::Reset,
        }
    }

    /// The die's shadow on the table, on the painted (white) themes.
    pub(crate) fn shadow_fill(&self) -> Option<Color> {
        match (self.colour, self.palette) {
            (true, Palette::Light | Palette::Projector) => Some(Color::Rgb(225, 225, 225)),
            _ => None,
        }
    }

    /// A loaded die's heavy corner: its own colour, apart from the contact highlight.
    pub(crate) fn heavy(&self) -> Style {
        if self.colour {
            Style::new()
                .fg(self.ink(Color::Magenta))
                .add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::BOLD | Modifier::UNDERLINED)
        }
    }

    /// The chaos twin's die, drawn as a ghost behind the first.
    pub(crate) fn ghost(&self) -> Color {
        self.ink(Color::DarkGray)
    }

    /// Line colours of the twin's separation: centre distance, orientation angle.
    pub(crate) fn separation_colours(&self) -> [Color; 2] {
        [Color::Blue, Color::Magenta].map(|c| self.ink(c))
    }

    /// The stopping threshold: the terminal's own colour, drawn dotted to set it apart.
    pub(crate) fn threshold(&self) -> Color {
        Color::Reset
    }
}

/// WCAG 2's relative luminance of an sRGB colour, 0 (black) to 1 (white).
fn relative_luminance(r: u8, g: u8, b: u8) -> f64 {
    let linear = |c: u8| {
        let c = c as f64 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * linear(r) + 0.7152 * linear(g) + 0.0722 * linear(b)
}
