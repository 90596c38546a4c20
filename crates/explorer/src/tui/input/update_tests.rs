//! `update`: what each key and click does, on every screen.

use crate::tui::input::update::update;
use crate::tui::state::app::{App, Mode, Prompt};
use crate::tui::state::messages::Msg;
use crate::tui::tests::fixtures::{Harness, start, stepped_back};
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::theme::Theme;
use crate::worker::{Command, Speed};
use dicesim_setup::preset::{Preset, Store};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};

fn app() -> App {
    start().app
}

fn press(app: &mut App, code: KeyCode) -> Vec<Command> {
    press_with(app, code, KeyModifiers::NONE)
}

fn press_with(app: &mut App, code: KeyCode, modifiers: KeyModifiers) -> Vec<Command> {
    update(app, Msg::Input(Event::Key(KeyEvent::new(code, modifiers))))
        .into_iter()
        .filter_map(|e| crate::tui::event_loop::effects::perform(app, e))
        .collect()
}

fn mouse(app: &mut App, kind: MouseEventKind, column: u16, row: u16) -> Vec<Command> {
    let m = MouseEvent {
        kind,
        column,
        row,
        modifiers: KeyModifiers::NONE,
    };
    update(app, Msg::Input(Event::Mouse(m)))
        .into_iter()
        .filter_map(|e| crate::tui::event_loop::effects::perform(app, e))
        .collect()
}

#[test]
fn playback_keys_send_their_commands() {
    let mut a = app();
    assert_eq!(press(&mut a, KeyCode::Char(' ')), [Command::TogglePlay]);
    assert_eq!(press(&mut a, KeyCode::Char('n')), [Command::Step(1)]);
    assert_eq!(press(&mut a, KeyCode::Char('r')), [Command::Replay]);
    assert_eq!(press(&mut a, KeyCode::Char('R')), [Command::RandomRoll]);
    assert_eq!(press(&mut a, KeyCode::Char('c')), [Command::ClearTable]);
    assert_eq!(
        press(&mut a, KeyCode::Char('b')),
        [Command::BatchStart(crate::tui::state::roll_view::BATCH_ROLLS)]
    );
    assert!(!a.quit);
}

#[test]
fn b_cancels_a_running_batch() {
    let mut s = start();
    s.key(KeyCode::Char('b'));
    assert!(s.app.roll.batch.is_some());
    assert_eq!(press(&mut s.app, KeyCode::Char('b')), [Command::BatchCancel]);
}

#[test]
fn speed_walks_the_ladder_and_stops_at_its_ends() {
    let mut a = app();
    let start = a.setup.speed;
    assert_eq!(
        press(&mut a, KeyCode::Char('[')),
        [Command::SetSpeed(start.slower())]
    );
    assert_eq!(press(&mut a, KeyCode::Char(']')), [Command::SetSpeed(start)]);
    assert_eq!(
        press(&mut a, KeyCode::Char('+')),
        [Command::SetSpeed(start.faster())]
    );
    assert_eq!(press(&mut a, KeyCode::Char('-')), [Command::SetSpeed(start)]);
    for _ in 0..30 {
        press(&mut a, KeyCode::Char(']'));
    }
    assert_eq!(a.setup.speed, Speed::INSTANT);
    assert!(
        press(&mut a, KeyCode::Char(']')).is_empty(),
        "nothing faster than instant"
    );
    for _ in 0..30 {
        press(&mut a, KeyCode::Char('-'));
    }
    assert_eq!(a.setup.speed, Speed::SLOWEST);
}

