//! The basin-map screen from deterministic states: a small map computed here with
//! `run_map`, handed to the app through the message the worker's map thread sends.

use super::state::app::App;
use super::state::app::Page;
use super::state::map_view::{MapView, ZOOM_FACTOR, map_layout};
use super::state::messages::{Effect, Msg};
use super::tests::{Harness, boundary_sizes, screen, spun_preset, start};
use crate::tui::input::update::update;
use crate::tui::render::screen::render;
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::theme::Theme;
use crate::worker::{Command, MapUpdate};
use dicesim_experiment::basin::node_setup;
use dicesim_experiment::{BasinMap, Layer, MapSpec, Method, run_map};
use dicesim_figures::plot::{FACE_COLOURS, cell_colour, time_range};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::layout::Rect;
use ratatui::style::Color;
use std::sync::atomic::AtomicBool;

/// Grid nodes of the test map: small enough to compute in a moment, odd in y so the last
/// character row holds a single cell.
const CELLS: (usize, usize) = (40, 27);

fn press(app: &mut App, code: KeyCode) -> Vec<Command> {
    update(
        app,
        Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))),
    )
    .into_iter()
    .filter_map(Effect::command)
    .collect()
}

/// The map the app asked for last, at [`CELLS`], as the worker would compute it.
pub(crate) fn computed(app: &App) -> MapUpdate {
    let (request, params, initial) = app.map.requested.expect("a map was requested");
    let mut x = request.x;
    let mut y = request.y;
    (x.cells, y.cells) = CELLS;
    let spec = MapSpec {
        x: x.axis().expect("valid axis"),
        y: y.axis().expect("valid axis"),
        method: Method::Adaptive,
    };
    let never = AtomicBool::new(false);
    let map = run_map(&params, &initial, &spec, 0, &never, &mut |_| {}).expect("the map computes");
    assert!(map.complete);
    MapUpdate {
        generation: request.generation,
        params,
        initial,
        map: Ok(map),
    }
}

/// The die view's scene, switched to the map screen, with the map in and the cursor moved.
/// `e` on the map screen, and the export it orders run into `dir` as the worker's export
/// runner would run it (the key itself asks for the current folder).
pub(crate) fn export_into(s: &mut Harness, dir: &std::path::Path) {
    for c in press(&mut s.app, KeyCode::Char('e')) {
        let c = match c {
            Command::ExportMap(mut m) => {
                m.dir = dir.to_path_buf();
                Command::ExportMap(m)
            }
            other => other,
        };
        s.simulator.handle(c);
    }
    s.simulator.run_export_here();
    s.sync();
}

pub(crate) fn map_scene(theme: Theme) -> Harness {
    let mut s = Harness::new(&spun_preset(), theme);
    let sent = press(&mut s.app, KeyCode::Tab);
    assert!(matches!(sent[..], [Command::MapStart(_)]), "{sent:?}");
    let m = computed(&s.app);
    update(&mut s.app, Msg::from(m));
    // The terminal asked for a larger grid than the test computes: start from its middle.
    s.app.map.cursor = (CELLS.0 / 2, CELLS.1 / 2);
    for k in [KeyCode::Right, KeyCode::Right, KeyCode::Right, KeyCode::Up] {
        press(&mut s.app, k);
    }
    s
}

fn draw(app: &App, width: u16, height: u16) -> Terminal<TestBackend> {
    let mut t = Terminal::new(TestBackend::new(width, height)).expect("test backend");
    t.draw(|f| render(app, f)).expect("draw");
    t
}

fn map_of(app: &App) -> &BasinMap {
    app.map.map().expect("a map is shown")
}

#[test]
fn map_screen() {
    let s = map_scene(Theme::default());
    assert_eq!(s.app.page, Page::Map);
    let cursor = s.app.map.cursor;
    assert_eq!(cursor, (CELLS.0 / 2 + 3, CELLS.1 / 2 + 1));
    let text = draw(&s.app, 120, 36).backend().to_string();
    assert!(
        text.contains(&format!("cursor cell ({}, {})", cursor.0, cursor.1)),
        "{text}"
    );
    // The axes in the parameter list's words, as the exported picture names them.
    let x = s.app.map.x.key;
    assert!(text.contains(&format!("x: {} →", x.title())), "{text}");
    assert!(!text.contains("initial.angular_velocity.x"), "{text}");
    insta::assert_snapshot!("map_120x36", text);
    insta::assert_snapshot!("map_80x24", draw(&s.app, 80, 24).backend().to_string());
}

