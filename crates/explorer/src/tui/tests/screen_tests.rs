//! Every screen of the explorer, in one list: main, map, twin, help and the dialogs, each
//! drawn at the classroom sizes (80×24 and 100×30, a projector's font) and at 120×36 in the
//! projector theme. The snapshots are here; so is the check, over every rendered buffer,
//! that no word is cut at a panel's edge and that the numbers a lesson is about are shown.
//!
//! The rule the check holds the panels to: a panel's text stops one column short of its
//! right edge (`super::fit`), so text that reaches the edge was cut, unless it ends in `…`,
//! the mark of an abbreviation.

use crate::tui::state::app::App;
use crate::tui::tests::fixtures::{
    Harness, complete, computed, editing, failed, filled_table, help, loaded_after, map_scene,
    mid_impact_with, partial, settled, start, twin_scene, unstable,
};
use crate::tui::vocabulary::theme::{Palette, Theme};
use crate::worker::{BatchProgress, Command};
use dicesim_setup::preset::{Preset, Store, shipped_text};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::KeyCode;

/// The sizes every screen is drawn and checked at.
pub(crate) const SIZES: [(u16, u16); 3] = [(80, 24), (100, 30), (120, 36)];

/// One screen state: its name (the snapshots' too), the app, and the texts that must be on
/// screen at every size (the numbers a lesson is about).
pub(crate) struct ScreenState {
    pub(crate) name: &'static str,
    pub(crate) app: App,
    pub(crate) shows: Vec<String>,
}

fn keyed(mut s: Harness, keys: &[KeyCode]) -> App {
    for &k in keys {
        s.key(k);
    }
    s.app
}

/// A shipped preset's scene, with only the shipped presets in its picker.
fn shipped(name: &str, theme: Theme) -> Harness {
    let text = shipped_text(name).expect("shipped");
    let preset = Preset::from_toml_str(text, name).expect("valid");
    let mut s = Harness::new(&preset, theme);
    s.app.store = Store::new(None);
    s
}

/// `loaded-corner` after a batch of `rolls` random rolls: a bias the table measures.
fn loaded_batch(rolls: u64, theme: Theme) -> Harness {
    let mut s = shipped("loaded-corner", theme);
    s.command(Command::BatchStart(rolls));
    s.simulator.run_batch_here();
    s.sync();
    s
}

/// The face up the die panel names, in the words it uses.
fn face_up(app: &App) -> String {
    format!("face up {}", app.roll.live.die.face_up)
}

/// Every screen the explorer draws, in the given theme. Adding a screen is one entry in one
/// of the lists below: it is then snapshot at every size, checked for cut words and for
/// contrast.
pub(crate) fn states(theme: Theme) -> Vec<ScreenState> {
    let mut states = die_states(theme);
    states.extend(twin_states(theme));
    states.extend(more_states(theme));
    states.extend(view_states(theme));
    states.extend(plot_states(theme));
    states.extend(dice_states(theme));
    for s in &mut states {
        s.app.theme = theme;
    }
    states
}

fn state(name: &'static str, app: App, shows: &[&str]) -> ScreenState {
    ScreenState {
        name,
        app,
        shows: shows.iter().map(|s| s.to_string()).collect(),
    }
}