#[test]
fn arrows_and_vim_keys_select_and_change_values() {
    let mut a = app();
    assert_eq!(a.selected_param(), Param::named("ground.stiffness"));
    assert!(
        press(&mut a, KeyCode::Up).is_empty(),
        "the first row stays selected"
    );
    press(&mut a, KeyCode::Down);
    press(&mut a, KeyCode::Char('j'));
    assert_eq!(a.selected_param(), Param::named("ground.friction"));
    let mu = a.setup.params.ground.friction;
    let fine = Param::named("ground.friction").nudged(mu, 1, false);
    assert_eq!(
        press(&mut a, KeyCode::Right),
        [Command::SetParam(
            Param::named("ground.friction").scan_key(),
            fine
        )]
    );
    assert_eq!(
        a.setup.params.ground.friction, fine,
        "the list shows the new value at once"
    );
    let coarse = Param::named("ground.friction").nudged(fine, -1, true);
    assert_eq!(
        press_with(&mut a, KeyCode::Left, KeyModifiers::SHIFT),
        [Command::SetParam(
            Param::named("ground.friction").scan_key(),
            coarse
        )]
    );
    let back = Param::named("ground.friction").nudged(coarse, 1, true);
    assert_eq!(
        press(&mut a, KeyCode::Char('L')),
        [Command::SetParam(
            Param::named("ground.friction").scan_key(),
            back
        )]
    );
    let down = Param::named("ground.friction").nudged(back, -1, false);
    assert_eq!(
        press(&mut a, KeyCode::Char('h')),
        [Command::SetParam(
            Param::named("ground.friction").scan_key(),
            down
        )]
    );
    press(&mut a, KeyCode::Char('k'));
    assert_eq!(a.selected_param(), Param::named("ground.damping"));
    press(&mut a, KeyCode::Char('G'));
    assert_eq!(a.selected_param(), *a.params_listed().last().expect("rows"));
}

#[test]
fn a_value_at_its_limit_sends_nothing() {
    let mut a = app();
    a.die_screen.selected = a
        .params_listed()
        .iter()
        .position(|&p| p == Param::named("ground.friction"))
        .expect("listed");
    assert_eq!(press(&mut a, KeyCode::Enter), []);
    for c in "0".chars() {
        press(&mut a, KeyCode::Char(c));
    }
    assert_eq!(
        press(&mut a, KeyCode::Enter),
        [Command::SetParam(Param::named("ground.friction").scan_key(), 0.0)]
    );
    assert!(press(&mut a, KeyCode::Left).is_empty());
}

#[test]
fn typing_a_value_validates_it_and_esc_cancels() {
    let mut a = app();
    a.die_screen.selected = a
        .params_listed()
        .iter()
        .position(|&p| p == Param::named("initial.height"))
        .expect("listed");
    press(&mut a, KeyCode::Enter);
    assert!(a.value_editor().is_some());
    for c in "2x5q".chars() {
        // Every printable character is text here: q does not quit, x is typed.
        press(&mut a, KeyCode::Char(c));
    }
    assert!(!a.quit);
    assert_eq!(a.value_editor().map(|e| e.text.as_str()), Some("2x5q"));
    assert!(press(&mut a, KeyCode::Enter).is_empty());
    assert!(a.value_editor().is_some_and(|e| {
        e.error
            .as_deref()
            .is_some_and(|m| m.contains("`2x5q` is not a number"))
    }));
    for _ in 0..3 {
        press(&mut a, KeyCode::Backspace);
    }
    for c in "5e9".chars() {
        press(&mut a, KeyCode::Char(c));
    }
    assert!(
        press(&mut a, KeyCode::Enter).is_empty(),
        "25e9 cm is out of range"
    );
    assert!(a.value_editor().is_some_and(|e| {
        e.error
            .as_deref()
            .is_some_and(|m| m.contains("outside 0…1000 cm"))
    }));
    press(&mut a, KeyCode::Backspace);
    press(&mut a, KeyCode::Backspace);
    assert_eq!(
        press(&mut a, KeyCode::Enter),
        [Command::SetParam(Param::named("initial.height").scan_key(), 25.0)]
    );
    assert!(a.value_editor().is_none());
    press(&mut a, KeyCode::Enter);
    press(&mut a, KeyCode::Char('7'));
    assert!(press(&mut a, KeyCode::Esc).is_empty());
    assert!(
        a.value_editor().is_none() && !a.quit,
        "Esc leaves the editor, not the program"
    );
    assert_eq!(a.setup.initial.height, 25.0);
}

