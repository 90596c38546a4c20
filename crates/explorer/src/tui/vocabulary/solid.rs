//! The die's body as the die panel draws it: its faces, edges and corner spheres in the
//! world, its outline on the view plane, and what of a line behind it still shows.

use dicesim_physics::body::CORNER_SIGNS;
use dicesim_physics::polyhedron::{self, ReadAt};
use dicesim_physics::{Die, Params};
use nalgebra::{Rotation3, Vector3};

/// Corner indices (0-based) of faces 1..6 (docs/model.md, "Faces").
pub(crate) const FACE_CORNERS: [[usize; 4]; 6] = [
    [0, 1, 2, 3],
    [0, 1, 4, 5],
    [0, 2, 4, 6],
    [1, 3, 5, 7],
    [2, 3, 6, 7],
    [4, 5, 6, 7],
];

/// The 12 edges: corners whose (x, y, z) signs differ in one place (corner k−1 has bits x y z).
pub(crate) const EDGES: [(usize, usize); 12] = [
    (0, 1),
    (2, 3),
    (4, 5),
    (6, 7),
    (0, 2),
    (1, 3),
    (4, 6),
    (5, 7),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];

/// The die's body in the world, as the worker reports it (its 8 corner-sphere centres, which
/// for a sharp die are its corners) with the sizes the physics gives it: the box of the three
/// half sizes shrunk by the corner radius and grown by a ball of that radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Solid {
    /// cm, world: the centres of the corner spheres 1..8.
    pub(crate) spheres: [Vector3<f64>; 8],
    /// cm, the corner radius.
    pub(crate) radius: f64,
    /// cm, the three half sizes of the sharp box.
    pub(crate) half_sizes: [f64; 3],
    /// cm, world: the geometric centre (not the centre of mass of a drilled or loaded die).
    pub(crate) centre: Vector3<f64>,
    /// The body's x, y and z axes in the world, unit vectors.
    pub(crate) axes: [Vector3<f64>; 3],
}

impl Solid {
    /// The box of `die` whose 8 corner spheres are at `spheres` (the first 8 points given).
    pub(crate) fn new(die: &Die, spheres: &[Vector3<f64>]) -> Solid {
        let spheres: [Vector3<f64>; 8] = std::array::from_fn(|k| spheres.get(k).copied().unwrap_or_default());
        let radius = die.corner_radius;
        let centre = spheres.iter().sum::<Vector3<f64>>() / 8.0;
        // Corners 1 and 5, 3 and 1, 2 and 1 differ along x, y and z only, by twice the
        // spheres' box half size `a − r` (positive: the radius is below every half size).
        let along = |k: usize, i: usize| (spheres[k] - spheres[0]) / (2.0 * (die.half_sizes[i] - radius));
        Solid {
            spheres,
            radius,
            half_sizes: die.half_sizes,
            centre,
            axes: [along(4, 0), along(2, 1), along(1, 2)],
        }
    }

    /// A body-frame direction in the world.
    pub(crate) fn direction(&self, v: [f64; 3]) -> Vector3<f64> {
        self.axes[0] * v[0] + self.axes[1] * v[1] + self.axes[2] * v[2]
    }

    /// cm, world: a body-frame point about the geometric centre.
    pub(crate) fn point(&self, p: [f64; 3]) -> Vector3<f64> {
        self.centre + self.direction(p)
    }

    /// The outward normal of face `f` (0-based), world.
    pub(crate) fn normal(&self, f: usize) -> Vector3<f64> {
        self.direction(dicesim_physics::face_frame(f as u8 + 1)[0])
    }

    /// cm, world: the corners of face `f`'s flat part (0-based face, corners in
    /// [`FACE_CORNERS`] order): its corner spheres' centres moved out by the radius. For a
    /// sharp die these are the face's corners.
    pub(crate) fn flat_face(&self, f: usize) -> [Vector3<f64>; 4] {
        let out = self.normal(f) * self.radius;
        FACE_CORNERS[f].map(|k| self.spheres[k] + out)
    }

    /// cm, world: sharp corner `k` (0-based) of the box the body is rounded from, where a
    /// loaded die's extra mass sits.
    pub(crate) fn sharp_corner(&self, k: usize) -> Vector3<f64> {
        self.spheres[k] + self.direction(CORNER_SIGNS[k]) * self.radius
    }

    /// cm, world: the bottom of corner sphere `k`, where it touches the table.
    pub(crate) fn foot_of_sphere(&self, k: usize) -> Vector3<f64> {
        self.spheres[k] - Vector3::z() * self.radius
    }

    /// cm, world: the body's lowest point.
    pub(crate) fn lowest(&self) -> Vector3<f64> {
        let k = (0..8)
            .min_by(|&i, &j| self.spheres[i].z.total_cmp(&self.spheres[j].z))
            .unwrap_or(0);
        self.foot_of_sphere(k)
    }

