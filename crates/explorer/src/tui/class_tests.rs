//! Tests of the classroom views (energy ledger, vectors, chaos twin, presets, exports,
//! themes) from deterministic states, built with the helpers of `tests.rs`.

use super::state::app::App;
use super::tests::{mid_impact, settled, start};
use crate::tui::panels::ledger::bar_rows;
use crate::tui::vocabulary::layout::screen_layout;
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

fn full() -> crate::tui::vocabulary::layout::Areas {
    screen_layout(Rect::new(0, 0, 120, 36)).expect("full size")
}

mod ledger {
    use super::*;

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
}

mod vectors {
    use super::*;
    use crate::tui::input::update::update;
    use crate::tui::panels::die;
    use crate::tui::panels::die::vectors::{ARROWS, Arrow, arrow_length};
    use crate::tui::state::messages::Msg;
    use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};

    fn with_vectors() -> App {
        let mut app = mid_impact().app;
        let sent = update(
            &mut app,
            Msg::Input(Event::Key(KeyEvent::new(KeyCode::Char('v'), KeyModifiers::NONE))),
        );
        assert!(sent.is_empty(), "a view toggle asks nothing of the worker");
        assert!(app.die_screen.arrows);
        app
    }

    #[test]
    fn v_toggles_the_arrows() {
        let mut app = with_vectors();
        update(
            &mut app,
            Msg::Input(Event::Key(KeyEvent::new(KeyCode::Char('v'), KeyModifiers::NONE))),
        );
        assert!(!app.die_screen.arrows);
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
        let t = panel(&app, area, die::render);
        insta::assert_snapshot!("die_vectors_mid_impact", t.backend());
        let b = t.backend().buffer();
        let text: String = (0..area.height)
            .flat_map(|y| (0..area.width).map(move |x| (x, y)))
            .map(|p| b[p].symbol().to_string())
            .collect();
        assert!(text.contains("10× as big is half a die longer"), "{text}");
        assert!(
            !text.contains("log₁₀"),
            "the scale in words, not a formula: {text}"
        );
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
        let plain = panel(&mid_impact().app, area, die::render);
        let pb = plain.backend().buffer();
        let cyan = (0..area.height)
            .flat_map(|y| (0..area.width).map(move |x| (x, y)))
            .filter(|&p| pb[p].fg == Color::Cyan)
            .count();
        assert_eq!(cyan, 0);
    }
}

mod twin {
    use super::*;
    use crate::tui::input::update::update;
    use crate::tui::state::messages::Msg;
    use crate::tui::tests::Harness;
    use crate::worker::{Command, Phase};
    use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};

    fn press(app: &mut App, code: KeyCode) -> Vec<Command> {
        update(
            app,
            Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))),
        )
        .into_iter()
        .filter_map(|e| crate::tui::event_loop::effects::perform(app, e))
        .collect()
    }

    /// The paper's roll and its twin at ε = 1e-9, `steps` steps in.
    pub(crate) fn twin_after(steps: u64) -> Harness {
        let mut s = start();
        s.key(KeyCode::Char('T'));
        s.command(Command::SetPlaying(false));
        s.simulator.advance_steps(steps);
        s.sync();
        s
    }

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
        assert_eq!(press(&mut a, KeyCode::Char('T')), [Command::SetTwin(Some(1e-9))]);
        assert_eq!(press(&mut a, KeyCode::Char('>')), [Command::SetTwin(Some(1e-8))]);
        assert_eq!(press(&mut a, KeyCode::Char('<')), [Command::SetTwin(Some(1e-9))]);
        for _ in 0..20 {
            press(&mut a, KeyCode::Char('<'));
        }
        assert_eq!(a.twin.epsilon, 1e-15);
        assert!(press(&mut a, KeyCode::Char('<')).is_empty(), "at its floor");
        for _ in 0..20 {
            press(&mut a, KeyCode::Char('>'));
        }
        assert_eq!(a.twin.epsilon, 0.1);
        assert_eq!(press(&mut a, KeyCode::Char('T')), [Command::SetTwin(None)]);
        // Without a twin, ε keys do nothing.
        assert!(press(&mut a, KeyCode::Char('>')).is_empty());
        assert!(press(&mut a, KeyCode::Char('E')).is_empty() && a.epsilon_editor().is_none());
    }

    #[test]
    fn typing_epsilon_validates_it() {
        let mut a = start().app;
        press(&mut a, KeyCode::Char('T'));
        press(&mut a, KeyCode::Char('E'));
        for c in "1e-20".chars() {
            assert!(press(&mut a, KeyCode::Char(c)).is_empty());
        }
        assert!(press(&mut a, KeyCode::Enter).is_empty());
        let error = a.epsilon_editor().and_then(|e| e.error.clone());
        assert_eq!(error.as_deref(), Some("ε = 1e-20 is outside 1e-15…0.1"));
        for _ in 0..5 {
            press(&mut a, KeyCode::Backspace);
        }
        for c in "2e-3".chars() {
            press(&mut a, KeyCode::Char(c));
        }
        assert_eq!(press(&mut a, KeyCode::Enter), [Command::SetTwin(Some(2e-3))]);
        assert!(a.epsilon_editor().is_none());
        press(&mut a, KeyCode::Char('E'));
        press(&mut a, KeyCode::Char('q'));
        assert!(!a.quit, "q is not a digit and does not quit while typing");
        press(&mut a, KeyCode::Esc);
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
}

