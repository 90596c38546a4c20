//! `--set KEY=VALUE` overrides, applied after a preset is loaded and checked like a file.

use super::contents::Preset;
use super::error::PresetError;
use crate::keys::ScanKey;
use crate::number::fmt_exact;
use crate::registry::{self, Value};
use dicesim_physics::{ContactLaw, GroundKey};

impl Preset {
    /// Applies one `--set KEY=VALUE` (dotted key as in a file; the value is read as a TOML
    /// value, a bare word as a string). On error `self` is unchanged. Returns what it did
    /// beyond setting the key, for the user to be told: choosing another contact law with
    /// `ground.contact` drops the keys of the law it leaves (docs/presets.md), and the note
    /// names each one that held a value of its own.
    pub(crate) fn apply_override(&mut self, key: &str, value: &str) -> Result<Option<String>, PresetError> {
        let err = |message: String| PresetError::Override {
            key: key.to_string(),
            message,
        };
        if let Ok(number) = value.parse::<f64>()
            && !number.is_finite()
        {
            return Err(err(format!("`{value}` is not a finite number")));
        }
        // A whole number past TOML's integers (2⁶³ − 1) would read as a word: say what it is.
        if value.parse::<i64>().is_err()
            && let Ok(big) = value.parse::<u64>()
        {
            return Err(err(format!(
                "{big} is above 2⁶³ − 1 = {}, the largest whole number a preset holds",
                i64::MAX
            )));
        }
        let mut parsed = parse_override_value(value);
        // TOML's integers have no −0: `-0` is the number −0 as typed, so a refusal echoes it.
        if parsed == toml::Value::Integer(0) && value.trim_start().starts_with('-') {
            parsed = toml::Value::Float(-0.0);
        }
        // A key the contact law does not read is refused, whatever the value.
        if let Some(unread) = GroundKey::named(key).filter(|k| k.law() != self.ground.contact) {
            return Err(err(unread.why_unread(self.ground.contact)));
        }
        // One component of a vector (`initial.velocity.y=5`) is set through its registry row.
        if let Ok(scan) = ScanKey::named(key)
            && !scan.spec.components().is_empty()
        {
            let number = match parsed {
                toml::Value::Float(x) => x,
                toml::Value::Integer(i) => i as f64,
                _ => return Err(err(format!("expected a number, found `{value}`"))),
            };
            let mut updated = self.clone();
            let mut params = updated.params();
            scan.set(&mut params, &mut updated.initial, number);
            updated.set_params(params);
            updated.validate()?;
            *self = updated;
            return Ok(None);
        }
        let mut table = toml::Table::try_from(&*self).map_err(|e| err(e.to_string()))?;
        let path: Vec<&str> = key.split('.').collect();
        if path.iter().any(|p| p.is_empty()) {
            return Err(err("empty key segment".to_string()));
        }
        let (last, parents) = path.split_last().expect("split on '.' yields at least one part");
        // One component of a vector, by the name basin axes and errors use for it.
        let mut component = None;
        if let Some(toml::Value::Array(items)) = value_at(&mut table, parents) {
            let names = component_names(parents);
            let Some(i) = names.iter().position(|n| n == last) else {
                return Err(err(format!(
                    "`{}` has the components {}",
                    parents.join("."),
                    names.join(", ")
                )));
            };
            if i >= items.len() {
                return Err(err(format!(
                    "`{}` has fewer than {} values",
                    parents.join("."),
                    i + 1
                )));
            }
            items[i] = parsed.clone();
            component = Some(i);
            if let (["initial", form], Some(toml::Value::Table(initial))) =
                (parents, table.get_mut("initial"))
            {
                match *form {
                    "angular_momentum" => drop(initial.remove("angular_velocity")),
                    "angular_velocity" => drop(initial.remove("angular_momentum")),
                    _ => {}
                }
            }
        }
        let mut node = &mut table;
        for (depth, part) in parents.iter().enumerate().filter(|_| component.is_none()) {
            let entry = node
                .entry(part.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            node = match entry {
                toml::Value::Table(t) => t,
                _ => return Err(err(format!("`{}` is not a table", parents[..=depth].join(".")))),
            };
        }
        // Spin is given one way, and the die's size: setting one form replaces the other.
        if component.is_none() && parents == ["initial"] {
            match *last {
                "angular_momentum" => drop(node.remove("angular_velocity")),
                "angular_velocity" => drop(node.remove("angular_momentum")),
                _ => {}
            }
        }
        if component.is_none() && parents == ["die"] {
            match *last {
                "half_size" => drop(node.remove("half_sizes")),
                "half_sizes" => drop(node.remove("half_size")),
                _ => {}
            }
        }
        // Another contact law: the keys only the law it leaves reads go, with a note.
        let mut note = None;
        if key == "ground.contact"
            && let Ok(law) = parsed.clone().try_into::<ContactLaw>()
            && law != self.ground.contact
        {
            note = self.drop_unread_by(law, node, key, value);
        }
        if component.is_none() {
            node.insert(last.to_string(), parsed);
        }
        let updated: Preset = serde_path_to_error::deserialize(toml::Value::Table(table)).map_err(|e| {
            // toml appends the table path on a second line; the key is already named.
            let inner = e.inner().to_string();
            let first = inner.lines().next().unwrap_or_default();
            err(first.split(" in `").next().unwrap_or(first).trim().to_string())
        })?;
        updated.validate()?;
        *self = updated;
        Ok(note)
    }

    /// Removes from `ground` (this preset's `[ground]` as TOML) every key `law` does not read,
    /// and says which of them held a value other than its default: `ground.contact=paper
    /// drops ground.restitution = 0.2375 …`; `None` when nothing of note was dropped.
    fn drop_unread_by(
        &self,
        law: ContactLaw,
        ground: &mut toml::Table,
        key: &str,
        value: &str,
    ) -> Option<String> {
        let setup = self.values();
        let mut dropped = Vec::new();
        for spec in registry::ALL.iter().filter(|s| s.law.is_some_and(|l| l != law)) {
            let name = spec.key().rsplit('.').next().unwrap_or_default();
            ground.remove(name);
            let held = (spec.read)(&setup);
            if held != spec.default_value() {
                let shown = match held {
                    Value::Number(x) => fmt_exact(x),
                    Value::Name(n) => format!("\"{n}\""),
                    other => format!("{other:?}"),
                };
                dropped.push(format!("{} = {shown}", spec.key()));
            }
        }
        (!dropped.is_empty()).then(|| {
            format!(
                "{key}={value} drops {}, which the \"{}\" contact law does not read",
                dropped.join(", "),
                law.name()
            )
        })
    }

    /// Applies `KEY=VALUE` overrides in order; on any error nothing is changed.
    pub fn with_overrides<S: AsRef<str>>(&self, overrides: &[S]) -> Result<Preset, PresetError> {
        self.with_overrides_noted(overrides).map(|(p, _)| p)
    }

    /// [`Preset::with_overrides`], and the notes of what the overrides did beyond setting
    /// their keys (a law switch's dropped keys), for the user to be told.
    pub fn with_overrides_noted<S: AsRef<str>>(
        &self,
        overrides: &[S],
    ) -> Result<(Preset, Vec<String>), PresetError> {
        let mut p = self.clone();
        let mut notes = Vec::new();
        for o in overrides {
            let o = o.as_ref();
            let (key, value) = o.split_once('=').ok_or_else(|| PresetError::Override {
                key: o.to_string(),
                message: "expected KEY=VALUE".to_string(),
            })?;
            notes.extend(p.apply_override(key.trim(), value.trim())?);
        }
        Ok((p, notes))
    }
}

/// The value at `path` in `table`, if every step but the last is a table.
fn value_at<'a>(table: &'a mut toml::Table, path: &[&str]) -> Option<&'a mut toml::Value> {
    let (first, rest) = path.split_first()?;
    let mut value = table.get_mut(*first)?;
    for part in rest {
        value = value.as_table_mut()?.get_mut(*part)?;
    }
    Some(value)
}

