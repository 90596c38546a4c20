//! The die panel: a solid die seen by the orbiting camera, the box (with its pips) or a
//! polyhedral die (with its numbers, [`polyhedral`]).
//!
//! A die is convex, so a face is seen exactly when its outward normal points towards the
//! viewer, and an edge exactly when it borders a seen face. Everything behind the die (the
//! floor tiles, its shadow, the chaos twin's ghost) is clipped against the die's outline, so
//! nothing shows through it. Seen faces are filled with a shade of their angle to the viewer
//! (in colour) and carry their pips as on a real die, opposite faces summing to 7; the face
//! up is tinted and framed.
//!
//! The picture is built once as a list of strokes, pips, fills and labels, then drawn either
//! with Braille dots (a ratatui canvas) or with ASCII slope characters (`-` `|` `/` `\`).
//! Labels are placed last on a grid of taken cells, so none ever covers another.

pub(crate) mod polyhedral;
pub(crate) mod vectors;

use crate::tui::state::app::App;
use crate::tui::state::camera::OrbitCamera;
use crate::tui::state::die_screen::Drawing;
pub(crate) use crate::tui::state::projection::{Projection, die_panel};
use crate::tui::state::throw::Throw;
use crate::tui::vocabulary::format::{face_text, fmt_num};
use crate::tui::vocabulary::solid::{
    Body, DieShape, EDGES, FACE_CORNERS, Flat, Hull, Solid, convex_hull, inside, outside_parts,
};
use crate::worker::{DieState, TwinSnapshot};
use dicesim_physics::InitialCondition;
use dicesim_physics::{face_frame, pip_centres};
use nalgebra::Vector3;
use ratatui::Frame;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Line as CanvasLine, Points};
use ratatui::widgets::{Block, Clear, Paragraph};
use vectors::Arrow;

/// An undrilled die's drawn pip radius, in units of the face's smaller half size.
const PIP_RADIUS: f64 = 0.17;

/// Where the frame marking the face up sits, in units of the face's half sizes from its
/// centre (never past the flat part of a rounded face).
const UP_FRAME: f64 = 0.82;

/// A line on the view plane, cm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Stroke {
    pub(crate) a: Flat,
    pub(crate) b: Flat,
    pub(crate) colour: Color,
}

/// Text anchored at a point of the view plane; placed on a free cell near it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Label {
    pub(crate) at: Flat,
    pub(crate) text: String,
    pub(crate) style: Style,
    /// Whether the label may move away from its anchor to find free cells: then it never
    /// sits on the die (where it would hide a face and read as one of its marks) nor right
    /// beside another label (`ω` and `v` touching read as one word, `ωv`).
    pub(crate) movable: bool,
}

/// The die panel's picture, before it is drawn in either marker.
#[derive(Debug, Clone, Default)]
pub(crate) struct Picture {
    /// Strokes in drawing order: the floor (tiles, shadow, ghost), the die, the arrows.
    pub(crate) layers: [Vec<Stroke>; 3],
    /// Pip discs: centre, the points that fill it, colour (drawn with the die).
    pub(crate) pips: Vec<(Flat, Vec<Flat>, Color)>,
    /// The shadow's outline and background, where a theme paints one.
    pub(crate) shadow: Option<(Vec<Flat>, Color)>,
    /// The seen faces' outlines and backgrounds.
    pub(crate) faces: Vec<(Vec<Flat>, Color)>,
    /// The die's outline: cells inside it are the die's own.
    pub(crate) outline: Vec<Flat>,
    /// In order of importance: earlier labels get the cells they want.
    pub(crate) labels: Vec<Label>,
}

/// Which faces (0-based) of the body the camera sees, and how squarely.
fn seen_faces(camera: &OrbitCamera, body: &Solid) -> [f64; 6] {
    std::array::from_fn(|f| camera.facing(&body.normal(f)))
}

/// The body of a die state (the live die's or the twin's), with the setup's sizes.
pub(crate) fn body_of(app: &App, die: &DieState) -> Body {
    Body::new(
        &app.roll.live.params,
        &app.roll.shape,
        &die.corners,
        die.centre,
        &die.orientation,
    )
}

/// The box of the die on screen (a box die's only).
#[cfg(test)]
fn solid(app: &App, die: &DieState) -> Solid {
    Solid::new(&app.roll.live.params.die, &die.corners)
}

/// The twin's body: a parameter twin's is the setup's with B's values, so a rounder or
/// drilled B is drawn as B is, not as A.
pub(crate) fn twin_body(app: &App, twin: &TwinSnapshot) -> Body {
    let mut params = app.roll.live.params;
    let mut start = InitialCondition::DEFAULT;
    for (key, value) in &twin.differs_by {
        key.set(&mut params, &mut start, *value);
    }
    // B's solid is A's unless B differs in the die itself (its own, made for the twin alone).
    let own;
    let shape = if params.die == app.roll.live.params.die {
        &app.roll.shape
    } else {
        own = DieShape::of(&params);
        &own
    };
    Body::new(
        &params,
        shape,
        &twin.die.corners,
        twin.die.centre,
        &twin.die.orientation,
    )
}

