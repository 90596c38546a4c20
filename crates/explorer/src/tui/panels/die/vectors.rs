//! Arrows on the die (`v`): angular velocity ω and angular momentum L from the centre of
//! mass, the centre-of-mass velocity v, and each touching corner's contact force F.
//!
//! Their sizes span orders of magnitude (a resting corner carries about M·g/8, an impact a
//! hundred times more), so lengths are log-compressed: `a·log₁₀(1 + |x|/x₀)`, with `a` the
//! die's half size and `x₀` a natural unit for each quantity; the legend says it in words
//! (ten times as big, half a die longer). Directions are exact.

use crate::tui::state::app::App;
use crate::tui::vocabulary::fit;
use crate::tui::vocabulary::format::fmt_num;
use crate::tui::vocabulary::solid::Flat;
use crate::worker::DieState;
use nalgebra::Vector3;
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};

/// What an arrow shows, in the legend's order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Arrow {
    AngularVelocity,
    AngularMomentum,
    Velocity,
    ContactForce,
}

pub(crate) const ARROWS: [Arrow; 4] = [
    Arrow::AngularVelocity,
    Arrow::AngularMomentum,
    Arrow::Velocity,
    Arrow::ContactForce,
];

impl Arrow {
    pub(crate) fn symbol(self) -> &'static str {
        match self {
            Arrow::AngularVelocity => "ω",
            Arrow::AngularMomentum => "L",
            Arrow::Velocity => "v",
            Arrow::ContactForce => "F",
        }
    }

    pub(crate) fn unit(self) -> &'static str {
        match self {
            Arrow::AngularVelocity => "rad/s",
            Arrow::AngularMomentum => "g·cm²/s",
            Arrow::Velocity => "cm/s",
            Arrow::ContactForce => "dyn",
        }
    }

    /// x₀: the size drawn `a·log₁₀ 2` long. For the force it is one corner's share of the
    /// die's weight, M·g/8, so a die at rest shows short arrows and an impact long ones.
    /// L is parallel to ω (the cube's inertia is isotropic); its larger x₀ keeps the two
    /// arrows, and their labels, apart.
    pub(crate) fn reference(self, app: &App) -> f64 {
        let p = &app.roll.live.params;
        match self {
            Arrow::AngularVelocity => 1.0,
            Arrow::AngularMomentum => 100.0,
            Arrow::Velocity => 10.0,
            Arrow::ContactForce => p.total_mass() * p.world.gravity / 8.0,
        }
    }

    pub(crate) fn colour(self, app: &App) -> Color {
        app.theme.vector_colours()[self as usize]
    }
}

/// cm: the drawn length of a vector of size `magnitude`.
pub(crate) fn arrow_length(magnitude: f64, reference: f64, half_size: f64) -> f64 {
    if magnitude.is_finite() && magnitude > 0.0 && reference > 0.0 {
        half_size * (1.0 + magnitude / reference).log10()
    } else {
        0.0
    }
}

/// dyn: a corner's contact force as a vector `(friction x, friction y, P)`.
pub(crate) fn force_vector(f: &dicesim_physics::ContactForce) -> Vector3<f64> {
    Vector3::new(f.friction[0], f.friction[1], f.normal + f.damping)
}

/// dyn: the sum of the contact forces on the die.
pub(crate) fn total_force(die: &DieState) -> Vector3<f64> {
    die.forces.iter().map(force_vector).sum()
}

/// The two strokes of an arrow's head at `tip`, `size` cm long, 25° either side of the
/// shaft and drawn in the screen plane so it always shows.
pub(crate) fn head(base: Flat, tip: Flat, size: f64) -> Vec<(Flat, Flat)> {
    let (dx, dy) = (tip.0 - base.0, tip.1 - base.1);
    let n = dx.hypot(dy);
    if n.is_nan() || n <= 1e-9 {
        return Vec::new();
    }
    let (ux, uy) = (dx / n, dy / n);
    let h = size.min(0.5 * n);
    let (c, s) = (25f64.to_radians().cos(), 25f64.to_radians().sin());
    [-1.0, 1.0]
        .into_iter()
        .map(|side| {
            let (bx, by) = (ux * c - uy * side * s, ux * side * s + uy * c);
            (tip, (tip.0 - h * bx, tip.1 - h * by))
        })
        .collect()
}

