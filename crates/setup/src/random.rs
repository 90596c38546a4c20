//! Random initial conditions drawn reproducibly: one ChaCha stream per (seed, roll index),
//! so a roll's draw depends on nothing else (not the thread, not the order of completion).

pub use dicesim_physics::RandomRanges;
use dicesim_physics::{InitialCondition, Limits, ParamError, Params, Simulation};
use nalgebra::{Quaternion, Rotation3, UnitQuaternion};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};

/// The one check of a setup whose starts are drawn from `ranges` (a batch, a comparison and
/// each of its fit's candidates, a prediction's curve, `--versus`'s setup B): every parameter
/// in its range and the body able to exist (what `roll` checks first, in the same words),
/// then the ranges, and no draw starting inside the table.
pub fn check_drawn_setup(
    params: &Params,
    ranges: &RandomRanges,
    base: &InitialCondition,
) -> Result<(), ParamError> {
    params.validate()?;
    ranges.validate()?;
    ranges.check_clear_of_table(params, base)
}

/// What [`RandomRanges`] needs beyond the physics crate, which defines it: the random
/// stream a roll's start is drawn from, and the registry's name for the height range.
pub trait RandomDraws {
    /// Refuses ranges whose draws can start with a corner inside the table (see the impl).
    fn check_clear_of_table(&self, params: &Params, base: &InitialCondition) -> Result<(), ParamError>;
    /// The initial condition of roll `index` of a batch seeded with `seed`.
    fn draw(&self, base: &InitialCondition, seed: u64, index: u64) -> InitialCondition;
}

impl RandomDraws for RandomRanges {
    /// Refuses ranges whose draws can start with a corner inside the table, before any roll,
    /// by the rule [`InitialCondition::check_clear_of_table`] applies to one start: the
    /// lowest height allowed is the die's reach below its centre of mass (its farthest
    /// corner, for a random orientation; the lowest corner at `base`'s orientation
    /// otherwise) less its resting depth (a die may start resting on the table, not pushed into
    /// it). The error names that height.
    fn check_clear_of_table(&self, params: &Params, base: &InitialCondition) -> Result<(), ParamError> {
        let reach = if self.random_orientation {
            // Some orientation points the farthest corner straight down.
            let upright = InitialCondition {
                orientation: [0.0; 3],
                ..*base
            };
            Simulation::for_outcome(params, &upright)
                .state()
                .corner_offsets
                .iter()
                .map(|r| r.norm())
                .fold(0.0, f64::max)
        } else {
            -Simulation::for_outcome(params, base)
                .state()
                .corner_offsets
                .iter()
                .map(|r| r.z)
                .fold(f64::INFINITY, f64::min)
        };
        let lowest = reach - params.resting_depth();
        if self.height[0] >= lowest {
            return Ok(());
        }
        let key = &crate::registry::RANDOM_HEIGHT;
        Err(ParamError {
            key: key.key().to_string(),
            value: self.height[0],
            limits: Limits {
                min: lowest,
                unit: if self.random_orientation {
                    "cm at its low end (lower, a drawn orientation can start a corner inside the table)"
                } else {
                    "cm at its low end at this orientation (lower, a corner starts inside the table)"
                },
                ..key.limits
            },
            detail: None,
        })
    }

    /// The initial condition of roll `index` of a batch seeded with `seed`: `base` with
    /// height, velocity, spin (and, if asked, orientation) drawn from these ranges.
    fn draw(&self, base: &InitialCondition, seed: u64, index: u64) -> InitialCondition {
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

/// Why a `--set` of `key` does not reach a roll whose start is drawn from `ranges` (`None`
/// where it does): the draw replaces the start's height, velocity and spin, and its
/// orientation too when `ranges` draw that. `command` names the command in the reason.
pub fn unapplied_when_drawn(key: &str, ranges: &RandomRanges, command: &str) -> Option<String> {
    let is = |name: &str| key == name || key.strip_prefix(name).is_some_and(|c| c.starts_with('.'));
    let drawn = |what: &str, range: &str| {
        Some(format!(
            "`{command}` draws each throw's {what} from `{range}`: set that range instead"
        ))
    };
    if is("initial.height") {
        drawn("height", "random.height")
    } else if is("initial.velocity") {
        drawn("velocity", "random.velocity")
    } else if is("initial.angular_velocity") || is("initial.angular_momentum") {
        drawn("spin", "random.angular_velocity")
    } else if is("initial.orientation") && ranges.random_orientation {
        Some(format!(
            "`{command}` draws each throw's orientation uniformly (`random.random_orientation` \
             is true), so the preset's orientation is not used"
        ))
    } else {
        None
    }
}

/// Why a `--set` of `key` does not reach a command that rolls the preset's one start
/// (`initial.*`) and draws nothing: every `random.*` key.
pub fn unapplied_when_fixed(key: &str, command: &str) -> Option<String> {
    key.starts_with("random.")
        .then(|| format!("`{command}` rolls the preset's one start (`initial.*`); it draws no random throws"))
}

/// Why a `--set random.seed` is not applied when `--seed` is also given.
pub fn seed_given(key: &str, seed_option: bool) -> Option<String> {
    (seed_option && key == "random.seed")
        .then(|| "--seed is given, and it replaces the preset's seed".to_string())
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
