//! Every value of a setup, stated once: its preset key, unit, allowed range, default, what it
//! means, how the explorer lists and steps it, and how it is read and written.
//!
//! Validation ([`Params::validate`], [`InitialCondition::validate`],
//! [`RandomRanges::validate`]), the preset file's lines and comments, `--set`, basin-map
//! axes, the explorer's parameter list and the README's table of keys are all derived from
//! [`ALL`]. Adding a scalar parameter is one row here, its field (with the row's default) in
//! its section's struct, and its use in the physics.

use super::initial::{InitialCondition, RandomRanges};
use super::params::{Limits, ParamError, Params};

/// The section of a preset a value belongs to, which is also what changing it means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    Die,
    Ground,
    World,
    Integrator,
    /// The initial condition of "the" roll: changing it makes a roll of its own.
    Initial,
    /// How random rolls are drawn.
    Random,
}

impl Role {
    /// Every section, in the order a preset file lists them.
    pub(crate) const ALL: [Role; 6] = [
        Role::Die,
        Role::Ground,
        Role::World,
        Role::Integrator,
        Role::Initial,
        Role::Random,
    ];

    /// The preset file's table name.
    pub(crate) fn section(self) -> &'static str {
        match self {
            Role::Die => "die",
            Role::Ground => "ground",
            Role::World => "world",
            Role::Integrator => "integrator",
            Role::Initial => "initial",
            Role::Random => "random",
        }
    }

    /// The comment on the section's header line in a written preset.
    pub(crate) fn comment(self) -> &'static str {
        match self {
            Role::Initial => "the initial condition of \"the\" roll",
            Role::Random => "how random rolls are drawn (batch runs, \"random roll\")",
            _ => "",
        }
    }
}

/// What kind of value a key holds, with its default.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// One number.
    Number(f64),
    /// Three numbers, named by these components in `--set` and scan keys.
    Vector {
        components: &'static [&'static str; 3],
        default: [f64; 3],
    },
    /// `[low, high]`, each inside the range and `low <= high`.
    Range([f64; 2]),
    /// One of these names (the first listed is not necessarily the default).
    Choice {
        names: &'static [&'static str],
        default: &'static str,
    },
    /// A non-negative integer.
    Seed(u64),
    Flag(bool),
    /// One number per corner 1..8, named `1` … `8` in `--set` and scan keys.
    PerCorner([f64; 8]),
}

/// How the explorer steps a value under ←/→: by a fixed amount, or by a factor for values
/// that span decades (stiffness, Δt, mass), where equal ratios are the natural steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Nudge {
    Add { fine: f64, coarse: f64 },
    Times { fine: f64, coarse: f64 },
}

/// A value as a setup stores it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    Number(f64),
    Vector([f64; 3]),
    Range([f64; 2]),
    Name(&'static str),
    Seed(u64),
    Flag(bool),
    PerCorner([f64; 8]),
    /// An optional value that is not given.
    Absent,
}

/// Everything a setup holds, for reading any value by its row.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Setup {
    pub(crate) params: Params,
    pub(crate) initial: InitialCondition,
    pub(crate) random: RandomRanges,
}

/// How a numeric value is read and changed by component (0 for a scalar): what `--set` on a
/// component, a basin-map axis and the explorer use.
#[derive(Debug, Clone, Copy)]
pub struct Scan {
    pub(crate) get: fn(&Params, &InitialCondition, usize) -> f64,
    /// Not range-checked: see [`Spec::check_number`].
    pub(crate) set: fn(&mut Params, &mut InitialCondition, usize, f64),
}

/// One row of the registry.
#[derive(Debug, Clone, Copy)]
pub struct Spec {
    /// Dotted preset key, unit (`""` for dimensionless) and allowed range.
    pub limits: Limits,
    pub shape: Shape,
    pub role: Role,
    /// Its meaning, as the comment beside it in a written preset and in the README.
    pub comment: &'static str,
    /// The explorer's short labels, one per component; empty: not in the explorer's list.
    pub labels: &'static [&'static str],
    /// Where the explorer lists it (lower first).
    pub list_position: u8,
    pub nudge: Option<Nudge>,
    /// Acts on the running roll at once (the explorer does not restart the roll).
    pub acts_mid_roll: bool,
    /// The value as stored (no conversion: a spin given as momentum reads as given).
    pub read: fn(&Setup) -> Value,
    /// Numeric values a scan or the explorer can change; `None` for the rest.
    pub scan: Option<Scan>,
}

