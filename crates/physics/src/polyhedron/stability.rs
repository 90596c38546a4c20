//! How firmly a die rests (docs/model.md, "Tipping over an edge" and "Resting depth on a
//! spring table"): the least energy that tips it off a face, and how deep a face sinks into
//! a spring table.

use super::die::Die;
use nalgebra::{Matrix3, Vector3};

/// The least tip of a die: from which face, over which edge, and how high its centre rises.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tipping {
    /// Index of the face it rests on.
    pub face: usize,
    /// The edge's two vertices.
    pub edge: (usize, usize),
    /// cm, how far the centre of mass rises: `d_e − h_f`.
    pub rise: f64,
}

impl Tipping {
    /// erg, the tipping barrier `M·g·rise` of a die of `mass` (g) under `gravity` (cm/s²).
    pub fn energy(&self, mass: f64, gravity: f64) -> f64 {
        mass * gravity * self.rise
    }
}

/// How a die rests on one face of a spring table.
#[derive(Debug, Clone, PartialEq)]
pub struct RestDepth {
    /// cm, how deep the table is pressed under the centre of mass.
    pub centre: f64,
    /// cm, how deep each of the face's vertices presses it, in the face's order.
    pub points: Vec<f64>,
}

impl Die {
    /// cm, the centre of mass's height over a rigid table with `face`'s normal straight down:
    /// the die's support in that direction.
    pub fn rest_height(&self, face: usize) -> f64 {
        let n = self.shape().faces[face].normal;
        let c = self.mass_properties().centre_of_mass;
        self.sphere_centres()
            .iter()
            .zip(self.radii())
            .map(|(x, r)| n.dot(&(x - c)) + r)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// cm, the centre of mass's height balanced on the (rounded) edge between vertices `i` and
    /// `j`: the cone joining their spheres where the table is normal to it, or the nearer
    /// sphere when the die would balance on a vertex instead.
    pub fn edge_height(&self, i: usize, j: usize) -> f64 {
        let c = self.mass_properties().centre_of_mass;
        let (ci, cj) = (self.sphere_centres()[i] - c, self.sphere_centres()[j] - c);
        let (ri, rj) = (self.radii()[i], self.radii()[j]);
        let (e, dr) = (cj - ci, rj - ri);
        let slope = |t: f64| {
            let p = ci + e * t;
            p.dot(&e) + dr * p.norm()
        };
        let height = |t: f64| (ci + e * t).norm() + ri + dr * t;
        if slope(0.0) >= 0.0 {
            return height(0.0);
        }
        if slope(1.0) <= 0.0 {
            return height(1.0);
        }
        // The slope rises monotonically in t (docs/model.md): bisect to the last bit.
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            if slope(mid) < 0.0 { lo = mid } else { hi = mid }
        }
        height(0.5 * (lo + hi))
    }

    /// cm, the least rise of the centre that tips the die off `face` and the edge it goes
    /// over; `None` when the die cannot rest on that face.
    pub fn face_tipping(&self, face: usize) -> Option<Tipping> {
        if !self.holds(face) {
            return None;
        }
        let rest = self.rest_height(face);
        let vertices = &self.shape().faces[face].vertices;
        (0..vertices.len())
            .map(|a| {
                let (i, j) = (vertices[a], vertices[(a + 1) % vertices.len()]);
                Tipping {
                    face,
                    edge: (i.min(j), i.max(j)),
                    rise: self.edge_height(i, j) - rest,
                }
            })
            .min_by(|a, b| a.rise.total_cmp(&b.rise))
    }

    /// The die's tipping barrier: the least tip over all faces it can rest on.
    pub fn tipping(&self) -> Tipping {
        (0..self.shape().faces.len())
            .filter_map(|f| self.face_tipping(f))
            .min_by(|a, b| a.rise.total_cmp(&b.rise))
            .expect("a convex die rests on at least one face")
    }

    /// How the die rests on `face` on a table whose every contact point is a spring of
    /// `stiffness` (dyn/cm) under `gravity` (cm/s²): level, `M·g/(n·k)` deep, when the face's
    /// points sit evenly about the centre's foot, else tilted until the springs' moments cancel.
    /// `None` when a point would lift off (the face is not held on all its points).
    pub fn rest_depth(&self, face: usize, stiffness: f64, gravity: f64) -> Option<RestDepth> {
        let f = &self.shape().faces[face];
        let props = self.mass_properties();
        let c = props.centre_of_mass;
        let on_plane = |x: &Vector3<f64>| x - f.normal * f.height_of(x);
        let foot = on_plane(&c);
        let e1 = (on_plane(&self.sphere_centres()[f.vertices[0]]) - foot)
            .try_normalize(0.0)
            .unwrap_or_else(|| f.normal.cross(&Vector3::x()).normalize());
        let e2 = f.normal.cross(&e1);
        let uw: Vec<(f64, f64)> = f
            .vertices
            .iter()
            .map(|&k| {
                let r = self.sphere_centres()[k] - foot;
                (r.dot(&e1), r.dot(&e2))
            })
            .collect();
        let mut a = Matrix3::zeros();
        for &(u, w) in &uw {
            let row = Vector3::new(1.0, u, w);
            a += row * row.transpose();
        }
        let b = Vector3::new(props.mass * gravity / stiffness, 0.0, 0.0);
        let x = a.lu().solve(&b)?;
        let points: Vec<f64> = uw.iter().map(|&(u, w)| x[0] + x[1] * u + x[2] * w).collect();
        points
            .iter()
            .all(|&d| d > 0.0)
            .then_some(RestDepth { centre: x[0], points })
    }
}
