//! Every value of a setup as the tools around the model see it: its preset key with unit,
//! range and default (read from the physics, which states them), what it means, how the
//! explorer lists and steps it, whether it acts mid-roll, and how it is read and written.
//!
//! The physics knows its parameters as plain structs with their defaults
//! ([`Params::DEFAULT`], [`InitialCondition::DEFAULT`], [`RandomRanges::DEFAULT`]) and
//! ranges ([`params::limits`], [`initial::limits`]), and validates them itself; everything
//! else here serves the layers above: the preset file's lines and comments, `--set`,
//! basin-map axes and scan keys (this layer), the explorer's parameter list and the README's
//! table of keys all come from [`ALL`]. It lives in the experiment layer, one above the
//! physics, because scan keys and map axes are the first users of a row; the preset layer
//! and the explorer above read it from here. Adding a scalar parameter is its field, default
//! and range in the physics, its use there, and one row here.

use dicesim_physics::initial::{self, YAW_PITCH_ROLL};
use dicesim_physics::params::Solid;
use dicesim_physics::params::{self, CORNERS, XYZ};
use dicesim_physics::{ContactLaw, GroundKey, InitialCondition, Limits, ParamError, Params, RandomRanges};

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
    /// One number or none; `absent` says what the model takes when it is not given.
    Optional {
        absent: &'static str,
    },
    /// A list of up to `most` items, each `width` numbers (1: a number per vertex; 3: a point
    /// `[x, y, z]`), none by default. Components are named `1`, `2`, … (from 1, as vertices
    /// are).
    List {
        width: usize,
        most: usize,
    },
}

/// How the explorer steps a value under ←/→: by a fixed amount, or by a factor for values
/// that span decades (stiffness, Δt, mass), where equal ratios are the natural steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Nudge {
    Add { fine: f64, coarse: f64 },
    Times { fine: f64, coarse: f64 },
}

/// A value as a setup stores it.
// A list's numbers are held in place, so a `Value` stays `Copy`; values are read one at a
// time and never stored by the many, so its size costs nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    Number(f64),
    Vector([f64; 3]),
    Range([f64; 2]),
    Name(&'static str),
    Seed(u64),
    Flag(bool),
    PerCorner([f64; 8]),
    /// A list of items of one width ([`Shape::List`]).
    List(Numbers),
    /// An optional value that is not given.
    Absent,
}

/// The numbers of a [`Value::List`], held in place (a [`Value`] is `Copy`): up to 20 items
/// of one width, 1 or 3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Numbers {
    values: [f64; 3 * params::MAX_DIE_VERTICES],
    len: u8,
    width: u8,
}

impl Numbers {
    /// The items `items`, each `width` numbers; at most 20 are kept (a die's vertices, which
    /// the physics holds to 20).
    pub fn new<const W: usize>(items: &[[f64; W]]) -> Numbers {
        let mut values = [0.0; 3 * params::MAX_DIE_VERTICES];
        let kept = items.len().min(params::MAX_DIE_VERTICES);
        for (k, item) in items[..kept].iter().enumerate() {
            values[k * W..(k + 1) * W].copy_from_slice(item);
        }
        Numbers {
            values,
            len: (kept * W) as u8,
            width: W as u8,
        }
    }

    /// One item after another, each [`Numbers::width`] numbers.
    pub fn items(&self) -> std::slice::Chunks<'_, f64> {
        self.values[..self.len as usize].chunks(self.width as usize)
    }

    /// Numbers per item: 1 or 3.
    pub fn width(&self) -> usize {
        self.width as usize
    }

    /// Every number, item after item.
    pub fn values(&self) -> &[f64] {
        &self.values[..self.len as usize]
    }

    /// As a TOML or JSON array: `[a, b]` of numbers, `[[x, y, z], …]` of points, each number
    /// written by `number`.
    pub fn text(&self, number: impl Fn(f64) -> String) -> String {
        let item = |item: &[f64]| match item {
            [x] => number(*x),
            _ => format!(
                "[{}]",
                item.iter().map(|&x| number(x)).collect::<Vec<_>>().join(", ")
            ),
        };
        format!("[{}]", self.items().map(item).collect::<Vec<_>>().join(", "))
    }
}

/// Everything a setup holds, for reading any value by its row.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Setup {
    pub params: Params,
    pub initial: InitialCondition,
    pub random: RandomRanges,
}