mod presets {
    use super::*;
    use crate::tui::input::update::update;
    use crate::tui::state::dialog::{Dialog, Group};
    use crate::tui::state::messages::Msg;
    use crate::tui::tests::Harness;
    use crate::tui::vocabulary::param::Param;
    use crate::worker::Command;
    use dicesim_setup::preset::{LESSON, Preset, Store};
    use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};

    fn press(app: &mut App, code: KeyCode) -> Vec<Command> {
        update(
            app,
            Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))),
        )
        .into_iter()
        .filter_map(|e| crate::tui::event_loop::effects::perform(app, e))
        .collect()
    }

    fn type_text(app: &mut App, text: &str) {
        for c in text.chars() {
            assert!(press(app, KeyCode::Char(c)).is_empty());
        }
    }

    /// A user folder holding one preset of the user's, `lab-2`.
    fn folder() -> (tempfile::TempDir, Store) {
        let dir = tempfile::tempdir().expect("temp dir");
        let store = Store::new(Some(dir.path().to_path_buf()));
        let mut mine = Preset {
            name: "lab-2".to_string(),
            description: "Our second lab: the paper's die from 30 cm.".to_string(),
            ..Preset::default()
        };
        mine.initial.height = 30.0;
        store.save(&mine, false).expect("saved");
        (dir, store)
    }

    fn screen(app: &App, w: u16, h: u16) -> String {
        let mut t = Terminal::new(TestBackend::new(w, h)).expect("test backend");
        t.draw(|f| crate::tui::render(app, f)).expect("draw");
        t.backend().to_string()
    }

    #[test]
    fn picker_lists_shipped_and_user_presets_and_loads_the_chosen_one() {
        let (_dir, store) = folder();
        let mut s = start();
        s.app.store = store;
        s.key(KeyCode::Char('o'));
        let Some(Dialog::Picker {
            choices, selected, ..
        }) = s.app.dialog()
        else {
            panic!("the picker is open")
        };
        // The lesson's presets first, in the lesson's order; the other shipped ones; the
        // user's last.
        let names: Vec<&str> = choices.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names[..LESSON.len()], *LESSON, "{names:?}");
        assert_eq!(names.last(), Some(&"lab-2"));
        assert!(choices.last().is_some_and(|c| c.user) && choices.iter().filter(|c| c.user).count() == 1);
        let groups: Vec<Group> = choices.iter().map(|c| c.group).collect();
        assert!(groups.is_sorted(), "{groups:?}");
        assert_eq!(choices[*selected].name, "paper", "the loaded preset is selected");
        assert!(
            choices
                .iter()
                .any(|c| c.name == "icy-table" && c.group == Group::Shipped)
        );
        let wide = screen(&s.app, 120, 36);
        let narrow = screen(&s.app, 80, 24);
        // At 80×24 the seventeen shipped presets push the user's heading below the fold
        // (the list scrolls to it); at 120×36 every heading is on screen.
        for heading in [Group::Lesson, Group::Shipped, Group::Yours].map(Group::heading) {
            assert!(wide.contains(heading), "{heading} in\n{wide}");
        }
        for heading in [Group::Lesson, Group::Shipped].map(Group::heading) {
            assert!(narrow.contains(heading), "{heading} in\n{narrow}");
        }
        for text in [&wide, &narrow] {
            // The selection's description beside the list, from the dialog's first row (at
            // 80×24 the list's first row holds its "more above" marker, blank at the top).
            let row = text
                .lines()
                .skip_while(|l| !l.contains("open a preset"))
                .nth(1)
                .expect("the dialog has rows");
            assert!(row.contains("The die of Chin and Li"), "{row}");
        }
        insta::assert_snapshot!("picker_120x36", wide);
        insta::assert_snapshot!("picker_80x24", narrow);
        // Down to the user's preset and load it: the worker switches, the dialog closes.
        s.key(KeyCode::End);
        let sent = press(&mut s.app, KeyCode::Enter);
        assert!(matches!(sent.as_slice(), [Command::LoadPreset(p)] if p.name == "lab-2"));
        assert!(s.app.dialog().is_none());
        for c in sent {
            s.simulator.handle(c);
        }
        s.sync();
        assert_eq!(s.app.setup.preset.name, "lab-2");
        assert_eq!(s.app.setup.initial.height, 30.0);
        assert_eq!(s.app.roll.live.step, 0);
        assert!(!s.app.setup.modified());
        assert!(screen(&s.app, 120, 36).starts_with("\" dicesim  lab-2 · preset roll"));
    }

    #[test]
    fn picker_keys_move_and_escape_closes() {
        let mut a = start().app;
        assert!(press(&mut a, KeyCode::Char('o')).is_empty());
        press(&mut a, KeyCode::End);
        let Some(Dialog::Picker {
            choices, selected, ..
        }) = a.dialog()
        else {
            panic!("open")
        };
        assert_eq!(*selected, choices.len() - 1);
        press(&mut a, KeyCode::Esc);
        assert!(
            a.dialog().is_none() && !a.quit,
            "Esc closes the picker, not the explorer"
        );
        press(&mut a, KeyCode::Char('o'));
        press(&mut a, KeyCode::Char('q'));
        assert!(a.dialog().is_none() && !a.quit);
    }

    #[test]
    fn header_marks_a_setup_that_differs_from_its_preset() {
        let mut s = start();
        assert!(!screen(&s.app, 120, 36).contains("(changed)"));
        s.command(Command::SetParam(Param::named("ground.friction").scan_key(), 0.5));
        assert!(s.app.setup.modified());
        assert!(screen(&s.app, 120, 36).starts_with("\" dicesim  paper (changed) ·"));
        assert!(screen(&s.app, 80, 24).starts_with("\"paper* │"));
        s.command(Command::SetParam(Param::named("ground.friction").scan_key(), 1.2));
        assert!(!s.app.setup.modified(), "back at the preset's value");
    }

    #[test]
    fn save_dialog_refuses_a_bad_name() {
        let mut s = start();
        // A bad name is refused before the folder is touched, so it need not exist.
        s.app.store = Store::new(Some("/nonexistent/dicesim-presets".into()));
        s.key(KeyCode::Char('s'));
        type_text(&mut s.app, "my preset!");
        assert!(press(&mut s.app, KeyCode::Enter).is_empty());
        let Some(Dialog::Save { error: Some(e), .. }) = s.app.dialog() else {
            panic!("still open, with an error")
        };
        assert!(e.contains("my preset!"), "{e}");
        insta::assert_snapshot!("save_bad_name_120x36", screen(&s.app, 120, 36));
        assert!(!std::path::Path::new("/nonexistent/dicesim-presets").exists());
    }

    #[test]
    fn save_asks_before_replacing_and_writes_the_setup() {
        let (dir, store) = folder();
        let mut s = start();
        s.app.store = store.clone();
        s.command(Command::SetParam(Param::named("ground.friction").scan_key(), 0.4));
        s.key(KeyCode::Char('s'));
        type_text(&mut s.app, "lab-2");
        press(&mut s.app, KeyCode::Enter);
        let Some(Dialog::Save {
            error: Some(e),
            confirm_replace: true,
            ..
        }) = s.app.dialog()
        else {
            panic!("asks first: {:?}", s.app.dialog())
        };
        assert!(e.contains("exists"), "{e}");
        assert_eq!(store.load("lab-2").expect("kept").0.initial.height, 30.0);
        press(&mut s.app, KeyCode::Enter);
        assert!(s.app.dialog().is_none());
        let saved = store.load("lab-2").expect("saved").0;
        assert_eq!(saved.ground.friction, 0.4);
        assert_eq!(saved.initial, s.app.setup.initial);
        assert_eq!(saved.random, Preset::default().random);
        assert!(s.app.notice.as_deref().is_some_and(|n| n.contains("lab-2.toml")));
        assert!(!s.app.setup.modified(), "the setup is now the saved preset");
        assert_eq!(s.app.setup.preset.name, "lab-2");
        // A new name saves without asking.
        s.key(KeyCode::Char('s'));
        type_text(&mut s.app, "lab-3");
        press(&mut s.app, KeyCode::Enter);
        assert!(s.app.dialog().is_none());
        assert!(dir.path().join("lab-3.toml").is_file());
    }

    #[test]
    fn the_simulator_loads_a_preset_with_a_fresh_table() {
        let mut s = Harness::new(&Preset::default(), crate::tui::Theme::default());
        s.command(Command::BatchStart(20));
        s.simulator.run_batch_here();
        s.sync();
        assert_eq!(s.app.roll.table.rolls(), 20);
        let gentle = Store::new(None).load("gentle-drop").expect("shipped").0;
        s.command(Command::LoadPreset(Box::new(gentle.clone())));
        assert_eq!(s.app.roll.table.rolls(), 0);
        assert_eq!(s.app.setup.params, gentle.params());
        assert_eq!(s.app.setup.initial, gentle.initial);
        assert_eq!(s.app.setup.preset, gentle);
        assert_eq!(s.simulator.preset(), &gentle);
        assert_eq!(s.app.notice.as_deref(), Some("loaded gentle-drop"));
    }
}

