//! Tests of the classroom views (energy ledger, vectors, chaos twin, presets, exports,
//! themes) from deterministic states, built with the helpers of `tests.rs`.

use super::app::App;
use super::ledger::{bar_rows, render_ledger};
use super::render::screen_layout;
use super::tests::{mid_impact, settled, start};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::layout::Rect;
use ratatui::style::Color;

/// One panel drawn on its own, as the full 120×36 screen places it.
fn panel(app: &App, area: Rect, draw: fn(&App, Rect, &mut ratatui::Frame)) -> Terminal<TestBackend> {
    let mut t = Terminal::new(TestBackend::new(area.width, area.height)).expect("test backend");
    t.draw(|f| draw(app, f.area(), f)).expect("draw");
    t
}

fn full() -> super::render::Areas {
    screen_layout(Rect::new(0, 0, 120, 36)).expect("full size")
}

mod ledger {
    use super::*;

    #[test]
    fn ledger_panel_mid_impact_and_settled() {
        let area = full().ledger;
        insta::assert_snapshot!(
            "ledger_mid_impact",
            panel(&mid_impact().app, area, render_ledger).backend()
        );
        insta::assert_snapshot!(
            "ledger_settled",
            panel(&settled().app, area, render_ledger).backend()
        );
    }

    #[test]
    fn the_books_close_as_shown() {
        for s in [start(), mid_impact(), settled()] {
            let l = s.app.live.ledger;
            let sum = l.current + l.damping_loss + l.friction_loss + l.integrator_loss;
            assert!((sum - l.initial).abs() <= 1e-9 * l.initial, "{l:?}");
            assert_eq!(l.current, s.app.live.energy.total());
        }
        let l = settled().app.live.ledger;
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
        let t = panel(&s.app, area, render_ledger);
        let b = t.backend().buffer();
        let series = s.app.theme.energy_series();
        // Bottom row inside the border: gravity, drawn in the gravitational line's colour.
        let bottom = area.height - 2;
        assert_eq!(b[(1, bottom)].symbol(), "█");
        assert_eq!(b[(1, bottom)].fg, series[3]);
        assert_eq!(series[3], Color::Green);
    }
}

mod vectors {
    use super::super::render::render_die;
    use super::super::vectors::{ARROWS, Arrow, arrow_length};
    use super::*;
    use crate::tui::app::{Msg, update};
    use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};

    fn with_vectors() -> App {
        let mut app = mid_impact().app;
        let sent = update(
            &mut app,
            Msg::Input(Event::Key(KeyEvent::new(KeyCode::Char('v'), KeyModifiers::NONE))),
        );
        assert!(sent.is_empty(), "a view toggle asks nothing of the worker");
        assert!(app.vectors);
        app
    }

    #[test]
    fn v_toggles_the_arrows() {
        let mut app = with_vectors();
        update(
            &mut app,
            Msg::Input(Event::Key(KeyEvent::new(KeyCode::Char('v'), KeyModifiers::NONE))),
        );
        assert!(!app.vectors);
    }

    #[test]
    fn lengths_are_log_compressed() {
        assert_eq!(arrow_length(0.0, 1.0, 1.0), 0.0);
        assert!((arrow_length(9.0, 1.0, 1.0) - 1.0).abs() < 1e-12);
        assert!((arrow_length(99.0, 1.0, 2.0) - 4.0).abs() < 1e-12);
        // A hundredfold force is drawn only about three times as long.
        let (small, big) = (
            arrow_length(980.0, 980.0, 1.0),
            arrow_length(98_000.0, 980.0, 1.0),
        );
        assert!(big / small > 2.0 && big / small < 7.0);
        assert_eq!(arrow_length(f64::NAN, 1.0, 1.0), 0.0);
    }

    #[test]
    fn die_with_vectors_mid_impact() {
        let app = with_vectors();
        let area = full().die;
        let t = panel(&app, area, render_die);
        insta::assert_snapshot!("die_vectors_mid_impact", t.backend());
        let b = t.backend().buffer();
        let text: String = (0..area.height)
            .flat_map(|y| (0..area.width).map(move |x| (x, y)))
            .map(|p| b[p].symbol().to_string())
            .collect();
        assert!(text.contains("length a·log₁₀(1+|x|/x₀)"), "{text}");
        // Every arrow is drawn in its own colour somewhere in the panel.
        for kind in ARROWS {
            let colour = kind.colour(&app);
            let cells = (0..area.height)
                .flat_map(|y| (0..area.width).map(move |x| (x, y)))
                .filter(|&p| b[p].fg == colour)
                .count();
            assert!(cells > 2, "{kind:?} in {colour:?}: {cells} cells");
        }
        assert_eq!(Arrow::AngularVelocity.colour(&app), Color::Cyan);
        // Without the toggle none of the arrow colours but the contact red appears.
        let plain = panel(&mid_impact().app, area, render_die);
        let pb = plain.backend().buffer();
        let cyan = (0..area.height)
            .flat_map(|y| (0..area.width).map(move |x| (x, y)))
            .filter(|&p| pb[p].fg == Color::Cyan)
            .count();
        assert_eq!(cyan, 0);
    }
}
