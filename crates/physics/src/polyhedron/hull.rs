//! The convex hull of a die's vertices (docs/model.md, "The hull of a list of corners"): every
//! plane through three vertices with all the others on or behind it is a face's plane, and the
//! vertices on one plane are one polygon. With at most 64 vertices the `n⁴/6` tests are cheap
//! and no starting simplex or insertion order can make two runs disagree.

use nalgebra::Vector3;
use std::fmt;

/// The most vertices a die may have: the largest body the step takes.
pub const MAX_VERTICES: usize = 64;

/// Relative tolerance of "on the plane", "the same point" and "on one line", times the die's
/// size (the largest distance of a vertex from the vertices' mean).
const RELATIVE_TOLERANCE: f64 = 1e-9;

/// One face: a convex polygon of the polyhedron's vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    /// Indices into [`Polyhedron::vertices`], counter-clockwise seen from outside.
    pub vertices: Vec<usize>,
    /// The outward unit normal.
    pub normal: Vector3<f64>,
    /// cm, the plane `normal·x = offset` the face lies in.
    pub offset: f64,
}

impl Face {
    /// cm, how far `x` lies outside the face's plane (negative behind it).
    pub fn height_of(&self, x: &Vector3<f64>) -> f64 {
        self.normal.dot(x) - self.offset
    }
}

/// A convex polyhedron: its vertices (cm) and its faces, in the order of [`face_order`].
#[derive(Debug, Clone, PartialEq)]
pub struct Polyhedron {
    pub(super) vertices: Vec<Vector3<f64>>,
    pub(super) faces: Vec<Face>,
}

impl Polyhedron {
    /// cm, the vertices in the order they were given.
    pub fn vertices(&self) -> &[Vector3<f64>] {
        &self.vertices
    }

    /// The faces, in the order of [`face_order`] (a shaved die's in its unshaved die's order).
    pub fn faces(&self) -> &[Face] {
        &self.faces
    }

    /// The edges, each once as `(a, b)` with `a < b`, with the faces on either side.
    pub fn edges(&self) -> Vec<Edge> {
        let mut edges: Vec<Edge> = Vec::new();
        for (f, face) in self.faces.iter().enumerate() {
            let n = face.vertices.len();
            for i in 0..n {
                let (a, b) = (face.vertices[i], face.vertices[(i + 1) % n]);
                let key = (a.min(b), a.max(b));
                match edges.iter_mut().find(|e| e.vertices == key) {
                    Some(edge) => edge.faces[1] = f,
                    None => edges.push(Edge {
                        vertices: key,
                        faces: [f, f],
                    }),
                }
            }
        }
        edges
    }

    /// cm, the largest distance of a vertex from the vertices' mean: the die's size for tolerances.
    pub fn size(&self) -> f64 {
        size_of(&self.vertices)
    }

    /// Whether `x` lies inside or on the solid, to the hull's tolerance.
    pub fn contains(&self, x: &Vector3<f64>) -> bool {
        let eps = RELATIVE_TOLERANCE * self.size();
        self.faces.iter().all(|f| f.height_of(x) <= eps)
    }
}

/// An edge between two vertices and the two faces that meet there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    pub vertices: (usize, usize),
    pub faces: [usize; 2],
}

/// Why a list of vertices is not a die, naming the vertex (0-based) at fault.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HullError {
    /// More than [`MAX_VERTICES`].
    TooMany { count: usize },
    /// Fewer than 4 vertices: no solid.
    TooFew { count: usize },
    /// A coordinate that is NaN or infinite.
    NotFinite { vertex: usize },
    /// Two vertices at the same place.
    Duplicate { vertex: usize, of: usize },
    /// Every vertex on one line or in one plane: no solid.
    Flat,
    /// A vertex that is not a corner of the hull: inside it, or on a face or an edge between
    /// its corners.
    NotConvex { vertex: usize },
}

impl fmt::Display for HullError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::TooMany { count } => {
                write!(f, "{count} vertices: a die has at most {MAX_VERTICES}")
            }
            Self::TooFew { count } => write!(f, "{count} vertices: a solid needs at least 4"),
            Self::NotFinite { vertex } => write!(f, "vertex {} is not a finite point", vertex + 1),
            Self::Duplicate { vertex, of } => {
                write!(
                    f,
                    "vertex {} is at the same place as vertex {}",
                    vertex + 1,
                    of + 1
                )
            }
            Self::Flat => write!(f, "the vertices lie on one line or in one plane: no solid"),
            Self::NotConvex { vertex } => write!(
                f,
                "vertex {} is not a corner of the die: it lies inside the others' hull or on one of its faces or edges (the list is not convex)",
                vertex + 1
            ),
        }
    }
}

impl std::error::Error for HullError {}

fn size_of(points: &[Vector3<f64>]) -> f64 {
    let mean = points.iter().sum::<Vector3<f64>>() / points.len() as f64;
    points.iter().map(|p| (p - mean).norm()).fold(0.0, f64::max)
}