mod export {
    use super::*;
    use crate::tui::input::update::update;
    use crate::tui::state::messages::Msg;
    use crate::tui::tests::screen;
    use crate::worker::Command;
    use dicesim_experiment::trace::{header, row};
    use dicesim_physics::Simulation;
    use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};

    fn press(app: &mut App, code: KeyCode) -> Vec<Command> {
        update(
            app,
            Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))),
        )
        .into_iter()
        .filter_map(|e| crate::tui::event_loop::effects::perform(app, e))
        .collect()
    }

    #[test]
    fn e_exports_into_the_current_folder_and_p_switches_the_log_scale() {
        let mut a = start().app;
        assert_eq!(
            press(&mut a, KeyCode::Char('e')),
            [Command::Export {
                dir: ".".into(),
                log_scale: false
            }]
        );
        assert!(!a.die_screen.log_scale);
        assert!(press(&mut a, KeyCode::Char('p')).is_empty());
        assert!(a.die_screen.log_scale);
    }

    #[test]
    fn the_exported_energy_plot_follows_the_screens_scale() {
        // `p` on screen, then `e`: the command carries the log scale to the export.
        let mut a = mid_impact().app;
        press(&mut a, KeyCode::Char('p'));
        assert!(a.die_screen.log_scale);
        let c = press(&mut a, KeyCode::Char('e'));
        assert!(
            matches!(c[..], [Command::Export { log_scale: true, .. }]),
            "{c:?}"
        );
        // The same roll exported on both scales: two different pictures (the export is
        // deterministic, so equal files would mean the scale was ignored).
        let png = |log_scale: bool| {
            let dir = tempfile::tempdir().expect("temp dir");
            let mut s = mid_impact();
            s.command(Command::Export {
                dir: dir.path().to_path_buf(),
                log_scale,
            });
            s.simulator.run_export_here();
            s.sync();
            std::fs::read(dir.path().join("dicesim-paper-preset-roll.png")).expect("png written")
        };
        let (linear, log) = (png(false), png(true));
        assert_eq!(linear, png(false), "an export is reproducible");
        assert_ne!(linear, log, "the log-scale export drew the linear plot");
    }

    #[test]
    fn export_writes_the_whole_roll_as_csv_and_its_energy_plot_as_png() {
        let dir = tempfile::tempdir().expect("temp dir");
        let mut s = mid_impact();
        s.command(Command::Export {
            dir: dir.path().to_path_buf(),
            log_scale: false,
        });
        assert!(
            s.app.roll.export.is_some(),
            "the export runs off the worker's thread"
        );
        s.simulator.run_export_here();
        s.sync();
        let csv = dir.path().join("dicesim-paper-preset-roll.csv");
        let png = dir.path().join("dicesim-paper-preset-roll.png");
        let notice = s.app.notice.clone().expect("the status line says where");
        assert!(notice.contains(&csv.display().to_string()), "{notice}");
        // The roll again from t = 0 to its end, every step, in `dicesim trace`'s format.
        let text = std::fs::read_to_string(&csv).expect("csv written");
        let lines: Vec<&str> = text.lines().collect();
        let mut sim = Simulation::new(&s.app.setup.params, &s.app.setup.initial).expect("valid");
        let clock = dicesim_setup::number::StepClock::new(s.app.setup.params.integrator.dt);
        let first = row(&sim, &clock);
        let outcome = sim.run_to_end();
        assert_eq!(lines[0], header().join(","));
        assert_eq!(lines[1], first.join(","));
        assert_eq!(lines.len() as u64, outcome.steps + 2);
        assert_eq!(*lines.last().expect("rows"), row(&sim, &clock).join(","));
        // Its sidecar names the setup rolled.
        let meta =
            std::fs::read(dir.path().join("dicesim-paper-preset-roll.csv.meta.json")).expect("sidecar");
        let meta: serde_json::Value = serde_json::from_slice(&meta).expect("JSON");
        assert_eq!(meta["provenance"]["preset"]["name"], "paper");
        assert_eq!(meta["provenance"]["changed_from_preset"], false);
        let image = std::fs::read(&png).expect("png written");
        assert!(image.starts_with(b"\x89PNG\r\n\x1a\n") && image.len() > 10_000);
        // A second export replaces nothing.
        s.command(Command::Export {
            dir: dir.path().to_path_buf(),
            log_scale: false,
        });
        s.simulator.run_export_here();
        assert!(dir.path().join("dicesim-paper-preset-roll-2.csv").is_file());
        assert!(dir.path().join("dicesim-paper-preset-roll-2.png").is_file());
        assert_eq!(std::fs::read_to_string(&csv).expect("kept"), text);
    }

    #[test]
    fn a_sends_the_animation_of_the_camera_s_view_and_the_status_line_follows_it() {
        let mut s = start();
        s.app.die_screen.camera.orbit(15.0, 10.0);
        let (yaw_deg, pitch_deg) = (s.app.die_screen.camera.yaw_deg, s.app.die_screen.camera.pitch_deg);
        assert_eq!(
            press(&mut s.app, KeyCode::Char('A')),
            [Command::ExportAnimation {
                dir: ".".into(),
                yaw_deg,
                pitch_deg
            }]
        );
        // Ordered into a folder of its own: the status line tells the rolling and the
        // drawing, and the same key (or the roll's export key) cancels.
        let dir = tempfile::tempdir().expect("temp dir");
        s.command(Command::ExportAnimation {
            dir: dir.path().to_path_buf(),
            yaw_deg,
            pitch_deg,
        });
        let status = screen(&s.app, 120, 40);
        assert!(
            status.contains("exporting the animation: rolling, 0% of the time cap · A cancels"),
            "{status}"
        );
        s.app.roll.export = Some(crate::worker::ExportStatus::Animation(
            dicesim_figures::animation::AnimationProgress {
                drawing: true,
                done: 12,
                total: 80,
            },
        ));
        let status = screen(&s.app, 120, 40);
        assert!(
            status.contains("exporting the animation: frame 12 of 80 · A cancels"),
            "{status}"
        );
        assert_eq!(press(&mut s.app, KeyCode::Char('A')), [Command::ExportCancel]);
        assert_eq!(press(&mut s.app, KeyCode::Char('e')), [Command::ExportCancel]);
        s.command(Command::ExportCancel);
        assert_eq!(
            s.app.notice.as_deref(),
            Some("export cancelled: nothing was written")
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        // Done: the status line says where it went.
        s.command(Command::ExportAnimation {
            dir: dir.path().to_path_buf(),
            yaw_deg,
            pitch_deg,
        });
        s.simulator.run_export_here();
        s.sync();
        let gif = std::fs::canonicalize(dir.path())
            .unwrap()
            .join("dicesim-paper-preset-roll.gif");
        assert!(
            gif.is_file(),
            "{:?}",
            std::fs::read_dir(dir.path()).unwrap().collect::<Vec<_>>()
        );
        let status = screen(&s.app, 160, 40);
        assert!(
            status.contains(&format!("animation saved to {}", gif.display())),
            "{status}"
        );
    }

    #[test]
    fn export_into_a_missing_folder_says_why() {
        let mut s = start();
        s.command(Command::Export {
            dir: "/nonexistent/dicesim-export".into(),
            log_scale: false,
        });
        s.simulator.run_export_here();
        s.sync();
        let notice = s.app.notice.clone().expect("a notice");
        assert!(
            notice.starts_with("cannot export the roll: /nonexistent/dicesim-export/"),
            "{notice}"
        );
        assert!(notice.ends_with("does not exist"), "{notice}");
        assert!(s.app.roll.export.is_none(), "the export is over");
        assert!(!std::path::Path::new("/nonexistent/dicesim-export").exists());
    }

    #[test]
    fn a_preset_name_never_leads_the_export_out_of_its_folder() {
        let root = tempfile::tempdir().expect("temp dir");
        let dir = root.path().join("a").join("b");
        std::fs::create_dir_all(&dir).unwrap();
        let mut s = start();
        let mut preset = s.simulator.preset().clone();
        preset.name = "x/../../escaped".to_string();
        s.command(Command::LoadPreset(Box::new(preset)));
        s.command(Command::Export {
            dir: dir.clone(),
            log_scale: false,
        });
        s.simulator.run_export_here();
        s.sync();
        let written: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(
            written.len(),
            3,
            "the trace, its sidecar and the plot: {written:?}"
        );
        assert!(
            written.contains(&"dicesim-x_______escaped-preset-roll.csv".to_string()),
            "{written:?}"
        );
        assert!(!root.path().join("escaped-preset-roll.csv").exists());
        assert_eq!(
            std::fs::read_dir(root.path()).unwrap().count(),
            1,
            "only a/ in the root"
        );
    }

    #[test]
    fn a_trace_above_the_limit_is_refused_with_the_trace_every_alternative() {
        let dir = tempfile::tempdir().expect("temp dir");
        let mut s = start();
        // Δt = 1e-5 with no friction: millions of rows, gigabytes of trace.
        s.command(Command::SetParam(
            crate::tui::vocabulary::param::Param::named("ground.friction").scan_key(),
            0.0,
        ));
        s.command(Command::SetParam(
            crate::tui::vocabulary::param::Param::named("integrator.dt").scan_key(),
            1e-5,
        ));
        s.command(Command::Export {
            dir: dir.path().to_path_buf(),
            log_scale: false,
        });
        s.simulator.run_export_here();
        s.sync();
        let notice = s.app.notice.clone().expect("a notice");
        assert!(notice.contains("rows) is over the 268.4 MB limit"), "{notice}");
        assert!(notice.contains("`dicesim trace --every "), "{notice}");
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "nothing written"
        );
    }
}