/// The legend under the die: each arrow's colour and size, then how lengths are scaled.
pub(crate) fn legend(app: &App, width: u16) -> Vec<Line<'static>> {
    let die = &app.roll.live.die;
    let sizes = [
        die.angular_velocity.norm(),
        die.angular_momentum.norm(),
        die.velocity.norm(),
        total_force(die).norm(),
    ];
    // Each arrow's size with its unit where the panel has room for every unit, without
    // the units where not; the scale in as many words as fit.
    let sizes_line = |units: bool, gap: &str| {
        let mut spans = Vec::new();
        for (i, (kind, size)) in ARROWS.iter().zip(sizes).enumerate() {
            let name = if *kind == Arrow::ContactForce {
                "ΣF"
            } else {
                kind.symbol()
            };
            if i > 0 {
                spans.push(Span::raw(gap.to_string()));
            }
            spans.push(Span::styled(
                format!("━{name} "),
                Style::new().fg(kind.colour(app)),
            ));
            let unit = if units {
                format!(" {}", kind.unit())
            } else {
                String::new()
            };
            spans.push(Span::raw(format!("{}{unit}", fmt_num(size))));
        }
        Line::from(spans)
    };
    // Every size with its unit, else without units, else closer together; only then cut.
    let forms = [(true, "  "), (false, "  "), (false, " ")];
    let sizes_line = forms
        .iter()
        .map(|&(units, gap)| sizes_line(units, gap))
        .find(|l| l.width() <= fit::room(width as usize))
        .unwrap_or_else(|| fit::abbreviate(sizes_line(false, " "), width as usize));
    // The scale `a·log₁₀(1 + |x|/x₀)` in words: far above x₀, ten times as big is half a die
    // (a) longer; x₀ itself is drawn a third of that.
    let force = fmt_num(Arrow::ContactForce.reference(app));
    let scale = fit::longest_fitting(
        &[
            format!(
                "arrows: 10× as big is half a die longer; ω 1, L 100, v 10, F {force} (one corner's share of \
                 the weight) are short stubs"
            ),
            format!("arrows: 10× as big is half a die longer; stubs: ω 1, L 100, v 10, F {force}"),
            "arrows: 10× as big is half a die longer".to_string(),
            "10× as big: half a die longer".to_string(),
        ],
        width as usize,
    );
    vec![sizes_line, Line::styled(scale, app.theme.heading())]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tui::panels::die::{Projection, picture, place_labels};
    use crate::tui::tests::fixtures::mid_impact_with;
    use crate::tui::tests::fixtures::twin_scene;
    use crate::tui::vocabulary::solid::inside;
    use crate::tui::vocabulary::theme::{Palette, Theme};
    use ratatui::crossterm::event::KeyCode;
    use ratatui::layout::Rect;

    /// Arrow labels find free cells: each arrow's symbol is placed, off the die, apart from
    /// every other label by at least one blank cell, at the die panel's sizes from the
    /// classroom's 80×24 to a wide screen.
    #[test]
    fn arrow_labels_sit_off_the_die_and_apart() {
        let projector = Theme {
            colour: true,
            palette: Palette::Projector,
        };
        let mut impact = mid_impact_with(projector);
        impact.key(KeyCode::Char('v'));
        let mut twin = twin_scene(projector);
        twin.key(KeyCode::Char('v'));
        for (name, app) in [("mid impact", &impact.app), ("twin", &twin.app)] {
            let touching = app.roll.live.die.forces.iter().filter(|f| f.depth > 0.0).count();
            for (w, h) in [(38, 14), (48, 20), (70, 26)] {
                let view = Projection::new(app, Rect::new(0, 0, w, h));
                let pic = picture(app, &view);
                let placed = place_labels(&pic.labels, &view, &pic.outline);
                let count = |s: &str| placed.iter().filter(|(_, _, l)| l.text == s).count();
                for kind in [Arrow::AngularVelocity, Arrow::AngularMomentum, Arrow::Velocity] {
                    assert_eq!(count(kind.symbol()), 1, "{name} {w}×{h}: {}", kind.symbol());
                }
                assert_eq!(count("F"), touching, "{name} {w}×{h}: one F per touching corner");
                for (c, r, l) in placed.iter().filter(|(_, _, l)| l.movable) {
                    for x in *c..c + l.text.chars().count() as u16 {
                        assert!(
                            !inside(&pic.outline, view.centre_of(x, *r)),
                            "{name} {w}×{h}: {:?} on the die at ({x},{r})",
                            l.text
                        );
                    }
                }
                for (i, (c1, r1, l1)) in placed.iter().enumerate() {
                    for (c2, r2, l2) in &placed[i + 1..] {
                        let (a, b) = (*c1 as i32, *c2 as i32);
                        let (la, lb) = (l1.text.chars().count() as i32, l2.text.chars().count() as i32);
                        let gap = if l1.movable || l2.movable { 1 } else { 0 };
                        let apart = r1 != r2 || a + la + gap <= b || b + lb + gap <= a;
                        assert!(
                            apart,
                            "{name} {w}×{h}: {:?} at ({c1},{r1}) and {:?} at ({c2},{r2})",
                            l1.text, l2.text
                        );
                    }
                }
            }
        }
    }
}