/// How a numeric value is read and changed by component (0 for a scalar): what `--set` on a
/// component, a basin-map axis and the explorer use.
#[derive(Debug, Clone, Copy)]
pub struct Scan {
    pub(crate) get: fn(&Params, &InitialCondition, usize) -> f64,
    /// Not range-checked: see [`Spec::check_number`].
    pub(crate) set: fn(&mut Params, &mut InitialCondition, usize, f64),
}

/// The items of a list, named from 1 as a die's vertices are.
const VERTEX_NAMES: [&str; params::MAX_DIE_VERTICES] = [
    "1", "2", "3", "4", "5", "6", "7", "8", "9", "10", "11", "12", "13", "14", "15", "16", "17", "18", "19",
    "20",
];

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
    /// The one contact law that reads it (`ground.contact`); `None`: read under every law.
    /// Under another law it is refused, never ignored (the physics says why,
    /// [`dicesim_physics::Ground::refusal`]).
    pub law: Option<ContactLaw>,
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
    pub fn key(&self) -> &'static str {
        self.limits.key
    }

    /// The names of a vector's or per-corner row's components; none for other shapes.
    pub(crate) fn components(&self) -> &'static [&'static str] {
        match self.shape {
            Shape::Vector { components, .. } => components,
            Shape::PerCorner(_) => CORNERS,
            Shape::List { most, .. } => &VERTEX_NAMES[..most],
            _ => &[],
        }
    }

    /// The default as a [`Value`].
    pub fn default_value(&self) -> Value {
        match self.shape {
            Shape::Number(x) => Value::Number(x),
            Shape::Vector { default, .. } => Value::Vector(default),
            Shape::Range(r) => Value::Range(r),
            Shape::Choice { default, .. } => Value::Name(default),
            Shape::Seed(s) => Value::Seed(s),
            Shape::Flag(b) => Value::Flag(b),
            Shape::PerCorner(v) => Value::PerCorner(v),
            Shape::Optional { .. } => Value::Absent,
            Shape::List { width: 1, .. } => Value::List(Numbers::new::<1>(&[])),
            Shape::List { .. } => Value::List(Numbers::new::<3>(&[])),
        }
    }

    /// Checks one number against the range, naming `key` in the error (NaN and infinities
    /// are outside every range).
    pub(crate) fn check_number(&self, key: &str, value: f64) -> Result<(), ParamError> {
        self.limits.check_as(key, value)
    }

    /// Checks a stored value: every component in range, a range's low end not above its high
    /// end. Errors name the component (`initial.velocity.y`, `random.height[1]`).
    #[cfg(test)]
    pub(crate) fn check(&self, value: Value) -> Result<(), ParamError> {
        match value {
            Value::Number(x) => self.limits.check(x),
            Value::Vector(v) => self.limits.check_components(self.components(), &v),
            Value::PerCorner(v) => self.limits.check_components(self.components(), &v),
            Value::Range(r) => self.limits.check_range(r),
            Value::List(list) => list.values().iter().try_for_each(|&x| self.limits.check(x)),
            Value::Name(_) | Value::Seed(_) | Value::Flag(_) | Value::Absent => Ok(()),
        }
    }
}

/// The row of a dotted preset key.
pub fn find(key: &str) -> Option<&'static Spec> {
    ALL.iter().copied().find(|s| s.key() == key)
}

/// Reads and sets a number field of `Params` by component (scalars ignore the component).
macro_rules! params_field {
    ($($path:ident).+) => {
        Some(Scan {
            get: |p, _, _| p.$($path).+,
            set: |p, _, _, v| p.$($path).+ = v,
        })
    };
}

pub const KIND: Spec = Spec {
    limits: params::KIND_KEY,
    shape: Shape::Choice {
        names: &Solid::NAMES,
        default: Params::DEFAULT.die.kind.name(),
    },
    role: Role::Die,
    comment: "\"box\" (the cuboid of the keys below: the paper's die) or a polyhedral die, \"d4\", \"d8\", \
              \"d10\", \"d%\" (a d10 read 00 to 90), \"d12\", \"d20\", sized by `height`, or \"convex\", given by \
              its `vertices`, each made of `density`; not written for the box",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Name(s.params.die.kind.name()),
    scan: None,
};

