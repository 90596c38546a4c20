//! Which body a die is, and everything that follows from it (docs/model.md, "Loaded dice"
//! and "Real dice"): its mass and inertia, its edge energy and fastest contact mode, its
//! stopping rule, how deep it rests, where a start places it and which face it shows at
//! rest.
//!
//! A die is one of three bodies. The paper's sharp cube keeps the paper's arithmetic bit
//! for bit (cube.rs); a loaded cube is that cube with extra corner masses, whose inertia
//! turns with it (mass.rs); any other die is a general body (shape.rs). `Die::kind`
//! (params.rs) tells them apart from the die's data; [`Body::new`] is the one place that
//! acts on the answer (the validation asks it too, to refuse the authors' point-mass energy
//! for a general body), and every other question about the body is asked of a [`Body`],
//! which answers for its own kind.
//!
//! The quantities the parameters imply about their body ([`Params::total_mass`],
//! [`Params::inertia`] …) and where a start places it ([`InitialCondition::check_clear_of_table`])
//! are the body's answers, so they are implemented here, beside it, rather than with the
//! data in params.rs and initial.rs.

use super::body::{body_corner_offsets, face_of_highest_corners, opposite_face};
use super::cube::Cube;
use super::initial::{InitialCondition, limits};
use super::mass::LoadedMass;
use super::params::{BodyKind, Limits, ParamError, Params, Solid};
use super::polyhedron::{self, DieKind};
use super::shape::Shape;
use super::stopping::StopRule;
use nalgebra::{Matrix3, Vector3};

/// The body a die is, with what its arithmetic needs, derived once from the parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Body {
    /// The paper's sharp cube of 8 equal corner masses, without pips.
    PaperCube(Cube),
    /// The paper's cube with extra point masses at some corners: the cube (its mass counts
    /// the extras) and the mass model that turns with it.
    LoadedCube(Cube, LoadedMass),
    /// Any other die: rounded, drilled or not a cube, loaded or not.
    Shaped(Shape),
}

impl Body {
    /// `p`'s body.
    pub(crate) fn new(p: &Params) -> Body {
        match p.die.kind() {
            BodyKind::PaperCube => Body::PaperCube(Cube::new(p)),
            BodyKind::LoadedCube => {
                let cube = Cube::new(p);
                Body::LoadedCube(cube, LoadedMass::new(p, &cube))
            }
            BodyKind::Shaped => Body::Shaped(Shape::new(p)),
        }
    }

    /// The general body, if this is one (the step reads its tensor and contact spheres).
    pub(crate) fn shape(&self) -> Option<&Shape> {
        match self {
            Body::Shaped(shape) => Some(shape),
            Body::PaperCube(_) | Body::LoadedCube(..) => None,
        }
    }

