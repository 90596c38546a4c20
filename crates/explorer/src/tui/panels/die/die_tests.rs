//! The die panel: the solid die from any camera, its contacts, arrows, marks and twins.

use crate::tui::panels::die::{self, Projection, picture, place_labels};
use crate::tui::render::screen::render;
use crate::tui::state::app::App;
use crate::tui::state::camera::OrbitCamera;
use crate::tui::state::die_screen::Drawing;
use crate::tui::state::projection::die_view;
use crate::tui::tests::fixtures::{
    Harness, after, at_rest, draw, full, lines_of, loaded_after, mid_impact, mid_impact_with, panel,
    panel_at, shipped, start, text,
};
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::param::Param;
use crate::tui::vocabulary::solid::inside;
use crate::tui::vocabulary::theme::{Palette, Theme};
use crate::worker::Phase;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::KeyCode;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier};

fn screen(app: &App, w: u16, h: u16) -> String {
    let mut t = Terminal::new(TestBackend::new(w, h)).expect("test backend");
    t.draw(|f| render(app, f)).expect("draw");
    t.backend().to_string()
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
    s.key(KeyCode::Char('T'));
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
            matches!(b[(body.x + c, body.y + r)].bg, Color::Rgb(r, g, bl) if r < 250 || g < 250 || bl < 250)
        })
        .count();
    assert_eq!(filled, inner.len(), "every inner cell of the die is shaded");
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

/// Cells of the die panel that mark a touching corner.
fn contact_cells(buffer: &Buffer, area: Rect, mark: &str) -> Vec<(u16, u16)> {
    let mut cells = Vec::new();
    for y in area.top()..area.bottom() {
        for x in area.left()..area.right() {
            if buffer[(x, y)].symbol() == mark {
                cells.push((x, y));
            }
        }
    }
    cells
}

#[test]
fn touching_corners_are_red_and_bold_or_reversed_without_colour() {
    let areas = screen_layout(Rect::new(0, 0, 120, 36)).expect("full size");
    let s = mid_impact();
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
    let t = draw(&s.app, 120, 36);
    let cells = contact_cells(t.backend().buffer(), areas.die, "●");
    assert!(!cells.is_empty() && cells.len() <= touching);
    for (x, y) in cells {
        let c = &t.backend().buffer()[(x, y)];
        assert_eq!(c.fg, Color::Red);
        assert!(c.modifier.contains(Modifier::BOLD));
    }
    // Edges at a touching corner are drawn in the contact colour too.
    let red_lines = (areas.die.top()..areas.die.bottom())
        .flat_map(|y| (areas.die.left()..areas.die.right()).map(move |x| (x, y)))
        .filter(|&p| t.backend().buffer()[p].fg == Color::Red && t.backend().buffer()[p].symbol() != "●")
        .count();
    assert!(red_lines > 0);

    let mono = mid_impact_with(Theme::monochrome());
    let t = draw(&mono.app, 120, 36);
    let cells = contact_cells(t.backend().buffer(), areas.die, "●");
    assert!(!cells.is_empty());
    for (x, y) in cells {
        assert!(
            t.backend().buffer()[(x, y)]
                .modifier
                .contains(Modifier::BOLD | Modifier::REVERSED)
        );
    }
}

