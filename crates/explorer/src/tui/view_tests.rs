//! The die, the energy plot's legend and ticks and the outcome table, as a class sees them:
//! snapshots of deterministic states and checks that a drawing defect would break.

use super::state::app::App;
use super::state::camera::OrbitCamera;
use super::state::die_screen::Drawing;
use super::tests::{Harness, Panel, mid_impact_with, spun_preset};
use crate::tui::panels::chart::nice_ticks;
use crate::tui::panels::die::{self, Projection, picture, place_labels};
use crate::tui::panels::outcomes::{self, RELIABLE_ROLLS};
use crate::tui::panels::quantity_plot;
use crate::tui::render::screen::render;
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::solid::inside;
use crate::tui::vocabulary::theme::{Palette, Theme};
use crate::worker::Phase;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

/// One panel drawn where the layout of a `w`×`h` terminal puts it, painted as the screen is.
fn panel_at(
    app: &App,
    w: u16,
    h: u16,
    pick: fn(&crate::tui::vocabulary::layout::Areas) -> Rect,
    draw: Panel,
) -> Buffer {
    let area = pick(&screen_layout(Rect::new(0, 0, w, h)).expect("big enough"));
    let mut t = Terminal::new(TestBackend::new(area.width, area.height)).expect("test backend");
    t.draw(|f| {
        draw(app, f.area(), f);
        app.theme.paint(f.buffer_mut());
    })
    .expect("draw");
    t.backend().buffer().clone()
}

