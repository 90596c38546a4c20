//! The parameter twin: die B's setup, its table of shared throws.

use crate::tui::state::app::App;
use crate::tui::tests::fixtures::{Harness, screen, spun_preset, start};
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::theme::{Palette, Theme};
use crate::worker::{Command, Phase};
use dicesim_physics::Simulation;
use ratatui::crossterm::event::KeyCode;

fn projector() -> Theme {
    Theme {
        palette: Palette::Projector,
        ..Theme::default()
    }
}

/// Differ mode on, friction selected, typed 0.3 (A keeps the paper's μ).
fn differing(theme: Theme) -> Harness {
    let mut s = start();
    s.app.theme = theme;
    s.key(KeyCode::Char('D'));
    s.select(Param::named("ground.friction"));
    s.key(KeyCode::Enter);
    for c in "0.3".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    s
}

fn friction(app: &App) -> f64 {
    app.setup.params.ground.friction
}

#[test]
fn a_typed_value_goes_to_b_only_and_a_keeps_its_own() {
    let paper = spun_preset().params().ground.friction;
    assert_ne!(paper, 0.3, "the test needs a change");
    let mut s = differing(Theme::default());
    assert_eq!(friction(&s.app), paper, "A's value on screen");
    assert_eq!(
        s.simulator.params().ground.friction,
        paper,
        "A's value in the worker"
    );
    let twin = s.app.roll.live.twin.clone().expect("die B rolls");
    assert_eq!(twin.differs_by.len(), 1);
    assert_eq!(
        (twin.differs_by[0].0.key.as_str(), twin.differs_by[0].1),
        ("ground.friction", 0.3)
    );
    // A nudge steps on from B's value, not from A's.
    s.key(KeyCode::Right);
    let b = s.app.twin.differs_by[0].1;
    assert!(b > 0.3 && b < paper, "B stepped up from 0.3 to {b}");
    assert_eq!(friction(&s.app), paper);
    // D again ends it: no die B, and the next change is A's.
    s.key(KeyCode::Char('D'));
    assert!(s.app.roll.live.twin.is_none());
    s.key(KeyCode::Right);
    assert!(friction(&s.app) > paper, "A changes again");
}

#[test]
fn both_outcomes_are_the_physics_of_each_setup() {
    let mut s = differing(Theme::default());
    s.command(Command::SetPlaying(false));
    s.run_to_end();
    let preset = spun_preset();
    let mut b = preset.params();
    b.ground.friction = 0.3;
    let face = |p| {
        Simulation::new(p, &preset.initial)
            .expect("valid")
            .run_to_end()
            .face
            .expect("a face")
    };
    let (a, b) = (face(&preset.params()), face(&b));
    let text = screen(&s.app, 120, 36);
    // The die panel's title words both, in full or (short of room) by the faces alone.
    let (full, short) = (format!("A face {a} · B face {b}"), format!("A {a} · B {b}"));
    assert!(text.contains(&full) || text.contains(&short), "{text}");
    assert!(text.contains("B: friction μ 0.3"), "{text}");
    let Some(twin) = &s.app.roll.live.twin else {
        panic!("B rolls")
    };
    assert!(matches!(twin.phase, Phase::Ended(_)));
}

#[test]
fn dt_cannot_differ_and_changes_nothing() {
    let mut s = start();
    s.key(KeyCode::Char('D'));
    let dt = s.app.setup.params.integrator.dt;
    s.select(Param::named("integrator.dt"));
    s.key(KeyCode::Right);
    assert_eq!(s.app.setup.params.integrator.dt, dt);
    assert_eq!(s.simulator.params().integrator.dt, dt);
    assert!(s.app.roll.live.twin.is_none());
    assert!(
        s.app
            .notice
            .as_deref()
            .is_some_and(|n| n.contains("Δt cannot differ")),
        "{:?}",
        s.app.notice
    );
}

#[test]
fn the_parameter_twin_screen() {
    let mut s = differing(projector());
    s.command(Command::SetPlaying(false));
    s.simulator.advance_steps(700);
    // A batch of shared throws, each rolled in A and in B, fills the table.
    s.app.roll.batch_size = 60;
    s.key(KeyCode::Char('b'));
    s.simulator.run_batch_here();
    s.sync();
    let table = s.app.roll.live.versus.expect("the shared throws' table");
    assert_eq!(table.throws(), 60);
    let text = screen(&s.app, 120, 36);
    let (share, [lo, hi]) = table.agreement().expect("faces in both");
    let agree = format!(
        "agree {}/{} = {:.1} % (95 % {:.1}–{:.1} %)",
        table.agreeing(),
        table.faced(),
        100.0 * share,
        100.0 * lo,
        100.0 * hi
    );
    assert!(text.contains(&agree), "{text}");
    assert!(text.contains("━B total"), "die B's curve is named: {text}");
    insta::assert_snapshot!("versus_twin_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("versus_twin_80x24", screen(&s.app, 80, 24));
    // A quantity plotted: A's curve and B's, named in the title.
    s.key(KeyCode::Char('w'));
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("━A ━B"), "{text}");
    insta::assert_snapshot!("versus_twin_height_120x36", text);
}

#[test]
fn die_b_is_drawn_with_its_own_body() {
    // B rounded by 0.4 cm while A keeps the paper's sharp cube.
    let mut s = start();
    s.key(KeyCode::Char('D'));
    s.select(Param::named("die.corner_radius"));
    s.key(KeyCode::Enter);
    for c in "0.4".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    assert_eq!(s.app.roll.live.params.die.corner_radius, 0.0, "A stays sharp");
    let twin = s.app.roll.live.twin.clone().expect("die B rolls");
    let crate::tui::vocabulary::solid::Body::Box(b) = crate::tui::panels::die::twin_body(&s.app, &twin)
    else {
        panic!("die B is a box")
    };
    assert_eq!(b.radius, 0.4);
}