    /// g, the whole die: the undrilled body's `8·m`, less its pips, plus any extra corner
    /// masses.
    pub(crate) fn mass(&self) -> f64 {
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => cube.mass(),
            Body::Shaped(shape) => shape.mass,
        }
    }

    /// g·cm², one moment of inertia for the whole body: the paper's cube's isotropic
    /// `(2a)²/6·8m` (a loaded cube's too: its extras turn with it); for any other body the
    /// mean of its principal moments about the centre of mass. A roll steps a loaded or a
    /// general body with its full tensor; this one number converts a spin stated as ω into
    /// L and back where no orientation is at hand.
    pub(crate) fn mean_inertia(&self) -> f64 {
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => cube.inertia(),
            Body::Shaped(shape) => shape.properties.inertia.trace() / 3.0,
        }
    }

    /// g·cm², the least principal moment of inertia about the centre of mass: the axis a
    /// push at a corner turns the body about most easily. The cube's one moment; a loaded
    /// cube's tensor at the corner offsets `corner_offsets` (its principal moments turn with
    /// it, so any orientation gives them); a general body's from its body-frame tensor.
    pub(crate) fn least_inertia(&self, corner_offsets: &[Vector3<f64>; 8]) -> f64 {
        let tensor = match self {
            Body::PaperCube(cube) => return cube.inertia(),
            Body::LoadedCube(_, mass) => mass.inertia(corner_offsets),
            Body::Shaped(shape) => shape.properties.inertia,
        };
        tensor.symmetric_eigen().eigenvalues.min()
    }

    /// The principal moments of inertia about the centre of mass (g·cm², ascending) and the
    /// principal axes (the columns, body frame: the frame whose axes run from corner 1 to
    /// corners 5, 3 and 2, a right-handed triple) of a body whose inertia is not isotropic;
    /// `None` for the paper's cube and any body whose moments agree to 10⁻¹² (a rounded cube,
    /// a cube loaded alike at every corner): for those the paper's rotation by `ω·Δt` is the
    /// exact free flight, and they keep it (docs/model.md, "Rotation of an anisotropic body").
    pub(crate) fn principal_frame(&self) -> Option<(Vector3<f64>, Matrix3<f64>)> {
        let tensor = match self {
            Body::PaperCube(_) => return None,
            Body::LoadedCube(cube, mass) => {
                mass.inertia(&mass.initial_corner_offsets(cube.half_size(), &InitialCondition::default()))
            }
            Body::Shaped(shape) => shape.properties.inertia,
        };
        principal_frame(&tensor)
    }

    /// erg, the energy to tip over an edge from lying flat: the cube's `M·g·a·(√2 − 1)`, a
    /// general body's lowest pass over every face and edge.
    pub(crate) fn edge_energy(&self) -> f64 {
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => cube.edge_energy(),
            Body::Shaped(shape) => shape.edge_energy,
        }
    }

    /// rad/s, the fastest contact mode: the cube rocking on its face, `√(6k/M)`; a general
    /// body rocking on its four contact spheres about the axis that gives the fastest mode.
    pub(crate) fn rocking_frequency(&self) -> f64 {
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => cube.rocking_frequency(),
            Body::Shaped(shape) => shape.rocking_frequency,
        }
    }

    /// The stopping rule of the parameters: the cube's (a loaded cube's too, which its
    /// faces' rules are scaled from), or a general body's widest over its faces.
    pub(crate) fn stop_rule(&self) -> StopRule {
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => cube.stop_rule(),
            Body::Shaped(shape) => shape.widest_stop_rule(),
        }
    }

    /// The widest rule over the faces down, which every face's rule passes within: the step
    /// screens with it before it looks up the face down ([`Body::stop_rule_at`]).
    pub(crate) fn widest_stop_rule(&self) -> StopRule {
        match self {
            Body::PaperCube(cube) => cube.stop_rule(),
            Body::LoadedCube(_, mass) => mass.widest_stop_rule(),
            Body::Shaped(shape) => shape.widest_stop_rule(),
        }
    }

    /// The stopping rule at these corner offsets (cm, world frame, about the centre of
    /// mass): a loaded cube's and a general body's are those of the face now down.
    pub(crate) fn stop_rule_at(&self, corner_offsets: &[Vector3<f64>; 8]) -> StopRule {
        match self {
            Body::PaperCube(cube) => cube.stop_rule(),
            Body::LoadedCube(_, mass) => mass.stop_rule(corner_offsets),
            Body::Shaped(shape) => shape.stop_rule(corner_offsets),
        }
    }

    /// cm, how deep the body sinks when it rests on a face (a general body: the deepest
    /// over its faces).
    pub(crate) fn resting_depth_on_face(&self) -> f64 {
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => cube.resting_depth_on_face(),
            Body::Shaped(shape) => shape.resting_depth,
        }
    }

    /// cm, the height of the centre of mass the potential energy is measured from: the
    /// cube's half size, a general body's lowest rest height on a rigid table.
    pub(crate) fn reference_height(&self) -> f64 {
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => cube.half_size(),
            Body::Shaped(shape) => shape.reference_height,
        }
    }

    /// cm, corners 1..8 (a general body's contact-sphere centres) relative to the centre of
    /// mass at t = 0, world frame: where both engines place the die.
    pub(crate) fn start_offsets(&self, initial: &InitialCondition) -> [Vector3<f64>; 8] {
        match self {
            Body::PaperCube(cube) => {
                let corners = body_corner_offsets(cube.half_size());
                if initial.orientation == [0.0; 3] {
                    corners
                } else {
                    let rotation = initial.rotation();
                    corners.map(|r| rotation * r)
                }
            }
            Body::LoadedCube(cube, mass) => mass.initial_corner_offsets(cube.half_size(), initial),
            Body::Shaped(shape) => shape.initial_sphere_offsets(initial),
        }
    }

    /// g·cm²/s, the angular momentum at t = 0 with the corners at `corner_offsets`: `L` as
    /// given, or for a start stated as an angular velocity the cube's `I·ω`, a loaded
    /// cube's `I(0)·ω`, a general body's `R·I·Rᵀ·ω`.
    pub(crate) fn initial_angular_momentum(
        &self,
        initial: &InitialCondition,
        corner_offsets: &[Vector3<f64>; 8],
    ) -> Vector3<f64> {
        match self {
            Body::PaperCube(cube) => initial.angular_momentum_for(cube.inertia()),
            Body::LoadedCube(_, mass) => mass.initial_angular_momentum(initial, corner_offsets),
            Body::Shaped(shape) => shape.initial_angular_momentum(initial),
        }
    }

    /// The face up of a body at rest with these corner offsets (the outcome rule): the face
    /// whose 4 corners are the 4 highest, `None` when they form no face. A general body's is
    /// the face up over the face its centre of mass stands on: a flat or long body can rest
    /// tilted further than the four highest corners allow.
    pub(crate) fn face_up_at_rest(&self, corner_offsets: &[Vector3<f64>; 8]) -> Option<u8> {
        match self {
            Body::Shaped(shape) => Some(opposite_face(shape.face_down(corner_offsets))),
            Body::PaperCube(_) | Body::LoadedCube(..) => {
                face_of_highest_corners(&corner_offsets.map(|r| r.z))
            }
        }
    }

    /// The body's x, y and z axes in the world frame (unit vectors), from its corner
    /// offsets: corner 5 minus corner 1 along x, 3 minus 1 along y, 2 minus 1 along z. A
    /// cube's differences are `2a` long; a general body's sphere centres `2·(a_i − r)` apart,
    /// so its differences are normalised instead.
    pub(crate) fn axes(&self, corner_offsets: &[Vector3<f64>; 8]) -> [Vector3<f64>; 3] {
        let r = corner_offsets;
        let differences = [r[4] - r[0], r[2] - r[0], r[1] - r[0]];
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => {
                let side = 2.0 * cube.half_size();
                differences.map(|d| d / side)
            }
            Body::Shaped(_) => differences.map(|d| d.normalize()),
        }
    }

    /// cm, the lowest point's height relative to the centre at t = 0 (negative): a cube's
    /// lowest corner about its geometric centre, a general body's lowest contact sphere's
    /// bottom about its centre of mass.
    pub(crate) fn lowest_point_at_start(&self, initial: &InitialCondition) -> f64 {
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => {
                let rotation = initial.rotation();
                body_corner_offsets(cube.half_size())
                    .iter()
                    .map(|r| {
                        if initial.orientation == [0.0; 3] {
                            r.z
                        } else {
                            (rotation * r).z
                        }
                    })
                    .fold(f64::INFINITY, f64::min)
            }
            Body::Shaped(shape) => shape
                .initial_sphere_offsets(initial)
                .iter()
                .map(|x| x.z - shape.radius)
                .fold(f64::INFINITY, f64::min),
        }
    }

    /// cm/s, the speed a spin of `spin_rate` (rad/s) gives the corner farthest from the
    /// geometric centre: `a·√3` away on a cube, `|a|` on a general body.
    pub(crate) fn corner_speed_of_spin(&self, spin_rate: f64) -> f64 {
        match self {
            Body::PaperCube(cube) | Body::LoadedCube(cube, _) => spin_rate * cube.half_size() * 3f64.sqrt(),
            Body::Shaped(shape) => {
                let [x, y, z] = shape.half_sizes;
                spin_rate * (x * x + y * y + z * z).sqrt()
            }
        }
    }
}

