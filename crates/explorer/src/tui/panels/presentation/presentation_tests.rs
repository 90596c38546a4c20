//! The presentation view: the die large, its height scale, the face up and the numbers.

use super::*;
use crate::tui::state::app::Page;
use crate::tui::state::die_screen::Readout;
use crate::tui::state::messages::Msg;
use crate::tui::tests::fixtures::{Harness, screen, spun_preset};
use crate::tui::vocabulary::layout::screen_layout;
use crate::tui::vocabulary::theme::{Palette, Theme};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::KeyCode;

const SIZES: [(u16, u16); 3] = [(80, 24), (100, 30), (120, 36)];

fn projector() -> Theme {
    Theme {
        palette: Palette::Projector,
        ..Theme::default()
    }
}

/// The spun paper roll (from 15 cm) in the presentation view, until its centre is
/// below `height` cm.
fn falling_to(height: f64, theme: Theme) -> Harness {
    let mut s = Harness::new(&spun_preset(), theme);
    s.key(KeyCode::Char('P'));
    while s.simulator.simulation().state().position.z >= height {
        assert_eq!(s.simulator.advance_steps(1), 1, "the die falls");
    }
    s.sync();
    s
}

fn buffer(app: &App, w: u16, h: u16) -> Buffer {
    let mut t = Terminal::new(TestBackend::new(w, h)).expect("test backend");
    t.draw(|f| crate::tui::render(app, f)).expect("draw");
    t.backend().buffer().clone()
}

fn row_text(b: &Buffer, y: u16, from: u16, to: u16) -> String {
    (from..to).map(|x| b[(x, y)].symbol()).collect()
}

/// The rows of the screen whose scale column reads `label ┤`.
fn tick_row(b: &Buffer, label: &str) -> Option<u16> {
    let want = format!("{label:>4} ┤");
    (0..b.area.height).find(|&y| row_text(b, y, 1, 1 + SCALE_WIDTH) == want)
}

/// The topmost row of the die's canvas holding a Braille dot (the die, falling above
/// the table's far tiles, is the highest thing drawn).
fn top_of_drawing(b: &Buffer) -> u16 {
    (1..b.area.height - 1)
        .find(|&y| {
            row_text(b, y, 1 + SCALE_WIDTH, b.area.width / 2)
                .chars()
                .any(|c| ('\u{2801}'..='\u{28ff}').contains(&c))
        })
        .expect("something is drawn")
}

#[test]
fn p_opens_and_closes_it_n_picks_the_number_and_esc_leaves() {
    let mut s = Harness::new(&spun_preset(), projector());
    s.key(KeyCode::Char('P'));
    assert_eq!(s.app.page, Page::Presentation);
    let names: Vec<&str> = (0..4)
        .map(|_| {
            let name = s.app.die_screen.readout.name();
            s.key(KeyCode::Char('N'));
            name
        })
        .collect();
    assert_eq!(names, ["height", "speed", "spin", "kinetic energy"]);
    assert_eq!(s.app.die_screen.readout, Readout::Height, "round again");
    // The main screen's keys work here: space plays.
    s.key(KeyCode::Char(' '));
    assert!(s.app.roll.live.playing);
    s.key(KeyCode::Esc);
    assert_eq!(s.app.page, Page::Die);
    s.key(KeyCode::Char('P'));
    s.key(KeyCode::Char('P'));
    assert_eq!(s.app.page, Page::Die);
    // On the main screen N means nothing; in the view, no value is typed blind.
    s.key(KeyCode::Char('N'));
    assert_eq!(s.app.die_screen.readout, Readout::Height);
    s.key(KeyCode::Char('P'));
    s.key(KeyCode::Enter);
    assert!(s.app.value_editor().is_none());
    assert!(s.app.notice.as_deref().is_some_and(|n| n.contains("main screen")));
}

