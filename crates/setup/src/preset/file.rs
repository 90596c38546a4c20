//! The preset file format: reading with positions in every error, writing the whole file with
//! its unit comments.

use super::contents::{FORMAT, Preset};
use super::error::{Location, PresetError};
use crate::registry::{self, ANGULAR_MOMENTUM, ANGULAR_VELOCITY, Role, Shape, Value};
use dicesim_physics::params::{CORNERS, SIZE_TWICE};
use dicesim_physics::{InitialCondition, ParamError};
use toml::de::{DeTable, DeValue};

/// Up to this column the values stand, then the comments start (as in the shipped presets).
const COMMENT_COLUMN: usize = 34;
/// Longer lines put their comment above them.
const MAX_LINE: usize = 110;
/// Where a long description is folded onto the next line.
const FOLD_WIDTH: usize = 84;

impl Preset {
    /// Reads a preset from TOML text. `origin` names the text in errors (a file path, or
    /// `shipped/NAME.toml`). Every error names the origin, the line and column and, where it
    /// is about one key, that key; nothing is returned unless the whole file is valid.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Preset, PresetError> {
        let spanned = DeTable::parse(text).map_err(|e| syntax_error(origin, text, &e))?;
        let doc = spanned.get_ref();
        check_format(doc, origin, text)?;
        // The size is stated once; said before the deserializer, which cannot name the lines.
        if let (Some(_), Some(both)) = (find(doc, "die.half_size"), find(doc, "die.half_sizes")) {
            return Err(PresetError::Key {
                at: Location::at(origin, text, both),
                key: "die.half_sizes".to_string(),
                message: SIZE_TWICE.to_string(),
            });
        }

        over_long_array(doc, origin, text)?;

        // One parse, one pass: the deserializer reads the parsed document, with its spans.
        let de = toml::Deserializer::from(spanned.clone());
        let preset: Preset = serde_path_to_error::deserialize(de).map_err(|e| {
            let key = e.path().to_string();
            let inner = e.into_inner();
            let at = match inner.span() {
                Some(span) => Location::at(origin, text, span.start),
                None => Location::file(origin),
            };
            PresetError::Key {
                at,
                key,
                message: inner.message().trim().to_string(),
            }
        })?;

        if let (Some(_), Some(l)) = (
            find(doc, "initial.angular_velocity"),
            find(doc, "initial.angular_momentum"),
        ) {
            return Err(PresetError::Key {
                at: Location::at(origin, text, l),
                key: "initial.angular_momentum".to_string(),
                message: "give the spin once: `angular_velocity` (rad/s) or `angular_momentum` (g·cm²/s), \
                          not both"
                    .to_string(),
            });
        }