/// Edges that border a seen face: exactly the visible ones of a convex body.
fn visible_edges(facing: &[f64; 6]) -> impl Iterator<Item = (usize, usize)> + '_ {
    EDGES.into_iter().filter(move |&(a, b)| {
        (0..6).any(|f| facing[f] > 0.0 && FACE_CORNERS[f].contains(&a) && FACE_CORNERS[f].contains(&b))
    })
}

/// Whether corner `k` lies on a seen face.
fn corner_seen(facing: &[f64; 6], k: usize) -> bool {
    (0..6).any(|f| facing[f] > 0.0 && FACE_CORNERS[f].contains(&k))
}

impl Picture {
    /// The strokes of `a`–`b` not hidden by the die, onto layer `layer`.
    fn behind(&mut self, layer: usize, a: Flat, b: Flat, colour: Color) {
        if ![a.0, a.1, b.0, b.1].iter().all(|v| v.is_finite()) {
            return;
        }
        for (a, b) in outside_parts(&self.outline, a, b) {
            self.layers[layer].push(Stroke { a, b, colour });
        }
    }

    fn stroke(&mut self, layer: usize, a: Flat, b: Flat, colour: Color) {
        if [a.0, a.1, b.0, b.1].iter().all(|v| v.is_finite()) {
            self.layers[layer].push(Stroke { a, b, colour });
        }
    }

    fn label(&mut self, at: Flat, text: impl Into<String>, style: Style, movable: bool) {
        self.labels.push(Label {
            at,
            text: text.into(),
            style,
            movable,
        });
    }
}

/// Whether the camera of `view` sees corner `k` of the die on screen.
#[cfg(test)]
pub(crate) fn corner_is_seen(app: &App, view: &Projection, k: usize) -> bool {
    corner_seen(&seen_faces(&view.camera, &solid(app, &app.roll.live.die)), k)
}

/// The picture of the die panel: pure geometry of the app state.
pub(crate) fn picture(app: &App, view: &Projection) -> Picture {
    match body_of(app, &app.roll.live.die) {
        Body::Box(body) => box_picture(app, view, &body),
        Body::Hull(hull) => hull_picture(app, view, &hull),
    }
}

/// The picture of the box (the paper's die and every real die built on it), with its pips.
fn box_picture(app: &App, view: &Projection, body: &Solid) -> Picture {
    let die = &app.roll.live.die;
    let half = app.roll.shape.scale;
    let mut pic = Picture {
        outline: body.outline(|p| view.flat(p)),
        ..Picture::default()
    };
    let facing = seen_faces(&view.camera, body);
    let contact: [bool; 8] = std::array::from_fn(|k| die.forces[k].depth > 0.0);
    corner_marks(&mut pic, app, view, body, &facing, &contact);
    floor(
        &mut pic,
        app,
        view,
        shadow_points(body, view),
        body.lowest(),
        half,
    );
    // The die: its seen faces filled, their edges, pips and the frame of the face up.
    for f in (0..6).filter(|&f| facing[f] > 0.0) {
        seen_face(&mut pic, app, view, body, &facing, f);
    }
    die_edges(&mut pic, app, view, body, &facing, &contact);
    if let Some(low) = app.die_screen.face_pair {
        pair_axis(&mut pic, app, view, body, low);
    }
    if app.die_screen.arrows {
        arrows(&mut pic, app, view, die);
    }
    if let Some(aim) = app.die_screen.throw {
        throw_aim(&mut pic, app, view, die, &aim);
    }
    pic
}