pub const DIE_HEIGHT: Spec = Spec {
    limits: params::limits::HEIGHT,
    shape: Shape::Number(Params::DEFAULT.die.height),
    role: Role::Die,
    comment: "cm, how tall a polyhedral die stands on a face: across its faces (face to top vertex on \
              the d4); a polyhedral die only",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.params.die.height),
    scan: None,
};

pub const DENSITY: Spec = Spec {
    limits: params::limits::DENSITY,
    shape: Shape::Number(Params::DEFAULT.die.density),
    role: Role::Die,
    comment: "g/cm³, a polyhedral die's uniform material (1.18: acrylic resin); a polyhedral die only",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.params.die.density),
    scan: None,
};

pub const VERTICES: Spec = Spec {
    limits: params::limits::VERTICES,
    shape: Shape::List {
        width: 3,
        most: params::MAX_DIE_VERTICES,
    },
    role: Role::Die,
    comment: "cm, a convex die's corners `[x, y, z]` in its own frame (`kind = \"convex\"`): its faces are \
              their hull's, numbered 1 to F (opposite faces summing to F + 1 where they pair); at most 20 \
              corners and 20 faces",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| Value::List(Numbers::new(s.params.die.vertices.points())),
    scan: None,
};

/// A polyhedral die's flaw keys: a number (its size, or where it is), none in the explorer.
macro_rules! flaw_number {
    ($name:ident, $limits:ident, $field:ident, $comment:expr) => {
        pub const $name: Spec = Spec {
            limits: params::limits::$limits,
            shape: Shape::Number(0.0),
            role: Role::Die,
            comment: $comment,
            labels: &[],
            list_position: u8::MAX,
            nudge: None,
            acts_mid_roll: false,
            law: None,
            read: |s| Value::Number(s.params.die.flaws.$field),
            scan: params_field!(die.flaws.$field),
        };
    };
}

/// A polyhedral die's key naming one of its faces by the number it shows.
macro_rules! flaw_face {
    ($name:ident, $limits:ident, $field:ident, $comment:expr) => {
        pub const $name: Spec = Spec {
            limits: params::limits::$limits,
            shape: Shape::Optional { absent: "no face" },
            role: Role::Die,
            comment: $comment,
            labels: &[],
            list_position: u8::MAX,
            nudge: None,
            acts_mid_roll: false,
            law: None,
            read: |s| {
                s.params
                    .die
                    .flaws
                    .$field
                    .map_or(Value::Absent, |f| Value::Seed(u64::from(f)))
            },
            scan: None,
        };
    };
}

flaw_number!(
    ROUNDING,
    ROUNDING,
    rounding,
    "cm, every vertex of a polyhedral die rounded by this (0: sharp)"
);

pub const VERTEX_ROUNDING: Spec = Spec {
    limits: params::limits::VERTEX_ROUNDING,
    shape: Shape::List {
        width: 1,
        most: params::MAX_DIE_VERTICES,
    },
    role: Role::Die,
    comment: "cm, each vertex's own rounding on top of `rounding`, one per vertex in the die's order \
              (docs/dice.md): uneven rounding",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| {
        Value::List(Numbers::new(
            &s.params
                .die
                .flaws
                .vertex_rounding
                .as_slice()
                .iter()
                .map(|&r| [r])
                .collect::<Vec<_>>(),
        ))
    },
    scan: None,
};

flaw_face!(
    WORN_FACE,
    WORN_FACE,
    worn_face,
    "the number of the face whose corners are worn rounder by `worn_rounding`"
);
flaw_number!(
    WORN_ROUNDING,
    WORN_ROUNDING,
    worn_rounding,
    "cm, added to the rounding of each corner of `worn_face`: uneven rounding as one number"
);
flaw_number!(
    BUBBLE_RADIUS,
    BUBBLE_RADIUS,
    bubble_radius,
    "cm, an air bubble in the die (0: none), wholly inside it"
);
flaw_face!(
    BUBBLE_TOWARD,
    BUBBLE_TOWARD,
    bubble_toward,
    "the number of the face the bubble lies toward"
);
flaw_number!(
    BUBBLE_OFFSET,
    BUBBLE_OFFSET,
    bubble_offset,
    "cm, from the sharp die's centre of mass along `bubble_toward`'s outward normal: the bubble's flaw size"
);
flaw_number!(
    POINT_MASS,
    POINT_MASS,
    point_mass,
    "g, a point mass set into the die (0: none): the load's flaw size"
);
flaw_face!(
    POINT_MASS_TOWARD,
    POINT_MASS_TOWARD,
    point_mass_toward,
    "the number of the face the point mass lies toward"
);
flaw_number!(
    POINT_MASS_OFFSET,
    POINT_MASS_OFFSET,
    point_mass_offset,
    "cm, from the sharp die's centre of mass along `point_mass_toward`'s outward normal"
);
flaw_face!(
    SHAVE_FACE,
    SHAVE_FACE,
    shave_face,
    "the number of the face shaved down"
);
flaw_number!(
    SHAVE_DEPTH,
    SHAVE_DEPTH,
    shave_depth,
    "cm, how much is shaved off `shave_face`: a plane cut parallel to it (0: none)"
);

