//! A polyhedral die (the d4 to the d20) as the die panel draws it: its hull seen by the
//! camera, the faces turned towards it filled and edged, each readable face carrying its
//! number at its centre (the d4 its vertices' numbers by each vertex, as printed), the face
//! up tinted. A convex body hides exactly the faces turned away, so an edge is seen exactly
//! when it borders a seen face; what lies behind (floor, shadow, ghost) is clipped by the
//! outline as for the box.

use super::{Picture, arrows, floor, throw_aim};
use crate::tui::state::app::App;
use crate::tui::state::camera::OrbitCamera;
use crate::tui::state::die_screen::Drawing;
use crate::tui::state::projection::Projection;
use crate::tui::vocabulary::format::face_text;
use crate::tui::vocabulary::solid::{Flat, Hull, convex_hull, die_scale};
use nalgebra::Vector3;
use ratatui::style::{Modifier, Style};

/// How squarely a face must face the camera for its number to be drawn (the cosine of the
/// angle between its normal and the line of sight): past about 60° off the line of sight
/// a number is foreshortened to half its width and reads as a neighbour's.
const READABLE: f64 = 0.5;

/// How far from a vertex towards its face's centre the d4's number by that vertex sits: a
/// printed d4 carries each vertex's number just inside the corner.
const BY_THE_VERTEX: f64 = 0.4;

/// How squarely each face faces the camera (positive: seen), in the die's face order.
pub(crate) fn facing(hull: &Hull, camera: &OrbitCamera) -> Vec<f64> {
    hull.normals.iter().map(|n| camera.facing(n)).collect()
}

/// The edges (vertex pairs) that border a seen face: the visible ones of a convex body.
pub(crate) fn seen_edges(hull: &Hull, camera: &OrbitCamera) -> Vec<(usize, usize)> {
    let facing = facing(hull, camera);
    hull.die
        .shape()
        .edges()
        .into_iter()
        .filter(|e| e.faces.iter().any(|&f| facing[f] > 0.0))
        .map(|e| e.vertices)
        .collect()
}

/// The numbers drawn on the die, the one read first, then the most readable: (where, text,
/// whether it is the number read). A die read at its top face carries one number at each
/// readable face's centre, the face up's whenever it is seen at all (a camera low over the
/// table sees it at a slant, and it is the number the class asks about); the d4 carries on
/// each readable face the numbers of its three vertices, each by its vertex, the top
/// vertex's (the number read) first.
pub(crate) fn numbers(app: &App, hull: &Hull, camera: &OrbitCamera) -> Vec<(Vector3<f64>, String, bool)> {
    let kind = app.roll.live.params.die.kind;
    let facing = facing(hull, camera);
    let up = hull.face_most_nearly_up();
    let read_at_top_face = hull.face_number(up).is_some();
    let first = |f: usize| read_at_top_face && f == up;
    let mut faces: Vec<usize> = (0..facing.len())
        .filter(|&f| facing[f] >= READABLE || first(f) && facing[f] > 0.0)
        .collect();
    faces.sort_by(|&a, &b| first(b).cmp(&first(a)).then(facing[b].total_cmp(&facing[a])));
    let top = (0..hull.vertices.len())
        .max_by(|&a, &b| hull.vertices[a].z.total_cmp(&hull.vertices[b].z))
        .unwrap_or(0);
    let mut out: Vec<(Vector3<f64>, String, bool)> = Vec::new();
    for f in faces {
        let centre = hull.face_centre(f);
        match hull.face_number(f) {
            Some(n) => out.push((centre, face_text(kind, n), first(f))),
            None => {
                // The d4: the highest vertex's number first, the one a player reads.
                let mut corners = hull.die.shape().faces()[f].vertices.clone();
                corners.sort_by(|&a, &b| hull.vertices[b].z.total_cmp(&hull.vertices[a].z));
                for k in corners {
                    if let Some(n) = hull.vertex_number(k) {
                        let at = hull.vertices[k] + (centre - hull.vertices[k]) * BY_THE_VERTEX;
                        out.push((at, face_text(kind, n), k == top));
                    }
                }
            }
        }
    }
    // The d4's top vertex's numbers (the one read) before the others.
    out.sort_by_key(|&(_, _, read)| !read);
    out
}

/// The picture of a polyhedral die: pure geometry of the app state.
pub(super) fn picture(app: &App, view: &Projection, hull: &Hull) -> Picture {
    let t = &app.theme;
    let die = &app.roll.live.die;
    let half = die_scale(&app.roll.live.params);
    let mut pic = Picture {
        outline: hull.outline(|p| view.flat(p)),
        ..Picture::default()
    };
    let facing = facing(hull, &view.camera);
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
    for (a, b) in seen_edges(hull, &view.camera) {
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
    for (at, text, read) in numbers(app, hull, &view.camera) {
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
