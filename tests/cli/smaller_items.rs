//! The smaller defects of issue 26: ε labels printed as given, and preset text that could
//! steer the terminal printed escaped.

use crate::common::dicesim_in;
use std::process::Command;

#[test]
fn epsilon_labels_are_printed_as_given() {
    let dir = tempfile::tempdir().unwrap();
    let o = dicesim_in(
        dir.path(),
        &["predict", "--rolls", "2", "--epsilon", "1.5e-3,2.5e-2"],
    );
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(o.status.success());
    for label in ["  1.5e-3   ", "  2.5e-2   "] {
        assert!(text.contains(label), "{label}: {text}");
    }
    assert!(!text.contains("2e-3"), "{text}");
}

#[test]
fn presets_list_and_show_escape_c1_controls_and_bidi_overrides() {
    let dir = tempfile::tempdir().unwrap();
    let presets = dir.path().join("presets");
    std::fs::create_dir(&presets).unwrap();
    let evil = "format = 1\nname = \"evil\"\ndescription = \"a\u{9b}31mred \u{202e}desrever\"\n";
    std::fs::write(presets.join("evil.toml"), evil).unwrap();
    for args in [&["presets", "list"][..], &["presets", "show", "evil"][..]] {
        let o = Command::new(env!("CARGO_BIN_EXE_dicesim"))
            .env("DICESIM_PRESETS", &presets)
            .args(args)
            .output()
            .unwrap();
        let text = String::from_utf8(o.stdout).unwrap();
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(
            !text.contains('\u{9b}') && !text.contains('\u{202e}'),
            "{args:?}: {text}"
        );
        // The list escapes for the terminal; the shown preset in TOML's own escapes, so it
        // loads back.
        let escaped = match args[1] {
            "list" => "\\u{9b}31mred \\u{202e}desrever",
            _ => "\\u009B31mred \\u202Edesrever",
        };
        assert!(text.contains(escaped), "{args:?}: {text}");
    }
}