pub const HALF_SIZES: Spec = Spec {
    limits: params::limits::HALF_SIZES,
    shape: Shape::Vector {
        components: XYZ,
        default: Params::DEFAULT.die.half_sizes,
    },
    role: Role::Die,
    comment: "cm, half the side along x (faces 1, 6), y (2, 5), z (3, 4); a cube may give `half_size = a`",
    labels: &["half size x", "half size y", "half size z"],
    list_position: 16,
    nudge: Some(Nudge::Add {
        fine: 0.05,
        coarse: 0.5,
    }),
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Vector(s.params.die.half_sizes),
    scan: Some(Scan {
        get: |p, _, i| p.die.half_sizes[i],
        set: |p, _, i, v| p.die.half_sizes[i] = v,
    }),
};

pub const CORNER_RADIUS: Spec = Spec {
    limits: params::limits::CORNER_RADIUS,
    shape: Shape::Number(Params::DEFAULT.die.corner_radius),
    role: Role::Die,
    comment: "cm, rounded corners and edges (0: sharp, the paper's); below the smallest half size",
    labels: &["corner radius r"],
    list_position: 17,
    nudge: Some(Nudge::Add {
        fine: 0.01,
        coarse: 0.1,
    }),
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.params.die.corner_radius),
    scan: params_field!(die.corner_radius),
};

pub const PIP_DIAMETER: Spec = Spec {
    limits: params::limits::PIP_DIAMETER,
    shape: Shape::Number(Params::DEFAULT.die.pip_diameter),
    role: Role::Die,
    comment: "cm, each pip's opening; the pips must lie apart on the flat of every face",
    labels: &["pip diameter"],
    list_position: 18,
    nudge: Some(Nudge::Add {
        fine: 0.01,
        coarse: 0.1,
    }),
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.params.die.pip_diameter),
    scan: params_field!(die.pip_diameter),
};

pub const PIP_DEPTH: Spec = Spec {
    limits: params::limits::PIP_DEPTH,
    shape: Shape::Number(Params::DEFAULT.die.pip_depth),
    role: Role::Die,
    comment: "cm, pips drilled as spherical caps this deep (0: none), at most half the diameter",
    labels: &["pip depth"],
    list_position: 19,
    nudge: Some(Nudge::Add {
        fine: 0.005,
        coarse: 0.05,
    }),
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.params.die.pip_depth),
    scan: params_field!(die.pip_depth),
};

pub const CORNER_MASS: Spec = Spec {
    limits: params::limits::CORNER_MASS,
    shape: Shape::Number(Params::DEFAULT.die.corner_mass),
    role: Role::Die,
    comment: "g, each of the 8 corners",
    labels: &["corner mass m"],
    list_position: 15,
    nudge: Some(Nudge::Times {
        fine: 1.1,
        coarse: 2.0,
    }),
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.params.die.corner_mass),
    scan: params_field!(die.corner_mass),
};

pub const EXTRA_CORNER_MASS: Spec = Spec {
    limits: params::limits::EXTRA_CORNER_MASS,
    shape: Shape::PerCorner(Params::DEFAULT.die.extra_corner_mass),
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
    list_position: 20,
    nudge: Some(Nudge::Add {
        fine: 0.1,
        coarse: 1.0,
    }),
    acts_mid_roll: false,
    law: None,
    read: |s| Value::PerCorner(s.params.die.extra_corner_mass),
    scan: Some(Scan {
        get: |p, _, i| p.die.extra_corner_mass[i],
        set: |p, _, i, v| p.die.extra_corner_mass[i] = v,
    }),
};

