//! A general die body (docs/model.md, "Real dice"): a cuboid of three half sizes with
//! rounded corners and edges, drilled pips and extra corner masses. The paper's sharp cube
//! (loaded or not) never comes here: it keeps the paper's arithmetic bit for bit.
//!
//! The body is the box of half sizes `b = a − r` grown by a ball of radius `r`. Its mass
//! properties are exact closed forms (the rounded box cut into an inner box, 6 face slabs,
//! 12 quarter cylinders and 8 ball octants; each pip a spherical cap), its inertia tensor
//! about the centre of mass is constant in the body frame, and a step turns it with the
//! body: `ω = R·I⁻¹·Rᵀ·L`, with `R`'s columns read off the contact spheres' centres.

use super::body::{
    CORNER_SIGNS, FACE_NORMALS, contact_sphere_centres, face_most_nearly_up, opposite_face, pips,
    sphere_centres,
};
use super::initial::InitialCondition;
use super::lane::Lane;
use super::params::{Die, Params};
use super::stopping::{StopRule, lowest_potential_at};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

/// Mass, centre of mass and inertia tensor of a body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// g.
    pub mass: f64,
    /// cm, body frame, relative to the geometric centre.
    pub centre_of_mass: Vector3<f64>,
    /// g·cm², about the centre of mass, body frame.
    pub inertia: Matrix3<f64>,
}

/// The rounded box of half sizes `a` and corner radius `r`: its volume (cm³) and its
/// second moments `∫x_i² dV` about the centre (cm⁵), docs/model.md "Real dice".
pub(crate) fn rounded_box(a: [f64; 3], r: f64) -> (f64, [f64; 3]) {
    let b = a.map(|a| a - r);
    let volume = 8.0 * b[0] * b[1] * b[2]
        + 8.0 * r * (b[1] * b[2] + b[0] * b[2] + b[0] * b[1])
        + 2.0 * PI * r * r * (b[0] + b[1] + b[2])
        + 4.0 / 3.0 * PI * r.powi(3);
    let moments = std::array::from_fn(|i| {
        let (bi, bj, bk) = (b[i], b[(i + 1) % 3], b[(i + 2) % 3]);
        let inner = 8.0 * bi * bj * bk * bi * bi / 3.0;
        let slabs_across = 8.0 * bj * bk * ((bi + r).powi(3) - bi.powi(3)) / 3.0;
        let slabs_along = 8.0 * r * bi * (bj + bk) * bi * bi / 3.0;
        let edges_along = 2.0 * PI * r * r * bi * bi * bi / 3.0;
        let edges_across =
            2.0 * (bj + bk) * (PI * r * r * bi * bi + 8.0 * bi * r.powi(3) / 3.0 + PI * r.powi(4) / 4.0);
        let corners =
            4.0 / 3.0 * PI * r.powi(3) * bi * bi + PI * r.powi(4) * bi + 4.0 / 15.0 * PI * r.powi(5);
        inner + slabs_across + slabs_along + edges_along + edges_across + corners
    });
    (volume, moments)
}

/// Depth over opening radius below which [`cap`] takes its moments in `ρ` and `h` alone.
const SHALLOW_CAP: f64 = 1e-6;

/// A spherical cap of opening radius `rho` and depth `h`, measured from its apex along its
/// axis `τ ∈ [0, h]` (cross-section `π·(2Rτ − τ²)`): `(V, ∫τ dV, ∫τ² dV, ∫u² dV)` with `u`
/// either coordinate across the axis (cm³, cm⁴, cm⁵, cm⁵).
///
/// The sphere's radius `R = (ρ² + h²)/(2h)` grows without bound as the pip gets shallow, and
/// the `R` form's terms overflow and underflow long before `h` reaches 0 (`4R²·h³` is ∞·0 =
/// NaN near `h = 10⁻¹⁵⁷`, and `h⁵` is 0 from `10⁻⁶²`). Below `h = 10⁻⁶·ρ` (a nanometre for a
/// real pip) the same moments are taken in `ρ` and `h` alone (docs/model.md, "Pips"), finite
/// for every depth and vanishing with it: a vanishing pip leaves the undrilled die. The `R`
/// form stays above, so every depth a preset has used keeps its values bit for bit.
pub(crate) fn cap(rho: f64, h: f64) -> (f64, f64, f64, f64) {
    if h >= SHALLOW_CAP * rho {
        let big_r = (rho * rho + h * h) / (2.0 * h);
        let volume = PI * (big_r * h * h - h.powi(3) / 3.0);
        let first = PI * (2.0 * big_r * h.powi(3) / 3.0 - h.powi(4) / 4.0);
        let second = PI * (big_r * h.powi(4) / 2.0 - h.powi(5) / 5.0);
        let across = PI / 4.0 * (4.0 * big_r * big_r * h.powi(3) / 3.0 - big_r * h.powi(4) + h.powi(5) / 5.0);
        return (volume, first, second, across);
    }
    let (s, h2) = (rho * rho, h * h);
    let volume = PI * h * (3.0 * s + h2) / 6.0;
    let first = PI * h2 * (4.0 * s + h2) / 12.0;
    let second = PI * h2 * h * (5.0 * s + h2) / 20.0;
    let across = PI * h * (10.0 * s * s + 5.0 * s * h2 + h2 * h2) / 120.0;
    (volume, first, second, across)
}

