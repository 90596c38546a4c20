//! The presets shipped in the repository's `presets/`, compiled in so an installed binary
//! still has them. The crate reaches them through its own `presets`, a link to that folder,
//! so the packaged crate carries the files it embeds (cargo packages a link's target).

use super::contents::Preset;
use super::error::PresetError;
use std::sync::LazyLock;

/// The preset used when none is named (the CLI without `--preset`, the TUI at start).
pub const DEFAULT_NAME: &str = "paper";

/// Name and file text of every shipped preset, in the order `presets list` shows them: the
/// default first, then what a teacher opens first.
pub const SHIPPED: &[(&str, &str)] = &[
    ("paper", include_str!("../../presets/paper.toml")),
    (
        "slow-motion-classroom",
        include_str!("../../presets/slow-motion-classroom.toml"),
    ),
    ("gentle-drop", include_str!("../../presets/gentle-drop.toml")),
    (
        "authors-program",
        include_str!("../../presets/authors-program.toml"),
    ),
    ("soft-table", include_str!("../../presets/soft-table.toml")),
    ("icy-table", include_str!("../../presets/icy-table.toml")),
    ("sticky-table", include_str!("../../presets/sticky-table.toml")),
    (
        "on-the-edge-of-stability",
        include_str!("../../presets/on-the-edge-of-stability.toml"),
    ),
    ("loaded-corner", include_str!("../../presets/loaded-corner.toml")),
    ("casino-die", include_str!("../../presets/casino-die.toml")),
    ("rounded-die", include_str!("../../presets/rounded-die.toml")),
    ("shaved-die", include_str!("../../presets/shaved-die.toml")),
    ("d4", include_str!("../../presets/d4.toml")),
    ("d8", include_str!("../../presets/d8.toml")),
    ("d10", include_str!("../../presets/d10.toml")),
    ("d100", include_str!("../../presets/d100.toml")),
    ("d12", include_str!("../../presets/d12.toml")),
    ("d20", include_str!("../../presets/d20.toml")),
    ("d20-bubble", include_str!("../../presets/d20-bubble.toml")),
    ("d20-tumbled", include_str!("../../presets/d20-tumbled.toml")),
    ("thick-coin", include_str!("../../presets/thick-coin.toml")),
    ("plate", include_str!("../../presets/plate.toml")),
    ("tennis-racket", include_str!("../../presets/tennis-racket.toml")),
    ("sleeping-top", include_str!("../../presets/sleeping-top.toml")),
    ("superball", include_str!("../../presets/superball.toml")),
    ("incline", include_str!("../../presets/incline.toml")),
    (
        "calibrated-table",
        include_str!("../../presets/calibrated-table.toml"),
    ),
    (
        "calibrated-table-budden",
        include_str!("../../presets/calibrated-table-budden.toml"),
    ),
];

/// The shipped presets the classroom lesson (crates/explorer/lesson.toml) opens, in the order
/// it first opens them: the explorer's picker lists them first, under a heading of their own.
pub const LESSON: &[&str] = &[
    "slow-motion-classroom",
    "paper",
    "loaded-corner",
    "gentle-drop",
    "sleeping-top",
    "superball",
    "incline",
];

/// The text of the shipped preset `name`.
pub fn shipped_text(name: &str) -> Option<&'static str> {
    SHIPPED.iter().find(|(n, _)| *n == name).map(|(_, text)| *text)
}

/// How errors name a shipped file.
pub(crate) fn origin(name: &str) -> String {
    format!("shipped/{name}.toml")
}

/// Loads the shipped preset `name`.
pub(crate) fn load(name: &str) -> Option<Result<Preset, PresetError>> {
    shipped_text(name).map(|text| Preset::from_toml_str(text, &origin(name)))
}

/// The shipped default, parsed once. Every shipped file is checked by the tests, so a failure
/// here is a build that should never have passed them.
pub(crate) fn default_preset() -> &'static Preset {
    static DEFAULT: LazyLock<Preset> = LazyLock::new(|| match load(DEFAULT_NAME) {
        Some(Ok(p)) => p,
        Some(Err(e)) => panic!("the shipped default preset is invalid: {e}"),
        None => panic!("no shipped preset named {DEFAULT_NAME}"),
    });
    &DEFAULT
}

impl Default for Preset {
    /// The shipped `paper` preset (the paper's constants and a lively first roll).
    fn default() -> Self {
        default_preset().clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_preset_loads_and_is_named_after_its_file() {
        for (name, _) in SHIPPED {
            let p = load(name).unwrap().unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(p.name, *name);
            assert!(p.description.len() > 80, "{name}: describe it for a teacher");
        }
        assert_eq!(Preset::default().name, DEFAULT_NAME);
    }
}
