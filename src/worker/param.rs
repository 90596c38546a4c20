//! The tunable values of a setup, as the explorer lists and changes them.
//!
//! Each value reads its unit and allowed range from the physics [`Limits`], so the range a
//! user sees is the range the model checks.

use crate::experiment::ScanKey;
use crate::physics::initial::{ANGULAR_VELOCITY, HEIGHT, ORIENTATION, VELOCITY};
use crate::physics::params::{CORNER_MASS, DAMPING, DT, FRICTION, GRAVITY, HALF_SIZE, STIFFNESS};
use crate::physics::{InitialCondition, Limits, ParamError, Params};

/// One tunable value. Vector-valued fields are listed per component (0 = x, 1 = y, 2 = z;
/// for the orientation 0 = yaw, 1 = pitch, 2 = roll).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Param {
    /// dyn/cm per corner, k.
    Stiffness,
    /// s/cm, γ.
    Damping,
    /// μ, dimensionless.
    Friction,
    /// cm, initial centre-of-mass height.
    Height,
    /// rad/s, initial angular velocity component.
    Spin(u8),
    /// cm/s, initial velocity component.
    Velocity(u8),
    /// °, initial yaw / pitch / roll.
    Orientation(u8),
    /// s, Δt.
    Dt,
    /// cm/s², g.
    Gravity,
    /// cm, a.
    HalfSize,
    /// g, m.
    CornerMass,
}

/// Every tunable value, in the order the parameter list shows them.
pub const ALL: [Param; 17] = [
    Param::Stiffness,
    Param::Damping,
    Param::Friction,
    Param::Height,
    Param::Spin(0),
    Param::Spin(1),
    Param::Spin(2),
    Param::Velocity(0),
    Param::Velocity(1),
    Param::Velocity(2),
    Param::Orientation(0),
    Param::Orientation(1),
    Param::Orientation(2),
    Param::Dt,
    Param::Gravity,
    Param::HalfSize,
    Param::CornerMass,
];

/// How a value moves under ←/→: by a fixed amount, or by a factor for values that span
/// decades (stiffness, Δt, mass), where equal ratios are the natural steps.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Nudge {
    Add { fine: f64, coarse: f64 },
    Times { fine: f64, coarse: f64 },
}