/// Mass, first moment (g·cm) and second-moment matrix `∫x·xᵀ dm` (g·cm²) of `die`'s body
/// about its geometric centre.
fn moments(die: &Die) -> (f64, Vector3<f64>, Matrix3<f64>) {
    let (volume, box_moments) = rounded_box(die.half_sizes, die.corner_radius);
    let body_mass = 8.0 * die.corner_mass;
    let density = body_mass / volume;
    let mut mass = body_mass;
    let mut first = Vector3::zeros();
    let mut second = Matrix3::from_diagonal(&Vector3::from(box_moments)) * density;
    for pip in pips(die) {
        let (v, m1, m2, across) = cap(pip.radius, pip.depth);
        let n = Vector3::from(pip.normal);
        let apex = Vector3::from(pip.centre) - n * pip.depth;
        let removed = density * v;
        mass -= removed;
        first -= (apex * v + n * m1) * density;
        let axial = n * n.transpose();
        second -= (apex * apex.transpose() * v
            + (apex * n.transpose() + n * apex.transpose()) * m1
            + axial * m2
            + (Matrix3::identity() - axial) * across)
            * density;
    }
    for (s, &dm) in CORNER_SIGNS.iter().zip(&die.extra_corner_mass) {
        let x = Vector3::from(std::array::from_fn(|i| s[i] * die.half_sizes[i]));
        mass += dm;
        first += x * dm;
        second += x * x.transpose() * dm;
    }
    (mass, first, second)
}

/// A body's mass properties: a plain function of the die, for the step and for any reader.
pub fn mass_properties(die: &Die) -> MassProperties {
    let (mass, first, second) = moments(die);
    let centre_of_mass = first / mass;
    let about_centre = second - centre_of_mass * centre_of_mass.transpose() * mass;
    MassProperties {
        mass,
        centre_of_mass,
        inertia: Matrix3::identity() * about_centre.trace() - about_centre,
    }
}

/// One face down: where the body rests and what it takes to tip it over each edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FaceReadout {
    /// 1..6, the face down.
    pub(crate) face: u8,
    /// cm, the centre of mass above a rigid table.
    pub(crate) rest_height: f64,
    /// cm, how far the body sinks into this table at rest.
    pub(crate) rest_depth: f64,
    /// erg, the lowest rise in potential from rest on this face on this table to balancing on
    /// one of its edges, springs included: what tells a settled body from a rocking one.
    pub(crate) spring_pass: f64,
    /// The four neighbouring faces it can tip onto, each with the energy (erg) to balance
    /// it on that edge from rest on a rigid table, rounded edge included.
    pub(crate) edges: [(u8, f64); 4],
}

/// The general body as a roll steps it: its mass properties and everything per step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Shape {
    pub(crate) properties: MassProperties,
    /// g, the whole die as the roll weighs it: the undrilled body's `8·m` less the pips plus
    /// the extra corner masses (the sum the paper's cube is weighed by, with the pips taken
    /// off, rather than `properties.mass`'s integral).
    pub(crate) mass: f64,
    /// `I⁻¹` about the centre of mass, body frame, by its upper triangle
    /// `(xx, xy, xz, yy, yz, zz)`, 1/(g·cm²).
    pub(crate) inverse_inertia: [f64; 6],
    /// 1/cm, `1/(2·b_i)`: a sphere-centre difference along body axis `i` times this is the
    /// axis's unit vector in the world frame.
    pub(crate) axis_scale: [f64; 3],
    /// cm, the corner radius.
    pub(crate) radius: f64,
    /// cm, the die's half sizes `a`.
    pub(crate) half_sizes: [f64; 3],
    /// cm, the half sizes of the box the corner spheres sit on, `a − r`.
    flat: [f64; 3],
    /// cm, the height of the centre of mass the potential is measured from: the lowest of
    /// the rest heights on a rigid table.
    pub(crate) reference_height: f64,
    /// erg, the lowest edge pass over every face and edge (docs/model.md, "Real dice").
    pub(crate) edge_energy: f64,
    /// cm, the deepest any face sinks into the table at rest.
    pub(crate) resting_depth: f64,
    /// rad/s, the fastest contact mode.
    pub(crate) rocking_frequency: f64,
    face_rules: [StopRule; 6],
}