#[test]
fn quitting_keys() {
    for (code, modifiers) in [
        (KeyCode::Char('q'), KeyModifiers::NONE),
        (KeyCode::Char('c'), KeyModifiers::CONTROL),
    ] {
        let mut a = app();
        assert_eq!(press_with(&mut a, code, modifiers), [Command::Quit]);
        assert!(a.quit);
    }
    let mut a = app();
    press(&mut a, KeyCode::Enter);
    assert_eq!(
        press_with(&mut a, KeyCode::Char('c'), KeyModifiers::CONTROL),
        [Command::Quit],
        "also while typing"
    );
}

#[test]
fn help_opens_scrolls_and_closes_without_quitting() {
    let mut a = app();
    press(&mut a, KeyCode::Char('?'));
    assert!(a.help_scroll().is_some());
    assert!(
        press(&mut a, KeyCode::Char(' ')).is_empty(),
        "keys do not reach the die under the help"
    );
    press(&mut a, KeyCode::Down);
    assert_eq!(a.help_scroll(), Some(1));
    press(&mut a, KeyCode::Esc);
    assert!(a.help_scroll().is_none() && !a.quit);
    press(&mut a, KeyCode::Char('?'));
    assert_eq!(a.help_scroll(), Some(0));
    press(&mut a, KeyCode::Char('?'));
    assert!(a.help_scroll().is_none());
}

#[test]
fn view_keys_change_only_the_view() {
    let mut a = app();
    let camera = a.die_screen.camera;
    for c in ['a', 'W', 'z', 'p', 'm'] {
        assert!(press(&mut a, KeyCode::Char(c)).is_empty());
    }
    assert!(
        a.die_screen.camera.yaw_deg != camera.yaw_deg && a.die_screen.camera.pitch_deg > camera.pitch_deg
    );
    assert!(a.die_screen.camera.zoom > camera.zoom && a.die_screen.log_scale);
    press(&mut a, KeyCode::Char('C'));
    assert_eq!(a.die_screen.camera, camera);
}

#[test]
fn key_releases_are_ignored() {
    let mut a = app();
    let mut release = KeyEvent::new(KeyCode::Char('q'), KeyModifiers::NONE);
    release.kind = KeyEventKind::Release;
    assert!(update(&mut a, Msg::Input(Event::Key(release))).is_empty());
    assert!(!a.quit);
}

#[test]
fn click_selects_a_parameter_and_scroll_changes_it() {
    let mut a = app();
    update(&mut a, Msg::Input(Event::Resize(120, 36)));
    let areas = screen_layout(a.screen).expect("full size");
    // Row 0 of the list is the heading; the rows follow in list order.
    let friction_row = areas.params.y
        + 2
        + a.params_listed()
            .iter()
            .position(|&p| p == Param::named("ground.friction"))
            .expect("listed") as u16;
    assert!(
        mouse(
            &mut a,
            MouseEventKind::Down(MouseButton::Left),
            areas.params.x + 3,
            friction_row
        )
        .is_empty()
    );
    assert_eq!(a.selected_param(), Param::named("ground.friction"));
    let up = Param::named("ground.friction").nudged(a.setup.params.ground.friction, 1, false);
    assert_eq!(
        mouse(&mut a, MouseEventKind::ScrollUp, areas.params.x + 3, friction_row),
        [Command::SetParam(Param::named("ground.friction").scan_key(), up)]
    );
    let zoom = a.die_screen.camera.zoom;
    mouse(&mut a, MouseEventKind::ScrollUp, areas.die.x + 5, areas.die.y + 5);
    assert_eq!(a.die_screen.camera.zoom, zoom + 1);
    let yaw = a.die_screen.camera.yaw_deg;
    mouse(
        &mut a,
        MouseEventKind::Down(MouseButton::Left),
        areas.die.x + 5,
        areas.die.y + 5,
    );
    mouse(
        &mut a,
        MouseEventKind::Drag(MouseButton::Left),
        areas.die.x + 8,
        areas.die.y + 5,
    );
    assert!(
        a.die_screen.camera.yaw_deg != yaw,
        "dragging the die orbits the camera"
    );
}

