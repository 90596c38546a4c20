//! The classroom lesson from its one source, the crate's `lesson.toml`: each step's keys are
//! pressed in the explorer (the worker's simulator in the test's own thread, so every screen
//! is deterministic) and what the step says the class will see is looked for on the screen.
//! The README's lesson is generated from the same file (a repository test, `tests/cli/docs.rs`,
//! holds the two together).

use crate::tui::input::update::update;
use crate::tui::state::dialog::Dialog;
use crate::tui::state::messages::Msg;
use crate::tui::tests::fixtures::{Harness, computed};
use crate::tui::tests::screen_tests::SIZES;
use crate::tui::vocabulary::theme::{Palette, Theme};
use dicesim_setup::preset::{Preset, Store};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::KeyCode;
use serde::Deserialize;

const LESSON: &str = include_str!("../../../lesson.toml");

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Lesson {
    /// The README's words before the steps (`tests/cli/docs.rs` reads them); named here so
    /// that a misspelt key in the file is refused.
    #[serde(rename = "intro")]
    _intro: String,
    step: Vec<LessonStep>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LessonStep {
    title: String,
    keys: Vec<String>,
    see: Vec<String>,
    /// What the README says of the step (read by `tests/cli/docs.rs`).
    #[serde(rename = "text")]
    _text: String,
}

fn lesson() -> Lesson {
    toml::from_str(LESSON).expect("lesson.toml reads")
}

fn screen(s: &Harness, (w, h): (u16, u16)) -> String {
    let mut t = Terminal::new(TestBackend::new(w, h)).expect("test backend");
    t.draw(|f| crate::tui::render(&s.app, f)).expect("draw");
    let b = t.backend().buffer();
    (0..b.area.height)
        .map(|y| (0..b.area.width).map(|x| b[(x, y)].symbol()).collect::<String>())
        .collect::<Vec<_>>()
        .join("\n")
}

fn code(name: &str) -> KeyCode {
    match name {
        "space" => KeyCode::Char(' '),
        "Enter" => KeyCode::Enter,
        "Tab" => KeyCode::Tab,
        "Esc" => KeyCode::Esc,
        "Home" => KeyCode::Home,
        "End" => KeyCode::End,
        "Up" => KeyCode::Up,
        "Down" => KeyCode::Down,
        "Left" => KeyCode::Left,
        "Right" => KeyCode::Right,
        "Backspace" => KeyCode::Backspace,
        c if c.chars().count() == 1 => KeyCode::Char(c.chars().next().expect("one character")),
        other => panic!("lesson.toml: unknown key `{other}`"),
    }
}

fn picked(s: &Harness) -> Option<String> {
    match s.app.dialog() {
        Some(Dialog::Picker {
            choices, selected, ..
        }) => Some(choices[*selected].name.clone()),
        _ => None,
    }
}

fn press(s: &mut Harness, key: &str) {
    match key {
        "wait" => s.run_to_end(),
        "batch" => {
            s.simulator.run_batch_here();
            s.sync();
        }
        "map" => {
            let m = computed(&s.app);
            update(&mut s.app, Msg::from(m));
        }
        k if k.starts_with("pick:") => {
            let name = &k["pick:".len()..];
            // Down through the list, then up: the picker stops at its ends.
            for code in [KeyCode::Down, KeyCode::Up] {
                for _ in 0..64 {
                    if picked(s).as_deref() == Some(name) {
                        return;
                    }
                    s.key(code);
                }
            }
            assert_eq!(picked(s).as_deref(), Some(name), "the picker lists {name}");
        }
        k => s.key(code(k)),
    }
}

/// Each step, in order, from the explorer as it opens (the `paper` preset, projector theme,
/// only the shipped presets): after its keys, everything its `see` lists is on screen at
/// each classroom size, a projector's 80×24 and 100×30 as well as 120×36.
#[test]
fn every_lesson_step_shows_what_it_says() {
    let theme = Theme {
        colour: true,
        palette: Palette::Projector,
    };
    let mut s = Harness::new(&Preset::default(), theme);
    s.app.store = Store::new(None);
    let mut missing = Vec::new();
    for (i, step) in lesson().step.iter().enumerate() {
        for key in &step.keys {
            press(&mut s, key);
        }
        for size in SIZES {
            let shown = screen(&s, size);
            let absent: Vec<&String> = step.see.iter().filter(|w| !shown.contains(w.as_str())).collect();
            if !absent.is_empty() {
                missing.push(format!(
                    "step {} ({}) at {}×{}: {absent:?} not on screen:\n{shown}",
                    i + 1,
                    step.title,
                    size.0,
                    size.1
                ));
            }
        }
    }
    assert!(missing.is_empty(), "{}", missing.join("\n\n"));
}
