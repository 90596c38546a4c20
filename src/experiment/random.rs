//! Random initial conditions drawn reproducibly: one ChaCha stream per (seed, roll index),
//! so a roll's draw depends on nothing else (not the thread, not the order of completion).

use crate::physics::InitialCondition;
pub use crate::physics::RandomRanges;
use nalgebra::{Quaternion, Rotation3, UnitQuaternion};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};

impl RandomRanges {
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
pub(crate) fn roll_rng(seed: u64, index: u64) -> ChaCha8Rng {
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
