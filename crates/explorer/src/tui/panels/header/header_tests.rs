//! The header: the preset, the roll's phase and time, and how a roll ended.

use crate::tui::tests::fixtures::{Harness, full, mid_impact, panel, screen, stability_readout_cell};
use crate::tui::vocabulary::theme::Theme;
use crate::worker::Phase;
use dicesim_physics::Status;
use dicesim_setup::preset::Preset;

/// Spin of 10 000 rad/s: the readout and the roll's end both say a corner moves too far
/// per step, and by how much.
#[test]
fn fast_spin_is_called_unstable_with_its_reason() {
    let preset = Preset::default()
        .with_overrides(&["initial.angular_velocity=[10000,0,0]"])
        .expect("in range");
    let mut s = Harness::new(&preset, Theme::default());
    let (text, _) = stability_readout_cell(&s.app);
    // Both the corner's travel (17.5 cm a step, 1749 % of its limit) and the table's
    // contact mode, stiffened by the striking corner's speed, are past their limits; the
    // readout names the first past its limit, never a share within it.
    let percent: f64 = text
        .split(" at ")
        .nth(1)
        .and_then(|t| t.split(" %").next())
        .and_then(|t| t.trim().parse().ok())
        .expect("a share");
    assert!(percent > 100.0, "{text}");
    s.run_to_end();
    assert!(matches!(s.app.roll.live.phase, Phase::Ended(o) if o.status == Status::Unstable));
    let wide = screen(&s.app, 120, 36);
    // ω·a·√3 + the fall from 15 cm, times Δt: 17.3 + 0.17 cm.
    assert!(
        wide.contains("unstable: spin too fast for Δt: a corner moves 17.489 cm per step"),
        "{wide}"
    );
    insta::assert_snapshot!("fast_spin_unstable_120x36", wide);
    insta::assert_snapshot!("fast_spin_unstable_80x24", screen(&s.app, 80, 24));
}

/// k = 100: the table cannot hold the die, so the roll runs to its time limit instead of
/// "settling" with the die sinking through the table.
#[test]
fn a_table_too_soft_ends_as_did_not_settle() {
    let preset = Preset::default()
        .with_overrides(&["ground.stiffness=100"])
        .expect("in range");
    let mut s = Harness::new(&preset, Theme::default());
    s.run_to_end();
    assert!(matches!(s.app.roll.live.phase, Phase::Ended(o) if o.status == Status::Timeout));
    let text = screen(&s.app, 120, 36);
    assert!(
        text.contains("did not settle: the table is too soft to hold the die"),
        "{text}"
    );
    insta::assert_snapshot!("soft_table_120x36", text);
}

/// The header alone, in its place on a 120×36 screen.
#[test]
fn panel_header_alone() {
    let app = mid_impact().app;
    insta::assert_snapshot!(
        "panel_header",
        panel(&app, full().header, super::render).backend()
    );
}