/// Rows are equal when they name the same key.
impl PartialEq for Spec {
    fn eq(&self, other: &Spec) -> bool {
        self.key() == other.key()
    }
}

impl Spec {
    /// The dotted preset key.
    pub(crate) fn key(&self) -> &'static str {
        self.limits.key
    }

    /// The default of a [`Shape::Number`] row (for the section structs' `Default`).
    pub(crate) const fn number(&self) -> f64 {
        match self.shape {
            Shape::Number(x) => x,
            _ => panic!("not a number row"),
        }
    }

    /// The default of a [`Shape::Vector`] row.
    pub(crate) const fn vector(&self) -> [f64; 3] {
        match self.shape {
            Shape::Vector { default, .. } => default,
            _ => panic!("not a vector row"),
        }
    }

    /// The default of a [`Shape::Range`] row.
    pub(crate) const fn range(&self) -> [f64; 2] {
        match self.shape {
            Shape::Range(r) => r,
            _ => panic!("not a range row"),
        }
    }

    /// The default of a [`Shape::Seed`] row.
    pub(crate) const fn seed(&self) -> u64 {
        match self.shape {
            Shape::Seed(s) => s,
            _ => panic!("not a seed row"),
        }
    }

    /// The default of a [`Shape::Flag`] row.
    pub(crate) const fn flag(&self) -> bool {
        match self.shape {
            Shape::Flag(b) => b,
            _ => panic!("not a flag row"),
        }
    }

    /// The default of a [`Shape::PerCorner`] row.
    pub(crate) const fn per_corner(&self) -> [f64; 8] {
        match self.shape {
            Shape::PerCorner(v) => v,
            _ => panic!("not a per-corner row"),
        }
    }

    /// The names of a vector's or per-corner row's components; none for other shapes.
    pub(crate) fn components(&self) -> &'static [&'static str] {
        match self.shape {
            Shape::Vector { components, .. } => components,
            Shape::PerCorner(_) => CORNERS,
            _ => &[],
        }
    }

    /// The default as a [`Value`].
    #[cfg(test)]
    pub(crate) fn default_value(&self) -> Value {
        match self.shape {
            Shape::Number(x) => Value::Number(x),
            Shape::Vector { default, .. } => Value::Vector(default),
            Shape::Range(r) => Value::Range(r),
            Shape::Choice { default, .. } => Value::Name(default),
            Shape::Seed(s) => Value::Seed(s),
            Shape::Flag(b) => Value::Flag(b),
            Shape::PerCorner(v) => Value::PerCorner(v),
        }
    }

    /// Checks one number against the range, naming `key` in the error (NaN and infinities
    /// are outside every range).
    pub(crate) fn check_number(&self, key: &str, value: f64) -> Result<(), ParamError> {
        self.limits.check(value).map_err(|mut e| {
            e.key = key.to_string();
            e
        })
    }

    /// Checks a stored value: every component in range, a range's low end not above its high
    /// end. Errors name the component (`initial.velocity.y`, `random.height[1]`).
    pub(crate) fn check(&self, value: Value) -> Result<(), ParamError> {
        let key = self.key();
        match value {
            Value::Number(x) => self.check_number(key, x),
            Value::Vector(v) => self.check_components(&v),
            Value::PerCorner(v) => self.check_components(&v),
            Value::Range(r) => {
                for (i, x) in r.into_iter().enumerate() {
                    self.check_number(&format!("{key}[{i}]"), x)?;
                }
                if r[0] > r[1] {
                    return Err(ParamError {
                        key: key.to_string(),
                        value: r[0],
                        limits: self.limits,
                        high_end: Some(r[1]),
                    });
                }
                Ok(())
            }
            Value::Name(_) | Value::Seed(_) | Value::Flag(_) | Value::Absent => Ok(()),
        }
    }
}

