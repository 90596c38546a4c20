//! The numeric setup values an experiment can scan, by their dotted preset key.
//!
//! Each key is a numeric row of the [registry](crate::registry) (a vector
//! by component): its range, unit and how it is read and set come from that row, so a scan
//! is checked exactly as a preset is.

use crate::registry::{self, Scan, Spec};
use dicesim_physics::{InitialCondition, Limits, ParamError, Params, check_setup};

/// A scan key that names no numeric setup value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("`{key}` is not a numeric setup key{hint}; known keys: {known}")]
pub struct UnknownKey {
    pub key: String,
    /// How to name it instead, when the key is a vector's (" (name one component, …)").
    pub hint: String,
    pub known: String,
}

/// A scannable value: its full key (components included), its registry row and component.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanKey {
    /// The full dotted key, e.g. `initial.angular_velocity.x`.
    pub key: String,
    /// The row it belongs to (a vector's row for each of its components).
    pub spec: &'static Spec,
    /// 0 for a scalar; the component's index for a vector.
    pub component: usize,
}

impl ScanKey {
    /// Every scannable key, in preset order (for help texts and pickers).
    pub fn all() -> &'static [ScanKey] {
        static ALL: std::sync::LazyLock<Vec<ScanKey>> = std::sync::LazyLock::new(ScanKey::build_all);
        &ALL
    }

    fn build_all() -> Vec<ScanKey> {
        let mut keys = Vec::new();
        for &spec in registry::ALL.iter().filter(|s| s.scan.is_some()) {
            match spec.components() {
                [] => keys.push(ScanKey {
                    key: spec.key().to_string(),
                    spec,
                    component: 0,
                }),
                names => keys.extend(names.iter().enumerate().map(|(component, name)| ScanKey {
                    key: format!("{}.{name}", spec.key()),
                    spec,
                    component,
                })),
            }
        }
        keys
    }

    /// The key named `key`; an unknown or non-numeric key is an error listing the valid ones.
    pub fn parse(key: &str) -> Result<ScanKey, UnknownKey> {
        Self::named(key).cloned()
    }

    /// The key named `key`, as [`ScanKey::parse`] but borrowed from [`ScanKey::all`].
    pub fn named(key: &str) -> Result<&'static ScanKey, UnknownKey> {
        let all = Self::all();
        if let Some(k) = all.iter().find(|k| k.key == key) {
            return Ok(k);
        }
        let hint = match registry::find(key) {
            Some(spec) if !spec.components().is_empty() => {
                format!(" (name one component, e.g. `{key}.{}`)", spec.components()[0])
            }
            _ => String::new(),
        };
        Err(UnknownKey {
            key: key.to_string(),
            hint,
            known: all.iter().map(|k| k.key.as_str()).collect::<Vec<_>>().join(", "),
        })
    }

    /// The row's limits (`limits.key` names the whole vector for components).
    pub fn limits(&self) -> Limits {
        self.spec.limits
    }

    /// Unit as shown to users (`""` for dimensionless).
    pub fn unit(&self) -> &'static str {
        self.spec.limits.unit
    }

    /// The key as a data file's column: its words joined by `_`, then its unit
    /// (`initial_height_cm`, `ground_friction`), as [`column_name`] names every column.
    pub fn column(&self) -> String {
        column_name(&self.key.replace('.', "_"), self.unit())
    }

    /// What the explorer calls the value, in the model's words: its parameter-list label
    /// (`spin ωy`), else its key's last part (`height` for `random.height`). Figures name
    /// their axes and legends with it, so a plot reads as the explorer does.
    pub fn words(&self) -> &str {
        match self.spec.labels.get(self.component) {
            Some(label) => label,
            None => self.key.rsplit('.').next().unwrap_or(&self.key),
        }
    }

    /// `words (unit)`, or the words alone for dimensionless values: a figure's axis title
    /// (`spin ωy (rad/s)`).
    pub fn title(&self) -> String {
        match self.unit() {
            "" => self.words().to_string(),
            unit => format!("{} ({unit})", self.words()),
        }
    }

    /// `words = value unit`: a figure's legend entry for one value of it (`drop height =
    /// 2 cm`), `value` written as the figure writes numbers.
    pub fn legend(&self, value: &str) -> String {
        match self.unit() {
            "" => format!("{} = {value}", self.words()),
            unit => format!("{} = {value} {unit}", self.words()),
        }
    }

    /// `key (unit)`, or the key alone for dimensionless values: how a table printed for a
    /// script names a column (the key it was given).
    pub fn label(&self) -> String {
        if self.unit().is_empty() {
            self.key.clone()
        } else {
            format!("{} ({})", self.key, self.unit())
        }
    }

    /// Checks `value` against the field's allowed range, naming this key in the error.
    pub fn check(&self, value: f64) -> Result<(), ParamError> {
        self.spec.check_number(&self.key, value)
    }

    /// Whether a `--set` of `key` (as given: a whole vector or one component) sets this
    /// value, so a command that sets this value itself would overwrite it.
    pub fn overlaps(&self, key: &str) -> bool {
        key == self.key || key == self.spec.key()
    }

    fn scan(&self) -> Scan {
        self.spec.scan.expect("scan keys are built from rows that scan")
    }

    /// The field's current value. A spin stated in the other form is converted (with the
    /// die's inertia), so `initial.angular_velocity.x` always reads ω_x.
    pub fn get(&self, params: &Params, initial: &InitialCondition) -> f64 {
        (self.scan().get)(params, initial, self.component)
    }

    /// Sets the field to `value` (not range-checked: see [`ScanKey::check`]).
    pub fn set(&self, params: &mut Params, initial: &mut InitialCondition, value: f64) {
        (self.scan().set)(params, initial, self.component, value)
    }

    /// Checks `value` against its range, then the setup it gives as `roll` checks its own
    /// ([`check_setup`]: a body that can exist, a key the contact law reads, a start clear of
    /// the table), then sets it; on error nothing changes.
    pub fn set_checked(
        &self,
        params: &mut Params,
        initial: &mut InitialCondition,
        value: f64,
    ) -> Result<(), ParamError> {
        self.check(value)?;
        let (mut p, mut ic) = (*params, *initial);
        self.set(&mut p, &mut ic, value);
        check_setup(&p, &ic)?;
        (*params, *initial) = (p, ic);
        Ok(())
    }
}

