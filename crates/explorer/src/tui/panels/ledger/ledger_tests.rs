//! The energy ledger: the bar of the energy now and the books of the energy gone.

use crate::tui::panels::ledger::bar_rows;
use crate::tui::tests::fixtures::{full, mid_impact, panel, screen, settled, shipped, start};
use crate::tui::vocabulary::layout::screen_layout;
use ratatui::crossterm::event::KeyCode;
use ratatui::style::Color;

#[test]
fn ledger_panel_mid_impact_and_settled() {
    let area = full().ledger;
    insta::assert_snapshot!(
        "ledger_mid_impact",
        panel(&mid_impact().app, area, crate::tui::panels::ledger::render).backend()
    );
    insta::assert_snapshot!(
        "ledger_settled",
        panel(&settled().app, area, crate::tui::panels::ledger::render).backend()
    );
}

#[test]
fn the_books_close_as_shown() {
    for s in [start(), mid_impact(), settled()] {
        let l = s.app.roll.live.ledger;
        let sum = l.current + l.damping_loss + l.friction_loss + l.integrator_loss;
        assert!((sum - l.initial).abs() <= 1e-9 * l.initial, "{l:?}");
        assert_eq!(l.current, s.app.roll.live.energy.total());
    }
    let l = settled().app.roll.live.ledger;
    assert!(
        l.damping_loss > 0.5 * l.initial,
        "damping takes most of it: {l:?}"
    );
}

#[test]
fn bar_is_full_at_the_start_and_drains_as_the_roll_goes_on() {
    let rows = 15;
    let (cells, total) = bar_rows(&start().app, rows);
    assert!(cells.iter().all(Option::is_some), "nothing lost yet: {cells:?}");
    assert_eq!(total, Some(rows - 1));
    // At the start the die is high up: gravity (index 0) is the bottom and the bulk.
    assert_eq!(cells[0], Some(0));
    assert!(cells.iter().filter(|c| **c == Some(0)).count() >= 12);
    let (cells, total) = bar_rows(&settled().app, rows);
    assert!(cells.iter().filter(|c| c.is_some()).count() <= 1, "{cells:?}");
    assert_eq!(total, Some(0));
    // Mid-impact the spring holds a visible share: the elastic form (index 3) shows.
    let (cells, _) = bar_rows(&mid_impact().app, rows);
    assert!(cells.contains(&Some(3)), "{cells:?}");
}

#[test]
fn bar_cells_take_the_colours_of_the_plot_lines() {
    let s = start();
    let area = full().ledger;
    let t = panel(&s.app, area, crate::tui::panels::ledger::render);
    let b = t.backend().buffer();
    let series = s.app.theme.energy_series();
    // Bottom row inside the border: gravity, drawn in the gravitational line's colour.
    let bottom = area.height - 2;
    assert_eq!(b[(1, bottom)].symbol(), "█");
    assert_eq!(b[(1, bottom)].fg, series[3]);
    assert_eq!(series[3], Color::Green);
}

/// Defect: `slow-motion-classroom`, `Home`, `.` ×133: the ledger cut `friction` mid-word.
#[test]
fn the_ledger_never_cuts_a_word() {
    let mut s = shipped("slow-motion-classroom");
    s.key(KeyCode::Home);
    for _ in 0..133 {
        s.key(KeyCode::Char('.'));
    }
    for (w, h) in [(80, 24), (100, 30), (120, 36)] {
        let text = screen(&s.app, w, h);
        let areas = screen_layout(ratatui::layout::Rect::new(0, 0, w, h)).expect("a screen");
        let ledger: Vec<String> = text
            .lines()
            .skip(areas.ledger.y as usize + 1)
            .take(areas.ledger.height as usize - 1)
            .map(|l| {
                l.trim_matches('"')
                    .chars()
                    .skip(areas.ledger.x as usize)
                    .collect()
            })
            .collect();
        for row in &ledger {
            assert!(!row.contains('…'), "a word cut at {w}×{h}: {row:?}");
        }
        assert!(ledger.iter().any(|r| r.contains("fric")), "{ledger:?}");
    }
}

/// The incline past its friction angle (35°), at the end of its roll on a projector's 80×24:
/// the total keeps its label beside a seven-character number, and the rotational energy of
/// a die that slides without turning reads 0, not the arithmetic's 1e-28.
#[test]
fn the_sliding_die_shows_its_total_and_no_rounding_noise_at_80_columns() {
    let mut s = shipped("incline");
    s.select(crate::tui::vocabulary::param::Param::named("ground.tilt"));
    s.key(KeyCode::Enter);
    for key in [
        KeyCode::Backspace,
        KeyCode::Backspace,
        KeyCode::Backspace,
        KeyCode::Backspace,
    ] {
        s.key(key);
    }
    for c in "35".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    s.run_to_end();
    assert!(
        s.app.roll.live.energy.rotational.abs() < 1e-9,
        "it slides without turning"
    );
    let text = screen(&s.app, 80, 24);
    let ledger: Vec<String> = text
        .lines()
        .map(|l| l.chars().skip(60).collect::<String>())
        .collect();
    let ledger = ledger.join("\n");
    assert!(ledger.contains("total"), "{ledger}");
    assert!(!ledger.contains("e-"), "{ledger}");
    assert!(
        ledger.contains("rot") && ledger.lines().any(|l| l.contains("rot") && l.contains(" 0 │")),
        "{ledger}"
    );
}