impl Spec {
    /// Checks each component, naming it (`initial.velocity.y`, `die.extra_corner_mass.8`).
    fn check_components(&self, values: &[f64]) -> Result<(), ParamError> {
        for (name, &x) in self.components().iter().zip(values) {
            self.check_number(&format!("{}.{name}", self.key()), x)?;
        }
        Ok(())
    }
}

/// Checks every row of `roles` in `setup`, in registry order; the first failure is returned.
pub(crate) fn validate(setup: &Setup, roles: &[Role]) -> Result<(), ParamError> {
    ALL.iter()
        .filter(|spec| roles.contains(&spec.role))
        .try_for_each(|spec| spec.check((spec.read)(setup)))
}

/// The row of a dotted preset key.
pub(crate) fn find(key: &str) -> Option<&'static Spec> {
    ALL.iter().copied().find(|s| s.key() == key)
}

const XYZ: &[&str; 3] = &["x", "y", "z"];
const YAW_PITCH_ROLL: &[&str; 3] = &["yaw", "pitch", "roll"];
const CORNERS: &[&str] = &["1", "2", "3", "4", "5", "6", "7", "8"];

/// Reads and sets a number field of `Params` by component (scalars ignore the component).
macro_rules! params_field {
    ($($path:ident).+) => {
        Some(Scan {
            get: |p, _, _| p.$($path).+,
            set: |p, _, _, v| p.$($path).+ = v,
        })
    };
}

pub const HALF_SIZE: Spec = Spec {
    limits: Limits {
        key: "die.half_size",
        unit: "cm",
        min: 0.1,
        max: 10.0,
    },
    shape: Shape::Number(1.0),
    role: Role::Die,
    comment: "cm, the paper's \"radius\" (side = 2 × half_size)",
    labels: &["half size a"],
    list_position: 15,
    nudge: Some(Nudge::Add {
        fine: 0.05,
        coarse: 0.5,
    }),
    acts_mid_roll: false,
    read: |s| Value::Number(s.params.die.half_size),
    scan: params_field!(die.half_size),
};

pub const CORNER_MASS: Spec = Spec {
    limits: Limits {
        key: "die.corner_mass",
        unit: "g",
        min: 0.01,
        max: 1000.0,
    },
    shape: Shape::Number(1.0),
    role: Role::Die,
    comment: "g, each of the 8 corners",
    labels: &["corner mass m"],
    list_position: 16,
    nudge: Some(Nudge::Times {
        fine: 1.1,
        coarse: 2.0,
    }),
    acts_mid_roll: false,
    read: |s| Value::Number(s.params.die.corner_mass),
    scan: params_field!(die.corner_mass),
};

pub const EXTRA_CORNER_MASS: Spec = Spec {
    limits: Limits {
        key: "die.extra_corner_mass",
        unit: "g",
        min: 0.0,
        max: 1000.0,
    },
    shape: Shape::PerCorner([0.0; 8]),
    role: Role::Die,
    comment: "g, extra point mass at corners 1..8: a loaded die (all zero: fair)",
    labels: &[
        "extra mass 1",
        "extra mass 2",
        "extra mass 3",
        "extra mass 4",
        "extra mass 5",
        "extra mass 6",
        "extra mass 7",
        "extra mass 8",
    ],
    list_position: 17,
    nudge: Some(Nudge::Add {
        fine: 0.1,
        coarse: 1.0,
    }),
    acts_mid_roll: false,
    read: |s| Value::PerCorner(s.params.die.extra_corner_mass),
    scan: Some(Scan {
        get: |p, _, i| p.die.extra_corner_mass[i],
        set: |p, _, i, v| p.die.extra_corner_mass[i] = v,
    }),
};