/// The picture of a polyhedral die (the box's is [`box_picture`]): its seen faces filled (the
/// face up tinted), its seen edges, and the numbers on them.
fn hull_picture(app: &App, view: &Projection, hull: &Hull) -> Picture {
    let t = &app.theme;
    let die = &app.roll.live.die;
    let half = app.roll.shape.scale;
    let mut pic = Picture {
        outline: hull.outline(|p| view.flat(p)),
        ..Picture::default()
    };
    let facing = polyhedral::facing(hull, &view.camera);
    let shape = hull.die.shape();
    let seen_vertex = |k: usize| {
        shape
            .faces()
            .iter()
            .zip(&facing)
            .any(|(face, &f)| f > 0.0 && face.vertices.contains(&k))
    };
    let contact = |k: usize| die.forces.get(k).is_some_and(|f| f.depth > 0.0);
    // A dot on each seen vertex in contact, before anything else takes its cell.
    let dot = if app.die_screen.drawing == Drawing::Ascii {
        "@"
    } else {
        "●"
    };
    for k in (0..hull.vertices.len()).filter(|&k| contact(k) && seen_vertex(k)) {
        pic.label(view.flat(&hull.vertices[k]), dot, t.contact(), false);
    }
    let feet: Vec<Flat> = hull
        .vertices
        .iter()
        .map(|p| view.flat(&Vector3::new(p.x, p.y, 0.0)))
        .collect();
    floor(&mut pic, app, view, feet, hull.lowest(), half);
    // The seen faces filled, the face up tinted where the die is read at its top face.
    let up = hull.face_number(0).is_some().then(|| hull.face_most_nearly_up());
    for (f, face) in shape.faces().iter().enumerate().filter(|&(f, _)| facing[f] > 0.0) {
        if let Some(fill) = t.face_fill(facing[f], Some(f) == up) {
            let corners: Vec<Flat> = face
                .vertices
                .iter()
                .map(|&k| view.flat(&hull.vertices[k]))
                .collect();
            pic.faces.push((convex_hull(&corners), fill));
        }
    }
    for (a, b) in polyhedral::seen_edges(hull, &view.camera) {
        let colour = if contact(a) || contact(b) {
            t.contact_colour()
        } else {
            t.die()
        };
        pic.stroke(
            1,
            view.flat(&hull.vertices[a]),
            view.flat(&hull.vertices[b]),
            colour,
        );
    }
    // The numbers, the one read first, then the most squarely seen: where two would overlap
    // or touch on a row the later one gives way, so no number is drawn over another and two
    // never read as one (a d4's `1` beside a `1` would read 11).
    let mut taken: Vec<(u16, u16, u16)> = Vec::new();
    for (at, text, read) in polyhedral::numbers(app.roll.live.params.die.kind, hull, &view.camera) {
        let Some((col, row)) = view.cell(view.flat(&at)) else {
            continue;
        };
        let end = col + text.chars().count() as u16;
        if taken.iter().any(|&(r, a, b)| r == row && col <= b && a <= end) {
            continue;
        }
        taken.push((row, col, end));
        let style = Style::new().fg(t.die()).add_modifier(Modifier::BOLD);
        let style = if read {
            style.add_modifier(Modifier::UNDERLINED)
        } else {
            style
        };
        pic.label(view.flat(&at), text, style, false);
    }
    if app.die_screen.arrows {
        arrows(&mut pic, app, view, die);
    }
    if let Some(aim) = app.die_screen.throw {
        throw_aim(&mut pic, app, view, die, &aim);
    }
    pic
}

/// A dot on each corner in contact, and a loaded die's heavy corners.
fn corner_marks(
    pic: &mut Picture,
    app: &App,
    view: &Projection,
    body: &Solid,
    facing: &[f64; 6],
    contact: &[bool; 8],
) {
    let t = &app.theme;
    for k in (0..8).filter(|&k| contact[k] && corner_seen(facing, k)) {
        let dot = if app.die_screen.drawing == Drawing::Ascii {
            "@"
        } else {
            "●"
        };
        pic.label(view.flat(&body.foot_of_sphere(k)), dot, t.contact(), false);
    }
    // A loaded die's extra masses: a mark on each seen heavy corner, and its mass beside
    // it (also for a corner behind the die, whose mark would be hidden).
    let extra = app.roll.live.params.die.extra_corner_mass;
    for k in (0..8).filter(|&k| extra[k] > 0.0) {
        let at = view.flat(&body.sharp_corner(k));
        if corner_seen(facing, k) {
            let mark = if app.die_screen.drawing == Drawing::Ascii {
                "#"
            } else {
                "◆"
            };
            pic.label(at, mark, t.heavy(), false);
        }
        pic.label(at, format!("+{} g", fmt_num(extra[k])), t.heavy(), true);
    }
}

/// The floor: tiles, the shadow straight below (the hull of `shadow`, the body's points
/// dropped onto the table), the drop line from the body's `lowest` point, all behind the
/// die; and the twin's ghost.
fn floor(
    pic: &mut Picture,
    app: &App,
    view: &Projection,
    shadow: Vec<Flat>,
    lowest: Vector3<f64>,
    half: f64,
) {
    let t = &app.theme;
    ground(pic, app, view, half);
    let foot = |p: &Vector3<f64>| Vector3::new(p.x, p.y, 0.0);
    let shadow = convex_hull(&shadow);
    if let Some(fill) = t.shadow_fill() {
        pic.shadow = Some((shadow.clone(), fill));
    }
    for i in 0..shadow.len() {
        pic.behind(0, shadow[i], shadow[(i + 1) % shadow.len()], t.shadow());
    }
    if lowest.z > 0.02 * half {
        pic.behind(0, view.flat(&lowest), view.flat(&foot(&lowest)), t.shadow());
    }
    if let Some(twin) = &app.roll.live.twin {
        ghost(pic, app, view, twin);
    }
}