impl Param {
    /// Short label for the list, in the model's words.
    pub fn label(self) -> &'static str {
        match self {
            Param::Stiffness => "stiffness k",
            Param::Damping => "damping γ",
            Param::Friction => "friction μ",
            Param::Height => "drop height",
            Param::Spin(0) => "spin ωx",
            Param::Spin(1) => "spin ωy",
            Param::Spin(_) => "spin ωz",
            Param::Velocity(0) => "velocity vx",
            Param::Velocity(1) => "velocity vy",
            Param::Velocity(_) => "velocity vz",
            Param::Orientation(0) => "yaw",
            Param::Orientation(1) => "pitch",
            Param::Orientation(_) => "roll",
            Param::Dt => "time step Δt",
            Param::Gravity => "gravity g",
            Param::HalfSize => "half size a",
            Param::CornerMass => "corner mass m",
        }
    }

    /// The preset key of this value, as `--set` takes it (`initial.velocity.x` names a component).
    pub fn key(self) -> String {
        match self {
            Param::Spin(i) | Param::Velocity(i) => {
                format!("{}.{}", self.limits().key, ["x", "y", "z"][i as usize % 3])
            }
            Param::Orientation(i) => format!(
                "{}.{}",
                self.limits().key,
                ["yaw", "pitch", "roll"][i as usize % 3]
            ),
            _ => self.limits().key.to_string(),
        }
    }

    pub fn limits(self) -> Limits {
        match self {
            Param::Stiffness => STIFFNESS,
            Param::Damping => DAMPING,
            Param::Friction => FRICTION,
            Param::Height => HEIGHT,
            Param::Spin(_) => ANGULAR_VELOCITY,
            Param::Velocity(_) => VELOCITY,
            Param::Orientation(_) => ORIENTATION,
            Param::Dt => DT,
            Param::Gravity => GRAVITY,
            Param::HalfSize => HALF_SIZE,
            Param::CornerMass => CORNER_MASS,
        }
    }

    /// Ground values act on the running roll at once; every other value defines a new roll.
    pub fn acts_mid_roll(self) -> bool {
        matches!(self, Param::Stiffness | Param::Damping | Param::Friction)
    }

    /// Part of the initial condition: changing it makes a roll of its own.
    pub fn is_initial_condition(self) -> bool {
        matches!(
            self,
            Param::Height | Param::Spin(_) | Param::Velocity(_) | Param::Orientation(_)
        )
    }

    /// The scan key that reads and writes this value: fields are mapped in one place.
    pub fn scan_key(self) -> &'static ScanKey {
        let key = self.key();
        ScanKey::all()
            .iter()
            .find(|k| k.key == key)
            .expect("every tunable value is a numeric setup key")
    }

    pub fn get(self, params: &Params, initial: &InitialCondition) -> f64 {
        self.scan_key().get(params, initial)
    }

    /// Sets the value after checking it against its range, and the start it gives against
    /// the table (no corner inside it); on error nothing changes.
    pub fn set(
        self,
        params: &mut Params,
        initial: &mut InitialCondition,
        value: f64,
    ) -> Result<(), ParamError> {
        let key = self.scan_key();
        key.check(value)?;
        let (mut p, mut ic) = (*params, *initial);
        key.set(&mut p, &mut ic, value);
        ic.check_clear_of_table(&p)?;
        (*params, *initial) = (p, ic);
        Ok(())
    }

    fn nudge(self) -> Nudge {
        match self {
            Param::Stiffness | Param::Dt | Param::CornerMass => Nudge::Times {
                fine: 1.1,
                coarse: 2.0,
            },
            Param::Damping => Nudge::Add {
                fine: 0.0005,
                coarse: 0.005,
            },
            Param::Friction => Nudge::Add {
                fine: 0.05,
                coarse: 0.5,
            },
            Param::Height => Nudge::Add {
                fine: 0.5,
                coarse: 5.0,
            },
            Param::Spin(_) => Nudge::Add {
                fine: 1.0,
                coarse: 10.0,
            },
            Param::Velocity(_) => Nudge::Add {
                fine: 5.0,
                coarse: 50.0,
            },
            Param::Orientation(_) => Nudge::Add {
                fine: 5.0,
                coarse: 45.0,
            },
            Param::Gravity => Nudge::Add {
                fine: 10.0,
                coarse: 100.0,
            },
            Param::HalfSize => Nudge::Add {
                fine: 0.05,
                coarse: 0.5,
            },
        }
    }

    /// The value one step up (`steps > 0`) or down from `value`, kept inside the range.
    ///
    /// Additive steps land on multiples of the step, so repeated presses give round numbers.
    pub fn nudged(self, value: f64, steps: i32, coarse: bool) -> f64 {
        let next = match self.nudge() {
            Nudge::Add { fine, coarse: big } => {
                let step = if coarse { big } else { fine };
                let n = (value / step).round() + steps as f64;
                // Round away representation noise such as 0.30000000000000004.
                let v = n * step;
                (v * 1e9).round() / 1e9
            }
            Nudge::Times { fine, coarse: big } => {
                let factor: f64 = if coarse { big } else { fine };
                let v = value * factor.powi(steps);
                let digits = 10f64.powf(v.abs().log10().floor() - 2.0);
                (v / digits).round() * digits
            }
        };
        let limits = self.limits();
        if next.is_finite() {
            next.clamp(limits.min, limits.max)
        } else {
            value
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_value_round_trips_through_set_and_get() {
        for p in ALL {
            let mut params = Params::default();
            let mut initial = InitialCondition::default();
            let l = p.limits();
            let v = l.min + 0.25 * (l.max - l.min);
            p.set(&mut params, &mut initial, v).unwrap();
            assert_eq!(p.get(&params, &initial), v, "{p:?}");
            assert!(p.set(&mut params, &mut initial, l.max * 2.0 + 1.0).is_err());
            assert_eq!(
                p.get(&params, &initial),
                v,
                "a refused value leaves {p:?} unchanged"
            );
        }
    }

    #[test]
    fn keys_name_components() {
        assert_eq!(Param::Spin(2).key(), "initial.angular_velocity.z");
        assert_eq!(Param::Orientation(1).key(), "initial.orientation.pitch");
        let mut params = Params::default();
        let mut initial = InitialCondition::default();
        let e = Param::Velocity(1)
            .set(&mut params, &mut initial, 1e9)
            .unwrap_err();
        assert_eq!(e.key, "initial.velocity.y");
    }

    #[test]
    fn spin_stated_as_momentum_is_shown_and_edited_as_velocity() {
        let params = Params::default();
        let mut initial = InitialCondition {
            angular_momentum: Some([16.0 / 3.0 * 2.0, 0.0, 0.0]),
            ..Default::default()
        };
        assert_eq!(Param::Spin(0).get(&params, &initial), 2.0);
        Param::Spin(1)
            .set(&mut params.clone(), &mut initial, 5.0)
            .unwrap();
        assert_eq!(initial.angular_momentum, None);
        assert_eq!(initial.angular_velocity, [2.0, 5.0, 0.0]);
    }

    #[test]
    fn nudges_step_and_stay_in_range() {
        assert_eq!(Param::Friction.nudged(1.2, 1, false), 1.25);
        assert_eq!(Param::Friction.nudged(1.2, -1, true), 0.5);
        assert_eq!(Param::Friction.nudged(0.1, -1, true), 0.0);
        assert_eq!(Param::Friction.nudged(4.9, 3, true), FRICTION.max);
        assert_eq!(Param::Stiffness.nudged(500_000.0, 1, true), 1_000_000.0);
        assert_eq!(Param::Stiffness.nudged(500_000.0, 1, false), 550_000.0);
        assert_eq!(Param::Dt.nudged(DT.max, 1, true), DT.max);
        assert_eq!(Param::Damping.nudged(0.1, 1, false), DAMPING.max);
    }
}