/// What the components of the array at `parents` are called:
/// its registry row's names where it has one (`x, y, z`, `yaw, pitch, roll`, the corners
/// `1`…`8`), so errors, scan keys and basin axes agree; `x, y, z` for any other array.
fn component_names(parents: &[&str]) -> &'static [&'static str] {
    match registry::find(&parents.join(".")).map(|spec| spec.components()) {
        Some(names) if !names.is_empty() => names,
        _ => &["x", "y", "z"],
    }
}

/// A `--set` value as TOML (`600000`, `[10,0,3]`, `true`, `"x"`); anything that does not
/// parse (a bare word such as `whole-die-norm`) is taken as a string.
fn parse_override_value(value: &str) -> toml::Value {
    let doc = format!("v = {value}");
    match doc.parse::<toml::Table>() {
        Ok(mut t) => t
            .remove("v")
            .unwrap_or_else(|| toml::Value::String(value.to_string())),
        Err(_) => toml::Value::String(value.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_physics::FrictionLaw;

    #[test]
    fn overrides_set_nested_values() {
        let p = Preset::default()
            .with_overrides(&[
                "ground.stiffness=600000",
                "initial.angular_velocity=[10,0,3]",
                "ground.friction_law=whole-die-norm",
                "integrator.stop_energy=\"point-masses\"",
            ])
            .unwrap();
        assert_eq!(p.ground.stiffness, 600000.0);
        assert_eq!(p.initial.angular_velocity, [10.0, 0.0, 3.0]);
        assert_eq!(p.ground.friction_law, FrictionLaw::WholeDieNorm);
    }

    #[test]
    fn a_key_the_contact_law_does_not_read_is_refused_and_changes_nothing() {
        let paper = Preset::default();
        let e = paper.with_overrides(&["ground.restitution=0.8"]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--set ground.restitution: the \"paper\" contact law does not read it (its restitution \
             follows from `ground.damping` and falls with impact speed); it is read under \
             `ground.contact = \"spring-friction\"`"
        );
        // The law first, then its keys; the paper's own are then refused, even at their default.
        let spring = paper
            .with_overrides(&[
                "ground.contact=spring-friction",
                "ground.restitution=0.8",
                "ground.tilt=20",
            ])
            .unwrap();
        assert_eq!((spring.ground.restitution, spring.ground.tilt), (0.8, 20.0));
        for key in ["ground.damping=0.005", "ground.friction_law=per-corner"] {
            let e = spring.with_overrides(&[key]).unwrap_err();
            assert!(
                e.to_string()
                    .contains("the \"spring-friction\" contact law does not read it"),
                "{key}: {e}"
            );
        }
        // Choosing the other law drops the keys of the law left, naming those with values
        // of their own (issue 49, defect 5): both ways, whatever their values.
        let sticky = paper
            .with_overrides(&["ground.damping=0.02", "ground.friction_law=whole-die-norm"])
            .unwrap();
        let (switched, notes) = sticky
            .with_overrides_noted(&["ground.contact=spring-friction"])
            .unwrap();
        assert_eq!(
            notes,
            [
                "ground.contact=spring-friction drops ground.damping = 0.02, ground.friction_law = \
              \"whole-die-norm\", which the \"spring-friction\" contact law does not read"
            ]
        );
        assert_eq!(switched.ground.contact, ContactLaw::SpringFriction);
        let d = dicesim_physics::Params::DEFAULT.ground;
        assert_eq!(
            (switched.ground.damping, switched.ground.friction_law),
            (d.damping, d.friction_law)
        );
        let (back, notes) = spring
            .with_overrides_noted(&["ground.contact=paper", "ground.damping=0.01"])
            .unwrap();
        assert_eq!(
            notes,
            [
                "ground.contact=paper drops ground.restitution = 0.8, ground.tilt = 20, which the \
              \"paper\" contact law does not read"
            ]
        );
        assert_eq!(
            (back.ground.restitution, back.ground.tilt, back.ground.damping),
            (d.restitution, d.tilt, 0.01)
        );
        // Keys at their defaults go without a word; the same law again changes nothing.
        assert!(
            paper
                .with_overrides_noted(&["ground.contact=spring-friction"])
                .unwrap()
                .1
                .is_empty()
        );
        assert!(
            spring
                .with_overrides_noted(&["ground.contact=spring-friction"])
                .unwrap()
                .1
                .is_empty()
        );
    }

    #[test]
    fn a_component_is_set_alone() {
        let p = Preset::default();
        let q = p
            .with_overrides(&["initial.velocity.y=7", "initial.orientation.pitch=-30"])
            .unwrap();
        assert_eq!(
            q.initial.velocity,
            [p.initial.velocity[0], 7.0, p.initial.velocity[2]]
        );
        assert_eq!(q.initial.orientation[1], -30.0);
        let e = p.with_overrides(&["initial.velocity.z=20000"]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "`initial.velocity.z` = 20000 is outside the allowed range -10000 to 10000 cm/s"
        );
        let e = p.with_overrides(&["initial.velocity.x=fast"]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--set initial.velocity.x: expected a number, found `fast`"
        );
    }

    #[test]
    fn angular_momentum_replaces_angular_velocity_and_back() {
        let p = Preset::default()
            .with_overrides(&["initial.angular_momentum=[0,-100,0]"])
            .unwrap();
        assert_eq!(p.initial.angular_momentum, Some([0.0, -100.0, 0.0]));
        let q = p.with_overrides(&["initial.angular_velocity=[1,2,3]"]).unwrap();
        assert_eq!(q.initial.angular_momentum, None);
        assert_eq!(q.initial.angular_velocity, [1.0, 2.0, 3.0]);
    }

    #[test]
    fn bad_overrides_name_the_key_and_change_nothing() {
        let p = Preset::default();
        let e = p.with_overrides(&["ground.stifness=1"]).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("--set ground.stifness: unknown field `stifness`"),
            "{e}"
        );
        let e = p.with_overrides(&["ground.friction=high"]).unwrap_err();
        assert!(e.to_string().contains("invalid type: string \"high\""), "{e}");
        let e = p.with_overrides(&["ground.friction=9"]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "`ground.friction` = 9 is outside the allowed range 0 to 5"
        );
        let e = p.with_overrides(&["format.x=1"]).unwrap_err();
        assert!(e.to_string().contains("`format` is not a table"), "{e}");
        let e = p.with_overrides(&["initial.velocity=[1,2]"]).unwrap_err();
        assert!(e.to_string().contains("invalid length 2"), "{e}");
        assert!(p.with_overrides(&["nonsense"]).is_err());
    }

    #[test]
    fn one_name_per_value_and_clear_numbers() {
        let p = Preset::default();
        let q = p
            .with_overrides(&["initial.velocity.y=7", "initial.orientation.pitch=30"])
            .unwrap();
        assert_eq!(q.initial.velocity[1], 7.0);
        assert_eq!(q.initial.orientation[1], 30.0);
        let e = p.with_overrides(&["initial.orientation.yaw=400"]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "`initial.orientation.yaw` = 400 is outside the allowed range -360 to 360 °"
        );
        let e = p.with_overrides(&["initial.orientation.x=1"]).unwrap_err();
        assert!(
            e.to_string().contains("has the components yaw, pitch, roll"),
            "{e}"
        );
        // A per-corner key's components are the corners 1..8: `.x` was taken as corner 1,
        // and `.0` was refused with "the components x, y, z".
        for bad in ["0", "x", "9"] {
            let e = p
                .with_overrides(&[format!("die.extra_corner_mass.{bad}=5")])
                .unwrap_err();
            assert!(
                e.to_string()
                    .ends_with("`die.extra_corner_mass` has the components 1, 2, 3, 4, 5, 6, 7, 8"),
                "{bad}: {e}"
            );
        }
        let q = p.with_overrides(&["die.extra_corner_mass.8=5"]).unwrap();
        assert_eq!(q.die.extra_corner_mass, [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 5.0]);
        for bad in ["1e309", "NaN", "-inf"] {
            let e = p.with_overrides(&[format!("ground.friction={bad}")]).unwrap_err();
            assert_eq!(
                e.to_string(),
                format!("--set ground.friction: `{bad}` is not a finite number")
            );
        }
        let e = p.with_overrides(&["ground.friction=1e308"]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "`ground.friction` = 1e308 is outside the allowed range 0 to 5"
        );
        let e = p.with_overrides(&["random.height=[5,1]"]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "`random.height` = [5, 1]: the low end is above the high end"
        );
    }
}

/// Refuses the first of `overrides` that a command cannot apply, before any work: a command
/// that replaces part of the setup (a map's axes, an experiment's die, a throw it draws
/// itself) says so rather than drop a `--set`. `why_not` gets each override's key as given
/// (`die.corner_radius`, `initial.velocity.y`) and returns why the command does not apply
/// it, or `None` where it does; the error names the key and that reason.
pub fn refuse_unapplied<S: AsRef<str>>(
    overrides: &[S],
    why_not: impl Fn(&str) -> Option<String>,
) -> Result<(), PresetError> {
    for o in overrides {
        let o = o.as_ref();
        let key = o.split_once('=').map_or(o, |(key, _)| key).trim();
        if let Some(why) = why_not(key) {
            return Err(PresetError::Override {
                key: key.to_string(),
                message: why,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod refuse_tests {
    use super::*;

    #[test]
    fn the_first_override_a_command_cannot_apply_is_named_with_its_reason() {
        let why_not = |key: &str| {
            key.starts_with("random.")
                .then(|| "this command rolls one fixed start".to_string())
        };
        let sets = ["ground.friction=0.3", " random.height = [1, 2]", "random.seed=4"];
        let e = refuse_unapplied(&sets, why_not).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--set random.height: this command rolls one fixed start"
        );
        assert!(refuse_unapplied(&sets[..1], why_not).is_ok());
        assert!(refuse_unapplied::<&str>(&[], why_not).is_ok());
    }
}