/// Seen face `f`: filled, its pips, and the frame of the face up.
fn seen_face(pic: &mut Picture, app: &App, view: &Projection, body: &Solid, facing: &[f64; 6], f: usize) {
    let t = &app.theme;
    let die = &app.roll.live.die;
    let drilled = app.roll.live.params.die.is_drilled();
    let face = f as u8 + 1;
    let up = face == die.face_up;
    let flat_part = body.flat_face(f).map(|p| view.flat(&p));
    // A face of the marked pair takes its pair's tint, the face up or not.
    let pair = app
        .die_screen
        .face_pair
        .filter(|&low| face == low || face == 7 - low)
        .map(|low| usize::from(face != low));
    let fill = match pair {
        Some(which) => t.pair_fill(facing[f], which),
        None => t.face_fill(facing[f], up),
    };
    if let Some(fill) = fill {
        pic.faces.push((convex_hull(&flat_part), fill));
    }
    // The face's two edge directions, world, and its half sizes along them, cm.
    let [normal, e1, e2] = face_frame(face);
    let (u, w) = (body.direction(e1), body.direction(e2));
    let size = |e: [f64; 3]| (0..3).map(|i| e[i].abs() * body.half_sizes[i]).sum::<f64>();
    let (a1, a2) = (size(e1), size(e2));
    let pip_radius = if drilled {
        0.5 * app.roll.live.params.die.pip_diameter
    } else {
        PIP_RADIUS * a1.min(a2)
    };
    let n = ((2.0 * pip_radius / (0.5 * view.dot())).ceil() as usize).clamp(2, 40);
    for centre in pip_centres(body.half_sizes, face) {
        let centre = body.point(centre);
        let mut disc = Vec::with_capacity(n * n);
        for i in 0..=n {
            for j in 0..=n {
                let (da, db) = (
                    pip_radius * (2.0 * i as f64 / n as f64 - 1.0),
                    pip_radius * (2.0 * j as f64 / n as f64 - 1.0),
                );
                if da * da + db * db <= pip_radius * pip_radius {
                    disc.push(view.flat(&(centre + da * u + db * w)));
                }
            }
        }
        pic.pips.push((view.flat(&centre), disc, t.die()));
    }
    if up {
        let centre = body.centre + body.direction(normal) * size(normal);
        let flat = |a: f64| (a - body.radius) * 0.95;
        let (s1, s2) = ((UP_FRAME * a1).min(flat(a1)), (UP_FRAME * a2).min(flat(a2)));
        let on_face = |x: f64, y: f64| view.flat(&(centre + x * u + y * w));
        let frame = [
            on_face(-s1, -s2),
            on_face(-s1, s2),
            on_face(s1, s2),
            on_face(s1, -s2),
        ];
        for i in 0..4 {
            pic.stroke(1, frame[i], frame[(i + 1) % 4], t.die());
        }
    }
}

/// The die's seen edges, those at a corner in contact in the contact colour.
fn die_edges(
    pic: &mut Picture,
    app: &App,
    view: &Projection,
    body: &Solid,
    facing: &[f64; 6],
    contact: &[bool; 8],
) {
    let t = &app.theme;
    let corners: Vec<Flat> = app.roll.live.die.corners.iter().map(|c| view.flat(c)).collect();
    let edge_colour = |a: usize, b: usize| {
        if contact[a] || contact[b] {
            t.contact_colour()
        } else {
            t.die()
        }
    };
    if body.radius > 0.0 {
        // A rounded die: its outline with the corners' arcs, and each seen face's flat part,
        // so the rounded edges show as the bands between neighbouring faces.
        let outline = pic.outline.clone();
        for i in 0..outline.len() {
            pic.stroke(1, outline[i], outline[(i + 1) % outline.len()], t.die());
        }
        for f in (0..6).filter(|&f| facing[f] > 0.0) {
            let flat_part = body.flat_face(f).map(|p| view.flat(&p));
            for (i, j) in FLAT_EDGES {
                let colour = edge_colour(FACE_CORNERS[f][i], FACE_CORNERS[f][j]);
                pic.stroke(1, flat_part[i], flat_part[j], colour);
            }
        }
    } else {
        for (a, b) in visible_edges(facing) {
            pic.stroke(1, corners[a], corners[b], edge_colour(a, b));
        }
    }
}

/// The body axis through the marked face pair (`low` and its opposite): from the centre out
/// past each face, its number at the tip, so a flip of the pair shows as the axis turning over.
fn pair_axis(pic: &mut Picture, app: &App, view: &Projection, body: &Solid, low: u8) {
    for face in [low, 7 - low] {
        let normal = face_frame(face)[0];
        let reach: f64 = (0..3).map(|i| normal[i].abs() * body.half_sizes[i]).sum();
        let tip = body.centre + body.direction(normal) * (1.7 * reach);
        pic.stroke(2, view.flat(&body.centre), view.flat(&tip), app.theme.die());
        pic.label(view.flat(&tip), face.to_string(), app.theme.heading(), true);
    }
}