#[test]
fn own_edits_win_until_the_worker_has_seen_them() {
    let mut s = start();
    let stale = s.simulator.snapshot();
    press(&mut s.app, KeyCode::Down);
    press(&mut s.app, KeyCode::Down);
    let cmds = press(&mut s.app, KeyCode::Right);
    let mine = s.app.setup.params.ground.friction;
    update(&mut s.app, Msg::from(stale));
    assert_eq!(
        s.app.setup.params.ground.friction, mine,
        "an older snapshot does not undo the edit"
    );
    for c in cmds {
        s.simulator.handle(c);
    }
    s.sync();
    assert_eq!(s.app.setup.params.ground.friction, mine);
    assert_eq!(s.app.roll.live.params.ground.friction, mine);
}

fn screen(app: &App, w: u16, h: u16) -> String {
    let mut t = Terminal::new(TestBackend::new(w, h)).expect("test backend");
    t.draw(|f| crate::tui::render(app, f)).expect("draw");
    t.backend().to_string()
}

fn changed() -> Harness {
    let mut s = start();
    s.command(Command::SetParam(Param::named("ground.friction").scan_key(), 0.5));
    s
}

#[test]
fn comma_steps_back_and_home_end_jump() {
    let mut s = stepped_back();
    s.key(KeyCode::Char(','));
    assert_eq!(s.app.roll.live.timeline.position, 169);
    assert_eq!(s.app.roll.live.step, 169);
    s.key(KeyCode::End);
    assert_eq!(
        s.app.roll.live.timeline.position,
        s.app.roll.live.timeline.furthest
    );
    assert!(matches!(s.app.roll.live.phase, crate::worker::Phase::Ended(_)));
    s.key(KeyCode::Home);
    assert_eq!(s.app.roll.live.time_s, 0.0);
    // Playing goes on from wherever the roll is.
    s.key(KeyCode::Char('.'));
    s.key(KeyCode::Char(' '));
    assert!(s.app.roll.live.playing && s.app.roll.live.timeline.position == 1);
}

#[test]
fn esc_never_quits() {
    for mut s in [start(), changed()] {
        s.key(KeyCode::Esc);
        assert!(!s.app.quit && s.app.prompt().is_none());
        s.key(KeyCode::Char('?'));
        s.key(KeyCode::Esc);
        s.key(KeyCode::Esc);
        assert!(
            !s.app.quit && s.app.help_scroll().is_none(),
            "Esc after closing help stays"
        );
        s.key(KeyCode::Tab);
        assert_eq!(s.app.mode(), Mode::Map);
        s.key(KeyCode::Esc);
        assert_eq!(s.app.mode(), Mode::Normal, "Esc on the map screen goes back");
        assert!(!s.app.quit);
    }
}

#[test]
fn q_asks_first_when_the_setup_has_changes() {
    let mut s = start();
    s.key(KeyCode::Char('q'));
    assert!(s.app.quit, "nothing to lose: q quits at once");

    let mut s = changed();
    s.key(KeyCode::Char('q'));
    assert!(!s.app.quit);
    assert_eq!(s.app.prompt(), Some(&Prompt::Quit));
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("Quit? The setup has unsaved changes"), "{text}");
    insta::assert_snapshot!("quit_prompt_120x36", text);
    insta::assert_snapshot!("quit_prompt_80x24", screen(&s.app, 80, 24));
    s.key(KeyCode::Char('x'));
    assert!(!s.app.quit && s.app.prompt().is_none(), "any other key stays");
    assert_eq!(s.app.setup.params.ground.friction, 0.5, "and changes nothing");
    s.key(KeyCode::Char('q'));
    s.key(KeyCode::Char('q'));
    assert!(s.app.quit, "q again quits");
    let mut s = changed();
    s.key(KeyCode::Char('q'));
    s.key(KeyCode::Char('y'));
    assert!(s.app.quit, "y quits");
}

