//! Random initial conditions drawn reproducibly: one ChaCha stream per (seed, roll index),
//! so a roll's draw depends on nothing else (not the thread, not the order of completion).

use crate::physics::{InitialCondition, Limits, ParamError, initial};
use nalgebra::{Quaternion, Rotation3, UnitQuaternion};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};

/// How random rolls are drawn (the `[random]` section of a preset).
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
            seed: 1,
            height: [15.0, 15.0],
            velocity: [-50.0, 50.0],
            angular_velocity: [-60.0, 60.0],
            random_orientation: false,
        }
    }
}

fn check_range(limits: Limits, key: &str, range: &[f64; 2]) -> Result<(), ParamError> {
    for (i, &value) in range.iter().enumerate() {
        limits.check(value).map_err(|mut e| {
            e.key = format!("{key}[{i}]");
            e
        })?;
    }
    if range[0] > range[1] {
        return Err(ParamError {
            key: key.to_string(),
            value: range[0],
            limits,
            high_end: Some(range[1]),
        });
    }
    Ok(())
}

impl RandomRanges {
    /// Each bound within the matching initial-condition range, and `low <= high`.
    pub fn validate(&self) -> Result<(), ParamError> {
        check_range(initial::HEIGHT, "random.height", &self.height)?;
        check_range(initial::VELOCITY, "random.velocity", &self.velocity)?;
        check_range(
            initial::ANGULAR_VELOCITY,
            "random.angular_velocity",
            &self.angular_velocity,
        )?;
        Ok(())
    }

    /// The initial condition of roll `index` of a batch seeded with `seed`: `base` with
    /// height, velocity, spin (and, if asked, orientation) drawn from these ranges.
    pub fn draw(&self, base: &InitialCondition, seed: u64, index: u64) -> InitialCondition {
        let mut rng = roll_rng(seed, index);
        let mut uniform = |r: [f64; 2]| rng.random_range(r[0]..=r[1]);
        let height = uniform(self.height);
        let velocity = [
            uniform(self.velocity),
            uniform(self.velocity),
            uniform(self.velocity),
        ];
        let angular_velocity = [
            uniform(self.angular_velocity),
            uniform(self.angular_velocity),
            uniform(self.angular_velocity),
        ];
        let orientation = if self.random_orientation {
            random_orientation_degrees(&mut rng)
        } else {
            base.orientation
        };
        InitialCondition {
            height,
            velocity,
            angular_velocity,
            angular_momentum: None,
            orientation,
        }
    }
}

/// The random stream of one roll: key = seed, ChaCha stream = roll index.
pub fn roll_rng(seed: u64, index: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index);
    rng
}

/// A rotation uniform over SO(3) (Shoemake's unit quaternion), as yaw, pitch, roll in degrees.
fn random_orientation_degrees(rng: &mut ChaCha8Rng) -> [f64; 3] {
    use std::f64::consts::TAU;
    let (u1, u2, u3): (f64, f64, f64) = (
        rng.random_range(0.0..1.0),
        rng.random_range(0.0..1.0),
        rng.random_range(0.0..1.0),
    );
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    let q = Quaternion::new(
        b * (TAU * u3).cos(),
        a * (TAU * u2).sin(),
        a * (TAU * u2).cos(),
        b * (TAU * u3).sin(),
    );
    let rotation: Rotation3<f64> = UnitQuaternion::from_quaternion(q).to_rotation_matrix();
    let (roll, pitch, yaw) = rotation.euler_angles();
    [yaw.to_degrees(), pitch.to_degrees(), roll.to_degrees()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draw_depends_on_seed_and_index_only() {
        let r = RandomRanges::default();
        let base = InitialCondition::default();
        assert_eq!(r.draw(&base, 7, 3), r.draw(&base, 7, 3));
        assert_ne!(r.draw(&base, 7, 3), r.draw(&base, 7, 4));
        assert_ne!(r.draw(&base, 8, 3), r.draw(&base, 7, 3));
    }

    #[test]
    fn draws_stay_in_their_ranges() {
        let r = RandomRanges {
            height: [2.0, 9.0],
            random_orientation: true,
            ..Default::default()
        };
        for i in 0..500 {
            let ic = r.draw(&InitialCondition::default(), 1, i);
            assert!((2.0..=9.0).contains(&ic.height));
            assert!(ic.velocity.iter().all(|v| (-50.0..=50.0).contains(v)));
            assert!(ic.angular_velocity.iter().all(|v| (-60.0..=60.0).contains(v)));
            ic.validate().unwrap();
        }
    }

    #[test]
    fn inverted_range_is_refused() {
        let r = RandomRanges {
            velocity: [10.0, -10.0],
            ..Default::default()
        };
        let e = r.validate().unwrap_err();
        assert_eq!(e.key, "random.velocity");
        assert_eq!(
            e.to_string(),
            "`random.velocity` = [10, -10]: the low end is above the high end"
        );
    }
}
