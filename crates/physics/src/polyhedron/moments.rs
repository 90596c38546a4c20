//! Volume, centre and second moments of a uniform convex solid by signed tetrahedra from an
//! inner point (docs/model.md, "Mass of the uniform solid"): exact up to rounding.

use super::hull::Polyhedron;
use crate::MassProperties;
use nalgebra::{Matrix3, Vector3};

/// The geometry of a uniform solid, without its density.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidMoments {
    /// cm³.
    pub volume: f64,
    /// cm, the centroid in the polyhedron's frame.
    pub centre: Vector3<f64>,
    /// cm⁵, `∫(x − c)(x − c)ᵀ dV` about the centroid.
    pub second: Matrix3<f64>,
}

impl SolidMoments {
    /// The solid's mass properties at `density` (g/cm³): mass, centre and inertia about it.
    pub fn mass_properties(&self, density: f64) -> MassProperties {
        let s = self.second * density;
        MassProperties {
            mass: self.volume * density,
            centre_of_mass: self.centre,
            inertia: Matrix3::identity() * s.trace() - s,
        }
    }
}

/// The moments of the uniform solid `p`.
pub fn solid_moments(p: &Polyhedron) -> SolidMoments {
    let o = p.vertices.iter().sum::<Vector3<f64>>() / p.vertices.len() as f64;
    let mut volume = 0.0;
    let mut first = Vector3::zeros();
    let mut second = Matrix3::zeros();
    for face in &p.faces {
        let u0 = p.vertices[face.vertices[0]] - o;
        for pair in face.vertices[1..].windows(2) {
            let (u1, u2) = (p.vertices[pair[0]] - o, p.vertices[pair[1]] - o);
            let v = u0.dot(&u1.cross(&u2)) / 6.0;
            let s = u0 + u1 + u2;
            volume += v;
            first += s * (v / 4.0);
            second += (u0 * u0.transpose() + u1 * u1.transpose() + u2 * u2.transpose() + s * s.transpose())
                * (v / 20.0);
        }
    }
    let offset = first / volume;
    SolidMoments {
        volume,
        centre: o + offset,
        second: second - offset * offset.transpose() * volume,
    }
}

/// The mass properties of a body made of `base` and point pieces: each `(mass, position,
/// own inertia about its own centre)`, with negative masses for material taken away.
pub(crate) fn combine(base: &MassProperties, pieces: &[(f64, Vector3<f64>, Matrix3<f64>)]) -> MassProperties {
    let mass = base.mass + pieces.iter().map(|p| p.0).sum::<f64>();
    let centre =
        (base.centre_of_mass * base.mass + pieces.iter().map(|p| p.1 * p.0).sum::<Vector3<f64>>()) / mass;
    let shifted = |m: f64, at: &Vector3<f64>| {
        let r = at - centre;
        (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * m
    };
    let mut inertia = base.inertia + shifted(base.mass, &base.centre_of_mass);
    for (m, at, own) in pieces {
        inertia += own + shifted(*m, at);
    }
    MassProperties {
        mass,
        centre_of_mass: centre,
        inertia,
    }
}