/// The principal moments (ascending) and axes (columns, a right-handed triple) of a
/// symmetric tensor, or `None` when its moments agree to 10⁻¹² of the largest (isotropic
/// to rounding) or are not all finite and positive.
pub(crate) fn principal_frame(tensor: &Matrix3<f64>) -> Option<(Vector3<f64>, Matrix3<f64>)> {
    let eigen = tensor.symmetric_eigen();
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    let moments = Vector3::from(order.map(|i| eigen.eigenvalues[i]));
    let (least, most) = (moments[0], moments[2]);
    if !(least > 0.0 && most.is_finite()) || most - least <= 1e-12 * most {
        return None;
    }
    let mut axes = Matrix3::from_columns(&order.map(|i| eigen.eigenvectors.column(i).normalize()));
    if axes.determinant() < 0.0 {
        axes.set_column(2, &-axes.column(2));
    }
    Some((moments, axes))
}

impl Solid {
    /// The regular die it is, `None` for the box and a convex die.
    pub fn regular(self) -> Option<DieKind> {
        match self {
            Solid::Box => None,
            Solid::D4 => Some(DieKind::D4),
            Solid::D8 => Some(DieKind::D8),
            Solid::D10 => Some(DieKind::D10),
            Solid::Percentile => Some(DieKind::Percentile),
            Solid::D12 => Some(DieKind::D12),
            Solid::D20 => Some(DieKind::D20),
            Solid::Convex => None,
        }
    }
}