        // A key the chosen contact law does not read is refused where the file gives it,
        // whatever its value.
        for spec in registry::ALL.iter().filter(|s| s.law.is_some()) {
            if find(doc, spec.key()).is_some()
                && let Some(mut refused) = preset.ground.refusal(spec.key())
            {
                // The way out, in the file's own words.
                if let Some(dicesim_physics::params::Detail::Refused(why)) = refused.detail.as_deref_mut() {
                    why.push_str(&format!(
                        "; remove the line, or choose that law with `contact = \"{}\"` in [ground] \
                         (`--set ground.contact=…` switches a preset's law, dropping the other law's keys)",
                        spec.law.map_or("", |l| l.name())
                    ));
                }
                return Err(range_error(doc, origin, text, refused));
            }
        }
        // Likewise a key the die's solid does not read: the box's shape beside a polyhedral
        // die, a polyhedral die's size beside the box.
        let die = preset.params().die;
        for spec in registry::ALL.iter().filter(|s| s.role == Role::Die) {
            let given = find(doc, spec.key()).or_else(|| {
                (spec.key() == "die.half_sizes")
                    .then(|| find(doc, "die.half_size"))
                    .flatten()
            });
            if let (Some(offset), Some(refused)) = (given, die.refusal(spec.key())) {
                return Err(PresetError::Range {
                    at: Location::at(origin, text, offset),
                    error: Box::new(refused),
                });
            }
        }
        preset
            .validate()
            .map_err(|error| range_error(doc, origin, text, error))?;
        Ok(preset)
    }

    /// The whole file: every key the contact law reads, with its unit and meaning in a
    /// comment. Reading it back
    /// with [`Preset::from_toml_str`] gives this preset again (with the spin stated the way
    /// it is used: `angular_momentum` when present, else `angular_velocity`).
    pub fn to_toml(&self) -> String {
        let mut out = String::new();
        let mut line = |key: &str, value: String, comment: &str| push_line(&mut out, key, &value, comment);
        let float = |x: f64| toml::Value::Float(x).to_string();
        let vector = |v: &[f64]| format!("[{}]", v.iter().map(|&x| float(x)).collect::<Vec<_>>().join(", "));
        let string = toml_string;

        line(
            "format",
            FORMAT.to_string(),
            "the file format's version; a newer one is refused clearly",
        );
        line("name", string(&self.name), "shown in the TUI header");
        line(
            "description",
            folded_string(&self.description),
            "shown in the TUI and by `presets list`",
        );

        let keys = self.written_keys();
        for role in Role::ALL {
            line(&format!("\n[{}]", role.section()), String::new(), role.comment());
            for (spec, value) in keys.iter().filter(|(spec, _)| spec.role == role) {
                // The two ways of stating the spin are written together, as one choice.
                if **spec == ANGULAR_VELOCITY || **spec == ANGULAR_MOMENTUM {
                    self.spin_lines(&mut line, &vector);
                    continue;
                }
                let value = match value {
                    Value::Number(x) => float(*x),
                    Value::Vector(v) => vector(v),
                    Value::Range(r) => vector(r),
                    Value::PerCorner(v) => vector(v),
                    // A die's corners one to a line; a list of numbers on one.
                    Value::List(list) if list.width() > 1 => format!(
                        "[\n{}]",
                        list.items()
                            .map(|p| format!("    {},\n", vector(p)))
                            .collect::<String>()
                    ),
                    Value::List(list) => vector(list.values()),
                    Value::Name(n) => string(n),
                    Value::Seed(n) => n.to_string(),
                    Value::Flag(b) => b.to_string(),
                    Value::Absent => continue,
                };
                line(key_name(spec), value, spec.comment);
            }
        }
        let view = self.view.lines();
        if !view.is_empty() {
            line(
                "\n[view]",
                String::new(),
                "how the explorer opens this preset (the CLI ignores it)",
            );
            for (key, value, comment) in view {
                line(&key, value, comment);
            }
        }
        out
    }

    /// The keys the file holds with their values, in the file's order: every key the contact
    /// law reads (only those, so the file reads back as it was written), the spin once in the
    /// form it was given (at `angular_velocity`'s place), no optional value left unset.
    fn written_keys(&self) -> Vec<(&'static registry::Spec, Value)> {
        let setup = self.values();
        let mut keys = Vec::new();
        for role in Role::ALL {
            for &spec in registry::ALL.iter().filter(|s| s.role == role) {
                if *spec == ANGULAR_MOMENTUM
                    || !setup.params.ground.reads(spec.key())
                    || !setup.params.die.states(spec.key())
                {
                    continue;
                }
                let (spec, value) = match self.initial.angular_momentum {
                    Some(l) if *spec == ANGULAR_VELOCITY => (&ANGULAR_MOMENTUM, Value::Vector(l)),
                    _ => (spec, (spec.read)(&setup)),
                };
                if value != Value::Absent {
                    keys.push((spec, value));
                }
            }
        }
        keys
    }

    /// The file [`Preset::to_toml`] writes, as JSON: the same sections, keys and values (the
    /// spin in the form given, only the keys the contact law reads), without the comments.
    /// What a provenance states as the setup, so a preset written from it is this one.
    pub fn to_json(&self) -> serde_json::Value {
        let mut file = serde_json::json!({
            "format": FORMAT,
            "name": self.name,
            "description": self.description,
        });
        for role in Role::ALL {
            file[role.section()] = serde_json::json!({});
        }
        for (spec, value) in self.written_keys() {
            file[spec.role.section()][key_name(spec)] = match value {
                Value::Number(x) => serde_json::json!(x),
                Value::Vector(v) => serde_json::json!(v),
                Value::Range(r) => serde_json::json!(r),
                Value::PerCorner(v) => serde_json::json!(v),
                Value::List(list) if list.width() > 1 => serde_json::json!(list.items().collect::<Vec<_>>()),
                Value::List(list) => serde_json::json!(list.values()),
                Value::Name(n) => serde_json::json!(n),
                Value::Seed(n) => serde_json::json!(n),
                Value::Flag(b) => serde_json::json!(b),
                Value::Absent => unreachable!("written_keys leaves out what is not given"),
            };
        }
        let view = self.view.lines();
        if !view.is_empty() {
            // The explorer's lines as the file has them, read back as TOML reads them.
            let lines: String = view
                .iter()
                .map(|(key, value, _)| format!("{key} = {value}\n"))
                .collect();
            file["view"] = toml::from_str(&lines).expect("the view's lines are TOML");
        }
        file
    }

    /// The spin, stated once; the other form is shown commented out, converted, so a reader
    /// sees both and can switch by moving the `#`.
    fn spin_lines(&self, line: &mut impl FnMut(&str, String, &str), vector: &dyn Fn(&[f64]) -> String) {
        let ic = &self.initial;
        let inertia = self.params().inertia();
        let omega = ic.angular_velocity_for(inertia);
        let momentum = ic.angular_momentum_for(inertia);
        let (w, l) = (vector(omega.as_slice()), vector(momentum.as_slice()));
        if ic.angular_momentum.is_some() {
            line(
                "# angular_velocity",
                w,
                "rad/s, world frame: the same spin as ω = L/I",
            );
            line("angular_momentum", l, "g·cm²/s, world frame (L = I·ω)");
        } else {
            line("angular_velocity", w, ANGULAR_VELOCITY.comment);
            line(
                "# angular_momentum",
                l,
                "g·cm²/s: the same spin stated as L = I·ω (give one of the two)",
            );
        }
    }

    /// This preset as [`Preset::to_toml`] writes it: a spin given as angular momentum makes
    /// the angular velocity field unused, so it is zeroed.
    pub fn as_written(&self) -> Preset {
        let mut p = self.clone();
        p.format = FORMAT;
        if p.initial.angular_momentum.is_some() {
            p.initial.angular_velocity = InitialCondition::default().angular_velocity;
        }
        p
    }
}

/// A key's name in its section: `stiffness` for `ground.stiffness`.
fn key_name(spec: &registry::Spec) -> &'static str {
    spec.key().rsplit('.').next().unwrap_or_default()
}

/// `key = value   # comment`, or a section header when `value` is empty. A comment that
/// would make the line too long goes on the line above.
fn push_line(out: &mut String, key: &str, value: &str, comment: &str) {
    let code = if value.is_empty() {
        key.to_string()
    } else {
        format!("{key} = {value}")
    };
    let first_line = code.trim_start_matches('\n').lines().next().unwrap_or_default();
    let width = first_line.chars().count();
    if comment.is_empty() {
        out.push_str(&code);
    } else if width + 2 + comment.chars().count() > MAX_LINE
        || code.contains("\"\"\"")
        || code.trim_start_matches('\n').contains('\n')
    {
        let blank = code.len() - code.trim_start_matches('\n').len();
        out.push_str(&code[..blank]);
        out.push_str(&format!("# {comment}\n"));
        out.push_str(&code[blank..]);
    } else {
        out.push_str(&code);
        out.push_str(&" ".repeat(COMMENT_COLUMN.saturating_sub(width).max(2)));
        out.push_str(&format!("# {comment}"));
    }
    out.push('\n');
}