/// Throw mode's aim: `+` where the die is grabbed and an arrow to where the drag has got,
/// in the velocity's colour (it is the velocity the throw gives).
fn throw_aim(pic: &mut Picture, app: &App, view: &Projection, die: &DieState, aim: &Throw) {
    let half = app.roll.shape.scale;
    let centre = view.flat(&die.centre);
    let grab = (centre.0 + aim.grab.0, centre.1 + aim.grab.1);
    let tip = (grab.0 + aim.drag.0, grab.1 + aim.drag.1);
    let colour = Arrow::Velocity.colour(app);
    if aim.drag != (0.0, 0.0) {
        pic.stroke(2, grab, tip, colour);
        for (a, b) in vectors::head(grab, tip, 0.2 * half) {
            pic.stroke(2, a, b, colour);
        }
    }
    pic.label(
        grab,
        "+",
        Style::new().fg(colour).add_modifier(Modifier::BOLD),
        false,
    );
}

/// The sides of a face's flat part, by index into its corners in [`FACE_CORNERS`] order
/// (the first two and the first and third differ along one edge each).
const FLAT_EDGES: [(usize, usize); 4] = [(0, 1), (1, 3), (3, 2), (2, 0)];

/// The points whose hull is the body's shadow straight below it: the corner spheres' feet,
/// and for a rounded die the rims of the discs they cast.
fn shadow_points(body: &Solid, view: &Projection) -> Vec<Flat> {
    let feet = body.spheres.map(|c| Vector3::new(c.x, c.y, 0.0));
    if body.radius <= 0.0 {
        return feet.iter().map(|p| view.flat(p)).collect();
    }
    const RIM: usize = 32;
    feet.iter()
        .flat_map(|p| {
            (0..RIM).map(move |i| {
                let (s, c) = (std::f64::consts::TAU * i as f64 / RIM as f64).sin_cos();
                view.flat(&(p + Vector3::new(c, s, 0.0) * body.radius))
            })
        })
        .collect()
}

/// A patch of floor tiles around the die, fixed to the world so the die's travel shows
/// against it; small enough that the die stays the thing to look at.
fn ground(pic: &mut Picture, app: &App, view: &Projection, half: f64) {
    let view_width = view.x.1 - view.x.0;
    let side = 2.0 * half;
    let spacing = 2.0 * side * (view_width / (6.0 * side)).round().max(1.0);
    let reach = 0.45 * view_width;
    let colour = app.theme.ground();
    let focus = view.focus;
    let cells = |c: f64| {
        (
            ((c - reach) / spacing).ceil() as i64,
            ((c + reach) / spacing).floor() as i64,
        )
    };
    let ((x0, x1), (y0, y1)) = (cells(focus.x), cells(focus.y));
    let (xa, xb) = (focus.x - reach, focus.x + reach);
    let (ya, yb) = (focus.y - reach, focus.y + reach);
    for i in x0..=x1 {
        let x = i as f64 * spacing;
        let (a, b) = (Vector3::new(x, ya, 0.0), Vector3::new(x, yb, 0.0));
        pic.behind(0, view.flat(&a), view.flat(&b), colour);
    }
    for j in y0..=y1 {
        let y = j as f64 * spacing;
        let (a, b) = (Vector3::new(xa, y, 0.0), Vector3::new(xb, y, 0.0));
        pic.behind(0, view.flat(&a), view.flat(&b), colour);
    }
}

/// The twin's die (chaos or parameter twin) as a ghost: its own visible edges (a rounded die's outline and flat
/// faces), hidden where the die covers them.
fn ghost(pic: &mut Picture, app: &App, view: &Projection, snapshot: &TwinSnapshot) {
    let colour = app.theme.ghost();
    let twin = &snapshot.die;
    let body = match twin_body(app, snapshot) {
        Body::Box(body) => body,
        Body::Hull(hull) => {
            for (a, b) in polyhedral::seen_edges(&hull, &view.camera) {
                pic.behind(
                    0,
                    view.flat(&hull.vertices[a]),
                    view.flat(&hull.vertices[b]),
                    colour,
                );
            }
            let name = if snapshot.differs_by.is_empty() {
                "twin"
            } else {
                "B"
            };
            pic.label(view.flat(&twin.centre), name, Style::new().fg(colour), true);
            return;
        }
    };
    let facing = seen_faces(&view.camera, &body);
    if body.radius > 0.0 {
        let outline = body.outline(|p| view.flat(p));
        for i in 0..outline.len() {
            pic.behind(0, outline[i], outline[(i + 1) % outline.len()], colour);
        }
        for f in (0..6).filter(|&f| facing[f] > 0.0) {
            let flat_part = body.flat_face(f).map(|p| view.flat(&p));
            for (i, j) in FLAT_EDGES {
                pic.behind(0, flat_part[i], flat_part[j], colour);
            }
        }
    } else {
        for (a, b) in visible_edges(&facing) {
            pic.behind(
                0,
                view.flat(&twin.corners[a]),
                view.flat(&twin.corners[b]),
                colour,
            );
        }
    }
    let parameter_twin = !snapshot.differs_by.is_empty();
    let name = if parameter_twin { "B" } else { "twin" };
    pic.label(view.flat(&twin.centre), name, Style::new().fg(colour), true);
}