#[test]
fn backspace_resets_to_the_preset_asking_first() {
    let mut s = changed();
    let preset = s.app.setup.preset.clone();
    s.key(KeyCode::Backspace);
    assert_eq!(s.app.prompt(), Some(&Prompt::Reset));
    let text = screen(&s.app, 120, 36);
    assert!(
        text.contains(&format!("Reset the setup to {}?", preset.name)),
        "{text}"
    );
    insta::assert_snapshot!("reset_prompt_120x36", text);
    s.key(KeyCode::Esc);
    assert_eq!(s.app.setup.params.ground.friction, 0.5, "Esc keeps the changes");
    s.key(KeyCode::Backspace);
    s.key(KeyCode::Backspace);
    assert_eq!(s.app.setup.params, preset.params());
    assert_eq!(s.simulator.params(), &preset.params());
    assert!(!s.app.setup.modified());
    // Nothing changed: nothing to ask, nothing to do.
    s.key(KeyCode::Backspace);
    assert!(s.app.prompt().is_none());
    assert!(
        s.app
            .notice
            .as_deref()
            .is_some_and(|n| n.contains("nothing to reset"))
    );
}

#[test]
fn opening_a_preset_over_changes_asks_first() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = changed();
    s.app.store = Store::new(Some(dir.path().to_path_buf()));
    s.key(KeyCode::Char('o'));
    assert_eq!(s.app.mode(), Mode::Dialog);
    s.key(KeyCode::Down);
    s.key(KeyCode::Enter);
    let Some(Prompt::Load(chosen)) = s.app.prompt().cloned() else {
        panic!("asks first: {:?}", s.app.prompt())
    };
    assert!(screen(&s.app, 120, 36).contains(&format!("Open {}?", chosen.name)));
    s.key(KeyCode::Char('n'));
    assert_eq!(s.app.mode(), Mode::Dialog, "no: back in the picker");
    assert_eq!(s.app.setup.params.ground.friction, 0.5);
    s.key(KeyCode::Enter);
    s.key(KeyCode::Enter);
    assert!(s.app.dialog().is_none());
    assert_eq!(s.app.setup.preset.name, chosen.name);
    assert_eq!(s.simulator.params(), &chosen.params());
}

#[test]
fn b_in_the_typed_batch_size_goes_on_round_the_ladder() {
    let mut s = start();
    s.key(KeyCode::Char('B'));
    s.key(KeyCode::Char('B'));
    assert_eq!(s.app.mode(), Mode::EditingValue, "past 100 000: type one");
    s.key(KeyCode::Char('B'));
    assert_eq!(s.app.mode(), Mode::Normal, "B leaves the number field");
    assert_eq!(s.app.roll.batch_size, 1_000);
    let text = screen(&s.app, 120, 36);
    assert!(!text.contains("not a number"), "{text}");
    // The footer says the size: in the notice while it shows, in the batch key's hint after.
    assert!(text.contains("batch size 1 000"), "{text}");
    s.app.notice = None;
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("b batch 1 000"), "{text}");
}

/// The batch size's editor takes a number's characters only: a letter (`b`, the batch key,
/// pressed out of habit) is refused as it is typed, and the field stays empty.
#[test]
fn the_batch_size_editor_refuses_letters() {
    let mut s = start();
    s.key(KeyCode::Char('B'));
    s.key(KeyCode::Char('B'));
    s.key(KeyCode::Char('b'));
    let editor = s.app.batch_editor().expect("typing a size");
    assert_eq!(editor.text, "");
    let footer = screen(&s.app, 80, 24);
    assert!(footer.contains("`b`: a batch size is a whole number"), "{footer}");
    assert!(!footer.contains("batch size: b"), "{footer}");
    for c in "5000".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    assert_eq!(s.app.roll.batch_size, 5_000);
}

