//! Random initial conditions drawn reproducibly: one ChaCha stream per (seed, roll index),
//! so a roll's draw depends on nothing else (not the thread, not the order of completion).

pub use dicesim_physics::RandomRanges;
use dicesim_physics::{InitialCondition, Limits, ParamError, Params, Reading, Simulation, StabilityCheck};
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
                    "cm at its low end (lower, a drawn orientation can start a corner deeper in the table than the die \
                     sinks resting on it)"
                } else {
                    "cm at its low end at this orientation (lower, a corner starts deeper in the table than the die \
                     sinks resting on it)"
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
        // Drawn last, and only when asked, so that a fixed orientation leaves every other
        // draw as it was before the spread existed.
        let orientation = if self.random_orientation {
            random_orientation_degrees(&mut rng)
        } else if self.orientation_spread > 0.0 {
            let turn = rotation_within(&mut rng, self.orientation_spread.to_radians());
            yaw_pitch_roll_degrees(&(turn * base.rotation()))
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

/// The largest seed, 2⁶³ − 1: a preset holds its seed as a TOML integer, which is signed
/// 64-bit, so a larger one could not be written back (docs/presets.md).
pub const MAX_SEED: u64 = i64::MAX as u64;

/// Why `seed` is refused: above [`MAX_SEED`].
fn seed_refusal(seed: impl std::fmt::Display) -> String {
    format!("{seed} is above 2⁶³ − 1 = {MAX_SEED}, the largest seed")
}

/// A `--seed` as typed: a whole number from 0 to 2⁶³ − 1 (clap's value parser).
pub fn parse_seed(text: &str) -> Result<u64, String> {
    match text.trim().parse::<u64>() {
        Ok(seed) if seed <= MAX_SEED => Ok(seed),
        Ok(seed) => Err(seed_refusal(seed)),
        Err(_) if text.trim().bytes().all(|b| b.is_ascii_digit()) && !text.trim().is_empty() => {
            Err(seed_refusal(text.trim()))
        }
        Err(_) => Err(format!(
            "`{text}`: a seed is a whole number from 0 to 2⁶³ − 1 = {MAX_SEED}"
        )),
    }
}

/// Refuses a preset's `random.seed` above [`MAX_SEED`], naming the key.
pub fn check_seed(seed: u64) -> Result<(), ParamError> {
    if seed <= MAX_SEED {
        return Ok(());
    }
    Err(ParamError {
        key: "random.seed".to_string(),
        value: f64::NAN,
        limits: Limits {
            key: "random.seed",
            unit: "",
            min: 0.0,
            max: MAX_SEED as f64,
        },
        detail: Some(Box::new(dicesim_physics::params::Detail::Refused(seed_refusal(
            seed,
        )))),
    })
}

/// Why a `--set random.seed` is not applied when `--seed` is also given.
pub fn seed_given(key: &str, seed_option: bool) -> Option<String> {
    (seed_option && key == "random.seed")
        .then(|| "--seed is given, and it replaces the preset's seed".to_string())
}

/// The stability check's verdict at the worst throw `ranges` can draw from `base`: the
/// highest drop, each velocity and spin component at the end of its range farthest from
/// zero, and every orientation that lands from highest — `base`'s, and when the
/// orientation is drawn (uniformly or by a spread) also each body axis vertical, the
/// landing face-down on each pair of faces. The reading with the largest load among those
/// throws is the verdict (`load() ≤ 1`: every throw is predicted to step stably).
pub fn worst_throw_reading(params: &Params, ranges: &RandomRanges, base: &InitialCondition) -> Reading {
    let far = |[low, high]: [f64; 2]| if high.abs() >= low.abs() { high } else { low };
    let worst = InitialCondition {
        height: ranges.height[1],
        velocity: [far(ranges.velocity); 3],
        angular_velocity: [far(ranges.angular_velocity); 3],
        angular_momentum: None,
        ..*base
    };
    let mut orientations = vec![base.orientation];
    if ranges.random_orientation || ranges.orientation_spread > 0.0 {
        // yaw, pitch, roll: body z, then x (pitch 90°), then y (roll 90°) vertical.
        orientations.extend([[0.0, 0.0, 0.0], [0.0, 90.0, 0.0], [0.0, 0.0, 90.0]]);
    }
    let check = StabilityCheck::new(params);
    orientations
        .into_iter()
        .map(|orientation| {
            check
                .predict(&InitialCondition { orientation, ..worst })
                .verdict()
        })
        .max_by(|a, b| a.load().total_cmp(&b.load()))
        .expect("at least the base orientation")
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
    yaw_pitch_roll_degrees(&UnitQuaternion::from_quaternion(q).to_rotation_matrix())
}

/// A rotation as a preset states an orientation: yaw, pitch, roll in degrees.
fn yaw_pitch_roll_degrees(rotation: &Rotation3<f64>) -> [f64; 3] {
    let (roll, pitch, yaw) = rotation.euler_angles();
    // + 0.0 turns a −0 (a turn too small to show, 1e-320°) into the 0 a start is written as.
    [yaw, pitch, roll].map(|a| a.to_degrees() + 0.0)
}

/// A rotation uniform (Haar) among those of angle at most `spread` (radians, 0 to π):
/// docs/model.md, "Throws near an orientation". The angle ω has density ∝ 1 − cos ω, so it
/// is the inverse of ω − sin ω at a uniform share of `spread − sin spread`; the axis is
/// uniform on the sphere, independent of ω.
pub fn rotation_within(rng: &mut ChaCha8Rng, spread: f64) -> Rotation3<f64> {
    use std::f64::consts::TAU;
    let (u, z, phi): (f64, f64, f64) = (
        rng.random_range(0.0..1.0),
        rng.random_range(-1.0..=1.0),
        rng.random_range(0.0..TAU),
    );
    let target = u * angle_mass(spread);
    // Bisection: angle_mass rises strictly on [0, π]; 60 halvings reach f64's resolution.
    let (mut low, mut high) = (0.0, spread);
    for _ in 0..60 {
        let mid = 0.5 * (low + high);
        if angle_mass(mid) < target {
            low = mid;
        } else {
            high = mid;
        }
    }
    let omega = 0.5 * (low + high);
    let r = (1.0 - z * z).max(0.0).sqrt();
    let axis = nalgebra::Unit::new_unchecked(nalgebra::Vector3::new(r * phi.cos(), r * phi.sin(), z));
    Rotation3::from_axis_angle(&axis, omega)
}

/// ω − sin ω (π times the uniform rotation's angle law at ω), by its series where the
/// difference of two near numbers would lose the digits a small spread needs.
fn angle_mass(omega: f64) -> f64 {
    if omega < 0.25 {
        let w2 = omega * omega;
        // ω³/3! − ω⁵/5! + ω⁷/7! − ω⁹/9! + ω¹¹/11!: the next term is below 10⁻¹⁵ of the sum.
        omega
            * w2
            * (1.0 / 6.0
                - w2 * (1.0 / 120.0 - w2 * (1.0 / 5040.0 - w2 * (1.0 / 362_880.0 - w2 / 39_916_800.0))))
    } else {
        omega - omega.sin()
    }
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

    /// The angle of the rotation taking `base`'s orientation to `drawn`'s, radians.
    fn turned_by(base: &InitialCondition, drawn: &InitialCondition) -> f64 {
        (drawn.rotation() * base.rotation().inverse()).angle()
    }

    /// A start turned off the identity, so a spread's composition order would show.
    fn tilted() -> InitialCondition {
        InitialCondition {
            orientation: [30.0, 20.0, 10.0],
            ..InitialCondition::default()
        }
    }

    #[test]
    fn no_spread_keeps_todays_draw_of_a_fixed_orientation() {
        // Today's draw, stated on its own: height, three velocities, three spins, in that
        // order from the roll's stream, the orientation the start's.
        let (r, base) = (RandomRanges::default(), tilted());
        for i in 0..200 {
            let mut rng = roll_rng(5, i);
            let mut u = |range: [f64; 2]| rng.random_range(range[0]..=range[1]);
            let height = u(r.height);
            let velocity = [u(r.velocity), u(r.velocity), u(r.velocity)];
            let spin = [
                u(r.angular_velocity),
                u(r.angular_velocity),
                u(r.angular_velocity),
            ];
            let drawn = r.draw(&base, 5, i);
            assert_eq!(drawn.height.to_bits(), height.to_bits());
            assert_eq!(drawn.velocity.map(f64::to_bits), velocity.map(f64::to_bits));
            assert_eq!(drawn.angular_velocity.map(f64::to_bits), spin.map(f64::to_bits));
            assert_eq!(
                drawn.orientation.map(f64::to_bits),
                base.orientation.map(f64::to_bits)
            );
        }
    }

    #[test]
    fn a_spread_keeps_every_rotation_within_its_angle() {
        let r = RandomRanges {
            orientation_spread: 10.0,
            ..Default::default()
        };
        let base = tilted();
        let mut largest: f64 = 0.0;
        for i in 0..20_000 {
            let drawn = r.draw(&base, 2, i);
            largest = largest.max(turned_by(&base, &drawn));
        }
        // Within 10° (up to the degrees' round trip), and reaching near it: P(ω ≤ 9.9°) ≈
        // 0.970 per draw (docs/model.md), so all 20 000 below it has probability 0.970²⁰⁰⁰⁰.
        assert!(largest <= 10f64.to_radians() + 1e-9, "{}°", largest.to_degrees());
        assert!(largest > 9.9f64.to_radians(), "{}°", largest.to_degrees());
    }

    #[test]
    fn a_half_turn_spread_draws_the_uniform_rotations_angle_law() {
        // Haar measure on SO(3): the angle ω has CDF (ω − sin ω)/π on [0, π].
        let r = RandomRanges {
            orientation_spread: 180.0,
            ..Default::default()
        };
        let base = tilted();
        let n = 60_000;
        // Kolmogorov–Smirnov distance of the drawn angles from that law.
        let distance = |ranges: &RandomRanges| {
            let mut angles: Vec<f64> = (0..n)
                .map(|i| turned_by(&base, &ranges.draw(&base, 3, i)))
                .collect();
            angles.sort_by(f64::total_cmp);
            let cdf = |w: f64| (w - w.sin()) / std::f64::consts::PI;
            angles
                .iter()
                .enumerate()
                .map(|(i, &w)| {
                    let f = cdf(w);
                    (f - i as f64 / n as f64).max((i + 1) as f64 / n as f64 - f)
                })
                .fold(0.0, f64::max)
        };
        let d = distance(&r);
        // Kolmogorov's distribution: P(√n·D > λ) = 2 Σ (−1)^(k−1) e^(−2k²λ²).
        let lambda = (n as f64).sqrt() * d;
        let p: f64 = 2.0
            * (1..=100)
                .map(|k: i32| {
                    let k = f64::from(k);
                    (-1f64).powf(k - 1.0) * (-2.0 * k * k * lambda * lambda).exp()
                })
                .sum::<f64>();
        assert!(p > 0.01, "KS D = {d}, p = {p}");
        // And the test can tell: a spread of 170° is not the uniform law.
        let narrower = RandomRanges {
            orientation_spread: 170.0,
            ..Default::default()
        };
        let d_other = distance(&narrower);
        assert!(
            (n as f64).sqrt() * d_other > 1.63,
            "170° passed as uniform: D = {d_other}"
        );
    }

    #[test]
    fn a_spread_beside_a_uniform_orientation_is_refused() {
        let r = RandomRanges {
            random_orientation: true,
            orientation_spread: 20.0,
            ..Default::default()
        };
        let e = r.validate().unwrap_err().to_string();
        assert!(
            e.starts_with("`random.orientation_spread` = 20: `random.random_orientation` is true"),
            "{e}"
        );
    }
}
