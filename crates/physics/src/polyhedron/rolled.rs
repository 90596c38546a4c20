//! A die as the step rolls it: the body of `N` contact points its geometry gives
//! ([`PointBody`]), with the stopping rule its tipping barrier sets on a spring table
//! (docs/model.md, "Stopping a die of any shape").

use super::die::Die;
use crate::params::Params;
use crate::points::{BodyError, PointBody};
use crate::stopping::StopRule;
use nalgebra::Vector3;

impl Die {
    /// The stopping rule of this die on `params`' table (stiffness `k` under every touching
    /// point, gravity `g`, the share `f` of the edge energy), and the edge energy (erg): the
    /// paper's rule with the tipping barrier `B = M·g·rise` for its `E_edge`,
    /// `E_max = min(f·B, B − (M g)²/(4k) − ½·(1 − f)·B)` and `K_max = E_max − V_rest`, the lowest
    /// rest `V_rest = min_f (M·g·(h_f − h_0) − (M g)²/(2·n_f·k))`; [`StopRule::NEVER`] when
    /// the table cannot hold a face.
    pub fn stop_rule(&self, params: &Params) -> (StopRule, f64) {
        let weight = self.mass_properties().mass * params.world.gravity;
        let k = params.ground.stiffness;
        let f = params.integrator.stop_energy_fraction;
        let barrier = weight * self.tipping().rise;
        let faces = 0..self.shape().faces().len();
        let lowest = faces
            .clone()
            .map(|f| self.rest_height(f))
            .fold(f64::INFINITY, f64::min);
        let rest = faces
            .map(|face| {
                let n = self.shape().faces()[face].vertices.len() as f64;
                weight * (self.rest_height(face) - lowest) - weight * weight / (2.0 * n * k)
            })
            .fold(f64::INFINITY, f64::min);
        let edge = barrier - weight * weight / (4.0 * k);
        let energy = (f * barrier).min(edge - 0.5 * (1.0 - f) * barrier);
        let sinks_whole = self.rest_depth_below_centre(weight, k, lowest);
        if energy <= rest || sinks_whole {
            return (StopRule::NEVER, barrier);
        }
        let rule = StopRule {
            energy_threshold: energy,
            kinetic_threshold: energy - rest,
        };
        (rule, barrier)
    }

    /// The stopping rule of each face down (in the shape's order of faces) on `params`'
    /// table (docs/model.md, "Stopping a die of any shape"): with `H_f = M·g·(h_f − h_0)` the
    /// face's rest above the lowest and `B_f` its own least tip ([`Die::face_tipping`]),
    /// `E_max,f = H_f + min(f·B_f, B_f − (M g)²/(4k) − ½·(1 − f)·B_f)` and
    /// `K_max,f = E_max,f − V_rest,f`, `V_rest,f = H_f − (M g)²/(2·n_f·k)`; [`StopRule::NEVER`]
    /// for a face the die cannot rest on or the table cannot hold it on, and for every face
    /// where [`Die::stop_rule`] is.
    pub fn face_stop_rules(&self, params: &Params) -> Vec<StopRule> {
        let weight = self.mass_properties().mass * params.world.gravity;
        let k = params.ground.stiffness;
        let f = params.integrator.stop_energy_fraction;
        let faces = 0..self.shape().faces().len();
        let lowest = faces
            .clone()
            .map(|f| self.rest_height(f))
            .fold(f64::INFINITY, f64::min);
        if !self.stop_rule(params).0.can_settle() {
            return faces.map(|_| StopRule::NEVER).collect();
        }
        faces
            .map(|face| {
                let Some(tip) = self.face_tipping(face) else {
                    return StopRule::NEVER;
                };
                let n = self.shape().faces()[face].vertices.len() as f64;
                let above = weight * (self.rest_height(face) - lowest);
                let barrier = weight * tip.rise;
                let edge = barrier - weight * weight / (4.0 * k);
                let energy = above + (f * barrier).min(edge - 0.5 * (1.0 - f) * barrier);
                let rest = above - weight * weight / (2.0 * n * k);
                if energy <= rest {
                    return StopRule::NEVER;
                }
                StopRule {
                    energy_threshold: energy,
                    kinetic_threshold: energy - rest,
                }
            })
            .collect()
    }