impl Shape {
    /// `p`'s body (any die; a roll uses it only for those that are not the paper's cube).
    pub(crate) fn new(p: &Params) -> Shape {
        let die = &p.die;
        let properties = mass_properties(die);
        let inverse = properties
            .inertia
            .try_inverse()
            .unwrap_or_else(|| Matrix3::from_element(f64::NAN));
        let sym = |i: usize, j: usize| 0.5 * (inverse[(i, j)] + inverse[(j, i)]);
        let b = die.half_sizes.map(|a| a - die.corner_radius);
        let c = properties.centre_of_mass;
        let height = |f: usize| die.half_sizes[axis(f)] - c.dot(&Vector3::from(FACE_NORMALS[f]));
        let reference_height = (0..6).map(height).fold(f64::INFINITY, f64::min);
        let (faces, face_rules) = read_faces(p, &properties, reference_height);
        let undrilled = 8.0 * die.corner_mass;
        let body = if die.is_drilled() {
            undrilled - pips_mass(die)
        } else {
            undrilled
        };
        Shape {
            properties,
            mass: body + die.extra_corner_mass.iter().sum::<f64>(),
            inverse_inertia: [sym(0, 0), sym(0, 1), sym(0, 2), sym(1, 1), sym(1, 2), sym(2, 2)],
            axis_scale: b.map(|b| 1.0 / (2.0 * b)),
            radius: die.corner_radius,
            half_sizes: die.half_sizes,
            flat: b,
            reference_height,
            edge_energy: faces
                .iter()
                .flat_map(|f| f.edges.iter().map(|e| e.1))
                .fold(f64::INFINITY, f64::min),
            resting_depth: faces.iter().map(|f| f.rest_depth).fold(0.0, f64::max),
            rocking_frequency: rocking_frequency(&properties, b, p.ground.stiffness),
            face_rules,
        }
    }

    /// The face the body rests on if it comes to rest from this orientation: the face the
    /// vertical through the centre of mass leaves the body by, against the box of the
    /// sphere centres (docs/model.md, "Real dice"). The body balances on an edge exactly
    /// where that vertical meets the edge's sphere axis, so this is the face whose basin it
    /// is in; for the paper's cube it is the face most nearly down, but a plate tilted 50°
    /// off its big face still falls back onto it.
    pub(crate) fn face_down(&self, sphere_offsets: &[Vector3<f64>; 8]) -> u8 {
        let o = sphere_offsets;
        // The world's down in the body frame: minus the z row of R, whose columns are the
        // body axes (sphere-centre differences, each 2·b_i long).
        let down = [(4, 0), (2, 1), (1, 2)].map(|(to, i)| -(o[to].z - o[0].z) * self.axis_scale[i]);
        let c = self.properties.centre_of_mass;
        let mut best = (f64::INFINITY, 0);
        for i in 0..3 {
            let sign = if down[i] < 0.0 { -1.0 } else { 1.0 };
            let reach = (self.flat[i] - sign * c[i]) / down[i].abs();
            if reach < best.0 {
                // Faces: −x 1, −y 2, −z 3, +z 4, +y 5, +x 6.
                best = (reach, if sign < 0.0 { i as u8 + 1 } else { 6 - i as u8 });
            }
        }
        if best.1 == 0 {
            opposite_face(face_most_nearly_up(sphere_offsets))
        } else {
            best.1
        }
    }

    /// The stopping rule of the face now down.
    pub(crate) fn stop_rule(&self, sphere_offsets: &[Vector3<f64>; 8]) -> StopRule {
        self.face_rules[self.face_down(sphere_offsets) as usize - 1]
    }

    /// Each face down on `p`'s table (`p` the parameters this body was made from).
    pub(crate) fn faces(&self, p: &Params) -> [FaceReadout; 6] {
        read_faces(p, &self.properties, self.reference_height).0
    }

    /// The widest rule over the faces (the step's cheap screen).
    pub(crate) fn widest_stop_rule(&self) -> StopRule {
        StopRule::widest(&self.face_rules)
    }

    /// cm, the contact spheres' centres relative to the centre of mass at the start, world
    /// frame.
    pub(crate) fn initial_sphere_offsets(&self, initial: &InitialCondition) -> [Vector3<f64>; 8] {
        let rotation = initial.rotation();
        let c = self.properties.centre_of_mass;
        sphere_centres(self.flat).map(|x| rotation * (x - c))
    }

