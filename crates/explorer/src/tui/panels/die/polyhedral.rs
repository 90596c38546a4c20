//! What the camera sees of a polyhedral die (the d4 to the d20), for the die panel to draw:
//! which faces face it, which edges it sees, and the numbers it can read and where. A convex
//! body hides exactly the faces turned away, so an edge is seen exactly when it borders a
//! seen face. Each readable face carries its number at its centre; the d4 carries its
//! vertices' numbers by each vertex, as printed.

use crate::tui::state::camera::OrbitCamera;
use crate::tui::vocabulary::format::face_text;
use crate::tui::vocabulary::solid::Hull;
use dicesim_physics::Solid;
use nalgebra::Vector3;

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
pub(crate) fn numbers(kind: Solid, hull: &Hull, camera: &OrbitCamera) -> Vec<(Vector3<f64>, String, bool)> {
    let facing = facing(hull, camera);
    let up = hull.face_most_nearly_up();
    // A die read at its face down (an odd prism) shows the number read underneath.
    let read_at_top_face = hull.die.numbering().read_at == dicesim_physics::polyhedron::ReadAt::TopFace;
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