/// ω, L and v from the centre, F from each touching corner, each with its symbol at the tip.
fn arrows(pic: &mut Picture, app: &App, view: &Projection, die: &DieState) {
    let half = app.roll.shape.scale;
    let mut arrow = |kind: Arrow, from: Vector3<f64>, v: Vector3<f64>, named: bool| {
        let length = vectors::arrow_length(v.norm(), kind.reference(app), half);
        if length <= 0.0 {
            return;
        }
        let colour = kind.colour(app);
        let tip = view.flat(&(from + v.normalize() * length));
        let base = view.flat(&from);
        pic.stroke(2, base, tip, colour);
        for (a, b) in vectors::head(base, tip, 0.2 * half) {
            pic.stroke(2, a, b, colour);
        }
        if !named {
            return;
        }
        pic.label(
            tip,
            kind.symbol(),
            Style::new().fg(colour).add_modifier(Modifier::BOLD),
            true,
        );
    };
    arrow(Arrow::AngularVelocity, die.centre, die.angular_velocity, true);
    arrow(Arrow::AngularMomentum, die.centre, die.angular_momentum, true);
    arrow(Arrow::Velocity, die.centre, die.velocity, true);
    // Every touching corner's force is drawn, its symbol only at the largest: four `F`s
    // side by side on a flat landing hide the die more than they say.
    let largest = die
        .forces
        .iter()
        .enumerate()
        .filter(|(_, f)| f.depth > 0.0)
        .max_by(|a, b| {
            vectors::force_vector(a.1)
                .norm()
                .total_cmp(&vectors::force_vector(b.1).norm())
        })
        .map(|(k, _)| k);
    for (k, (corner, f)) in die.corners.iter().zip(&die.forces).enumerate() {
        if f.depth > 0.0 {
            arrow(
                Arrow::ContactForce,
                *corner,
                vectors::force_vector(f),
                Some(k) == largest,
            );
        }
    }
}

/// The ASCII character that draws a stroke of this direction on cells twice as tall as wide.
fn slope_char(dx_cells: f64, dy_cells: f64) -> char {
    // Screen units: a cell is about twice as tall as it is wide.
    let angle = (2.0 * dy_cells).atan2(dx_cells).to_degrees().rem_euclid(180.0);
    match angle {
        a if !(22.5..157.5).contains(&a) => '-',
        a if (67.5..112.5).contains(&a) => '|',
        a if a < 90.0 => '/',
        _ => '\\',
    }
}

/// Draws the picture's strokes and pips in ASCII slope characters straight into `buf`.
fn draw_ascii(pic: &Picture, view: &Projection, buf: &mut Buffer) {
    let area = view.area;
    let (w, h) = (area.width as f64, area.height as f64);
    let to_cells = |p: Flat| {
        (
            (p.0 - view.x.0) / (view.x.1 - view.x.0) * w,
            (view.y.1 - p.1) / (view.y.1 - view.y.0) * h,
        )
    };
    let mut put = |cx: f64, cy: f64, ch: char, colour: Color| {
        if cx >= 0.0 && cy >= 0.0 && cx < w && cy < h {
            let cell = &mut buf[(area.x + cx as u16, area.y + cy as u16)];
            cell.set_char(ch).set_fg(colour);
        }
    };
    for (layer, strokes) in pic.layers.iter().enumerate() {
        for s in strokes {
            let (a, b) = (to_cells(s.a), to_cells(s.b));
            // Screen y grows downwards; the slope is read with y up.
            let ch = slope_char(b.0 - a.0, a.1 - b.1);
            let n = ((b.0 - a.0).abs().max((b.1 - a.1).abs()) * 2.0).ceil().max(1.0) as usize;
            for i in 0..=n {
                let f = i as f64 / n as f64;
                put(a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1), ch, s.colour);
            }
        }
        if layer == 1 {
            for (centre, _, colour) in &pic.pips {
                let c = to_cells(*centre);
                put(c.0, c.1, 'o', *colour);
            }
        }
    }
}

/// Draws the picture's strokes and pips with Braille dots.
fn draw_braille(pic: &Picture, view: &Projection, frame: &mut Frame) {
    let canvas = Canvas::default()
        .marker(Marker::Braille)
        .x_bounds([view.x.0, view.x.1])
        .y_bounds([view.y.0, view.y.1])
        .paint(|ctx| {
            for (layer, strokes) in pic.layers.iter().enumerate() {
                for s in strokes {
                    ctx.draw(&CanvasLine::new(s.a.0, s.a.1, s.b.0, s.b.1, s.colour));
                }
                if layer == 1 {
                    for (_, disc, colour) in &pic.pips {
                        ctx.draw(&Points {
                            coords: disc,
                            color: *colour,
                        });
                    }
                }
                ctx.layer();
            }
        });
    frame.render_widget(canvas, view.area);
}

