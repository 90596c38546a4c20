//! The preset dialogs: the picker, the save dialog and the questions over them.

use super::picker_window;
use crate::tui::state::app::App;
use crate::tui::state::dialog::{Dialog, Group};
use crate::tui::tests::fixtures::press_performing;
use crate::tui::tests::fixtures::{Harness, start};
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::theme::Theme;
use crate::worker::Command;
use dicesim_setup::preset::{LESSON, Preset, Store};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::KeyCode;

fn type_text(app: &mut App, text: &str) {
    for c in text.chars() {
        assert!(press_performing(app, KeyCode::Char(c)).is_empty());
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
    // The shipped presets (the six dice among them) push the user's heading below the fold
    // at both sizes: the list scrolls to it, and says how many more there are.
    for text in [&wide, &narrow] {
        for heading in [Group::Lesson, Group::Shipped].map(Group::heading) {
            assert!(text.contains(heading), "{heading} in\n{text}");
        }
        assert!(text.contains("more"), "the list marks what is below:\n{text}");
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
    let sent = press_performing(&mut s.app, KeyCode::Enter);
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
    assert!(press_performing(&mut a, KeyCode::Char('o')).is_empty());
    press_performing(&mut a, KeyCode::End);
    let Some(Dialog::Picker {
        choices, selected, ..
    }) = a.dialog()
    else {
        panic!("open")
    };
    assert_eq!(*selected, choices.len() - 1);
    press_performing(&mut a, KeyCode::Esc);
    assert!(
        a.dialog().is_none() && !a.quit,
        "Esc closes the picker, not the explorer"
    );
    press_performing(&mut a, KeyCode::Char('o'));
    press_performing(&mut a, KeyCode::Char('q'));
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
    assert!(press_performing(&mut s.app, KeyCode::Enter).is_empty());
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
    press_performing(&mut s.app, KeyCode::Enter);
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
    press_performing(&mut s.app, KeyCode::Enter);
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
    press_performing(&mut s.app, KeyCode::Enter);
    assert!(s.app.dialog().is_none());
    assert!(dir.path().join("lab-3.toml").is_file());
}

#[test]
fn the_simulator_loads_a_preset_with_a_fresh_table() {
    let mut s = Harness::new(&Preset::default(), Theme::default());
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

/// A preset with a theme, for the projector check.
#[test]
fn prompts_read_in_the_projector_theme() {
    let mut s = Harness::new(&Preset::default(), Theme::default().next().next());
    s.command(Command::SetParam(Param::named("ground.friction").scan_key(), 0.5));
    s.key(KeyCode::Char('q'));
    insta::assert_snapshot!("quit_prompt_projector_100x30", screen(&s.app, 100, 30));
}

#[test]
fn the_picker_keeps_the_selection_in_view_between_its_markers() {
    // Fifteen presets in seven rows: five entries between the two marker rows.
    assert_eq!(picker_window(15, 0, 7), (0, 5, true));
    assert_eq!(picker_window(15, 4, 7), (0, 5, true));
    assert_eq!(picker_window(15, 5, 7), (1, 5, true));
    assert_eq!(picker_window(15, 14, 7), (10, 5, true));
    // Everything fits: no markers.
    assert_eq!(picker_window(5, 4, 7), (0, 5, false));
}

/// The explorer rolls any die: the picker offers every shipped polyhedral die, and a user's
/// d20 opens with its own numbers in the outcome table.
#[test]
fn picker_offers_the_shipped_dice_and_opens_a_users() {
    let (dir, store) = folder();
    let d20 = dicesim_setup::preset::shipped_text("d20").expect("the shipped d20");
    std::fs::write(
        dir.path().join("my-d20.toml"),
        d20.replace("name = \"d20\"", "name = \"my-d20\""),
    )
    .expect("written");
    let mut s = start();
    s.app.store = store;
    s.key(KeyCode::Char('o'));
    let Some(Dialog::Picker { choices, .. }) = s.app.dialog() else {
        panic!("the picker is open")
    };
    for shipped in ["d4", "d8", "d10", "d100", "d12", "d20"] {
        let c = choices.iter().find(|c| c.name == shipped).expect("offered");
        assert!(c.preset.is_ok(), "{shipped}: {:?}", c.preset.as_ref().err());
    }
    let mine = choices
        .iter()
        .find(|c| c.name == "my-d20")
        .expect("the user's die listed");
    let preset = mine.preset.clone().expect("it opens");
    assert!(preset.params().die.is_polyhedral());
    s.command(Command::LoadPreset(preset));
    assert_eq!(s.app.roll.live.params.die.kind, dicesim_physics::Solid::D20);
    assert_eq!(s.app.roll.table.tally.numbers(), (1..=20).collect::<Vec<u8>>());
}
