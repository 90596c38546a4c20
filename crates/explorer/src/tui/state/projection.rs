//! The die panel's view: which part of the view plane its cells show, so that the die (and a
//! twin beside it) is in the picture, and where a cell lies on that plane. The panels draw
//! through it; the mouse handling reads a grab on the die through it.

use super::app::App;
use super::camera::OrbitCamera;
use crate::tui::vocabulary::fit;
use crate::tui::vocabulary::solid::Flat;
use crate::worker::{DieState, Phase};
use dicesim_physics::{Status, UnstableReason, why_it_cannot_settle};
use nalgebra::Vector3;
use ratatui::layout::Rect;
use ratatui::style::Style;

/// How much wider than the camera's own view the panel may open to show a twin beside the
/// die; a twin farther off is left out of the picture and the die stays framed alone.
const MOST_WIDENING: f64 = 4.0;

/// The die panel inside its border: the reason a roll ended on its top rows (when it ended
/// unstable or could not settle), the arrows' legend on its bottom two (when the arrows are
/// on and there is room), and the picture of the die between them.
#[derive(Debug, Clone)]
pub(crate) struct DiePanel {
    /// The reason's wrapped lines, their style and rows.
    pub(crate) reason: Option<(Vec<String>, Style, Rect)>,
    /// The centre's height and the preset's readouts (signed spin, lean, slid), wrapped, on
    /// rows of their own under the reason.
    pub(crate) readouts: Option<(Vec<String>, Rect)>,
    pub(crate) legend: Option<Rect>,
    pub(crate) picture: Rect,
}

/// The parts of the die panel whose inside (its border's inner area) is `body`.
pub(crate) fn die_panel(app: &App, mut body: Rect) -> DiePanel {
    let mut reason = None;
    if let Some((text, style)) = end_reason(app) {
        let lines = fit::wrap(&text, body.width as usize);
        let rows = (lines.len() as u16).min(body.height.saturating_sub(3));
        reason = Some((lines, style, Rect { height: rows, ..body }));
        body.y += rows;
        body.height -= rows;
    }
    // The centre's height and the preset's readouts on rows of their own, over the die
    // rather than on it.
    let mut readouts = None;
    let mut texts = vec![format!("centre {:.2} cm up", app.roll.live.die.centre.z)];
    texts.extend(super::die_screen::readout_texts(
        app.die_screen.readouts,
        &app.roll.live,
    ));
    if body.height >= 4 {
        let lines = fit::wrap(&texts.join(" · "), body.width as usize);
        let rows = (lines.len() as u16).min(2);
        readouts = Some((lines, Rect { height: rows, ..body }));
        body.y += rows;
        body.height -= rows;
    }
    let mut legend = None;
    if app.die_screen.arrows && body.height >= 6 {
        legend = Some(Rect {
            y: body.bottom() - 2,
            height: 2,
            ..body
        });
        body.height -= 2;
    }
    DiePanel {
        reason,
        readouts,
        legend,
        picture: body,
    }
}

/// The view the die panel whose outer area is `panel` draws the die in.
pub(crate) fn die_view(app: &App, panel: Rect) -> Projection {
    let inside = ratatui::widgets::Block::bordered().inner(panel);
    Projection::new(app, die_panel(app, inside).picture)
}

/// Why the roll on screen ended unstable, or could not settle on its table, when it did.
pub(crate) fn end_reason(app: &App) -> Option<(String, Style)> {
    match app.roll.live.phase {
        Phase::Ended(o) if o.status == Status::Unstable => Some((
            format!(
                "unstable: {}",
                UnstableReason::new(&app.roll.live.params, &app.roll.live.initial)
            ),
            app.theme.danger(),
        )),
        Phase::Ended(o) if o.status == Status::Timeout => why_it_cannot_settle(&app.roll.live.params)
            .map(|why| (format!("did not settle: {why}"), app.theme.caution())),
        _ => None,
    }
}

/// The part of the view plane the die panel shows, and the cells it is drawn in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Projection {
    pub(crate) camera: OrbitCamera,
    /// The horizontal point the camera follows (the die's foot, or midway between the die's
    /// and its twin's).
    pub(crate) focus: Vector3<f64>,
    pub(crate) x: (f64, f64),
    pub(crate) y: (f64, f64),
    pub(crate) area: Rect,
}

/// The foot of a die's centre on the table.
fn foot(d: &DieState) -> Vector3<f64> {
    Vector3::new(d.centre.x, d.centre.y, 0.0)
}

