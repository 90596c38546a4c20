//! Model parameters (docs/model.md), in CGS units, with their defaults ([`Params::DEFAULT`])
//! and their keys, units and allowed ranges ([`limits`]), each stated here once: the
//! registry of setup values one layer up reads them from here.
//!
//! The structs mirror the sections of a preset file (docs/presets.md), so the preset layer
//! deserialises straight into them; every struct denies unknown keys and fills missing ones
//! with the paper's defaults.
//!
//! Data and their validation only: `Die::kind` says which body a die is, and what follows
//! from that (its mass, inertia, edge energy, stopping rule, resting depth) is the body
//! model's (model.rs).

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
                detail: None,
            })
        }
    }

    /// Checks one number against the range, naming `key` in the error (a component, or a
    /// range's end).
    pub fn check_as(&self, key: &str, value: f64) -> Result<(), ParamError> {
        self.check(value).map_err(|mut e| {
            e.key = key.to_string();
            e
        })
    }

    /// Checks each component, naming it (`initial.velocity.y`, `die.extra_corner_mass.8`).
    pub fn check_components(&self, names: &[&str], values: &[f64]) -> Result<(), ParamError> {
        for (name, &x) in names.iter().zip(values) {
            // The component's name only for an error: a merge checks millions of starts.
            if !(x >= self.min && x <= self.max) {
                self.check_as(&format!("{}.{name}", self.key), x)?;
            }
        }
        Ok(())
    }

    /// Checks a range `[low, high]`: each end inside, the low end not above the high end.
    /// Errors name the end (`random.height[1]`).
    pub fn check_range(&self, range: [f64; 2]) -> Result<(), ParamError> {
        for (i, x) in range.into_iter().enumerate() {
            self.check_as(&format!("{}[{i}]", self.key), x)?;
        }
        if range[0] > range[1] {
            return Err(ParamError {
                key: self.key.to_string(),
                value: range[0],
                limits: *self,
                detail: Some(Box::new(Detail::HighEnd(range[1]))),
            });
        }
        Ok(())
    }
}

/// The names of a vector's components, and of the corners 1..8 of a per-corner value.
pub const XYZ: &[&str; 3] = &["x", "y", "z"];
pub const CORNERS: &[&str; 8] = &["1", "2", "3", "4", "5", "6", "7", "8"];

/// Each numeric parameter's key, unit and allowed range.
pub mod limits {
    use super::Limits;

    const fn limits(key: &'static str, unit: &'static str, min: f64, max: f64) -> Limits {
        Limits { key, unit, min, max }
    }

    pub const HALF_SIZES: Limits = limits("die.half_sizes", "cm", 0.1, 10.0);
    /// Also below the smallest half size ([`super::Params::validate`]).
    pub const CORNER_RADIUS: Limits = limits("die.corner_radius", "cm", 0.0, 10.0);
    /// Also small enough for the pips to fit the flat of every face ([`super::Params::validate`]).
    pub const PIP_DIAMETER: Limits = limits("die.pip_diameter", "cm", 0.0, 10.0);
    /// Also at most the pip's radius: a hole no deeper than a hemisphere.
    pub const PIP_DEPTH: Limits = limits("die.pip_depth", "cm", 0.0, 5.0);
    pub const CORNER_MASS: Limits = limits("die.corner_mass", "g", 0.01, 1000.0);
    pub const EXTRA_CORNER_MASS: Limits = limits("die.extra_corner_mass", "g", 0.0, 1000.0);
    pub const STIFFNESS: Limits = limits("ground.stiffness", "dyn/cm", 100.0, 1e8);
    pub const DAMPING: Limits = limits("ground.damping", "s/cm", 0.0, 0.1);
    pub const FRICTION: Limits = limits("ground.friction", "", 0.0, 5.0);
    /// Also at least `ground.friction`, the kinetic coefficient ([`super::Params::validate`]).
    pub const STATIC_FRICTION: Limits = limits("ground.static_friction", "", 0.0, 5.0);
    /// From 0.2: the clamped spring-dashpot cannot rebound slower than e^(−2) ≈ 0.135 of the
    /// impact while underdamped (docs/model.md, "The spring-friction contact").
    pub const RESTITUTION: Limits = limits("ground.restitution", "", 0.2, 1.0);
    pub const TANGENTIAL_STIFFNESS_RATIO: Limits = limits("ground.tangential_stiffness_ratio", "", 0.05, 2.0);
    /// The same range as `ground.restitution`, for the same reason.
    pub const FACE_RESTITUTION: Limits = limits("ground.face_restitution", "", 0.2, 1.0);
    pub const TABLE_MASS: Limits = limits("ground.table_mass", "g", 0.1, 1e6);
    pub const TABLE_STIFFNESS: Limits = limits("ground.table_stiffness", "dyn/cm", 0.0, 1e9);
    pub const TABLE_DAMPING: Limits = limits("ground.table_damping", "dyn·s/cm", 0.0, 1e7);
    pub const TILT: Limits = limits("ground.tilt", "°", 0.0, 60.0);
    pub const TILT_DIRECTION: Limits = limits("ground.tilt_direction", "°", 0.0, 360.0);
    pub const GRAVITY: Limits = limits("world.gravity", "cm/s²", 10.0, 10000.0);
    pub const DT: Limits = limits("integrator.dt", "s", 1e-5, 1e-2);
    pub const STOP_ENERGY_FRACTION: Limits = limits("integrator.stop_energy_fraction", "", 0.01, 1.0);
    pub const MAX_TIME: Limits = limits("integrator.max_time", "s", 0.01, 120.0);
    /// A polyhedral die's size: how tall it stands on a face (docs/dice.md, "Size and material").
    pub const HEIGHT: Limits = limits("die.height", "cm", 0.1, 20.0);
    /// From cork to tungsten.
    pub const DENSITY: Limits = limits("die.density", "g/cm³", 0.1, 20.0);
    /// A convex die's corners, each coordinate (die frame); also a die at least
    /// `die.height`'s least standing on every face ([`super::Params::validate`]).
    pub const VERTICES: Limits = limits("die.vertices", "cm", -10.0, 10.0);
    /// Every vertex of a polyhedral die rounded alike; also no sphere past a face.
    pub const ROUNDING: Limits = limits("die.rounding", "cm", 0.0, 10.0);
    /// Each vertex's own rounding, added to `die.rounding`.
    pub const VERTEX_ROUNDING: Limits = limits("die.vertex_rounding", "cm", 0.0, 10.0);
    /// The face whose vertices are worn rounder; any number on the die's faces.
    pub const WORN_FACE: Limits = limits("die.worn_face", "", 0.0, 255.0);
    /// How much rounder the worn face's vertices are: uneven rounding as one number.
    pub const WORN_ROUNDING: Limits = limits("die.worn_rounding", "cm", 0.0, 10.0);
    /// An air bubble's radius (0: none); also inside every face.
    pub const BUBBLE_RADIUS: Limits = limits("die.bubble_radius", "cm", 0.0, 10.0);
    pub const BUBBLE_TOWARD: Limits = limits("die.bubble_toward", "", 0.0, 255.0);
    /// How far off the centre of mass the bubble lies: the bubble's size as a flaw.
    pub const BUBBLE_OFFSET: Limits = limits("die.bubble_offset", "cm", 0.0, 10.0);
    /// A point mass set into the die (0: none).
    pub const POINT_MASS: Limits = limits("die.point_mass", "g", 0.0, 1000.0);
    pub const POINT_MASS_TOWARD: Limits = limits("die.point_mass_toward", "", 0.0, 255.0);
    pub const POINT_MASS_OFFSET: Limits = limits("die.point_mass_offset", "cm", 0.0, 10.0);
    /// The face shaved down.
    pub const SHAVE_FACE: Limits = limits("die.shave_face", "", 0.0, 255.0);
    /// How deep it is shaved (0: not at all): a plane cut parallel to the face.
    pub const SHAVE_DEPTH: Limits = limits("die.shave_depth", "cm", 0.0, 10.0);
}

