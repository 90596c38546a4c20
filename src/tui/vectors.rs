//! Arrows on the die (`v`): angular velocity ω and angular momentum L from the centre of
//! mass, the centre-of-mass velocity v, and each touching corner's contact force F.
//!
//! Their sizes span orders of magnitude (a resting corner carries about M·g/8, an impact a
//! hundred times more), so lengths are log-compressed: `a·log₁₀(1 + |x|/x₀)`, with `a` the
//! die's half size and `x₀` a natural unit for each quantity. Directions are exact.

use super::app::App;
use super::camera::Camera;
use super::format::fmt_num;
use crate::worker::DieState;
use nalgebra::Vector3;
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Context, Line as CanvasLine};

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
        let p = &app.live.params;
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
fn force_vector(f: &crate::physics::ContactForce) -> Vector3<f64> {
    Vector3::new(f.friction[0], f.friction[1], f.normal + f.damping)
}

/// dyn: the sum of the contact forces on the die.
fn total_force(die: &DieState) -> Vector3<f64> {
    die.forces.iter().map(force_vector).sum()
}

/// Draws every arrow of `die` on the canvas.
pub(crate) fn draw(ctx: &mut Context, app: &App, cam: &Camera, focus: &Vector3<f64>, die: &DieState) {
    let half = app.live.params.die.half_size;
    let mut arrow = |kind: Arrow, from: Vector3<f64>, v: Vector3<f64>, label: bool| {
        let length = arrow_length(v.norm(), kind.reference(app), half);
        if length <= 0.0 {
            return;
        }
        let tip = from + v.normalize() * length;
        draw_arrow(ctx, cam, focus, &from, &tip, kind.colour(app), 0.2 * half);
        if label {
            let p = cam.project(&tip, focus);
            ctx.print(
                p.x,
                p.y,
                Span::styled(kind.symbol(), Style::new().fg(kind.colour(app))),
            );
        }
    };
    arrow(Arrow::AngularVelocity, die.centre, die.angular_velocity, true);
    arrow(Arrow::AngularMomentum, die.centre, die.angular_momentum, true);
    arrow(Arrow::Velocity, die.centre, die.velocity, true);
    for (corner, f) in die.corners.iter().zip(&die.forces) {
        if f.depth > 0.0 {
            arrow(Arrow::ContactForce, *corner, force_vector(f), false);
        }
    }
}

/// A shaft and a two-stroke head, the head drawn in the screen plane so it always shows.
fn draw_arrow(
    ctx: &mut Context,
    cam: &Camera,
    focus: &Vector3<f64>,
    from: &Vector3<f64>,
    to: &Vector3<f64>,
    colour: Color,
    head: f64,
) {
    let (p, q) = (cam.project(from, focus), cam.project(to, focus));
    if ![p.x, p.y, q.x, q.y].iter().all(|v| v.is_finite()) {
        return;
    }
    ctx.draw(&CanvasLine::new(p.x, p.y, q.x, q.y, colour));
    let (dx, dy) = (q.x - p.x, q.y - p.y);
    let n = dx.hypot(dy);
    if n < 1e-9 {
        return;
    }
    let (ux, uy) = (dx / n, dy / n);
    let h = head.min(0.5 * n);
    for s in [-1.0, 1.0] {
        // 25° either side of the shaft, pointing back from the tip.
        let (c, sn) = (25f64.to_radians().cos(), s * 25f64.to_radians().sin());
        let (bx, by) = (ux * c - uy * sn, ux * sn + uy * c);
        ctx.draw(&CanvasLine::new(q.x, q.y, q.x - h * bx, q.y - h * by, colour));
    }
}

/// The legend under the die: each arrow's colour and size, then how lengths are scaled.
pub(crate) fn legend(app: &App, width: u16) -> Vec<Line<'static>> {
    let die = &app.live.die;
    let sizes = [
        die.angular_velocity.norm(),
        die.angular_momentum.norm(),
        die.velocity.norm(),
        total_force(die).norm(),
    ];
    let wide = width >= 60;
    let mut first = Vec::new();
    for (kind, size) in ARROWS.iter().zip(sizes) {
        let name = if *kind == Arrow::ContactForce {
            "ΣF"
        } else {
            kind.symbol()
        };
        first.push(Span::styled(
            format!("━{name} "),
            Style::new().fg(kind.colour(app)),
        ));
        let unit = if wide {
            format!(" {}", kind.unit())
        } else {
            String::new()
        };
        first.push(Span::raw(format!("{}{unit}  ", fmt_num(size))));
    }
    let scale = if wide {
        format!(
            "length a·log₁₀(1+|x|/x₀), x₀: ω 1, L 100, v 10, F {} (M·g/8)",
            fmt_num(Arrow::ContactForce.reference(app))
        )
    } else {
        "length a·log₁₀(1+|x|/x₀)".to_string()
    };
    vec![Line::from(first), Line::styled(scale, app.theme.heading())]
}