#[test]
fn energy_log_scale_and_ascii_die() {
    let mut s = mid_impact();
    s.key(KeyCode::Char('p'));
    s.key(KeyCode::Char('m'));
    assert!(s.app.die_screen.log_scale);
    let areas = screen_layout(Rect::new(0, 0, 120, 36)).expect("full size");
    let t = draw(&s.app, 120, 36);
    let text = t.backend().to_string();
    assert!(text.contains("log (y)"));
    let die = lines_of(t.backend().buffer())[areas.die.y as usize..areas.die.bottom() as usize].join("\n");
    assert!(
        ['-', '|', '/', '\\'].iter().any(|&c| die.contains(c))
            && !die.contains('*')
            && !die.chars().any(|c| ('\u{2800}'..='\u{28ff}').contains(&c)),
        "ASCII only:\n{die}"
    );
    insta::assert_snapshot!("log_ascii_120x36", text);
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

/// `M` marks a face pair: its faces take their own tints and its axis is drawn through them
/// with both numbers at its tips; 2 and 5 first, the pair the tennis racket flips.
#[test]
fn m_marks_the_face_pair_two_and_five_first() {
    let mut s = shipped("tennis-racket");
    s.simulator.advance_steps(60);
    s.sync();
    s.key(KeyCode::Char('M'));
    assert_eq!(s.app.die_screen.face_pair, Some(2));
    let areas = screen_layout(s.app.screen).expect("a screen");
    let view = die_view(&s.app, areas.die);
    let pic = picture(&s.app, &view);
    for face in ["2", "5"] {
        assert!(pic.labels.iter().any(|l| l.text == face), "the axis's tip {face}");
    }
    let mut t = Terminal::new(TestBackend::new(120, 36)).expect("backend");
    t.draw(|f| render(&s.app, f)).expect("draw");
    let b = t.backend().buffer();
    let die = areas.die;
    // The pair's tints on the projector's white: warm (red full) and cool (green full).
    let tinted = (die.y..die.bottom())
        .flat_map(|y| (die.x..die.right()).map(move |x| (x, y)))
        .filter(|&p| match b[p].bg {
            Color::Rgb(r, g, bl) => (r == 255 && bl < g) || (g == 255 && r < g),
            _ => false,
        })
        .count();
    assert!(tinted > 4, "{tinted} cells of the pair's tints");
    for _ in 0..3 {
        s.key(KeyCode::Char('M'));
    }
    assert_eq!(s.app.die_screen.face_pair, None, "2·5 → 1·6 → 3·4 → none");
}

/// Defect: with the parameter twin, die B came to rest off the top of the die panel.
#[test]
fn the_parameter_twins_die_b_stays_in_the_picture() {
    let mut s = start();
    s.key(KeyCode::Char('D'));
    s.select(Param::named("ground.friction"));
    s.key(KeyCode::Enter);
    for c in "0.3".chars() {
        s.key(KeyCode::Char(c));
    }
    s.key(KeyCode::Enter);
    s.run_to_end();
    for (w, h) in [(80, 24), (100, 30), (120, 36)] {
        s.app.screen = Rect::new(0, 0, w, h);
        let areas = screen_layout(s.app.screen).expect("a screen");
        let view = die_view(&s.app, areas.die);
        let twin = s.app.roll.live.twin.as_ref().expect("die B");
        for body in [&s.app.roll.live.die, &twin.die] {
            for c in &body.corners {
                assert!(
                    view.cell(view.flat(c)).is_some(),
                    "{w}×{h}: a corner off the picture"
                );
            }
        }
        let mut t = Terminal::new(TestBackend::new(w, h)).expect("backend");
        t.draw(|f| render(&s.app, f)).expect("draw");
        let b = t.backend().buffer();
        let ghost = s.app.theme.ghost();
        let drawn = (areas.die.y + 1..areas.die.bottom() - 1)
            .flat_map(|y| (areas.die.x + 1..areas.die.right() - 1).map(move |x| (x, y)))
            .filter(|&p| b[p].fg == ghost && b[p].symbol() != " ")
            .count();
        assert!(drawn > 8, "{w}×{h}: die B drawn in {drawn} cells");
    }
}

/// The die panel alone, in its place on a 120×36 screen.
#[test]
fn panel_die_alone() {
    let app = mid_impact().app;
    insta::assert_snapshot!("panel_die", panel(&app, full().die, super::render).backend());
}

/// The readouts a preset chooses (`[view] readouts`), read on the 80×24 screen and in the
/// presentation view, each against what docs/explorer.md ("Readouts") derives for it.
mod readouts {
    use super::*;

    fn on_screen(s: &Harness) -> String {
        screen(&s.app, 80, 24)
    }

    /// The spin's sign before and after superball's first bounce: thrown with backspin
    /// ωy = -200 rad/s (its preset), it leaves the bounce spinning forwards (ωy > 0).
    #[test]
    fn superball_shows_its_spin_turn_round_at_the_bounce() {
        let mut s = shipped("superball");
        assert!(s.app.die_screen.readouts.spin);
        let before = on_screen(&s);
        assert!(before.contains("ωy -200.0"), "{before}");
        // To the first impact, then on until the ball is clear of the table again.
        s.key(KeyCode::Char('i'));
        while s.simulator.simulation().in_contact() {
            s.simulator.advance_steps(1);
        }
        s.sync();
        let w = s.app.roll.live.die.angular_velocity.y;
        assert!(w > 100.0, "ωy after the bounce {w}");
        let after = on_screen(&s);
        assert!(after.contains(&format!("ωy +{w:.1}")), "{after}");
        // In the presentation view too, the component on a line of its own.
        s.key(KeyCode::Char('P'));
        let shown = on_screen(&s);
        assert!(shown.contains(&format!("ωy +{w:.1}")), "{shown}");
    }

    /// The sleeping top starts with its long diagonal 1° off the vertical (its preset's
    /// orientation), so its lean reads 1.0°; upright on its corner it would read 0.
    #[test]
    fn sleeping_top_shows_its_lean_in_degrees() {
        let s = shipped("sleeping-top");
        let shown = on_screen(&s);
        assert!(shown.contains("lean 1.0°"), "{shown}");
    }

    /// The incline's die slides without turning from its push of 20 cm/s and stops after
    /// v₀²/(2·g·(μk·cos 25° − sin 25°)) = 6.68 cm; it has slid that far at its end.
    #[test]
    fn incline_shows_how_far_the_die_slid() {
        let mut s = shipped("incline");
        assert!(on_screen(&s).contains("slid 0.00 cm"), "{}", on_screen(&s));
        s.run_to_end();
        let g = s.app.roll.live.params.world.gravity;
        let theta = 25f64.to_radians();
        let a = g * (0.5 * theta.cos() - theta.sin());
        let expected = 20.0 * 20.0 / (2.0 * a);
        let slid = s.app.roll.live.die.slid_cm.expect("on the table");
        assert!(
            (slid - expected).abs() < 0.03 * expected,
            "slid {slid} cm, expected {expected}"
        );
        let shown = on_screen(&s);
        assert!(shown.contains(&format!("slid {slid:.2} cm")), "{shown}");
    }
}

/// The sleeping top spins on a corner, where no face is up: its title says so instead of
/// naming whichever face is a little higher this step (which flips as it spins).
#[test]
fn a_die_spinning_on_its_corner_has_no_face_up_in_its_title() {
    let mut s = shipped("sleeping-top");
    let mut titles = Vec::new();
    for _ in 0..8 {
        s.simulator.advance_steps(400);
        s.sync();
        let text = screen(&s.app, 80, 24);
        titles.push(text.lines().nth(1).expect("the panels' top row").to_string());
    }
    for t in &titles {
        assert!(t.contains("face up –, on a corner"), "{t}");
    }
    // A die flat on the table has its face.
    let s = at_rest(Theme::default());
    assert!(screen(&s.app, 80, 24).contains(&format!("face up {}", s.app.roll.live.die.face_up)));
}

/// At 80×24 the die's info line has a row of its own and the contact force is named once:
/// on superball's first bounce with the arrows on, no Braille dot or arrow label shares the
/// row of "centre … cm up", and one `F` stands for the forces however many corners touch.
#[test]
fn the_info_line_and_the_force_labels_leave_the_die_alone_at_80x24() {
    let mut s = shipped("superball");
    s.key(KeyCode::Char('i'));
    s.simulator.advance_steps(5);
    s.sync();
    if !s.app.die_screen.arrows {
        s.key(KeyCode::Char('v'));
    }
    let touching = s
        .app
        .roll
        .live
        .die
        .forces
        .iter()
        .filter(|f| f.depth > 0.0)
        .count();
    assert!(
        touching >= 2,
        "the bounce should press more than one corner: {touching}"
    );
    let text = screen(&s.app, 80, 24);
    let die_panel: Vec<String> = text
        .lines()
        .skip(1)
        .take(10)
        .map(|l| l.chars().skip(38).collect())
        .collect();
    let info = die_panel
        .iter()
        .find(|l| l.contains("cm up"))
        .expect("the info line");
    assert!(
        !info
            .chars()
            .any(|c| ('\u{2800}'..='\u{28ff}').contains(&c) || "LF".contains(c)),
        "{info}"
    );
    // The legend under the picture names ΣF once whatever the picture shows; count the
    // picture's labels only.
    let forces = die_panel
        .iter()
        .filter(|l| !l.contains("━ΣF"))
        .map(|l| l.matches('F').count())
        .sum::<usize>();
    assert_eq!(forces, 1, "{}", die_panel.join("\n"));
}