#[test]
fn half_blocks_carry_the_faces_of_two_cells() {
    let s = map_scene(Theme::default());
    let map = map_of(&s.app);
    let grid = map_layout(Rect::new(0, 0, 120, 36)).expect("full size").grid;
    let t = draw(&s.app, 120, 36);
    let buffer = t.backend().buffer();
    let face_colour = |i: usize, j: usize| {
        let f = map
            .cell(i, j)
            .and_then(|c| c.outcome.face)
            .expect("a settled face");
        let c = FACE_COLOURS[f as usize - 1];
        Color::Rgb(c.0, c.1, c.2)
    };
    let h = map.height();
    // The top row holds the two highest rows of cells; column 0 is x node 0.
    let top = &buffer[(grid.x, grid.y)];
    assert_eq!(top.symbol(), "▀");
    assert_eq!((top.fg, top.bg), (face_colour(0, h - 1), face_colour(0, h - 2)));
    let (i, row) = (CELLS.0 - 1, 5);
    let cell = &buffer[(grid.x + i as u16, grid.y + row)];
    let upper = h - 1 - 2 * row as usize;
    assert_eq!(
        (cell.fg, cell.bg),
        (face_colour(i, upper), face_colour(i, upper - 1))
    );
    // With an odd number of rows the last character row holds only the bottom row.
    let last = &buffer[(grid.x + 1, grid.y + h.div_ceil(2) as u16 - 1)];
    assert_eq!((last.fg, last.bg), (face_colour(1, 0), Color::Reset));
    // Somewhere the map has a border between two faces inside one character.
    let mut mixed = 0;
    for r in 0..h.div_ceil(2) as u16 {
        for c in 0..CELLS.0 as u16 {
            let b = &buffer[(grid.x + c, grid.y + r)];
            mixed += usize::from(b.fg != b.bg && b.bg != Color::Reset);
        }
    }
    assert!(mixed > 0, "the test map should cross a border");
}