pub const STIFFNESS: Spec = Spec {
    limits: Limits {
        key: "ground.stiffness",
        unit: "dyn/cm",
        min: 100.0,
        max: 1e8,
    },
    shape: Shape::Number(500_000.0),
    role: Role::Ground,
    comment: "dyn/cm per corner (k)",
    labels: &["stiffness k"],
    list_position: 0,
    nudge: Some(Nudge::Times {
        fine: 1.1,
        coarse: 2.0,
    }),
    acts_mid_roll: true,
    read: |s| Value::Number(s.params.ground.stiffness),
    scan: params_field!(ground.stiffness),
};

pub const DAMPING: Spec = Spec {
    limits: Limits {
        key: "ground.damping",
        unit: "s/cm",
        min: 0.0,
        max: 0.1,
    },
    shape: Shape::Number(0.005),
    role: Role::Ground,
    comment: "s/cm (γ)",
    labels: &["damping γ"],
    list_position: 1,
    nudge: Some(Nudge::Add {
        fine: 0.0005,
        coarse: 0.005,
    }),
    acts_mid_roll: true,
    read: |s| Value::Number(s.params.ground.damping),
    scan: params_field!(ground.damping),
};

pub const FRICTION: Spec = Spec {
    limits: Limits {
        key: "ground.friction",
        unit: "",
        min: 0.0,
        max: 5.0,
    },
    shape: Shape::Number(1.2),
    role: Role::Ground,
    comment: "kinetic coefficient (μ)",
    labels: &["friction μ"],
    list_position: 2,
    nudge: Some(Nudge::Add {
        fine: 0.05,
        coarse: 0.5,
    }),
    acts_mid_roll: true,
    read: |s| Value::Number(s.params.ground.friction),
    scan: params_field!(ground.friction),
};

pub(crate) const FRICTION_LAW: Spec = Spec {
    limits: Limits {
        key: "ground.friction_law",
        unit: "",
        min: 0.0,
        max: 0.0,
    },
    shape: Shape::Choice {
        names: &["per-corner", "whole-die-norm"],
        default: "per-corner",
    },
    role: Role::Ground,
    comment: "\"per-corner\" (paper, eq. 15) or \"whole-die-norm\" (authors' program)",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: true,
    read: |s| Value::Name(s.params.ground.friction_law.name()),
    scan: None,
};

pub const GRAVITY: Spec = Spec {
    limits: Limits {
        key: "world.gravity",
        unit: "cm/s²",
        min: 10.0,
        max: 10000.0,
    },
    shape: Shape::Number(980.0),
    role: Role::World,
    comment: "cm/s², downwards",
    labels: &["gravity g"],
    list_position: 14,
    nudge: Some(Nudge::Add {
        fine: 10.0,
        coarse: 100.0,
    }),
    acts_mid_roll: false,
    read: |s| Value::Number(s.params.world.gravity),
    scan: params_field!(world.gravity),
};

pub const DT: Spec = Spec {
    limits: Limits {
        key: "integrator.dt",
        unit: "s",
        min: 1e-5,
        max: 1e-2,
    },
    shape: Shape::Number(0.001),
    role: Role::Integrator,
    comment: "s",
    labels: &["time step Δt"],
    list_position: 13,
    nudge: Some(Nudge::Times {
        fine: 1.1,
        coarse: 2.0,
    }),
    acts_mid_roll: false,
    read: |s| Value::Number(s.params.integrator.dt),
    scan: params_field!(integrator.dt),
};

pub const STOP_ENERGY_FRACTION: Spec = Spec {
    limits: Limits {
        key: "integrator.stop_energy_fraction",
        unit: "",
        min: 0.01,
        max: 1.0,
    },
    shape: Shape::Number(0.8),
    role: Role::Integrator,
    comment: "a roll ends below this share of the edge-tipping energy",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    read: |s| Value::Number(s.params.integrator.stop_energy_fraction),
    scan: params_field!(integrator.stop_energy_fraction),
};

pub const MAX_TIME: Spec = Spec {
    limits: Limits {
        key: "integrator.max_time",
        unit: "s",
        min: 0.01,
        max: 120.0,
    },
    shape: Shape::Number(30.0),
    role: Role::Integrator,
    comment: "s of simulated time; past it the roll \"did not settle\"",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    read: |s| Value::Number(s.params.integrator.max_time),
    scan: params_field!(integrator.max_time),
};