#[test]
fn the_batch_size_is_chosen_or_typed() {
    let mut s = start();
    assert_eq!(s.app.roll.batch_size, 10_000);
    assert!(screen(&s.app, 120, 36).contains("b batch 10 000"));
    s.key(KeyCode::Char('B'));
    assert_eq!(s.app.roll.batch_size, 100_000);
    s.key(KeyCode::Char('B'));
    assert_eq!(s.app.mode(), Mode::EditingValue);
    for c in "2.5".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("a whole number from 1 to 10 000 000"), "{text}");
    for _ in 0..3 {
        s.key(KeyCode::Backspace);
    }
    for c in "2500".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    assert_eq!(s.app.roll.batch_size, 2_500);
    assert!(screen(&s.app, 120, 36).contains("b batch 2 500"));
    s.key(KeyCode::Char('b'));
    assert_eq!(s.app.roll.batch.map(|b| b.total), Some(2_500));
    s.key(KeyCode::Char('b'));
    // After a typed size the ladder starts again.
    s.key(KeyCode::Char('B'));
    assert_eq!(s.app.roll.batch_size, 1_000);
    s.key(KeyCode::Char('B'));
    assert_eq!(s.app.roll.batch_size, 10_000);
    let mut s = start();
    s.app.roll.batch_size = 100_000;
    s.key(KeyCode::Char('B'));
    s.key(KeyCode::Esc);
    assert_eq!(s.app.roll.batch_size, 100_000, "Esc keeps the size");
    s.key(KeyCode::Char('B'));
    assert_eq!(s.app.mode(), Mode::EditingValue, "from the largest, B types one");
}

#[test]
fn slow_motion_classroom_opens_slowed_down_with_its_arrows() {
    let preset = Store::new(None).load("slow-motion-classroom").expect("shipped").0;
    let s = Harness::new(&preset, Theme::default());
    assert_eq!(s.app.roll.live.speed.label(), "1/10×");
    assert!(s.app.die_screen.arrows);
    assert!(screen(&s.app, 120, 36).contains("speed 1/10×"));
    // Loading it over another preset applies its view too, and a preset without a view
    // opens as the explorer does: at 1×, without arrows or twin, the theme kept.
    let mut s = start();
    s.key(KeyCode::Char('t'));
    s.command(Command::LoadPreset(Box::new(preset)));
    assert_eq!(s.app.setup.speed.label(), "1/10×");
    assert!(s.app.die_screen.arrows);
    s.key(KeyCode::Char('T'));
    s.key(KeyCode::Char('a'));
    s.command(Command::LoadPreset(Box::default()));
    assert_eq!(s.app.setup.speed.label(), "1×");
    assert_eq!(s.simulator.live().speed().label(), "1×");
    // The twin turned on stays on (a lesson compares presets with it).
    assert!(!s.app.die_screen.arrows && s.app.twin.on && s.app.roll.live.twin.is_some());
    assert_eq!(
        s.app.die_screen.camera,
        crate::tui::state::camera::OrbitCamera::default()
    );
    assert_eq!(s.app.theme.palette, crate::tui::vocabulary::theme::Palette::Light);
}

#[test]
fn s_saves_the_view_and_a_description_and_loading_applies_them() {
    let dir = tempfile::tempdir().expect("temp dir");
    let store = Store::new(Some(dir.path().to_path_buf()));
    let mut s = changed();
    s.app.store = store.clone();
    for key in ['[', '[', 'v', 't', 'a', 'T'] {
        s.key(KeyCode::Char(key));
    }
    s.key(KeyCode::Char('s'));
    for c in "lab-3".chars() {
        s.key(KeyCode::Char(c));
    }
    let automatic = s.app.setup.automatic_description();
    assert_eq!(automatic, "The `paper` preset with ground.friction=0.5.");
    // A fixed folder for the picture (the temporary one's name changes every run).
    s.app.store = Store::new(Some("/home/teacher/presets".into()));
    let text = screen(&s.app, 120, 36);
    assert!(
        text.contains(&automatic),
        "the empty description shows what it will be:\n{text}"
    );
    insta::assert_snapshot!("save_dialog_120x36", text);
    s.app.store = store.clone();
    s.key(KeyCode::Tab);
    for c in "Friction halved for lab 3.".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    assert!(s.app.dialog().is_none(), "{:?}", s.app.dialog());
    let saved = store.load("lab-3").expect("saved").0;
    assert_eq!(saved.description, "Friction halved for lab 3.");
    assert_eq!(saved.ground.friction, 0.5);
    let view = saved.view;
    assert_eq!(view.speed.map(|v| v.label()), Some("1/5×"));
    assert_eq!(view.arrows, Some(true));
    assert_eq!(view.theme, Some(dicesim_setup::preset::ThemeName::Light));
    assert_eq!(view.twin, Some(1e-9));
    assert_eq!(view.camera.map(|c| c.yaw), Some(15.0));
    assert_eq!(view.screen, Some(dicesim_setup::preset::Screen::Die));
    let text = std::fs::read_to_string(dir.path().join("lab-3.toml")).expect("written");
    assert!(text.contains("\nspeed = \"1/5×\""), "{text}");

    // Opened in a fresh explorer, it looks the same.
    let s = Harness::new(&saved, Theme::default());
    assert_eq!(s.app.roll.live.speed.label(), "1/5×");
    assert!(s.app.die_screen.arrows && s.app.twin.on && s.app.roll.live.twin.is_some());
    assert_eq!(s.app.theme.palette, crate::tui::vocabulary::theme::Palette::Light);
    assert_eq!(s.app.die_screen.camera.yaw_deg, 15.0);
}

