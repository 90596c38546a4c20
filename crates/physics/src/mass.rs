//! The mass model of a loaded die (docs/model.md, "Loaded dice"): the paper's uniform cube
//! plus extra point masses at its corners.
//!
//! A fair die never reaches this module: its isotropic inertia and its centre of mass at the
//! cube's centre keep the paper's arithmetic, and the reference trajectories, untouched.
//! A loaded die's centre of mass moves off the geometric centre, its inertia about the centre
//! of mass is a full tensor that turns with the body, so `ω = I(t)⁻¹·L` is recomputed every
//! step, in flight too, from the current corner offsets (the paper's eq. 8–9).

use super::body::{CORNER_SIGNS, FACE_NORMALS, body_corner_offsets, face_most_nearly_up, opposite_face};
use super::cube::Cube;
use super::initial::InitialCondition;
use super::lane::Lane;
use super::params::Params;
use super::stopping::StopRule;
use nalgebra::{Matrix3, Vector3};

/// Everything a loaded die's step needs beyond the fair die's constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LoadedMass {
    /// g, the uniform cube (8 corners of `die.corner_mass`).
    uniform_mass: f64,
    /// g, the uniform corner mass `m`.
    corner_mass: f64,
    /// g, the extra point mass at each corner.
    extra: [f64; 8],
    /// g·cm², the uniform cube's isotropic inertia about its own centre, `(2a)²/6·8m`.
    uniform_inertia: f64,
    /// cm, body frame: the centre of mass relative to the cube's geometric centre.
    centre_of_mass: Vector3<f64>,
    /// The stopping rule for a die lying on each face 1..6 (index: the face down).
    face_rules: [StopRule; 6],
}

impl LoadedMass {
    /// The mass model of `p`'s loaded die, the paper's `cube` with its extra corner masses.
    pub(crate) fn new(p: &Params, cube: &Cube) -> LoadedMass {
        let a = cube.half_size();
        let mut moment = Vector3::zeros();
        for (s, &dm) in CORNER_SIGNS.iter().zip(&p.die.extra_corner_mass) {
            moment += Vector3::from(*s) * (a * dm);
        }
        let centre_of_mass = moment / cube.mass();
        LoadedMass {
            uniform_mass: cube.uniform_mass(),
            corner_mass: p.die.corner_mass,
            extra: p.die.extra_corner_mass,
            uniform_inertia: cube.inertia(),
            centre_of_mass,
            face_rules: face_rules(cube, p.world.gravity, &centre_of_mass),
        }
    }

    /// cm, body frame: the centre of mass relative to the cube's geometric centre.
    #[cfg(test)]
    pub(crate) fn centre_of_mass(&self) -> Vector3<f64> {
        self.centre_of_mass
    }

    /// cm, corners 1..8 relative to the centre of mass at the start, world frame.
    pub(crate) fn initial_corner_offsets(
        &self,
        half_size: f64,
        initial: &InitialCondition,
    ) -> [Vector3<f64>; 8] {
        let rotation = initial.rotation();
        body_corner_offsets(half_size).map(|r| rotation * (r - self.centre_of_mass))
    }

    /// g·cm²/s: `L` as given, or `I(0)·ω` for a start stated as an angular velocity.
    pub(crate) fn initial_angular_momentum(
        &self,
        initial: &InitialCondition,
        corner_offsets: &[Vector3<f64>; 8],
    ) -> Vector3<f64> {
        match initial.angular_momentum {
            Some(l) => Vector3::from(l),
            None => self.inertia(corner_offsets) * Vector3::from(initial.angular_velocity),
        }
    }

    /// g·cm², the inertia tensor about the centre of mass, world frame, at the current
    /// corner offsets (see [`InertiaTensor::new`]).
    pub(crate) fn inertia(&self, corner_offsets: &[Vector3<f64>; 8]) -> Matrix3<f64> {
        InertiaTensor::new(
            self.uniform_inertia,
            self.uniform_mass,
            &self.extra,
            corner_offsets,
        )
        .matrix()
    }

