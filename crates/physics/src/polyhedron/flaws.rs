//! The flaws that make a real die unfair, in the die's own frame (docs/model.md, "Flaws"): a
//! spherical void, an extra point mass, a shaved face and rounding per vertex. Each is checked
//! against the solid, and each changes the mass properties or the contact spheres.

use super::hull::{HullError, Polyhedron, convex_hull};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;
use std::fmt;

/// The flaws of one die; the default is a sharp, uniform die.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Flaws {
    /// cm, each vertex's rounding radius (of the die after any shave): empty for a sharp die,
    /// one value for every vertex alike, or one per vertex.
    pub rounding: Vec<f64>,
    pub bubble: Option<Bubble>,
    pub point_mass: Option<PointMass>,
    pub shave: Option<Shave>,
}

/// A spherical void in the solid (an air bubble).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bubble {
    /// cm, die frame.
    pub centre: Vector3<f64>,
    /// cm.
    pub radius: f64,
}

/// An extra point mass set into the die.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointMass {
    /// cm, die frame.
    pub position: Vector3<f64>,
    /// g.
    pub mass: f64,
}

/// A plane cut keeping `normal·x ≤ offset` (die frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shave {
    /// Unit vector, out of the die.
    pub normal: Vector3<f64>,
    /// cm.
    pub offset: f64,
}

/// Why a flaw makes an impossible body; faces are named by their number.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FlawError {
    /// The bubble's radius is not positive and finite.
    BubbleRadius,
    /// The bubble reaches to (or through) the face with this number.
    BubbleOutside { face: u32 },
    /// The point mass is negative or not finite.
    PointMassValue,
    /// The point mass lies outside the face with this number.
    PointMassOutside { face: u32 },
    /// The plane does not cut the die.
    ShaveMisses,
    /// The cut leaves part of the face it faces standing: it would add a face.
    ShaveLeavesFace { face: u32 },
    /// The cut takes away the whole of another face.
    ShaveRemovesFace { face: u32 },
    /// The die can no longer rest on the shaved face: its centre of mass is not over it.
    ShaveTopples { face: u32 },
    /// What is left is no solid.
    ShaveHull(HullError),
    /// The rounding list has neither 0, 1 nor one radius per vertex.
    RoundingCount { given: usize, vertices: usize },
    /// A radius that is negative or not finite (vertex 1-based).
    RoundingValue { vertex: usize },
    /// The vertex's sphere reaches past the face with this number.
    RoundingTooLarge { vertex: usize, face: u32 },
}

impl fmt::Display for FlawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::BubbleRadius => write!(f, "the bubble's radius must be positive"),
            Self::BubbleOutside { face } => {
                write!(f, "the bubble reaches face {face}: it must lie inside the die")
            }
            Self::PointMassValue => write!(f, "the point mass must be a finite mass of at least 0 g"),
            Self::PointMassOutside { face } => {
                write!(f, "the point mass lies outside the die, beyond face {face}")
            }
            Self::ShaveMisses => write!(f, "the shaving plane does not cut the die"),
            Self::ShaveLeavesFace { face } => {
                write!(
                    f,
                    "the cut leaves part of face {face}: a shave must take the whole face down"
                )
            }
            Self::ShaveRemovesFace { face } => write!(f, "the cut removes the whole of face {face}"),
            Self::ShaveTopples { face } => {
                write!(
                    f,
                    "the shaved die cannot rest on face {face}: its centre of mass is not over it"
                )
            }
            Self::ShaveHull(e) => write!(f, "the shaved die is no solid: {e}"),
            Self::RoundingCount { given, vertices } => {
                write!(
                    f,
                    "{given} rounding radii for {vertices} vertices: give one, or one per vertex"
                )
            }
            Self::RoundingValue { vertex } => {
                write!(f, "vertex {vertex}'s rounding radius must be at least 0")
            }
            Self::RoundingTooLarge { vertex, face } => {
                write!(
                    f,
                    "vertex {vertex}'s rounding reaches past face {face}: the radius is too large"
                )
            }
        }
    }
}

impl std::error::Error for FlawError {}

impl Bubble {
    /// `(mass, centre, inertia about its centre)` of the material it takes out at `density`,
    /// after checking it lies inside every face of `shape` (numbers for the error).
    pub(crate) fn removed(
        &self,
        shape: &Polyhedron,
        numbers: &[u32],
        density: f64,
    ) -> Result<(f64, Vector3<f64>, Matrix3<f64>), FlawError> {
        if !(self.radius > 0.0 && self.radius.is_finite() && self.centre.iter().all(|c| c.is_finite())) {
            return Err(FlawError::BubbleRadius);
        }
        let eps = 1e-9 * shape.size();
        if let Some(f) = shape
            .faces
            .iter()
            .position(|f| -f.height_of(&self.centre) - self.radius <= eps)
        {
            return Err(FlawError::BubbleOutside { face: numbers[f] });
        }
        let mass = density * 4.0 / 3.0 * PI * self.radius.powi(3);
        let own = Matrix3::identity() * (0.4 * mass * self.radius * self.radius);
        Ok((-mass, self.centre, -own))
    }
}