#[test]
fn a_view_on_the_map_screen_opens_it() {
    let mut preset = Preset::default();
    preset.view.screen = Some(dicesim_setup::preset::Screen::Map);
    let mut s = Harness::new(&preset, Theme::default());
    s.sync();
    assert_eq!(s.app.mode(), Mode::Map);
    assert!(s.app.map.requested.is_some(), "the map is asked for at once");
}

#[test]
fn the_views_camera_limits_are_the_cameras() {
    use crate::tui::state::camera::OrbitCamera;
    assert_eq!(dicesim_setup::preset::PITCH.min, OrbitCamera::MIN_PITCH);
    assert_eq!(dicesim_setup::preset::PITCH.max, OrbitCamera::MAX_PITCH);
    assert_eq!(dicesim_setup::preset::ZOOM.min, f64::from(OrbitCamera::MIN_ZOOM));
    assert_eq!(dicesim_setup::preset::ZOOM.max, f64::from(OrbitCamera::MAX_ZOOM));
}

#[test]
fn a_digit_on_a_parameter_row_opens_the_value_editor_with_it_typed() {
    let mut s = start();
    s.select(Param::named("initial.height"));
    s.key(KeyCode::Char('2'));
    s.key(KeyCode::Char('0'));
    assert_eq!(
        s.app.mode(),
        Mode::EditingValue,
        "2 opens no map and starts no map"
    );
    assert_eq!(s.app.value_editor().map(|e| e.text.as_str()), Some("20"));
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("20▏"), "{text}");
    insta::assert_snapshot!("digit_typed_editor_120x36", text);
    insta::assert_snapshot!("digit_typed_editor_80x24", screen(&s.app, 80, 24));
    s.key(KeyCode::Enter);
    assert_eq!(s.app.setup.initial.height, 20.0, "Enter applies the 20 typed");
    assert_eq!(s.app.mode(), Mode::Normal);
}

#[test]
fn a_key_that_means_nothing_does_nothing_and_the_footer_says_so() {
    let mut s = start();
    let before = (
        s.app.die_screen.log_scale,
        s.app.setup.params,
        s.app.setup.initial,
    );
    // `u` is no key of the main screen.
    s.key(KeyCode::Char('u'));
    assert_eq!(
        (
            s.app.die_screen.log_scale,
            s.app.setup.params,
            s.app.setup.initial
        ),
        before
    );
    assert_eq!(s.app.mode(), Mode::Normal);
    let text = screen(&s.app, 120, 36);
    assert!(text.contains("u: nothing here (? lists the keys)"), "{text}");
    insta::assert_snapshot!("nothing_here_footer_120x36", text);
    // The next key that does something clears it.
    s.key(KeyCode::Down);
    assert!(!screen(&s.app, 120, 36).contains("nothing here"));
    // In the help too: Esc, ? and q close it, anything else stays and says so.
    s.key(KeyCode::Char('?'));
    s.key(KeyCode::Char('x'));
    assert_eq!(s.app.mode(), Mode::Help);
    assert_eq!(
        s.app.notice.as_deref(),
        Some("x: nothing here (? lists the keys)")
    );
    s.key(KeyCode::Char('q'));
    assert_eq!(s.app.mode(), Mode::Normal, "q closes the help");
    assert!(!s.app.quit, "and does not quit from it");
}

/// The shipped preset `name`.
fn shipped(name: &str) -> Preset {
    Store::new(None).load(name).expect("shipped").0
}