#[test]
fn settle_time_layer() {
    let mut s = map_scene(Theme::default());
    press(&mut s.app, KeyCode::Char('v'));
    assert_eq!(s.app.map.layer, Layer::SettleTime);
    let map = map_of(&s.app).clone();
    let grid = map_layout(Rect::new(0, 0, 120, 36)).expect("full size").grid;
    let t = draw(&s.app, 120, 36);
    let text = t.backend().to_string();
    assert!(text.contains("settle time"), "{text}");
    let times = time_range(&map);
    let h = map.height();
    let c = cell_colour(map.cell(2, h - 1), Layer::SettleTime, times);
    assert_eq!(
        t.backend().buffer()[(grid.x + 2, grid.y)].fg,
        Color::Rgb(c.0, c.1, c.2)
    );
    // Brighter means longer: the longest-settling cell is drawn in the scale's top colour.
    let (longest, _) = (0..map.width() * h)
        .filter_map(|k| map.cells[k].map(|c| (k, c.outcome.time_s)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("cells");
    let top = cell_colour(map.cells[longest].as_ref(), Layer::SettleTime, times);
    assert_eq!((top.0, top.1, top.2), (253, 231, 37));
    insta::assert_snapshot!("map_settle_time_120x36", text);
}

#[test]
fn without_colour_faces_are_digits() {
    let s = map_scene(Theme::monochrome());
    let map = map_of(&s.app);
    let grid = map_layout(Rect::new(0, 0, 120, 36)).expect("full size").grid;
    let t = draw(&s.app, 120, 36);
    let buffer = t.backend().buffer();
    for y in 0..36 {
        for x in 0..120 {
            let c = &buffer[(x, y)];
            assert_eq!((c.fg, c.bg), (Color::Reset, Color::Reset), "cell {x},{y}");
        }
    }
    let f = map
        .cell(0, map.height() - 1)
        .and_then(|c| c.outcome.face)
        .expect("face");
    assert_eq!(buffer[(grid.x, grid.y)].symbol(), f.to_string());
    assert!(t.backend().to_string().contains("digits 1-6 show the face up"));
}

#[test]
fn help_lists_the_map_keys_and_footer_says_tab() {
    let s = start();
    let text = draw(&s.app, 120, 36).backend().to_string();
    assert!(text.contains("Tab map"), "{text}");
    let mut s = map_scene(Theme::default());
    press(&mut s.app, KeyCode::Char('?'));
    let text = draw(&s.app, 120, 36).backend().to_string();
    assert!(text.contains("Basin-map screen"), "{text}");
}

/// Pure `update`: cursor, zoom, axes, stale maps, replay; no worker involved.
mod keys {
    use super::*;

    fn starts(sent: &[Command]) -> Vec<crate::worker::MapRequest> {
        sent.iter()
            .filter_map(|c| match c {
                Command::MapStart(r) => Some(*r),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn the_cursor_stays_on_the_map() {
        let mut s = map_scene(Theme::default());
        let a = &mut s.app;
        for _ in 0..100 {
            press(a, KeyCode::Left);
            press(a, KeyCode::Char('j'));
        }
        assert_eq!(a.map.cursor, (0, 0));
        for _ in 0..100 {
            press(a, KeyCode::Char('l'));
            press(a, KeyCode::Up);
        }
        assert_eq!(a.map.cursor, (CELLS.0 - 1, CELLS.1 - 1));
        update(
            a,
            Msg::Input(Event::Key(KeyEvent::new(KeyCode::Left, KeyModifiers::SHIFT))),
        );
        assert_eq!(a.map.cursor.0, CELLS.0 - 1 - 8);
    }

    #[test]
    fn zoom_shrinks_around_the_cursor_and_zooming_out_restores() {
        let mut s = map_scene(Theme::default());
        let a = &mut s.app;
        let before = (a.map.x, a.map.y, a.map.cursor, a.map.generation);
        let map = map_of(a).clone();
        let (i, j) = a.map.cursor;
        let (cx, cy) = (map.x.value(i), map.y.value(j));
        let sent = press(a, KeyCode::Char('z'));
        let [r] = starts(&sent)[..] else {
            panic!("{sent:?}")
        };
        assert_eq!(r.generation, before.3 + 1);
        for (axis, old, centre) in [(&r.x, &before.0, cx), (&r.y, &before.1, cy)] {
            let span = axis.max - axis.min;
            assert!((span - (old.max - old.min) / ZOOM_FACTOR).abs() < 1e-9);
            assert!(axis.min <= centre && centre <= axis.max);
            assert!(axis.min >= old.min && axis.max <= old.max);
        }
        assert!(a.map.map().is_none(), "the old map is not drawn on the new axes");
        assert_eq!(a.map.cursor, (r.x.cells / 2, r.y.cells / 2));
        let inner = computed(a);
        update(a, Msg::from(inner));
        press(a, KeyCode::Char('z'));
        assert_eq!(a.map.zooms.len(), 2);
        press(a, KeyCode::Char('Z'));
        let sent = press(a, KeyCode::Char('Z'));
        let [r] = starts(&sent)[..] else {
            panic!("{sent:?}")
        };
        assert_eq!(
            (r.x.min, r.x.max, r.y.min, r.y.max),
            (before.0.min, before.0.max, before.1.min, before.1.max)
        );
        assert_eq!(a.map.cursor, before.2);
        assert!(a.map.zooms.is_empty());
        assert!(
            starts(&press(a, KeyCode::Char('Z'))).is_empty(),
            "nothing further out"
        );
    }

    #[test]
    fn a_new_axis_restarts_the_map_and_stale_maps_are_ignored() {
        let mut s = map_scene(Theme::default());
        let a = &mut s.app;
        let old = computed(a);
        let generation = a.map.generation;
        let sent = press(a, KeyCode::Char('x'));
        let [r] = starts(&sent)[..] else {
            panic!("{sent:?}")
        };
        assert_eq!(r.generation, generation + 1);
        assert_eq!(
            Param::of(r.x.key),
            Param::named("initial.angular_velocity.z"),
            "the next value that is not y's"
        );
        // A late partial map of the old axes arrives: it must not be drawn.
        let mut late = old.clone();
        if let Ok(m) = &mut late.map {
            m.complete = false;
        }
        update(a, Msg::from(late));
        assert!(a.map.shown.is_none());
        assert!(a.map.running);
        let fresh = computed(a);
        update(a, Msg::from(fresh.clone()));
        assert_eq!(a.map.shown.as_ref(), Some(&fresh));
        assert!(!a.map.running);
        // Once the new map is in, an old one still cannot replace it.
        update(a, Msg::from(old));
        assert_eq!(a.map.shown.as_ref(), Some(&fresh));
    }

    #[test]
    fn leaving_an_unfinished_map_cancels_it_and_coming_back_restarts_it() {
        let mut a = start().app;
        press(&mut a, KeyCode::Tab);
        let sent = press(&mut a, KeyCode::Tab);
        assert_eq!(sent, [Command::MapCancel]);
        assert_eq!(a.page, Page::Die);
        let sent = press(&mut a, KeyCode::Tab);
        assert_eq!(starts(&sent).len(), 1);
        // A finished map on an unchanged setup is shown again without recomputing.
        let mut s = map_scene(Theme::default());
        press(&mut s.app, KeyCode::Tab);
        assert!(press(&mut s.app, KeyCode::Tab).is_empty());
        assert!(s.app.map.map().is_some());
    }

    #[test]
    fn ranges_are_typed_and_checked() {
        let mut s = map_scene(Theme::default());
        let a = &mut s.app;
        let type_range = |a: &mut App, text: &str| {
            press(a, KeyCode::Char('Y'));
            for _ in 0..20 {
                press(a, KeyCode::Backspace);
            }
            for c in text.chars() {
                press(a, KeyCode::Char(c));
            }
            press(a, KeyCode::Enter)
        };
        for (bad, why) in [
            ("-20000 5", "outside the allowed range"),
            ("10 5", "must be below"),
            ("5", "MIN MAX"),
            ("1e 5", "not a number"),
        ] {
            assert!(type_range(a, bad).is_empty(), "{bad}");
            let e = a.map.editing.as_ref().and_then(|r| r.editor.error.clone());
            assert!(e.as_ref().is_some_and(|e| e.contains(why)), "{bad}: {e:?}");
            press(a, KeyCode::Esc);
            assert!(a.map.editing.is_none());
        }
        let sent = type_range(a, "-10:10");
        let [r] = starts(&sent)[..] else {
            panic!("{sent:?}")
        };
        assert_eq!((r.y.min, r.y.max), (-10.0, 10.0));
        assert_eq!(Param::of(r.y.key), Param::named("initial.angular_velocity.y"));
    }

    #[test]
    fn the_range_editor_and_the_default_range_keep_to_bodies_that_can_exist() {
        use crate::tui::state::map_view::{Side, default_range};
        use crate::tui::vocabulary::key_table::{Action, Input};
        use crate::worker::MapAxis;
        use dicesim_physics::{InitialCondition, Params, check_setup};
        // A die rounded by 0.9 on its half size of 1: a coarse step of 0.1 either side put 1,
        // a corner radius no body has, at the default range's top end.
        let params = Params {
            die: dicesim_physics::Die {
                corner_radius: 0.9,
                ..Params::DEFAULT.die
            },
            ..Params::DEFAULT
        };
        let initial = InitialCondition::default();
        let radius = Param::named("die.corner_radius");
        let (lo, hi) = default_range(radius, &params, &initial);
        assert!(lo < 0.9 && 0.9 < hi && hi < 1.0, "{lo} {hi}");
        for v in [lo, hi] {
            let (mut p, mut ic) = (params, initial);
            radius.scan_key().set(&mut p, &mut ic, v);
            check_setup(&p, &ic).unwrap();
        }
        // "0 2" typed for the corner radius is refused with roll's words for the first node
        // past the half size, and the axis stays as it was.
        let screen = Rect::new(0, 0, 100, 30);
        let mut m = MapView::new(&params, &initial);
        m.x = MapAxis {
            key: radius.scan_key(),
            min: lo,
            max: hi,
            cells: 0,
        };
        m.edit_range(Side::X);
        let typed = |m: &mut MapView, text: &str| {
            let editor = &mut m.editing.as_mut().unwrap().editor;
            editor.text.clear();
            for c in text.chars() {
                m.type_range(&Input::Type(c), screen, &params, &initial);
            }
            let confirm = Input::Act {
                action: Action::Confirm,
                coarse: false,
            };
            m.type_range(&confirm, screen, &params, &initial)
        };
        assert_eq!(typed(&mut m, "0 2"), None);
        let e = m.editing.as_ref().and_then(|r| r.editor.error.clone()).unwrap();
        assert!(e.starts_with("the node die.corner_radius = 1"), "{e}");
        assert!(
            e.contains("the corner radius must be below the smallest half size, 1 cm"),
            "{e}"
        );
        assert_eq!((m.x.min, m.x.max), (lo, hi));
        // A range of bodies that exist is taken.
        let sent = typed(&mut m, "0 0.95").expect("a map is asked for");
        assert_eq!((sent.x.min, sent.x.max), (0.0, 0.95));
    }

    #[test]
    fn enter_replays_the_exact_cell_in_the_die_view() {
        let mut s = map_scene(Theme::default());
        let map = map_of(&s.app).clone();
        let shown = s.app.map.shown.clone().expect("map");
        let (i, j) = s.app.map.cursor;
        let (params, initial) = node_setup(&shown.params, &shown.initial, &map.x, &map.y, i, j);
        let sent = press(&mut s.app, KeyCode::Enter);
        assert_eq!(sent, [Command::PlaySetup(Box::new(params), initial)]);
        assert_eq!(s.app.page, Page::Die);
        // The worker's simulator plays it to the face the map shows for that cell.
        for c in sent {
            s.simulator.handle(c);
        }
        s.run_to_end();
        let outcome = map.cell(i, j).expect("cell").outcome;
        let crate::worker::Phase::Ended(played) = s.app.roll.live.phase else {
            panic!("the roll ended")
        };
        // The map's time is the steps × Δt its files print; the screen's the clock's.
        assert_eq!(
            (played.status, played.face, played.steps),
            (outcome.status, outcome.face, outcome.steps)
        );
        assert_eq!(s.app.setup.initial, initial);
    }

    /// A PNG's size and the share of ink (non-white pixels) in its bottom tenth, where the
    /// caption stands.
    fn size_and_caption_ink(path: &std::path::Path) -> ((u32, u32), f64) {
        let decoder = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(path).expect("written"),
        ));
        let mut reader = decoder.read_info().expect("a PNG");
        let mut pixels = vec![0; reader.output_buffer_size().expect("an image that fits in memory")];
        let info = reader.next_frame(&mut pixels).expect("its pixels");
        let (w, h) = (info.width as usize, info.height as usize);
        let rows = &pixels[(h - h / 10) * w * 3..h * w * 3];
        let ink = rows.chunks(3).filter(|p| p.iter().any(|&c| c < 200)).count();
        ((info.width, info.height), ink as f64 / (rows.len() / 3) as f64)
    }

    #[test]
    fn export_writes_the_size_chosen_with_its_text_scaled() {
        let mut s = map_scene(Theme::default());
        let dir = tempfile::tempdir().expect("temp dir");
        export_into(&mut s, dir.path());
        let (small, small_ink) = size_and_caption_ink(&dir.path().join("basin-map.png"));
        assert_eq!(small, (1200, 800));
        press(&mut s.app, KeyCode::Char('E'));
        press(&mut s.app, KeyCode::Char('E'));
        let notice = s.app.notice.clone().unwrap_or_default();
        assert!(notice.contains("3000×2000 (print)"), "{notice}");
        s.app.notice = None;
        assert!(
            screen(&s.app, 120, 36).contains("PNG 3000×2000"),
            "the footer says the size"
        );
        export_into(&mut s, dir.path());
        let notice = s.app.notice.clone().unwrap_or_default();
        assert!(notice.contains("3000×2000 px"), "{notice}");
        let (large, large_ink) = size_and_caption_ink(&dir.path().join("basin-map-2.png"));
        assert_eq!(large, (3000, 2000));
        // The caption grew with the picture: it inks about the same share of its strip
        // (unscaled text would ink some 2.5² times less).
        assert!(
            (large_ink / small_ink - 1.0).abs() < 0.35,
            "caption ink {small_ink:.4} at 1200×800, {large_ink:.4} at 3000×2000"
        );
        // Four sizes, then the first again.
        press(&mut s.app, KeyCode::Char('E'));
        press(&mut s.app, KeyCode::Char('E'));
        assert!(
            s.app
                .notice
                .as_ref()
                .is_some_and(|n| n.contains("1200×800 (screen)"))
        );
    }

    #[test]
    fn a_map_export_runs_as_the_workers_job_and_e_cancels_it() {
        let mut s = map_scene(Theme::default());
        let sent = press(&mut s.app, KeyCode::Char('e'));
        let [Command::ExportMap(m)] = &sent[..] else {
            panic!("{sent:?}")
        };
        // The map on screen, at the size chosen, from the setup its cells started from.
        let shown = s.app.map.shown.clone().expect("a map");
        assert_eq!(
            (&m.map, m.params, m.initial, m.size),
            (
                shown.map.as_ref().expect("computed"),
                shown.params,
                shown.initial,
                (1200, 800)
            )
        );
        let dir = tempfile::tempdir().expect("temp dir");
        let mut m = m.clone();
        m.dir = dir.path().to_path_buf();
        s.simulator.handle(Command::ExportMap(m));
        s.sync();
        assert!(
            screen(&s.app, 120, 36).contains("exporting the basin map at 1200×800 px · e cancels"),
            "the status line says what runs and how to stop it"
        );
        assert_eq!(press(&mut s.app, KeyCode::Char('e')), [Command::ExportCancel]);
        s.simulator.handle(Command::ExportCancel);
        s.simulator.run_export_here();
        s.sync();
        assert_eq!(
            s.app.notice.as_deref(),
            Some("export cancelled: nothing was written")
        );
        assert_eq!(std::fs::read_dir(dir.path()).expect("the folder").count(), 0);
    }

    #[test]
    fn export_writes_a_png_and_its_cells_and_says_where() {
        let mut s = map_scene(Theme::default());
        let dir = tempfile::tempdir().expect("temp dir");
        export_into(&mut s, dir.path());
        let path = dir.path().join("basin-map.png");
        assert!(path.exists());
        // The cells as CSV: a header, then one row per known cell, each as the map holds it.
        let csv = std::fs::read_to_string(dir.path().join("basin-map.csv")).expect("the cells");
        let map = map_of(&s.app);
        let known = map.cells.iter().flatten().count();
        assert_eq!(csv.lines().count(), known + 1, "{}", &csv[..200.min(csv.len())]);
        let (i, j) = s.app.map.cursor;
        let cell = map.cell(i, j).expect("the cursor's cell is known");
        let row = csv
            .lines()
            .find(|l| l.starts_with(&format!("{i},{j},")))
            .expect("the cursor's row");
        let fields: Vec<&str> = row.split(',').collect();
        let face = cell.outcome.face.map_or(String::new(), |f| f.to_string());
        assert_eq!(
            (fields[5], fields[7]),
            (face.as_str(), cell.outcome.steps.to_string().as_str()),
            "{row}"
        );
        assert!(
            s.app
                .notice
                .as_ref()
                .is_some_and(|n| n.contains(&path.display().to_string()))
        );
        export_into(&mut s, dir.path());
        assert!(
            dir.path().join("basin-map-2.png").exists() && dir.path().join("basin-map-2.csv").exists(),
            "an earlier export is kept"
        );
        // Nothing is written unless asked.
        s.simulator.run_export_here();
        assert!(!dir.path().join("basin-map-3.png").exists());
    }

    #[test]
    fn the_default_axes_are_spin_x_against_spin_y_around_the_setup() {
        let preset = spun_preset();
        let m = MapView::new(&preset.params(), &preset.initial);
        let w = preset.initial.angular_velocity;
        assert_eq!(
            (Param::of(m.x.key), Param::of(m.y.key)),
            (
                Param::named("initial.angular_velocity.x"),
                Param::named("initial.angular_velocity.y")
            )
        );
        // The width of the default random range, on round numbers, around the current spin.
        for (a, now) in [(&m.x, w[0]), (&m.y, w[1])] {
            assert_eq!(a.max - a.min, 120.0);
            assert!(a.min < now && now < a.max);
            assert_eq!((a.min % 10.0, a.max % 10.0), (0.0, 0.0));
        }
    }
}

/// The map screen in its three looks: computed with the cursor moved, monochrome with the
/// other layer, and waiting for its first map.
fn map_screens() -> [App; 3] {
    let mut s = map_scene(Theme::default());
    let mut mono = map_scene(Theme::monochrome());
    press(&mut mono.app, KeyCode::Char('v'));
    press(&mut s.app, KeyCode::Char('X'));
    let mut waiting = start().app;
    press(&mut waiting, KeyCode::Tab);
    [s.app, mono.app, waiting]
}

#[test]
fn every_boundary_size_draws_the_map_screen() {
    for app in &map_screens() {
        for (width, height) in boundary_sizes() {
            draw(app, width, height);
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]

    #[test]
    fn random_sizes_draw_the_map_screen(which in 0usize..3, width in 1u16..=200, height in 1u16..=60) {
        static SCREENS: std::sync::OnceLock<[App; 3]> = std::sync::OnceLock::new();
        draw(&SCREENS.get_or_init(map_screens)[which], width, height);
    }
}