pub const STIFFNESS: Spec = Spec {
    limits: params::limits::STIFFNESS,
    shape: Shape::Number(Params::DEFAULT.ground.stiffness),
    role: Role::Ground,
    comment: "dyn/cm per corner (k)",
    labels: &["stiffness k"],
    list_position: 0,
    nudge: Some(Nudge::Times {
        fine: 1.1,
        coarse: 2.0,
    }),
    acts_mid_roll: true,
    law: None,
    read: |s| Value::Number(s.params.ground.stiffness),
    scan: params_field!(ground.stiffness),
};

pub const DAMPING: Spec = Spec {
    limits: params::limits::DAMPING,
    shape: Shape::Number(Params::DEFAULT.ground.damping),
    role: Role::Ground,
    comment: "s/cm (γ), the paper's law only",
    labels: &["damping γ"],
    list_position: 1,
    nudge: Some(Nudge::Add {
        fine: 0.0005,
        coarse: 0.005,
    }),
    acts_mid_roll: true,
    law: Some(GroundKey::Damping.law()),
    read: |s| Value::Number(s.params.ground.damping),
    scan: params_field!(ground.damping),
};

pub const FRICTION: Spec = Spec {
    limits: params::limits::FRICTION,
    shape: Shape::Number(Params::DEFAULT.ground.friction),
    role: Role::Ground,
    comment: "kinetic coefficient (μ; μ_k under the spring-friction law)",
    labels: &["friction μ"],
    list_position: 2,
    nudge: Some(Nudge::Add {
        fine: 0.05,
        coarse: 0.5,
    }),
    acts_mid_roll: true,
    law: None,
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
        default: Params::DEFAULT.ground.friction_law.name(),
    },
    role: Role::Ground,
    comment: "\"per-corner\" (paper, eq. 15) or \"whole-die-norm\" (authors' program), the paper's law only",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: true,
    law: Some(GroundKey::FrictionLaw.law()),
    read: |s| Value::Name(s.params.ground.friction_law.name()),
    scan: None,
};

pub(crate) const CONTACT: Spec = Spec {
    limits: Limits {
        key: "ground.contact",
        unit: "",
        min: 0.0,
        max: 0.0,
    },
    shape: Shape::Choice {
        names: &["paper", "spring-friction"],
        default: Params::DEFAULT.ground.contact.name(),
    },
    role: Role::Ground,
    comment: "\"paper\" (eq. 13–15: damping γ, kinetic friction) or \"spring-friction\" (restitution, \
              static friction, a tangential spring, a tilted table)",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: true,
    law: None,
    read: |s| Value::Name(s.params.ground.contact.name()),
    scan: None,
};

pub const STATIC_FRICTION: Spec = Spec {
    limits: params::limits::STATIC_FRICTION,
    shape: Shape::Number(Params::DEFAULT.ground.static_friction),
    role: Role::Ground,
    comment: "static coefficient (μ_s), at least `friction`; the spring-friction law only",
    labels: &["static friction μs"],
    list_position: 22,
    nudge: Some(Nudge::Add {
        fine: 0.05,
        coarse: 0.5,
    }),
    acts_mid_roll: true,
    law: Some(GroundKey::StaticFriction.law()),
    read: |s| Value::Number(s.params.ground.static_friction),
    scan: params_field!(ground.static_friction),
};

pub const RESTITUTION: Spec = Spec {
    limits: params::limits::RESTITUTION,
    shape: Shape::Number(Params::DEFAULT.ground.restitution),
    role: Role::Ground,
    comment: "restitution (e) of a flat drop, the same at every impact speed; the spring-friction law only",
    labels: &["restitution e"],
    list_position: 21,
    nudge: Some(Nudge::Add {
        fine: 0.05,
        coarse: 0.2,
    }),
    acts_mid_roll: true,
    law: Some(GroundKey::Restitution.law()),
    read: |s| Value::Number(s.params.ground.restitution),
    scan: params_field!(ground.restitution),
};

pub const TANGENTIAL_STIFFNESS_RATIO: Spec = Spec {
    limits: params::limits::TANGENTIAL_STIFFNESS_RATIO,
    shape: Shape::Number(Params::DEFAULT.ground.tangential_stiffness_ratio),
    role: Role::Ground,
    comment: "k_t/k, the tangential spring over the normal one (2/7: a ball's two periods equal); \
              the spring-friction law only",
    labels: &["tangential k_t/k"],
    list_position: 23,
    nudge: Some(Nudge::Times {
        fine: 1.1,
        coarse: 2.0,
    }),
    acts_mid_roll: true,
    law: Some(GroundKey::TangentialStiffnessRatio.law()),
    read: |s| Value::Number(s.params.ground.tangential_stiffness_ratio),
    scan: params_field!(ground.tangential_stiffness_ratio),
};