/// The convex polyhedron whose corners are exactly `points`, or why there is none.
pub fn convex_hull(points: &[Vector3<f64>]) -> Result<Polyhedron, HullError> {
    let count = points.len();
    if count > MAX_VERTICES {
        return Err(HullError::TooMany { count });
    }
    if let Some(vertex) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(HullError::NotFinite { vertex });
    }
    if count < 4 {
        return Err(HullError::TooFew { count });
    }
    let eps = RELATIVE_TOLERANCE * size_of(points);
    for j in 1..count {
        if let Some(i) = (0..j).find(|&i| (points[j] - points[i]).norm() <= eps) {
            return Err(HullError::Duplicate { vertex: j, of: i });
        }
    }
    let mut planes: Vec<u64> = Vec::new();
    for i in 0..count {
        for j in i + 1..count {
            for k in j + 1..count {
                if let Some(on) = supporting_plane(points, [i, j, k], eps)
                    && !planes.contains(&on)
                {
                    planes.push(on);
                }
            }
        }
    }
    if planes.is_empty() {
        return Err(HullError::Flat);
    }
    let mut faces = Vec::with_capacity(planes.len());
    let mut is_corner = vec![false; count];
    for on in planes {
        let face = polygon(points, on, eps)?;
        for &v in &face.vertices {
            is_corner[v] = true;
        }
        faces.push(face);
    }
    if let Some(vertex) = is_corner.iter().position(|c| !c) {
        return Err(HullError::NotConvex { vertex });
    }
    faces.sort_by(|a, b| face_order(&a.normal, &b.normal));
    Ok(Polyhedron {
        vertices: points.to_vec(),
        faces,
    })
}

/// The vertices on the plane through `points[i, j, k]` as a bit mask, when every point lies on
/// it or on one side; `None` for a line or a plane that cuts the points.
fn supporting_plane(points: &[Vector3<f64>], [i, j, k]: [usize; 3], eps: f64) -> Option<u64> {
    let normal = (points[j] - points[i]).cross(&(points[k] - points[i]));
    let length = normal.norm();
    // The three lie on one line when the triangle's height over its longest side is below eps.
    let longest = [(j, i), (k, i), (k, j)]
        .map(|(a, b)| (points[a] - points[b]).norm())
        .into_iter()
        .fold(0.0, f64::max);
    if length <= eps * longest {
        return None;
    }
    let n = normal / length;
    let d = n.dot(&points[i]);
    let (mut above, mut below, mut on) = (false, false, 0u64);
    for (l, p) in points.iter().enumerate() {
        let h = n.dot(p) - d;
        if h > eps {
            above = true;
        } else if h < -eps {
            below = true;
        } else {
            on |= 1 << l;
        }
    }
    (above != below).then_some(on)
}

/// The face on the plane of the vertices `on`: their 2-D hull, counter-clockwise seen from
/// outside, its normal by Newell's sum over the polygon. A vertex on the plane that is not a
/// corner of the polygon is not a corner of the die.
fn polygon(points: &[Vector3<f64>], on: u64, eps: f64) -> Result<Face, HullError> {
    let members: Vec<usize> = (0..points.len()).filter(|l| on & (1 << l) != 0).collect();
    // The plane's normal from its widest triangle, turned away from a vertex off the plane
    // (all of them lie behind it).
    let a = points[members[0]];
    let b = points[members[1]];
    let widest = members[2..]
        .iter()
        .map(|&m| (b - a).cross(&(points[m] - a)))
        .max_by(|x, y| x.norm().total_cmp(&y.norm()))
        .expect("a plane holds at least three vertices")
        .normalize();
    let behind = (0..points.len())
        .find(|l| on & (1 << l) == 0)
        .expect("the vertices are not flat");
    let rough = if widest.dot(&(points[behind] - a)) > 0.0 {
        -widest
    } else {
        widest
    };
    let e1 = (points[members[1]] - points[members[0]]).normalize();
    let e2 = rough.cross(&e1);
    let uv = |l: usize| {
        let r = points[l] - points[members[0]];
        (r.dot(&e1), r.dot(&e2))
    };
    let mut sorted = members.clone();
    sorted.sort_by(|&a, &b| {
        let (pa, pb) = (uv(a), uv(b));
        pa.0.total_cmp(&pb.0).then(pa.1.total_cmp(&pb.1))
    });
    let turn = |o: usize, a: usize, b: usize| {
        let (po, pa, pb) = (uv(o), uv(a), uv(b));
        let cross = (pa.0 - po.0) * (pb.1 - po.1) - (pa.1 - po.1) * (pb.0 - po.0);
        // Twice the triangle's area over its base: a height, against eps.
        let base = ((pb.0 - po.0).powi(2) + (pb.1 - po.1).powi(2)).sqrt();
        cross > eps * base
    };
    let mut hull: Vec<usize> = Vec::new();
    for pass in [sorted.clone(), sorted.iter().rev().copied().collect()] {
        let start = hull.len();
        for &l in &pass {
            while hull.len() >= start + 2 && !turn(hull[hull.len() - 2], hull[hull.len() - 1], l) {
                hull.pop();
            }
            hull.push(l);
        }
        hull.pop();
    }
    if let Some(&vertex) = members.iter().find(|m| !hull.contains(m)) {
        return Err(HullError::NotConvex { vertex });
    }
    let mut normal = Vector3::zeros();
    for (a, &p) in hull.iter().enumerate() {
        let (p, q) = (points[p], points[hull[(a + 1) % hull.len()]]);
        normal += Vector3::new(
            (p.y - q.y) * (p.z + q.z),
            (p.z - q.z) * (p.x + q.x),
            (p.x - q.x) * (p.y + q.y),
        );
    }
    let normal = normal.normalize();
    let offset = hull.iter().map(|&l| normal.dot(&points[l])).sum::<f64>() / hull.len() as f64;
    Ok(Face {
        vertices: hull,
        normal,
        offset,
    })
}

/// The order faces are listed and numbered in: by their normal, highest first (`z` down to
/// within 10⁻⁹), then by azimuth counter-clockwise from +x.
pub fn face_order(a: &Vector3<f64>, b: &Vector3<f64>) -> std::cmp::Ordering {
    let azimuth = |n: &Vector3<f64>| n.y.atan2(n.x).rem_euclid(std::f64::consts::TAU);
    if (a.z - b.z).abs() > 1e-9 {
        b.z.total_cmp(&a.z)
    } else {
        azimuth(a).total_cmp(&azimuth(b))
    }
}