pub(crate) const STOP_ENERGY: Spec = Spec {
    limits: Limits {
        key: "integrator.stop_energy",
        unit: "",
        min: 0.0,
        max: 0.0,
    },
    shape: Shape::Choice {
        names: &["rigid-body", "point-masses"],
        default: "rigid-body",
    },
    role: Role::Integrator,
    comment: "\"rigid-body\" (docs/model.md) or \"point-masses\" (the authors' program)",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    read: |s| Value::Name(s.params.integrator.stop_energy.name()),
    scan: None,
};

pub const HEIGHT: Spec = Spec {
    limits: Limits {
        key: "initial.height",
        unit: "cm",
        min: 0.0,
        max: 1000.0,
    },
    shape: Shape::Number(15.0),
    role: Role::Initial,
    comment: "cm, centre of mass above the ground",
    labels: &["drop height"],
    list_position: 3,
    nudge: Some(Nudge::Add {
        fine: 0.5,
        coarse: 5.0,
    }),
    acts_mid_roll: false,
    read: |s| Value::Number(s.initial.height),
    scan: Some(Scan {
        get: |_, ic, _| ic.height,
        set: |_, ic, _, v| ic.height = v,
    }),
};

pub const VELOCITY: Spec = Spec {
    limits: Limits {
        key: "initial.velocity",
        unit: "cm/s",
        min: -10_000.0,
        max: 10_000.0,
    },
    shape: Shape::Vector {
        components: XYZ,
        default: [0.0; 3],
    },
    role: Role::Initial,
    comment: "cm/s, centre of mass",
    labels: &["velocity vx", "velocity vy", "velocity vz"],
    list_position: 7,
    nudge: Some(Nudge::Add {
        fine: 5.0,
        coarse: 50.0,
    }),
    acts_mid_roll: false,
    read: |s| Value::Vector(s.initial.velocity),
    scan: Some(Scan {
        get: |_, ic, i| ic.velocity[i],
        set: |_, ic, i, v| ic.velocity[i] = v,
    }),
};

/// Spin is stated one way in an initial condition: reading a component of either form
/// converts with the die's inertia, and setting one first restates the spin in that form, so
/// the other two components keep their physical value.
pub const ANGULAR_VELOCITY: Spec = Spec {
    limits: Limits {
        key: "initial.angular_velocity",
        unit: "rad/s",
        min: -10_000.0,
        max: 10_000.0,
    },
    shape: Shape::Vector {
        components: XYZ,
        default: [0.0; 3],
    },
    role: Role::Initial,
    comment: "rad/s, world frame",
    labels: &["spin ωx", "spin ωy", "spin ωz"],
    list_position: 4,
    nudge: Some(Nudge::Add {
        fine: 1.0,
        coarse: 10.0,
    }),
    acts_mid_roll: false,
    read: |s| Value::Vector(s.initial.angular_velocity),
    scan: Some(Scan {
        get: |p, ic, i| ic.angular_velocity_for(p.inertia())[i],
        set: |p, ic, i, v| {
            let mut w: [f64; 3] = ic.angular_velocity_for(p.inertia()).into();
            w[i] = v;
            ic.angular_velocity = w;
            ic.angular_momentum = None;
        },
    }),
};

pub const ANGULAR_MOMENTUM: Spec = Spec {
    limits: Limits {
        key: "initial.angular_momentum",
        unit: "g·cm²/s",
        min: -1e6,
        max: 1e6,
    },
    shape: Shape::Vector {
        components: XYZ,
        default: [0.0; 3],
    },
    role: Role::Initial,
    comment: "g·cm²/s, world frame (L = I·ω); given instead of angular_velocity",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    read: |s| s.initial.angular_momentum.map_or(Value::Absent, Value::Vector),
    scan: Some(Scan {
        get: |p, ic, i| ic.angular_momentum_for(p.inertia())[i],
        set: |p, ic, i, v| {
            let mut l: [f64; 3] = ic.angular_momentum_for(p.inertia()).into();
            l[i] = v;
            ic.angular_momentum = Some(l);
        },
    }),
};

