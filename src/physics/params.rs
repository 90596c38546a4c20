//! Model parameters (docs/model.md), in CGS units, with their defaults ([`Params::DEFAULT`])
//! and their keys, units and allowed ranges ([`limits`]), each stated here once: the
//! registry of setup values one layer up reads them from here.
//!
//! The structs mirror the sections of a preset file (docs/presets.md), so the preset layer
//! deserialises straight into them; every struct denies unknown keys and fills missing ones
//! with the paper's defaults.

use serde::{Deserialize, Serialize};
use std::fmt;

/// A numeric parameter's identity: its dotted preset key, its unit and its allowed range.
///
/// Every range check, error message and UI label reads from these, so a field's limits are
/// stated once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Dotted preset / `--set` key, e.g. `ground.stiffness`.
    pub key: &'static str,
    /// Unit as shown to users (`""` for dimensionless).
    pub unit: &'static str,
    pub min: f64,
    pub max: f64,
}

impl Limits {
    /// Checks `value` (NaN and infinities are outside every range).
    pub fn check(&self, value: f64) -> Result<(), ParamError> {
        if value >= self.min && value <= self.max {
            Ok(())
        } else {
            Err(ParamError {
                key: self.key.to_string(),
                value,
                limits: *self,
                high_end: None,
            })
        }
    }

    /// Checks one number against the range, naming `key` in the error (a component, or a
    /// range's end).
    pub(crate) fn check_as(&self, key: &str, value: f64) -> Result<(), ParamError> {
        self.check(value).map_err(|mut e| {
            e.key = key.to_string();
            e
        })
    }

    /// Checks each component, naming it (`initial.velocity.y`, `die.extra_corner_mass.8`).
    pub(crate) fn check_components(&self, names: &[&str], values: &[f64]) -> Result<(), ParamError> {
        for (name, &x) in names.iter().zip(values) {
            self.check_as(&format!("{}.{name}", self.key), x)?;
        }
        Ok(())
    }

    /// Checks a range `[low, high]`: each end inside, the low end not above the high end.
    /// Errors name the end (`random.height[1]`).
    pub(crate) fn check_range(&self, range: [f64; 2]) -> Result<(), ParamError> {
        for (i, x) in range.into_iter().enumerate() {
            self.check_as(&format!("{}[{i}]", self.key), x)?;
        }
        if range[0] > range[1] {
            return Err(ParamError {
                key: self.key.to_string(),
                value: range[0],
                limits: *self,
                high_end: Some(range[1]),
            });
        }
        Ok(())
    }
}

/// The names of a vector's components, and of the corners 1..8 of a per-corner value.
pub(crate) const XYZ: &[&str; 3] = &["x", "y", "z"];
pub(crate) const CORNERS: &[&str; 8] = &["1", "2", "3", "4", "5", "6", "7", "8"];

/// Each numeric parameter's key, unit and allowed range.
pub mod limits {
    use super::Limits;

    const fn limits(key: &'static str, unit: &'static str, min: f64, max: f64) -> Limits {
        Limits { key, unit, min, max }
    }

    pub const HALF_SIZE: Limits = limits("die.half_size", "cm", 0.1, 10.0);
    pub const CORNER_MASS: Limits = limits("die.corner_mass", "g", 0.01, 1000.0);
    pub const EXTRA_CORNER_MASS: Limits = limits("die.extra_corner_mass", "g", 0.0, 1000.0);
    pub const STIFFNESS: Limits = limits("ground.stiffness", "dyn/cm", 100.0, 1e8);
    pub const DAMPING: Limits = limits("ground.damping", "s/cm", 0.0, 0.1);
    pub const FRICTION: Limits = limits("ground.friction", "", 0.0, 5.0);
    pub const GRAVITY: Limits = limits("world.gravity", "cm/s²", 10.0, 10000.0);
    pub const DT: Limits = limits("integrator.dt", "s", 1e-5, 1e-2);
    pub const STOP_ENERGY_FRACTION: Limits = limits("integrator.stop_energy_fraction", "", 0.01, 1.0);
    pub const MAX_TIME: Limits = limits("integrator.max_time", "s", 0.01, 120.0);
}

/// A value outside its allowed range: names the field, the value and the range.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamError {
    pub key: String,
    pub value: f64,
    pub limits: Limits,
    /// For a range `[low, high]` given the wrong way round: `value` is the low end, this
    /// the high end below it.
    pub high_end: Option<f64>,
}

