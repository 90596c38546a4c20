//! The initial condition of a roll (the `[initial]` section of a preset).

use super::body::body_corner_offsets;
use super::params::{Limits, ParamError, Params};
use nalgebra::{Rotation3, Vector3};
use serde::{Deserialize, Serialize};

pub const HEIGHT: Limits = Limits {
    key: "initial.height",
    unit: "cm",
    min: 0.0,
    max: 1000.0,
};
pub const VELOCITY: Limits = Limits {
    key: "initial.velocity",
    unit: "cm/s",
    min: -10_000.0,
    max: 10_000.0,
};
pub const ANGULAR_VELOCITY: Limits = Limits {
    key: "initial.angular_velocity",
    unit: "rad/s",
    min: -10_000.0,
    max: 10_000.0,
};
pub const ANGULAR_MOMENTUM: Limits = Limits {
    key: "initial.angular_momentum",
    unit: "g·cm²/s",
    min: -1e6,
    max: 1e6,
};
pub const ORIENTATION: Limits = Limits {
    key: "initial.orientation",
    unit: "°",
    min: -360.0,
    max: 360.0,
};

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
            height: 15.0,
            velocity: [0.0; 3],
            angular_velocity: [0.0; 3],
            angular_momentum: None,
            orientation: [0.0; 3],
        }
    }
}

impl InitialCondition {
    pub fn validate(&self) -> Result<(), ParamError> {
        HEIGHT.check(self.height)?;
        VELOCITY.check_vector(&self.velocity)?;
        ANGULAR_VELOCITY.check_vector(&self.angular_velocity)?;
        if let Some(l) = &self.angular_momentum {
            ANGULAR_MOMENTUM.check_vector(l)?;
        }
        ORIENTATION.check_components(&self.orientation, ["yaw", "pitch", "roll"])?;
        Ok(())
    }

    /// Refuses a start with any corner inside the table deeper than the die's resting depth
    /// `M·g/(4k)` (a die may be placed resting on the table, not pushed into it): the error
    /// names the lowest height allowed at this orientation.
    pub fn check_clear_of_table(&self, params: &Params) -> Result<(), ParamError> {
        let lowest = -self.lowest_corner_offset(params.die.half_size) - params.resting_depth();
        if self.height >= lowest {
            Ok(())
        } else {
            Err(ParamError {
                key: HEIGHT.key.to_string(),
                value: self.height,
                limits: Limits {
                    min: lowest,
                    unit: "cm at this orientation (lower, a corner starts inside the table)",
                    ..HEIGHT
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
    pub fn angular_momentum_for(&self, inertia: f64) -> Vector3<f64> {
        match self.angular_momentum {
            Some(l) => Vector3::from(l),
            None => Vector3::from(self.angular_velocity) * inertia,
        }
    }

    /// rad/s, the initial angular velocity for a body of moment of inertia `inertia`.
    pub fn angular_velocity_for(&self, inertia: f64) -> Vector3<f64> {
        match self.angular_momentum {
            Some(l) => Vector3::from(l) / inertia,
            None => Vector3::from(self.angular_velocity),
        }
    }

    /// The body-to-world rotation at `t = 0`.
    pub fn rotation(&self) -> Rotation3<f64> {
        let [yaw, pitch, roll] = self.orientation.map(f64::to_radians);
        // from_euler_angles(roll, pitch, yaw) = Rz(yaw)·Ry(pitch)·Rx(roll); all zeros give the
        // exact identity, so the reference's unrotated start is reproduced bit for bit.
        Rotation3::from_euler_angles(roll, pitch, yaw)
    }
}