/// A value outside its allowed range: names the field, the value and the range.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamError {
    pub key: String,
    pub value: f64,
    pub limits: Limits,
    /// More than a value outside its range (boxed: errors travel far and stay small).
    pub detail: Option<Box<Detail>>,
}

/// What else a [`ParamError`] says.
#[derive(Debug, Clone, PartialEq)]
pub enum Detail {
    /// A range `[low, high]` given the wrong way round: the error's value is the low end,
    /// this the high end below it.
    HighEnd(f64),
    /// A value refused by a rule that ties it to others (a corner radius against the half
    /// sizes): the rule and its bound in words, said instead of the range.
    Refused(String),
}

impl ParamError {
    /// `key` = `value` refused for `why` (the rule and the bound it sets).
    pub(crate) fn refused(limits: Limits, value: f64, why: String) -> ParamError {
        ParamError {
            key: limits.key.to_string(),
            value,
            limits,
            detail: Some(Box::new(Detail::Refused(why))),
        }
    }
}

/// cm, rounded to 10⁻⁹ cm: a bound computed from others reads 0.2, not 0.19999999999999996.
fn rounded_to_nanometres(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}

/// A number as a person reads it, exactly: the shortest digits that read back as `value`,
/// in e-notation from 10¹⁵ up and below 10⁻⁶ (1e308 rather than its 309 digits, 1e-200
/// rather than 200 zeros), plain between. A parameter error's value and bounds use it, and
/// the layers above re-export it (`dicesim_setup::number::fmt_exact`).
pub fn fmt_number(value: f64) -> String {
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
        if let Some(Detail::Refused(why)) = self.detail.as_deref() {
            return if self.value.is_nan() {
                write!(f, "`{}`: {why}", self.key)
            } else {
                write!(f, "`{}` = {}: {why}", self.key, fmt_number(self.value))
            };
        }
        if let Some(&Detail::HighEnd(high)) = self.detail.as_deref() {
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

/// The friction-law choice's key, for its refusal.
pub(crate) const FRICTION_LAW_KEY: Limits = Limits {
    key: "ground.friction_law",
    unit: "",
    min: 0.0,
    max: 0.0,
};

/// The stop-energy choice's key, for its refusal.
const STOP_ENERGY_KEY: Limits = Limits {
    key: "integrator.stop_energy",
    unit: "",
    min: 0.0,
    max: 0.0,
};

/// No roll runs longer than this many steps, whatever its parameters (under a second).
pub const MAX_STEPS_CAP: u64 = 12_000_000;

/// Which solid a die is: the box (a cuboid of 8 corners, the paper's die and every die built
/// on it) or one of the regular polyhedral dice (docs/dice.md), each a body of its vertices.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub enum Solid {
    /// The cuboid of `die.half_sizes`: what a file without `die.kind` describes.
    #[default]
    #[serde(rename = "box")]
    Box,
    #[serde(rename = "d4")]
    D4,
    #[serde(rename = "d8")]
    D8,
    #[serde(rename = "d10")]
    D10,
    /// The d10's shape labelled 00, 10, …, 90.
    #[serde(rename = "d%")]
    Percentile,
    #[serde(rename = "d12")]
    D12,
    #[serde(rename = "d20")]
    D20,
    /// Any convex die, given by its corners (`die.vertices`): the hull's faces numbered 1 to
    /// `F` (docs/dice.md, "A convex die of its corners").
    #[serde(rename = "convex")]
    Convex,
}

impl Solid {
    pub const ALL: [Solid; 8] = [
        Solid::Box,
        Solid::D4,
        Solid::D8,
        Solid::D10,
        Solid::Percentile,
        Solid::D12,
        Solid::D20,
        Solid::Convex,
    ];

    /// Every name, as [`Solid::name`] gives them, in [`Solid::ALL`]'s order.
    pub const NAMES: [&'static str; 8] = ["box", "d4", "d8", "d10", "d%", "d12", "d20", "convex"];

    /// The name a preset gives it: `box`, or the players' `d4` … `d20`, `d%`.
    pub const fn name(self) -> &'static str {
        Solid::NAMES[self as usize]
    }

    /// The solid named `name` ([`Solid::name`]).
    pub fn from_name(name: &str) -> Option<Solid> {
        Solid::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The solid whose numbers are `numbers` ([`Solid::face_numbers`]): each solid's list is
    /// its own, so a tally that knows only its list knows its die.
    pub fn showing(numbers: &[u8]) -> Option<Solid> {
        Solid::ALL.into_iter().find(|s| s.face_numbers() == numbers)
    }

    /// The number on the face opposite the one that shows `face`, as real dice are numbered
    /// (docs/dice.md): the two sum to the lowest and the highest number together (7 on the
    /// box, N + 1 on the d8 to the d20, 9 on the d10, 90 on the d%); none on the d4, each of
    /// whose faces lies opposite a vertex.
    pub fn opposite_number(self, face: u8) -> Option<u8> {
        let numbers = self.face_numbers();
        match self {
            Solid::D4 | Solid::Convex => None,
            _ => (numbers[0] + numbers[numbers.len() - 1]).checked_sub(face),
        }
    }

    /// The numbers a roll of it can show, in the order its tables list them; none for a
    /// convex die, whose numbers its corners give ([`Die::face_numbers`]).
    pub const fn face_numbers(self) -> &'static [u8] {
        match self {
            Solid::Box => &[1, 2, 3, 4, 5, 6],
            Solid::D4 => &[1, 2, 3, 4],
            Solid::D8 => &[1, 2, 3, 4, 5, 6, 7, 8],
            Solid::D10 => &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9],
            Solid::Percentile => &[0, 10, 20, 30, 40, 50, 60, 70, 80, 90],
            Solid::D12 => &[1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12],
            Solid::D20 => &[
                1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
            ],
            Solid::Convex => &[],
        }
    }
}

/// The die's keys read by some solids only: the box's shape and masses, a regular die's
/// size, a polyhedral die's material, a convex die's corners and a polyhedral die's flaws
/// ([`Die::reads`]).
const BOX_KEYS: [Limits; 6] = [
    limits::HALF_SIZES,
    limits::CORNER_RADIUS,
    limits::PIP_DIAMETER,
    limits::PIP_DEPTH,
    limits::CORNER_MASS,
    limits::EXTRA_CORNER_MASS,
];
const POLYHEDRON_KEYS: [Limits; 2] = [limits::HEIGHT, limits::DENSITY];
/// The flaws that make a polyhedral die unfair, each with one number that sizes it
/// (docs/dice.md, "Flaws"): the rest place it.
pub const FLAW_KEYS: [Limits; 12] = [
    limits::ROUNDING,
    limits::VERTEX_ROUNDING,
    limits::WORN_FACE,
    limits::WORN_ROUNDING,
    limits::BUBBLE_RADIUS,
    limits::BUBBLE_TOWARD,
    limits::BUBBLE_OFFSET,
    limits::POINT_MASS,
    limits::POINT_MASS_TOWARD,
    limits::POINT_MASS_OFFSET,
    limits::SHAVE_FACE,
    limits::SHAVE_DEPTH,
];

/// The most faces a body may number (a d20's): the most numbers a die shows.
pub const MAX_FACES: usize = 20;

/// The most corners a convex die may have: the largest body the engines carry (the d12's 20
/// points; a die of fewer rolls as the next body up, docs/dice.md "A convex die of its
/// corners").
pub const MAX_DIE_VERTICES: usize = 20;

