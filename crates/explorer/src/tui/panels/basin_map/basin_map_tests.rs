//! The basin map screen: its cells, layers, legend and cursor, at every size.

use crate::tui::input::update::update;
use crate::tui::render::screen::render;
use crate::tui::state::app::{App, Page};
use crate::tui::state::map_view::map_layout;
use crate::tui::state::messages::Msg;
use crate::tui::tests::fixtures::{
    CELLS, at_rest, boundary_sizes, computed, map_of, map_scene, press, screen, shipped, start,
};
use crate::tui::vocabulary::theme::{Palette, Theme};
use dicesim_experiment::Layer;
use dicesim_figures::plot::{FACE_COLOURS, cell_colour, time_range};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::crossterm::event::KeyCode;
use ratatui::layout::Rect;
use ratatui::style::Color;

fn draw(app: &App, width: u16, height: u16) -> Terminal<TestBackend> {
    let mut t = Terminal::new(TestBackend::new(width, height)).expect("test backend");
    t.draw(|f| render(app, f)).expect("draw");
    t
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
    let c = cell_colour(map.numbers, map.cell(2, h - 1), Layer::SettleTime, times);
    assert_eq!(
        t.backend().buffer()[(grid.x + 2, grid.y)].fg,
        Color::Rgb(c.0, c.1, c.2)
    );
    // Brighter means longer: the longest-settling cell is drawn in the scale's top colour.
    let (longest, _) = (0..map.width() * h)
        .filter_map(|k| map.cells[k].map(|c| (k, c.outcome.time_s)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("cells");
    let top = cell_colour(map.numbers, map.cells[longest].as_ref(), Layer::SettleTime, times);
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

mod map_screen {
    use super::*;
    use crate::tui::state::map_view::MapView;
    use crate::tui::tests::fixtures::{export_into, map_scene};
    use dicesim_experiment::{Cell, Layer, MapSpec, Method, run_map};
    use dicesim_figures::plot::Record;
    use dicesim_setup::preset::{Preset, shipped_text};
    use ratatui::style::Color;
    use std::sync::atomic::AtomicBool;

    fn light() -> Theme {
        Theme {
            palette: Palette::Light,
            ..Theme::default()
        }
    }

    #[test]
    fn the_map_is_painted_in_the_light_theme() {
        let s = map_scene(light());
        let mut t = Terminal::new(TestBackend::new(120, 36)).expect("test backend");
        t.draw(|f| render(&s.app, f)).expect("draw");
        let b = t.backend().buffer();
        let unpainted = b
            .content()
            .iter()
            .filter(|c| c.bg == Color::Reset || c.fg == Color::Reset)
            .count();
        assert_eq!(unpainted, 0, "every cell gets the theme's paper and ink");
        insta::assert_snapshot!("map_light_120x36", t.backend().to_string());
    }

    /// The text chunks of a PNG file, keyword → text.
    fn text_chunks(bytes: &[u8]) -> Vec<(String, String)> {
        let reader = png::Decoder::new(std::io::Cursor::new(bytes))
            .read_info()
            .expect("a PNG");
        reader
            .info()
            .utf8_text
            .iter()
            .map(|c| (c.keyword.clone(), c.get_text().expect("UTF-8 text")))
            .collect()
    }

    #[test]
    fn the_settle_time_layer_marks_filled_cells_and_the_readout_says_so() {
        let mut s = map_scene(Theme::default());
        s.app.map.layer = Layer::SettleTime;
        // On the paper's setup refinement rolls every cell; mark the cursor's cell as one the
        // adaptive method filled in, as it does wherever a block's corners agree.
        let filled = s.app.map.cursor;
        let Some(Ok(map)) = s.app.map.shown.as_mut().map(|u| &mut u.map) else {
            panic!("a map")
        };
        let w = map.width();
        let c = map.cells[filled.1 * w + filled.0].as_mut().expect("computed");
        assert_eq!(c.outcome.status, dicesim_physics::Status::Settled);
        c.sampled = false;
        let map = map.clone();
        let text = screen(&s.app, 120, 36);
        assert!(text.contains("· inferred"), "{text}");
        assert!(text.contains("time not known"), "{text}");
        assert!(text.contains("not rolled (filled in)"), "{text}");
        let c = map.cell(filled.0, filled.1).expect("filled");
        let colour = cell_colour(map.numbers, Some(c), Layer::SettleTime, None);
        let rolled = Cell { sampled: true, ..*c };
        assert_ne!(
            colour,
            cell_colour(map.numbers, Some(&rolled), Layer::SettleTime, None),
            "a filled cell does not wear a copied time's colour"
        );
    }

    #[test]
    fn the_exported_map_records_its_setup() {
        let mut s = map_scene(Theme::default());
        let dir = tempfile::tempdir().expect("temp dir");
        export_into(&mut s, dir.path());
        let bytes = std::fs::read(dir.path().join("basin-map.png")).expect("written");
        let chunks = text_chunks(&bytes);
        let get = |k: &str| {
            chunks
                .iter()
                .find(|(key, _)| key == k)
                .map(|(_, t)| t.clone())
                .unwrap_or_else(|| panic!("no {k} chunk in {chunks:?}"))
        };
        let setup = get("dicesim-setup");
        let p = &s.app.map.shown.as_ref().expect("a map").params;
        assert!(
            setup.contains(&format!("ground.stiffness = {}", p.ground.stiffness)),
            "{setup}"
        );
        assert!(setup.contains("integrator.dt = 0.001"), "{setup}");
        assert!(get("dicesim-axes").contains("initial.angular_velocity.x from"));
        assert!(get("Title").starts_with("Face up"));
        assert!(
            get("Description").contains("height 15 cm"),
            "{}",
            get("Description")
        );
    }

    #[test]
    fn the_energy_png_follows_the_scale_and_records_its_setup() {
        let s = at_rest(Theme::default());
        let samples: Vec<(f64, dicesim_physics::Energy)> =
            s.app.roll.history.iter().map(|h| (h.time_s, h.energy)).collect();
        let record = Record::of_setup(
            "paper — energy",
            "paper",
            &s.app.setup.params,
            &s.app.setup.initial,
        );
        let threshold = s.app.roll.live.stop_threshold;
        let log =
            dicesim_figures::energy_plot::energy_plot_png(&samples, threshold, true, &record).expect("draws");
        let linear = dicesim_figures::energy_plot::energy_plot_png(&samples, threshold, false, &record)
            .expect("draws");
        assert_ne!(log, linear, "the scale changes the picture");
        let chunks = text_chunks(&log);
        assert!(
            chunks
                .iter()
                .any(|(k, t)| k == "dicesim-setup" && t.contains("initial.height = 15")),
            "{chunks:?}"
        );
    }

    /// Share of neighbouring cells (along x and y) that end differently.
    fn border_share(name: &str) -> f64 {
        let preset = Preset::from_toml_str(shipped_text(name).expect("shipped"), name).expect("valid");
        let (params, initial) = (preset.params(), preset.initial);
        let view = MapView::new(&params, &initial);
        let (mut x, mut y) = (view.x, view.y);
        (x.cells, y.cells) = (80, 40);
        let spec = MapSpec {
            x: x.axis().expect("axis"),
            y: y.axis().expect("axis"),
            method: Method::Uniform,
        };
        let map = run_map(&params, &initial, &spec, 0, &AtomicBool::new(false), &mut |_| {}).expect("map");
        let class = |i, j| map.cell(i, j).map(|c| (c.outcome.status, c.outcome.face));
        let (mut differ, mut pairs) = (0, 0);
        for j in 0..map.height() {
            for i in 0..map.width() {
                for (a, b) in [(i + 1, j), (i, j + 1)] {
                    if a < map.width() && b < map.height() {
                        pairs += 1;
                        differ += usize::from(class(i, j) != class(a, b));
                    }
                }
            }
        }
        differ as f64 / pairs as f64
    }

    #[test]
    fn gentle_drop_shows_borders_on_the_maps_default_axes_where_paper_is_noise() {
        // Regions with borders: some neighbours differ, most agree. Noise: most differ.
        let gentle = border_share("gentle-drop");
        let paper = border_share("paper");
        assert!(gentle > 0.01 && gentle < 0.2, "gentle-drop: {gentle}");
        assert!(paper > 2.0 * gentle, "paper {paper} against gentle-drop {gentle}");
    }
}

/// Defect: at 80×24 on `gentle-drop`, the map's colour key stayed under the cursor's text.
#[test]
fn the_maps_colour_key_stays_at_80_by_24() {
    let mut s = shipped("gentle-drop");
    s.key(KeyCode::Tab);
    let m = computed(&s.app);
    update(&mut s.app, Msg::from(m));
    // The cursor on a cell filled in from its block's corners: the longest cursor text.
    let map = s.app.map.map().expect("computed");
    let inferred = (0..map.width())
        .flat_map(|i| (0..map.height()).map(move |j| (i, j)))
        .find(|&(i, j)| map.cell(i, j).is_some_and(|c| !c.sampled))
        .expect("an inferred cell");
    s.app.map.cursor = inferred;
    for (w, h) in [(80, 24), (100, 30)] {
        let text = screen(&s.app, w, h);
        assert!(
            text.contains("like its block's"),
            "the inferred cell's words at {w}×{h}:\n{text}"
        );
        assert!(
            text.contains("██1 ██2 ██3 ██4 ██5 ██6"),
            "the colour key at {w}×{h}:\n{text}"
        );
        assert!(text.contains("legend: face up"), "{text}");
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