#[test]
fn a_random_roll_is_no_change_of_the_users_and_o_opens_without_asking() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut s = start();
    s.app.store = Store::new(Some(dir.path().to_path_buf()));
    s.key(KeyCode::Char('R'));
    assert_ne!(
        s.app.setup.initial, s.app.setup.preset.initial,
        "R drew another start from the ranges"
    );
    assert!(!s.app.setup.modified(), "a draw is not an edit");
    s.key(KeyCode::Char('o'));
    s.key(KeyCode::Down);
    s.key(KeyCode::Enter);
    assert!(s.app.prompt().is_none(), "no question: {:?}", s.app.prompt());
    assert_ne!(s.app.setup.preset.name, spun_name(), "the chosen preset opened");
    // An edit after a draw is a change, and is guarded again.
    let mut s = start();
    s.key(KeyCode::Char('R'));
    s.select(Param::named("initial.height"));
    s.key(KeyCode::Right);
    assert!(s.app.setup.modified());
    s.key(KeyCode::Char('q'));
    assert_eq!(s.app.prompt(), Some(&Prompt::Quit));
}

/// The name of the preset [`start`] opens.
fn spun_name() -> String {
    start().app.setup.preset.name
}

#[test]
fn opening_a_preset_keeps_the_twin_rolling_at_its_epsilon() {
    let mut s = start();
    s.key(KeyCode::Char('T'));
    s.key(KeyCode::Char('>'));
    let epsilon = s.app.twin.epsilon;
    assert!(s.app.twin.on && s.app.roll.live.twin.is_some());
    let gentle = shipped("gentle-drop");
    assert_eq!(gentle.view.twin, None, "the preset asks for no twin of its own");
    s.command(Command::LoadPreset(Box::new(gentle.clone())));
    assert_eq!(s.app.setup.preset.name, gentle.name);
    assert!(s.app.twin.on, "the explorer still says the twin is on");
    let twin = s.app.roll.live.twin.as_ref().expect("the worker rolls a twin");
    assert_eq!(twin.epsilon, epsilon);
    // The twin is the new preset's start perturbed, not the old one's: both start at
    // gentle-drop's 1.8 cm, the twin ε higher.
    let h = s.app.roll.live.die.centre.z;
    assert!((h - 1.8).abs() < 1e-12, "{h}");
    assert!(
        (twin.die.centre.z - 1.8 * (1.0 + epsilon)).abs() < 1e-9,
        "{}",
        twin.die.centre.z
    );
}

#[test]
fn the_map_after_opening_a_preset_spans_that_presets_own_values() {
    let mut s = Harness::new(&shipped("paper"), Theme::default());
    s.app.screen = ratatui::layout::Rect::new(0, 0, 100, 30);
    s.key(KeyCode::Tab);
    // The map spans the random range of spin, 120 rad/s wide, around the preset's own spin
    // (its ends on the value list's coarse grid of 10 rad/s): about x the paper spins at
    // 12 rad/s, about y at −20; gentle-drop at 1 and −1.
    let around = |range: (f64, f64), own: f64| {
        let width = range.1 - range.0;
        (110.0..=130.0).contains(&width) && ((range.0 + range.1) / 2.0 - own).abs() <= 10.0
    };
    let axes = |s: &Harness| {
        (
            (s.app.map.x.min, s.app.map.x.max),
            (s.app.map.y.min, s.app.map.y.max),
        )
    };
    let (x, y) = axes(&s);
    assert!(around(x, 12.0) && around(y, -20.0), "{x:?} {y:?}");
    s.key(KeyCode::Tab);
    s.command(Command::LoadPreset(Box::new(shipped("gentle-drop"))));
    s.key(KeyCode::Tab);
    let (x, y) = axes(&s);
    assert!(around(x, 1.0) && around(y, -1.0), "{x:?} {y:?}");
    let (request, params, initial) = s.app.map.requested.expect("a map was asked for");
    assert_eq!((request.x.min, request.x.max), x);
    assert_eq!(initial.height, 1.8);
    assert_eq!(params, shipped("gentle-drop").params());
}