/// Up to [`MAX_DIE_VERTICES`] values, one per vertex, held in place: `Params` is `Copy` and
/// compared per roll, so a list is a fixed array and its length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PerVertex<T> {
    /// The values, then `fill` up to the end (so equal lists compare equal).
    values: [T; MAX_DIE_VERTICES],
    len: u8,
}

impl<T: Copy> PerVertex<T> {
    /// No values.
    pub const fn empty(fill: T) -> PerVertex<T> {
        PerVertex {
            values: [fill; MAX_DIE_VERTICES],
            len: 0,
        }
    }

    /// `values`, or `None` for more than [`MAX_DIE_VERTICES`].
    pub fn new(values: &[T], fill: T) -> Option<PerVertex<T>> {
        let mut list = PerVertex::empty(fill);
        list.values.get_mut(..values.len())?.copy_from_slice(values);
        list.len = values.len() as u8;
        Some(list)
    }

    pub fn as_slice(&self) -> &[T] {
        &self.values[..self.len as usize]
    }

    pub fn len(&self) -> usize {
        self.len as usize
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// A convex die's corners (cm, die frame), with the number of faces their hull has (0 when
/// they make no solid: [`Params::validate`] says why), counted once here so that the numbers
/// a record may show are known without a hull per record.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vertices {
    pub(crate) points: PerVertex<[f64; 3]>,
    /// Set by `Vertices::new` (polyhedron/keys.rs, which has the hull).
    pub(crate) faces: u8,
}

/// Why a list of corners cannot be held: more than [`MAX_DIE_VERTICES`].
pub const TOO_MANY_VERTICES: &str =
    "a convex die has at most 20 vertices (`die.vertices`): the largest body the engines carry";

impl Vertices {
    /// No corners: the value of every die but a convex one.
    pub const NONE: Vertices = Vertices {
        points: PerVertex::empty([0.0; 3]),
        faces: 0,
    };

    /// cm, die frame.
    pub fn points(&self) -> &[[f64; 3]] {
        self.points.as_slice()
    }

    /// The faces of their hull (0: no solid).
    pub fn face_count(&self) -> usize {
        self.faces as usize
    }
}

/// A polyhedral die's flaws as a preset states them, in the die's own words (docs/dice.md,
/// "Flaws"): each sized by one number (0: none) and placed by a face's number. All zero is a
/// sharp, uniform die.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DieFlaws {
    /// cm, every vertex rounded by this.
    pub rounding: f64,
    /// cm, each vertex's own rounding on top of `rounding` (none given: 0 each), in the order
    /// of the die's vertices (docs/dice.md's tables; a convex die's as listed).
    pub vertex_rounding: PerVertex<f64>,
    /// The number of the face whose vertices are worn rounder by `worn_rounding`.
    pub worn_face: Option<u8>,
    /// cm, added to the rounding of each vertex of `worn_face`.
    pub worn_rounding: f64,
    /// cm, an air bubble's radius (0: none).
    pub bubble_radius: f64,
    /// The number of the face the bubble lies toward.
    pub bubble_toward: Option<u8>,
    /// cm, from the centre of mass of the sharp, uniform die along `bubble_toward`'s outward
    /// normal.
    pub bubble_offset: f64,
    /// g, a point mass set into the die (0: none).
    pub point_mass: f64,
    pub point_mass_toward: Option<u8>,
    /// cm, as `bubble_offset`.
    pub point_mass_offset: f64,
    /// The number of the face shaved down.
    pub shave_face: Option<u8>,
    /// cm, how much thinner the die is across that face: a plane cut parallel to it.
    pub shave_depth: f64,
}

impl DieFlaws {
    /// A sharp, uniform die.
    pub const NONE: DieFlaws = DieFlaws {
        rounding: 0.0,
        vertex_rounding: PerVertex::empty(0.0),
        worn_face: None,
        worn_rounding: 0.0,
        bubble_radius: 0.0,
        bubble_toward: None,
        bubble_offset: 0.0,
        point_mass: 0.0,
        point_mass_toward: None,
        point_mass_offset: 0.0,
        shave_face: None,
        shave_depth: 0.0,
    };

    /// Whether the flaw key `key` holds other than its default (none, 0).
    pub fn states(&self, key: &str) -> bool {
        let d = &DieFlaws::NONE;
        match key {
            "die.rounding" => self.rounding != d.rounding,
            "die.vertex_rounding" => !self.vertex_rounding.is_empty(),
            "die.worn_face" => self.worn_face.is_some(),
            "die.worn_rounding" => self.worn_rounding != d.worn_rounding,
            "die.bubble_radius" => self.bubble_radius != d.bubble_radius,
            "die.bubble_toward" => self.bubble_toward.is_some(),
            "die.bubble_offset" => self.bubble_offset != d.bubble_offset,
            "die.point_mass" => self.point_mass != d.point_mass,
            "die.point_mass_toward" => self.point_mass_toward.is_some(),
            "die.point_mass_offset" => self.point_mass_offset != d.point_mass_offset,
            "die.shave_face" => self.shave_face.is_some(),
            "die.shave_depth" => self.shave_depth != d.shave_depth,
            _ => false,
        }
    }

    /// Whether any flaw key is given.
    pub fn any(&self) -> bool {
        *self != DieFlaws::NONE
    }

    /// The value of a flaw key as a number (a face's number; NaN for a list or none), for
    /// its refusal.
    fn value(&self, key: &str) -> f64 {
        let face = |f: Option<u8>| f.map_or(f64::NAN, f64::from);
        match key {
            "die.rounding" => self.rounding,
            "die.worn_face" => face(self.worn_face),
            "die.worn_rounding" => self.worn_rounding,
            "die.bubble_radius" => self.bubble_radius,
            "die.bubble_toward" => face(self.bubble_toward),
            "die.bubble_offset" => self.bubble_offset,
            "die.point_mass" => self.point_mass,
            "die.point_mass_toward" => face(self.point_mass_toward),
            "die.point_mass_offset" => self.point_mass_offset,
            "die.shave_face" => face(self.shave_face),
            "die.shave_depth" => self.shave_depth,
            _ => f64::NAN,
        }
    }
}

/// The die's kind's key, for its refusals.
pub const KIND_KEY: Limits = Limits {
    key: "die.kind",
    unit: "",
    min: 0.0,
    max: 0.0,
};

/// The die: a cuboid with rounded corners and drilled pips (the paper's: a sharp cube of
/// 8 corner point masses, without pips), docs/model.md "Real dice"; or, with `kind`, a
/// regular polyhedral die of a height and a density (docs/dice.md).
///
/// A file states the size as `half_sizes = [ax, ay, az]` or, for a cube, the older
/// `half_size = a`; a cube is written back the older way, so the paper's die reads and
/// serialises as it always has.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "DieKeys", into = "DieKeys")]
pub struct Die {
    /// cm, half the side along the body axes x (faces 1 and 6), y (2 and 5), z (3 and 4).
    pub half_sizes: [f64; 3],
    /// cm, the radius of the rounded corners and edges (0: sharp, the paper's die).
    pub corner_radius: f64,
    /// cm, the diameter of each pip's opening in its face.
    pub pip_diameter: f64,
    /// cm, how deep each pip is drilled: a spherical cap (0: no pips, the paper's die).
    pub pip_depth: f64,
    /// g, each of the 8 corners: `8·corner_mass` is the undrilled body's mass.
    pub corner_mass: f64,
    /// g, point masses added at corners 1..8 (a loaded die, docs/model.md "Loaded dice");
    /// all zero is the paper's fair die.
    pub extra_corner_mass: [f64; 8],
    /// The solid: the box of the keys above, or a polyhedral die of the two below.
    pub kind: Solid,
    /// cm, how tall a polyhedral die stands on a face: across its faces, from a face to the
    /// top vertex on the d4 (docs/dice.md, "Size and material").
    pub height: f64,
    /// g/cm³, a polyhedral die's uniform material.
    pub density: f64,
    /// cm, a convex die's corners (die frame); none for every other die.
    pub vertices: Vertices,
    /// A polyhedral die's flaws (all none: sharp and uniform).
    pub flaws: DieFlaws,
}