pub const FACE_RESTITUTION: Spec = Spec {
    limits: params::limits::FACE_RESTITUTION,
    shape: Shape::Optional {
        absent: "`ground.restitution`",
    },
    role: Role::Ground,
    comment: "restitution (e_f) of a point striking while the body leans on the table (a fall onto a \
              face over an edge), not one landing from flight; the spring-friction law only",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: true,
    law: Some(GroundKey::FaceRestitution.law()),
    read: |s| {
        s.params
            .ground
            .face_restitution
            .map_or(Value::Absent, Value::Number)
    },
    scan: Some(Scan {
        get: |p, _, _| p.ground.face_restitution.unwrap_or(p.ground.restitution),
        set: |p, _, _, v| p.ground.face_restitution = Some(v),
    }),
};

pub const TABLE_MASS: Spec = Spec {
    limits: params::limits::TABLE_MASS,
    shape: Shape::Optional {
        absent: "a rigid table",
    },
    role: Role::Ground,
    comment: "g, a compliant table's top (m_T), moving along the normal under every point at once; \
              the spring-friction law only",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: true,
    law: Some(GroundKey::TableMass.law()),
    read: |s| s.params.ground.table_mass.map_or(Value::Absent, Value::Number),
    scan: Some(Scan {
        get: |p, _, _| p.ground.table_mass.unwrap_or(f64::INFINITY),
        set: |p, _, _, v| p.ground.table_mass = Some(v),
    }),
};

pub const TABLE_STIFFNESS: Spec = Spec {
    limits: params::limits::TABLE_STIFFNESS,
    shape: Shape::Optional {
        absent: "0, a free top",
    },
    role: Role::Ground,
    comment: "dyn/cm, the spring (K_T) holding the table top to the floor; with `table_mass` only; \
              the spring-friction law only",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: true,
    law: Some(GroundKey::TableStiffness.law()),
    read: |s| {
        s.params
            .ground
            .table_stiffness
            .map_or(Value::Absent, Value::Number)
    },
    scan: Some(Scan {
        get: |p, _, _| p.ground.table_stiffness.unwrap_or(0.0),
        set: |p, _, _, v| p.ground.table_stiffness = Some(v),
    }),
};

pub const TABLE_DAMPING: Spec = Spec {
    limits: params::limits::TABLE_DAMPING,
    shape: Shape::Optional { absent: "0" },
    role: Role::Ground,
    comment: "dyn·s/cm, the table top's own damper (C_T), the same whatever body strikes; with \
              `table_mass` only; the spring-friction law only",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: true,
    law: Some(GroundKey::TableDamping.law()),
    read: |s| s.params.ground.table_damping.map_or(Value::Absent, Value::Number),
    scan: Some(Scan {
        get: |p, _, _| p.ground.table_damping.unwrap_or(0.0),
        set: |p, _, _, v| p.ground.table_damping = Some(v),
    }),
};

pub const TILT: Spec = Spec {
    limits: params::limits::TILT,
    shape: Shape::Number(Params::DEFAULT.ground.tilt),
    role: Role::Ground,
    comment: "degrees, the table's slope (gravity tilted in the table's frame); the spring-friction law only",
    labels: &["table tilt"],
    list_position: 24,
    nudge: Some(Nudge::Add {
        fine: 1.0,
        coarse: 5.0,
    }),
    acts_mid_roll: true,
    law: Some(GroundKey::Tilt.law()),
    read: |s| Value::Number(s.params.ground.tilt),
    scan: params_field!(ground.tilt),
};

pub const TILT_DIRECTION: Spec = Spec {
    limits: params::limits::TILT_DIRECTION,
    shape: Shape::Number(Params::DEFAULT.ground.tilt_direction),
    role: Role::Ground,
    comment: "degrees from +x toward +y, the way the table slopes down; the spring-friction law only",
    labels: &["tilt direction"],
    list_position: 25,
    nudge: Some(Nudge::Add {
        fine: 5.0,
        coarse: 45.0,
    }),
    acts_mid_roll: true,
    law: Some(GroundKey::TiltDirection.law()),
    read: |s| Value::Number(s.params.ground.tilt_direction),
    scan: params_field!(ground.tilt_direction),
};