    /// g·cm²/s: `L` as given, or `R·I·Rᵀ·ω` for a start stated as an angular velocity.
    pub(crate) fn initial_angular_momentum(&self, initial: &InitialCondition) -> Vector3<f64> {
        match initial.angular_momentum {
            Some(l) => Vector3::from(l),
            None => {
                let rotation = initial.rotation();
                rotation
                    * self.properties.inertia
                    * rotation.transpose()
                    * Vector3::from(initial.angular_velocity)
            }
        }
    }
}

/// g, what drilling removes from `8·m`: the pips' volume at the undrilled body's density.
fn pips_mass(die: &Die) -> f64 {
    let (volume, _) = rounded_box(die.half_sizes, die.corner_radius);
    let density = 8.0 * die.corner_mass / volume;
    pips(die).iter().map(|p| cap(p.radius, p.depth).0).sum::<f64>() * density
}

/// rad/s, the fastest rocking mode on four contact spheres (docs/model.md, "Real dice"):
/// springs `k` (dyn/cm) at `±b_j` (`flat`, cm) rocking the body about axis `i`,
/// `√(4k·b_j²/I_ii)`, the largest over the six pairs of axes (`√(6k/M)` for the paper's
/// cube).
fn rocking_frequency(properties: &MassProperties, flat: [f64; 3], stiffness: f64) -> f64 {
    let b = flat;
    let mut fastest: f64 = 0.0;
    for i in 0..3 {
        for j in (0..3).filter(|&j| j != i) {
            fastest = fastest.max(4.0 * stiffness * b[j] * b[j] / properties.inertia[(i, i)]);
        }
    }
    fastest.sqrt()
}

/// The rest depth and edge energies of each face down, and from them each face's
/// stopping rule: the paper's rule moved to that face's rest and scaled to its lowest
/// edge (docs/model.md, "Real dice").
fn read_faces(p: &Params, properties: &MassProperties, reference: f64) -> ([FaceReadout; 6], [StopRule; 6]) {
    let die = &p.die;
    let weight = properties.mass * p.world.gravity;
    let (k, r) = (p.ground.stiffness, die.corner_radius);
    let c = properties.centre_of_mass;
    let spheres = contact_sphere_centres(die);
    let frac = p.integrator.stop_energy_fraction;
    // Heights of the sphere bottoms relative to the centre of mass with `down` (body
    // frame, unit) pointing at the table, ascending.
    let offsets = |down: &Vector3<f64>| {
        let mut o = spheres.map(|x| -(x - c).dot(down) - r);
        o.sort_by(f64::total_cmp);
        o
    };
    let mut faces = [FaceReadout {
        face: 0,
        rest_height: 0.0,
        rest_depth: 0.0,
        spring_pass: 0.0,
        edges: [(0, 0.0); 4],
    }; 6];
    let mut rules = [StopRule::NEVER; 6];
    let lowest = |down: &Vector3<f64>| lowest_potential_at(weight, k, reference, &offsets(down));
    for (f, normal) in FACE_NORMALS.iter().enumerate() {
        let n_f = Vector3::from(*normal);
        let (a_f, c_f) = (die.half_sizes[axis(f)], c.dot(&n_f));
        let rest_height = a_f - c_f;
        let mut edges = [(0u8, 0.0); 4];
        let mut v_edge = f64::INFINITY;
        for (slot, e) in (0..6).filter(|&e| e != f && e != 5 - f).enumerate() {
            let n_e = Vector3::from(FACE_NORMALS[e]);
            let lever_f = a_f - r - c_f;
            let lever_e = die.half_sizes[axis(e)] - r - c.dot(&n_e);
            let balanced = r + lever_f.hypot(lever_e);
            edges[slot] = (e as u8 + 1, weight * (balanced - rest_height));
            let down = (n_f * lever_f + n_e * lever_e).normalize();
            v_edge = v_edge.min(lowest(&down).1);
        }
        let (centre, v_rest) = lowest(&n_f);
        faces[f] = FaceReadout {
            face: f as u8 + 1,
            rest_height,
            rest_depth: rest_height - centre,
            spring_pass: v_edge - v_rest,
            edges,
        };
        let pass = edges.iter().map(|e| e.1).fold(f64::INFINITY, f64::min);
        let rigid_rest = weight * (rest_height - reference);
        let threshold = (rigid_rest + frac * pass).min(v_edge - 0.5 * (1.0 - frac) * pass);
        rules[f] = if threshold > v_rest && centre > 0.0 {
            StopRule {
                energy_threshold: threshold,
                kinetic_threshold: threshold - v_rest,
            }
        } else {
            StopRule::NEVER
        };
    }
    (faces, rules)
}