impl Die {
    /// Whether any corner carries extra mass.
    pub fn is_loaded(&self) -> bool {
        self.extra_corner_mass.iter().any(|&m| m != 0.0)
    }

    /// Whether it has drilled pips (both a depth and a diameter).
    pub fn is_drilled(&self) -> bool {
        self.pip_depth > 0.0 && self.pip_diameter > 0.0
    }

    /// Which body this die is: the one place that tells the paper's cube from any other
    /// body (docs/model.md, "Real dice"). A sharp cube without pips keeps the paper's
    /// arithmetic bit for bit, its extra corner masses (if any) added as point masses; a
    /// rounded, drilled or not cubic die is a general body, loaded or not.
    pub(crate) fn kind(&self) -> BodyKind {
        let [x, y, z] = self.half_sizes;
        let cube = x == y && y == z && self.corner_radius == 0.0 && !self.is_drilled();
        match (cube, self.is_loaded()) {
            (true, false) => BodyKind::PaperCube,
            (true, true) => BodyKind::LoadedCube,
            (false, _) => BodyKind::Shaped,
        }
    }

    /// The numbers a roll of this die can show, in the order its tables list them: what a
    /// tally counts and its χ² has one degree of freedom fewer than. A box shows 1 to 6, a
    /// d`N` 1 to `N`, the d10 0 to 9 and the d% 0, 10, …, 90, a convex die of `F` faces 1 to
    /// `F` (none while its corners make no solid).
    pub fn face_numbers(&self) -> &'static [u8] {
        match self.kind {
            Solid::Convex => &Solid::D20.face_numbers()[..self.vertices.face_count().min(MAX_FACES)],
            kind => kind.face_numbers(),
        }
    }

    /// Whether it is a polyhedral die (not the box).
    pub fn is_polyhedral(&self) -> bool {
        self.kind != Solid::Box
    }

    /// The keys this die does not read.
    fn unread(&self) -> Vec<Limits> {
        match self.kind {
            Solid::Box => POLYHEDRON_KEYS
                .iter()
                .chain(&FLAW_KEYS)
                .chain([&limits::VERTICES])
                .copied()
                .collect(),
            Solid::Convex => BOX_KEYS.iter().chain([&limits::HEIGHT]).copied().collect(),
            _ => BOX_KEYS.iter().chain([&limits::VERTICES]).copied().collect(),
        }
    }

    /// Whether this die reads `key` (a dotted preset key): the box its shape and masses, a
    /// regular polyhedral die its height, density and flaws, a convex die its vertices,
    /// density and flaws; every die its kind.
    pub fn reads(&self, key: &str) -> bool {
        !self
            .unread()
            .iter()
            .any(|l| l.key == key || (key == "die.half_size" && l.key == "die.half_sizes"))
    }

    /// Whether a file describing this die states `key`: every key it reads, but the box's
    /// kind, which a file without `die.kind` is, and a flaw it does not have.
    pub fn states(&self, key: &str) -> bool {
        let flaw = FLAW_KEYS.iter().any(|l| l.key == key);
        self.reads(key) && (key != KIND_KEY.key || self.is_polyhedral()) && (!flaw || self.flaws.states(key))
    }

    /// The refusal of `key` when this die does not read it: what a file or `--set` says when
    /// the key is given, whatever its value.
    pub fn refusal(&self, key: &str) -> Option<ParamError> {
        if self.reads(key) {
            return None;
        }
        let limits = self
            .unread()
            .into_iter()
            .find(|l| l.key == key || (key == "die.half_size" && l.key == "die.half_sizes"))?;
        Some(ParamError::refused(
            limits,
            self.flaws.value(limits.key),
            self.why_unread(limits.key),
        ))
    }

    /// Why this die does not read `key`, and the way out.
    fn why_unread(&self, key: &str) -> String {
        let flaw = FLAW_KEYS.iter().any(|l| l.key == key);
        match self.kind {
            Solid::Box if flaw => format!(
                "`{key}` is a polyhedral die's flaw; the box has its own: extra mass at a corner \
                 (`die.extra_corner_mass`, g) and rounded corners (`die.corner_radius`, cm) (give \
                 `die.kind`, e.g. \"d20\", for a polyhedral die)"
            ),
            Solid::Box if key == limits::VERTICES.key => "`die.vertices` are a convex die's corners (with \
                 `die.kind = \"convex\"`); the box is sized by `die.half_sizes`"
                .to_string(),
            Solid::Box => format!(
                "`{key}` sizes a polyhedral die; the box is sized by `die.half_sizes` and weighed \
                 by `die.corner_mass` (give `die.kind`, e.g. \"d20\", for a polyhedral die)"
            ),
            Solid::Convex if key == limits::HEIGHT.key => "a convex die's size is its corners, \
                 `die.vertices` (cm); `die.height` sizes a regular die (d4 to d20)"
                .to_string(),
            Solid::Convex => format!(
                "a convex die is given by its corners, `die.vertices` (cm), and made of \
                 `die.density` (g/cm³); `{key}` describes the box only (leave out `die.kind` for the box)"
            ),
            kind if key == limits::VERTICES.key => format!(
                "a {} is a regular die sized by `die.height` (cm); `die.vertices` are a convex \
                 die's corners (with `die.kind = \"convex\"`)",
                kind.name()
            ),
            kind => format!(
                "a {} is a polyhedral die, sized by `die.height` (cm) and made of `die.density` \
                 (g/cm³); `{key}` describes the box only (leave out `die.kind` for the box)",
                kind.name()
            ),
        }
    }

    /// The first key this die does not read that differs from its default.
    fn check_unread(&self) -> Result<(), ParamError> {
        let d = &Params::DEFAULT.die;
        let differs = |key: &str| match key {
            "die.half_sizes" => self.half_sizes != d.half_sizes,
            "die.corner_radius" => self.corner_radius != d.corner_radius,
            "die.pip_diameter" => self.pip_diameter != d.pip_diameter,
            "die.pip_depth" => self.pip_depth != d.pip_depth,
            "die.corner_mass" => self.corner_mass != d.corner_mass,
            "die.extra_corner_mass" => self.extra_corner_mass != d.extra_corner_mass,
            "die.height" => self.height != d.height,
            "die.density" => self.density != d.density,
            "die.vertices" => self.vertices != d.vertices,
            flaw => self.flaws.states(flaw),
        };
        let keys = BOX_KEYS
            .iter()
            .chain(&POLYHEDRON_KEYS)
            .chain([&limits::VERTICES])
            .chain(&FLAW_KEYS);
        for limits in keys {
            if differs(limits.key)
                && let Some(refused) = self.refusal(limits.key)
            {
                return Err(refused);
            }
        }
        Ok(())
    }

    /// A polyhedral die's vertices and flaws each in its range (their sizes against the solid
    /// are the body's to check, `Params::check_polyhedral_die`).
    fn check_ranges(&self) -> Result<(), ParamError> {
        for (k, point) in self.vertices.points().iter().enumerate() {
            for x in point {
                limits::VERTICES.check_as(&format!("{}.{}", limits::VERTICES.key, k + 1), *x)?;
            }
        }
        let f = &self.flaws;
        for (limits, value) in [
            (limits::ROUNDING, f.rounding),
            (limits::WORN_ROUNDING, f.worn_rounding),
            (limits::BUBBLE_RADIUS, f.bubble_radius),
            (limits::BUBBLE_OFFSET, f.bubble_offset),
            (limits::POINT_MASS, f.point_mass),
            (limits::POINT_MASS_OFFSET, f.point_mass_offset),
            (limits::SHAVE_DEPTH, f.shave_depth),
        ] {
            limits.check(value)?;
        }
        for (k, &r) in f.vertex_rounding.as_slice().iter().enumerate() {
            limits::VERTEX_ROUNDING.check_as(&format!("{}.{}", limits::VERTEX_ROUNDING.key, k + 1), r)?;
        }
        Ok(())
    }

    /// cm, the cube's half size `a` (the first half size of any other body).
    pub fn half_size(&self) -> f64 {
        self.half_sizes[0]
    }

    /// cm, the smallest half size.
    pub fn smallest_half_size(&self) -> f64 {
        self.half_sizes.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// cm, the largest half size.
    pub fn largest_half_size(&self) -> f64 {
        self.half_sizes.iter().copied().fold(0.0, f64::max)
    }
}

