//! The parameter list: values, their limits, the stability readout and refusals.

use crate::tui::panels::params_panel::{STABILITY_CAUTION, STABILITY_DANGER};
use crate::tui::state::app::App;
use crate::tui::tests::fixtures::{Harness, full, mid_impact, panel, screen, stability_readout_cell, start};
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::theme::Theme;
use crate::worker::Command;
use dicesim_physics::{Limit, Stability};
use dicesim_setup::preset::Preset;
use ratatui::crossterm::event::KeyCode;
use ratatui::style::{Color, Modifier};

#[test]
fn stability_readout_warns_as_the_tightest_limit_nears() {
    let mut s = start();
    let (text, calm) = stability_readout_cell(&s.app);
    assert!(text.contains("of limit"), "{text}");
    assert_eq!(calm.bg, Color::Reset);
    // The contact-mode reading is ω_rock·√(1 + γ·u)·Δt, with ω_rock ∝ √k and the striking
    // factor √(1 + γ·u) free of k (docs/model.md, "Stability"): a share of its limit is
    // reached at k₀·(share·limit / reading₀)².
    let k_for = |share: f64, app: &App| {
        let p = &app.setup.params;
        let r = Stability::predict(p, &app.setup.initial)
            .reading(Limit::ContactMode)
            .unwrap();
        p.ground.stiffness * (share * r.allowed / r.value).powi(2)
    };
    let k = k_for((STABILITY_CAUTION + STABILITY_DANGER) / 2.0, &s.app);
    s.command(Command::SetParam(Param::named("ground.stiffness").scan_key(), k));
    let (text, caution) = stability_readout_cell(&s.app);
    assert!(text.contains("table stiffness at 90 % of limit"), "{text}");
    assert_eq!(caution.bg, Color::Yellow);
    let k = k_for(STABILITY_DANGER + 0.3, &s.app);
    s.command(Command::SetParam(Param::named("ground.stiffness").scan_key(), k));
    let (text, danger) = stability_readout_cell(&s.app);
    assert!(text.contains("table stiffness at 130 % of limit"), "{text}");
    assert_eq!(danger.bg, Color::Red);
    assert!(danger.modifier.contains(Modifier::BOLD));
}

#[test]
fn a_start_inside_the_table_is_refused() {
    let mut s = start();
    s.select(Param::named("initial.height"));
    s.key(KeyCode::Enter);
    for _ in 0..4 {
        s.key(KeyCode::Backspace);
    }
    s.key(KeyCode::Char('0'));
    s.key(KeyCode::Enter);
    assert_eq!(s.app.setup.initial.height, 15.0);
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("0: corner in the table; ≥ 0.9961 cm"), "{text}");
    insta::assert_snapshot!("start_inside_table_refused_80x24", screen(&s.app, 80, 24));
}

/// A batch whose random drop heights reach below the die's lowest corner (the paper's
/// preset keeps the start's orientation, upright: a cm below the centre) is refused up
/// front, as `dicesim batch` refuses it: no roll is drawn, the table stays empty and the
/// footer names the key and the lowest allowed height.
#[test]
fn a_batch_whose_range_could_start_a_corner_in_the_table_is_refused() {
    let preset = Preset::default()
        .with_overrides(&["random.height=[0.5,2]"])
        .expect("in range");
    let mut s = Harness::new(&preset, Theme::default());
    s.command(Command::BatchStart(20));
    assert!(s.simulator.take_batch_request().is_none(), "a batch was started");
    s.simulator.run_batch_here();
    s.sync();
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("batch not started"), "{text}");
    assert!(text.contains("random.height"), "{text}");
    // a = 1 cm less the resting depth M·g/(4k) = 8·980/(4·500 000) = 0.00392 cm.
    assert!(text.contains("0.99608"), "{text}");
    assert_eq!(s.app.roll.table.rolls(), 0);
}

/// The real dice's values in the parameter list: a value in range that no body can have
/// with the others is refused with the physics' reason and changes nothing; one it can have
/// is sent to the worker, which restarts the roll with the new body.
#[test]
fn a_body_value_no_die_can_have_is_refused_and_changes_nothing() {
    use crate::tui::vocabulary::param::Param;
    let preset = Preset::from_toml_str(
        dicesim_setup::preset::shipped_text("rounded-die").expect("shipped"),
        "rounded-die",
    )
    .expect("valid");
    let mut s = Harness::new(&preset, Theme::default());
    let before = (s.app.setup.params, s.app.setup.initial);
    // In the row's range (0…10 cm) but not below the smallest half size, 0.8 cm.
    let radius = Param::named("die.corner_radius");
    let refused = s.app.setup.set_param(radius, 0.9).unwrap_err();
    assert!(refused.contains("below the smallest half size"), "{refused}");
    // Pips 0.5 cm wide do not fit beside each other on a 1.6 cm face rounded by 0.15 cm.
    let refused = s
        .app
        .setup
        .set_param(Param::named("die.pip_diameter"), 0.5)
        .unwrap_err();
    assert!(refused.contains("at most 0.4 cm"), "{refused}");
    assert!((s.app.setup.params, s.app.setup.initial) == before);
    // A flatter die is a die: the worker takes it and rolls it from the start.
    let z = Param::named("die.half_sizes.z");
    s.simulator.advance_steps(50);
    let c = s.app.setup.set_param(z, 0.6).expect("a body");
    s.command(c);
    assert_eq!(s.app.roll.live.params.die.half_sizes, [0.8, 0.8, 0.6]);
    assert_eq!(
        s.app.roll.live.timeline.position, 0,
        "the body changed: the roll starts again"
    );
}

/// The parameter list alone, in its place on a 120×36 screen.
#[test]
fn panel_params_alone() {
    let app = mid_impact().app;
    insta::assert_snapshot!(
        "panel_params",
        panel(&app, full().params, super::render).backend()
    );
}
