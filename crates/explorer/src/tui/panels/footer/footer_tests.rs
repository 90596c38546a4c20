//! The footer: the keys that work now, from the key table.

use crate::tui::tests::fixtures::{full, mid_impact, panel, screen, start};
use ratatui::crossterm::event::KeyCode;

#[test]
fn the_footer_and_help_come_from_the_key_table() {
    let s = start();
    let text = screen(&s.app, 120, 36);
    let footer = text.lines().last().expect("a footer").to_string();
    for hint in ["space play", ", . step", "? help", "q quit"] {
        assert!(footer.contains(hint), "{footer}");
    }
    let narrow = screen(&s.app, 80, 24);
    let footer = narrow.lines().last().expect("a footer").to_string();
    assert!(footer.contains("? help") && footer.contains("q quit"), "{footer}");
    let mut s = start();
    s.key(KeyCode::Char('?'));
    let help = screen(&s.app, 120, 36);
    // The overlay's text with its wrapping undone: the rows' words in order.
    let words = |text: &str| text.split_whitespace().collect::<Vec<_>>().join(" ");
    let inside: String = help
        .lines()
        .filter_map(|l| l.split('│').nth(2))
        .collect::<Vec<_>>()
        .join(" ");
    for row in crate::tui::vocabulary::key_table::BINDINGS.iter().take(6) {
        assert!(
            words(&inside).contains(&words(row.help)),
            "no `{}` in\n{help}",
            row.help
        );
    }
}

/// The footer alone, in its place on a 120×36 screen.
#[test]
fn panel_footer_alone() {
    let app = mid_impact().app;
    insta::assert_snapshot!(
        "panel_footer",
        panel(&app, full().footer, super::render).backend()
    );
}

/// On a projector's 80×24 the keys a lesson uses stay in the footer (replay, random, throw,
/// map, presentation: they were dropped for want of room); the least used give up their
/// words first, then go.
#[test]
fn the_lessons_keys_stay_in_the_footer_at_80_columns() {
    let s = start();
    let narrow = screen(&s.app, 80, 24);
    let footer = narrow.lines().last().expect("a footer").to_string();
    let keys: Vec<&str> = footer.split_whitespace().collect();
    for key in ["space", "r", "R", "b", "f", "Tab", "P", "?", "q"] {
        assert!(keys.contains(&key), "no `{key}` in {footer}");
    }
    assert!(
        footer.contains("space play") && footer.contains("? help"),
        "{footer}"
    );
}
