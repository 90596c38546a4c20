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
    /// about the centre of mass, the mass properties, and its faces as they are read: the
    /// outward normal of each face reversed, with the number read while that face is down, so
    /// that the face "up" the step reads is the number a player reads. Refused when `N` is not
    /// the vertex count, when the vertices are rounded unevenly (the body takes one radius),
    /// or as [`PointBody::new`] refuses.
    pub fn point_body<const N: usize>(&self, params: &Params) -> Result<PointBody<N>, BodyError> {
        let count = self.shape().vertices().len();
        if count != N {
            return Err(BodyError(format!("this die has {count} vertices, not {N}")));
        }
        let radius = self.radii()[0];
        if self.radii().iter().any(|&r| r != radius) {
            return Err(BodyError(
                "the step rounds every point alike: uneven rounding is not rolled".into(),
            ));
        }
        let props = self.mass_properties();
        let vertices: [Vector3<f64>; N] = std::array::from_fn(|k| self.sphere_centres()[k]);
        let faces: Vec<(Vector3<f64>, u8)> = (0..self.shape().faces().len())
            .map(|f| {
                let number = u8::try_from(self.numbering().read_with_down(f)).unwrap_or(u8::MAX);
                (-self.shape().faces()[f].normal, number)
            })
            .collect();
        let (stop_rule, edge_energy) = self.stop_rule(params);
        PointBody::new(
            vertices,
            radius,
            props.mass,
            props.centre_of_mass,
            props.inertia,
            &faces,
            stop_rule,
            edge_energy,
        )
    }
}