mod themes {
    use super::*;
    use crate::tui::Theme;
    use crate::tui::input::update::update;
    use crate::tui::state::messages::Msg;
    use crate::tui::tests::mid_impact_with;
    use crate::tui::vocabulary::theme::Palette;
    use ratatui::buffer::Buffer;
    use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
    use ratatui::style::Modifier;

    fn press(app: &mut App, code: KeyCode) {
        let sent = update(
            app,
            Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))),
        );
        assert!(sent.is_empty(), "a theme asks nothing of the worker");
    }

    fn buffer(app: &App) -> Buffer {
        let mut t = Terminal::new(TestBackend::new(120, 36)).expect("test backend");
        t.draw(|f| crate::tui::render(app, f)).expect("draw");
        t.backend().buffer().clone()
    }

    /// Cells of `area` showing `symbol`.
    fn cells_with(b: &Buffer, area: Rect, symbol: &str) -> Vec<(u16, u16)> {
        (area.top()..area.bottom())
            .flat_map(|y| (area.left()..area.right()).map(move |x| (x, y)))
            .filter(|&p| b[p].symbol() == symbol)
            .collect()
    }

    #[test]
    fn t_cycles_dark_light_projector() {
        let mut a = start().app;
        assert_eq!(a.theme.palette, Palette::Dark);
        press(&mut a, KeyCode::Char('t'));
        assert_eq!(a.theme.palette, Palette::Light);
        assert_eq!(
            a.notice.as_deref(),
            Some("theme: light (t cycles dark, light, projector)")
        );
        press(&mut a, KeyCode::Char('t'));
        assert_eq!(a.theme.palette, Palette::Projector);
        press(&mut a, KeyCode::Char('t'));
        assert_eq!(a.theme.palette, Palette::Dark);
    }

    #[test]
    fn dark_keeps_the_terminal_background() {
        let b = buffer(&mid_impact().app);
        let areas = full();
        let (x, y) = (areas.params.x + 3, areas.params.y + 2);
        assert_eq!((b[(x, y)].fg, b[(x, y)].bg), (Color::Reset, Color::Reset));
    }

    #[test]
    fn light_paints_white_with_dark_inks() {
        let mut s = mid_impact_with(Theme::default().next());
        s.app.die_screen.arrows = true;
        let b = buffer(&s.app);
        let areas = full();
        // Plain text: black on white, not bold.
        let (x, y) = (areas.params.x + 3, areas.params.y + 2);
        assert_eq!(
            (b[(x, y)].fg, b[(x, y)].bg),
            (Color::Rgb(0, 0, 0), Color::Rgb(255, 255, 255))
        );
        assert!(!b[(x, y)].modifier.contains(Modifier::BOLD));
        // Every cell has a painted background (warnings keep their own).
        for y in 0..36 {
            for x in 0..120 {
                assert_ne!(b[(x, y)].bg, Color::Reset, "cell {x},{y}");
            }
        }
        // A touching corner in the light red (drawn without the arrows' legend over it);
        // at the impact the die is low, so the bar's bottom is rotational, light magenta.
        s.app.die_screen.arrows = false;
        let plain = buffer(&s.app);
        let dots = cells_with(&plain, areas.die, "●");
        assert!(!dots.is_empty());
        for p in dots {
            assert_eq!(plain[p].fg, Color::Rgb(160, 0, 0));
        }
        let bar = (areas.ledger.x + 1, areas.ledger.bottom() - 2);
        assert_eq!(b[bar].symbol(), "█");
        assert_eq!(b[bar].fg, Color::Rgb(130, 0, 140));
        // ω's arrow in the darkened cyan.
        let omega = cells_with(&b, areas.die, "ω");
        assert!(omega.iter().any(|&p| b[p].fg == Color::Rgb(0, 80, 120)));
    }

    #[test]
    fn projector_is_bold_black_on_white_with_strong_inks() {
        let s = mid_impact_with(Theme::default().next().next());
        assert_eq!(s.app.theme.palette, Palette::Projector);
        let b = buffer(&s.app);
        for y in 0..36 {
            for x in 0..120 {
                assert!(b[(x, y)].modifier.contains(Modifier::BOLD), "cell {x},{y}");
            }
        }
        let areas = full();
        let (x, y) = (areas.params.x + 3, areas.params.y + 2);
        assert_eq!(
            (b[(x, y)].fg, b[(x, y)].bg),
            (Color::Rgb(0, 0, 0), Color::Rgb(255, 255, 255))
        );
        let dots = cells_with(&b, areas.die, "●");
        assert!(!dots.is_empty());
        for p in dots {
            assert_eq!(b[p].fg, Color::Rgb(170, 0, 0));
        }
    }

    #[test]
    fn no_color_stays_colourless_in_every_theme() {
        let mut s = mid_impact_with(Theme::monochrome());
        s.app.die_screen.arrows = true;
        for _ in 0..3 {
            press(&mut s.app, KeyCode::Char('t'));
            assert!(s.app.notice.as_deref().is_some_and(|n| n.contains("NO_COLOR")));
            let b = buffer(&s.app);
            for y in 0..36 {
                for x in 0..120 {
                    assert_eq!(
                        (b[(x, y)].fg, b[(x, y)].bg),
                        (Color::Reset, Color::Reset),
                        "cell {x},{y}"
                    );
                }
            }
        }
    }
}

