//! A die: its convex shape, its numbers, its mass and its flaws, and what a player reads off
//! it. The shape and the flaws are in the die's own frame; the contact points a body steps
//! are measured from the centre of mass.

use super::flaws::{FlawError, Flaws, sphere_centres};
use super::hull::{HullError, Polyhedron, convex_hull};
use super::moments::{combine, solid_moments};
use super::numbering::Numbering;
use crate::MassProperties;
use nalgebra::{Rotation3, Vector3};

/// A die of any convex shape.
#[derive(Debug, Clone, PartialEq)]
pub struct Die {
    /// The solid in the die's own frame (the sharp, uniform solid's centre at the origin for the
    /// dice this module builds), after any shave.
    shape: Polyhedron,
    /// The solid as it was made, before any flaw: what [`Die::with_flaws`] starts from.
    made: Polyhedron,
    numbering: Numbering,
    /// g/cm³, of the uniform material.
    density: f64,
    flaws: Flaws,
    mass: MassProperties,
    /// cm, die frame, one per vertex: where each vertex's contact sphere is centred.
    sphere_centres: Vec<Vector3<f64>>,
    /// cm, one per vertex.
    radii: Vec<f64>,
    /// rad, per face: the tilt from straight down past which that face is not read.
    tilt_limits: Vec<f64>,
}

/// One point a die touches a table with, as the step takes it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// cm, the sphere's centre from the centre of mass, in the die's frame.
    pub offset: Vector3<f64>,
    /// cm, 0 for a sharp vertex.
    pub radius: f64,
}

/// The face a die shows and the number a player reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reading {
    /// Index into the shape's faces: the face down.
    pub face: usize,
    pub number: u32,
}

impl Die {
    /// The sharp, uniform die of `shape` at `density` (g/cm³).
    pub fn new(shape: Polyhedron, numbering: Numbering, density: f64) -> Self {
        let mass = solid_moments(&shape).mass_properties(density);
        let tilt_limits = tilt_limits(&shape);
        Self {
            sphere_centres: shape.vertices.clone(),
            radii: vec![0.0; shape.vertices.len()],
            made: shape.clone(),
            shape,
            numbering,
            density,
            flaws: Flaws::default(),
            mass,
            tilt_limits,
        }
    }

    /// The sharp, uniform die whose corners are `vertices` (cm), numbered by
    /// [`Numbering::for_shape`].
    pub fn from_vertices(vertices: &[Vector3<f64>], density: f64) -> Result<Self, HullError> {
        let shape = convex_hull(vertices)?;
        let numbering = Numbering::for_shape(&shape);
        Ok(Self::new(shape, numbering, density))
    }

    /// This die as it was made (sharp and uniform: any flaws it has are replaced) with `flaws`:
    /// the shave first,
    /// then the bubble and the point mass inside what is left, then the rounding of its
    /// vertices.
    pub fn with_flaws(&self, flaws: &Flaws) -> Result<Self, FlawError> {
        let numbers = &self.numbering.numbers;
        let (shape, shaved) = match &flaws.shave {
            Some(shave) => {
                let (shape, face) = shave.cut(&self.made, numbers)?;
                (shape, Some(face))
            }
            None => (self.made.clone(), None),
        };
        let mut pieces = Vec::new();
        if let Some(bubble) = &flaws.bubble {
            pieces.push(bubble.removed(&shape, numbers, self.density)?);
        }
        if let Some(point) = &flaws.point_mass {
            pieces.push(point.added(&shape, numbers)?);
        }
        let mass = combine(&solid_moments(&shape).mass_properties(self.density), &pieces);
        let count = shape.vertices.len();
        let radii = match flaws.rounding.len() {
            0 => vec![0.0; count],
            1 => vec![flaws.rounding[0]; count],
            n if n == count => flaws.rounding.clone(),
            given => {
                return Err(FlawError::RoundingCount {
                    given,
                    vertices: count,
                });
            }
        };
        let sphere_centres = sphere_centres(&shape, &radii, numbers)?;
        let die = Self {
            tilt_limits: tilt_limits(&shape),
            shape,
            made: self.made.clone(),
            numbering: self.numbering.clone(),
            density: self.density,
            flaws: flaws.clone(),
            mass,
            sphere_centres,
            radii,
        };
        if let Some(face) = shaved
            && !die.holds(face)
        {
            return Err(FlawError::ShaveTopples { face: numbers[face] });
        }
        Ok(die)
    }