/// The die screen: rolling, at rest, editing and refusing values, batches.
fn die_states(theme: Theme) -> Vec<ScreenState> {
    let mut arrows = mid_impact_with(theme);
    arrows.key(KeyCode::Char('v'));
    // The table's push on the die at the impact, whole in the arrows' legend.
    let force = format!(
        "━ΣF {}",
        crate::tui::vocabulary::format::fmt_num(
            crate::tui::panels::die::vectors::total_force(&arrows.app.roll.live.die).norm()
        )
    );
    let mut refused = editing();
    refused.key(KeyCode::Char('9'));
    refused.key(KeyCode::Enter);
    let settled_app = settled().app;
    let settled_face = face_up(&settled_app);
    let mut running = loaded_batch(600, theme);
    running.app.roll.batch = Some(BatchProgress {
        done: 3072,
        total: 10000,
    });
    let mut height = start();
    height.select(crate::tui::vocabulary::param::Param::named("initial.height"));
    // 15 cm typed over with 0: the die would start inside the table.
    let mut refused_height = start();
    refused_height.select(crate::tui::vocabulary::param::Param::named("initial.height"));
    refused_height.key(KeyCode::Enter);
    for key in [
        KeyCode::Backspace,
        KeyCode::Backspace,
        KeyCode::Char('0'),
        KeyCode::Enter,
    ] {
        refused_height.key(key);
    }
    let refusal = refused_height
        .app
        .value_editor()
        .and_then(|e| e.error.clone())
        .expect("refused");
    assert!(refusal.starts_with("0: corner in the table"), "{refusal}");
    vec![
        state("start", start().app, &["face up", "Δt"]),
        state("mid impact with arrows", arrows.app, &["face up", &force]),
        state(
            "settled",
            settled_app,
            &[&settled_face, "lost since 0 s", "damping", "Δt"],
        ),
        state("unstable", unstable().app, &["unstable", "Δt"]),
        state("help", help().app, &[]),
        state("editing", editing().app, &["friction μ = 0.8"]),
        state("editing refused", refused.app, &[]),
        state("value hint", height.app, &["initial.height", "restarts the roll"]),
        state("height refused", refused_height.app, &[&refusal]),
        // 600 rolls of the batch and one random roll.
        state("batch done", filled_table().app, &["95 %", "n 601"]),
        state(
            "loaded batch",
            loaded_batch(2000, theme).app,
            &["95 %", "bias this large shows in", "n 2000"],
        ),
        state("batch running", running.app, &["batch 3072/10000"]),
        state(
            "lesson card",
            lesson_card(theme).app,
            &["step 1 of", "PageDown the screen"],
        ),
        state("superball spin", shipped("superball", theme).app, &["ωy -200.0"]),
        state(
            "sleeping top lean",
            shipped("sleeping-top", theme).app,
            &["lean 1.0°"],
        ),
        state("incline slid", shipped("incline", theme).app, &["slid 0.00 cm"]),
    ]
}

/// The shipped lesson's first step opened, its card up.
fn lesson_card(theme: Theme) -> Harness {
    let mut s = Harness::new(&Preset::default(), theme);
    let lesson = crate::lesson::Lesson::shipped(&Store::new(None)).expect("reads");
    s.app.lesson = Some(crate::tui::state::lesson_run::LessonRun::new(lesson));
    s.key(KeyCode::PageDown);
    s
}

/// The chaos twin beside the die, and at rest.
fn twin_states(theme: Theme) -> Vec<ScreenState> {
    // Both dice of the twin at rest: the verdict the lesson's step 4 is about, worked out
    // here from the two faces.
    let mut twin_end = twin_scene(theme);
    twin_end.run_to_end();
    let face_of = |phase: &crate::worker::Phase| match phase {
        crate::worker::Phase::Ended(o) => o.face,
        _ => None,
    };
    let die_face = face_of(&twin_end.app.roll.live.phase).expect("the die settles");
    let twin_face = twin_end
        .app
        .roll
        .live
        .twin
        .as_ref()
        .and_then(|t| face_of(&t.phase))
        .expect("the twin settles");
    let verdict = if die_face == twin_face {
        "same face"
    } else {
        "faces differ"
    };
    vec![
        state(
            "twin",
            keyed(twin_scene(theme), &[KeyCode::Char('v')]),
            &["twin face up"],
        ),
        state("twin curve", complete(theme).app, &["ε½", "P(same face)"]),
        state(
            "twin settled",
            twin_end.app,
            &[verdict, &format!("face up {die_face}")],
        ),
    ]
}

/// The map, the loaded die, the dialogs and the prompts.
fn more_states(theme: Theme) -> Vec<ScreenState> {
    let mut loaded = loaded_after(40, theme);
    loaded.key(KeyCode::Char('v'));
    vec![
        state("map", map_scene(theme).app, &["face up"]),
        state("loaded die", loaded.app, &["+0.5 g"]),
        state(
            "preset picker",
            keyed(shipped("paper", theme), &[KeyCode::Char('o')]),
            &["paper", "more"],
        ),
        state("save dialog", keyed(start(), &[KeyCode::Char('s')]), &[]),
        state(
            "quit prompt",
            keyed(start(), &[KeyCode::Char('l'), KeyCode::Char('q')]),
            &[],
        ),
        state(
            "reset prompt",
            keyed(start(), &[KeyCode::Char('l'), KeyCode::Backspace]),
            &[],
        ),
    ]
}