pub const GRAVITY: Spec = Spec {
    limits: params::limits::GRAVITY,
    shape: Shape::Number(Params::DEFAULT.world.gravity),
    role: Role::World,
    comment: "cm/s², downwards",
    labels: &["gravity g"],
    list_position: 14,
    nudge: Some(Nudge::Add {
        fine: 10.0,
        coarse: 100.0,
    }),
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.params.world.gravity),
    scan: params_field!(world.gravity),
};

pub const DT: Spec = Spec {
    limits: params::limits::DT,
    shape: Shape::Number(Params::DEFAULT.integrator.dt),
    role: Role::Integrator,
    comment: "s",
    labels: &["time step Δt"],
    list_position: 13,
    nudge: Some(Nudge::Times {
        fine: 1.1,
        coarse: 2.0,
    }),
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.params.integrator.dt),
    scan: params_field!(integrator.dt),
};

pub const STOP_ENERGY_FRACTION: Spec = Spec {
    limits: params::limits::STOP_ENERGY_FRACTION,
    shape: Shape::Number(Params::DEFAULT.integrator.stop_energy_fraction),
    role: Role::Integrator,
    comment: "a roll ends below this share of the edge-tipping energy",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.params.integrator.stop_energy_fraction),
    scan: params_field!(integrator.stop_energy_fraction),
};

pub const MAX_TIME: Spec = Spec {
    limits: params::limits::MAX_TIME,
    shape: Shape::Number(Params::DEFAULT.integrator.max_time),
    role: Role::Integrator,
    comment: "s of simulated time; past it the roll \"did not settle\"",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
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
        default: Params::DEFAULT.integrator.stop_energy.name(),
    },
    role: Role::Integrator,
    comment: "\"rigid-body\" (docs/model.md) or \"point-masses\" (the authors' program)",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Name(s.params.integrator.stop_energy.name()),
    scan: None,
};

pub const HEIGHT: Spec = Spec {
    limits: initial::limits::HEIGHT,
    shape: Shape::Number(InitialCondition::DEFAULT.height),
    role: Role::Initial,
    comment: "cm, centre of mass above the ground",
    labels: &["drop height"],
    list_position: 3,
    nudge: Some(Nudge::Add {
        fine: 0.5,
        coarse: 5.0,
    }),
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.initial.height),
    scan: Some(Scan {
        get: |_, ic, _| ic.height,
        set: |_, ic, _, v| ic.height = v,
    }),
};