/// The classroom views draw at any terminal size without panicking.
mod sizes {
    use super::*;
    use crate::tui::Theme;
    use crate::tui::input::update::update;
    use crate::tui::state::messages::Msg;
    use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};

    fn with_keys(mut app: App, keys: &[KeyCode]) -> App {
        for &k in keys {
            update(
                &mut app,
                Msg::Input(Event::Key(KeyEvent::new(k, KeyModifiers::NONE))),
            );
        }
        app
    }

    fn classroom_views() -> [App; 6] {
        let twin = twin::twin_after(500).app;
        let mut editing = with_keys(twin.clone(), &[KeyCode::Char('E'), KeyCode::Char('1')]);
        editing.die_screen.arrows = true;
        [
            with_keys(mid_impact().app, &[KeyCode::Char('v'), KeyCode::Char('t')]),
            twin,
            editing,
            with_keys(start().app, &[KeyCode::Char('o'), KeyCode::Down]),
            with_keys(
                start().app,
                &[KeyCode::Char('s'), KeyCode::Char('!'), KeyCode::Enter],
            ),
            {
                let mut a = settled().app;
                a.theme = Theme::default().next().next();
                a.die_screen.arrows = true;
                a
            },
        ]
    }

    fn draw_at(app: &App, width: u16, height: u16) {
        let mut t = Terminal::new(TestBackend::new(width, height)).expect("test backend");
        t.draw(|f| crate::tui::render(app, f)).expect("draw");
    }

    #[test]
    fn every_classroom_view_draws_at_every_boundary_size() {
        for app in &classroom_views() {
            for (width, height) in super::super::tests::boundary_sizes() {
                draw_at(app, width, height);
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]

        #[test]
        fn classroom_views_draw_at_random_sizes(which in 0usize..6, width in 1u16..=200, height in 1u16..=60) {
            static VIEWS: std::sync::OnceLock<[App; 6]> = std::sync::OnceLock::new();
            draw_at(&VIEWS.get_or_init(classroom_views)[which], width, height);
        }
    }
}
