//! The chaos twin: its separation from the die and both outcomes.

use crate::tui::state::app::App;
use crate::tui::tests::fixtures::press_performing;
use crate::tui::tests::fixtures::{full, panel, start, twin_after};
use crate::worker::{Command, Phase};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::KeyCode;
use ratatui::style::Color;

fn screen(app: &App, w: u16, h: u16) -> String {
    let mut t = Terminal::new(TestBackend::new(w, h)).expect("test backend");
    t.draw(|f| crate::tui::render(app, f)).expect("draw");
    t.backend().to_string()
}

#[test]
fn chaos_twin_after_700_steps() {
    let s = twin_after(700);
    let twin = s.app.roll.live.twin.as_ref().expect("a twin");
    assert_eq!(twin.epsilon, 1e-9);
    assert_eq!(s.app.roll.live.step, 700);
    let text = screen(&s.app, 120, 36);
    assert!(
        text.contains("twin: height, velocity and spin × (1 + ε)"),
        "{text}"
    );
    insta::assert_snapshot!("twin_700_120x36", text);
    insta::assert_snapshot!("twin_700_80x24", screen(&s.app, 80, 24));
}

#[test]
fn both_outcomes_show_once_both_dice_have_settled() {
    let mut s = twin_after(0);
    s.run_to_end();
    let twin = s.app.roll.live.twin.as_ref().expect("a twin");
    assert!(matches!(twin.phase, Phase::Ended(_)), "{:?}", twin.phase);
    assert!(matches!(s.app.roll.live.phase, Phase::Ended(_)));
    let lines = crate::tui::panels::twins::separation::outcome_lines(&s.app, 80);
    assert_eq!(lines.len(), 1, "{lines:?}");
    let line = lines[0].to_string();
    assert!(line.starts_with("die settled: face"), "{line}");
    assert!(line.contains("twin settled: face"), "{line}");
    assert!(
        line.ends_with("same face") || line.ends_with("faces differ"),
        "{line}"
    );
    // On a narrow panel the verdict keeps a line of its own, whole.
    let narrow = crate::tui::panels::twins::separation::outcome_lines(&s.app, 18);
    let verdict = narrow.last().expect("lines").to_string();
    assert!(verdict == "same face" || verdict == "faces differ", "{narrow:?}");
    assert!(narrow[0].to_string().starts_with("die "), "{narrow:?}");
    // Samples cover the whole roll, up to the later of the two ends.
    let last = s.app.twin.history.last().expect("samples");
    assert_eq!(last.time_s, s.app.roll.live.time_s);
}

#[test]
fn the_ghost_is_drawn_in_its_own_colour() {
    let s = twin_after(300);
    let area = full().die;
    let t = panel(&s.app, area, crate::tui::panels::die::render);
    let b = t.backend().buffer();
    let ghost = (0..area.height)
        .flat_map(|y| (0..area.width).map(move |x| (x, y)))
        .filter(|&p| b[p].fg == Color::DarkGray && b[p].symbol() != " ")
        .count();
    assert!(ghost > 10, "{ghost} ghost cells");
    assert_eq!(s.app.theme.ghost(), Color::DarkGray);
}

#[test]
fn t_toggles_the_twin_and_angle_brackets_step_epsilon_by_decades() {
    let mut a = start().app;
    assert_eq!(
        press_performing(&mut a, KeyCode::Char('T')),
        [Command::SetTwin(Some(1e-9))]
    );
    assert_eq!(
        press_performing(&mut a, KeyCode::Char('>')),
        [Command::SetTwin(Some(1e-8))]
    );
    assert_eq!(
        press_performing(&mut a, KeyCode::Char('<')),
        [Command::SetTwin(Some(1e-9))]
    );
    for _ in 0..20 {
        press_performing(&mut a, KeyCode::Char('<'));
    }
    assert_eq!(a.twin.epsilon, 1e-15);
    assert!(
        press_performing(&mut a, KeyCode::Char('<')).is_empty(),
        "at its floor"
    );
    for _ in 0..20 {
        press_performing(&mut a, KeyCode::Char('>'));
    }
    assert_eq!(a.twin.epsilon, 0.1);
    assert_eq!(
        press_performing(&mut a, KeyCode::Char('T')),
        [Command::SetTwin(None)]
    );
    // Without a twin, ε keys do nothing.
    assert!(press_performing(&mut a, KeyCode::Char('>')).is_empty());
    assert!(press_performing(&mut a, KeyCode::Char('E')).is_empty() && a.epsilon_editor().is_none());
}

#[test]
fn typing_epsilon_validates_it() {
    let mut a = start().app;
    press_performing(&mut a, KeyCode::Char('T'));
    press_performing(&mut a, KeyCode::Char('E'));
    for c in "1e-20".chars() {
        assert!(press_performing(&mut a, KeyCode::Char(c)).is_empty());
    }
    assert!(press_performing(&mut a, KeyCode::Enter).is_empty());
    let error = a.epsilon_editor().and_then(|e| e.error.clone());
    assert_eq!(error.as_deref(), Some("ε = 1e-20 is outside 1e-15…0.1"));
    for _ in 0..5 {
        press_performing(&mut a, KeyCode::Backspace);
    }
    for c in "2e-3".chars() {
        press_performing(&mut a, KeyCode::Char(c));
    }
    assert_eq!(
        press_performing(&mut a, KeyCode::Enter),
        [Command::SetTwin(Some(2e-3))]
    );
    assert!(a.epsilon_editor().is_none());
    press_performing(&mut a, KeyCode::Char('E'));
    press_performing(&mut a, KeyCode::Char('q'));
    assert!(!a.quit, "q is not a digit and does not quit while typing");
    press_performing(&mut a, KeyCode::Esc);
    assert!(a.epsilon_editor().is_none() && !a.quit);
}

#[test]
fn the_simulator_steps_both_dice_in_lock_step_from_the_epsilon_scale() {
    let mut s = start();
    s.command(Command::SetTwin(Some(1e-9)));
    let twin = s.app.roll.live.twin.as_ref().expect("a twin");
    let h = s.app.setup.initial.height;
    assert!((twin.separation.centre - 1e-9 * h).abs() < 1e-6 * 1e-9 * h);
    assert_eq!(s.app.twin.history.len(), 1);
    s.command(Command::SetPlaying(false));
    s.simulator.advance_steps(2000);
    s.sync();
    let twin = s.app.roll.live.twin.as_ref().expect("a twin");
    assert!(twin.separation.centre > 1e3 * 1e-9 * h, "{:?}", twin.separation);
    let times: Vec<f64> = s.app.twin.history.iter().map(|x| x.time_s).collect();
    assert!(times.windows(2).all(|w| w[0] < w[1]), "one sample per time");
    // Out of range ε: refused with a notice, the twin stays as it was.
    s.command(Command::SetTwin(Some(1.0)));
    assert!(
        s.app
            .notice
            .as_deref()
            .is_some_and(|n| n.contains("twin.epsilon"))
    );
    assert_eq!(s.app.roll.live.twin.as_ref().map(|t| t.epsilon), Some(1e-9));
    s.command(Command::SetTwin(None));
    assert!(s.app.roll.live.twin.is_none());
}
