//! The numeric setup values an experiment can scan, by their dotted preset key.
//!
//! This is the one place that maps a key such as `initial.angular_velocity.x` or
//! `ground.friction` to the field it sets; ranges and units come from the physics layer's
//! [`Limits`], so a scan is checked exactly as a preset is.

use super::Error;
use crate::physics::initial::{ANGULAR_MOMENTUM, ANGULAR_VELOCITY, HEIGHT, ORIENTATION, VELOCITY};
use crate::physics::params::{
    CORNER_MASS, DAMPING, DT, FRICTION, GRAVITY, HALF_SIZE, MAX_TIME, STIFFNESS, STOP_ENERGY_FRACTION,
};
use crate::physics::{InitialCondition, Limits, ParamError, Params};

/// Which field a key sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Field {
    HalfSize,
    CornerMass,
    Stiffness,
    Damping,
    Friction,
    Gravity,
    Dt,
    StopEnergyFraction,
    MaxTime,
    Height,
    Velocity(usize),
    AngularVelocity(usize),
    AngularMomentum(usize),
    /// 0 = yaw, 1 = pitch, 2 = roll.
    Orientation(usize),
}

/// A scannable value: its full key (components included), unit, allowed range and setter.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanKey {
    /// The full dotted key, e.g. `initial.angular_velocity.x`.
    pub key: String,
    /// The field's limits (`limits.key` names the whole vector for components).
    pub limits: Limits,
    field: Field,
}

const SCALARS: [(Limits, Field); 10] = [
    (HALF_SIZE, Field::HalfSize),
    (CORNER_MASS, Field::CornerMass),
    (STIFFNESS, Field::Stiffness),
    (DAMPING, Field::Damping),
    (FRICTION, Field::Friction),
    (GRAVITY, Field::Gravity),
    (DT, Field::Dt),
    (STOP_ENERGY_FRACTION, Field::StopEnergyFraction),
    (MAX_TIME, Field::MaxTime),
    (HEIGHT, Field::Height),
];

const XYZ: [&str; 3] = ["x", "y", "z"];
const YAW_PITCH_ROLL: [&str; 3] = ["yaw", "pitch", "roll"];

/// A vector-valued field: one key per component.
struct VectorField {
    limits: Limits,
    components: [&'static str; 3],
    field: fn(usize) -> Field,
}

const VECTORS: [VectorField; 4] = [
    VectorField {
        limits: VELOCITY,
        components: XYZ,
        field: Field::Velocity,
    },
    VectorField {
        limits: ANGULAR_VELOCITY,
        components: XYZ,
        field: Field::AngularVelocity,
    },
    VectorField {
        limits: ANGULAR_MOMENTUM,
        components: XYZ,
        field: Field::AngularMomentum,
    },
    VectorField {
        limits: ORIENTATION,
        components: YAW_PITCH_ROLL,
        field: Field::Orientation,
    },
];

impl ScanKey {
    /// Every scannable key, in preset order (for help texts and pickers).
    pub fn all() -> &'static [ScanKey] {
        static ALL: std::sync::LazyLock<Vec<ScanKey>> = std::sync::LazyLock::new(ScanKey::build_all);
        &ALL
    }

    fn build_all() -> Vec<ScanKey> {
        let mut keys: Vec<ScanKey> = SCALARS
            .iter()
            .map(|&(limits, field)| ScanKey {
                key: limits.key.to_string(),
                limits,
                field,
            })
            .collect();
        for v in &VECTORS {
            for (i, name) in v.components.iter().enumerate() {
                keys.push(ScanKey {
                    key: format!("{}.{name}", v.limits.key),
                    limits: v.limits,
                    field: (v.field)(i),
                });
            }
        }
        keys
    }

    /// The key named `key`; an unknown or non-numeric key is an error listing the valid ones.
    pub fn parse(key: &str) -> Result<ScanKey, Error> {
        let all = Self::all();
        if let Some(k) = all.iter().find(|k| k.key == key) {
            return Ok(k.clone());
        }
        let hint = if VECTORS.iter().any(|v| v.limits.key == key) {
            format!(" (name one component, e.g. `{key}.x`)")
        } else {
            String::new()
        };
        Err(Error::UnknownKey {
            key: key.to_string(),
            hint,
            known: all.iter().map(|k| k.key.as_str()).collect::<Vec<_>>().join(", "),
        })
    }