/// The three bodies a `[die]` table can describe ([`Die::kind`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum BodyKind {
    /// The paper's sharp cube of 8 equal corner masses, without pips.
    PaperCube,
    /// The paper's cube with extra point masses at some corners (docs/model.md, "Loaded dice").
    LoadedCube,
    /// Any other die: rounded corners, drilled pips or unequal half sizes, loaded or not.
    Shaped,
}

/// A `[die]` table as a file states it: the size one of two ways, the new keys optional.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct DieKeys {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    half_size: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    half_sizes: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "is_zero")]
    corner_radius: f64,
    #[serde(default, skip_serializing_if = "is_zero")]
    pip_diameter: f64,
    #[serde(default, skip_serializing_if = "is_zero")]
    pip_depth: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    corner_mass: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    extra_corner_mass: Option<[f64; 8]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    kind: Option<Solid>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    height: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    density: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    vertices: Option<Vec<[f64; 3]>>,
    #[serde(default, skip_serializing_if = "is_zero")]
    rounding: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    vertex_rounding: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    worn_face: Option<u8>,
    #[serde(default, skip_serializing_if = "is_zero")]
    worn_rounding: f64,
    #[serde(default, skip_serializing_if = "is_zero")]
    bubble_radius: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bubble_toward: Option<u8>,
    #[serde(default, skip_serializing_if = "is_zero")]
    bubble_offset: f64,
    #[serde(default, skip_serializing_if = "is_zero")]
    point_mass: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    point_mass_toward: Option<u8>,
    #[serde(default, skip_serializing_if = "is_zero")]
    point_mass_offset: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    shave_face: Option<u8>,
    #[serde(default, skip_serializing_if = "is_zero")]
    shave_depth: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// Why a `[die]` table states its size twice.
pub const SIZE_TWICE: &str =
    "give the size once: `half_sizes` (cm, three half sizes) or `half_size` (cm, a cube), not both";

impl TryFrom<DieKeys> for Die {
    type Error = &'static str;

    fn try_from(k: DieKeys) -> Result<Die, Self::Error> {
        let half_sizes = match (k.half_size, k.half_sizes) {
            (Some(_), Some(_)) => return Err(SIZE_TWICE),
            (Some(a), None) => [a; 3],
            (None, Some(sizes)) => sizes,
            (None, None) => Params::DEFAULT.die.half_sizes,
        };
        let d = &Params::DEFAULT.die;
        Ok(Die {
            half_sizes,
            corner_radius: k.corner_radius,
            pip_diameter: k.pip_diameter,
            pip_depth: k.pip_depth,
            corner_mass: k.corner_mass.unwrap_or(d.corner_mass),
            extra_corner_mass: k.extra_corner_mass.unwrap_or(d.extra_corner_mass),
            kind: k.kind.unwrap_or(d.kind),
            height: k.height.unwrap_or(d.height),
            density: k.density.unwrap_or(d.density),
            vertices: match &k.vertices {
                Some(points) => Vertices::new(points)?,
                None => Vertices::NONE,
            },
            flaws: DieFlaws {
                rounding: k.rounding,
                vertex_rounding: match &k.vertex_rounding {
                    Some(radii) => PerVertex::new(radii, 0.0).ok_or(TOO_MANY_RADII)?,
                    None => PerVertex::empty(0.0),
                },
                worn_face: k.worn_face,
                worn_rounding: k.worn_rounding,
                bubble_radius: k.bubble_radius,
                bubble_toward: k.bubble_toward,
                bubble_offset: k.bubble_offset,
                point_mass: k.point_mass,
                point_mass_toward: k.point_mass_toward,
                point_mass_offset: k.point_mass_offset,
                shave_face: k.shave_face,
                shave_depth: k.shave_depth,
            },
        })
    }
}

/// Why a list of radii cannot be held: more than [`MAX_DIE_VERTICES`].
const TOO_MANY_RADII: &str =
    "at most 20 radii in `die.vertex_rounding`: one per vertex, and a die has at most 20";

impl From<Die> for DieKeys {
    /// Equal half sizes are written as the one `half_size`, and zero radius and pips not at
    /// all: the paper's die serialises byte for byte as before these keys existed. A box is
    /// written without its kind, height and density; a polyhedral die with only those (a
    /// convex die with its vertices for its height) and the flaws it has.
    fn from(d: Die) -> DieKeys {
        let [x, y, z] = d.half_sizes;
        let cube = x == y && y == z;
        let box_ = !d.is_polyhedral();
        let f = &d.flaws;
        DieKeys {
            half_size: (box_ && cube).then_some(x),
            half_sizes: (box_ && !cube).then_some(d.half_sizes),
            corner_radius: if box_ { d.corner_radius } else { 0.0 },
            pip_diameter: if box_ { d.pip_diameter } else { 0.0 },
            pip_depth: if box_ { d.pip_depth } else { 0.0 },
            corner_mass: box_.then_some(d.corner_mass),
            extra_corner_mass: box_.then_some(d.extra_corner_mass),
            kind: (!box_).then_some(d.kind),
            height: (!box_ && d.kind != Solid::Convex).then_some(d.height),
            density: (!box_).then_some(d.density),
            vertices: (d.kind == Solid::Convex).then(|| d.vertices.points().to_vec()),
            rounding: f.rounding,
            vertex_rounding: (!f.vertex_rounding.is_empty()).then(|| f.vertex_rounding.as_slice().to_vec()),
            worn_face: f.worn_face,
            worn_rounding: f.worn_rounding,
            bubble_radius: f.bubble_radius,
            bubble_toward: f.bubble_toward,
            bubble_offset: f.bubble_offset,
            point_mass: f.point_mass,
            point_mass_toward: f.point_mass_toward,
            point_mass_offset: f.point_mass_offset,
            shave_face: f.shave_face,
            shave_depth: f.shave_depth,
        }
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
    pub const fn name(self) -> &'static str {
        match self {
            FrictionLaw::PerCorner => "per-corner",
            FrictionLaw::WholeDieNorm => "whole-die-norm",
        }
    }
}

/// Which contact law the ground applies at every contact point (docs/model.md, "Forces on a
/// corner" and "The spring-friction contact").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactLaw {
    /// The paper's eq. 13–15: a damped spring `k·d·(1 − γ·u_z)` and kinetic friction only.
    #[default]
    Paper,
    /// A linear spring-dashpot whose damping gives the restitution `e`, a tangential spring
    /// on each point's slip since it touched, capped by static friction and sliding at the
    /// kinetic (Cundall–Strack), on a table that may be tilted.
    SpringFriction,
}