/// What the parameters imply about their body.
impl Params {
    /// The polyhedral die of `die.kind` (its `die.height`, or a convex die's `die.vertices`)
    /// and `die.density`, with the flaws its keys give; `None` for the box. Parameters that
    /// [`Params::validate`] accepts always make their die.
    ///
    /// # Panics
    /// On parameters [`Params::validate`] refuses for their die, with its words.
    pub fn polyhedral_die(&self) -> Option<polyhedron::Die> {
        polyhedron::made_die(self).unwrap_or_else(|e| panic!("a die the validation refuses: {e}"))
    }

    /// g, the whole die: the undrilled body's `8·m` less the pips plus any extra corner
    /// masses (adding the extras' zeros leaves the fair die's `8·m` bit for bit); a
    /// polyhedral die's solid.
    pub fn total_mass(&self) -> f64 {
        match self.polyhedral_die() {
            Some(die) => die.mass_properties().mass,
            None => Body::new(self).mass(),
        }
    }

    /// g·cm², one moment of inertia for the whole body: what
    /// converts a spin stated as ω into L and back where no orientation is at hand (preset
    /// files, `--set`, the explorer's spin fields). Bitwise 16/3 at the defaults; a
    /// polyhedral die's mean principal moment.
    pub fn inertia(&self) -> f64 {
        match self.polyhedral_die() {
            Some(die) => die.mass_properties().inertia.trace() / 3.0,
            None => Body::new(self).mean_inertia(),
        }
    }

    /// erg, the energy to tip over an edge from lying flat: `M·g·a·(√2 − 1)` for the
    /// paper's cube; for any other body the lowest edge pass over every face and edge
    /// (docs/model.md, "Real dice"); a polyhedral die's tipping barrier.
    pub fn edge_energy(&self) -> f64 {
        match self.polyhedral_die() {
            Some(die) => die.stop_rule(self).1,
            None => Body::new(self).edge_energy(),
        }
    }

    /// `ω_rock·Δt`, the fastest contact mode times the step: semi-implicit Euler is stable
    /// only below 2 (docs/model.md, "Stability"); for a polyhedral die `ω·Δt` of one point
    /// on the table ([`Params::point_contact_number`]).
    pub fn stability_number(&self) -> f64 {
        match self.polyhedral_die() {
            Some(die) => point_contact_number(self, &die),
            None => Body::new(self).rocking_frequency() * self.integrator.dt,
        }
    }

