//! The classroom lesson from its one source, the crate's `lesson.toml`: each step's keys are
//! pressed in the explorer (the worker's simulator in the test's own thread, so every screen
//! is deterministic) and what the step says the class will see is looked for on the screen.
//! The README's lesson is generated from the same file (a repository test, `tests/cli/docs.rs`,
//! holds the two together).

use crate::lesson::Lesson;
use crate::tui::input::update::update;
use crate::tui::state::app::Page;
use crate::tui::state::dialog::Dialog;
use crate::tui::state::lesson_run::LessonRun;
use crate::tui::state::messages::Msg;
use crate::tui::tests::fixtures::{Harness, computed};
use crate::tui::tests::screen_tests::SIZES;
use crate::tui::vocabulary::theme::{Palette, Theme};
use dicesim_setup::preset::{Preset, Speed, Store};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::KeyCode;

fn lesson() -> Lesson {
    Lesson::shipped(&Store::new(None)).expect("lesson.toml reads")
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
    for (i, step) in lesson().steps.iter().enumerate() {
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

/// What each step of the shipped lesson says it opens, read from the file's text itself
/// (not through the lesson reader under test): its preset, speed, arrows, plot and screen.
fn expected(
    step: &toml::Table,
) -> (
    String,
    Option<String>,
    Option<bool>,
    Option<String>,
    Option<String>,
) {
    let s = |k: &str| step.get(k).and_then(|v| v.as_str()).map(str::to_string);
    (
        s("preset").expect("a step names its preset"),
        s("speed"),
        step.get("arrows").and_then(|v| v.as_bool()),
        s("plot"),
        s("screen"),
    )
}

/// `PageDown` walks the shipped lesson from the explorer as it opens: each step opens its
/// preset at its speed with its arrows, plot and screen (or the preset's own where the step
/// says none, and the energy terms for the plot), its card up with its sentence; `PageDown` again puts the card down, and a key
/// in between (here `v`, the arrows) works as ever. `PageUp` from the last step goes back one.
#[test]
fn the_step_keys_walk_every_lesson_step_opening_its_preset_speed_and_view() {
    let file: toml::Table = toml::from_str(crate::lesson::SHIPPED).expect("TOML");
    let steps = file["step"].as_array().expect("steps");
    let mut s = Harness::new(&Preset::default(), Theme::default());
    s.app.lesson = Some(LessonRun::new(lesson()));
    let store = Store::new(None);
    for (i, step) in steps.iter().enumerate() {
        let (preset, speed, arrows, plot, screen_name) = expected(step.as_table().expect("a table"));
        s.key(KeyCode::PageDown);
        let run = s.app.lesson.as_ref().expect("a lesson");
        assert_eq!((run.at, run.card), (Some(i), true), "step {}", i + 1);
        assert_eq!(s.app.setup.preset.name, preset, "step {}", i + 1);
        let own = store.load(&preset).expect("the step's preset loads").0.view;
        let speed = speed.map_or(own.speed.unwrap_or_default(), |l| {
            Speed::from_label(&l).expect("a speed")
        });
        assert_eq!(s.app.setup.speed, speed, "step {} speed", i + 1);
        assert_eq!(
            s.app.die_screen.arrows,
            arrows.or(own.arrows).unwrap_or(false),
            "step {} arrows",
            i + 1
        );
        // The step's plot, or the energy terms where it names none (not the step before's).
        let quantity = plot.as_deref().and_then(|plot| {
            dicesim_setup::quantity::QUANTITIES
                .iter()
                .position(|q| q.column == plot)
        });
        assert_eq!(
            s.app.die_screen.plot.quantity,
            quantity,
            "step {} plot {plot:?}",
            i + 1
        );
        // The row the step changes, selected (the incline's tilt, the top's spin).
        if let Some(key) = step.get("select").and_then(|v| v.as_str()) {
            assert_eq!(s.app.selected_param().key(), key, "step {} row", i + 1);
        }
        let page = match screen_name.as_deref() {
            Some("map") => Page::Map,
            Some("presentation") => Page::Presentation,
            _ => Page::Die,
        };
        assert_eq!(s.app.page, page, "step {} screen", i + 1);
        assert_eq!(
            s.app.die_screen.readouts,
            own.readouts.unwrap_or_default(),
            "step {} readouts",
            i + 1
        );
        let sentence = step["say"].as_str().expect("a sentence");
        let shown = screen(&s, (80, 24));
        let first_word: String = sentence.split(' ').next().unwrap_or("").to_uppercase();
        let drawn = crate::tui::vocabulary::big_type::render_line(&first_word);
        assert!(
            shown.contains(&drawn[0]),
            "step {}: {first_word} in large type:\n{shown}",
            i + 1
        );
        // The card goes down at a key and the key works (`v`: the arrows, on the map the layer).
        let arrows_before = s.app.die_screen.arrows;
        s.key(KeyCode::Char('v'));
        assert!(!s.app.lesson.as_ref().expect("a lesson").card);
        if page == Page::Die {
            assert_eq!(s.app.die_screen.arrows, !arrows_before);
        }
        s.key(KeyCode::Char('v'));
    }
    let last = steps.len() - 1;
    s.key(KeyCode::PageUp);
    assert_eq!(s.app.lesson.as_ref().and_then(|r| r.at), Some(last - 1));
    assert_eq!(
        s.app.setup.preset.name,
        expected(steps[last - 1].as_table().expect("a table")).0
    );
}

/// The value axis's labels of the plot titled `title`: the numbers right before a `│` on
/// the rows under its title.
fn axis_labels(shown: &str, title: &str) -> Vec<f64> {
    shown
        .lines()
        .skip_while(|l| !l.contains(title))
        .skip(1)
        .flat_map(|l| {
            let cells: Vec<char> = l.chars().collect();
            (1..cells.len())
                .filter(|&i| cells[i] == '│' && cells[i - 1].is_ascii_digit())
                .map(|i| {
                    let start = (0..i)
                        .rev()
                        .take_while(|&j| cells[j].is_ascii_digit() || cells[j] == '.')
                        .last();
                    cells[start.unwrap_or(i)..i].iter().collect::<String>()
                })
                .filter_map(|t| t.parse::<f64>().ok())
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Step 3 (the ledger) opens the total energy alone with its axis fitted, so at the first
/// impact the plot spans the bump the README describes (the total is about 79 000 erg there)
/// instead of 0 to the total, where `y` on the energy terms showed no change.
#[test]
fn the_ledgers_step_shows_the_total_energys_bump_at_the_first_impact() {
    let mut s = Harness::new(&Preset::default(), Theme::default());
    s.app.lesson = Some(LessonRun::new(lesson()));
    for _ in 0..5 {
        s.key(KeyCode::PageDown);
    }
    assert_eq!(s.app.lesson.as_ref().and_then(|r| r.at), Some(2));
    s.key(KeyCode::Home);
    s.key(KeyCode::Char('i'));
    let total = s.app.roll.live.energy.total();
    for size in SIZES {
        let shown = screen(&s, size);
        let labels = axis_labels(&shown, "total energy");
        let lowest = labels.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(
            labels.len() >= 2 && lowest > 0.5 * total,
            "{size:?}: axis {labels:?} for a total of {total} erg:\n{shown}"
        );
    }
}
