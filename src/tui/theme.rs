//! Styles that carry meaning, for colour terminals (dark, light, projector) and for
//! `NO_COLOR`, where bold, reverse and underline carry the same meaning.
//!
//! Only the standard ANSI colours whose hue the terminal's own theme keeps readable on both
//! dark and light backgrounds are used (no white, grey or yellow text); warnings use a
//! background, which reads on any theme and on a projector.

use ratatui::style::{Color, Modifier, Style};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Theme {
    pub colour: bool,
}

impl Default for Theme {
    fn default() -> Self {
        Theme { colour: true }
    }
}

impl Theme {
    /// Colour unless `NO_COLOR` is set to a non-empty value (no-color.org).
    pub fn from_env() -> Theme {
        Theme {
            colour: std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty()),
        }
    }

    pub fn monochrome() -> Theme {
        Theme { colour: false }
    }

    /// A colour for lines and text, or the terminal's own foreground without colour.
    pub fn ink(&self, c: Color) -> Color {
        if self.colour { c } else { Color::Reset }
    }

    fn fg(&self, c: Color) -> Style {
        Style::new().fg(self.ink(c))
    }

    pub fn heading(&self) -> Style {
        Style::new().add_modifier(Modifier::BOLD)
    }

    pub fn key(&self) -> Style {
        self.fg(Color::Blue).add_modifier(Modifier::BOLD)
    }

    pub fn selected(&self) -> Style {
        Style::new().add_modifier(Modifier::REVERSED)
    }

    /// A corner touching the ground (the authors drew those edges red).
    pub fn contact(&self) -> Style {
        if self.colour {
            Style::new().fg(Color::Red).add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::BOLD | Modifier::REVERSED)
        }
    }

    pub fn contact_colour(&self) -> Color {
        self.ink(Color::Red)
    }

    /// Worth a look: the stability number past 1, a p-value that doubts fairness.
    pub fn caution(&self) -> Style {
        if self.colour {
            Style::new().fg(Color::Black).bg(Color::Yellow)
        } else {
            Style::new().add_modifier(Modifier::BOLD | Modifier::UNDERLINED)
        }
    }

    /// Trouble: the stability number near 2, an unstable roll, a refused value.
    pub fn danger(&self) -> Style {
        if self.colour {
            Style::new()
                .fg(Color::White)
                .bg(Color::Red)
                .add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::BOLD | Modifier::REVERSED)
        }
    }

    pub fn good(&self) -> Style {
        self.fg(Color::Green).add_modifier(Modifier::BOLD)
    }

    pub fn bar(&self) -> Style {
        self.fg(Color::Blue)
    }

    pub fn ground(&self) -> Color {
        self.ink(Color::Green)
    }

    pub fn shadow(&self) -> Color {
        self.ink(Color::DarkGray)
    }

    pub fn die(&self) -> Color {
        Color::Reset
    }

    /// Line colours of total, translational, rotational, gravitational and elastic energy.
    pub fn energy_series(&self) -> [Color; 5] {
        [
            Color::Reset,
            Color::Blue,
            Color::Magenta,
            Color::Green,
            Color::Red,
        ]
        .map(|c| self.ink(c))
    }

    /// Arrow colours of ω, L, the centre-of-mass velocity and the contact forces.
    pub fn vector_colours(&self) -> [Color; 4] {
        [Color::Cyan, Color::Magenta, Color::Blue, Color::Red].map(|c| self.ink(c))
    }

    /// The chaos twin's die, drawn as a ghost behind the first.
    pub fn ghost(&self) -> Color {
        self.ink(Color::DarkGray)
    }

    /// Line colours of the twin's separation: centre distance, orientation angle.
    pub fn separation_colours(&self) -> [Color; 2] {
        [Color::Blue, Color::Magenta].map(|c| self.ink(c))
    }

    /// The stopping threshold: the terminal's own colour, drawn dotted to set it apart.
    pub fn threshold(&self) -> Color {
        Color::Reset
    }
}