    /// cm, how far each corner sinks when the die rests flat: `M·g/(4k)`; a polyhedral
    /// die's deepest point resting on any face.
    pub fn resting_depth(&self) -> f64 {
        match self.polyhedral_die() {
            Some(die) => polyhedral_resting_depth(self, &die),
            None => resting_depth(self, &Body::new(self)),
        }
    }

    /// Refuses a polyhedral die on a step it cannot take: one point on the table, a spring
    /// `k` under the least mass a push there moves, `m = (1/M + r²/I_min)⁻¹` (`r` the farthest
    /// point's reach), rocks at `ω = √(k/m)`, and `ω·Δt` above [`CONTACT_MODE_LIMIT`] runs
    /// away (docs/model.md, "Fair dice come out fair": the d4 at 1 ms).
    pub(crate) fn check_polyhedral_step(&self) -> Result<(), ParamError> {
        let Some(die) = self.polyhedral_die() else {
            return Ok(());
        };
        let number = point_contact_number(self, &die);
        if number <= CONTACT_MODE_LIMIT {
            return Ok(());
        }
        let dt = self.integrator.dt;
        let most = dt * CONTACT_MODE_LIMIT / number;
        Err(ParamError::refused(
            super::params::limits::DT,
            dt,
            format!(
                "too long a step for this {}: one point on the table rocks with ω·Δt = {number:.2}, \
                 and above {CONTACT_MODE_LIMIT} the step feeds energy in and the die runs away \
                 (docs/model.md, \"Fair dice come out fair\"); at most {} s here (the dice presets \
                 take 0.00025)",
                self.die.kind.name(),
                super::params::fmt_number((most * 1e7).floor() / 1e7)
            ),
        ))
    }
}

/// `ω·Δt` above this lets a contact mode gain energy (stability.rs, which reads it for the
/// box; the same number here, where the stability readings cannot be asked).
const CONTACT_MODE_LIMIT: f64 = 1.25;

/// `√(k·(1/M + r²/I_min))·Δt` of `die` on `p`'s table: one point, the farthest from the
/// centre of mass, on a spring `k`, pushed across its reach.
fn point_contact_number(p: &Params, die: &polyhedron::Die) -> f64 {
    let props = die.mass_properties();
    let reach_squared = die
        .contact_points()
        .iter()
        .map(|point| point.offset.norm_squared())
        .fold(0.0, f64::max);
    let least_inertia = props.inertia.symmetric_eigen().eigenvalues.min();
    let inverse_mass = 1.0 / props.mass + reach_squared / least_inertia;
    (p.ground.stiffness * inverse_mass).sqrt() * p.integrator.dt
}

/// cm, the deepest any point of `die` sinks resting on a face of `p`'s table (`M·g/(3k)`,
/// a triangle's share, where a face would not hold).
fn polyhedral_resting_depth(p: &Params, die: &polyhedron::Die) -> f64 {
    let (k, g) = (p.ground.stiffness, p.world.gravity);
    let fallback = die.mass_properties().mass * g / (3.0 * k);
    (0..die.shape().faces().len())
        .map(|face| {
            die.rest_depth(face, k, g)
                .map_or(fallback, |rest| rest.points.iter().copied().fold(0.0, f64::max))
        })
        .fold(0.0, f64::max)
}

/// cm, `M·g/(4k)` for `body` on `p`'s table.
fn resting_depth(p: &Params, body: &Body) -> f64 {
    body.mass() * p.world.gravity / (4.0 * p.ground.stiffness)
}

/// Where a start places the die.
impl InitialCondition {
    /// cm, the lowest point's height relative to the centre at `t = 0` (negative), for
    /// `params`' die: a cube's lowest corner, a general body's lowest contact sphere's
    /// bottom about its centre of mass.
    pub fn lowest_corner_offset(&self, params: &Params) -> f64 {
        Body::new(params).lowest_point_at_start(self)
    }