/// Seeking, the presentation view, throwing.
fn view_states(theme: Theme) -> Vec<ScreenState> {
    vec![
        state(
            "stepped back",
            {
                let mut s = settled();
                s.key(KeyCode::Home);
                for _ in 0..170 {
                    s.key(KeyCode::Char('.'));
                }
                s.app
            },
            &["face up"],
        ),
        state("twin curve computing", partial().app, &[]),
        state("twin curve failed", failed().app, &[]),
        state(
            "map settle times",
            keyed(map_scene(theme), &[KeyCode::Char('v')]),
            &[],
        ),
        state("presentation", keyed(settled(), &[KeyCode::Char('P')]), &[]),
        state(
            "light shadow, high camera",
            keyed(
                settled(),
                &[KeyCode::Char('W'), KeyCode::Char('W'), KeyCode::Char('W')],
            ),
            &["face up"],
        ),
        // The event keys: the first impact from the start, its notice and mark.
        state(
            "first impact",
            keyed(start(), &[KeyCode::Char('i')]),
            &["impact 1 begins at", "◆"],
        ),
        state(
            "face decided",
            keyed(start(), &[KeyCode::Char('F'), KeyCode::Home]),
            &["✓", "face up"],
        ),
        // Throw mode, aimed with the keys: the aim's velocity and spin in the footer.
        state(
            "throw aimed",
            keyed(
                start(),
                &[
                    KeyCode::Char('f'),
                    KeyCode::Char('w'),
                    KeyCode::Right,
                    KeyCode::Right,
                    KeyCode::Right,
                    KeyCode::Up,
                ],
            ),
            &["cm/s", "rad/s", "Enter throw"],
        ),
        state(
            "thrown",
            keyed(
                start(),
                &[KeyCode::Char('f'), KeyCode::Right, KeyCode::Right, KeyCode::Enter],
            ),
            &["thrown: v ("],
        ),
    ]
}

/// The plot fitted, a face pair marked, the map's inferred cells, a parameter twin at rest.
fn plot_states(theme: Theme) -> Vec<ScreenState> {
    vec![
        // Two curves of one unit, the readout at the marker, the axis fitted around it.
        state(
            "height and lowest corner fitted",
            {
                let mut s = settled();
                s.key(KeyCode::Home);
                for _ in 0..140 {
                    s.key(KeyCode::Char('.'));
                }
                keyed(s, &[KeyCode::Char('w'), KeyCode::Char('Y'), KeyCode::Char('y')])
            },
            &["height", "cm"],
        ),
        state(
            "tennis racket, faces 2 and 5 marked",
            {
                let mut s = shipped("tennis-racket", theme);
                s.simulator.advance_steps(60);
                s.sync();
                keyed(s, &[KeyCode::Char('M')])
            },
            &["face up"],
        ),
        state(
            "map, inferred cell",
            {
                let mut app = keyed(shipped("gentle-drop", theme), &[KeyCode::Tab]);
                let m = computed(&app);
                crate::tui::input::update::update(&mut app, crate::tui::state::messages::Msg::from(m));
                let map = app.map.map().expect("computed");
                app.map.cursor = (0..map.width())
                    .flat_map(|i| (0..map.height()).map(move |j| (i, j)))
                    .find(|&(i, j)| map.cell(i, j).is_some_and(|c| !c.sampled))
                    .expect("an inferred cell");
                app
            },
            &["██1 ██2 ██3 ██4 ██5 ██6", "legend: face up"],
        ),
        state(
            "parameter twin at rest",
            {
                let mut s = start();
                s.key(KeyCode::Char('D'));
                s.select(crate::tui::vocabulary::param::Param::named("ground.friction"));
                s.key(KeyCode::Enter);
                for c in "0.3".chars() {
                    s.key(KeyCode::Char(c));
                }
                s.key(KeyCode::Enter);
                s.run_to_end();
                s.app
            },
            &["dice"],
        ),
    ]
}

pub(crate) fn projector() -> Theme {
    Theme {
        colour: true,
        palette: Palette::Projector,
    }
}

pub(crate) fn draw(app: &App, (w, h): (u16, u16)) -> Buffer {
    let mut t = Terminal::new(TestBackend::new(w, h)).expect("test backend");
    t.draw(|f| crate::tui::render(app, f)).expect("draw");
    t.backend().buffer().clone()
}

