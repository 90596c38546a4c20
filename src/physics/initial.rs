//! The initial condition of a roll (the `[initial]` section of a preset).

use super::body::body_corner_offsets;
use super::mass::LoadedMass;
use super::params::{Limits, ParamError, Params};
use super::registry::{self, Role, Setup};
use nalgebra::{Rotation3, Vector3};
use serde::{Deserialize, Serialize};

/// Where the die starts and how it moves at `t = 0`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct InitialCondition {
    /// cm, centre of mass above the ground.
    pub height: f64,
    /// cm/s, centre of mass.
    pub velocity: [f64; 3],
    /// rad/s, world frame.
    pub angular_velocity: [f64; 3],
    /// g·cm²/s: the same spin stated as `L = I·ω`. When present it takes the place of
    /// `angular_velocity` (the reference data are stated this way, and `L` is what the
    /// integrator carries, so it is used bit for bit).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angular_momentum: Option<[f64; 3]>,
    /// Degrees: yaw (about z), pitch (about y), roll (about x), as the aircraft convention
    /// applies them: `R = Rz(yaw)·Ry(pitch)·Rx(roll)`.
    pub orientation: [f64; 3],
}

impl Default for InitialCondition {
    fn default() -> Self {
        InitialCondition {
            height: registry::HEIGHT.number(),
            velocity: registry::VELOCITY.vector(),
            angular_velocity: registry::ANGULAR_VELOCITY.vector(),
            angular_momentum: None,
            orientation: registry::ORIENTATION.vector(),
        }
    }
}

impl InitialCondition {
    /// Checks every value against its allowed range; the first failure is returned.
    pub(crate) fn validate(&self) -> Result<(), ParamError> {
        let setup = Setup {
            initial: *self,
            ..Setup::default()
        };
        registry::validate(&setup, &[Role::Initial])
    }

    /// Refuses a start with any corner inside the table deeper than the die's resting depth
    /// `M·g/(4k)` (a die may be placed resting on the table, not pushed into it): the error
    /// names the lowest height allowed at this orientation.
    pub(crate) fn check_clear_of_table(&self, params: &Params) -> Result<(), ParamError> {
        let lowest_offset = match LoadedMass::new(params) {
            Some(m) => m
                .initial_corner_offsets(params.die.half_size, self)
                .iter()
                .map(|r| r.z)
                .fold(f64::INFINITY, f64::min),
            None => self.lowest_corner_offset(params.die.half_size),
        };
        let lowest = -lowest_offset - params.resting_depth();
        if self.height >= lowest {
            Ok(())
        } else {
            Err(ParamError {
                key: registry::HEIGHT.key().to_string(),
                value: self.height,
                limits: Limits {
                    min: lowest,
                    unit: "cm at this orientation (lower, a corner starts inside the table)",
                    ..registry::HEIGHT.limits
                },
                high_end: None,
            })
        }
    }

    /// cm, the lowest corner's height relative to the centre at `t = 0` (negative), with
    /// the corners placed exactly as the simulation places them.
    pub fn lowest_corner_offset(&self, half_size: f64) -> f64 {
        let corners = body_corner_offsets(half_size);
        let rotation = self.rotation();
        corners
            .iter()
            .map(|r| {
                if self.orientation == [0.0; 3] {
                    r.z
                } else {
                    (rotation * r).z
                }
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// g·cm²/s, the initial angular momentum for a body of moment of inertia `inertia`.
    pub(crate) fn angular_momentum_for(&self, inertia: f64) -> Vector3<f64> {
        match self.angular_momentum {
            Some(l) => Vector3::from(l),
            None => Vector3::from(self.angular_velocity) * inertia,
        }
    }

    /// rad/s, the initial angular velocity for a body of moment of inertia `inertia`.
    pub(crate) fn angular_velocity_for(&self, inertia: f64) -> Vector3<f64> {
        match self.angular_momentum {
            Some(l) => Vector3::from(l) / inertia,
            None => Vector3::from(self.angular_velocity),
        }
    }

    /// The body-to-world rotation at `t = 0`.
    pub(crate) fn rotation(&self) -> Rotation3<f64> {
        let [yaw, pitch, roll] = self.orientation.map(f64::to_radians);
        // from_euler_angles(roll, pitch, yaw) = Rz(yaw)·Ry(pitch)·Rx(roll); all zeros give the
        // exact identity, so the reference's unrotated start is reproduced bit for bit.
        Rotation3::from_euler_angles(roll, pitch, yaw)
    }
}

/// How random rolls are drawn (the `[random]` section of a preset); the drawing itself is
/// the experiment layer's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RandomRanges {
    pub seed: u64,
    /// cm, centre of mass, uniform in `[low, high]`.
    pub height: [f64; 2],
    /// cm/s, each component uniform in `[low, high]`.
    pub velocity: [f64; 2],
    /// rad/s, each component uniform in `[low, high]`.
    pub angular_velocity: [f64; 2],
    /// true: orientation uniform over all rotations; false: the initial condition's.
    pub random_orientation: bool,
}

impl Default for RandomRanges {
    fn default() -> Self {
        RandomRanges {
            seed: registry::SEED.seed(),
            height: registry::RANDOM_HEIGHT.range(),
            velocity: registry::RANDOM_VELOCITY.range(),
            angular_velocity: registry::RANDOM_ANGULAR_VELOCITY.range(),
            random_orientation: registry::RANDOM_ORIENTATION.flag(),
        }
    }
}

impl RandomRanges {
    /// Each bound within the matching initial-condition range, and `low <= high`.
    pub(crate) fn validate(&self) -> Result<(), ParamError> {
        let setup = Setup {
            random: *self,
            ..Setup::default()
        };
        registry::validate(&setup, &[Role::Random])
    }
}
