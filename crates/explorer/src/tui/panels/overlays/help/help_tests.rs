//! The help overlay.

use crate::tui::tests::fixtures::{help, screen, start};
use crate::tui::vocabulary::key_table::{Action, Scope, label};
use ratatui::crossterm::event::KeyCode;

#[test]
fn help_overlay() {
    let s = help();
    insta::assert_snapshot!("help_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("help_80x24", screen(&s.app, 80, 24));
}

/// The help at a projector's 80×24: a wrapped line goes on under its own text, never at the
/// overlay's left edge where it reads as an item, and quitting is on its first page.
#[test]
fn the_help_hangs_its_wrapped_lines_and_shows_quit_on_its_first_page() {
    let mut s = start();
    s.key(KeyCode::Char('?'));
    let text = screen(&s.app, 80, 24);
    let lines: Vec<&str> = text.lines().map(|l| l.trim_matches('"')).collect();
    let top = lines
        .iter()
        .position(|l| l.contains("help · the model"))
        .expect("the help");
    let rows: Vec<&str> = lines[top + 1..]
        .iter()
        .take_while(|l| l.starts_with('│'))
        .filter_map(|l| l.split('│').nth(1))
        .collect();
    let keys_end = rows
        .iter()
        .position(|r| r.starts_with("Basin-map"))
        .unwrap_or(rows.len());
    for r in &rows[1..keys_end] {
        let first = r.chars().next().unwrap_or(' ');
        assert!(first == ' ', "a line at the left edge: {r:?}\n{text}");
        // A key row starts two columns in; a continuation at the text's column, 16.
        let indent = r.chars().take_while(|c| *c == ' ').count();
        assert!(
            indent == 2 || indent == 16 || r.trim().is_empty(),
            "{indent}: {r:?}\n{text}"
        );
    }
    let quit = label(Scope::Die, Action::Quit);
    assert!(
        rows.iter()
            .any(|r| r.trim_start().starts_with(&format!("{quit} ")) && r.contains("quit")),
        "quit on the first page:\n{text}"
    );
}