    /// The body's outline on the view plane, counter-clockwise: the hull of the corners for
    /// a sharp die; for a rounded one the hull of the discs the corner spheres project to
    /// (an orthographic view keeps lengths, so each ball is a disc of the corner radius),
    /// which rounds the outline's corners with arcs.
    pub(crate) fn outline(&self, flat: impl Fn(&Vector3<f64>) -> Flat) -> Vec<Flat> {
        let centres = self.spheres.map(|c| flat(&c));
        if self.radius <= 0.0 {
            return convex_hull(&centres);
        }
        let discs: Vec<Flat> = centres
            .iter()
            .flat_map(|&(x, y)| {
                (0..ARC_POINTS).map(move |i| {
                    let (s, c) = (std::f64::consts::TAU * i as f64 / ARC_POINTS as f64).sin_cos();
                    (x + self.radius * c, y + self.radius * s)
                })
            })
            .collect();
        convex_hull(&discs)
    }
}

/// The solid a die's parameters describe, as the panels draw it: a polyhedral die's (its hull,
/// numbers and mass; `None` for the box, drawn from its corners) and the size the view scales
/// with. Made when the parameters change, never per frame.
#[derive(Debug, Clone)]
pub(crate) struct DieShape {
    pub(crate) die: Option<polyhedron::Die>,
    /// cm, the size the view, the floor tiles and the arrows scale with: the box's largest
    /// half size; a polyhedral die's circumradius (about its centre of mass) over √3, the half
    /// size of the cube with that circumradius, so a d20 fills the panel as a cube of its
    /// reach does.
    pub(crate) scale: f64,
}

impl DieShape {
    pub(crate) fn of(params: &Params) -> DieShape {
        let die = params.polyhedral_die();
        let scale = match &die {
            Some(die) => {
                let centre = die.mass_properties().centre_of_mass;
                let reach = die
                    .shape()
                    .vertices()
                    .iter()
                    .map(|v| (v - centre).norm())
                    .fold(0.0, f64::max);
                reach / 3f64.sqrt()
            }
            None => params.die.largest_half_size(),
        };
        DieShape { die, scale }
    }
}

/// A die's body as drawn: the box (the paper's die and every real die built on it) or a
/// polyhedral die's hull.
#[derive(Debug, Clone)]
// A body is made for a frame and matched at once; boxing the larger one would add an
// allocation to every frame for nothing.
#[allow(clippy::large_enum_variant)]
pub(crate) enum Body {
    Box(Solid),
    Hull(Hull),
}

impl Body {
    /// The body of `params`' die with its points at `points` (world), turned by `orientation`
    /// with its centre of mass at `centre`.
    /// The body of `params`' die, whose solid is `shape` ([`DieShape::of`] them), with its
    /// points at `points` (world), turned by `orientation` with its centre of mass at
    /// `centre`.
    pub(crate) fn new(
        params: &Params,
        shape: &DieShape,
        points: &[Vector3<f64>],
        centre: Vector3<f64>,
        orientation: &Rotation3<f64>,
    ) -> Body {
        match &shape.die {
            Some(die) => Body::Hull(Hull::new(die.clone(), centre, orientation)),
            None => Body::Box(Solid::new(&params.die, points)),
        }
    }

    /// The outline on the view plane, counter-clockwise.
    pub(crate) fn outline(&self, flat: impl Fn(&Vector3<f64>) -> Flat) -> Vec<Flat> {
        match self {
            Body::Box(b) => b.outline(flat),
            Body::Hull(h) => h.outline(flat),
        }
    }

    /// cm, world: the body's lowest point.
    pub(crate) fn lowest(&self) -> Vector3<f64> {
        match self {
            Body::Box(b) => b.lowest(),
            Body::Hull(h) => h.lowest(),
        }
    }
}

/// A polyhedral die in the world: its hull's vertices turned by the die's orientation and
/// placed at its centre of mass, its faces' outward normals likewise, and the numbers on them.
#[derive(Debug, Clone)]
pub(crate) struct Hull {
    pub(crate) die: polyhedron::Die,
    /// cm, world: the hull's vertices, in the die's vertex order (the contact points' order).
    pub(crate) vertices: Vec<Vector3<f64>>,
    /// World: each face's outward unit normal, in the die's face order.
    pub(crate) normals: Vec<Vector3<f64>>,
    /// cm, world: the centre of mass.
    pub(crate) centre: Vector3<f64>,
}

impl Hull {
    /// `die` turned by `orientation` (body frame into the world: the frame of its vertices
    /// about its centre of mass) with its centre of mass at `centre`.
    pub(crate) fn new(die: polyhedron::Die, centre: Vector3<f64>, orientation: &Rotation3<f64>) -> Hull {
        let com = die.mass_properties().centre_of_mass;
        let vertices = die
            .shape()
            .vertices()
            .iter()
            .map(|v| centre + orientation * (v - com))
            .collect();
        let normals = die
            .shape()
            .faces()
            .iter()
            .map(|f| orientation * f.normal)
            .collect();
        Hull {
            die,
            vertices,
            normals,
            centre,
        }
    }

    /// cm, world: the centre of face `f`'s polygon (the mean of its vertices).
    pub(crate) fn face_centre(&self, f: usize) -> Vector3<f64> {
        let face = &self.die.shape().faces()[f];
        face.vertices
            .iter()
            .map(|&k| self.vertices[k])
            .sum::<Vector3<f64>>()
            / face.vertices.len() as f64
    }