/// Fills the backgrounds: each cell whose middle lies on a seen face takes its shade, and
/// the shadow shows where the die does not cover it.
fn draw_fills(pic: &Picture, view: &Projection, buf: &mut Buffer) {
    for row in 0..view.area.height {
        for col in 0..view.area.width {
            let p = view.centre_of(col, row);
            let fill = if inside(&pic.outline, p) {
                pic.faces.iter().find(|(outline, _)| inside(outline, p))
            } else {
                pic.shadow.as_ref().filter(|(outline, _)| inside(outline, p))
            };
            if let Some((_, colour)) = fill {
                buf[(view.area.x + col, view.area.y + row)].set_bg(*colour);
            }
        }
    }
}

/// Where a label of `len` characters may go relative to its anchor's cell, nearest first:
/// on it, beside it, above and below, then in widening rings.
fn offsets(len: i32, reach: i32) -> impl Iterator<Item = (i32, i32)> {
    let near = [
        (0, 0),
        (1, 0),
        (-len, 0),
        (0, -1),
        (0, 1),
        (1, -1),
        (1, 1),
        (-len, -1),
        (-len, 1),
    ];
    let rings = (2..=reach).flat_map(move |r| {
        (-r..=r).flat_map(move |dr| {
            (-r - len..=r).filter_map(move |dc| {
                let ring = dr.abs() == r || dc == -r - len || dc == r;
                ring.then_some((dc, dr))
            })
        })
    });
    near.into_iter().chain(rings)
}

/// Places the labels in order, each on the first free cells near its anchor: never on a
/// cell an earlier label took, never past the panel's edge, and a movable label never on the
/// die nor touching another label.
pub(crate) fn place_labels(labels: &[Label], view: &Projection, outline: &[Flat]) -> Vec<(u16, u16, Label)> {
    let (w, h) = (view.area.width, view.area.height);
    let mut taken = vec![false; w as usize * h as usize];
    let mut placed = Vec::new();
    for label in labels {
        let anchor = if label.movable {
            // Anchors just outside the view (an arrow's tip) come back to its edge.
            let x = label
                .at
                .0
                .clamp(view.x.0, view.x.1 - 1e-9 * (view.x.1 - view.x.0));
            let y = label
                .at
                .1
                .clamp(view.y.0 + 1e-9 * (view.y.1 - view.y.0), view.y.1);
            view.cell((x, y))
        } else {
            view.cell(label.at)
        };
        let Some((col, row)) = anchor else { continue };
        let len = label.text.chars().count() as i32;
        let taken_at = |x: i32, r: i32| x >= 0 && x < w as i32 && taken[r as usize * w as usize + x as usize];
        let free = |c: i32, r: i32| {
            c >= 0
                && r >= 0
                && c + len <= w as i32
                && r < h as i32
                && (c..c + len).all(|x| {
                    !(taken_at(x, r) || label.movable && inside(outline, view.centre_of(x as u16, r as u16)))
                })
                && !(label.movable && (taken_at(c - 1, r) || taken_at(c + len, r)))
        };
        let reach = if label.movable { w.max(h) as i32 } else { 0 };
        let Some((dc, dr)) = offsets(len, reach)
            .take(if label.movable { usize::MAX } else { 1 })
            .find(|&(dc, dr)| free(col as i32 + dc, row as i32 + dr))
        else {
            continue;
        };
        let (c, r) = ((col as i32 + dc) as u16, (row as i32 + dr) as u16);
        for x in c..c + len as u16 {
            taken[r as usize * w as usize + x as usize] = true;
        }
        placed.push((c, r, label.clone()));
    }
    placed
}

/// cos 50°: a face up tilted further than this from the vertical is no face up (a cube's
/// most nearly up face is at most 54.7° off, when a corner points straight up).
const CORNER_UP_COS: f64 = 0.642_787_609_686_539_3;

