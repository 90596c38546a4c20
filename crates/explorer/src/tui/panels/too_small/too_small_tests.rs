//! The notice shown instead of a screen too small for the explorer.

use crate::tui::tests::fixtures::{screen, start};

#[test]
fn too_small_says_how_large() {
    let s = start();
    let text = screen(&s.app, 70, 20);
    assert!(text.contains("at least 80×24"), "{text}");
    insta::assert_snapshot!("too_small_70x20", text);
}