    /// The stopping rule for the die's current orientation: the one of the face now down.
    pub(crate) fn stop_rule(&self, corner_offsets: &[Vector3<f64>; 8]) -> StopRule {
        let down = opposite_face(face_most_nearly_up(corner_offsets));
        self.face_rules[down as usize - 1]
    }

    /// The widest rule over the faces: the largest of each threshold, which every face's
    /// rule passes within (the step's cheap screen before the face down is looked up).
    pub(crate) fn widest_stop_rule(&self) -> StopRule {
        StopRule::widest(&self.face_rules)
    }

    /// The authors' point-mass energy with each corner's own mass: the corner masses
    /// `m + Δm_k` (g), and the total mass `8·m + ΣΔm_k` (g) its `M·g·a` term uses.
    pub(crate) fn point_masses(&self) -> ([f64; 8], f64) {
        let total_mass = self.uniform_mass + self.extra.iter().sum::<f64>();
        (
            std::array::from_fn(|k| self.corner_mass + self.extra[k]),
            total_mass,
        )
    }
}

/// g·cm², a loaded die's inertia tensor by its upper triangle (it is exactly symmetric:
/// every term's `(i, j)` entry is built from `r_i·r_j`, which equals `r_j·r_i` bit for bit).
///
/// Written once over the lane type: the scalar engine builds and inverts one roll's tensor,
/// the lane engine four at once. Every operation is the one nalgebra 0.35 performs for the
/// `Matrix3` expressions this replaced, in the same order and with the same operands, so
/// both widths keep the bits of the records written before: `Matrix3 · scalar` and
/// `identity · s` multiply each entry (`0·s` off the diagonal, kept: it is NaN for s = ∞),
/// `r·rᵀ` has entries `r_i·r_j`, `norm_squared` sums `+0 + ((x² + y²) + z²)`, a sum of
/// vectors folds from the zero vector.
#[derive(Debug, Clone, Copy)]
pub(crate) struct InertiaTensor<L> {
    xx: L,
    xy: L,
    xz: L,
    yy: L,
    yz: L,
    zz: L,
}

impl<L: Lane> InertiaTensor<L> {
    /// The tensor about the centre of mass from the current corner offsets `r_k`: the
    /// uniform cube's `I_u·E` (g·cm²) about its geometric centre `g` (the mean of the
    /// offsets), moved to the centre of mass by the parallel-axis term
    /// `M_u·(|g|²·E − g·gᵀ)` (`M_u` in g), plus each extra mass's
    /// `Δm_k·(|r_k|²·E − r_k·r_kᵀ)`.
    #[inline(always)]
    pub(crate) fn new(
        uniform_inertia: L,
        uniform_mass: L,
        extra_masses: &[L; 8],
        corner_offsets: &[Vector3<L>; 8],
    ) -> Self {
        let zero = L::zero();
        let mut sum = [zero; 3];
        for r in corner_offsets {
            sum = [sum[0] + r.x, sum[1] + r.y, sum[2] + r.z];
        }
        let eight = L::splat(8.0);
        let centre = Vector3::new(sum[0] / eight, sum[1] / eight, sum[2] / eight);
        let off = zero * uniform_inertia;
        let cube = InertiaTensor {
            xx: uniform_inertia,
            xy: off,
            xz: off,
            yy: uniform_inertia,
            yz: off,
            zz: uniform_inertia,
        };
        let mut tensor = cube.plus(&Self::point(uniform_mass, &centre));
        for (r, &dm) in corner_offsets.iter().zip(extra_masses) {
            tensor = tensor.plus(&Self::point(dm, r));
        }
        tensor
    }

    /// `m·(|r|²·E − r·rᵀ)`.
    #[inline(always)]
    fn point(m: L, r: &Vector3<L>) -> Self {
        let norm_squared = L::zero() + ((r.x * r.x + r.y * r.y) + r.z * r.z);
        let off = L::zero() * norm_squared;
        InertiaTensor {
            xx: (norm_squared - r.x * r.x) * m,
            xy: (off - r.x * r.y) * m,
            xz: (off - r.x * r.z) * m,
            yy: (norm_squared - r.y * r.y) * m,
            yz: (off - r.y * r.z) * m,
            zz: (norm_squared - r.z * r.z) * m,
        }
    }