pub const ORIENTATION: Spec = Spec {
    limits: Limits {
        key: "initial.orientation",
        unit: "°",
        min: -360.0,
        max: 360.0,
    },
    shape: Shape::Vector {
        components: YAW_PITCH_ROLL,
        default: [0.0; 3],
    },
    role: Role::Initial,
    comment: "degrees: yaw (z), pitch (y), roll (x), applied in that order",
    labels: &["yaw", "pitch", "roll"],
    list_position: 10,
    nudge: Some(Nudge::Add {
        fine: 5.0,
        coarse: 45.0,
    }),
    acts_mid_roll: false,
    read: |s| Value::Vector(s.initial.orientation),
    scan: Some(Scan {
        get: |_, ic, i| ic.orientation[i],
        set: |_, ic, i, v| ic.orientation[i] = v,
    }),
};

pub(crate) const SEED: Spec = Spec {
    limits: Limits {
        key: "random.seed",
        unit: "",
        min: 0.0,
        max: 0.0,
    },
    shape: Shape::Seed(1),
    role: Role::Random,
    comment: "roll i's draw depends on (seed, i) alone",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    read: |s| Value::Seed(s.random.seed),
    scan: None,
};

/// A random range's bounds are checked against the initial condition's range.
const fn random_range(of: &Spec, key: &'static str, default: [f64; 2], comment: &'static str) -> Spec {
    Spec {
        limits: Limits { key, ..of.limits },
        shape: Shape::Range(default),
        role: Role::Random,
        comment,
        labels: &[],
        list_position: u8::MAX,
        nudge: None,
        acts_mid_roll: false,
        read: |_| Value::Absent,
        scan: None,
    }
}

pub(crate) const RANDOM_HEIGHT: Spec = Spec {
    read: |s| Value::Range(s.random.height),
    ..random_range(
        &HEIGHT,
        "random.height",
        [15.0, 15.0],
        "cm, uniform in [low, high]",
    )
};

pub(crate) const RANDOM_VELOCITY: Spec = Spec {
    read: |s| Value::Range(s.random.velocity),
    ..random_range(
        &VELOCITY,
        "random.velocity",
        [-50.0, 50.0],
        "cm/s, each component uniform in [low, high]",
    )
};

pub(crate) const RANDOM_ANGULAR_VELOCITY: Spec = Spec {
    read: |s| Value::Range(s.random.angular_velocity),
    ..random_range(
        &ANGULAR_VELOCITY,
        "random.angular_velocity",
        [-60.0, 60.0],
        "rad/s, each component uniform in [low, high]",
    )
};

pub(crate) const RANDOM_ORIENTATION: Spec = Spec {
    limits: Limits {
        key: "random.random_orientation",
        unit: "",
        min: 0.0,
        max: 0.0,
    },
    shape: Shape::Flag(false),
    role: Role::Random,
    comment: "true: orientation uniform over all rotations",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    read: |s| Value::Flag(s.random.random_orientation),
    scan: None,
};

/// Every value of a setup, in the order a preset file lists them.
pub(crate) static ALL: [&Spec; 22] = [
    &HALF_SIZE,
    &CORNER_MASS,
    &EXTRA_CORNER_MASS,
    &STIFFNESS,
    &DAMPING,
    &FRICTION,
    &FRICTION_LAW,
    &GRAVITY,
    &DT,
    &STOP_ENERGY_FRACTION,
    &MAX_TIME,
    &STOP_ENERGY,
    &HEIGHT,
    &VELOCITY,
    &ANGULAR_VELOCITY,
    &ANGULAR_MOMENTUM,
    &ORIENTATION,
    &SEED,
    &RANDOM_HEIGHT,
    &RANDOM_VELOCITY,
    &RANDOM_ANGULAR_VELOCITY,
    &RANDOM_ORIENTATION,
];