fn text(b: &Buffer) -> String {
    let a = b.area;
    (a.top()..a.bottom())
        .map(|y| {
            (a.left()..a.right())
                .map(|x| b[(x, y)].symbol())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn screen(app: &App, w: u16, h: u16) -> String {
    let mut t = Terminal::new(TestBackend::new(w, h)).expect("test backend");
    t.draw(|f| render(app, f)).expect("draw");
    t.backend().to_string()
}

/// The paper's spun roll `steps` steps in: at 150 the die is still falling, tumbling.
fn after(steps: u64, theme: Theme) -> Harness {
    let mut s = Harness::new(&spun_preset(), theme);
    s.simulator.advance_steps(steps);
    s.sync();
    s
}

fn at_rest(theme: Theme) -> Harness {
    let mut s = Harness::new(&spun_preset(), theme);
    s.run_to_end();
    s
}

const HIGH: OrbitCamera = OrbitCamera {
    yaw_deg: 135.0,
    pitch_deg: 60.0,
    zoom: 1,
};

/// The die's own cells in the panel: those whose middle lies inside its outline, away
/// from the outline itself (where the edge's dots and the floor may share a cell).
fn inner_cells(app: &App, body: Rect) -> Vec<(u16, u16)> {
    let view = Projection::new(app, body);
    let pic = picture(app, &view);
    let (cw, ch) = (
        (view.x.1 - view.x.0) / body.width as f64,
        (view.y.1 - view.y.0) / body.height as f64,
    );
    let mut cells = Vec::new();
    for row in 0..body.height {
        for col in 0..body.width {
            let p = (
                view.x.0 + cw * (col as f64 + 0.5),
                view.y.1 - ch * (row as f64 + 0.5),
            );
            let deep = [(-cw, -ch), (cw, -ch), (-cw, ch), (cw, ch)]
                .iter()
                .all(|&(dx, dy)| inside(&pic.outline, (p.0 + dx, p.1 + dy)));
            if deep {
                cells.push((col, row));
            }
        }
    }
    cells
}

/// Draws the die panel and checks what a solid die promises: no floor tile, shadow or ghost
/// inside its outline, pips drawn, labels on cells of their own.
fn check_solid(app: &App) -> Buffer {
    let b = panel_at(app, 120, 36, |a| a.die, die::render);
    let body = Rect::new(1, 1, b.area.width - 2, b.area.height - 2);
    let inner = inner_cells(app, Rect::new(0, 0, body.width, body.height));
    assert!(inner.len() > 10, "the die covers some cells: {}", inner.len());
    let hidden = [app.theme.ground(), app.theme.shadow(), app.theme.ghost()];
    for &(c, r) in &inner {
        let cell = &b[(body.x + c, body.y + r)];
        if cell.symbol() != " " {
            assert!(
                !hidden.contains(&cell.fg) || cell.fg == app.theme.die(),
                "floor or ghost drawn through the die at ({c}, {r}): {:?}\n{}",
                cell,
                text(&b)
            );
        }
    }
    let view = Projection::new(app, body);
    let pic = picture(app, &view);
    let placed = place_labels(&pic.labels, &view, &pic.outline);
    let mut taken = std::collections::HashSet::new();
    for (c, r, label) in &placed {
        for x in *c..*c + label.text.chars().count() as u16 {
            assert!(taken.insert((x, *r)), "label {:?} overlaps another", label.text);
        }
    }
    b
}

#[test]
fn the_solid_die_mid_air_from_two_angles() {
    let mut s = after(150, Theme::default());
    assert_eq!(s.app.roll.live.phase, Phase::Falling);
    let low = check_solid(&s.app);
    insta::assert_snapshot!("die_mid_air_default_camera", text(&low));
    s.app.die_screen.camera = HIGH;
    let high = check_solid(&s.app);
    insta::assert_snapshot!("die_mid_air_high_camera", text(&high));
    assert_ne!(text(&low), text(&high));
}

#[test]
fn the_solid_die_at_rest_from_two_angles() {
    let mut s = at_rest(Theme::default());
    let low = check_solid(&s.app);
    insta::assert_snapshot!("die_at_rest_default_camera", text(&low));
    s.app.die_screen.camera = HIGH;
    insta::assert_snapshot!("die_at_rest_high_camera", text(&check_solid(&s.app)));
}

/// The shipped loaded die, `steps` steps into its own roll.
pub(crate) fn loaded_after(steps: u64, theme: Theme) -> Harness {
    use dicesim_setup::preset::{Preset, shipped_text};
    let text = shipped_text("loaded-corner").expect("shipped");
    let preset = Preset::from_toml_str(text, "loaded-corner").expect("valid");
    let mut s = Harness::new(&preset, theme);
    s.simulator.advance_steps(steps);
    s.sync();
    s
}

#[test]
fn the_heavy_corner_of_a_loaded_die_is_marked() {
    for drawing in [Drawing::Braille, Drawing::Ascii] {
        let mut s = loaded_after(150, Theme::default());
        s.app.die_screen.drawing = drawing;
        let extra = s.app.roll.live.params.die.extra_corner_mass;
        let heavy = extra.iter().position(|&m| m > 0.0).expect("a heavy corner");
        let label = format!("+{} g", crate::tui::vocabulary::format::fmt_num(extra[heavy]));
        let b = check_solid(&s.app);
        let t = text(&b);
        assert!(t.contains(&label), "{label} on the die:\n{t}");
        // The mark is drawn where the corner is, when the camera sees that corner.
        let view = Projection::new(&s.app, Rect::new(0, 0, b.area.width - 2, b.area.height - 2));
        let pic = picture(&s.app, &view);
        let mark = if drawing == Drawing::Ascii { "#" } else { "◆" };
        let marked = pic.labels.iter().any(|l| l.text == mark);
        let seen = die::corner_is_seen(&s.app, &view, heavy);
        assert_eq!(marked, seen, "mark {marked}, corner seen {seen}");
        if drawing == Drawing::Braille {
            insta::assert_snapshot!("die_loaded_mid_air", t);
        }
    }
    // A fair die carries no mark.
    let s = after(150, Theme::default());
    let view = Projection::new(&s.app, Rect::new(0, 0, 64, 13));
    let pic = picture(&s.app, &view);
    assert!(
        !pic.labels.iter().any(|l| l.text.ends_with(" g") || l.text == "◆"),
        "no mass marked on a fair die"
    );
}

#[test]
fn a_die_shows_at_most_three_faces_and_nine_edges() {
    let s = after(150, Theme::default());
    let body = Rect::new(0, 0, 66, 15);
    let view = Projection::new(&s.app, body);
    let pic = picture(&s.app, &view);
    // Seen faces are filled in colour themes; each seen face carries its pips.
    let faces = pic.faces.len();
    assert!((1..=3).contains(&faces), "{faces} faces seen");
    let die_strokes = pic.layers[1].len();
    assert!(
        die_strokes <= 9 + 4,
        "at most 9 edges and the up face's frame: {die_strokes}"
    );
    let pips: usize = pic.pips.len();
    assert!((1..=6 + 5 + 4).contains(&pips), "{pips} pips");
}

#[test]
fn ascii_draws_slopes_not_stars() {
    let mut s = after(150, Theme::default());
    s.app.die_screen.drawing = Drawing::Ascii;
    let b = panel_at(&s.app, 120, 36, |a| a.die, die::render);
    let t = text(&b);
    assert!(!t.contains('*'), "{t}");
    for c in ['-', '|', '/', '\\'] {
        assert!(t.contains(c), "no `{c}` in\n{t}");
    }
    insta::assert_snapshot!("die_ascii_mid_air", t);
}

#[test]
fn every_arrow_has_its_label_and_the_legend_sits_below_the_die() {
    let mut s = mid_impact_with(Theme::default());
    s.app.die_screen.arrows = true;
    let b = check_solid(&s.app);
    let t = text(&b);
    let rows: Vec<&str> = t.lines().collect();
    let touching = s
        .app
        .roll
        .live
        .die
        .forces
        .iter()
        .filter(|f| f.depth > 0.0)
        .count();
    assert!(touching > 0);
    let f_labels = rows[1..rows.len() - 3]
        .iter()
        .map(|r| r.matches('F').count())
        .sum::<usize>();
    assert_eq!(f_labels, touching, "one F per touching corner\n{t}");
    for symbol in ["ω", "L", "v"] {
        assert!(
            rows[1..rows.len() - 3].iter().any(|r| r.contains(symbol)),
            "{symbol}\n{t}"
        );
    }
    assert!(
        rows[rows.len() - 2].contains("10× as big is half a die longer"),
        "{t}"
    );
    insta::assert_snapshot!("die_vectors_solid_mid_impact", t);
    // The contact highlight has a colour no arrow has.
    let colours = s.app.theme.vector_colours();
    assert!(!colours.contains(&s.app.theme.contact_colour()));
}

#[test]
fn the_twins_label_never_covers_the_die() {
    let mut s = after(150, Theme::default());
    s.key(ratatui::crossterm::event::KeyCode::Char('T'));
    s.simulator.advance_steps(150);
    s.sync();
    assert!(s.app.roll.live.twin.is_some());
    let t = text(&check_solid(&s.app));
    assert!(t.contains("twin"), "{t}");
}

fn projector() -> Theme {
    Theme {
        palette: Palette::Projector,
        ..Theme::default()
    }
}

#[test]
fn projector_screen_with_the_solid_die() {
    let s = after(150, projector());
    let t = screen(&s.app, 100, 30);
    insta::assert_snapshot!("projector_mid_air_100x30", t);
    let b = panel_at(&s.app, 100, 30, |a| a.die, die::render);
    // Seen faces are filled: a good share of the die's cells carry a face's grey.
    let body = Rect::new(1, 1, b.area.width - 2, b.area.height - 2);
    let inner = inner_cells(&s.app, Rect::new(0, 0, body.width, body.height));
    let filled = inner
        .iter()
        .filter(|&&(c, r)| {
            matches!(b[(body.x + c, body.y + r)].bg, ratatui::style::Color::Rgb(r, g, bl) if r < 250 || g < 250 || bl < 250)
        })
        .count();
    assert_eq!(filled, inner.len(), "every inner cell of the die is shaded");
}

#[test]
fn the_energy_legend_names_every_term_at_both_sizes() {
    for theme in [Theme::default(), Theme::monochrome()] {
        let s = mid_impact_with(theme);
        for (w, h) in [(80, 24), (120, 36)] {
            let b = panel_at(&s.app, w, h, |a| a.energy, quantity_plot::render);
            let t = text(&b);
            for name in ["total", "transl", "rot", "grav", "elastic"] {
                assert!(t.contains(name), "{name} missing at {w}×{h}:\n{t}");
            }
            if !theme.colour {
                // Without colour every line has its own character, which the legend shows.
                for item in ["#total", "+transl", "xrot", "ograv", "*elastic"] {
                    assert!(t.contains(item), "`{item}` at {w}×{h}:\n{t}");
                }
            }
            // No tick reads like 99750: each is a multiple of a round step.
            let ticks: Vec<f64> = t
                .lines()
                .filter_map(|l| l.split('│').nth(1))
                .filter_map(|cell| cell.trim().parse::<f64>().ok())
                .collect();
            assert!(ticks.len() >= 2, "{t}");
            let step = (ticks[0] - ticks[1]).abs();
            let mantissa = step / 10f64.powf(step.log10().floor());
            assert!(
                [1.0, 2.0, 5.0].iter().any(|m| (m - mantissa).abs() < 1e-9),
                "{ticks:?}\n{t}"
            );
            let name = format!(
                "energy_{}_{w}x{h}",
                if theme.colour { "colour" } else { "no_colour" }
            );
            insta::assert_snapshot!(name, t);
        }
    }
}

#[test]
fn ticks_are_round_numbers() {
    assert_eq!(nice_ticks(0.0, 199_500.0, 3).2, vec![0.0, 100_000.0, 200_000.0]);
    let (lo, hi, ticks) = nice_ticks(-480.0, 120_000.0, 4);
    assert!(lo <= -480.0 && hi >= 120_000.0);
    let step = ticks[1] - ticks[0];
    let mantissa = step / 10f64.powf(step.log10().floor());
    assert!(
        [1.0, 2.0, 5.0].iter().any(|m| (m - mantissa).abs() < 1e-9),
        "step {step}"
    );
    assert!(ticks.len() <= 4);
    assert!(ticks.iter().all(|t| (t / step).fract().abs() < 1e-9), "{ticks:?}");
}

/// A table with every ending: faces, rolls without a face, rolls that did not settle and
/// unstable ones.
fn every_ending() -> App {
    let mut s = mid_impact_with(Theme::default());
    let t = &mut s.app.roll.table;
    t.tally.counts = [512, 498, 530, 505, 470, 558];
    t.without_face = 7;
    t.did_not_settle = 16;
    t.unstable = 2114;
    s.app
}

#[test]
fn the_outcome_table_shows_every_ending_whole() {
    let app = every_ending();
    for (w, h) in [(80, 24), (120, 36)] {
        let b = panel_at(&app, w, h, |a| a.outcomes, outcomes::render);
        let t = text(&b);
        let flat = t
            .lines()
            .map(|l| l.trim_matches(|c| c == '│' || c == ' ' || c == '└' || c == '┘' || c == '─'))
            .collect::<Vec<_>>()
            .join(" ");
        for words in [
            "settled without a face 7",
            "did not settle 16",
            "unstable 2114",
            "n 3073",
        ] {
            assert!(flat.contains(words), "`{words}` at {w}×{h}:\n{t}");
        }
        for face in 1..=6 {
            assert!(t.contains(&format!("  {face}  ")), "face {face} at {w}×{h}:\n{t}");
        }
        insta::assert_snapshot!(format!("outcomes_every_ending_{w}x{h}"), t);
    }
}

/// The 95 % Wilson score interval, written out here from its formula.
fn wilson(k: u64, n: u64) -> [f64; 2] {
    let (k, n, z) = (k as f64, n as f64, 1.959_963_984_540_054);
    let p = k / n;
    let centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
    let half = z / (1.0 + z * z / n) * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
    [centre - half, centre + half]
}

#[test]
fn each_face_shows_its_95_percent_interval_in_figures_and_on_its_bar() {
    let app = every_ending();
    let counts = app.roll.table.tally.counts;
    let n: u64 = counts.iter().sum();
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    assert!(t.contains("95 % int."), "{t}");
    for (f, &k) in counts.iter().enumerate() {
        let [low, high] = wilson(k, n).map(|x| 100.0 * x);
        let figures = format!("{low:.1}–{high:.1}");
        let row = t
            .lines()
            .find(|l| l.starts_with(&format!("│  {}  ", f + 1)))
            .unwrap_or_else(|| panic!("face {} row:\n{t}", f + 1));
        assert!(row.contains(&figures), "face {} wants {figures}:\n{row}", f + 1);
    }
    // Where the interval covers 1/6 the fair mark sits inside the shading.
    let wide = |k: u64| outcomes::share_bar(k as f64 / n as f64, Some(wilson(k, n)), 29);
    let (low, fair, high) = (wide(350), wide(480), wide(700));
    assert!(
        fair.contains('┼') && !fair.contains('┃') && !fair.contains('┆'),
        "{fair}"
    );
    assert!(high.contains('┃') && !high.contains('┼'), "above 1/6: {high}");
    assert!(low.contains('┆') && !low.contains('┼'), "below 1/6: {low}");
    // A tight interval around 1/6 on a narrow bar (12 cells, 2.8 % each): 15.5–16.9 %
    // covers the fair share, so the mark reads fair though no cell is half shaded.
    let tight = outcomes::share_bar(0.162, Some([0.155, 0.169]), 12);
    assert_eq!(tight.chars().nth(6), Some('┼'), "{tight}");
    let below = outcomes::share_bar(0.150, Some([0.143, 0.157]), 12);
    assert_eq!(below.chars().nth(6), Some('┆'), "{below}");
    let above = outcomes::share_bar(0.185, Some([0.177, 0.192]), 12);
    assert_eq!(above.chars().nth(6), Some('┃'), "{above}");
    // The solid part ends at the interval's low end, the shading at its high end.
    let [l, h] = wilson(700, n);
    let cells = |x: f64| x * 3.0 * 29.0;
    let solid = high.chars().filter(|&c| c == '█' || c == '┃').count() as f64;
    let reach = high.trim_end().chars().count() as f64;
    assert!(
        (solid - cells(l)).abs() <= 1.0,
        "solid {solid} cells, low end at {}",
        cells(l)
    );
    assert!(
        (reach - cells(h)).abs() <= 1.0,
        "bar ends at {reach}, high end at {}",
        cells(h)
    );
    // At 80×24 the figures stay (a class reads them off a projector) and the count column
    // gives way; the bar is still shaded.
    let t = text(&panel_at(&app, 80, 24, |a| a.outcomes, outcomes::render));
    let [low, high] = wilson(counts[0], n).map(|x| 100.0 * x);
    assert!(t.contains(&format!("{low:.1}–{high:.1}")), "{t}");
    assert!(!t.contains("count") && t.contains('░'), "{t}");
}

#[test]
fn the_table_says_how_many_rolls_show_its_bias() {
    let mut app = every_ending();
    app.roll.table.without_face = 0;
    app.roll.table.did_not_settle = 0;
    app.roll.table.unstable = 0;
    // The heavy-corner die's shares, 20 000 rolls: a bias a class can measure.
    app.roll.table.tally.counts = [3000, 3000, 3000, 3700, 3650, 3650];
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    let n = app.roll.table.tally.rolls_to_detect().expect("a measured bias");
    assert!(
        t.contains(&format!(
            "bias this large shows in {} rolls",
            crate::tui::vocabulary::format::group(n)
        )),
        "{t}"
    );
    assert!(n > 100 && n < 20_000, "{n}");
    app.roll.table.tally.counts = [100, 100, 100, 100, 100, 100];
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    assert!(t.contains("no bias beyond chance so far"), "{t}");
}

#[test]
fn a_p_value_from_too_few_rolls_is_marked_unreliable() {
    let mut app = every_ending();
    app.roll.table.tally.counts = [3, 5, 4, 6, 2, 4];
    assert!(app.roll.table.tally.total() < RELIABLE_ROLLS);
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    assert!(t.contains("unreliable below n 30"), "{t}");
    app.roll.table.tally.counts = [30, 50, 40, 60, 20, 40];
    let t = text(&panel_at(&app, 120, 36, |a| a.outcomes, outcomes::render));
    assert!(!t.contains("unreliable") && t.contains(" p "), "{t}");
}

mod map_screen {
    use super::*;
    use crate::tui::map_tests::{export_into, map_scene};
    use crate::tui::state::map_view::MapView;
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
        let colour = dicesim_figures::plot::cell_colour(Some(c), Layer::SettleTime, None);
        let rolled = Cell { sampled: true, ..*c };
        assert_ne!(
            colour,
            dicesim_figures::plot::cell_colour(Some(&rolled), Layer::SettleTime, None),
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

/// The real dice of issue 20 as the explorer draws them: their proportions, rounded corners
/// and drilled pips, whole screens at both sizes.
mod real_dice {
    use super::*;
    use crate::tui::vocabulary::solid::Solid;
    use dicesim_physics::Params;
    use dicesim_physics::contact_sphere_centres;
    use dicesim_setup::preset::{Preset, shipped_text};
    use nalgebra::Vector3;

    fn shipped(name: &str, overrides: &[&str]) -> Harness {
        let text = shipped_text(name).expect("shipped");
        let preset = Preset::from_toml_str(text, name)
            .expect("valid")
            .with_overrides(overrides)
            .expect("valid overrides");
        Harness::new(&preset, Theme::default())
    }

    /// The tennis racket at the first step its middle axis has turned more than a quarter
    /// turn away from `L`: half way through its first flip, in flight.
    fn tennis_racket_mid_flip() -> Harness {
        let mut s = shipped("tennis-racket", &[]);
        for _ in 0..4000 {
            s.simulator.advance_steps(1);
            s.sync();
            let die = &s.app.roll.live.die;
            let body = Solid::new(&s.app.roll.live.params.die, &die.corners);
            if body.axes[1].dot(&die.angular_momentum.normalize()) < 0.0 {
                assert!(die.centre.z > 100.0, "the flip comes in flight");
                return s;
            }
        }
        panic!("the middle axis never turned over in 2 s");
    }

    #[test]
    fn the_rounded_die_the_plate_and_the_tennis_racket_mid_flip() {
        let spin = ["initial.angular_velocity=[12,-20,6]"];
        let mut rounded = shipped("rounded-die", &spin);
        rounded.simulator.advance_steps(150);
        rounded.sync();
        let mut plate = shipped("plate", &spin);
        plate.simulator.advance_steps(300);
        plate.sync();
        let racket = tennis_racket_mid_flip();
        for (name, s) in [
            ("rounded_die", &rounded),
            ("plate", &plate),
            ("tennis_racket_mid_flip", &racket),
        ] {
            for (w, h) in [(80, 24), (120, 36)] {
                insta::assert_snapshot!(format!("{name}_{w}x{h}"), screen(&s.app, w, h));
            }
        }
    }

    /// A rounded cuboid's body read back from its sphere centres: axes, flat faces, sharp
    /// corners and the outline's arcs, against the sizes it was built from.
    #[test]
    fn a_rounded_cuboid_has_its_sizes_flat_faces_and_round_outline() {
        let mut die = Params::DEFAULT.die;
        die.half_sizes = [1.5, 1.0, 0.5];
        die.corner_radius = 0.2;
        let offset = Vector3::new(3.0, -2.0, 4.0);
        let body = Solid::new(&die, &contact_sphere_centres(&die).map(|c| c + offset));
        for (i, axis) in body.axes.iter().enumerate() {
            assert!((axis - Vector3::ith(i, 1.0)).norm() < 1e-12, "axis {i}: {axis}");
        }
        assert!((body.centre - offset).norm() < 1e-12);
        // Face 4 is z = +az: its flat part spans the half sizes less the radius.
        for p in body.flat_face(3) {
            let q = p - offset;
            assert!(
                (q.z - 0.5).abs() < 1e-12
                    && (q.x.abs() - 1.3).abs() < 1e-12
                    && (q.y.abs() - 0.8).abs() < 1e-12
            );
        }
        assert!((body.sharp_corner(7) - offset - Vector3::new(1.5, 1.0, 0.5)).norm() < 1e-12);
        assert!((body.lowest().z - (offset.z - 0.5)).abs() < 1e-12);
        // Seen level along y: the outline reaches the half sizes but cuts the corners round.
        let level = OrbitCamera {
            yaw_deg: 0.0,
            pitch_deg: 0.0,
            zoom: 0,
        };
        let outline = body.outline(|p| {
            let q = level.project(p, &offset);
            (q.x, q.y - offset.z)
        });
        let reach = outline.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
        assert!((reach - 1.5).abs() < 1e-9, "reaches the half size: {reach}");
        assert!(inside(&outline, (1.49, 0.0)) && inside(&outline, (0.0, 0.49)));
        // 0.1·r in from the sharp corner on both sides is 1.27·r from its sphere's centre.
        assert!(!inside(&outline, (1.5 - 0.02, 0.5 - 0.02)), "the corner is round");
        assert!(inside(&outline, (1.5 - 0.16 * 0.5, 0.0)));
    }

    /// Drilled pips are drawn their real size: each disc spans the pip diameter, and every
    /// seen face carries its number of them.
    #[test]
    fn drilled_pips_are_drawn_at_their_diameter() {
        let s = shipped("rounded-die", &[]);
        let body = Rect::new(0, 0, 60, 20);
        let view = Projection::new(&s.app, body);
        let pic = picture(&s.app, &view);
        let radius = 0.5 * s.app.roll.live.params.die.pip_diameter;
        let mut counted = 0;
        for (centre, disc, _) in &pic.pips {
            let widest = disc
                .iter()
                .map(|p| ((p.0 - centre.0).powi(2) + (p.1 - centre.1).powi(2)).sqrt())
                .fold(0.0, f64::max);
            assert!(widest <= radius * (1.0 + 1e-9), "{widest} > {radius}");
            assert!(
                widest > 0.8 * radius,
                "a seen pip keeps its width across: {widest}"
            );
            counted += 1;
        }
        // Level at the start, seen from the default camera: face 4 up and two sides.
        assert!((7..=15).contains(&counted), "{counted} pips");
    }
}

/// The real dice's values in the parameter list: a value in range that no body can have
/// with the others is refused with the physics' reason and changes nothing; one it can have
/// is sent to the worker, which restarts the roll with the new body.
#[test]
fn a_body_value_no_die_can_have_is_refused_and_changes_nothing() {
    use crate::tui::vocabulary::param::Param;
    let preset = dicesim_setup::preset::Preset::from_toml_str(
        dicesim_setup::preset::shipped_text("rounded-die").expect("shipped"),
        "rounded-die",
    )
    .expect("valid");
    let mut s = Harness::new(&preset, Theme::default());
    let before = (s.app.setup.params, s.app.setup.initial);
    // In the row's range (0…10 cm) but not below the smallest half size, 0.8 cm.
    let radius = Param::named("die.corner_radius");
    let refused = s.app.setup.set_param(radius, 0.9).unwrap_err();
    assert!(refused.contains("below the smallest half size"), "{refused}");
    // Pips 0.5 cm wide do not fit beside each other on a 1.6 cm face rounded by 0.15 cm.
    let refused = s
        .app
        .setup
        .set_param(Param::named("die.pip_diameter"), 0.5)
        .unwrap_err();
    assert!(refused.contains("at most 0.4 cm"), "{refused}");
    assert!((s.app.setup.params, s.app.setup.initial) == before);
    // A flatter die is a die: the worker takes it and rolls it from the start.
    let z = Param::named("die.half_sizes.z");
    s.simulator.advance_steps(50);
    let c = s.app.setup.set_param(z, 0.6).expect("a body");
    s.command(c);
    assert_eq!(s.app.roll.live.params.die.half_sizes, [0.8, 0.8, 0.6]);
    assert_eq!(
        s.app.roll.live.timeline.position, 0,
        "the body changed: the roll starts again"
    );
}
