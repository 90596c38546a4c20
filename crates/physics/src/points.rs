//! A body as its contact points and its mass (docs/model.md, "A body of N points"): `N`
//! points in the body's frame, each the centre of a sphere of its own rounding radius (0: a
//! sharp corner; a convex body with rounded corners touches a plane at its lowest sphere), the mass,
//! the centre of mass and the inertia tensor about it, and the outward normals of its faces
//! with the number each shows. A convex polyhedron's geometry gives all of it: its vertices,
//! its mass properties and its faces.
//!
//! From it the step's body constants follow ([`PointBody::body_constants`]); which face is
//! down and which is up are its faces' doing ([`PointBody::face_down`], [`PointBody::face_up`]),
//! not a box's.

use super::contact::Law;
use super::initial::InitialCondition;
use super::kernel::{BodyConstants, Constants, Faces, Kernel};
use super::model::principal_frame;
use super::params::Params;
use super::sim::RUNAWAY_ENERGY_FACTOR;
use super::stopping::StopRule;
use nalgebra::{Matrix3, Vector3};

pub use super::params::MAX_FACES;

/// A rigid body of `N` contact points (4 ≤ N ≤ 64) with its mass properties and faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointBody<const N: usize> {
    /// cm, the points relative to the centre of mass, body frame.
    points: [Vector3<f64>; N],
    /// cm, each point's rounding radius.
    radii: [f64; N],
    /// g.
    mass: f64,
    /// g·cm², about the centre of mass, body frame.
    inertia: Matrix3<f64>,
    /// Outward unit normals of the faces (body frame), and the number each shows; the first
    /// `face_count` are the body's.
    normals: [Vector3<f64>; MAX_FACES],
    numbers: [u8; MAX_FACES],
    face_count: usize,
    /// The points its orientation is read off: `[o, x, y]`, `x − o` and `y − o` not parallel.
    frame: [usize; 3],
    /// The stopping rule on a level table, erg (with rules per face, the widest of them,
    /// which screens), and the energy to tip it over an edge from its lowest face.
    stop_rule: StopRule,
    edge_energy: f64,
    /// The rule of each face down, in the faces' order, when they differ
    /// ([`PointBody::with_face_rules`]).
    face_rules: Option<[StopRule; MAX_FACES]>,
}

/// Why a body cannot be made, in words.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyError(pub String);