    /// The number printed on face `f` where it is read at the top face (docs/dice.md, "The
    /// tables"); `None` for a die read at a vertex (the d4), whose faces carry its vertices'.
    pub(crate) fn face_number(&self, f: usize) -> Option<u32> {
        let numbering = self.die.numbering();
        (numbering.read_at != ReadAt::TopVertex).then(|| numbering.numbers[f])
    }

    /// The number printed by vertex `k` on every face that meets there, for a die read at its
    /// top vertex (the d4): the number of the face it does not touch, the one read with that
    /// face down.
    pub(crate) fn vertex_number(&self, k: usize) -> Option<u32> {
        let numbering = self.die.numbering();
        if numbering.read_at != ReadAt::TopVertex {
            return None;
        }
        let faces = self.die.shape().faces();
        (0..faces.len())
            .find(|&f| !faces[f].vertices.contains(&k))
            .map(|f| numbering.numbers[f])
    }

    /// The face whose normal points most nearly up: the one a player reads on a die read at
    /// its top face.
    pub(crate) fn face_most_nearly_up(&self) -> usize {
        (0..self.normals.len())
            .max_by(|&a, &b| self.normals[a].z.total_cmp(&self.normals[b].z))
            .unwrap_or(0)
    }

    /// cm, world: the lowest vertex.
    pub(crate) fn lowest(&self) -> Vector3<f64> {
        self.vertices
            .iter()
            .copied()
            .min_by(|a, b| a.z.total_cmp(&b.z))
            .unwrap_or(self.centre)
    }

    /// The hull's outline on the view plane, counter-clockwise.
    pub(crate) fn outline(&self, flat: impl Fn(&Vector3<f64>) -> Flat) -> Vec<Flat> {
        convex_hull(&self.vertices.iter().map(flat).collect::<Vec<_>>())
    }
}

/// Points on each corner sphere's outline: enough that its arc reads as round at any zoom
/// the explorer allows.
const ARC_POINTS: usize = 32;

pub(crate) use dicesim_figures::plane::{Flat, convex_hull, inside};

/// The parts of the segment `a`–`b` outside the counter-clockwise convex polygon `hull`
/// (Cyrus–Beck clipping): what a line behind an opaque convex body still shows.
pub(crate) fn outside_parts(hull: &[Flat], a: Flat, b: Flat) -> Vec<(Flat, Flat)> {
    if hull.len() < 3 {
        return vec![(a, b)];
    }
    let d = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for i in 0..hull.len() {
        let (v, w) = (hull[i], hull[(i + 1) % hull.len()]);
        let e = (w.0 - v.0, w.1 - v.1);
        // Left of the edge (inside) where f(t) = start + t·rate ≥ 0.
        let start = e.0 * (a.1 - v.1) - e.1 * (a.0 - v.0);
        let rate = e.0 * d.1 - e.1 * d.0;
        if rate == 0.0 {
            if start < 0.0 {
                return vec![(a, b)];
            }
        } else if rate > 0.0 {
            t0 = t0.max(-start / rate);
        } else {
            t1 = t1.min(-start / rate);
        }
    }
    if t0 >= t1 {
        return vec![(a, b)];
    }
    let at = |t: f64| (a.0 + t * d.0, a.1 + t * d.1);
    let mut parts = Vec::with_capacity(2);
    if t0 > 0.0 {
        parts.push((a, at(t0)));
    }
    if t1 < 1.0 {
        parts.push((at(t1), b));
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_physics::body::body_corner_offsets;

    #[test]
    fn faces_and_edges_follow_the_papers_numbering() {
        let c = body_corner_offsets(1.0);
        // face 4 is z = +a, face 1 is x = −a (docs/model.md).
        assert!(FACE_CORNERS[3].iter().all(|&k| c[k].z > 0.0));
        assert!(FACE_CORNERS[0].iter().all(|&k| c[k].x < 0.0));
        for (a, b) in EDGES {
            assert!(
                ((c[a] - c[b]).norm() - 2.0).abs() < 1e-12,
                "edge {a}-{b} has the side's length"
            );
        }
    }

    #[test]
    fn a_square_hides_the_middle_of_a_line_through_it() {
        let square = convex_hull(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)]);
        assert_eq!(square.len(), 4, "the inner point is not on the hull: {square:?}");
        assert!(inside(&square, (0.5, 0.5)) && !inside(&square, (1.5, 0.5)));
        let parts = outside_parts(&square, (-1.0, 0.5), (2.0, 0.5));
        assert_eq!(parts, vec![((-1.0, 0.5), (0.0, 0.5)), ((1.0, 0.5), (2.0, 0.5))]);
        assert!(
            outside_parts(&square, (0.2, 0.2), (0.8, 0.7)).is_empty(),
            "wholly behind"
        );
        let missing = ((-1.0, 3.0), (2.0, 3.0));
        assert_eq!(outside_parts(&square, missing.0, missing.1), vec![missing]);
    }
}