    #[inline(always)]
    fn plus(&self, other: &Self) -> Self {
        InertiaTensor {
            xx: self.xx + other.xx,
            xy: self.xy + other.xy,
            xz: self.xz + other.xz,
            yy: self.yy + other.yy,
            yz: self.yz + other.yz,
            zz: self.zz + other.zz,
        }
    }

    /// rad/s, `ω = I⁻¹·L` for `L` in g·cm²/s: nalgebra's `try_inverse` (the 3×3 cofactor
    /// formula over the determinant, operation for operation) and its `Matrix3 · Vector3`
    /// (each entry `(a₀·L₀ + a₁·L₁) + a₂·L₂`). Where the determinant is zero nalgebra
    /// gives no inverse and ω is NaN, so the roll ends unstable; the tensor is positive
    /// definite (every mass is positive), so it never happens for a die that is in range.
    #[inline(always)]
    pub(crate) fn angular_velocity(&self, l: &Vector3<L>) -> Vector3<L> {
        let (m11, m12, m13) = (self.xx, self.xy, self.xz);
        let (m21, m22, m23) = (self.xy, self.yy, self.yz);
        let (m31, m32, m33) = (self.xz, self.yz, self.zz);
        let minor_m12_m23 = m22 * m33 - m32 * m23;
        let minor_m11_m23 = m21 * m33 - m31 * m23;
        let minor_m11_m22 = m21 * m32 - m31 * m22;
        let det = m11 * minor_m12_m23 - m12 * minor_m11_m23 + m13 * minor_m11_m22;
        let inverse = [
            [
                minor_m12_m23 / det,
                (m13 * m32 - m33 * m12) / det,
                (m12 * m23 - m22 * m13) / det,
            ],
            [
                -minor_m11_m23 / det,
                (m11 * m33 - m31 * m13) / det,
                (m13 * m21 - m23 * m11) / det,
            ],
            [
                minor_m11_m22 / det,
                (m12 * m31 - m32 * m11) / det,
                (m11 * m22 - m21 * m12) / det,
            ],
        ];
        let row = |a: &[L; 3]| (a[0] * l.x + a[1] * l.y) + a[2] * l.z;
        let invertible = det.ne(L::zero());
        let nan = L::splat(f64::NAN);
        Vector3::new(
            L::select(invertible, row(&inverse[0]), nan),
            L::select(invertible, row(&inverse[1]), nan),
            L::select(invertible, row(&inverse[2]), nan),
        )
    }
}

impl InertiaTensor<f64> {
    /// The full matrix.
    pub(crate) fn matrix(&self) -> Matrix3<f64> {
        #[rustfmt::skip]
        let m = Matrix3::new(
            self.xx, self.xy, self.xz,
            self.xy, self.yy, self.yz,
            self.xz, self.yz, self.zz,
        );
        m
    }
}