impl PointMass {
    /// `(mass, position, no inertia of its own)`, after checking it lies inside `shape`.
    pub(crate) fn added(
        &self,
        shape: &Polyhedron,
        numbers: &[u32],
    ) -> Result<(f64, Vector3<f64>, Matrix3<f64>), FlawError> {
        if !(self.mass >= 0.0 && self.mass.is_finite() && self.position.iter().all(|c| c.is_finite())) {
            return Err(FlawError::PointMassValue);
        }
        let eps = 1e-9 * shape.size();
        if let Some(f) = shape.faces.iter().position(|f| f.height_of(&self.position) > eps) {
            return Err(FlawError::PointMassOutside { face: numbers[f] });
        }
        Ok((self.mass, self.position, Matrix3::zeros()))
    }
}

impl Shave {
    /// `shape` cut by the plane, its faces in `shape`'s order (the cut face in place of the face
    /// it faces), and the index of that face.
    pub(crate) fn cut(&self, shape: &Polyhedron, numbers: &[u32]) -> Result<(Polyhedron, usize), FlawError> {
        let n = self.normal.normalize();
        let eps = 1e-9 * shape.size();
        let height = |x: &Vector3<f64>| n.dot(x) - self.offset;
        if shape.vertices.iter().all(|v| height(v) <= eps) {
            return Err(FlawError::ShaveMisses);
        }
        let mut points: Vec<Vector3<f64>> = shape
            .vertices
            .iter()
            .filter(|v| height(v) <= eps)
            .copied()
            .collect();
        for edge in shape.edges() {
            let (a, b) = (shape.vertices[edge.vertices.0], shape.vertices[edge.vertices.1]);
            let (ha, hb) = (height(&a), height(&b));
            if (ha > eps && hb < -eps) || (ha < -eps && hb > eps) {
                points.push(a + (b - a) * (ha / (ha - hb)));
            }
        }
        let cut = convex_hull(&points).map_err(FlawError::ShaveHull)?;
        let shaved = (0..shape.faces.len())
            .max_by(|&a, &b| {
                shape.faces[a]
                    .normal
                    .dot(&n)
                    .total_cmp(&shape.faces[b].normal.dot(&n))
            })
            .expect("a die has faces");
        let same_plane = |f: &super::hull::Face, g: &super::hull::Face| {
            f.normal.dot(&g.normal) > 1.0 - 1e-9 && (f.offset - g.offset).abs() <= eps
        };
        let mut faces = Vec::with_capacity(shape.faces.len());
        for (index, face) in shape.faces.iter().enumerate() {
            let kept = cut.faces.iter().find(|g| same_plane(face, g));
            let new = cut.faces.iter().find(|g| g.normal.dot(&n) > 1.0 - 1e-9);
            match (index == shaved, kept, new) {
                (true, Some(_), _) => return Err(FlawError::ShaveLeavesFace { face: numbers[index] }),
                (true, None, Some(g)) | (false, Some(g), _) => faces.push(g.clone()),
                (false, None, _) | (true, None, None) => {
                    return Err(FlawError::ShaveRemovesFace { face: numbers[index] });
                }
            }
        }
        Ok((
            Polyhedron {
                vertices: cut.vertices,
                faces,
            },
            shaved,
        ))
    }
}

/// The centre of each vertex's sphere of radius `radii[k]` (die frame): tangent to the faces
/// at the vertex and behind every face (docs/model.md, "Flaws").
pub(crate) fn sphere_centres(
    shape: &Polyhedron,
    radii: &[f64],
    numbers: &[u32],
) -> Result<Vec<Vector3<f64>>, FlawError> {
    let eps = 1e-9 * shape.size();
    let mut centres = Vec::with_capacity(radii.len());
    for (k, (&v, &r)) in shape.vertices.iter().zip(radii).enumerate() {
        if !(r >= 0.0 && r.is_finite()) {
            return Err(FlawError::RoundingValue { vertex: k + 1 });
        }
        if r == 0.0 {
            centres.push(v);
            continue;
        }
        let at: Vec<&super::hull::Face> = shape.faces.iter().filter(|f| f.vertices.contains(&k)).collect();
        // Least squares for n_f·u = 1: (Σ n nᵀ)·u = Σ n.
        let normal_matrix: Matrix3<f64> = at.iter().map(|f| f.normal * f.normal.transpose()).sum();
        let sum: Vector3<f64> = at.iter().map(|f| f.normal).sum();
        let u = normal_matrix
            .lu()
            .solve(&sum)
            .expect("three faces at a vertex span space");
        let nearest = at.iter().map(|f| f.normal.dot(&u)).fold(f64::INFINITY, f64::min);
        let centre = v - u * (r / nearest);
        if let Some(f) = shape.faces.iter().position(|f| f.height_of(&centre) + r > eps) {
            return Err(FlawError::RoundingTooLarge {
                vertex: k + 1,
                face: numbers[f],
            });
        }
        centres.push(centre);
    }
    Ok(centres)
}