/// The die panel: title, the solid die, and the arrows' legend under it when they are on.
pub(crate) fn render(app: &App, area: Rect, frame: &mut Frame) {
    let t = &app.theme;
    let die = &app.roll.live.die;
    let body = body_of(app, die);
    let lowest = body.lowest().z;
    let face_up = match &body {
        // On a corner no face is up: the most nearly up one is tilted past 50° (54.7° with
        // the long diagonal upright), and which it is changes as the die spins about that corner.
        Body::Box(body) if body.normal(die.face_up as usize - 1).z < CORNER_UP_COS => {
            "face up –, on a corner".to_string()
        }
        Body::Box(_) => format!("face up {}", die.face_up),
        Body::Hull(_) => format!(
            "face up {}",
            face_text(app.roll.live.params.die.kind, die.face_up.into())
        ),
    };
    // The face up matters most (the lesson's question), then the twin's, then when the face
    // was decided (the status line says it too), then the height: once the face is decided,
    // the lowest corner makes room.
    let mut title = vec![
        (0, vec![Span::styled(" die ", t.heading())]),
        (0, vec![Span::raw(format!("· {face_up} "))]),
    ];
    if let Some(t_s) = decided_at(app) {
        title.push((2, vec![Span::raw(format!("· face decided {t_s:.3} s "))]));
    }
    title.push((3, vec![Span::raw(format!("· lowest corner {lowest:.2} cm "))]));
    let room = area.width.saturating_sub(2) as usize;
    if let Some((outcomes, differs)) = crate::tui::panels::twins::versus_table::outcomes_text(app, false) {
        // The parameter twin: both outcomes (by the faces alone when short of room) and
        // what B differs by, in place of one face.
        let differs = format!("· {differs} ");
        let full = format!(" dice · {outcomes} {differs}");
        let outcomes = if full.chars().count() <= crate::tui::vocabulary::fit::room(room) {
            outcomes
        } else {
            crate::tui::panels::twins::versus_table::outcomes_text(app, true)
                .map_or(outcomes, |(short, _)| short)
        };
        title[0] = (0, vec![Span::styled(" dice ", t.heading())]);
        title[1] = (0, vec![Span::raw(format!("· {outcomes} "))]);
        title.push((1, vec![Span::styled(differs, Style::new().fg(t.ghost()))]));
    } else if let Some(twin) = &app.roll.live.twin {
        title.push((
            1,
            vec![Span::styled(
                format!("· twin face up {} ", twin.die.face_up),
                Style::new().fg(t.ghost()),
            )],
        ));
    }
    let block = Block::bordered().title(crate::tui::vocabulary::fit::line(title, room));
    let body = block.inner(area);
    frame.render_widget(block, area);
    if body.width < 2 || body.height < 2 {
        return;
    }
    // The reason a roll ended and the arrows' legend take rows of their own: they hide
    // nothing of the die.
    let parts = die_panel(app, body);
    if let Some((lines, style, top)) = parts.reason {
        let lines: Vec<Line> = lines.into_iter().map(|l| Line::styled(l, style)).collect();
        frame.render_widget(Clear, top);
        frame.render_widget(Paragraph::new(lines), top);
    }
    if let Some((lines, rows)) = parts.readouts {
        let lines: Vec<Line> = lines.into_iter().map(Line::raw).collect();
        frame.render_widget(Paragraph::new(lines), rows);
    }
    if let Some(legend) = parts.legend {
        frame.render_widget(Paragraph::new(vectors::legend(app, body.width)), legend);
    }
    draw(app, &Projection::new(app, parts.picture), frame);
}

/// The die's picture seen in `view`, drawn into its area: strokes, fills, then labels.
pub(crate) fn draw(app: &App, view: &Projection, frame: &mut Frame) {
    let body = view.area;
    let pic = picture(app, view);
    match app.die_screen.drawing {
        Drawing::Braille => draw_braille(&pic, view, frame),
        Drawing::Ascii => draw_ascii(&pic, view, frame.buffer_mut()),
    }
    let buf = frame.buffer_mut();
    draw_fills(&pic, view, buf);
    for (col, row, label) in place_labels(&pic.labels, view, &pic.outline) {
        buf.set_span(
            body.x + col,
            body.y + row,
            &Span::styled(label.text.as_str(), label.style),
            body.width - col,
        );
    }
}

/// s: when the stopping rule decided the face, once the roll on screen is past it. The die
/// plays on to rest after it, but the roll's outcome, table entry and exports end there.
pub(crate) fn decided_at(app: &App) -> Option<f64> {
    let live = &app.roll.live;
    live.timeline
        .decided
        .filter(|&d| live.timeline.position >= d)
        .map(|d| d as f64 * live.params.integrator.dt)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slopes_read_as_their_characters() {
        assert_eq!(slope_char(4.0, 0.0), '-');
        assert_eq!(slope_char(0.0, 3.0), '|');
        assert_eq!(slope_char(2.0, 1.0), '/');
        assert_eq!(slope_char(-2.0, 1.0), '\\');
        assert_eq!(slope_char(-4.0, -0.5), '-');
    }

    #[test]
    fn each_face_has_its_number_of_pips_and_opposite_faces_sum_to_seven() {
        let die = dicesim_physics::Params::DEFAULT.die;
        let body = Solid::new(&die, &dicesim_physics::body::body_corner_offsets(1.0));
        for f in 0..6 {
            let pips = pip_centres(die.half_sizes, f as u8 + 1);
            assert_eq!(pips.len(), f + 1);
            let opposite = (0..6)
                .find(|&g| (body.normal(f) + body.normal(g)).norm() < 1e-12)
                .expect("a cube's faces come in opposite pairs");
            assert_eq!(
                pips.len() + pip_centres(die.half_sizes, opposite as u8 + 1).len(),
                7,
                "face {} and face {}",
                f + 1,
                opposite + 1
            );
        }
    }
}

#[cfg(test)]
mod die_tests;