/// A number as a person reads it: 1e308 rather than its 309 digits.
fn fmt_number(value: f64) -> String {
    let magnitude = value.abs();
    if value.is_finite() && (magnitude >= 1e15 || (magnitude > 0.0 && magnitude < 1e-6)) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = if self.limits.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.limits.unit)
        };
        if let Some(high) = self.high_end {
            return write!(
                f,
                "`{}` = [{}, {}]: the low end is above the high end",
                self.key,
                fmt_number(self.value),
                fmt_number(high)
            );
        }
        write!(
            f,
            "`{}` = {} is outside the allowed range {} to {}{unit}",
            self.key,
            fmt_number(self.value),
            fmt_number(self.limits.min),
            fmt_number(self.limits.max)
        )
    }
}

impl std::error::Error for ParamError {}

/// No roll runs longer than this many steps, whatever its parameters (under a second).
pub const MAX_STEPS_CAP: u64 = 12_000_000;

/// The die: a cube of 8 corner point masses.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Die {
    /// cm; the paper's "radius" (side = 2 × half_size).
    pub half_size: f64,
    /// g, each of the 8 corners.
    pub corner_mass: f64,
    /// g, point masses added at corners 1..8 (a loaded die, docs/model.md "Loaded dice");
    /// all zero is the paper's fair die.
    pub extra_corner_mass: [f64; 8],
}

impl Die {
    /// Whether any corner carries extra mass: such a die steps on its own code path.
    pub fn is_loaded(&self) -> bool {
        self.extra_corner_mass.iter().any(|&m| m != 0.0)
    }
}

impl Default for Die {
    fn default() -> Self {
        Params::DEFAULT.die
    }
}

/// How the horizontal friction force on a touching corner is scaled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FrictionLaw {
    /// The paper's eq. 15: `−μ·|P|·û` with each corner's own slip direction.
    #[default]
    PerCorner,
    /// The authors' original program: each corner's slip divided by the largest singular
    /// value of the 8×2 matrix of all corners' horizontal slips, times the signed `P`.
    WholeDieNorm,
}

impl FrictionLaw {
    pub(crate) const fn name(self) -> &'static str {
        match self {
            FrictionLaw::PerCorner => "per-corner",
            FrictionLaw::WholeDieNorm => "whole-die-norm",
        }
    }
}

/// The ground: a stiff damped spring under every corner, with kinetic friction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Ground {
    /// dyn/cm per corner (k).
    pub stiffness: f64,
    /// s/cm (γ): the vertical force is `k·d·(1 − γ·u_z)`.
    pub damping: f64,
    /// Kinetic friction coefficient (μ).
    pub friction: f64,
    pub friction_law: FrictionLaw,
}

impl Default for Ground {
    fn default() -> Self {
        Params::DEFAULT.ground
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct World {
    /// cm/s², pointing down.
    pub gravity: f64,
}

impl Default for World {
    fn default() -> Self {
        Params::DEFAULT.world
    }
}

/// Which energy the stopping rule compares with the threshold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StopEnergy {
    /// docs/model.md: translational + rotational (with the cube's inertia) + gravitational + elastic.
    #[default]
    RigidBody,
    /// The authors' program: the 8 corners as point masses (½·m·Σ|u_k|²), gravity, and the
    /// ground term ½·Σ d_k·P_k with the damped vertical force.
    PointMasses,
}

impl StopEnergy {
    pub const fn name(self) -> &'static str {
        match self {
            StopEnergy::RigidBody => "rigid-body",
            StopEnergy::PointMasses => "point-masses",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Integrator {
    /// s, the time step Δt.
    pub dt: f64,
    /// A roll ends below this share of the edge-tipping energy.
    pub stop_energy_fraction: f64,
    /// s of simulated time; past it the roll "did not settle".
    pub max_time: f64,
    pub stop_energy: StopEnergy,
}

impl Default for Integrator {
    fn default() -> Self {
        Params::DEFAULT.integrator
    }
}

/// Every model parameter, grouped as in a preset file.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Params {
    pub die: Die,
    pub ground: Ground,
    pub world: World,
    pub integrator: Integrator,
}

impl Default for Params {
    fn default() -> Self {
        Params::DEFAULT
    }
}

impl Params {
    /// The paper's parameters: a 2 cm die of 8 g on a stiff, damped, rough table.
    pub const DEFAULT: Params = Params {
        die: Die {
            half_size: 1.0,
            corner_mass: 1.0,
            extra_corner_mass: [0.0; 8],
        },
        ground: Ground {
            stiffness: 500_000.0,
            damping: 0.005,
            friction: 1.2,
            friction_law: FrictionLaw::PerCorner,
        },
        world: World { gravity: 980.0 },
        integrator: Integrator {
            dt: 0.001,
            stop_energy_fraction: 0.8,
            max_time: 30.0,
            stop_energy: StopEnergy::RigidBody,
        },
    };