impl<const N: usize> PointBody<N> {
    /// The body with `vertices` (cm, body frame), each rounded by `radius` (cm), of `mass`
    /// (g) with its centre of mass at `centre_of_mass` (cm, body frame) and the inertia tensor
    /// `inertia` about it (g·cm², body frame); `faces`: each face's outward normal (body
    /// frame, any length) and the number it shows. `stop_rule` and `edge_energy` (erg) are
    /// the body's on a level table: what its faces' and edges' passes give.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        vertices: [Vector3<f64>; N],
        radius: f64,
        mass: f64,
        centre_of_mass: Vector3<f64>,
        inertia: Matrix3<f64>,
        faces: &[(Vector3<f64>, u8)],
        stop_rule: StopRule,
        edge_energy: f64,
    ) -> Result<PointBody<N>, BodyError> {
        let error = |why: String| Err(BodyError(why));
        if !(4..=64).contains(&N) {
            return error(format!("a body has 4 to 64 contact points, not {N}"));
        }
        let finite = |v: &Vector3<f64>| v.iter().all(|x| x.is_finite());
        if !vertices.iter().all(finite) || !finite(&centre_of_mass) {
            return error("every vertex and the centre of mass must be finite".into());
        }
        if !(radius >= 0.0 && radius.is_finite() && mass > 0.0 && mass.is_finite()) {
            return error(format!("radius {radius} cm must be ≥ 0 and mass {mass} g > 0"));
        }
        let eigen = inertia.symmetric_eigen();
        if (inertia - inertia.transpose()).norm() > 1e-12 * inertia.norm()
            || !eigen.eigenvalues.iter().all(|&i| i > 0.0 && i.is_finite())
        {
            return error("the inertia tensor must be symmetric with positive moments".into());
        }
        if faces.is_empty() || faces.len() > MAX_FACES {
            return error(format!("a body has 1 to {MAX_FACES} faces, not {}", faces.len()));
        }
        let points = vertices.map(|v| v - centre_of_mass);
        let Some(frame) = frame_points(&points) else {
            return error("the points all lie on one line".into());
        };
        let mut normals = [Vector3::zeros(); MAX_FACES];
        let mut numbers = [0; MAX_FACES];
        for (k, (normal, number)) in faces.iter().enumerate() {
            if !(normal.norm() > 0.0 && finite(normal)) {
                return error(format!("face {number} has no normal"));
            }
            normals[k] = normal.normalize();
            numbers[k] = *number;
        }
        Ok(PointBody {
            points,
            radii: [radius; N],
            mass,
            inertia,
            normals,
            numbers,
            face_count: faces.len(),
            frame,
            stop_rule,
            edge_energy,
            face_rules: None,
        })
    }

    /// This body with point `k` rounded by `radii[k]` (cm) instead of the one radius it was
    /// made with (a die whose corners wore unevenly).
    pub fn with_radii(mut self, radii: [f64; N]) -> Result<PointBody<N>, BodyError> {
        if let Some(k) = radii.iter().position(|r| !(*r >= 0.0 && r.is_finite())) {
            return Err(BodyError(format!(
                "point {}'s radius {} cm must be ≥ 0",
                k + 1,
                radii[k]
            )));
        }
        self.radii = radii;
        Ok(self)
    }

    /// This body stopping by `rules[f]` while face `f` (in the order of its faces) is the face
    /// it shows, its normal as given most nearly up ([`PointBody::face_up`]; a die gives its
    /// faces' normals reversed, so that is the die's face `f` down), instead of one rule for
    /// every face: a body whose faces rest at different heights or hold it by different
    /// barriers (docs/model.md, "Stopping a die of any shape"). The step screens with the
    /// widest of them.
    pub fn with_face_rules(mut self, rules: &[StopRule]) -> Result<PointBody<N>, BodyError> {
        if rules.len() != self.face_count {
            return Err(BodyError(format!(
                "{} stopping rules for {} faces: give one a face",
                rules.len(),
                self.face_count
            )));
        }
        let mut by_face = [StopRule::NEVER; MAX_FACES];
        by_face[..rules.len()].copy_from_slice(rules);
        self.stop_rule = StopRule::widest(rules);
        self.face_rules = Some(by_face);
        Ok(self)
    }

    /// g.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// cm, the points relative to the centre of mass, body frame.
    pub fn points(&self) -> &[Vector3<f64>; N] {
        &self.points
    }

    /// cm, each point's rounding radius.
    pub fn radii(&self) -> &[f64; N] {
        &self.radii
    }

    /// The stopping rule on a level table while face `f` (in the order of its faces) is the
    /// face it shows.
    pub fn stop_rule_on(&self, f: usize) -> StopRule {
        self.face_rules.map_or(self.stop_rule, |rules| rules[f])
    }

    /// Whether its stopping rule depends on the face it shows ([`PointBody::with_face_rules`]).
    pub fn has_face_rules(&self) -> bool {
        self.face_rules.is_some()
    }

    /// g·cm², the inertia tensor about the centre of mass, body frame.
    pub fn inertia(&self) -> Matrix3<f64> {
        self.inertia
    }

    /// cm, the height of the centre of mass above a rigid table when the body rests on face
    /// `f`: the farthest sphere along the face's normal (its centre's reach plus its radius).
    fn rest_height(&self, f: usize) -> f64 {
        let n = &self.normals[f];
        self.points
            .iter()
            .zip(&self.radii)
            .map(|(p, r)| n.dot(p) + r)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// cm, the lowest of [`PointBody::rest_height`] over the faces: the height its
    /// potential energy is measured from.
    pub fn reference_height(&self) -> f64 {
        (0..self.face_count)
            .map(|f| self.rest_height(f))
            .fold(f64::INFINITY, f64::min)
    }

    /// The body-to-world rotation of a body whose points are at `offsets` (cm, world frame,
    /// about the centre of mass), read off its frame points as the step reads them.
    pub fn orientation(&self, offsets: &[Vector3<f64>; N]) -> Matrix3<f64> {
        basis(offsets, self.frame) * basis(&self.points, self.frame).transpose()
    }

    /// The number of the face whose outward normal points most nearly down at `offsets`.
    pub fn face_down(&self, offsets: &[Vector3<f64>; N]) -> u8 {
        self.numbers[self.face_by(offsets, |a, b| b < a)]
    }

    /// The number of the face whose outward normal points most nearly up at `offsets`.
    pub fn face_up(&self, offsets: &[Vector3<f64>; N]) -> u8 {
        self.numbers[self.face_by(offsets, |a, b| b > a)]
    }

    /// The index of the face whose normal's world height `better` prefers over every other's.
    fn face_by(&self, offsets: &[Vector3<f64>; N], better: fn(f64, f64) -> bool) -> usize {
        let row = self.orientation(offsets).row(2).transpose();
        let mut best = 0;
        for f in 1..self.face_count {
            if better(row.dot(&self.normals[best]), row.dot(&self.normals[f])) {
                best = f;
            }
        }
        best
    }

    /// The start of a roll from `initial`: the points' offsets (world frame) and the angular
    /// momentum, `L` as given or `R·I·Rᵀ·ω`.
    pub(crate) fn start(&self, initial: &InitialCondition) -> ([Vector3<f64>; N], Vector3<f64>) {
        let rotation = initial.rotation();
        let offsets = self.points.map(|p| rotation * p);
        let l = match initial.angular_momentum {
            Some(l) => Vector3::from(l),
            None => {
                let r = rotation.matrix();
                r * self.inertia * r.transpose() * Vector3::from(initial.angular_velocity)
            }
        };
        (offsets, l)
    }

    /// The roll of this body from `initial` on `params`' table (its world, ground and
    /// integrator; not its die) under the law `W`: the step's kernel on one lane, placed, its
    /// spin and forces computed, and its runaway bound set as a roll's is.
    pub(crate) fn kernel<W: Law>(
        &self,
        params: &Params,
        initial: &InitialCondition,
    ) -> Kernel<f64, W, N, PointBody<N>> {
        let (c, on_table) = self.on_table::<W>(params);
        let (offsets, l) = self.start(initial);
        let mut kernel = Kernel::placed(c, on_table, initial, offsets, l);
        let e = kernel.energy();
        let energy = ((e.translational + e.rotational) + e.gravitational) + e.elastic;
        kernel.c.stop.runaway = RUNAWAY_ENERGY_FACTOR * energy.max(self.edge_energy);
        kernel
    }

    /// The step's constants of this body on `params`' table (its world, ground and
    /// integrator) under the law `W`, `runaway` still +∞, and the body as the kernel holds it:
    /// each face's rule as the law's table has it, as the widest is.
    pub(crate) fn on_table<W: Law>(&self, params: &Params) -> (Constants<f64, W, N>, PointBody<N>) {
        let dt = params.integrator.dt;
        let body = self.body_constants(W::gravity(params), params.world.gravity, dt);
        let c = Constants::with_body(params, body, self.edge_energy, self.stop_rule);
        let mut on_table = *self;
        if let Some(rules) = &mut on_table.face_rules {
            for rule in rules.iter_mut() {
                *rule = W::stop_rule(*rule, params, self.edge_energy);
            }
        }
        (c, on_table)
    }

    /// The step's body constants under gravity `[gx, gy, gz]` (cm/s², the table's frame;
    /// `g` its size) with step `dt` (s). An isotropic body turns by the paper's rotation;
    /// any other by the splitting about its principal axes, which the step reads off the
    /// frame points.
    pub(crate) fn body_constants(&self, [gx, gy, gz]: [f64; 3], g: f64, dt: f64) -> BodyConstants<f64, N> {
        let mass = self.mass;
        let (weight_x, weight_y, weight_z) = (mass * gx, mass * gy, mass * gz);
        let a = self.reference_height();
        let m = mass / N as f64;
        let principal = principal_frame(&self.inertia);
        let reading = basis(&self.points, self.frame);
        BodyConstants {
            mass,
            weight_z,
            flight_kick: Vector3::new(
                ((0.0 + weight_x) / mass) * dt,
                ((0.0 + weight_y) / mass) * dt,
                ((0.0 + weight_z) / mass) * dt,
            ),
            half_mass: 0.5 * mass,
            mass_gravity: mass * -gz,
            half_size: a,
            half_corner_mass: 0.5 * m,
            corner_mass_gravity: m * g,
            mass_gravity_half_size: mass * g * a,
            corner_masses: [m; N],
            gravity: g,
            loaded_mass_gravity_half_size: mass * g * a,
            uniform_inertia: self.inertia.trace() / 3.0,
            uniform_mass: mass,
            extra_masses: [0.0; 8],
            inverse_inertia: [0.0; 6],
            axis_scale: [1.0; 3],
            inverse_moments: principal.map_or([0.0; 3], |(moments, _)| moments.map(|i| 1.0 / i).into()),
            // Component j, in the frame read off the points, of principal axis i.
            principal_axes: principal.map_or([0.0; 9], |(_, axes)| {
                let along = reading.transpose() * axes;
                std::array::from_fn(|entry| along[(entry / 3, entry % 3)])
            }),
            principal_corners: match principal {
                Some((_, axes)) => self.points.map(|p| axes.transpose() * p),
                None => [Vector3::zeros(); N],
            },
            frame: self.frame,
            split: principal.is_some(),
            corner_radii: self.radii,
            loaded: false,
            shaped: false,
            // The splitting turns the body every step, in flight too.
            turning: principal.is_some(),
            faced: self.face_rules.is_some(),
            rounded: self.radii.iter().any(|&r| r > 0.0) as u32,
        }
    }
}

