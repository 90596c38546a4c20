//! The outcome table: counts, shares and their intervals, the fairness test, the endings.

use crate::tui::panels::outcomes;
use crate::tui::panels::outcomes::RELIABLE_ROLLS;
use crate::tui::state::app::App;
use crate::tui::tests::fixtures::{filled_table, full, mid_impact_with, panel, panel_at, screen, text};
use crate::tui::vocabulary::theme::Theme;

#[test]
fn filled_outcome_table() {
    let s = filled_table();
    assert_eq!(s.app.roll.table.rolls(), 601);
    insta::assert_snapshot!("table_120x36", screen(&s.app, 120, 36));
    insta::assert_snapshot!("table_80x24", screen(&s.app, 80, 24));
}

/// A table with every ending: faces, rolls without a face, rolls that did not settle and
/// unstable ones.
fn every_ending() -> App {
    let mut s = mid_impact_with(Theme::default());
    let t = &mut s.app.roll.table;
    t.tally.counts = vec![512, 498, 530, 505, 470, 558];
    t.without_face = 7;
    t.did_not_settle = 16;
    t.unstable = 2114;
    s.app
}

#[test]
fn the_outcome_table_shows_every_ending_whole() {
    let app = every_ending();
    for (w, h) in [(80, 24), (120, 36)] {
        let b = panel_at(&app, w, h, |a| a.outcomes, outcomes::render);
        let t = text(&b);
        let flat = t
            .lines()
            .map(|l| l.trim_matches(|c| c == '│' || c == ' ' || c == '└' || c == '┘' || c == '─'))
            .collect::<Vec<_>>()
            .join(" ");
        for words in [
            "settled without a face 7",
            "did not settle 16",
            "unstable 2114",
            "n 3073",
        ] {
            assert!(flat.contains(words), "`{words}` at {w}×{h}:\n{t}");
        }
        for face in 1..=6 {
            assert!(t.contains(&format!("  {face}  ")), "face {face} at {w}×{h}:\n{t}");
        }
        insta::assert_snapshot!(format!("outcomes_every_ending_{w}x{h}"), t);
    }
}

/// The 95 % Wilson score interval, written out here from its formula.
fn wilson(k: u64, n: u64) -> [f64; 2] {
    let (k, n, z) = (k as f64, n as f64, 1.959_963_984_540_054);
    let p = k / n;
    let centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
    let half = z / (1.0 + z * z / n) * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
    [centre - half, centre + half]
}

#[test]
fn each_face_shows_its_95_percent_interval_in_figures_and_on_its_bar() {
    let app = every_ending();
    let counts = app.roll.table.tally.counts.clone();
    let n: u64 = counts.iter().sum();
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    assert!(t.contains("95 % int."), "{t}");
    for (f, &k) in counts.iter().enumerate() {
        let [low, high] = wilson(k, n).map(|x| 100.0 * x);
        let figures = format!("{low:.1}–{high:.1}");
        let row = t
            .lines()
            .find(|l| l.starts_with(&format!("│  {}  ", f + 1)))
            .unwrap_or_else(|| panic!("face {} row:\n{t}", f + 1));
        assert!(row.contains(&figures), "face {} wants {figures}:\n{row}", f + 1);
    }
    // Where the interval covers 1/6 the fair mark sits inside the shading.
    let wide = |k: u64| outcomes::share_bar(k as f64 / n as f64, Some(wilson(k, n)), 29, 0.0, 1.0 / 6.0);
    let (low, fair, high) = (wide(350), wide(480), wide(700));
    assert!(fair.contains('┼') && !fair.contains('┆'), "{fair}");
    // Above 1/6 the solid bar runs through the mark's cell; below it the mark stands alone.
    assert!(
        high.chars().nth(14) == Some('█') && !high.contains('┼') && !high.contains('┆'),
        "above 1/6: {high}"
    );
    assert!(low.contains('┆') && !low.contains('┼'), "below 1/6: {low}");
    // A tight interval around 1/6 on a narrow bar (12 cells, 2.8 % each): 15.5–16.9 %
    // covers the fair share, so the mark reads fair though no cell is half shaded.
    let tight = outcomes::share_bar(0.162, Some([0.155, 0.169]), 12, 0.0, 1.0 / 6.0);
    assert_eq!(tight.chars().nth(6), Some('┼'), "{tight}");
    let below = outcomes::share_bar(0.150, Some([0.143, 0.157]), 12, 0.0, 1.0 / 6.0);
    assert_eq!(below.chars().nth(6), Some('┆'), "{below}");
    let above = outcomes::share_bar(0.185, Some([0.177, 0.192]), 12, 0.0, 1.0 / 6.0);
    assert_eq!(above.chars().nth(6), Some('█'), "{above}");
    // The solid part ends at the interval's low end, the shading at its high end.
    let [l, h] = wilson(700, n);
    let cells = |x: f64| x * 3.0 * 29.0;
    let solid = high.chars().filter(|&c| c == '█').count() as f64;
    let reach = high.trim_end().chars().count() as f64;
    assert!(
        (solid - cells(l)).abs() <= 1.0,
        "solid {solid} cells, low end at {}",
        cells(l)
    );
    assert!(
        (reach - cells(h)).abs() <= 1.0,
        "bar ends at {reach}, high end at {}",
        cells(h)
    );
    // At 80×24 the figures stay (a class reads them off a projector) and the count column
    // gives way; the bar is still shaded.
    let t = text(&panel_at(&app, 80, 24, |a| a.outcomes, outcomes::render));
    let [low, high] = wilson(counts[0], n).map(|x| 100.0 * x);
    assert!(t.contains(&format!("{low:.1}–{high:.1}")), "{t}");
    assert!(!t.contains("count") && t.contains('░'), "{t}");
}

#[test]
fn the_table_says_how_many_rolls_show_its_bias() {
    let mut app = every_ending();
    app.roll.table.without_face = 0;
    app.roll.table.did_not_settle = 0;
    app.roll.table.unstable = 0;
    // The heavy-corner die's shares, 20 000 rolls: a bias a class can measure.
    app.roll.table.tally.counts = vec![3000, 3000, 3000, 3700, 3650, 3650];
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    let n = app.roll.table.tally.rolls_to_detect().expect("a measured bias");
    assert!(
        t.contains(&format!(
            "bias this large shows in {} rolls",
            crate::tui::vocabulary::format::group(n)
        )),
        "{t}"
    );
    assert!(n > 100 && n < 20_000, "{n}");
    app.roll.table.tally.counts = vec![100, 100, 100, 100, 100, 100];
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    assert!(t.contains("no bias beyond chance so far"), "{t}");
}

#[test]
fn a_p_value_from_too_few_rolls_is_marked_unreliable() {
    let mut app = every_ending();
    app.roll.table.tally.counts = vec![3, 5, 4, 6, 2, 4];
    assert!(app.roll.table.tally.total() < RELIABLE_ROLLS);
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    assert!(t.contains("unreliable below n 30"), "{t}");
    app.roll.table.tally.counts = vec![30, 50, 40, 60, 20, 40];
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    assert!(!t.contains("unreliable") && t.contains(" p "), "{t}");
}

/// The outcome table alone, in its place on a 120×36 screen.
#[test]
fn panel_outcomes_alone() {
    let app = filled_table().app;
    insta::assert_snapshot!(
        "panel_outcomes",
        panel(&app, full().outcomes, super::render).backend()
    );
}