    /// The solid in the die's own frame, after any shave.
    pub fn shape(&self) -> &Polyhedron {
        &self.shape
    }

    /// The numbers on its faces and where they are read.
    pub fn numbering(&self) -> &Numbering {
        &self.numbering
    }

    /// g/cm³, of the uniform material.
    pub fn density(&self) -> f64 {
        self.density
    }

    /// The flaws it was made with.
    pub fn flaws(&self) -> &Flaws {
        &self.flaws
    }

    /// Mass, centre of mass (die frame) and inertia about it, flaws included.
    pub fn mass_properties(&self) -> MassProperties {
        self.mass
    }

    /// The points the die touches a table with: each vertex's sphere, from the centre of mass.
    pub fn contact_points(&self) -> Vec<ContactPoint> {
        self.sphere_centres
            .iter()
            .zip(&self.radii)
            .map(|(c, &radius)| ContactPoint {
                offset: c - self.mass.centre_of_mass,
                radius,
            })
            .collect()
    }

    /// The face whose outward normal is most nearly `down` (the world's down in the die's
    /// frame, any length): always an answer, for a die in flight.
    pub fn face_most_nearly_down(&self, down: &Vector3<f64>) -> usize {
        let mut best = 0;
        for (f, face) in self.shape.faces.iter().enumerate() {
            if face.normal.dot(down) > self.shape.faces[best].normal.dot(down) {
                best = f;
            }
        }
        best
    }

    /// The face down and the number read, or "no face" (`None`) when the die stands on an
    /// edge or a vertex: the face most nearly down is read only while its normal is within a
    /// quarter of the angle between it and its nearest neighbour's normal of straight down
    /// (docs/dice.md, "Reading a die").
    pub fn reading(&self, down: &Vector3<f64>) -> Option<Reading> {
        let face = self.face_most_nearly_down(down);
        let tilt = self.shape.faces[face].normal.angle(down);
        (tilt <= self.tilt_limits[face]).then(|| Reading {
            face,
            number: self.numbering.read_with_down(face),
        })
    }

    /// [`Die::reading`] of a die turned by `orientation` (die frame to world, z up).
    pub fn reading_at(&self, orientation: &Rotation3<f64>) -> Option<Reading> {
        self.reading(&(orientation.inverse() * -Vector3::z()))
    }

    /// Whether the die can rest on `face`: the foot of its centre of mass on the face's plane
    /// lies inside the polygon of the face's contact spheres' feet (strictly, to 10⁻⁹ of its size).
    pub fn holds(&self, face: usize) -> bool {
        let f = &self.shape.faces[face];
        let foot = |x: &Vector3<f64>| x - f.normal * f.height_of(x);
        let c = foot(&self.mass.centre_of_mass);
        let eps = 1e-9 * self.shape.size();
        let corners: Vec<Vector3<f64>> = f
            .vertices
            .iter()
            .map(|&k| foot(&self.sphere_centres[k]))
            .collect();
        (0..corners.len()).all(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
            let side = b - a;
            (side.cross(&(c - a))).dot(&f.normal) > eps * side.norm()
        })
    }

    /// cm per vertex: the rounding radii.
    pub fn radii(&self) -> &[f64] {
        &self.radii
    }

    /// Each vertex's sphere centre in the die frame.
    pub(crate) fn sphere_centres(&self) -> &[Vector3<f64>] {
        &self.sphere_centres
    }
}

/// rad, a quarter of the angle from each face's normal to its nearest edge neighbour's.
fn tilt_limits(shape: &Polyhedron) -> Vec<f64> {
    let mut limits = vec![f64::INFINITY; shape.faces.len()];
    for edge in shape.edges() {
        let [f, g] = edge.faces;
        let angle = shape.faces[f].normal.angle(&shape.faces[g].normal) / 4.0;
        limits[f] = limits[f].min(angle);
        limits[g] = limits[g].min(angle);
    }
    limits
}