pub const VELOCITY: Spec = Spec {
    limits: initial::limits::VELOCITY,
    shape: Shape::Vector {
        components: XYZ,
        default: InitialCondition::DEFAULT.velocity,
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
    law: None,
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
    limits: initial::limits::ANGULAR_VELOCITY,
    shape: Shape::Vector {
        components: XYZ,
        default: InitialCondition::DEFAULT.angular_velocity,
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
    law: None,
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
    limits: initial::limits::ANGULAR_MOMENTUM,
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
    law: None,
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
    limits: initial::limits::ORIENTATION,
    shape: Shape::Vector {
        components: YAW_PITCH_ROLL,
        default: InitialCondition::DEFAULT.orientation,
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
    law: None,
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
    shape: Shape::Seed(RandomRanges::DEFAULT.seed),
    role: Role::Random,
    comment: "roll i's draw depends on (seed, i) alone",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Seed(s.random.seed),
    scan: None,
};

/// A random range's bounds are checked against the initial condition's range.
const fn random_range(limits: Limits, default: [f64; 2], comment: &'static str) -> Spec {
    Spec {
        limits,
        shape: Shape::Range(default),
        role: Role::Random,
        comment,
        labels: &[],
        list_position: u8::MAX,
        nudge: None,
        acts_mid_roll: false,
        law: None,
        read: |_| Value::Absent,
        scan: None,
    }
}

pub(crate) const RANDOM_HEIGHT: Spec = Spec {
    read: |s| Value::Range(s.random.height),
    ..random_range(
        initial::limits::RANDOM_HEIGHT,
        RandomRanges::DEFAULT.height,
        "cm, uniform in [low, high]",
    )
};

pub(crate) const RANDOM_VELOCITY: Spec = Spec {
    read: |s| Value::Range(s.random.velocity),
    ..random_range(
        initial::limits::RANDOM_VELOCITY,
        RandomRanges::DEFAULT.velocity,
        "cm/s, each component uniform in [low, high]",
    )
};

pub(crate) const RANDOM_ANGULAR_VELOCITY: Spec = Spec {
    read: |s| Value::Range(s.random.angular_velocity),
    ..random_range(
        initial::limits::RANDOM_ANGULAR_VELOCITY,
        RandomRanges::DEFAULT.angular_velocity,
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
    shape: Shape::Flag(RandomRanges::DEFAULT.random_orientation),
    role: Role::Random,
    comment: "true: orientation uniform over all rotations",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Flag(s.random.random_orientation),
    scan: None,
};

pub(crate) const ORIENTATION_SPREAD: Spec = Spec {
    limits: initial::limits::ORIENTATION_SPREAD,
    shape: Shape::Number(RandomRanges::DEFAULT.orientation_spread),
    role: Role::Random,
    comment: "°, turned by a uniform rotation of at most this (0 fixed, 180 any)",
    labels: &[],
    list_position: u8::MAX,
    nudge: None,
    acts_mid_roll: false,
    law: None,
    read: |s| Value::Number(s.random.orientation_spread),
    scan: None,
};

/// Every value of a setup, in the order a preset file lists them.
pub static ALL: [&Spec; 52] = [
    &KIND,
    &DIE_HEIGHT,
    &DENSITY,
    &VERTICES,
    &ROUNDING,
    &VERTEX_ROUNDING,
    &WORN_FACE,
    &WORN_ROUNDING,
    &BUBBLE_RADIUS,
    &BUBBLE_TOWARD,
    &BUBBLE_OFFSET,
    &POINT_MASS,
    &POINT_MASS_TOWARD,
    &POINT_MASS_OFFSET,
    &SHAVE_FACE,
    &SHAVE_DEPTH,
    &HALF_SIZES,
    &CORNER_RADIUS,
    &PIP_DIAMETER,
    &PIP_DEPTH,
    &CORNER_MASS,
    &EXTRA_CORNER_MASS,
    &STIFFNESS,
    &DAMPING,
    &FRICTION,
    &FRICTION_LAW,
    &CONTACT,
    &STATIC_FRICTION,
    &RESTITUTION,
    &TANGENTIAL_STIFFNESS_RATIO,
    &FACE_RESTITUTION,
    &TABLE_MASS,
    &TABLE_STIFFNESS,
    &TABLE_DAMPING,
    &TILT,
    &TILT_DIRECTION,
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
    &ORIENTATION_SPREAD,
];

/// A number in a text table: as written in a preset, without a trailing `.0`.
fn number_text(x: f64) -> String {
    format!("{x}")
}

/// The table of preset keys in docs/presets.md, one line per row: key, unit, allowed range,
/// default and meaning. The repository's docs test keeps that copy equal to this.
pub fn markdown_table() -> String {
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
            Shape::Optional { absent } => (range_text(&spec.limits), format!("not given: {absent}")),
            Shape::List { width: 1, most } => (
                format!("{} each, up to {most} (one per vertex)", range_text(&spec.limits)),
                "none".to_string(),
            ),
            Shape::List { most, .. } => (
                format!(
                    "`[x, y, z]`, each {}, 4 to {most} of them",
                    range_text(&spec.limits)
                ),
                "none".to_string(),
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

fn range_text(l: &Limits) -> String {
    format!("{} to {}", number_text(l.min), number_text(l.max))
}

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
        setup.params.validate().unwrap();
        setup.initial.validate().unwrap();
        setup.random.validate().unwrap();
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
    fn each_row_names_the_law_the_physics_reads_it_under() {
        for spec in ALL {
            let law = GroundKey::named(spec.key()).map(|k| k.law());
            assert_eq!(spec.law, law, "{}", spec.key());
            for contact in [ContactLaw::Paper, ContactLaw::SpringFriction] {
                let mut ground = Params::DEFAULT.ground;
                ground.contact = contact;
                assert_eq!(
                    ground.reads(spec.key()),
                    spec.law.is_none_or(|l| l == contact),
                    "{}",
                    spec.key()
                );
            }
        }
    }
}