#[test]
fn the_mouse_orbits_and_zooms_and_selects_no_hidden_value() {
    use ratatui::crossterm::event::{Event, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
    let mut s = Harness::new(&spun_preset(), projector());
    s.key(KeyCode::Char('P'));
    let areas = screen_layout(s.app.screen).expect("fits");
    // Where the parameter list would be on the main screen: its third row.
    let (column, row) = (areas.params.x + 3, areas.params.y + 4);
    let mouse = |kind| {
        Msg::Input(Event::Mouse(MouseEvent {
            kind,
            column,
            row,
            modifiers: KeyModifiers::NONE,
        }))
    };
    let (selected, zoom) = (s.app.die_screen.selected, s.app.die_screen.camera.zoom);
    crate::tui::input::update::update(&mut s.app, mouse(MouseEventKind::Down(MouseButton::Left)));
    assert_eq!(
        s.app.die_screen.selected, selected,
        "no value selected behind the die"
    );
    assert_eq!(
        s.app.die_screen.drag,
        Some((column, row)),
        "a drag starts anywhere"
    );
    crate::tui::input::update::update(&mut s.app, mouse(MouseEventKind::ScrollUp));
    assert_eq!(s.app.die_screen.camera.zoom, zoom + 1);
    assert_eq!(s.app.setup.params, spun_preset().params(), "no value scrolled");
}

#[test]
fn each_number_has_its_unit_and_the_physics_value() {
    let mut s = falling_to(10.0, projector());
    let live = s.app.roll.live.clone();
    let v = live.die.velocity;
    // 5 cm fallen from rest in height: the centre moves down at √(2·g·5 cm), about
    // 99 cm/s, besides the push across.
    let speed = (v.x * v.x + v.y * v.y + v.z * v.z).sqrt();
    assert!(speed > (2.0 * 981.0 * 4.99f64).sqrt(), "{speed}");
    let expect = [
        format!("{:.2} cm", live.die.centre.z),
        format!("{speed:.1} cm/s"),
        format!("{:.1} rad/s", live.die.angular_velocity.norm()),
        format!(
            "{} erg",
            crate::tui::vocabulary::format::fmt_num(live.energy.translational + live.energy.rotational)
        ),
    ];
    for want in expect {
        let t = screen(&s.app, 100, 30);
        assert!(t.contains(&want), "{want} not in\n{t}");
        s.key(KeyCode::Char('N'));
    }
}

#[test]
fn the_face_up_is_in_large_digits_nothing_drawn_over_them() {
    for theme in [projector(), Theme::default()] {
        let s = falling_to(10.0, theme);
        let face = char::from_digit(s.app.roll.live.die.face_up as u32, 10).expect("1…6");
        for (w, h) in SIZES {
            let b = buffer(&s.app, w, h);
            let side = (w * 2 / 7).clamp(24, 36);
            let (x0, x1) = (w - side + 1, w - 1);
            // The digit's rows, in order, each centred in the panel.
            let rows: Vec<String> = (2..h - 2)
                .map(|y| row_text(&b, y, x0, x1))
                .filter(|r| r.contains('█'))
                .map(|r| r.trim_matches(' ').to_string())
                .collect();
            assert!(rows.len() >= 5, "{w}×{h}: {rows:?}");
            assert!(
                rows.iter().all(|r| r.chars().all(|c| c == '█' || c == ' ')),
                "nothing but the digit in its rows at {w}×{h}: {rows:?}"
            );
            let sy = rows.len() / GLYPH_ROWS;
            let width = rows.iter().map(|r| r.chars().count()).max().unwrap_or(0);
            let sx = (width + 4) / GLYPH_COLUMNS;
            let want: Vec<String> = big_digit(face, sx, sy)
                .into_iter()
                .map(|r| r.trim_matches(' ').to_string())
                .filter(|r| !r.is_empty())
                .collect();
            assert_eq!(rows, want, "face {face} at {w}×{h}");
        }
    }
}

#[test]
fn the_camera_does_not_follow_the_die_up_and_down() {
    let start = {
        let mut s = Harness::new(&spun_preset(), projector());
        s.key(KeyCode::Char('P'));
        s
    };
    let lower = falling_to(10.0, projector());
    for (w, h) in SIZES {
        let (a, b) = (buffer(&start.app, w, h), buffer(&lower.app, w, h));
        let floor = tick_row(&a, "0").expect("the table's tick");
        assert_eq!(tick_row(&b, "0"), Some(floor), "the table stays at {w}×{h}");
        let ten = tick_row(&a, "10").expect("a 10 cm tick");
        assert_eq!(tick_row(&b, "10"), Some(ten));
        assert!(ten < floor);
        // The die is drawn lower as it falls, by about 5 cm of the scale: half the
        // rows from the table to the 10 cm tick.
        let drop = top_of_drawing(&b) as f64 - top_of_drawing(&a) as f64;
        let five_cm = (floor - ten) as f64 / 2.0;
        assert!(
            (drop - five_cm).abs() <= 1.5,
            "{w}×{h}: drawn {drop} rows lower, 5 cm is {five_cm} rows"
        );
    }
    // The main screen's view follows the die: its picture rises with it.
    let main = |s: &Harness| {
        let area = screen_layout(Rect::new(0, 0, 120, 36)).expect("fits").die;
        Projection::new(&s.app, area).y
    };
    assert_ne!(main(&start), main(&lower));
}

#[test]
fn ticks_are_one_two_or_five_times_a_power_of_ten() {
    // 16 cm in at most 5 ticks: 1 and 2 cm give 16 and 8, 5 cm gives 3.2.
    assert_eq!(tick_step(16.0, 5), 5.0);
    // 0.9 cm in 4: 0.1 → 9, 0.2 → 4.5, 0.5 → 1.8.
    assert_eq!(tick_step(0.9, 4), 0.5);
    assert_eq!(tick_step(40.0, 4), 10.0);
    let digit = big_digit('4', 4, 2);
    assert_eq!(digit.len(), 10);
    assert!(digit.iter().all(|r| r.chars().count() == 20));
    let faces: Vec<_> = ('1'..='6').map(glyph).collect();
    for (i, a) in faces.iter().enumerate() {
        assert!(faces[i + 1..].iter().all(|b| b != a), "each face its own glyph");
    }
}

#[test]
fn the_speed_shows_and_follows_the_speed_keys() {
    let mut s = falling_to(5.0, projector());
    let was = s.app.setup.speed;
    let before = row_text(&buffer(&s.app, 80, 24), 0, 0, 80);
    assert!(before.contains(&format!("speed {}", was.label())), "{before}");
    s.key(KeyCode::Char(']'));
    let after = row_text(&buffer(&s.app, 80, 24), 0, 0, 80);
    assert!(
        after.contains(&format!("speed {}", s.app.setup.speed.label())),
        "{after}"
    );
    assert_ne!(s.app.setup.speed, was, "] is the faster key in this view");
    assert_ne!(before, after, "and the screen says so");
}

#[test]
fn snapshots_at_three_sizes_in_the_projector_theme() {
    let s = falling_to(10.0, projector());
    for (w, h) in SIZES {
        insta::assert_snapshot!(format!("presentation_falling_{w}x{h}"), screen(&s.app, w, h));
    }
}