impl<const N: usize> Faces<N> for PointBody<N> {
    /// The rule of the face it shows (one rule whatever the face for a body without rules
    /// per face).
    fn stop_rule_at(&self, offsets: &[Vector3<f64>; N]) -> StopRule {
        match &self.face_rules {
            Some(rules) => rules[self.face_by(offsets, |a, b| b > a)],
            None => self.stop_rule,
        }
    }

    fn face_up_at_rest(&self, offsets: &[Vector3<f64>; N]) -> Option<u8> {
        Some(self.face_up(offsets))
    }
}

/// The first point, the next one apart from it and the next one off the line through both:
/// the points a body's orientation is read off.
fn frame_points<const N: usize>(points: &[Vector3<f64>; N]) -> Option<[usize; 3]> {
    let scale = points.iter().map(|p| p.norm()).fold(0.0, f64::max);
    let x = (1..N).find(|&k| (points[k] - points[0]).norm() > 1e-9 * scale)?;
    let along = points[x] - points[0];
    let y = (1..N).find(|&k| along.cross(&(points[k] - points[0])).norm() > 1e-6 * along.norm() * scale)?;
    Some([0, x, y])
}

/// The orthonormal frame `offsets` give at `[o, x, y]`, as columns, by the step's
/// arithmetic ([`crate::spin`]'s Gram–Schmidt): x along `x − o`, y the part of `y − o`
/// normal to it, z their cross product.
fn basis<const N: usize>(offsets: &[Vector3<f64>; N], [o, x, y]: [usize; 3]) -> Matrix3<f64> {
    let ex = (offsets[x] - offsets[o]).normalize();
    let along = offsets[y] - offsets[o];
    let ey = (along - ex * ex.dot(&along)).normalize();
    Matrix3::from_columns(&[ex, ey, ex.cross(&ey)])
}