impl ContactLaw {
    pub const fn name(self) -> &'static str {
        match self {
            ContactLaw::Paper => "paper",
            ContactLaw::SpringFriction => "spring-friction",
        }
    }
}

/// The ground: a stiff spring under every contact point, with friction, by the contact law.
///
/// `stiffness` and `friction` are read by both laws; `damping` and `friction_law` by the
/// paper's only, the rest by the spring-friction law only ([`Ground::reads`]). A key a law
/// does not read must keep its default: [`Params::validate`] refuses any other value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Ground {
    /// dyn/cm per corner (k).
    pub stiffness: f64,
    /// s/cm (γ): the vertical force is `k·d·(1 − γ·u_z)`.
    pub damping: f64,
    /// Kinetic friction coefficient (μ; μ_k under the spring-friction law).
    pub friction: f64,
    pub friction_law: FrictionLaw,
    /// The contact law; the keys below are the spring-friction law's (written only when they
    /// differ from their defaults, so the paper's ground serialises as it always has).
    #[serde(skip_serializing_if = "is_paper")]
    pub contact: ContactLaw,
    /// Static friction coefficient μ_s: a stuck point's tangential force may reach μ_s·N.
    #[serde(skip_serializing_if = "is_default_static_friction")]
    pub static_friction: f64,
    /// Coefficient of restitution e of a flat drop, constant over impact speed.
    #[serde(skip_serializing_if = "is_default_restitution")]
    pub restitution: f64,
    /// k_t/k: the tangential spring's stiffness over the normal one (2/7: a solid ball's
    /// tangential and normal periods are equal); the tangential damping is c·k_t/k.
    #[serde(skip_serializing_if = "is_default_tangential_stiffness_ratio")]
    pub tangential_stiffness_ratio: f64,
    /// e_f, the restitution of a point that strikes while the body leans on the table (another
    /// of its points has touched for at least a flat drop's contact time): a fall onto a face
    /// over an edge, not a landing from flight (docs/model.md, "A loss that tells a face fall
    /// from a bounce in flight"). `None`: `restitution`, the law as it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub face_restitution: Option<f64>,
    /// g, the mass m_T of a compliant table's top, which moves along the normal under every
    /// point of the body at once (docs/model.md, "A compliant table"). `None`: a rigid table,
    /// the law as it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub table_mass: Option<f64>,
    /// dyn/cm, the spring K_T holding the table top to the floor (`None`: 0, a free top).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub table_stiffness: Option<f64>,
    /// dyn·s/cm, the table top's own damper C_T (`None`: 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub table_damping: Option<f64>,
    /// Degrees, the table's slope (gravity tilted in the table's frame).
    #[serde(skip_serializing_if = "is_zero")]
    pub tilt: f64,
    /// Degrees from +x toward +y: the direction the table slopes down.
    #[serde(skip_serializing_if = "is_zero")]
    pub tilt_direction: f64,
}

fn is_paper(law: &ContactLaw) -> bool {
    *law == ContactLaw::Paper
}

fn is_default_static_friction(x: &f64) -> bool {
    *x == Params::DEFAULT.ground.static_friction
}

fn is_default_restitution(x: &f64) -> bool {
    *x == Params::DEFAULT.ground.restitution
}

fn is_default_tangential_stiffness_ratio(x: &f64) -> bool {
    *x == Params::DEFAULT.ground.tangential_stiffness_ratio
}

/// A ground key that only one contact law reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GroundKey {
    Damping,
    FrictionLaw,
    StaticFriction,
    Restitution,
    TangentialStiffnessRatio,
    FaceRestitution,
    TableMass,
    TableStiffness,
    TableDamping,
    Tilt,
    TiltDirection,
}

impl GroundKey {
    pub const ALL: [GroundKey; 11] = [
        GroundKey::Damping,
        GroundKey::FrictionLaw,
        GroundKey::StaticFriction,
        GroundKey::Restitution,
        GroundKey::TangentialStiffnessRatio,
        GroundKey::FaceRestitution,
        GroundKey::TableMass,
        GroundKey::TableStiffness,
        GroundKey::TableDamping,
        GroundKey::Tilt,
        GroundKey::TiltDirection,
    ];

    /// The dotted preset key.
    pub const fn key(self) -> &'static str {
        match self {
            GroundKey::Damping => "ground.damping",
            GroundKey::FrictionLaw => "ground.friction_law",
            GroundKey::StaticFriction => "ground.static_friction",
            GroundKey::Restitution => "ground.restitution",
            GroundKey::TangentialStiffnessRatio => "ground.tangential_stiffness_ratio",
            GroundKey::FaceRestitution => "ground.face_restitution",
            GroundKey::TableMass => "ground.table_mass",
            GroundKey::TableStiffness => "ground.table_stiffness",
            GroundKey::TableDamping => "ground.table_damping",
            GroundKey::Tilt => "ground.tilt",
            GroundKey::TiltDirection => "ground.tilt_direction",
        }
    }

    /// The one law that reads this key.
    pub const fn law(self) -> ContactLaw {
        match self {
            GroundKey::Damping | GroundKey::FrictionLaw => ContactLaw::Paper,
            _ => ContactLaw::SpringFriction,
        }
    }

    /// The key of `key`, if only one law reads it.
    pub fn named(key: &str) -> Option<GroundKey> {
        GroundKey::ALL.into_iter().find(|k| k.key() == key)
    }

    /// Why `law` refuses this key: what the law does instead of reading it.
    pub fn why_unread(self, law: ContactLaw) -> String {
        let instead = match self {
            GroundKey::Damping => "its normal damping comes from `ground.restitution`",
            GroundKey::FrictionLaw => "its friction is the tangential spring capped by static friction",
            GroundKey::StaticFriction => "it has kinetic friction only",
            GroundKey::Restitution => {
                "its restitution follows from `ground.damping` and falls with impact speed"
            }
            GroundKey::TangentialStiffnessRatio => "it has no tangential spring",
            GroundKey::FaceRestitution => "its damping is the same at every impact",
            GroundKey::TableMass | GroundKey::TableStiffness | GroundKey::TableDamping => {
                "its table is rigid"
            }
            GroundKey::Tilt | GroundKey::TiltDirection => {
                "its table is level, as the authors' program had it"
            }
        };
        format!(
            "the \"{}\" contact law does not read it ({instead}); it is read under `ground.contact = \"{}\"`",
            law.name(),
            self.law().name()
        )
    }

    /// Whether `ground` holds this key's default.
    fn is_default(self, ground: &Ground) -> bool {
        let d = &Params::DEFAULT.ground;
        match self {
            GroundKey::Damping => ground.damping == d.damping,
            GroundKey::FrictionLaw => ground.friction_law == d.friction_law,
            GroundKey::StaticFriction => ground.static_friction == d.static_friction,
            GroundKey::Restitution => ground.restitution == d.restitution,
            GroundKey::TangentialStiffnessRatio => {
                ground.tangential_stiffness_ratio == d.tangential_stiffness_ratio
            }
            GroundKey::FaceRestitution => ground.face_restitution == d.face_restitution,
            GroundKey::TableMass => ground.table_mass == d.table_mass,
            GroundKey::TableStiffness => ground.table_stiffness == d.table_stiffness,
            GroundKey::TableDamping => ground.table_damping == d.table_damping,
            GroundKey::Tilt => ground.tilt == d.tilt,
            GroundKey::TiltDirection => ground.tilt_direction == d.tilt_direction,
        }
    }

    /// The key's value as a number for its refusal (NaN for the friction law's name).
    fn value(self, ground: &Ground) -> f64 {
        match self {
            GroundKey::Damping => ground.damping,
            GroundKey::FrictionLaw => f64::NAN,
            GroundKey::StaticFriction => ground.static_friction,
            GroundKey::Restitution => ground.restitution,
            GroundKey::TangentialStiffnessRatio => ground.tangential_stiffness_ratio,
            GroundKey::FaceRestitution => ground.face_restitution.unwrap_or(f64::NAN),
            GroundKey::TableMass => ground.table_mass.unwrap_or(f64::NAN),
            GroundKey::TableStiffness => ground.table_stiffness.unwrap_or(f64::NAN),
            GroundKey::TableDamping => ground.table_damping.unwrap_or(f64::NAN),
            GroundKey::Tilt => ground.tilt,
            GroundKey::TiltDirection => ground.tilt_direction,
        }
    }

    fn limits(self) -> Limits {
        match self {
            GroundKey::Damping => limits::DAMPING,
            GroundKey::FrictionLaw => FRICTION_LAW_KEY,
            GroundKey::StaticFriction => limits::STATIC_FRICTION,
            GroundKey::Restitution => limits::RESTITUTION,
            GroundKey::TangentialStiffnessRatio => limits::TANGENTIAL_STIFFNESS_RATIO,
            GroundKey::FaceRestitution => limits::FACE_RESTITUTION,
            GroundKey::TableMass => limits::TABLE_MASS,
            GroundKey::TableStiffness => limits::TABLE_STIFFNESS,
            GroundKey::TableDamping => limits::TABLE_DAMPING,
            GroundKey::Tilt => limits::TILT,
            GroundKey::TiltDirection => limits::TILT_DIRECTION,
        }
    }
}