    /// Refuses a start with any corner inside the table deeper than the die's resting depth
    /// `M·g/(4k)` (a die may be placed resting on the table, not pushed into it): the error
    /// names the lowest height allowed at this orientation.
    pub fn check_clear_of_table(&self, params: &Params) -> Result<(), ParamError> {
        Placement::new(params).check_clear_of_table(self)
    }
}

/// Where the starts of one setup place its die, for a caller that looks at many starts of
/// one setup (a merge checks millions of records): the body is built once, not per start,
/// and each answer is the very one a [`Simulation`](crate::Simulation) of the start gives.
pub struct Placement {
    body: Body,
    /// cm, a polyhedral die's contact points from its centre of mass, die frame (the box's
    /// corners are the body's).
    points: Option<Vec<Vector3<f64>>>,
    /// cm, the corners' rounding, which the table must clear.
    corner_radius: f64,
    /// cm, `M·g/(4k)`.
    resting_depth: f64,
}

impl Placement {
    /// The placement of `params`' die.
    pub fn new(params: &Params) -> Placement {
        let body = Body::new(params);
        let die = params.polyhedral_die();
        Placement {
            corner_radius: params.die.corner_radius,
            resting_depth: params.resting_depth(),
            points: die.map(|die| die.contact_points().iter().map(|p| p.offset).collect()),
            body,
        }
    }

    /// cm, corners 1..8 (a general body's contact-sphere centres) relative to the centre of
    /// mass at t = 0, world frame: where both engines place the die.
    pub fn start_offsets(&self, initial: &InitialCondition) -> [Vector3<f64>; 8] {
        self.body.start_offsets(initial)
    }

    /// [`InitialCondition::check_clear_of_table`] for this setup.
    pub fn check_clear_of_table(&self, initial: &InitialCondition) -> Result<(), ParamError> {
        let lowest_offset = match &self.points {
            Some(points) => {
                let rotation = initial.rotation();
                points
                    .iter()
                    .map(|p| (rotation * p).z)
                    .fold(f64::INFINITY, f64::min)
            }
            None => self
                .start_offsets(initial)
                .iter()
                .map(|r| r.z - self.corner_radius)
                .fold(f64::INFINITY, f64::min),
        };
        let lowest = -lowest_offset - self.resting_depth;
        if initial.height >= lowest {
            Ok(())
        } else {
            Err(ParamError {
                key: limits::HEIGHT.key.to_string(),
                value: initial.height,
                limits: Limits {
                    min: lowest,
                    unit: "cm at this orientation (lower, a corner starts deeper in the table than the die sinks resting on it)",
                    ..limits::HEIGHT
                },
                detail: None,
            })
        }
    }
}

/// The one check of a setup rolled from a given start, whatever builds it (a preset, `--set`,
/// a map's cell, a fit's candidate, the explorer's editors): every parameter in its range and
/// the body they describe able to exist, then the start in its ranges and clear of the table.
/// The first failure is the answer, so every path that builds the same setup refuses it with
/// the same words.
pub fn check_setup(params: &Params, initial: &InitialCondition) -> Result<(), ParamError> {
    params.validate()?;
    initial.validate()?;
    initial.check_clear_of_table(params)
}

/// cm, how deep the body sinks when it rests on a face, with as many corners touching as
/// the depth implies (4, or all 8 on a table too soft to carry it); for a body other than
/// the paper's cube, the deepest over its faces.
pub fn resting_depth_on_face(p: &Params) -> f64 {
    Body::new(p).resting_depth_on_face()
}

