//! The initial condition of a roll (the `[initial]` section of a preset) and the ranges
//! random rolls are drawn from: data and their validation. Where a start puts the die's
//! corners, and whether that is clear of the table, depends on the body and is the body
//! model's (model.rs).

use super::params::{Limits, ParamError, XYZ};
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

/// The names of the orientation's components.
pub const YAW_PITCH_ROLL: &[&str; 3] = &["yaw", "pitch", "roll"];

/// Each value's key, unit and allowed range; a random range's bounds lie in the range of
/// the value it draws.
pub mod limits {
    use super::Limits;

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
    pub const RANDOM_HEIGHT: Limits = Limits {
        key: "random.height",
        ..HEIGHT
    };
    pub const RANDOM_VELOCITY: Limits = Limits {
        key: "random.velocity",
        ..VELOCITY
    };
    pub const RANDOM_ANGULAR_VELOCITY: Limits = Limits {
        key: "random.angular_velocity",
        ..ANGULAR_VELOCITY
    };
    pub const ORIENTATION_SPREAD: Limits = Limits {
        key: "random.orientation_spread",
        unit: "°",
        min: 0.0,
        max: 180.0,
    };
}

impl Default for InitialCondition {
    fn default() -> Self {
        InitialCondition::DEFAULT
    }
}

impl InitialCondition {
    /// The die at rest, unrotated, its centre 15 cm above the table.
    pub const DEFAULT: InitialCondition = InitialCondition {
        height: 15.0,
        velocity: [0.0; 3],
        angular_velocity: [0.0; 3],
        angular_momentum: None,
        orientation: [0.0; 3],
    };

    /// Checks every value against its allowed range, in the order a preset lists them; the
    /// first failure is returned.
    pub fn validate(&self) -> Result<(), ParamError> {
        limits::HEIGHT.check(self.height)?;
        limits::VELOCITY.check_components(XYZ, &self.velocity)?;
        limits::ANGULAR_VELOCITY.check_components(XYZ, &self.angular_velocity)?;
        if let Some(l) = &self.angular_momentum {
            limits::ANGULAR_MOMENTUM.check_components(XYZ, l)?;
        }
        limits::ORIENTATION.check_components(YAW_PITCH_ROLL, &self.orientation)
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
    /// degrees: each throw's orientation is the initial condition's turned by a random
    /// rotation of angle at most this, uniform (Haar) among those; 0 keeps it fixed, 180 is
    /// uniform over all rotations. Refused beside `random_orientation = true`, which
    /// already draws every orientation.
    pub orientation_spread: f64,
}

impl Default for RandomRanges {
    fn default() -> Self {
        RandomRanges::DEFAULT
    }
}

impl RandomRanges {
    /// Throws from 15 cm with up to 50 cm/s and 60 rad/s per component, unrotated.
    pub const DEFAULT: RandomRanges = RandomRanges {
        seed: 1,
        height: [15.0, 15.0],
        velocity: [-50.0, 50.0],
        angular_velocity: [-60.0, 60.0],
        random_orientation: false,
        orientation_spread: 0.0,
    };

    /// Each bound within the matching initial-condition range, and `low <= high`.
    pub fn validate(&self) -> Result<(), ParamError> {
        limits::RANDOM_HEIGHT.check_range(self.height)?;
        limits::RANDOM_VELOCITY.check_range(self.velocity)?;
        limits::RANDOM_ANGULAR_VELOCITY.check_range(self.angular_velocity)?;
        limits::ORIENTATION_SPREAD.check(self.orientation_spread)?;
        if self.random_orientation && self.orientation_spread > 0.0 {
            return Err(ParamError::refused(
                limits::ORIENTATION_SPREAD,
                self.orientation_spread,
                "`random.random_orientation` is true and already draws every orientation: \
                 give one of the two (180° spread is the uniform draw)"
                    .to_string(),
            ));
        }
        Ok(())
    }
}