/// The stopping rule of each face down, from the fair rule of a die of the same total mass.
///
/// The fair rule asks for an energy below a share of `E_edge`, the lowest pass over an edge
/// above rest, with the potential zero for a die lying flat. A loaded die lying on face f
/// rests at `V_f = −M·g·(c·n_f)` (its centre of mass `a − c·n_f` above the table, `n_f` the
/// face's outward normal), and balanced on the edge to face e its centre is
/// `√((a − c·n_f)² + (a − c·n_e)²)` above the table. So the pass out of face f is
/// `B_f = min_e M·g·(√((a − c·n_f)² + (a − c·n_e)²) − (a − c·n_f))`, and the rule for face
/// f is the fair rule moved up by `V_f` and scaled by `B_f / E_edge` (the fair die gets its
/// own rule back: `V_f = 0`, `B_f = E_edge`).
fn face_rules(cube: &Cube, gravity: f64, centre_of_mass: &Vector3<f64>) -> [StopRule; 6] {
    let fair = cube.stop_rule();
    let weight = cube.mass() * gravity;
    let a = cube.half_size();
    let edge = cube.edge_energy();
    let height = |f: usize| a - centre_of_mass.dot(&Vector3::from(FACE_NORMALS[f]));
    std::array::from_fn(|f| {
        if !fair.can_settle() {
            return fair;
        }
        let rest = weight * (height(f) - a);
        let pass = (0..6)
            .filter(|&e| e != f && e != 5 - f)
            .map(|e| weight * ((height(f).powi(2) + height(e).powi(2)).sqrt() - height(f)))
            .fold(f64::INFINITY, f64::min);
        let scale = pass / edge;
        // The fair rule's resting energy, `energy_threshold − kinetic_threshold`, is the
        // table's give below a die at rest; it stays the same on every face.
        let give = fair.energy_threshold - fair.kinetic_threshold;
        let energy_threshold = rest + scale * fair.energy_threshold;
        StopRule {
            energy_threshold,
            kinetic_threshold: energy_threshold - (rest + give),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn loaded(extra: [f64; 8]) -> Params {
        let mut p = Params::default();
        p.die.extra_corner_mass = extra;
        p
    }

    fn mass_model(p: &Params) -> LoadedMass {
        LoadedMass::new(p, &Cube::new(p))
    }

    #[test]
    fn centre_of_mass_moves_toward_the_heavy_corner() {
        let mut extra = [0.0; 8];
        extra[7] = 1.0;
        let m = mass_model(&loaded(extra));
        // One gram at (a, a, a) on a die of 9 g: the centre moves a/9 along each axis.
        assert!((m.centre_of_mass() - Vector3::repeat(1.0 / 9.0)).norm() < 1e-15);
    }

    #[test]
    fn inertia_is_the_sum_of_point_masses_and_the_cube() {
        // Eight equal extras: the centre stays put and each adds Δm·(3a² − a²) per axis,
        // 16·Δm·a² in all, isotropically.
        let m = mass_model(&loaded([0.5; 8]));
        let r = m.initial_corner_offsets(1.0, &InitialCondition::default());
        let i = m.inertia(&r);
        let expected = Matrix3::identity() * (16.0 / 3.0 + 16.0 * 0.5);
        assert!((i - expected).norm() < 1e-12, "{i}");
        // A heavy corner: the tensor equals the direct sum over all masses, each at its
        // distance from the centre of mass, with the cube's own part by the parallel axes.
        let mut extra = [0.0; 8];
        extra[2] = 2.0;
        let m = mass_model(&loaded(extra));
        let ic = InitialCondition {
            orientation: [30.0, 20.0, 10.0],
            ..Default::default()
        };
        let r = m.initial_corner_offsets(1.0, &ic);
        let c = ic.rotation() * m.centre_of_mass();
        let mut direct = Matrix3::identity() * (16.0 / 3.0);
        // The cube's centre is at −c from the centre of mass; its mass is 8 g.
        direct += (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * 8.0;
        direct += (Matrix3::identity() * r[2].norm_squared() - r[2] * r[2].transpose()) * 2.0;
        assert!((m.inertia(&r) - direct).norm() < 1e-12);
        // The masses balance about the centre of mass.
        let balance: Vector3<f64> = r.iter().sum::<Vector3<f64>>() * 1.0 + r[2] * 2.0;
        assert!(balance.norm() < 1e-12, "{balance}");
    }

    #[test]
    fn the_faces_at_the_heavy_corner_rest_higher_and_pass_more_easily() {
        let mut extra = [0.0; 8];
        extra[7] = 1.0; // corner 8 meets faces 4, 5 and 6
        let p = loaded(extra);
        let m = mass_model(&p);
        let fair = Cube::new(&p).stop_rule();
        // Face 3 down puts corner 8 on top: the centre rests a/9 higher.
        let up = m.face_rules[2];
        let down = m.face_rules[3];
        assert!(up.energy_threshold > down.energy_threshold);
        assert!(down.kinetic_threshold < fair.kinetic_threshold);
        assert!(up.kinetic_threshold < down.kinetic_threshold);
        for rule in m.face_rules {
            assert!(rule.kinetic_threshold > 0.0 && rule.can_settle());
        }
    }
}