impl Projection {
    /// The view of the die in `area`: the die's width in view fixed by the zoom, its height
    /// from the cells' 1:2 aspect, the table kept in the lower third. A twin (the chaos
    /// twin's ghost, a parameter twin's die B) is framed with it: the view centres between
    /// the two and opens wider when they do not both fit, up to [`MOST_WIDENING`] times.
    pub(crate) fn new(app: &App, area: Rect) -> Projection {
        let die = &app.roll.live.die;
        let camera = app.die_screen.camera;
        let half = app.roll.shape.scale;
        // cm of view up per cm across: cells are twice as tall as wide.
        let aspect = 2.0 * area.height as f64 / area.width.max(1) as f64;
        let radius = app.roll.live.params.die.corner_radius;
        let mut width = camera.width_cm(half);
        let mut focus = foot(die);
        let mut dice = vec![die];
        if let Some(twin) = &app.roll.live.twin {
            let both = (foot(die) + foot(&twin.die)) / 2.0;
            let (x, y) = extent(&camera, &both, &[die, &twin.die], radius);
            // The margins a die alone gets: a little table either side, a little sky.
            let needed = (x.1 - x.0 + half).max((y.1 - y.0 + 0.5 * half) / aspect);
            if needed <= MOST_WIDENING * width {
                width = width.max(needed);
                focus = both;
                dice.push(&twin.die);
            }
        }
        let height = width * aspect;
        let (_, (lowest, highest)) = extent(&camera, &focus, &dice, radius);
        let centre_y = if dice.len() > 1 {
            (lowest + highest) / 2.0
        } else {
            camera.project(&die.centre, &focus).y
        }
        .max(0.35 * height);
        // Never above the die's lowest corner: a short panel shows the whole die resting on
        // the table and gives up sky instead; nor below a twin's top.
        let mut bottom = (centre_y - height / 2.0).min(lowest - 0.04 * height);
        if dice.len() > 1 {
            bottom = bottom
                .max(highest + 0.25 * half - height)
                .min(lowest - 0.04 * height);
        }
        Projection {
            camera,
            focus,
            x: (-width / 2.0, width / 2.0),
            y: (bottom, bottom + height),
            area,
        }
    }

    pub(crate) fn flat(&self, p: &Vector3<f64>) -> Flat {
        let q = self.camera.project(p, &self.focus);
        (q.x, q.y)
    }

    /// The cell (column, row from the top, inside `area`) a point falls in, if in view.
    pub(crate) fn cell(&self, p: Flat) -> Option<(u16, u16)> {
        let fx = (p.0 - self.x.0) / (self.x.1 - self.x.0);
        let fy = (self.y.1 - p.1) / (self.y.1 - self.y.0);
        let (w, h) = (self.area.width as f64, self.area.height as f64);
        ((0.0..1.0).contains(&fx) && (0.0..1.0).contains(&fy)).then_some(((fx * w) as u16, (fy * h) as u16))
    }

    /// The point at the middle of a cell.
    pub(crate) fn centre_of(&self, col: u16, row: u16) -> Flat {
        let (w, h) = (self.area.width as f64, self.area.height as f64);
        (
            self.x.0 + (self.x.1 - self.x.0) * (col as f64 + 0.5) / w,
            self.y.1 - (self.y.1 - self.y.0) * (row as f64 + 0.5) / h,
        )
    }

    /// cm of the view plane one cell spans, across and up.
    pub(crate) fn cell_size(&self) -> (f64, f64) {
        (
            (self.x.1 - self.x.0) / self.area.width.max(1) as f64,
            (self.y.1 - self.y.0) / self.area.height.max(1) as f64,
        )
    }

    /// cm between neighbouring Braille dots, the finer of the two directions.
    pub(crate) fn dot(&self) -> f64 {
        let (across, up) = self.cell_size();
        (across / 2.0).min(up / 4.0)
    }
}

/// The view-plane box of `dice`' corners seen from `focus`: (across, up) ranges, a rounded
/// body's spheres reaching `radius` past their centres.
fn extent(
    camera: &OrbitCamera,
    focus: &Vector3<f64>,
    dice: &[&DieState],
    radius: f64,
) -> ((f64, f64), (f64, f64)) {
    let mut x = (f64::INFINITY, f64::NEG_INFINITY);
    let mut y = (f64::INFINITY, f64::NEG_INFINITY);
    for p in dice.iter().flat_map(|d| d.corners.iter()) {
        let q = camera.project(p, focus);
        x = (x.0.min(q.x - radius), x.1.max(q.x + radius));
        y = (y.0.min(q.y - radius), y.1.max(q.y + radius));
    }
    (x, y)
}