/// A long one-line text as a multi-line basic string folded at spaces (a line-ending `\`
/// joins the lines back), so the file reads well; anything it cannot fold exactly stays on
/// one line.
fn folded_string(text: &str) -> String {
    let single = toml_string(text);
    let body = match single.strip_prefix('"').and_then(|b| b.strip_suffix('"')) {
        Some(body) if single.chars().count() > MAX_LINE - 16 && !body.starts_with('"') => body,
        _ => return single,
    };
    let mut folded = String::from("\"\"\"\\\n");
    let mut width = 0;
    let chars: Vec<char> = body.chars().collect();
    for (i, &c) in chars.iter().enumerate() {
        folded.push(c);
        width += 1;
        // A fold eats the whitespace that starts the next line, so fold only at a single space.
        let single_space =
            c == ' ' && i > 0 && chars[i - 1] != ' ' && chars.get(i + 1).is_some_and(|n| *n != ' ');
        if single_space && width >= FOLD_WIDTH {
            folded.push_str("\\\n");
            width = 0;
        }
    }
    folded.push_str("\"\"\"");
    let same = format!("v = {folded}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|t| t.get("v").and_then(|v| v.as_str().map(|v| v == text)));
    if same == Some(true) { folded } else { single }
}

/// Whether `c` must be written as an escape: a control character (C0, DEL or C1, which a
/// terminal acts on) or a bidirectional override or isolate (which reorders the line it is
/// on), the characters [`crate::output::printable`] would otherwise escape in a form
/// (`\u{202e}`) that TOML does not read.
fn needs_escape(c: char) -> bool {
    c.is_control() || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// `text` as a TOML string. Text with nothing to escape is written as the `toml` crate
/// writes it; text with a control or bidi character becomes a basic string with TOML's own
/// escapes (`\n`, `\u202E`), so the file shows no such character and reads back as `text`.
fn toml_string(text: &str) -> String {
    if !text.chars().any(needs_escape) {
        return toml::Value::String(text.to_string()).to_string();
    }
    let mut out = String::with_capacity(text.len() + 8);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if needs_escape(c) => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn syntax_error(origin: &str, text: &str, e: &toml::de::Error) -> PresetError {
    let at = match e.span() {
        Some(span) => Location::at(origin, text, span.start),
        None => Location::file(origin),
    };
    let mut message = e.message().trim().to_string();
    // toml says "duplicate key" and points at it: name it, the way every other error does.
    if message == "duplicate key"
        && let Some(key) = e.span().and_then(|span| text.get(span))
    {
        message = format!("duplicate key `{}`", key.trim());
    }
    PresetError::Syntax { at, message }
}

/// A newer format is refused before anything else is read: its keys may mean other things.
fn check_format(doc: &DeTable<'_>, origin: &str, text: &str) -> Result<(), PresetError> {
    let Some((key, value)) = doc.iter().find(|(k, _)| k.get_ref() == "format") else {
        return Ok(());
    };
    let Some(found) = value
        .get_ref()
        .as_integer()
        .and_then(|i| i64::from_str_radix(i.as_str(), i.radix()).ok())
    else {
        return Ok(()); // not an integer: the deserializer names the type error
    };
    if found > i64::from(FORMAT) {
        return Err(PresetError::NewerFormat {
            at: Location::at(origin, text, key.span().start),
            found,
        });
    }
    Ok(())
}

/// An array with more elements than its key has components is refused at the first one too
/// many: the deserializer fills a fixed-size field and would ignore the rest (as `--set`
/// refuses `[1,2,3,4]` for a vector).
fn over_long_array(doc: &DeTable<'_>, origin: &str, text: &str) -> Result<(), PresetError> {
    for spec in registry::ALL {
        let expected = match spec.shape {
            Shape::Vector { components, .. } => components.len(),
            Shape::Range(range) => range.len(),
            Shape::PerCorner(corners) => corners.len(),
            Shape::List { most, .. } => most,
            Shape::Number(_)
            | Shape::Optional { .. }
            | Shape::Choice { .. }
            | Shape::Seed(_)
            | Shape::Flag(_) => {
                continue;
            }
        };
        let (section, name) = spec.key().split_once('.').unwrap_or(("", spec.key()));
        let array = doc
            .iter()
            .find(|(k, _)| k.get_ref() == section)
            .and_then(|(_, v)| v.get_ref().as_table())
            .and_then(|t| t.iter().find(|(k, _)| k.get_ref() == name))
            .and_then(|(_, v)| v.get_ref().as_array());
        if let Some(array) = array
            && array.len() > expected
        {
            let message = match spec.shape {
                Shape::List { .. } => format!(
                    "{} values, and a die has at most {expected} vertices: the largest body the \
                     engines carry",
                    array.len()
                ),
                _ => format!(
                    "invalid length {}, expected an array of length {expected}",
                    array.len()
                ),
            };
            return Err(PresetError::Key {
                at: Location::at(origin, text, array[expected].span().start),
                key: spec.key().to_string(),
                message,
            });
        }
    }
    Ok(())
}

/// Names the line of the out-of-range key when the file has it.
fn range_error(doc: &DeTable<'_>, origin: &str, text: &str, error: ParamError) -> PresetError {
    let at = match find(doc, &error.key) {
        Some(offset) => Location::at(origin, text, offset),
        None => Location::file(origin),
    };
    PresetError::Range {
        at,
        error: Box::new(error),
    }
}

/// The byte offset of a key as [`ParamError`] names it (`ground.friction`,
/// `initial.velocity.y`, `die.extra_corner_mass.8`, `random.height[1]`): the key itself, or
/// the array element when the key names a component (an axis or a corner).
fn find(doc: &DeTable<'_>, key: &str) -> Option<usize> {
    let mut table = doc;
    let mut segments = key.split('.').peekable();
    while let Some(segment) = segments.next() {
        let (name, index) = match segment.split_once('[') {
            Some((name, rest)) => (name, rest.trim_end_matches(']').parse::<usize>().ok()),
            None => (segment, None),
        };
        let (k, v) = table.iter().find(|(k, _)| k.get_ref() == name)?;
        let component = match (index, segments.peek()) {
            (Some(i), _) => Some(i),
            (None, Some(&axis)) if v.get_ref().is_array() => ["x", "y", "z"]
                .iter()
                .position(|a| *a == axis)
                .or_else(|| CORNERS.iter().position(|c| *c == axis))
                // A die's vertex, from 1 (`die.vertices.5`).
                .or_else(|| axis.parse::<usize>().ok().and_then(|k| k.checked_sub(1))),
            _ => None,
        };
        if let Some(i) = component {
            let element = v.get_ref().as_array()?.get(i)?;
            return Some(element.span().start);
        }
        match (segments.peek(), v.get_ref()) {
            (None, _) => return Some(k.span().start),
            (Some(_), DeValue::Table(t)) => table = t,
            _ => return None,
        }
    }
    None
}

/// For tests: the deserializer alone, without spans, so a test can check what a file means.
#[cfg(test)]
pub(crate) fn parse_plain(text: &str) -> Preset {
    use serde::Deserialize;
    Preset::deserialize(toml::Deserializer::parse(text).unwrap()).unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;
    use dicesim_physics::{FrictionLaw, Params};

    const ORIGIN: &str = "dir/p.toml";

    fn err(text: &str) -> PresetError {
        Preset::from_toml_str(text, ORIGIN).unwrap_err()
    }

    /// Every character [`needs_escape`] names: C0, DEL, C1 and the bidi overrides/isolates.
    fn controls_and_bidi() -> Vec<char> {
        let mut all: Vec<char> = (0u32..0x20)
            .chain(0x7f..0xa0)
            .filter_map(char::from_u32)
            .collect();
        all.extend(('\u{202a}'..='\u{202e}').chain('\u{2066}'..='\u{2069}'));
        all
    }

    #[test]
    fn a_shown_preset_with_control_or_bidi_characters_reads_back() {
        // `presets show` prints `output::printable(&preset.to_toml())`; it wrote U+202E as
        // `\u{202e}`, which is no TOML escape, so the shown preset did not load back.
        for c in controls_and_bidi() {
            for text in [format!("a{c}b"), format!("\"q\" \\ {c}"), format!("{c}")] {
                let preset = Preset {
                    name: text.clone(),
                    description: format!("{} {text}", "long words ".repeat(12)),
                    ..Preset::default()
                };
                let shown = crate::output::printable(&preset.to_toml());
                // Line breaks are the file's own; inside a string they are written `\n`.
                assert!(
                    c == '\n' || !shown.contains(c),
                    "U+{:04X} reached the terminal: {shown}",
                    c as u32
                );
                let back = Preset::from_toml_str(&shown, ORIGIN)
                    .unwrap_or_else(|e| panic!("U+{:04X}: {e}\n{shown}", c as u32));
                assert_eq!(back.name, preset.name, "U+{:04X}", c as u32);
                assert_eq!(back.description, preset.description, "U+{:04X}", c as u32);
            }
        }
    }

    #[test]
    fn a_box_preset_is_written_without_the_polyhedral_keys() {
        let text = Preset::default().to_toml();
        let die: Vec<&str> = text
            .split("[die]")
            .nth(1)
            .and_then(|rest| rest.split("\n[").next())
            .unwrap()
            .lines()
            .filter_map(|l| {
                l.split(" = ")
                    .next()
                    .filter(|k| !k.is_empty() && !k.starts_with('#'))
            })
            .collect();
        // The box's keys as a written preset has always listed them.
        assert_eq!(
            die,
            [
                "half_sizes",
                "corner_radius",
                "pip_diameter",
                "pip_depth",
                "corner_mass",
                "extra_corner_mass"
            ]
        );
        let json = Preset::default().to_json();
        assert!(json["die"].get("kind").is_none() && json["die"].get("height").is_none());
        assert!(
            toml::to_string(&Params::default())
                .unwrap()
                .find("kind")
                .is_none()
        );
    }

    #[test]
    fn a_polyhedral_die_is_written_with_its_kind_size_and_material_only() {
        let p = Preset::from_toml_str(
            "[die]\nkind = \"d%\"\nheight = 2.0\n[integrator]\ndt = 0.00025\n",
            ORIGIN,
        )
        .unwrap();
        assert_eq!(p.die.kind, dicesim_physics::Solid::Percentile);
        assert_eq!((p.die.height, p.die.density), (2.0, 1.18));
        let text = p.to_toml();
        assert!(text.contains("kind = \"d%\""), "{text}");
        assert!(
            text.contains("height = 2.0") && text.contains("density = 1.18"),
            "{text}"
        );
        for boxy in ["half_size", "corner_radius", "pip_", "corner_mass"] {
            assert!(!text.contains(boxy), "{boxy} in\n{text}");
        }
        assert_eq!(Preset::from_toml_str(&text, ORIGIN).unwrap(), p.as_written());
        let params = toml::to_string(&p.params()).unwrap();
        assert!(
            params.contains("kind = \"d%\"") && !params.contains("corner_mass"),
            "{params}"
        );
    }

    #[test]
    fn a_box_key_beside_a_polyhedron_is_refused_at_its_line() {
        for (text, line, key) in [
            ("[die]\nkind = \"d20\"\nhalf_size = 0.8\n", 3, "die.half_sizes"),
            (
                "[die]\nkind = \"d20\"\n\ncorner_mass = 1.0\n",
                4,
                "die.corner_mass",
            ),
            ("[die]\nhalf_size = 0.8\nheight = 1.6\n", 3, "die.height"),
        ] {
            let e = err(text).to_string();
            assert!(e.starts_with(&format!("dir/p.toml:{line}:")), "{e}");
            assert!(e.contains(&format!("`{key}`")), "{e}");
        }
        let e = err("[die]\nkind = \"d6\"\n").to_string();
        assert!(e.starts_with("dir/p.toml:2:") && e.contains("d20"), "{e}");
        let e = err("[die]\nkind = \"d4\"\n").to_string();
        assert!(e.contains("`integrator.dt`") && e.contains("runs away"), "{e}");
    }

    /// Each flaw key and a convex die's corners, refused at the line that gives them, by key
    /// and why (docs/dice.md, "Flaws": the 16 mm d20's inradius is 0.8 cm).
    #[test]
    fn a_flaw_or_a_corner_that_makes_no_die_is_refused_at_its_line() {
        const D20: &str = "[die]\nkind = \"d20\"\n[integrator]\ndt = 0.00025\n[die]\n";
        let d20 = |lines: &str| format!("[integrator]\ndt = 0.00025\n[die]\nkind = \"d20\"\n{lines}");
        let convex = |lines: &str| format!("[integrator]\ndt = 0.00025\n[die]\nkind = \"convex\"\n{lines}");
        let cube = "[1.0, 1.0, 1.0], [1.0, 1.0, -1.0], [1.0, -1.0, 1.0], [1.0, -1.0, -1.0],\n\
                    [-1.0, 1.0, 1.0], [-1.0, 1.0, -1.0], [-1.0, -1.0, 1.0], [-1.0, -1.0, -1.0],";
        assert!(Preset::from_toml_str(D20, ORIGIN).is_err(), "a table given twice");
        for (text, line, key, words) in [
            (
                d20("bubble_radius = 0.35\nbubble_toward = 20\nbubble_offset = 0.5\n"),
                7,
                "die.bubble_offset",
                "reaches face 20",
            ),
            (
                d20("bubble_radius = 0.9\n"),
                5,
                "die.bubble_radius",
                "reaches face",
            ),
            (
                d20("bubble_radius = 0.1\nbubble_toward = 21\n"),
                6,
                "die.bubble_toward",
                "faces show 1 to 20",
            ),
            (
                d20("point_mass = 0.5\npoint_mass_offset = 0.3\n"),
                6,
                "die.point_mass_offset",
                "`die.point_mass_toward`",
            ),
            (
                d20("shave_face = 3\nshave_depth = 1.2\n"),
                6,
                "die.shave_depth",
                "removes the whole of face",
            ),
            (d20("rounding = 11.0\n"), 5, "die.rounding", "0 to 10 cm"),
            (d20("rounding = 1.0\n"), 5, "die.rounding", "reaches past face"),
            (
                d20("worn_face = 9\nworn_rounding = 1.5\n"),
                6,
                "die.worn_rounding",
                "reaches past face",
            ),
            (
                d20("vertex_rounding = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0]\n"),
                5,
                "die.vertex_rounding.11",
                "vertex 11's rounding reaches past face",
            ),
            (
                d20("vertices = [[0.0, 0.0, 1.0]]\n"),
                5,
                "die.vertices",
                "a d20 is a regular die",
            ),
            (
                convex("height = 1.6\n"),
                5,
                "die.height",
                "a convex die's size is its corners",
            ),
            (convex(""), 1, "die.vertices", "at least 4"),
            (
                convex(&format!("vertices = [\n{cube}\n[0.0, 0.0, 0.5],\n]\n")),
                8,
                "die.vertices.9",
                "not a corner of the die",
            ),
            (
                convex(&format!("vertices = [\n{cube}\n[1.0, -1.0, -1.0],\n]\n")),
                8,
                "die.vertices.9",
                "same place as vertex 4",
            ),
            (
                convex("vertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]\n"),
                5,
                "die.vertices",
                "one line or in one plane",
            ),
            (
                convex(&format!("vertices = [{}]\n", "[0.0, 0.0, 0.0], ".repeat(21))),
                5,
                "die.vertices",
                "at most 20 vertices",
            ),
            (
                "[die]\nbubble_radius = 0.1\n".to_string(),
                2,
                "die.bubble_radius",
                "`die.extra_corner_mass`",
            ),
            (
                "[die]\nvertices = [[0.0, 0.0, 1.0]]\n".to_string(),
                2,
                "die.vertices",
                "`die.half_sizes`",
            ),
        ] {
            let e = err(&text).to_string();
            if line > 1 {
                assert!(e.starts_with(&format!("dir/p.toml:{line}:")), "{e}\n{text}");
            }
            assert!(e.starts_with("dir/p.toml"), "{e}");
            assert!(e.contains(&format!("`{key}`")), "{key}: {e}");
            assert!(e.contains(words), "{words}: {e}");
        }
    }

    /// A convex die and a flawed d20 are written with their keys and read back as they were.
    #[test]
    fn a_convex_die_and_a_flawed_one_are_written_and_read_back() {
        let text = "[integrator]\ndt = 0.00025\n[die]\nkind = \"convex\"\nvertices = [[1.0, 1.0, 1.0], \
                    [1.0, 1.0, -1.0], [1.0, -1.0, 1.0], [1.0, -1.0, -1.0], [-1.0, 1.0, 1.0], \
                    [-1.0, 1.0, -1.0], [-1.0, -1.0, 1.0], [-1.0, -1.0, -1.0]]\nrounding = 0.05\n\
                    worn_face = 6\nworn_rounding = 0.1\n";
        let p = Preset::from_toml_str(text, ORIGIN).unwrap();
        assert_eq!(p.die.face_numbers(), &[1, 2, 3, 4, 5, 6]);
        let written = p.to_toml();
        assert!(
            written.contains("vertices = [\n    [1.0, 1.0, 1.0],\n"),
            "{written}"
        );
        assert!(
            written.contains("worn_face = 6") && !written.contains("bubble"),
            "{written}"
        );
        let die_table = written.split("[ground]").next().unwrap_or_default();
        assert!(
            !die_table.lines().any(|l| l.starts_with("height")),
            "a convex die has no `height`: {written}"
        );
        assert_eq!(Preset::from_toml_str(&written, ORIGIN).unwrap(), p.as_written());
        let json = p.to_json();
        assert_eq!(json["die"]["vertices"][7], serde_json::json!([-1.0, -1.0, -1.0]));
        // The regular dice' written files keep to their kind, size and material.
        let d20 =
            Preset::from_toml_str("[die]\nkind = \"d20\"\n[integrator]\ndt = 0.00025\n", ORIGIN).unwrap();
        let written = d20.to_toml();
        for flaw in ["rounding", "bubble", "point_mass", "shave", "worn", "vertices"] {
            assert!(!written.lines().any(|l| l.starts_with(flaw)), "{flaw}: {written}");
        }
    }

    #[test]
    fn missing_keys_take_the_papers_defaults() {
        let p = Preset::from_toml_str("[ground]\nfriction = 0.3\n", ORIGIN).unwrap();
        assert_eq!(p.ground.friction, 0.3);
        assert_eq!(p.die, Params::default().die);
        assert_eq!(p.initial, InitialCondition::default());
        assert_eq!(p.format, FORMAT);
        assert_eq!(p.name, "");
    }

    #[test]
    fn malformed_toml_names_file_line_and_column() {
        let e = err("name = \"x\"\n\n[ground\nfriction = 1\n");
        assert!(matches!(e, PresetError::Syntax { .. }), "{e:?}");
        let msg = e.to_string();
        assert!(msg.starts_with("dir/p.toml:3:"), "{msg}");
        assert!(msg.contains("unclosed table"), "{msg}");
    }

    #[test]
    fn unknown_key_names_file_line_column_and_key() {
        let e = err("format = 1\n[ground]\nfriction = 1.0\nstifness = 1.0\n");
        assert_eq!(
            e.to_string().lines().next().unwrap(),
            "dir/p.toml:4:1: key `ground.stifness`: unknown field `stifness`, expected one of \
             `stiffness`, `damping`, `friction`, `friction_law`, `contact`, `static_friction`, \
             `restitution`, `tangential_stiffness_ratio`, `face_restitution`, `table_mass`, \
             `table_stiffness`, `table_damping`, `tilt`, `tilt_direction`"
        );
        let e = err("colour = \"red\"\n");
        assert!(
            e.to_string()
                .starts_with("dir/p.toml:1:1: key `colour`: unknown field"),
            "{e}"
        );
    }

    #[test]
    fn wrong_type_names_file_line_column_and_key() {
        let e = err("[ground]\nfriction = \"high\"\n");
        assert_eq!(
            e.to_string(),
            "dir/p.toml:2:12: key `ground.friction`: invalid type: string \"high\", expected f64"
        );
        let e = err("[initial]\nvelocity = [1.0, 2.0]\n");
        let msg = e.to_string();
        assert!(msg.starts_with("dir/p.toml:2:"), "{msg}");
        assert!(
            msg.contains("`initial.velocity`") && msg.contains("invalid length 2"),
            "{msg}"
        );
        let e = err("[ground]\nfriction_law = \"per_corner\"\n");
        assert!(e.to_string().contains("unknown variant `per_corner`"), "{e}");
    }

    #[test]
    fn an_array_longer_than_its_key_is_refused_at_the_first_element_too_many() {
        for (section, line, key, extra) in [
            (
                "initial",
                "velocity = [1.0, 2.0, 3.0, \"junk\", {a = 1}]",
                "initial.velocity",
                "\"junk\"",
            ),
            (
                "die",
                "extra_corner_mass = [0, 0, 0, 0, 0, 0, 0, 0.5, 9]",
                "die.extra_corner_mass",
                "9]",
            ),
            ("random", "height = [2.0, 8.0, 20.0]", "random.height", "20.0"),
        ] {
            let column = line.find(extra).unwrap() + 1;
            let length = line.matches(',').count() + 1;
            let expected = match section {
                "initial" => 3,
                "die" => 8,
                _ => 2,
            };
            assert_eq!(
                err(&format!("[{section}]\n{line}\n")).to_string(),
                format!(
                    "dir/p.toml:2:{column}: key `{key}`: invalid length {length}, expected an array of length {expected}"
                )
            );
        }
        // As long as its key's components: read.
        let p = Preset::from_toml_str("[random]\nheight = [2.0, 8.0]\n", ORIGIN).unwrap();
        assert_eq!(p.random.height, [2.0, 8.0]);
    }

    #[test]
    fn out_of_range_names_file_line_key_and_range() {
        let e = err("[die]\nhalf_size = 1.0\n[ground]\n\nfriction = 9.0\n");
        assert_eq!(
            e.to_string(),
            "dir/p.toml:5:1: `ground.friction` = 9 is outside the allowed range 0 to 5"
        );
        let e = err("[initial]\nvelocity = [0.0,\n  20000.0, 0.0]\n");
        assert_eq!(
            e.to_string(),
            "dir/p.toml:3:3: `initial.velocity.y` = 20000 is outside the allowed range -10000 to 10000 cm/s"
        );
        // The eighth corner's mass is the array's eighth element: line 3, column 15.
        let e = err("[die]\nextra_corner_mass = [0, 0, 0,\n  0, 0, 0, 0, 5000]\n");
        assert_eq!(
            e.to_string(),
            "dir/p.toml:3:15: `die.extra_corner_mass.8` = 5000 is outside the allowed range 0 to 1000 g"
        );
        let e = err("[random]\nheight = [5.0, 2.0]\n");
        assert_eq!(
            e.to_string(),
            "dir/p.toml:2:1: `random.height` = [5, 2]: the low end is above the high end"
        );
        let e = err("[ground]\nfriction = 0.5\nfriction = 0.6\n");
        assert_eq!(e.to_string(), "dir/p.toml:3:1: duplicate key `friction`");
        let e = err("[initial]\norientation = [400.0, 0.0, 0.0]\n");
        assert!(e.to_string().contains("`initial.orientation.yaw` = 400"), "{e}");
        let e = err("format = 0\n");
        assert_eq!(
            e.to_string(),
            "dir/p.toml:1:1: `format` = 0 is outside the allowed range 1 to 1"
        );
    }

    #[test]
    fn a_key_the_contact_law_does_not_read_is_refused_on_its_line_whatever_its_value() {
        let e = err("[ground]\nfriction = 0.5\nrestitution = 0.5\n");
        assert!(
            e.to_string().starts_with(
                "dir/p.toml:3:1: `ground.restitution` = 0.5: the \"paper\" contact law does not read it"
            ),
            "{e}"
        );
        let e = err("[ground]\ncontact = \"spring-friction\"\n\ndamping = 0.005\n");
        assert!(
            e.to_string().starts_with(
                "dir/p.toml:4:1: `ground.damping` = 0.005: the \"spring-friction\" contact law does not read \
                 it (its normal damping comes from `ground.restitution`)"
            ),
            "{e}"
        );
        let e = err("[ground]\ncontact = \"spring-friction\"\nfriction = 0.8\nstatic_friction = 0.6\n");
        assert!(
            e.to_string()
                .contains("static friction must be at least the kinetic"),
            "{e}"
        );
    }

    #[test]
    fn a_spring_friction_table_is_written_with_its_own_keys_and_reads_back() {
        let mut p = Preset::default();
        p.ground.contact = dicesim_physics::ContactLaw::SpringFriction;
        (p.ground.restitution, p.ground.static_friction, p.ground.tilt) = (0.8, 1.5, 12.5);
        let text = p.to_toml();
        for key in [
            "contact = \"spring-friction\"",
            "restitution = 0.8",
            "static_friction = 1.5",
            "tilt = 12.5",
        ] {
            assert!(text.contains(key), "no `{key}` in\n{text}");
        }
        for unread in ["damping = ", "friction_law = "] {
            assert!(!text.contains(unread), "`{unread}` written in\n{text}");
        }
        assert_eq!(Preset::from_toml_str(&text, ORIGIN).unwrap(), p);
        let paper = Preset::default().to_toml();
        assert!(
            paper.contains("contact = \"paper\"") && !paper.contains("restitution = "),
            "{paper}"
        );
    }

    #[test]
    fn the_face_restitution_is_written_only_when_given_and_refused_where_it_cannot_act() {
        let mut p = Preset::default();
        p.ground.contact = dicesim_physics::ContactLaw::SpringFriction;
        let text = p.to_toml();
        assert!(
            !text.contains("face_restitution"),
            "written though not given:\n{text}"
        );
        assert!(p.to_json()["ground"].get("face_restitution").is_none());
        p.ground.face_restitution = Some(0.35);
        let text = p.to_toml();
        assert!(text.contains("face_restitution = 0.35"), "{text}");
        assert_eq!(Preset::from_toml_str(&text, ORIGIN).unwrap(), p);
        let e = err("[ground]\ncontact = \"spring-friction\"\nface_restitution = 0.1\n");
        assert!(
            e.to_string().starts_with(
                "dir/p.toml:3:1: `ground.face_restitution` = 0.1 is outside the allowed range 0.2 to 1"
            ),
            "{e}"
        );
        let e = err("[ground]\nface_restitution = 0.5\n");
        assert!(
            e.to_string().starts_with(
                "dir/p.toml:2:1: `ground.face_restitution` = 0.5: the \"paper\" contact law does not read \
                 it (its damping is the same at every impact)"
            ),
            "{e}"
        );
        let set = Preset::default()
            .with_overrides(&["ground.contact=spring-friction", "ground.face_restitution=1"])
            .unwrap();
        assert_eq!(set.ground.face_restitution, Some(1.0));
    }

    #[test]
    fn a_table_tops_spring_and_damper_need_its_mass() {
        let e = err("[ground]\ncontact = \"spring-friction\"\ntable_stiffness = 1000.0\n");
        assert!(
            e.to_string().contains(
                "`ground.table_stiffness` = 1000: a table top's spring and damper hold its mass: give \
                 `ground.table_mass` (g) too"
            ),
            "{e}"
        );
        let text = "[ground]\ncontact = \"spring-friction\"\ntable_mass = 40.0\ntable_damping = 5.0\n";
        let p = Preset::from_toml_str(text, ORIGIN).unwrap();
        assert_eq!(
            (
                p.ground.table_mass,
                p.ground.table_stiffness,
                p.ground.table_damping
            ),
            (Some(40.0), None, Some(5.0))
        );
        assert_eq!(Preset::from_toml_str(&p.to_toml(), ORIGIN).unwrap(), p);
        let e = err("[ground]\ntable_mass = 40.0\n");
        assert!(e.to_string().contains("(its table is rigid)"), "{e}");
    }

    #[test]
    fn newer_format_is_refused_before_its_keys_are_read() {
        let e = err("name = \"future\"\nformat = 2\n[sparkles]\nglitter = true\n");
        assert_eq!(
            e.to_string(),
            "dir/p.toml:2:1: preset format 2 is newer than this dicesim understands (it reads \
             format 1); update dicesim to load it"
        );
    }

    #[test]
    fn both_spins_at_once_are_refused() {
        let e = err("[initial]\nangular_velocity = [1.0, 0.0, 0.0]\nangular_momentum = [1.0, 0.0, 0.0]\n");
        let msg = e.to_string();
        assert!(
            msg.starts_with("dir/p.toml:3:1: key `initial.angular_momentum`: give the spin once"),
            "{msg}"
        );
    }

    #[test]
    fn written_file_has_every_key_and_its_unit() {
        let mut p = Preset::default();
        p.ground.friction_law = FrictionLaw::WholeDieNorm;
        let text = p.to_toml();
        for key in [
            "format = 1",
            "half_size = ",
            "corner_mass = ",
            "stiffness = ",
            "damping = ",
            "friction = ",
            "friction_law = \"whole-die-norm\"",
            "gravity = ",
            "dt = ",
            "stop_energy_fraction = ",
            "max_time = ",
            "stop_energy = \"rigid-body\"",
            "height = ",
            "velocity = ",
            "angular_velocity = ",
            "# angular_momentum = ",
            "orientation = ",
            "seed = ",
            "random_orientation = ",
        ] {
            assert!(text.contains(key), "no `{key}` in\n{text}");
        }
        for unit in [
            "# dyn/cm per corner",
            "# s/cm",
            "# cm/s², downwards",
            "# rad/s, world frame",
        ] {
            assert!(text.contains(unit), "no `{unit}` in\n{text}");
        }
        assert_eq!(parse_plain(&text), p);
    }

    #[test]
    fn the_commented_spin_is_the_same_spin() {
        let mut p = Preset::default();
        p.initial.angular_velocity = [3.0, 0.0, -1.5];
        p.initial.angular_momentum = None;
        let inertia = p.params().inertia();
        let text = p.to_toml();
        // The first `angular_velocity` is [initial]'s; [random] has its own further down.
        let uncommented = text
            .replacen("angular_velocity = [", "# angular_velocity = [", 1)
            .replacen("# angular_momentum = [", "angular_momentum = [", 1);
        let q = Preset::from_toml_str(&uncommented, ORIGIN).unwrap();
        assert_eq!(
            q.initial.angular_momentum,
            Some([3.0 * inertia, 0.0, -1.5 * inertia])
        );
    }

    #[test]
    fn the_view_is_read_written_and_checked_like_every_other_table() {
        use crate::preset::{CameraView, Readouts, Screen, Speed, ThemeName, View};
        let p = Preset::from_toml_str(
            "[view]\nspeed = \"1/20×\"\ncamera = { yaw = 45.0, pitch = 60.0, zoom = 2 }\n\
             theme = \"projector\"\narrows = true\ntwin = 1e-6\nscreen = \"map\"\n\
             readouts = [\"lean\", \"spin\"]\n",
            ORIGIN,
        )
        .unwrap();
        let view = View {
            speed: Speed::from_label("1/20"),
            camera: Some(CameraView {
                yaw: 45.0,
                pitch: 60.0,
                zoom: 2,
            }),
            theme: Some(ThemeName::Projector),
            arrows: Some(true),
            twin: Some(1e-6),
            screen: Some(Screen::Map),
            readouts: Some(Readouts {
                spin: true,
                lean: true,
                slid: false,
            }),
        };
        assert_eq!(p.view, view);
        let text = p.to_toml();
        assert!(text.contains("\n[view]"), "{text}");
        assert_eq!(Preset::from_toml_str(&text, ORIGIN).unwrap(), p);
        assert!(
            !Preset::default().to_toml().contains("[view]"),
            "no view, no table"
        );
        assert_eq!(
            Preset::from_toml_str("[view]\nspeed = \"instant\"\n", ORIGIN)
                .unwrap()
                .view
                .speed,
            Some(Speed::INSTANT)
        );

        let e = err("[view]\nspeed = \"1/20\"\ncolour = \"red\"\n");
        assert!(
            e.to_string()
                .starts_with("dir/p.toml:3:1: key `view.colour`: unknown field `colour`"),
            "{e}"
        );
        let e = err("[view]\nreadouts = [\"spin\", \"tilt\"]\n");
        assert!(
            e.to_string().starts_with("dir/p.toml:2:") && e.to_string().contains("tilt"),
            "{e}"
        );
        let e = err("[view]\nspeed = \"1/3\"\n");
        assert!(
            e.to_string().starts_with(
                "dir/p.toml:2:9: key `view.speed`: `1/3` is not a playback speed; one of 1/100×, 1/50×"
            ),
            "{e}"
        );
        let e = err("[view]\ntheme = \"neon\"\n");
        assert!(
            e.to_string()
                .starts_with("dir/p.toml:2:9: key `view.theme`: unknown variant `neon`"),
            "{e}"
        );
        let e = err("[view]\nscreen = 2\n");
        assert!(
            e.to_string().starts_with("dir/p.toml:2:10: key `view.screen`"),
            "{e}"
        );
        let e = err("[view]\narrows = \"yes\"\n");
        assert!(
            e.to_string()
                .starts_with("dir/p.toml:2:10: key `view.arrows`: invalid type"),
            "{e}"
        );
        let e = err("[view]\ncamera = { yaw = 0.0, pitch = 95.0 }\n");
        assert_eq!(
            e.to_string(),
            "dir/p.toml:2:23: `view.camera.pitch` = 95 is outside the allowed range -10 to 89 °"
        );
        let e = err("[view]\ncamera = { yaw = 0.0, pitch = 5.0, roll = 1.0 }\n");
        assert!(
            e.to_string().contains("key `view.camera.roll`: unknown field"),
            "{e}"
        );
        let e = err("[view]\n\ntwin = 0.5\n");
        assert_eq!(
            e.to_string(),
            "dir/p.toml:3:1: `view.twin` = 0.5 is outside the allowed range 1e-15 to 0.1"
        );
    }
}