/// The body axis (0 x, 1 y, 2 z) of face index `f` (0..5).
fn axis(f: usize) -> usize {
    FACE_NORMALS[f]
        .iter()
        .position(|&x| x != 0.0)
        .expect("a face normal is an axis")
}

/// rad/s, `ω = R·I⁻¹·Rᵀ·L` per lane: `R`'s columns are the body axes in the world frame,
/// the sphere-centre differences along each axis (corner 1 to 5, 1 to 3, 1 to 2) times
/// `1/(2·b_i)`; `I⁻¹` is the body-frame inverse by its upper triangle.
#[inline(always)]
pub(crate) fn angular_velocity<L: Lane>(
    inverse: &[L; 6],
    axis_scale: &[L; 3],
    offsets: &[Vector3<L>; 8],
    l: &Vector3<L>,
) -> Vector3<L> {
    let o = offsets;
    let column = |to: usize, s: L| {
        Vector3::new(
            (o[to].x - o[0].x) * s,
            (o[to].y - o[0].y) * s,
            (o[to].z - o[0].z) * s,
        )
    };
    let (ex, ey, ez) = (
        column(4, axis_scale[0]),
        column(2, axis_scale[1]),
        column(1, axis_scale[2]),
    );
    let dot = |a: &Vector3<L>| (a.x * l.x + a.y * l.y) + a.z * l.z;
    let (lx, ly, lz) = (dot(&ex), dot(&ey), dot(&ez));
    let [xx, xy, xz, yy, yz, zz] = *inverse;
    let wx = (xx * lx + xy * ly) + xz * lz;
    let wy = (xy * lx + yy * ly) + yz * lz;
    let wz = (xz * lx + yz * ly) + zz * lz;
    Vector3::new(
        (ex.x * wx + ey.x * wy) + ez.x * wz,
        (ex.y * wx + ey.y * wy) + ez.y * wz,
        (ex.z * wx + ey.z * wy) + ez.z * wz,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cube::Cube;

    fn die(half_sizes: [f64; 3], radius: f64) -> Die {
        Die {
            half_sizes,
            corner_radius: radius,
            ..Params::DEFAULT.die
        }
    }

    fn close(a: f64, b: f64, relative: f64) -> bool {
        (a - b).abs() <= relative * b.abs().max(1e-300)
    }

    /// The largest difference between two bodies' mass (g), centre of mass (cm) and inertia
    /// (g·cm²), each relative to the undrilled body's own scale.
    fn distance(a: &MassProperties, undrilled: &MassProperties) -> f64 {
        let scale_i = undrilled.inertia.norm();
        let scale_c = undrilled.centre_of_mass.norm().max(1.0);
        ((a.mass - undrilled.mass).abs() / undrilled.mass)
            .max((a.centre_of_mass - undrilled.centre_of_mass).norm() / scale_c)
            .max((a.inertia - undrilled.inertia).norm() / scale_i)
    }

    #[test]
    fn every_allowed_pip_gives_finite_positive_definite_mass_properties_tending_to_the_undrilled() {
        // `roll --set die.pip_diameter=0.3 --set die.pip_depth=1e-200` ran away after one step
        // with a NaN inertia (R² overflowed), and at 1e-320 R itself was infinite.
        use rand::{RngExt, SeedableRng};
        let mut rng = rand::rngs::StdRng::seed_from_u64(36);
        for case in 0..400 {
            let half_sizes: [f64; 3] = std::array::from_fn(|_| rng.random_range(0.2..3.0));
            let smallest = half_sizes.iter().copied().fold(f64::INFINITY, f64::min);
            let radius = rng.random_range(0.0..0.4 * smallest);
            let widest = (0.5 * smallest).min(smallest - 2.0 * radius);
            let mut p = Params {
                die: Die {
                    pip_diameter: rng.random_range(0.01..=1.0) * widest,
                    ..die(half_sizes, radius)
                },
                ..Params::default()
            };
            let undrilled = mass_properties(&p.die);
            // Depths from a hemisphere down through the subnormals, log-uniform, then the
            // smallest positive double.
            let hemisphere = 0.5 * p.die.pip_diameter;
            let mut depths: Vec<f64> = (0..12)
                .map(|_| hemisphere * 10f64.powf(-rng.random_range(0.0..323.0)))
                .collect();
            depths.extend([hemisphere, 1e-200, 1e-320, f64::from_bits(1)]);
            depths.retain(|&h| h > 0.0 && h <= hemisphere);
            // The slope of the change at a moderate depth bounds it below (continuity at 0).
            let moderate = 1e-6 * hemisphere;
            let slope = {
                let mut q = p;
                q.die.pip_depth = moderate;
                distance(&mass_properties(&q.die), &undrilled) / moderate
            };
            for h in depths {
                p.die.pip_depth = h;
                assert_eq!(p.validate(), Ok(()), "case {case}: {:?}", p.die);
                let m = mass_properties(&p.die);
                let what = format!("case {case}: {:?}, depth {h:e}: {m:?}", p.die);
                assert!(
                    m.mass.is_finite() && m.mass > 0.0 && m.mass <= undrilled.mass,
                    "{what}"
                );
                assert!(m.centre_of_mass.iter().all(|x| x.is_finite()), "{what}");
                assert!(m.inertia.iter().all(|x| x.is_finite()), "{what}");
                let asymmetry = (m.inertia - m.inertia.transpose()).norm();
                assert!(asymmetry <= 1e-12 * m.inertia.norm(), "{what}");
                let eigen = m.inertia.symmetric_eigen().eigenvalues;
                assert!(eigen.iter().all(|&e| e > 0.0), "{what}: eigenvalues {eigen:?}");
                assert!(m.inertia.cholesky().is_some(), "{what}");
                if h <= moderate {
                    let bound = 2.0 * slope * h + 16.0 * f64::EPSILON;
                    let d = distance(&m, &undrilled);
                    assert!(
                        d <= bound,
                        "{what}: {d:e} from the undrilled die, more than {bound:e}"
                    );
                }
                let shape = Shape::new(&p);
                assert!(
                    shape.mass.is_finite() && shape.rocking_frequency.is_finite(),
                    "{what}"
                );
                assert!(shape.inverse_inertia.iter().all(|x| x.is_finite()), "{what}");
            }
        }
    }

    #[test]
    fn the_shallow_cap_moments_are_the_r_forms_where_both_are_finite() {
        // The ρ, h forms are the R forms rewritten with 2R·h = ρ² + h²: where the R form is
        // still sound both must agree to rounding, on both sides of the switch between them.
        let rho = 0.15;
        for h in [0.15f64, 0.1, 1e-3, 1e-6, 1.5e-7, 1e-9] {
            let big_r = (rho * rho + h * h) / (2.0 * h);
            let r_form = (
                PI * (big_r * h * h - h.powi(3) / 3.0),
                PI * (2.0 * big_r * h.powi(3) / 3.0 - h.powi(4) / 4.0),
                PI * (big_r * h.powi(4) / 2.0 - h.powi(5) / 5.0),
                PI / 4.0 * (4.0 * big_r * big_r * h.powi(3) / 3.0 - big_r * h.powi(4) + h.powi(5) / 5.0),
            );
            let s = rho * rho;
            let polynomial = (
                PI * h * (3.0 * s + h * h) / 6.0,
                PI * h * h * (4.0 * s + h * h) / 12.0,
                PI * h.powi(3) * (5.0 * s + h * h) / 20.0,
                PI * h * (10.0 * s * s + 5.0 * s * h * h + h.powi(4)) / 120.0,
            );
            let used = cap(rho, h);
            for (a, b) in [
                (used.0, polynomial.0),
                (used.3, polynomial.3),
                (r_form.0, polynomial.0),
                (r_form.1, polynomial.1),
                (r_form.2, polynomial.2),
                (r_form.3, polynomial.3),
            ] {
                assert!(close(a, b, 1e-12), "h = {h:e}: {a:e} against {b:e}");
            }
        }
        // Half a ball of radius ρ: 2πρ³/3 and, across the axis, 2πρ⁵/15.
        let (v, _, _, across) = cap(rho, rho);
        assert!(close(v, 2.0 * PI * rho.powi(3) / 3.0, 1e-14));
        assert!(close(across, 2.0 * PI * rho.powi(5) / 15.0, 1e-14));
        // Past the overflow the moments still vanish with the depth, like π·ρ²·h/2.
        let (v, first, second, across) = cap(rho, 1e-200);
        assert!(close(v, PI * rho * rho * 1e-200 / 2.0, 1e-14), "{v:e}");
        assert!([first, second].iter().all(|x| *x >= 0.0 && *x < 1e-300));
        assert!(
            close(across, PI * rho.powi(4) * 1e-200 / 12.0, 1e-14),
            "{across:e}"
        );
    }

    #[test]
    fn a_sharp_cuboid_has_the_textbook_inertia() {
        // I_xx = M·(ay² + az²)/3 and so on, no products of inertia, centre in the middle.
        let d = die([0.5, 1.0, 1.7], 0.0);
        let p = mass_properties(&d);
        let m = 8.0 * d.corner_mass;
        let [ax, ay, az] = d.half_sizes;
        let expected = [ay * ay + az * az, ax * ax + az * az, ax * ax + ay * ay].map(|s| m * s / 3.0);
        for (i, expected) in expected.into_iter().enumerate() {
            assert!(close(p.inertia[(i, i)], expected, 1e-12), "{i}: {}", p.inertia);
            for j in (0..3).filter(|&j| j != i) {
                assert!(p.inertia[(i, j)].abs() < 1e-15);
            }
        }
        assert_eq!(p.mass, m);
        assert!(p.centre_of_mass.norm() < 1e-15);
        // The paper's cube is its special case.
        let cube = mass_properties(&Params::DEFAULT.die);
        assert!(close(cube.inertia[(0, 0)], 16.0 / 3.0, 1e-15));
    }

    /// The rounded box cut into slices across x: a slice at `|x| ≤ b_x` is the rounded
    /// rectangle of half sizes `(a_y, a_z)` and radius r; beyond, one of half sizes
    /// `b + ρ` and radius `ρ = √(r² − (|x| − b_x)²)`. Simpson's rule over `x` of its area,
    /// and of `x²` times it, gives the volume and `∫x² dV` along another path.
    fn sliced(a: [f64; 3], r: f64) -> (f64, f64) {
        let b = a.map(|a| a - r);
        let area = |x: f64| {
            let rho = if x.abs() <= b[0] {
                r
            } else {
                (r * r - (x.abs() - b[0]).powi(2)).max(0.0).sqrt()
            };
            4.0 * b[1] * b[2] + 4.0 * rho * (b[1] + b[2]) + PI * rho * rho
        };
        let n = 200_000;
        let h = 2.0 * a[0] / n as f64;
        let (mut volume, mut second) = (0.0, 0.0);
        for i in 0..=n {
            let x = -a[0] + h * i as f64;
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            volume += w * area(x);
            second += w * x * x * area(x);
        }
        (volume * h / 3.0, second * h / 3.0)
    }

    #[test]
    fn the_rounded_box_matches_its_slices_and_the_ball() {
        let (a, r) = ([1.3, 0.7, 0.9], 0.35);
        let (volume, moments) = rounded_box(a, r);
        let (v, sx) = sliced(a, r);
        // Simpson's error on the corners' square-root profile limits the agreement.
        assert!(close(volume, v, 1e-7), "{volume} {v}");
        assert!(close(moments[0], sx, 1e-7), "{} {sx}", moments[0]);
        let (_, sy) = sliced([a[1], a[2], a[0]], r);
        assert!(close(moments[1], sy, 1e-7), "{} {sy}", moments[1]);
        // All radius: a ball, 4πr³/3 and ∫x² dV = 4πr⁵/15.
        let (ball, m) = rounded_box([0.5; 3], 0.5);
        assert!(close(ball, 4.0 / 3.0 * PI * 0.125, 1e-15));
        assert!(close(m[2], 4.0 * PI * 0.5f64.powi(5) / 15.0, 1e-15));
    }

    #[test]
    fn a_drilled_die_leans_toward_one_two_and_three() {
        // Textbook cap (height h, sphere radius R): volume πh²(3R − h)/3, centroid
        // 3(2R − h)²/(4(3R − h)) from the sphere's centre, which is R − h outside the face.
        // Faces 2..5's pips cancel across each face, so along x only 6 − 1 = 5 caps count,
        // along y 5 − 2 = 3, along z 4 − 3 = 1, each centred a − depth inside the centre.
        let d = Die {
            pip_diameter: 0.4,
            pip_depth: 0.15,
            ..Params::DEFAULT.die
        };
        let (rho, h, a) = (0.2, 0.15, 1.0);
        let big_r = (rho * rho + h * h) / (2.0 * h);
        let cap_volume = PI * h * h * (3.0 * big_r - h) / 3.0;
        let centroid_depth = 3.0 * (2.0 * big_r - h).powi(2) / (4.0 * (3.0 * big_r - h)) - (big_r - h);
        let density = 8.0 * d.corner_mass / 8.0;
        let mass = 8.0 - 21.0 * density * cap_volume;
        let lean = |pips: f64| -pips * density * cap_volume * (a - centroid_depth) / mass;
        let p = mass_properties(&d);
        assert!(close(p.mass, mass, 1e-13));
        for (i, pips) in [5.0, 3.0, 1.0].into_iter().enumerate() {
            assert!(
                close(p.centre_of_mass[i], lean(pips), 1e-9),
                "{i}: {}",
                p.centre_of_mass
            );
        }
        let drilled = Params {
            die: d,
            ..Params::DEFAULT
        };
        assert!(close(Shape::new(&drilled).mass, mass, 1e-13));
    }

    /// The highest the centre of mass gets when the body tilts from face f onto face e,
    /// from the support function of the 8 spheres, searched over the tilt angle.
    fn balanced_height(die: &Die, f: usize, e: usize) -> f64 {
        let spheres = contact_sphere_centres(die);
        let (n_f, n_e) = (Vector3::from(FACE_NORMALS[f]), Vector3::from(FACE_NORMALS[e]));
        (0..=200_000)
            .map(|i| {
                let t = std::f64::consts::FRAC_PI_2 * i as f64 / 200_000.0;
                let down = n_f * t.cos() + n_e * t.sin();
                spheres
                    .iter()
                    .map(|x| x.dot(&down))
                    .fold(f64::NEG_INFINITY, f64::max)
                    + die.corner_radius
            })
            .fold(f64::NEG_INFINITY, f64::max)
    }

    #[test]
    fn a_rounded_cuboid_rests_and_balances_where_its_spheres_say() {
        let mut p = Params::DEFAULT;
        p.die = die([0.6, 1.0, 1.4], 0.25);
        let shape = Shape::new(&p);
        let weight = shape.properties.mass * p.world.gravity;
        let (faces, _) = read_faces(&p, &shape.properties, shape.reference_height);
        let mut deepest: f64 = 0.0;
        for face in faces {
            let f = face.face as usize - 1;
            assert!(close(face.rest_height, p.die.half_sizes[axis(f)], 1e-15));
            // Four springs carry the weight: M·g/(4k) each.
            assert!(
                close(face.rest_depth, weight / (4.0 * p.ground.stiffness), 1e-9),
                "{face:?}"
            );
            for (e, energy) in face.edges {
                let height = balanced_height(&p.die, f, e as usize - 1);
                let expected = weight * (height - face.rest_height);
                assert!(close(energy, expected, 1e-9), "{f} {e}: {energy} {expected}");
                assert!(shape.edge_energy <= energy);
            }
            deepest = deepest.max(face.rest_depth);
        }
        assert_eq!(shape.resting_depth, deepest);
        // Rounding lowers the pass: the same box sharp needs more.
        let mut sharp = p;
        sharp.die.corner_radius = 0.0;
        assert!(Shape::new(&sharp).edge_energy > shape.edge_energy);
    }

    #[test]
    fn the_paper_cube_as_a_general_body_gives_the_papers_rule() {
        // The cube run through the general formulas (as if it were not the paper's) gives
        // the paper's rule on every face.
        let p = Params::DEFAULT;
        let shape = Shape::new(&p);
        let cube = Cube::new(&p);
        let paper = cube.stop_rule();
        for f in 0..6 {
            let rule = shape.face_rules[f];
            assert!(
                close(rule.energy_threshold, paper.energy_threshold, 1e-12),
                "{rule:?} {paper:?}"
            );
            assert!(close(rule.kinetic_threshold, paper.kinetic_threshold, 1e-12));
        }
        assert!(close(shape.edge_energy, cube.edge_energy(), 1e-14));
        assert!(close(shape.rocking_frequency, cube.rocking_frequency(), 1e-14));
        assert_eq!(shape.mass, cube.mass());
    }

    #[test]
    fn a_tilted_plate_falls_back_where_its_centre_of_mass_stands() {
        // The plate on face 6, tipped about the edge to face 2: it balances where the
        // vertical through its centre meets the edge, atan(1/0.5) = 63.4° from flat.
        let mut p = Params::DEFAULT;
        p.die = die([0.5, 1.0, 1.0], 0.0);
        let shape = Shape::new(&p);
        let onto_face_6 = nalgebra::Rotation3::from_axis_angle(&Vector3::y_axis(), PI / 2.0);
        let face_down = |degrees: f64| {
            let tilt = nalgebra::Rotation3::from_axis_angle(&Vector3::x_axis(), degrees.to_radians());
            let offsets = contact_sphere_centres(&p.die).map(|x| tilt * onto_face_6 * x);
            shape.face_down(&offsets)
        };
        assert_eq!(face_down(0.0), 6);
        assert_eq!(face_down(50.0), 6, "the highest corners already say face 5 is up");
        assert_eq!(face_down(63.0), 6);
        assert_eq!(face_down(64.0), 2);
        assert_eq!(face_down(89.0), 2);
    }
}