/// A data file's column name for a quantity `name` in `unit`: the name, then the unit in
/// letters a column name can hold (`/` as `_per_`, `²` as `2`, `·` as `_`, `°` as `deg`):
/// `velocity_x_cm_per_s`, `angular_momentum_x_g_cm2_per_s`, `yaw_deg`. A dimensionless
/// quantity (a count, a share, a friction coefficient) is its name alone.
pub fn column_name(name: &str, unit: &str) -> String {
    if unit.is_empty() {
        return name.to_string();
    }
    let unit = unit
        .replace('/', "_per_")
        .replace('²', "2")
        .replace('·', "_")
        .replace('°', "deg");
    format!("{name}_{unit}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_key_the_contact_law_does_not_read_is_refused_and_changes_nothing() {
        let (mut p, mut ic) = (Params::default(), InitialCondition::default());
        let tilt = ScanKey::named("ground.tilt").unwrap();
        let e = tilt.set_checked(&mut p, &mut ic, 10.0).unwrap_err();
        assert_eq!(e.key, "ground.tilt");
        assert!(e.to_string().contains("its table is level"), "{e}");
        assert_eq!(p.ground.tilt, 0.0, "nothing changed");
        p.ground.contact = dicesim_physics::ContactLaw::SpringFriction;
        tilt.set_checked(&mut p, &mut ic, 10.0).unwrap();
        assert_eq!(p.ground.tilt, 10.0);
        let damping = ScanKey::named("ground.damping").unwrap();
        let before = p.ground.damping;
        let e = damping.set_checked(&mut p, &mut ic, 0.01).unwrap_err();
        assert!(e.to_string().contains("its normal damping comes from"), "{e}");
        assert_eq!(p.ground.damping, before, "nothing changed");
    }

    #[test]
    fn every_key_sets_its_own_field() {
        for key in ScanKey::all() {
            let (mut p, mut ic) = (Params::default(), InitialCondition::default());
            let value = 0.25 * key.limits().min + 0.75 * key.limits().max;
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
                let index = key
                    .spec
                    .components()
                    .iter()
                    .position(|n| *n == part)
                    .filter(|_| parts.peek().is_none() && node.is_array());
                node = match index {
                    Some(i) => &node[i],
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
    fn figures_name_a_value_in_the_explorers_words_with_its_unit() {
        let spin = ScanKey::named("initial.angular_velocity.y").unwrap();
        assert_eq!(spin.words(), spin.spec.labels[1]);
        assert_eq!(spin.title(), format!("{} (rad/s)", spin.spec.labels[1]));
        // A key with no parameter-list row is named by the last part of its key.
        let max_time = ScanKey::named("integrator.max_time").unwrap();
        assert!(max_time.spec.labels.is_empty(), "no parameter-list row");
        assert_eq!(max_time.legend("2"), "max_time = 2 s");
        assert_eq!(ScanKey::named("ground.friction").unwrap().title(), "friction μ");
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

    #[test]
    fn every_key_names_a_column_with_its_unit() {
        assert_eq!(
            ScanKey::parse("initial.height").unwrap().column(),
            "initial_height_cm"
        );
        assert_eq!(
            ScanKey::parse("ground.friction").unwrap().column(),
            "ground_friction"
        );
        assert_eq!(
            ScanKey::parse("initial.angular_velocity.x").unwrap().column(),
            "initial_angular_velocity_x_rad_per_s"
        );
        assert_eq!(column_name("l", "g·cm²/s"), "l_g_cm2_per_s");
        assert_eq!(column_name("yaw", "°"), "yaw_deg");
        let columns: Vec<String> = ScanKey::all().iter().map(ScanKey::column).collect();
        for c in &columns {
            assert!(c.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_'), "{c}");
        }
        let mut unique = columns.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), columns.len());
    }
}