impl Ground {
    /// Whether this ground's contact law reads `key` (a dotted preset key); every key but
    /// the [`GroundKey`]s is read by both laws.
    pub fn reads(&self, key: &str) -> bool {
        GroundKey::named(key).is_none_or(|k| k.law() == self.contact)
    }

    /// The refusal of `key` (a dotted preset key) when this ground's contact law does not read
    /// it: what a file, `--set` or the explorer says when the key is given, whatever its value.
    pub fn refusal(&self, key: &str) -> Option<ParamError> {
        let key = GroundKey::named(key).filter(|k| k.law() != self.contact)?;
        Some(ParamError::refused(
            key.limits(),
            key.value(self),
            key.why_unread(self.contact),
        ))
    }

    /// The first key this ground's law does not read that differs from its default.
    fn check_unread(&self) -> Result<(), ParamError> {
        for key in GroundKey::ALL {
            if key.law() != self.contact && !key.is_default(self) {
                return Err(ParamError::refused(
                    key.limits(),
                    key.value(self),
                    key.why_unread(self.contact),
                ));
            }
        }
        Ok(())
    }
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
            half_sizes: [1.0; 3],
            corner_radius: 0.0,
            pip_diameter: 0.0,
            pip_depth: 0.0,
            corner_mass: 1.0,
            extra_corner_mass: [0.0; 8],
            kind: Solid::Box,
            // A standard ("16 mm") die of cast acrylic resin (docs/dice.md).
            height: 1.6,
            density: 1.18,
            vertices: Vertices::NONE,
            flaws: DieFlaws::NONE,
        },
        ground: Ground {
            stiffness: 500_000.0,
            damping: 0.005,
            friction: 1.2,
            friction_law: FrictionLaw::PerCorner,
            contact: ContactLaw::Paper,
            static_friction: 1.2,
            restitution: 0.5,
            tangential_stiffness_ratio: 2.0 / 7.0,
            face_restitution: None,
            table_mass: None,
            table_stiffness: None,
            table_damping: None,
            tilt: 0.0,
            tilt_direction: 0.0,
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
    pub fn validate(&self) -> Result<(), ParamError> {
        let (d, g, i) = (&self.die, &self.ground, &self.integrator);
        // A key the solid does not read is refused first: its range is no matter then.
        d.check_unread()?;
        if d.is_polyhedral() {
            if d.kind != Solid::Convex {
                limits::HEIGHT.check(d.height)?;
            }
            limits::DENSITY.check(d.density)?;
            d.check_ranges()?;
            self.check_polyhedral_die()?;
        }
        limits::HALF_SIZES.check_components(XYZ, &d.half_sizes)?;
        limits::CORNER_RADIUS.check(d.corner_radius)?;
        let smallest = d.smallest_half_size();
        if d.corner_radius >= smallest {
            return Err(ParamError::refused(
                limits::CORNER_RADIUS,
                d.corner_radius,
                format!(
                    "the corner radius must be below the smallest half size, {} cm",
                    fmt_number(smallest)
                ),
            ));
        }
        limits::PIP_DIAMETER.check(d.pip_diameter)?;
        let widest_pip = (0.5 * smallest).min(smallest - 2.0 * d.corner_radius);
        // An undrilled die has no pips to fit on its faces, however round its corners.
        if d.pip_diameter > 0.0 && d.pip_diameter > widest_pip {
            return Err(ParamError::refused(
                limits::PIP_DIAMETER,
                d.pip_diameter,
                format!(
                    "the pips must lie apart on the flat of every face: at most {} cm here (half the \
                     smallest half size, and at most the smallest half size less twice the corner radius)",
                    fmt_number(rounded_to_nanometres(widest_pip.max(0.0)))
                ),
            ));
        }
        limits::PIP_DEPTH.check(d.pip_depth)?;
        if d.pip_depth > 0.5 * d.pip_diameter {
            return Err(ParamError::refused(
                limits::PIP_DEPTH,
                d.pip_depth,
                format!(
                    "a pip is a spherical cap at most a hemisphere deep: at most half the pip \
                     diameter, {} cm",
                    fmt_number(0.5 * d.pip_diameter)
                ),
            ));
        }
        limits::CORNER_MASS.check(d.corner_mass)?;
        limits::EXTRA_CORNER_MASS.check_components(CORNERS, &d.extra_corner_mass)?;
        limits::STIFFNESS.check(g.stiffness)?;
        limits::DAMPING.check(g.damping)?;
        limits::FRICTION.check(g.friction)?;
        limits::STATIC_FRICTION.check(g.static_friction)?;
        if g.contact == ContactLaw::SpringFriction && g.static_friction < g.friction {
            return Err(ParamError::refused(
                limits::STATIC_FRICTION,
                g.static_friction,
                format!(
                    "static friction must be at least the kinetic `ground.friction`, {}: a stuck \
                     point lets go at μ_s·N and then slides at μ_k·N",
                    fmt_number(g.friction)
                ),
            ));
        }
        limits::RESTITUTION.check(g.restitution)?;
        limits::TANGENTIAL_STIFFNESS_RATIO.check(g.tangential_stiffness_ratio)?;
        if let Some(e_f) = g.face_restitution {
            limits::FACE_RESTITUTION.check(e_f)?;
        }
        if let Some(m) = g.table_mass {
            limits::TABLE_MASS.check(m)?;
        }
        for (limits, value) in [
            (limits::TABLE_STIFFNESS, g.table_stiffness),
            (limits::TABLE_DAMPING, g.table_damping),
        ] {
            let Some(value) = value else { continue };
            limits.check(value)?;
            if g.table_mass.is_none() {
                return Err(ParamError::refused(
                    limits,
                    value,
                    "a table top's spring and damper hold its mass: give `ground.table_mass` (g) too"
                        .to_string(),
                ));
            }
        }
        limits::TILT.check(g.tilt)?;
        limits::TILT_DIRECTION.check(g.tilt_direction)?;
        g.check_unread()?;
        limits::GRAVITY.check(self.world.gravity)?;
        limits::DT.check(i.dt)?;
        limits::STOP_ENERGY_FRACTION.check(i.stop_energy_fraction)?;
        limits::MAX_TIME.check(i.max_time)?;
        if d.is_polyhedral() {
            if i.stop_energy == StopEnergy::PointMasses {
                return Err(ParamError::refused(
                    STOP_ENERGY_KEY,
                    f64::NAN,
                    "\"point-masses\" (the authors' energy of 8 corner point masses) is defined for \
                     the paper's sharp cube without pips only; a polyhedral die needs \"rigid-body\""
                        .to_string(),
                ));
            }
            return self.check_polyhedral_step();
        }
        if i.stop_energy == StopEnergy::PointMasses && d.kind() == BodyKind::Shaped {
            return Err(ParamError::refused(
                STOP_ENERGY_KEY,
                f64::NAN,
                "\"point-masses\" (the authors' energy of 8 corner point masses) is defined for the \
                 paper's sharp cube without pips only; this die needs \"rigid-body\""
                    .to_string(),
            ));
        }
        Ok(())
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
    fn defaults_are_the_papers() {
        let p = Params::default();
        assert_eq!(p.die.kind(), BodyKind::PaperCube);
        assert_eq!(p.max_steps(), 30_000);
        p.validate().unwrap();
    }

    #[test]
    fn only_a_sharp_cube_without_pips_is_the_papers_body() {
        let kind = |change: fn(&mut Die)| {
            let mut die = Params::DEFAULT.die;
            change(&mut die);
            die.kind()
        };
        assert_eq!(kind(|d| d.extra_corner_mass[7] = 0.5), BodyKind::LoadedCube);
        assert_eq!(kind(|d| d.corner_radius = 0.1), BodyKind::Shaped);
        assert_eq!(kind(|d| d.half_sizes[2] = 0.9), BodyKind::Shaped);
        // Pips need both a depth and a diameter to be drilled.
        assert_eq!(kind(|d| d.pip_depth = 0.1), BodyKind::PaperCube);
        assert_eq!(
            kind(|d| (d.pip_depth, d.pip_diameter) = (0.1, 0.3)),
            BodyKind::Shaped
        );
        assert_eq!(
            kind(|d| (d.corner_radius, d.extra_corner_mass[0]) = (0.1, 1.0)),
            BodyKind::Shaped
        );
    }

    #[test]
    fn the_point_mass_energy_is_refused_for_a_general_body_only() {
        let mut p = Params::default();
        p.integrator.stop_energy = StopEnergy::PointMasses;
        p.die.extra_corner_mass[3] = 1.0;
        p.validate()
            .expect("a loaded cube's corners are its point masses");
        p.die.corner_radius = 0.1;
        let e = p.validate().unwrap_err();
        assert_eq!(e.key, "integrator.stop_energy");
        assert!(e.to_string().contains("\"rigid-body\""), "{e}");
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

    #[test]
    fn round_corners_need_room_for_pips_only_on_a_drilled_die() {
        // A 1 cm cube (half size 0.5) rounded by 0.3 cm leaves 0.5 − 2·0.3 < 0 for pips.
        let mut p = Params::default();
        p.die.half_sizes = [0.5, 0.5, 0.5];
        p.die.corner_radius = 0.3;
        p.die.pip_diameter = 0.0;
        p.die.pip_depth = 0.0;
        p.validate().expect("no pips, nothing to fit");
        p.die.pip_diameter = 0.1;
        let e = p.validate().unwrap_err();
        assert_eq!(e.key, "die.pip_diameter");
        assert!(e.to_string().contains("at most 0 cm"), "{e}");
    }

    /// A polyhedral die of `kind` at Δt = 0.25 ms, the dice' table.
    fn dice(kind: Solid) -> Params {
        let mut p = Params::default();
        p.die.kind = kind;
        p.integrator.dt = 0.00025;
        p
    }

    #[test]
    fn a_polyhedral_die_shows_its_own_numbers() {
        assert_eq!(Params::DEFAULT.die.face_numbers(), &[1, 2, 3, 4, 5, 6]);
        let numbers = |kind| dice(kind).die.face_numbers().to_vec();
        assert_eq!(numbers(Solid::D4), (1..=4).collect::<Vec<u8>>());
        assert_eq!(numbers(Solid::D8), (1..=8).collect::<Vec<u8>>());
        assert_eq!(numbers(Solid::D10), (0..=9).collect::<Vec<u8>>());
        assert_eq!(
            numbers(Solid::Percentile),
            (0..=9).map(|n| 10 * n).collect::<Vec<u8>>()
        );
        assert_eq!(numbers(Solid::D12), (1..=12).collect::<Vec<u8>>());
        assert_eq!(numbers(Solid::D20), (1..=20).collect::<Vec<u8>>());
        for kind in Solid::ALL {
            assert_eq!(Solid::from_name(kind.name()), Some(kind));
        }
        for kind in Solid::ALL.into_iter().filter(|&k| k != Solid::Convex) {
            dice(kind).validate().unwrap();
        }
        // A convex die without its corners is no die yet.
        assert_eq!(dice(Solid::Convex).validate().unwrap_err().key, "die.vertices");
    }

    #[test]
    fn the_box_keys_are_refused_beside_a_polyhedron_and_its_size_beside_the_box() {
        let mut p = dice(Solid::D20);
        p.die.half_sizes = [0.8; 3];
        let e = p.validate().unwrap_err();
        assert_eq!(e.key, "die.half_sizes");
        assert!(e.to_string().contains("a d20 is a polyhedral die"), "{e}");
        let mut p = dice(Solid::D8);
        p.die.extra_corner_mass[2] = 0.5;
        assert_eq!(p.validate().unwrap_err().key, "die.extra_corner_mass");
        let mut p = Params::default();
        p.die.height = 2.0;
        let e = p.validate().unwrap_err();
        assert_eq!(e.key, "die.height");
        assert!(
            e.to_string().contains("the box is sized by `die.half_sizes`"),
            "{e}"
        );
        let mut p = dice(Solid::D12);
        p.die.density = 30.0;
        assert_eq!(p.validate().unwrap_err().key, "die.density");
        assert!(Params::DEFAULT.die.reads("die.half_size"));
        assert!(!dice(Solid::D4).die.reads("die.half_size"));
        assert!(!Params::DEFAULT.die.states("die.kind") && dice(Solid::D4).die.states("die.kind"));
    }

    #[test]
    fn the_d4_is_refused_on_the_papers_step() {
        // docs/model.md, "Fair dice come out fair": one point of the 16 mm resin d4 on the table
        // moves like M/8.5 (M = 1.18 g/cm³ · 0.8868 cm³ = 1.0465 g), ω = √(k·8.5/M) = 2 015 rad/s:
        // ω·Δt = 2.02 at 1 ms, past 1.25; 0.50 at 0.25 ms.
        let mut p = dice(Solid::D4);
        p.integrator.dt = 0.001;
        let e = p.validate().unwrap_err();
        assert_eq!(e.key, "integrator.dt");
        assert!(e.to_string().contains("ω·Δt = 2.02"), "{e}");
        assert!(e.to_string().contains("runs away"), "{e}");
        let mut p = dice(Solid::D4);
        p.integrator.dt = 0.00025;
        assert!(
            (p.stability_number() - 0.504).abs() < 0.001,
            "{}",
            p.stability_number()
        );
        p.validate().unwrap();
        // The other dice take the paper's step (docs: ω·Δt 0.75 to 0.85 at 1 ms).
        let mut p = dice(Solid::D20);
        p.integrator.dt = 0.001;
        p.validate().unwrap();
    }

    #[test]
    fn the_authors_point_mass_energy_is_refused_for_a_polyhedron() {
        let mut p = dice(Solid::D20);
        p.integrator.stop_energy = StopEnergy::PointMasses;
        assert_eq!(p.validate().unwrap_err().key, "integrator.stop_energy");
    }
}