    /// Unit as shown to users (`""` for dimensionless).
    pub fn unit(&self) -> &'static str {
        self.limits.unit
    }

    /// `key (unit)`, or the key alone for dimensionless values: an axis title.
    pub fn label(&self) -> String {
        if self.unit().is_empty() {
            self.key.clone()
        } else {
            format!("{} ({})", self.key, self.unit())
        }
    }

    /// Checks `value` against the field's allowed range, naming this key in the error.
    pub fn check(&self, value: f64) -> Result<(), ParamError> {
        self.limits.check(value).map_err(|mut e| {
            e.key = self.key.clone();
            e
        })
    }

    /// The field's current value. A spin stated in the other form is converted (with the
    /// die's inertia), so `initial.angular_velocity.x` always reads ω_x.
    pub fn get(&self, params: &Params, initial: &InitialCondition) -> f64 {
        match self.field {
            Field::HalfSize => params.die.half_size,
            Field::CornerMass => params.die.corner_mass,
            Field::Stiffness => params.ground.stiffness,
            Field::Damping => params.ground.damping,
            Field::Friction => params.ground.friction,
            Field::Gravity => params.world.gravity,
            Field::Dt => params.integrator.dt,
            Field::StopEnergyFraction => params.integrator.stop_energy_fraction,
            Field::MaxTime => params.integrator.max_time,
            Field::Height => initial.height,
            Field::Velocity(i) => initial.velocity[i],
            Field::AngularVelocity(i) => initial.angular_velocity_for(params.inertia())[i],
            Field::AngularMomentum(i) => initial.angular_momentum_for(params.inertia())[i],
            Field::Orientation(i) => initial.orientation[i],
        }
    }

    /// Sets the field to `value` (not range-checked: see [`ScanKey::check`]).
    ///
    /// Spin is stated one way in an initial condition: setting a component of one form first
    /// restates the other form's spin in this one (with the die's inertia), so the other two
    /// components keep their physical value.
    pub fn set(&self, params: &mut Params, initial: &mut InitialCondition, value: f64) {
        match self.field {
            Field::HalfSize => params.die.half_size = value,
            Field::CornerMass => params.die.corner_mass = value,
            Field::Stiffness => params.ground.stiffness = value,
            Field::Damping => params.ground.damping = value,
            Field::Friction => params.ground.friction = value,
            Field::Gravity => params.world.gravity = value,
            Field::Dt => params.integrator.dt = value,
            Field::StopEnergyFraction => params.integrator.stop_energy_fraction = value,
            Field::MaxTime => params.integrator.max_time = value,
            Field::Height => initial.height = value,
            Field::Velocity(i) => initial.velocity[i] = value,
            Field::AngularVelocity(i) => {
                let mut w: [f64; 3] = initial.angular_velocity_for(params.inertia()).into();
                w[i] = value;
                initial.angular_velocity = w;
                initial.angular_momentum = None;
            }
            Field::AngularMomentum(i) => {
                let mut l: [f64; 3] = initial.angular_momentum_for(params.inertia()).into();
                l[i] = value;
                initial.angular_momentum = Some(l);
            }
            Field::Orientation(i) => initial.orientation[i] = value,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_sets_its_own_field() {
        for key in ScanKey::all() {
            let (mut p, mut ic) = (Params::default(), InitialCondition::default());
            let value = 0.25 * key.limits.min + 0.75 * key.limits.max;
            key.set(&mut p, &mut ic, value);
            assert_eq!(key.get(&p, &ic), value, "{}", key.key);
            let (p0, ic0) = (Params::default(), InitialCondition::default());
            assert!(p != p0 || ic != ic0, "{} changed nothing", key.key);
            // Read the value back through the preset-shaped JSON, by the key's own path.
            let json = serde_json::json!({
                "die": p.die, "ground": p.ground, "world": p.world, "integrator": p.integrator,
                "initial": ic,
            });
            let mut node = &json;
            let mut parts = key.key.split('.').peekable();
            while let Some(part) = parts.next() {
                let index = YAW_PITCH_ROLL
                    .iter()
                    .chain(XYZ.iter())
                    .position(|n| *n == part)
                    .filter(|_| parts.peek().is_none() && node.is_array());
                node = match index {
                    Some(i) => &node[i % 3],
                    None => &node[part],
                };
            }
            assert_eq!(node.as_f64(), Some(value), "{}", key.key);
        }
    }

    #[test]
    fn spin_components_keep_the_other_axes() {
        let p = Params::default();
        let mut ic = InitialCondition {
            angular_momentum: Some([16.0 / 3.0, 32.0 / 3.0, 0.0]),
            ..Default::default()
        };
        ScanKey::parse("initial.angular_velocity.z")
            .unwrap()
            .set(&mut p.clone(), &mut ic, 5.0);
        assert_eq!(ic.angular_momentum, None);
        assert_eq!(ic.angular_velocity, [1.0, 2.0, 5.0]);
    }

    #[test]
    fn unknown_and_vector_keys_are_explained() {
        let e = ScanKey::parse("ground.stifness").unwrap_err().to_string();
        assert!(
            e.starts_with("`ground.stifness` is not a numeric setup key"),
            "{e}"
        );
        assert!(e.contains("ground.stiffness"), "{e}");
        let e = ScanKey::parse("initial.velocity").unwrap_err().to_string();
        assert!(e.contains("`initial.velocity.x`"), "{e}");
        let e = ScanKey::parse("ground.friction_law").unwrap_err().to_string();
        assert!(e.contains("not a numeric setup key"), "{e}");
    }

    #[test]
    fn range_errors_name_the_component() {
        let k = ScanKey::parse("initial.angular_velocity.x").unwrap();
        assert_eq!(
            k.check(20_000.0).unwrap_err().to_string(),
            "`initial.angular_velocity.x` = 20000 is outside the allowed range -10000 to 10000 rad/s"
        );
        assert_eq!(k.label(), "initial.angular_velocity.x (rad/s)");
        assert_eq!(
            ScanKey::parse("ground.friction").unwrap().label(),
            "ground.friction"
        );
    }
}