/// A number in a text table: as written in a preset, without a trailing `.0`.
#[cfg(test)]
fn number_text(x: f64) -> String {
    format!("{x}")
}

/// The README's table of preset keys, one line per row: key, unit, allowed range, default
/// and meaning. A test keeps the README's copy equal to this.
#[cfg(test)]
pub(crate) fn markdown_table() -> String {
    let mut out = String::from("| key | unit | allowed | default | meaning |\n|---|---|---|---|---|\n");
    for spec in ALL {
        let (allowed, default) = match spec.shape {
            Shape::Number(x) => (range_text(&spec.limits), number_text(x)),
            Shape::Vector { components, default } => (
                format!("{} (each of {})", range_text(&spec.limits), components.join(", ")),
                list_text(&default),
            ),
            Shape::Range(r) => (
                format!("low ≤ high, each {}", range_text(&spec.limits)),
                list_text(&r),
            ),
            Shape::Choice { names, default } => (
                names
                    .iter()
                    .map(|n| format!("`\"{n}\"`"))
                    .collect::<Vec<_>>()
                    .join(", "),
                format!("`\"{default}\"`"),
            ),
            Shape::Seed(s) => ("0 to 2⁶³ − 1".to_string(), s.to_string()),
            Shape::Flag(b) => ("`true`, `false`".to_string(), format!("`{b}`")),
            Shape::PerCorner(v) => (
                format!("{} (each of corners 1 to 8)", range_text(&spec.limits)),
                list_text(&v),
            ),
        };
        let default = if spec.key() == ANGULAR_MOMENTUM.key() {
            "not given".to_string()
        } else {
            default
        };
        let unit = if spec.limits.unit.is_empty() {
            "–"
        } else {
            spec.limits.unit
        };
        let meaning = spec.comment.replace('|', "\\|");
        out.push_str(&format!(
            "| `{}` | {unit} | {allowed} | {default} | {meaning} |\n",
            spec.key()
        ));
    }
    out
}

#[cfg(test)]
fn range_text(l: &Limits) -> String {
    format!("{} to {}", number_text(l.min), number_text(l.max))
}

#[cfg(test)]
fn list_text(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|&x| number_text(x)).collect();
    format!("[{}]", items.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_unique_and_in_section_order() {
        for (i, a) in ALL.iter().enumerate() {
            assert!(
                a.key().starts_with(&format!("{}.", a.role.section())),
                "{} is listed under {:?}",
                a.key(),
                a.role
            );
            for b in &ALL[i + 1..] {
                assert_ne!(a.key(), b.key());
            }
        }
        let roles: Vec<usize> = ALL
            .iter()
            .map(|s| Role::ALL.iter().position(|r| *r == s.role).unwrap())
            .collect();
        assert!(roles.is_sorted(), "rows grouped by section, in file order");
    }

    #[test]
    fn every_default_is_what_a_default_setup_holds() {
        let setup = Setup::default();
        for spec in ALL {
            let expected = match spec.default_value() {
                _ if spec.key() == ANGULAR_MOMENTUM.key() => Value::Absent,
                v => v,
            };
            assert_eq!((spec.read)(&setup), expected, "{}", spec.key());
            spec.check(expected).unwrap();
        }
        validate(&setup, &Role::ALL).unwrap();
    }

    #[test]
    fn explorer_rows_have_a_label_per_component_and_a_step() {
        for spec in ALL.iter().filter(|s| !s.labels.is_empty()) {
            let components = spec.components().len().max(1);
            assert_eq!(spec.labels.len(), components, "{}", spec.key());
            assert!(spec.nudge.is_some() && spec.scan.is_some(), "{}", spec.key());
        }
    }

    #[test]
    fn the_readme_table_is_the_registrys() {
        let table = markdown_table();
        for (name, text) in [
            ("README.md", include_str!("../../README.md")),
            ("docs/presets.md", include_str!("../../docs/presets.md")),
        ] {
            assert!(
                text.contains(&table),
                "{name}'s table of preset keys differs from the registry; it should read:\n{table}"
            );
        }
    }
}
