//! The map screen's keys: the cursor, zoom, axes, ranges, replay and export.

use crate::tui::input::update::update;
use crate::tui::state::app::{App, Page};
use crate::tui::state::map_view::{MapView, ZOOM_FACTOR};
use crate::tui::state::messages::Msg;
use crate::tui::tests::fixtures::{
    CELLS, computed, export_into, map_of, map_scene, press, screen, spun_preset, start,
};
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::theme::Theme;
use crate::worker::Command;
use dicesim_experiment::basin::node_setup;
use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::layout::Rect;

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