    /// Whether its faces stop it alike: every face's rule ([`Die::face_stop_rules`]) within
    /// [`ALIKE`] of the die's barrier of the one rule ([`Die::stop_rule`]). The faces of a
    /// regular die are alike by its symmetry and differ in rounding only; a bubble, a point
    /// mass, a shave or uneven rounding sets them apart.
    pub fn faces_stop_alike(&self, params: &Params) -> bool {
        let (one, barrier) = self.stop_rule(params);
        let near = |a: f64, b: f64| a == b || (a - b).abs() <= ALIKE * barrier;
        self.face_stop_rules(params).iter().all(|rule| {
            near(rule.energy_threshold, one.energy_threshold)
                && near(rule.kinetic_threshold, one.kinetic_threshold)
        })
    }

    /// Whether resting on its lowest face the die would sink its centre below the table top.
    fn rest_depth_below_centre(&self, weight: f64, k: f64, lowest: f64) -> bool {
        let most = self
            .shape()
            .faces()
            .iter()
            .map(|f| f.vertices.len())
            .max()
            .unwrap_or(3) as f64;
        weight / (most * k) >= lowest
    }

    /// The body of `N` points (`N` its vertex count) the step rolls: each vertex's sphere
    /// (its own radius) about the centre of mass, the mass properties, and its faces as they
    /// are read: the outward normal of each face reversed, with the number read while that face
    /// is down, so that the face "up" the step reads is the number a player reads. It stops by
    /// the one rule when its faces stop alike ([`Die::faces_stop_alike`]), else by each face's
    /// own. A die of fewer vertices than `N` is carried with its last `N − V` points sharp
    /// at its centre of mass, where they never reach the table: they sit as high above it as
    /// the centre does, an inradius at rest (docs/dice.md, "A convex die of its corners").
    /// Refused when `N` is below the vertex count, or as [`PointBody::new`] refuses.
    pub fn point_body<const N: usize>(&self, params: &Params) -> Result<PointBody<N>, BodyError> {
        let count = self.shape().vertices().len();
        if count > N {
            return Err(BodyError(format!("this die has {count} vertices, more than {N}")));
        }
        let radii: [f64; N] = std::array::from_fn(|k| self.radii().get(k).copied().unwrap_or(0.0));
        let props = self.mass_properties();
        let vertices: [Vector3<f64>; N] = std::array::from_fn(|k| {
            self.sphere_centres()
                .get(k)
                .copied()
                .unwrap_or(props.centre_of_mass)
        });
        let faces: Vec<(Vector3<f64>, u8)> = (0..self.shape().faces().len())
            .map(|f| {
                let number = u8::try_from(self.numbering().read_with_down(f)).unwrap_or(u8::MAX);
                (-self.shape().faces()[f].normal, number)
            })
            .collect();
        let (stop_rule, edge_energy) = self.stop_rule(params);
        let body = PointBody::new(
            vertices,
            radii[0],
            props.mass,
            props.centre_of_mass,
            props.inertia,
            &faces,
            stop_rule,
            edge_energy,
        )?
        .with_radii(radii)?;
        if self.faces_stop_alike(params) {
            Ok(body)
        } else {
            body.with_face_rules(&self.face_stop_rules(params))
        }
    }
}

/// The share of a die's barrier by which its faces' rules may differ from its one rule and
/// still be alike: far above the rounding of the rest heights and edges (10⁻¹⁵ of the size)
/// and far below any flaw the registry lets a die have.
pub const ALIKE: f64 = 1e-9;