pub(crate) fn text(buf: &Buffer) -> String {
    let a = buf.area;
    (a.top()..a.bottom())
        .map(|y| {
            (a.left()..a.right())
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Whether a symbol is drawing (a line, block, shape or Braille dot) rather than text.
fn is_drawing(symbol: &str) -> bool {
    symbol.chars().all(|c| {
        matches!(c as u32,
            0x2190..=0x21FF // arrows
            | 0x2500..=0x259F // box drawing, block elements
            | 0x25A0..=0x25FF // geometric shapes
            | 0x2800..=0x28FF // Braille
            | 0x2022 | 0x00B7) // a plot's dotted lines: • ·
    })
}

/// Whether the cell is a panel's edge: a corner, or a vertical line that runs up to a
/// corner and down to one (the interval bars of a plot run into points, not corners).
fn is_edge(buf: &Buffer, x: u16, y: u16) -> bool {
    let at = |y: u16| buf[(x, y)].symbol();
    match at(y) {
        "┐" | "┘" | "┌" | "└" | "┤" | "├" | "┬" | "┴" => true,
        "│" => {
            let mut up = y;
            while up > buf.area.top() && at(up) == "│" {
                up -= 1;
            }
            let mut down = y;
            while down + 1 < buf.area.bottom() && at(down) == "│" {
                down += 1;
            }
            matches!(at(up), "┐" | "┌" | "┬" | "├" | "┤") && matches!(at(down), "┘" | "└" | "┴" | "├" | "┤")
        }
        _ => false,
    }
}

/// Texts cut at a panel's edge: a run of text that reaches an edge (or the screen's) without
/// ending in `…`. Each as (x, y, the run).
pub(crate) fn cut_words(buf: &Buffer) -> Vec<(u16, u16, String)> {
    let a = buf.area;
    let mut cuts = Vec::new();
    for y in a.top()..a.bottom() {
        let mut run = String::new();
        for x in a.left()..a.right() {
            let symbol = buf[(x, y)].symbol();
            let blank = symbol.trim().is_empty();
            let edge_next = x + 1 == a.right() || is_edge(buf, x + 1, y);
            if blank || is_edge(buf, x, y) {
                run.clear();
                continue;
            }
            run.push_str(symbol);
            if edge_next && !is_drawing(symbol) && symbol != "…" {
                cuts.push((x, y, run.clone()));
            }
        }
    }
    cuts
}

#[test]
fn the_cut_check_catches_a_cut_word_and_passes_whole_ones() {
    let mut t = Terminal::new(TestBackend::new(28, 3)).expect("test backend");
    t.draw(|f| {
        use ratatui::widgets::{Block, Paragraph};
        let [left, right] = f.area().layout(&ratatui::layout::Layout::horizontal(
            [ratatui::layout::Constraint::Length(14); 2],
        ));
        // The cut: the legend's unit and bracket lost at the edge.
        f.render_widget(Paragraph::new("F 980 (M·g/8)").block(Block::bordered()), left);
        f.render_widget(Paragraph::new("whole words…").block(Block::bordered()), right);
    })
    .expect("draw");
    let cuts = cut_words(t.backend().buffer());
    assert_eq!(
        cuts,
        vec![(12, 1, "(M·g/8".to_string())],
        "{}",
        text(t.backend().buffer())
    );
    // A word ending one column short of the edge, and text at the screen's edge.
    let mut buf = Buffer::empty(ratatui::layout::Rect::new(0, 0, 8, 2));
    buf.set_string(0, 0, "face 3 ", ratatui::style::Style::new());
    buf.set_string(0, 1, "restarts", ratatui::style::Style::new());
    assert_eq!(cut_words(&buf), vec![(7, 1, "restarts".to_string())]);
}

#[test]
fn no_word_is_cut_and_the_lessons_numbers_show_at_every_size() {
    let mut problems = Vec::new();
    for s in states(projector()) {
        for size in SIZES {
            let buf = draw(&s.app, size);
            let shown = text(&buf);
            let where_ = format!("{} at {}×{}", s.name, size.0, size.1);
            for (x, y, run) in cut_words(&buf) {
                problems.push(format!("{where_}: `{run}` cut at ({x},{y})"));
            }
            for want in &s.shows {
                if !shown.contains(want.as_str()) {
                    problems.push(format!("{where_}: `{want}` not shown"));
                }
            }
            if problems.len() > 200 {
                break;
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn every_screen_at_every_size() {
    for s in states(projector()) {
        for size in SIZES {
            let name = format!("{}_{}x{}", s.name.replace([' ', ','], "_"), size.0, size.1);
            insta::assert_snapshot!(name, text(&draw(&s.app, size)));
        }
    }
}

/// A shipped polyhedral die's preset roll, rolling: 0.1 s (400 steps of its 0.25 ms) after
/// its first touch of the table, mid-tumble.
pub(crate) fn die_rolling(name: &str, theme: Theme) -> Harness {
    let mut s = shipped(name, theme);
    while !s.simulator.roll().in_contact() {
        assert_eq!(s.simulator.advance_steps(1), 1, "{name} reaches the table");
    }
    s.simulator.advance_steps(400);
    s.sync();
    s
}

/// The polyhedral dice: a d4, a d10 and a d20 rolling, each face's number drawn on it (the
/// d4's by its vertices), and a d20's outcome table of 20 faces after a batch.
fn dice_states(theme: Theme) -> Vec<ScreenState> {
    let mut table = shipped("d20", theme);
    table.command(Command::BatchStart(300));
    table.simulator.run_batch_here();
    table.sync();
    let n = format!("n {}", table.app.roll.table.tally.total());
    vec![
        state("d4 rolling", die_rolling("d4", theme).app, &["face up", "d4"]),
        state("d10 rolling", die_rolling("d10", theme).app, &["face up", "d10"]),
        state("d20 rolling", die_rolling("d20", theme).app, &["face up", "d20"]),
        state("d20 outcome table", table.app, &["face up", &n]),
    ]
}

/// The dice in the default (dark) theme: the same screens, snapshot apart from the
/// projector's (their text is the theme's too: its fills and marks).
#[test]
fn the_dice_in_the_default_theme() {
    for s in dice_states(Theme::default()) {
        for size in SIZES {
            let name = format!(
                "default_{}_{}x{}",
                s.name.replace([' ', ','], "_"),
                size.0,
                size.1
            );
            insta::assert_snapshot!(name, text(&draw(&s.app, size)));
        }
    }
}

/// Cells of solid bar in a table row: whole blocks, and eighths for the partial one.
fn solid_cells(row: &str) -> f64 {
    let eighths = ['▏', '▎', '▍', '▌', '▋', '▊', '▉', '█'];
    row.chars()
        .filter_map(|c| eighths.iter().position(|&e| e == c))
        .map(|k| (k + 1) as f64 / 8.0)
        .sum()
}

/// `loaded-corner` after 2 000 rolls at 80×24 and 100×30, read from the back of a room: the
/// bars start where the intervals allow (every interval lies in 12.1–21.8 %, so from 10 %,
/// 1/6 in the middle, to 23.3 %) and face 1's bar (low end 18.3 %) is at least four cells
/// longer than face 5's (12.1 %): 13 cells over 13.3 % give 8.1 and 2.0. Over 0–1/3 they
/// were 7.1 and 4.7, "one cell" apart. Above 1/6 the bar runs through the fair mark's
/// column, below it the dotted mark stands alone, so the two cannot be taken for each other.
#[test]
fn a_loaded_dies_bias_is_cells_long_at_80x24_and_100x30() {
    let s = loaded_batch(2000, projector());
    for size in [(80, 24), (100, 30)] {
        let shown = text(&draw(&s.app, size));
        let row = |face: u8| {
            shown
                .lines()
                .find(|l| l.starts_with(&format!("│  {face}  ")))
                .unwrap_or_else(|| panic!("face {face}:\n{shown}"))
                .to_string()
        };
        let (one, five) = (row(1), row(5));
        assert!(
            solid_cells(&one) - solid_cells(&five) >= 4.0,
            "{size:?}\n{one}\n{five}"
        );
        assert!(shown.contains("10 %"), "the bars' start named: {shown}");
        let bar = |r: &str| r.chars().skip(23).take(13).collect::<String>();
        assert_eq!(bar(&one).chars().nth(6), Some('█'), "{one}");
        assert_eq!(bar(&five).chars().nth(6), Some('┆'), "{five}");
    }
}