/// Why no roll can settle on this table, in words; `None` when one can. The numbers are the
/// body's own: the paper's and a loaded cube's from the cube, a general body's from the face
/// that comes nearest to holding it (the highest resting centre, or the largest pass).
pub fn why_it_cannot_settle(p: &Params) -> Option<String> {
    if let Some(why) = super::contact::why_a_tilt_cannot_hold(p) {
        return Some(why);
    }
    let body = Body::new(p);
    if body.stop_rule().can_settle() {
        return None;
    }
    let too_soft_to_hold = |depth: f64, below: f64| {
        format!(
            "the table is too soft to hold the die: at rest it would sink {depth:.3} cm, its centre \
             {below:.3} cm below the table top"
        )
    };
    let too_soft_to_keep = |depth: f64, pass: f64| {
        format!(
            "the table is too soft to keep a face: at rest the die sinks {depth:.3} cm, and tipping \
             it over an edge takes only {pass:.1} erg, too little to tell a settled die from a rocking one"
        )
    };
    Some(match &body {
        Body::PaperCube(cube) | Body::LoadedCube(cube, _) => {
            let (depth, a) = (cube.resting_depth_on_face(), cube.half_size());
            if depth >= a {
                too_soft_to_hold(depth, depth - a)
            } else {
                too_soft_to_keep(depth, cube.edge_balanced_energy() - cube.resting_energy())
            }
        }
        Body::Shaped(shape) => {
            // So round that even a rigid table would not hold a face (a ball): the shape's
            // doing, not the table's.
            let [x, y, z] = shape.half_sizes;
            let sharp_box = body.mass() * p.world.gravity * x.min(y).min(z) * (2f64.sqrt() - 1.0);
            if shape.edge_energy < 0.01 * sharp_box {
                return Some(format!(
                    "the die is too round to keep a face: tipping it over an edge takes {:.2} erg \
                     even on a rigid table ({sharp_box:.0} erg for a sharp box its size)",
                    shape.edge_energy
                ));
            }
            let faces = shape.faces(p);
            let centre = |f: &crate::shape::FaceReadout| f.rest_height - f.rest_depth;
            let standing = faces.iter().filter(|f| centre(f) > 0.0);
            match standing.max_by(|a, b| a.spring_pass.total_cmp(&b.spring_pass)) {
                Some(best) => too_soft_to_keep(best.rest_depth, best.spring_pass),
                None => {
                    let highest = faces
                        .iter()
                        .max_by(|a, b| centre(a).total_cmp(&centre(b)))
                        .expect("six faces");
                    too_soft_to_hold(highest.rest_depth, -centre(highest))
                }
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Die;

    fn with_die(change: fn(&mut Die)) -> Params {
        let mut p = Params::default();
        change(&mut p.die);
        p
    }

    #[test]
    fn the_defaults_are_the_papers_cube() {
        let p = Params::default();
        assert!(matches!(Body::new(&p), Body::PaperCube(_)));
        assert_eq!(p.total_mass(), 8.0);
        assert_eq!(p.inertia(), 16.0 / 3.0);
        assert!((p.edge_energy() - 3247.4).abs() < 0.05);
        // √(6k/M)·Δt = √(6·500000/8)·0.001.
        assert!((p.stability_number() - 0.61237).abs() < 1e-5);
        assert!((p.resting_depth() - 3.92e-3).abs() < 1e-5);
        assert_eq!(resting_depth_on_face(&p), Cube::new(&p).resting_depth_on_face());
        assert_eq!(why_it_cannot_settle(&p), None);
    }

    #[test]
    fn a_loaded_cube_weighs_its_extras_but_spins_as_the_uniform_cube() {
        let p = with_die(|d| d.extra_corner_mass[7] = 0.5);
        let body = Body::new(&p);
        assert!(matches!(body, Body::LoadedCube(..)));
        assert_eq!(p.total_mass(), 8.5);
        assert_eq!(p.inertia(), 16.0 / 3.0);
        // Its rule of the parameters is the cube's, which its faces' rules only scale.
        assert_eq!(body.stop_rule(), Cube::new(&p).stop_rule());
        let widest = body.widest_stop_rule();
        assert!(widest.energy_threshold > body.stop_rule().energy_threshold);
    }

    #[test]
    fn a_rounded_die_is_a_general_body_with_its_own_numbers() {
        let p = with_die(|d| d.corner_radius = 0.2);
        let body = Body::new(&p);
        let Body::Shaped(shape) = body else {
            panic!("a rounded die is a general body: {body:?}")
        };
        assert_eq!(p.edge_energy(), shape.edge_energy);
        // Rounded corners lower the pass and lighten the body.
        assert!(p.edge_energy() < Params::default().edge_energy());
        assert_eq!(p.total_mass(), 8.0, "undrilled: still 8·m");
        assert!(p.inertia() < 16.0 / 3.0);
        assert_eq!(body.reference_height(), 1.0);
    }

    #[test]
    fn a_drilled_die_is_lighter_and_rests_shallower() {
        let p = with_die(|d| (d.pip_diameter, d.pip_depth) = (0.3, 0.1));
        assert!(p.total_mass() < 8.0);
        assert!(p.resting_depth() < Params::default().resting_depth());
    }

    #[test]
    fn a_start_inside_the_table_is_refused_by_the_lowest_corner() {
        let p = Params::default();
        // Tipped 45° about x, the lowest corner is a·√2 below the centre.
        let tipped = InitialCondition {
            orientation: [0.0, 0.0, 45.0],
            ..InitialCondition::default()
        };
        assert!((tipped.lowest_corner_offset(&p) + 2f64.sqrt()).abs() < 1e-12);
        let resting = InitialCondition {
            height: 2f64.sqrt() - p.resting_depth(),
            ..tipped
        };
        resting.check_clear_of_table(&p).expect("resting on its edge");
        let pushed = InitialCondition {
            height: 1.3,
            ..tipped
        };
        let e = pushed.check_clear_of_table(&p).unwrap_err();
        assert_eq!(e.key, "initial.height");
        assert!((e.limits.min - resting.height).abs() < 1e-12, "{e}");
    }

    #[test]
    fn a_soft_table_says_why_with_the_bodys_own_numbers() {
        // A rounded slab whose x half size is its smallest: the cube's formula took the first
        // half size as the height of every face and said 11.200 cm below. All 8 spheres touch
        // (M·g/(4k) = 19.6 cm), so each carries M·g/8 and the centre rests at
        // z = r − M·g/(8k) = 0.1 − 9.8 cm whatever face is down: 9.7 cm under the top, the
        // lower spheres of the x face (height a_x = 0.5) sunk 0.5 + 9.7 = 10.2 cm.
        let mut p = with_die(|d| (d.half_sizes, d.corner_radius) = ([0.5, 2.0, 2.0], 0.1));
        p.ground.stiffness = 100.0;
        assert!(matches!(Body::new(&p), Body::Shaped(_)));
        let why = why_it_cannot_settle(&p).expect("k = 100 cannot hold the slab");
        assert!(why.starts_with("the table is too soft to hold the die"), "{why}");
        assert!(why.contains("its centre 9.700 cm below"), "{why}");
        assert!(why.contains("sink 10.200 cm"), "{why}");
    }

    #[test]
    fn a_ball_says_it_is_too_round_for_a_face_whatever_the_table() {
        // Corners rounded to 0.9999 of the half size: a ball to 10⁻⁴ cm, whose edge pass is
        // M·g·b·(√2 − 1) with b = 10⁻⁴ cm, 0.32 erg, against 3247 erg for the sharp cube.
        let p = with_die(|d| d.corner_radius = 0.9999);
        let why = why_it_cannot_settle(&p).expect("a ball has no face to rest on");
        assert!(why.starts_with("the die is too round to keep a face"), "{why}");
        assert!(
            why.contains("takes 0.32 erg") && why.contains("(3247 erg"),
            "{why}"
        );
        assert_eq!(why_it_cannot_settle(&with_die(|d| d.corner_radius = 0.2)), None);
    }

    #[test]
    fn a_soft_table_says_why_it_cannot_hold_a_face() {
        let mut p = Params::default();
        p.ground.stiffness = 100.0;
        let why = why_it_cannot_settle(&p).expect("k = 100 cannot hold the die");
        assert!(why.starts_with("the table is too soft to hold the die"), "{why}");
        // M·g/(4k) = 19.6 cm: all 8 corners sink and the centre rests 9.8 cm under the top.
        assert!(why.contains("9.800 cm below"), "{why}");
    }
}