    /// Checks every field against its allowed range, in the order a preset lists them; the
    /// first failure is returned.
    pub(crate) fn validate(&self) -> Result<(), ParamError> {
        let (d, g, i) = (&self.die, &self.ground, &self.integrator);
        limits::HALF_SIZE.check(d.half_size)?;
        limits::CORNER_MASS.check(d.corner_mass)?;
        limits::EXTRA_CORNER_MASS.check_components(CORNERS, &d.extra_corner_mass)?;
        limits::STIFFNESS.check(g.stiffness)?;
        limits::DAMPING.check(g.damping)?;
        limits::FRICTION.check(g.friction)?;
        limits::GRAVITY.check(self.world.gravity)?;
        limits::DT.check(i.dt)?;
        limits::STOP_ENERGY_FRACTION.check(i.stop_energy_fraction)?;
        limits::MAX_TIME.check(i.max_time)
    }

    /// g, the whole die: 8 corners and any extra corner masses (adding their zeros leaves
    /// the fair die's `8·m` bit for bit).
    pub fn total_mass(&self) -> f64 {
        self.uniform_mass() + self.die.extra_corner_mass.iter().sum::<f64>()
    }

    /// g, the uniform cube alone (8 corners of `die.corner_mass`).
    pub(crate) fn uniform_mass(&self) -> f64 {
        8.0 * self.die.corner_mass
    }

    /// g·cm², the isotropic moment of inertia of the uniform solid cube about its centre,
    /// `(2a)²/6·M` (a loaded die adds its extra masses to it, [`super::mass`]).
    ///
    /// Written in the authors' order of operations so the default is bitwise 16/3.
    pub(crate) fn inertia(&self) -> f64 {
        let side = 2.0 * self.die.half_size;
        side * side / 6.0 * self.uniform_mass()
    }

    /// erg, the energy to tip over an edge from lying flat: `M·g·a·(√2 − 1)`.
    pub fn edge_energy(&self) -> f64 {
        self.total_mass() * self.world.gravity * self.die.half_size * (std::f64::consts::SQRT_2 - 1.0)
    }

    /// erg, the stopping threshold: a roll ends once its energy is at or below this.
    pub(crate) fn stop_threshold(&self) -> f64 {
        // (fraction · M·g·a) · (√2 − 1): the authors' grouping, bitwise 2597.9474632040528.
        self.integrator.stop_energy_fraction
            * (self.total_mass() * self.world.gravity * self.die.half_size)
            * (std::f64::consts::SQRT_2 - 1.0)
    }

    /// rad/s, the fastest contact mode: a die lying flat rocking on its face, `√(6k/M)`.
    pub(crate) fn rocking_frequency(&self) -> f64 {
        (6.0 * self.ground.stiffness / self.total_mass()).sqrt()
    }

    /// `ω_rock·Δt`: semi-implicit Euler is stable only below 2 (docs/model.md, "Stability").
    pub fn stability_number(&self) -> f64 {
        self.rocking_frequency() * self.integrator.dt
    }

    /// cm, how far each corner sinks when the die rests flat: `M·g/(4k)`.
    pub fn resting_depth(&self) -> f64 {
        self.total_mass() * self.world.gravity / (4.0 * self.ground.stiffness)
    }

    /// The step count at which a roll is declared "did not settle".
    pub fn max_steps(&self) -> u64 {
        let steps = (self.integrator.max_time / self.integrator.dt).ceil();
        // Validated parameters give at most 1.2·10⁷; the clamp bounds unvalidated ones.
        if steps >= 1.0 {
            steps.min(MAX_STEPS_CAP as f64) as u64
        } else {
            1
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::excessive_precision)] // the reference's threshold, digit for digit
    fn defaults_are_the_papers() {
        let p = Params::default();
        assert_eq!(p.inertia(), 16.0 / 3.0);
        assert_eq!(p.stop_threshold(), 2597.9474632040528);
        assert!((p.edge_energy() - 3247.4).abs() < 0.05);
        assert!((p.rocking_frequency() - 612.37).abs() < 0.01);
        assert!((p.resting_depth() - 3.92e-3).abs() < 1e-5);
        assert_eq!(p.max_steps(), 30_000);
        p.validate().unwrap();
    }

    #[test]
    fn out_of_range_names_field_value_and_range() {
        let mut p = Params::default();
        p.ground.friction = 7.5;
        let e = p.validate().unwrap_err();
        assert_eq!(e.key, "ground.friction");
        assert_eq!(
            e.to_string(),
            "`ground.friction` = 7.5 is outside the allowed range 0 to 5"
        );
        p.ground.friction = f64::NAN;
        assert!(p.validate().unwrap_err().to_string().contains("NaN"));
        let mut p = Params::default();
        p.integrator.dt = 0.5;
        assert_eq!(
            p.validate().unwrap_err().to_string(),
            "`integrator.dt` = 0.5 is outside the allowed range 0.00001 to 0.01 s"
        );
    }
}
